// Tests of rhabel/abel/multi_interval.hpp (paper 41, several contact intervals): independent
// residual, forward/inverse consistency against apply_union (own term spectral, cross terms by
// pointwise exterior quadrature), the decoupling limit of far-apart intervals, the homogeneous
// directions, and the nearly-touching hard case (honest report, no false convergence).
#include <doctest/doctest.h>

#include "rhabel/abel.hpp"
#include "support.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

using namespace rhabel::abel;
using namespace abel_test;

TEST_CASE("two separated intervals, mixed classes: independent residual and loads") {
  for (double alpha : {0.0, 0.3, 0.7}) {
    abel_parameters<double> par(alpha, 0.2);
    const bool unbounded_ok = 2 * alpha + 0.2 < 1;
    std::vector<interval_spec<double>> intervals{
        {-2.0, -0.5, edge::bounded, edge::unbounded},
        {0.5, 1.5, unbounded_ok ? edge::unbounded : edge::bounded, edge::unbounded}};
    std::vector<std::function<double(double)>> F{[](double s) { return std::cos(s); },
                                                 [](double s) { return 1 + 0.2 * s * s; }};
    multi_solve_options<double> options;
    options.degree = 32;
    options.loads = {std::nullopt, 0.7};
    const auto sol = solve_union(par, intervals, F, options);
    INFO("alpha=" << alpha);
    CHECK(sol.residual < 1e-12);
    CHECK(sol.condition < 1e3);
    if (sol.exponents[1].nu == 1) CHECK(sol.densities[1].integral() == doctest::Approx(0.7).epsilon(8 * eps));
  }
}

TEST_CASE("forward/inverse consistency: F_j = apply_union(g) recovers the coefficients of g") {
  abel_parameters<double> par(0.35, 0.1);
  std::vector<interval_spec<double>> intervals{{0.0, 1.0, edge::bounded, edge::unbounded},
                                               {1.4, 2.0, edge::bounded, edge::unbounded},
                                               {3.0, 5.0, edge::bounded, edge::unbounded}};
  std::vector<jacobi_density<double>> g;
  for (const auto& iv : intervals) {
    const auto e = par.exponents(iv.leading, iv.trailing);
    g.push_back({iv.lo, iv.hi, e.gam, e.del, {1.0, -0.3, 0.2, 0.05}});
  }
  std::vector<std::function<double(double)>> F;
  for (std::size_t j = 0; j < 3; ++j) F.push_back([&](double s) { return apply_union(par, g, s); });
  multi_solve_options<double> options;
  options.degree = 40;
  const auto sol = solve_union(par, intervals, F, options);
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t n = 0; n < 4; ++n)
      // 1e-11 absolute on O(1) coefficients: the cross terms are analytic but the gap 0.4 vs
      // length 1 costs ~ 40 Chebyshev points for 1e-12.
      CHECK(sol.densities[j].coefficients[n] == doctest::Approx(g[j].coefficients[n]).epsilon(1e-11).scale(1.0));
  CHECK(sol.residual < 1e-11);
}

TEST_CASE("far-apart intervals decouple: the coupled solution tends to the single-interval ones") {
  abel_parameters<double> par(0.4, 0.3);
  const double gap = 1e6;
  std::vector<interval_spec<double>> intervals{{-1.0, 1.0, edge::bounded, edge::unbounded},
                                               {1.0 + gap, 3.0 + gap, edge::bounded, edge::unbounded}};
  std::vector<std::function<double(double)>> F{[](double) { return 1.0; }, [](double) { return 2.0; }};
  const auto coupled = solve_union(par, intervals, F);
  abel_operator<double> op(par, -1.0, 1.0);
  const auto single = solve(op, edge::bounded, edge::unbounded, [](double) { return 1.0; });
  // Cross term ~ load x gap^(alpha-1) = O(1e-6 ^ 0.6) ~ 2.5e-4 relative.
  const double coupling = 10 * std::pow(gap, par.alpha() - 1);
  CHECK(std::abs(coupled.densities[0].integral() - single.density.integral()) <=
        coupling * std::abs(single.density.integral()));
  CHECK(std::abs(coupled.densities[0].integral() - single.density.integral()) > 0);
}

TEST_CASE("homogeneous directions (nu = +1) solve the coupled system with zero data") {
  abel_parameters<double> par(0.2, 0.1);
  std::vector<interval_spec<double>> intervals{{-1.0, 0.0, edge::unbounded, edge::unbounded},
                                               {0.5, 2.0, edge::bounded, edge::bounded}};
  std::vector<std::function<double(double)>> F{[](double) { return 0.0; }, [](double s) { return s; }};
  const auto sol = solve_union(par, intervals, F);
  REQUIRE(sol.homogeneous[0].size() == 2);
  CHECK(sol.homogeneous[1].empty());
  const auto& H = sol.homogeneous[0];
  CHECK(H[0].integral() == doctest::Approx(1.0).epsilon(8 * eps));
  // A H = 0 on interval 0, and = the reported defect (a constant image P_0 times h^alpha) on interval 1.
  for (double s : {-0.8, -0.3}) CHECK(std::abs(apply_union(par, H, s)) < 1e-12);
  const double h1 = 0.75;
  for (double s : {0.7, 1.8})
    CHECK(apply_union(par, H, s) == doctest::Approx(std::pow(h1, par.alpha()) * (-sol.homogeneous_defects[0][1])).epsilon(1e-10));
}

