// A sampled profile with its contact set unknown (rhabel/punch/profile.hpp) against oracles that
// share no code with its active set: the closed-form single parabola (via the parabolic
// indentor's own closed-form path, which the profile's spline and general-profile path do not
// use), and the independent boundary-element oracle of bem_oracle.hpp, which finds the contact
// set of a rigid body by its own active set on panels.
#include <doctest/doctest.h>

#include "bem_oracle.hpp"
#include "rhabel/punch.hpp"

#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace pu = rhabel::punch;
constexpr double pi = 3.141592653589793238462643383279502884;

// (pi/2) E_U for E1 = 1, speed 1, nu = 0: loads in units of int g are load / this.
double pressure_scale(double alpha) { return pi / 2 * boost::math::tgamma(1 - alpha); }

pu::solve_options profile_options() {
  pu::solve_options o;
  o.tolerance = 1e-10;
  // The spline of a sampled surface is C2: the density converges like degree^-3 (profile.hpp), so
  // the residual of (8) against the spline reaches ~1e-8 at 150 samples per unit, not 1e-12.
  o.acceptance = 1e-6;
  return o;
}
}  // namespace

TEST_CASE("a profile sampled from a parabola gives the parabola's answer") {
  // The natural spline of a parabola is the parabola away from its ends (the end's error decays
  // by 0.27 per sample): 600 samples on [-3, 3], the contact (L ~ 1) hundreds of samples from
  // the ends. The general-profile path then solves the same equation as the parabolic one, to the
  // degree-128 series of a forcing that is linear: edges to the root tolerance.
  constexpr double edge_tol = 1e-9;  // relative to L: root tolerance 1e-10 of both paths, x10
  for (const double alpha : {0.0, 0.3, 0.7}) {
    CAPTURE(alpha);
    const double R = 1, apex = 0.3, load = 0.3 * pressure_scale(alpha);
    pu::profile_scene ps;
    ps.material.alpha = alpha;
    ps.load = load;
    for (int i = 0; i <= 600; ++i) {
      const double x = -3 + 6.0 * i / 600;
      ps.profile.x.push_back(x);
      ps.profile.z.push_back(-(x - apex) * (x - apex) / (2 * R));
    }
    const auto o = profile_options();
    const auto ours = pu::solve_profile(ps, o);
    REQUIRE(ours.contacts.size() == 1);
    CHECK(ours.diagnostics.code == pu::status_code::ok);
    pu::scene sc;
    sc.material.alpha = alpha;
    sc.indentors.push_back({pu::parabolic{R}, load, apex});
    const auto ref = pu::solve(sc, o);
    const auto& c = ours.contacts[0];
    const auto& r = ref.indentors[0];
    CHECK(std::abs(c.a - r.a) <= edge_tol * r.contact_length);
    CHECK(std::abs(c.b - r.b) <= edge_tol * r.contact_length);
    CHECK(std::abs(c.load - load) <= 1e-9 * load);  // the body's load, matched to the acceptance
    CHECK(std::abs(c.hysteretic_friction - r.hysteretic_friction) <= 1e-9 * std::abs(r.hysteretic_friction) + 1e-15);
  }
}

