// Tests of the boundary-layer route of rhabel/abel/multi_interval.hpp (solve_union_layered,
// detail/layered_union.hpp): nearly touching intervals down to a gap
// of 1e-6 of their length with a few dozen unknowns each. Oracles that share no code with the
// route: the polynomial route where it converges (gap 1e-2, every class), its recorded degree-1536
// value at gap 1e-4, the alpha = 0 closed form of the two-interval null space, densities given in
// advance (forward/inverse), and the independent residual.
#include <doctest/doctest.h>

#include "rhabel/abel.hpp"
#include "support.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

using namespace rhabel::abel;
using namespace abel_test;

namespace {

std::vector<interval_spec<double>> pair_at(double gap, edge leading, edge trailing) {
  return {{-1.0, 0.0, leading, trailing}, {gap, 1.0, leading, trailing}};
}

std::vector<std::function<double(double)>> minus_s() {
  return std::vector<std::function<double(double)>>(2, [](double s) { return -s; });
}

/// The tests' options: `degree`, 16 residual points, loads 1 and 0.5 (used by nu = +1 only).
multi_solve_options<double> with_degree(std::size_t degree) {
  multi_solve_options<double> options;
  options.degree = degree;
  options.residual_points = 16;
  options.loads = {1.0, 0.5};
  return options;
}

/// solve_union_layered at `degree` and `per_decade` poles a decade.
multi_solution<double> layered(const abel_parameters<double>& par, const std::vector<interval_spec<double>>& intervals,
                               const std::vector<std::function<double(double)>>& F, std::size_t degree,
                               std::size_t per_decade) {
  return solve_union_layered(par, intervals, F, with_degree(degree), per_decade);
}

/// g_i(t) of a solution (polynomial part plus layer).
double density(const multi_solution<double>& sol, std::size_t i, double t) {
  return sol.densities[i](t) + (sol.layers.empty() ? 0.0 : sol.layers[i](t));
}

}  // namespace

// Gap 1e-2: the polynomial route converges at degree 160 (residual <= 1e-13, measured), an
// independent discretisation of the same equation. Every class (nu = -1, 0, +1 with loads).
TEST_CASE("gap 1e-2: the layered route agrees with the converged polynomial route (every class)") {
  const abel_parameters<double> par(0.3, 0.2);
  const double gap = 1e-2;
  struct cls {
    edge leading, trailing;
  };
  for (const cls c : {cls{edge::bounded, edge::bounded}, cls{edge::bounded, edge::unbounded},
                      cls{edge::unbounded, edge::unbounded}}) {
    const auto reference = solve_union(par, pair_at(gap, c.leading, c.trailing), minus_s(), with_degree(160));
    REQUIRE(reference.residual < 1e-12);
    const auto sol = layered(par, pair_at(gap, c.leading, c.trailing), minus_s(), 24, 12);
    INFO("classes " << int(c.leading) << int(c.trailing) << ": residual " << sol.residual);
    CHECK(sol.status == solve_status::converged);
    CHECK(sol.residual < 1e-12);
    REQUIRE(sol.layers.size() == 2);
    CHECK(!sol.layers[0].hi_distances.empty());  // poles at the facing ends only
    CHECK(sol.layers[0].lo_distances.empty());
    CHECK(!sol.layers[1].lo_distances.empty());
    CHECK(sol.layers[1].hi_distances.empty());
    for (std::size_t i = 0; i < 2; ++i) {
      // 1e-11: measured <= 1e-14 (loads, defects) and 2.4e-13 of max(1, |g|) (values).
      CHECK(std::abs(sol.load(i) - reference.load(i)) < 1e-11 * std::abs(reference.load(i)));
      CHECK(std::abs(sol.solvability_defects[i] - reference.solvability_defects[i]) < 1e-11);
      // Across the interval and inside the layer (0.3 and 3 gaps from the facing end).
      const std::vector<double> probes = i == 0 ? std::vector<double>{-0.9, -0.5, -0.1, -3 * gap, -0.3 * gap}
                                                : std::vector<double>{1.3 * gap, 4 * gap, 0.1, 0.5, 0.9};
      for (const double t : probes) {
        const double ref = density(reference, i, t);
        INFO("t " << t << ": " << density(sol, i, t) << " against " << ref);
        CHECK(std::abs(density(sol, i, t) - ref) < 1e-10 * std::max(1.0, std::abs(ref)));
      }
    }
  }
}