TEST_CASE("nearly touching intervals (gap 1e-6): reported residual is honest and improves with degree") {
  abel_parameters<double> par(0.3, 0.2);
  std::vector<interval_spec<double>> intervals{{-1.0, 0.0, edge::bounded, edge::bounded},
                                               {1e-6, 1.0, edge::bounded, edge::bounded}};
  std::vector<std::function<double(double)>> F{[](double s) { return -s; }, [](double s) { return -s; }};
  double previous = 1e300;
  for (std::size_t degree : {16, 32, 64}) {
    multi_solve_options<double> options;
    options.degree = degree;
    const auto sol = solve_union(par, intervals, F, options);
    CHECK(std::isfinite(sol.residual));
    CHECK(sol.residual < previous);
    previous = sol.residual;
  }
  // Not converged to 1e-12 at degree 64: the cross terms are nearly singular at the facing ends.
  CHECK(previous > 1e-12);
}

// Regression "residual at the collocation points" (issue 3, defect 6): with residual_points equal
// to the degree (or any size with the same power of 2) the residual was sampled at the
// collocation points, where it is ~ rounding whatever the error: 1e-15 reported for a
// solution whose int g was wrong by 1e-3 (gap 1e-2, degree 16). Oracle: int g at degree 128
// (converged there to ~1e-14, measured) against degree 16.
TEST_CASE("nearly touching intervals (gap 1e-2): the residual is never sampled at the collocation points") {
  abel_parameters<double> par(0.3, 0.2);
  const double gap = 1e-2;
  std::vector<interval_spec<double>> intervals{{-1.0, 0.0, edge::bounded, edge::bounded},
                                               {gap, 1.0, edge::bounded, edge::bounded}};
  std::vector<std::function<double(double)>> F{[](double s) { return -s; }, [](double s) { return -s; }};
  multi_solve_options<double> options;
  options.degree = 128;
  const auto fine = solve_union(par, intervals, F, options);
  // 1e-12: measured residual 2.4e-14 at degree 128 (1e-10 at 96 would not be; the cross terms are
  // nearly singular on the scale of the gap).
  CHECK(fine.residual < 1e-12);
  CHECK(fine.status == solve_status::converged);
  for (std::size_t points : {16, 32}) {
    options.degree = 16;
    options.residual_points = points;
    const auto coarse = solve_union(par, intervals, F, options);
    const double error = std::abs(coarse.densities[0].integral() / fine.densities[0].integral() - 1);
    INFO("residual points " << points << ": error " << error << ", residual " << coarse.residual);
    CHECK(error > 1e-4);                      // the degree-16 solution is poor ...
    CHECK(coarse.residual > error / 10);      // ... and its residual says so
    CHECK(coarse.status == solve_status::not_converged);
  }
}

// Gaps 1e-4 and 1e-6 (relative to lengths 1): the target residual 1e-10 is NOT reached by the
// global Jacobi representation (the densities have a boundary layer of the width of the gap at
// the facing ends; measured residual 2.6e-6 at degree 256 for gap 1e-4). The solver must say so:
// status not_converged, residual above the tolerance and decreasing with the degree.
TEST_CASE("nearly touching intervals (gaps 1e-4, 1e-6): not_converged with an honest residual") {
  abel_parameters<double> par(0.3, 0.2);
  for (double gap : {1e-4, 1e-6}) {
    std::vector<interval_spec<double>> intervals{{-1.0, 0.0, edge::bounded, edge::bounded},
                                                 {gap, 1.0, edge::bounded, edge::bounded}};
    std::vector<std::function<double(double)>> F{[](double s) { return -s; }, [](double s) { return -s; }};
    multi_solve_options<double> options;
    options.degree = 48;
    const auto sol = solve_union(par, intervals, F, options);
    INFO("gap=" << gap << " residual=" << sol.residual);
    CHECK(sol.status == solve_status::not_converged);
    CHECK(sol.residual > options.residual_tolerance);
  }
}

TEST_CASE("union: bad input") {
  abel_parameters<double> par(0.3, 0.2);
  std::vector<std::function<double(double)>> F{[](double) { return 1.0; }, [](double) { return 1.0; }};
  std::vector<interval_spec<double>> overlapping{{0.0, 1.0}, {0.5, 2.0}};
  CHECK_THROWS_AS(solve_union(par, overlapping, F), std::domain_error);
  std::vector<interval_spec<double>> one{{0.0, 1.0}};
  CHECK_THROWS_AS(solve_union(par, one, F), std::domain_error);
}