TEST_CASE("several bumps: the contact set and the contacts of the boundary-element oracle") {
  // The profile: the upper envelope of four parabolic caps (tips at c_j, heights h_j, radii R_j),
  // sampled uniformly on each piece between the envelope's corners, which are declared (the
  // spline keeps them). The third cap is 0.3 lower and stays clear at this load; the others touch.
  struct cap {
    double c, h, R;
  };
  const std::vector<cap> caps{{0, 0, 1}, {2, -0.02, 0.8}, {4, -0.3, 1.2}, {6, -0.01, 1}};
  auto cap_z = [](const cap& k, double x) { return k.h - (x - k.c) * (x - k.c) / (2 * k.R); };
  // Corner between caps p and q: where the two are equal (a quadratic; the root between tips).
  auto corner = [&](const cap& p, const cap& q) {
    double lo = p.c, hi = q.c;
    for (int it = 0; it < 200; ++it) {
      const double mid = (lo + hi) / 2;
      (cap_z(p, mid) > cap_z(q, mid) ? lo : hi) = mid;
    }
    return (lo + hi) / 2;
  };
  std::vector<double> cuts{-3};
  for (std::size_t k = 0; k + 1 < caps.size(); ++k) cuts.push_back(corner(caps[k], caps[k + 1]));
  cuts.push_back(9);
  const double alpha = 0.3, load_g = 0.6;
  pu::profile_scene ps;
  ps.material.alpha = alpha;
  ps.load = load_g * pressure_scale(alpha);
  for (std::size_t k = 0; k < caps.size(); ++k) {
    const int n = 300;
    for (int i = k == 0 ? 0 : 1; i <= n; ++i) {
      const double x = cuts[k] + (cuts[k + 1] - cuts[k]) * i / n;
      ps.profile.x.push_back(x);
      ps.profile.z.push_back(cap_z(caps[k], x));
    }
    if (k > 0) ps.profile.corners.push_back(cuts[k]);
  }
  const auto ours = pu::solve_profile(ps, profile_options());
  CAPTURE(ours.diagnostics.status);
  REQUIRE(ours.diagnostics.code == pu::status_code::ok);

  namespace bem = punch_test::bem;
  bem::scene bs;
  bs.alpha = alpha;
  bs.beta = 0;
  bs.one_body = true;
  bs.total_load = load_g;
  for (std::size_t k = 0; k < caps.size(); ++k) {
    bem::indentor I{bem::parabola{caps[k].R}, caps[k].c, 0.0, cuts[k], cuts[k + 1]};
    I.offset = caps[k].h;  // the oracle's profile f + z
    bs.indentors.push_back(I);
  }
  const auto oracle = bem::solve(bs, bem::test_options(bem::options{}.levels));
  REQUIRE(oracle.converged);
  std::vector<std::size_t> touching;
  for (std::size_t k = 0; k < caps.size(); ++k)
    if (oracle.contacts[k].in_contact) touching.push_back(k);
  REQUIRE(touching.size() == ours.contacts.size());
  CHECK(touching == std::vector<std::size_t>{0, 1, 3});  // the scene's design: the low cap stays clear
  for (std::size_t m = 0; m < touching.size(); ++m) {
    CAPTURE(m);
    const auto& theirs = oracle.contacts[touching[m]];
    const auto& c = ours.contacts[m];
    CHECK(ours.tips[m] == doctest::Approx(caps[touching[m]].c).epsilon(0.02));
    // Twice the oracle's bar (an estimate: test_coupled_bem.cpp) plus the spline's effect on the
    // edges: the caps are exact parabolas on samples 1/100 apart, the natural ends at the corners
    // decay to 1e-14 within 25 samples, and the contacts lie > 60 samples from the corners.
    CHECK(std::abs(c.a - theirs.a.value) <= 2 * theirs.a.error + 1e-9 * c.contact_length);
    CHECK(std::abs(c.b - theirs.b.value) <= 2 * theirs.b.error + 1e-9 * c.contact_length);
    CHECK(std::abs(c.load / pressure_scale(alpha) - theirs.load.value) <= 2 * theirs.load.error + 1e-8 * theirs.load.value);
    CHECK(theirs.a.error < 2e-3 * c.contact_length);  // the comparison is not vacuous
  }
  CHECK(ours.clearance >= -1e-6);
}

TEST_CASE("solve_profile refuses bad input naming the field") {
  pu::profile_scene ps;
  ps.profile.x = {0, 1, 2, 3, 4};
  ps.profile.z = {0, 1, 2, 1, 0};
  auto message = [&](const pu::profile_scene& s) {
    try {
      pu::solve_profile(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  auto bad = ps;
  bad.profile.x[2] = 1;
  CHECK(message(bad).find("profile.x[2] = 1 must be > profile.x[1] = 1") != std::string::npos);
  bad = ps;
  bad.profile.z.pop_back();
  CHECK(message(bad).find("profile.x has 5 samples and profile.z 4") != std::string::npos);
  bad = ps;
  bad.profile.z[1] = std::nan("");
  CHECK(message(bad).find("profile.z[1] = nan must be finite") != std::string::npos);
  bad = ps;
  bad.load = -1;
  CHECK(message(bad).find("load = -1 must be finite and > 0") != std::string::npos);
  bad = ps;
  bad.profile.corners = {1.5};
  CHECK(message(bad).find("profile.corners (1.5) must each be one of profile.x[1]") != std::string::npos);
  bad = ps;
  bad.profile.z = {5, 1, 2, 1, 0};
  CHECK(message(bad).find("highest at an end") != std::string::npos);
  bad = ps;
  bad.material.alpha = 1;
  CHECK(message(bad).find("rhabel::punch::solve_profile: material.alpha = 1 must be in [0, 1)") != std::string::npos);
}
