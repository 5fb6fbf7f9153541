// The boundary-element solver of sampled profiles (rhabel/punch/profile_bem.hpp), finite and
// periodic, against oracles that share no code with it:
//   * its periodic panel kernel against the Fourier series of the power-law kernel's multiplier
//     (bem_profile_oracle.hpp's periodic_panel_fourier, a different representation);
//   * Westergaard's closed form for the elastic sinusoid (contact width against mean pressure);
//   * the spectral solver (rhabel::punch::solve_profile, 1e-9) on a sampled parabola;
//   * the test suite's own boundary-element oracle (bem_profile_oracle.hpp: its own splines,
//     kernel tables and active set) on self-affine profiles at three seeds, finite and periodic.
// The contract checked: a result that says ok agrees with the oracle within the two error
// estimates (a factor 2 over their sum: both are estimates, not bounds) and has its patch count.
#include <doctest/doctest.h>

#include "../punch/src/panel_grid.hpp"
#include "punch/bem_profile_oracle.hpp"
#include "punch/rough_profiles.hpp"
#include "rhabel/punch.hpp"
#include "rhabel/punch/profile_bem.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace pu = rhabel::punch;
namespace bp = punch_test::bem_profile;
constexpr double pi = 3.141592653589793238462643383279502884;

// The two solvers' error estimates are estimates: agreement is asked within twice their sum.
constexpr double estimate_factor = 2;

double kappa_of(double alpha, double beta) { return std::cos((alpha + beta / 2) * pi) / std::cos(beta * pi / 2); }

pu::profile_scene scene_of(const std::vector<double>& x, const std::vector<double>& z, double alpha, double load,
                           double period = 0) {
  pu::profile_scene s;
  s.material.alpha = alpha;  // E1 1, nu 0, k 0, speed 1
  s.profile.x = x;
  s.profile.z = z;
  s.profile.period = period;
  s.load = load;
  return s;
}

}  // namespace

TEST_CASE("periodic panel kernel: differences against the Fourier series of its multiplier") {
  // Period 1, panel h = 1/64; the kernel is defined up to a constant, so differences between
  // collocation offsets are compared. The series' truncation at 2e5 modes is ~modes^(-1-alpha)
  // (bem_profile_oracle.hpp: 3e-10 at alpha 0): the tolerance 2e-9 is that with a margin.
  constexpr double series_tol = 2e-9;
  const double h = 1.0 / 64;
  for (const auto& [alpha, beta] : {std::pair{0.0, 0.0}, {0.3, 0.0}, {0.3, 0.4}, {0.7, 0.3}, {0.05, 0.9}}) {
    CAPTURE(alpha);
    CAPTURE(beta);
    const double kappa = kappa_of(alpha, beta);
    // (1 - kappa)/alpha = 2 sin((alpha + beta) pi/2) sin(alpha pi/2)/(alpha cos(beta pi/2)).
    const double c1 = alpha == 0 ? pi * std::sin(beta * pi / 2) / std::cos(beta * pi / 2)
                                 : (1 - kappa) / alpha;
    const rhabel::punch::detail::periodic_panel_kernel W(alpha, kappa, c1);
    const double ref = bp::periodic_panel_fourier(alpha, beta, 1.0, h, 0.5, 200000);
    for (double sigma : {0.75 * h, 1.75 * h, 0.1, 0.37, 0.9, 1 - 0.25 * h}) {
      CAPTURE(sigma);
      const double fourier = bp::periodic_panel_fourier(alpha, beta, 1.0, h, sigma, 200000) - ref;
      CHECK(std::abs(W(h, sigma) - W(h, 0.5) - fourier) <= series_tol);
    }
  }
}