// Gap 1e-4 (relative to lengths 1): the polynomial route needs degree ~800 for 1e-10 (its test
// records int g at degree 1536); the layered route reaches it at 24 + ~45 unknowns an interval.
TEST_CASE("gap 1e-4, alpha 0.25, beta 0.3, bounded ends: int g of the degree-1536 polynomial solve") {
  const abel_parameters<double> par(0.25, 0.3);
  const auto sol = layered(par, pair_at(1e-4, edge::bounded, edge::bounded), minus_s(), 24, 8);
  const double reference[2] = {0.40988240595917425, 0.23221830030750071};  // test_multi_interval.cpp
  INFO("residual " << sol.residual);
  CHECK(sol.status == solve_status::converged);
  CHECK(sol.residual < 1e-12);
  // 1e-11: measured 3e-15 (the reference itself has a residual of 1.6e-14).
  for (std::size_t i = 0; i < 2; ++i) CHECK(std::abs(sol.load(i) / reference[i] - 1) < 1e-11);
}

// Densities given in advance (polynomial, no layer), their data F = A g by apply_union (spectral
// own term, cross terms by exterior quadrature): the layered route must give them back although
// its data carry the neighbour's edge singularity at distance 1e-6.
TEST_CASE("gap 1e-6: forward/inverse, the densities behind the data come back") {
  for (const double alpha : {0.0, 0.3, 0.7}) {
    const abel_parameters<double> par(alpha, 0.2);
    const double gap = 1e-6;
    const auto intervals = pair_at(gap, edge::bounded, edge::unbounded);
    const auto e = par.exponents(edge::bounded, edge::unbounded);
    std::vector<jacobi_density<double>> g(2);
    for (std::size_t i = 0; i < 2; ++i) {
      g[i].lo = intervals[i].lo;
      g[i].hi = intervals[i].hi;
      g[i].gam = e.gam;
      g[i].del = e.del;
      g[i].coefficients = {1.0, 0.3 * double(i + 1), -0.2, 0.1};
    }
    std::vector<std::function<double(double)>> F;
    for (std::size_t j = 0; j < 2; ++j) F.push_back([&par, &g](double s) { return apply_union(par, g, s); });
    const auto sol = layered(par, intervals, F, 24, 8);
    INFO("alpha " << alpha << ": residual " << sol.residual);
    CHECK(sol.status == solve_status::converged);
    CHECK(sol.residual < 1e-10);
    // 1e-11: measured <= 5e-15 (residuals <= 2.4e-12).
    for (std::size_t i = 0; i < 2; ++i) CHECK(std::abs(sol.load(i) / g[i].integral() - 1) < 1e-11);
  }
}

// Gap 1e-6 (the polynomial route: residual 3e-2 at degree 108, ~1e4 needed): converged with the
// residual at the tolerance, and int g the same with more poles and a higher degree.
TEST_CASE("gap 1e-6, bounded ends: converged, and int g independent of the basis size") {
  for (const double alpha : {0.0, 0.3, 0.9}) {
    const abel_parameters<double> par(alpha, 0.2);
    const auto intervals = pair_at(1e-6, edge::bounded, edge::bounded);
    const auto coarse = layered(par, intervals, minus_s(), 24, 8);
    const auto fine = layered(par, intervals, minus_s(), 32, 12);
    INFO("alpha " << alpha << ": residuals " << coarse.residual << ", " << fine.residual);
    CHECK(coarse.status == solve_status::converged);
    CHECK(coarse.residual < 1e-11);
    CHECK(fine.residual < 1e-11);
    // 1e-10: measured <= 5.5e-13 (residuals <= 4.3e-14).
    for (std::size_t i = 0; i < 2; ++i) CHECK(std::abs(coarse.load(i) / fine.load(i) - 1) < 1e-10);
  }
}