TEST_CASE("periodic elastic sinusoid: Westergaard's contact width, C_f = 0") {
  // z = -(Delta/2)(1 - cos(2 pi x/lambda)), alpha = 0, nu = 0, E1 = 1: E* = 1 and
  // p_mean = (pi E* Delta/(2 lambda)) sin^2(pi a/lambda) for the contact width 2a.
  const double lambda = 2, Delta = 0.01;
  const std::size_t n = 400;
  std::vector<double> x(n), z(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = -0.5 + lambda * static_cast<double>(i) / static_cast<double>(n);
    z[i] = -Delta / 2 * (1 - std::cos(2 * pi * x[i] / lambda));
  }
  pu::solve_options o;
  o.acceptance = 1e-5;
  for (double share : {0.05, 0.3, 0.8}) {  // p_mean as a share of the full-contact pressure pi Delta/(2 lambda)
    CAPTURE(share);
    const double p_mean = share * pi * Delta / (2 * lambda);
    const auto r = pu::solve_profile_bem(scene_of(x, z, 0.0, p_mean * lambda, lambda), o);
    CAPTURE(r.diagnostics.status);
    CHECK(r.diagnostics.code == pu::status_code::ok);
    REQUIRE(r.patches.size() == 1);
    const double a = lambda / pi * std::asin(std::sqrt(share));
    CHECK(std::abs(r.contact_fraction.value - 2 * a / lambda) <= r.contact_fraction.error);
    // Edges modulo the period (a patch through x_0 is reported from its start in the last period).
    CHECK(std::abs(std::remainder(r.patches[0].a + a, lambda)) <= r.patches[0].edge_error);
    CHECK(std::abs(std::remainder(r.patches[0].b - a, lambda)) <= r.patches[0].edge_error);
    CHECK(r.patches[0].a >= x.front());
    CHECK(r.patches[0].a < x.front() + lambda);
    CHECK(std::abs(r.hysteretic_friction.value) <= r.hysteretic_friction.error + 1e-12);
    CHECK(r.mean_pressure == doctest::Approx(p_mean).epsilon(1e-15));
    CHECK(r.patches[0].load.value == doctest::Approx(p_mean * lambda).epsilon(1e-6));
  }
}

TEST_CASE("sampled parabola, finite window: C_f of the spectral solver") {
  // R = 1, 601 samples on [-3, 3]; the spectral solver's C_f is accurate to ~1e-9 here
  // (test_profile.cpp), far below the boundary-element estimates.
  std::vector<double> x, z;
  for (int i = 0; i <= 600; ++i) {
    x.push_back(-3 + 0.01 * i);
    z.push_back(-x.back() * x.back() / 2);
  }
  for (double alpha : {0.0, 0.3, 0.7}) {
    CAPTURE(alpha);
    const auto s = scene_of(x, z, alpha, 0.05);
    pu::solve_options o;
    o.acceptance = 1e-5;
    const auto r = pu::solve_profile_bem(s, o);
    CAPTURE(r.diagnostics.status);
    CHECK(r.diagnostics.code == pu::status_code::ok);
    REQUIRE(r.patches.size() == 1);
    pu::solve_options so;
    so.acceptance = 1e-6;
    so.tolerance = 1e-10;
    const auto spectral = pu::solve_profile(s, so);
    REQUIRE(spectral.contacts.size() == 1);
    const auto& c = spectral.contacts[0];
    CHECK(std::abs(r.hysteretic_friction.value - c.hysteretic_friction) <= estimate_factor * r.hysteretic_friction.error);
    CHECK(std::abs(r.patches[0].a - c.a) <= 2 * r.patches[0].edge_error);
    CHECK(std::abs(r.patches[0].b - c.b) <= 2 * r.patches[0].edge_error);
    CHECK(r.patches[0].load.value == doctest::Approx(0.05).epsilon(1e-9));
  }
}