// Closed form (test_multi_interval.cpp, gap 1e-4 at degree 1024 there): alpha = 0, beta = 0, both
// intervals unbounded at both ends; the coupled homogeneous density of interval 1 is
// sigma_i (c0 + c1 t)/sqrt|R(t)|, R = (t - a1)(t - b1)(t - a2)(t - b2): q = sigma g sqrt|R| is one
// straight line across both intervals, here at gap 1e-6, probed inside the layer.
TEST_CASE("gap 1e-6, alpha 0, beta 0: the coupled homogeneous density is (c0 + c1 t)/sqrt|R| (closed form)") {
  const abel_parameters<double> par(0.0, 0.0);
  const double gap = 1e-6;
  const double a1 = -1.0, b1 = 0.0, a2 = gap, b2 = 1.0;
  const std::vector<interval_spec<double>> intervals{{a1, b1, edge::unbounded, edge::unbounded},
                                                     {a2, b2, edge::unbounded, edge::unbounded}};
  const std::vector<std::function<double(double)>> F{[](double) { return 0.0; }, [](double) { return 0.0; }};
  multi_solve_options<double> options = with_degree(24);
  options.loads = {};
  options.residual_points = 0;  // the closed form is the oracle
  const auto sol = solve_union_layered(par, intervals, F, options, 12);
  REQUIRE(sol.homogeneous[0].size() == 2);
  REQUIRE(sol.homogeneous_layers[0].size() == 2);
  const auto& H = sol.homogeneous[0];
  const auto& HL = sol.homogeneous_layers[0];
  CHECK(H[0].integral() + HL[0].integral() == doctest::Approx(1.0).epsilon(1e-13));
  CHECK(std::abs(H[1].integral() + HL[1].integral()) < 1e-13);
  auto q = [&](std::size_t i, double from_lo, double to_hi) {
    const double t = H[i].lo + from_lo;
    const double R = i == 0 ? from_lo * to_hi * (a2 - t) * (b2 - t) : (t - a1) * (t - b1) * from_lo * to_hi;
    const double g = H[i].value_at_distance(from_lo, to_hi) + HL[i].value_at_distance(from_lo, to_hi);
    return (i == 0 ? -1.0 : 1.0) * g * std::sqrt(std::abs(R));
  };
  const double t_p = -0.5, t_r = 0.5 + gap / 2;
  const double q_p = q(0, t_p - a1, b1 - t_p), q_r = q(1, t_r - a2, b2 - t_r);
  const double slope = (q_r - q_p) / (t_r - t_p);
  const double size = std::max(std::abs(q_p), std::abs(q_r));
  double worst = 0;
  for (const double d : {1e-3, 0.3, 30 * gap, 3 * gap, 0.3 * gap, 0.03 * gap}) {
    for (std::size_t i = 0; i < 2; ++i) {
      for (const bool at_facing : {true, false}) {
        const bool from_lo = (i == 1) == at_facing;  // the facing end: hi of I_1, lo of I_2
        const double L = H[i].hi - H[i].lo;
        const double u = from_lo ? d : L - d, v = from_lo ? L - d : d;
        const double t = from_lo ? H[i].lo + u : H[i].hi - v;
        worst = std::max(worst, std::abs(q(i, u, v) - (q_p + slope * (t - t_p))) / size);
      }
    }
  }
  INFO("max deviation from one line: " << worst);
  // 1e-9: measured 3.1e-12; the polynomial route reaches 1.9e-11 at gap 1e-4 with degree 768.
  CHECK(worst < 1e-9);
  CHECK(std::abs(slope) > 1e-3 * size);
}

// The evidence is honest: too few poles (2 a decade) leave the layer unresolved, and the
// independent residual says so.
TEST_CASE("gap 1e-6: too few poles give not_converged with the residual that shows it") {
  const abel_parameters<double> par(0.3, 0.2);
  const auto intervals = pair_at(1e-6, edge::bounded, edge::bounded);
  const auto poor = layered(par, intervals, minus_s(), 8, 1);
  const auto good = layered(par, intervals, minus_s(), 24, 8);
  const double error = std::abs(poor.load(0) / good.load(0) - 1);
  INFO("residual " << poor.residual << ", int g error " << error);
  CHECK(poor.status == solve_status::not_converged);
  CHECK(poor.residual > 1e-10);
  CHECK(poor.residual > error / 10);
}

// Bad input: a basis that would not fit in options.max_memory_bytes (10^5 or SIZE_MAX poles a
// decade; 8 a decade at a gap of 1e-300 of the length, ~2400 poles, under a 1 MiB bound) is
// refused before anything is allocated, naming the parameter; so are 0 poles a decade.
TEST_CASE("layered route: a basis beyond max_memory_bytes is refused, naming the parameter") {
  const abel_parameters<double> par(0.3, 0.2);
  const auto pair = pair_at(1e-6, edge::bounded, edge::bounded);
  try {
    (void)layered(par, pair, minus_s(), 24, 100000);
    FAIL("no exception");
  } catch (const std::domain_error& e) {
    CHECK(std::string(e.what()).find("poles_per_decade") != std::string::npos);
  }
  // No allocation of 1e20 poles first.
  CHECK_THROWS_AS(layered(par, pair, minus_s(), 24, std::numeric_limits<std::size_t>::max()), std::domain_error);
  CHECK_THROWS_AS(layered(par, pair, minus_s(), 24, 0), std::domain_error);
  multi_solve_options<double> options = with_degree(24);
  options.max_memory_bytes = std::size_t(1) << 20;
  CHECK_THROWS_AS(solve_union_layered(par, pair_at(1e-300, edge::bounded, edge::bounded), minus_s(), options, 8),
                  std::domain_error);
}