TEST_CASE("self-affine profiles, periodic and finite, against the boundary-element oracle") {
  struct case_t {
    std::uint64_t seed;
    double load;
    bool periodic;
  };
  std::vector<case_t> cases{{1, 5e-4, true}, {2, 3e-3, true}, {3, 5e-4, true}, {2, 5e-4, false}, {3, 5e-4, false}};
  if (punch_test::bem::sanitizer_build) cases = {{3, 5e-4, true}};
  std::size_t ok = 0;
  for (const auto& c : cases) {
    CAPTURE(c.seed);
    CAPTURE(c.load);
    CAPTURE(c.periodic);
    const auto samples = punch_test::self_affine(1000, c.seed);
    const double period = c.periodic ? 1.0 : 0.0;
    pu::solve_options o;
    o.acceptance = 1e-4;
    const auto r = pu::solve_profile_bem(scene_of(samples.x, samples.z, 0.3, c.load, period), o);
    CAPTURE(r.diagnostics.status);
    const auto oracle = bp::solve(bp::make_scene_physical(samples.x, samples.z, 1, 0.3, 0, 0, 1, c.load, period),
                                  bp::test_options());
    if (r.diagnostics.code != pu::status_code::ok) continue;
    ++ok;
    CHECK(r.patches.size() == oracle.patches.size());
    CHECK(std::abs(r.hysteretic_friction.value - oracle.friction.value) <=
          estimate_factor * (r.hysteretic_friction.error + oracle.friction.error));
    CHECK(std::abs(r.contact_fraction.value - oracle.fraction.value) <=
          estimate_factor * (r.contact_fraction.error + oracle.fraction.error));
  }
  CHECK(ok == cases.size());  // measured: every case ok at acceptance 1e-4
}

TEST_CASE("profile.period: hostile input is refused naming the field") {
  std::vector<double> x{0, 0.1, 0.2, 0.3, 0.4, 0.5}, z{-0.02, -0.01, 0, -0.01, -0.02, -0.03};
  auto refused = [&](double period, std::vector<double> corners, const char* field) {
    auto s = scene_of(x, z, 0.3, 0.01, period);
    s.profile.corners = std::move(corners);
    // Both solvers take a period and validate it alike.
    bool both = true;
    for (const bool bem : {true, false}) {
      try {
        if (bem)
          (void)pu::solve_profile_bem(s);
        else
          (void)pu::solve_profile(s);
        both = false;
      } catch (const std::invalid_argument& e) {
        both = both && std::string(e.what()).find(field) != std::string::npos;
      }
    }
    return both;
  };
  CHECK(refused(0.5, {}, "profile.period"));  // the last sample at x_0 + period
  CHECK(refused(0.3, {}, "profile.period"));
  CHECK(refused(-1, {}, "profile.period"));
  CHECK(refused(std::nan(""), {}, "profile.period"));
  CHECK(refused(std::numeric_limits<double>::infinity(), {}, "profile.period"));
  CHECK(refused(0.6, {0.2}, "profile.corners"));
  const auto s = scene_of(x, z, 0.3, 0.01, 0.6);
  pu::bem_options bo;
  bo.max_panels = 10;
  CHECK_THROWS_AS(pu::solve_profile_bem(s, {}, bo), std::invalid_argument);
}

TEST_CASE("the time limit and max_panels end the refinement with not_converged and the numbers") {
  const auto samples = punch_test::self_affine(1000, 2);
  const auto s = scene_of(samples.x, samples.z, 0.3, 3e-3, 1.0);
  pu::solve_options o;
  o.acceptance = 1e-12;  // beyond reach
  pu::bem_options bo;
  bo.max_panels = 8000;
  const auto r = pu::solve_profile_bem(s, o, bo);
  CAPTURE(r.diagnostics.status);
  CHECK(r.diagnostics.code == pu::status_code::not_converged);
  CHECK(r.diagnostics.status.find("max_panels") != std::string::npos);
  CHECK(r.diagnostics.level_panels.size() == 4);  // 1000, 2000, 4000, 8000
  CHECK(!r.patches.empty());
  o.time_limit = 1e-3;
  const auto t = pu::solve_profile_bem(s, o);
  CAPTURE(t.diagnostics.status);
  CHECK(t.diagnostics.code == pu::status_code::not_converged);
  CHECK(t.diagnostics.status.find("time") != std::string::npos);
  // solve_options::interrupt: polled at the same checks; once it fires, punch::interrupted and no
  // result.
  o.time_limit = 0;
  std::size_t calls = 0;
  o.interrupt = [&calls] { return ++calls >= 5; };
  CHECK_THROWS_AS(pu::solve_profile_bem(s, o, bo), pu::interrupted);
  CHECK(calls == 5);
}
