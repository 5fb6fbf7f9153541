// Tests of rhabel/abel/multi_interval.hpp (paper 41, several contact intervals): independent
// residual, forward/inverse consistency against apply_union (own term spectral, cross terms by
// pointwise exterior quadrature), the decoupling limit of far-apart intervals, the homogeneous
// directions, and the nearly-touching hard case (honest report, no false convergence).
#include <doctest/doctest.h>

#include "rhabel/abel.hpp"
#include "support.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/eigen.hpp>

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

/// The nearly-touching configuration of the tests: [-1, 0] and [gap, 1] (lengths ~1, so gap is
/// relative), both with the given edge classes.
std::vector<interval_spec<double>> unit_pair(double gap, edge leading, edge trailing) {
  return {{-1.0, 0.0, leading, trailing}, {gap, 1.0, leading, trailing}};
}

/// F = -s (a parabola-like profile) on each of `count` intervals.
std::vector<std::function<double(double)>> minus_s(std::size_t count) {
  return std::vector<std::function<double(double)>>(count, [](double s) { return -s; });
}

/// solve_union on the bounded/bounded unit_pair(gap) with F = -s on both intervals.
multi_solution<double> solve_bounded_pair(const abel_parameters<double>& par, double gap,
                                          const multi_solve_options<double>& options) {
  return solve_union(par, unit_pair(gap, edge::bounded, edge::bounded), minus_s(2), options);
}

/// A density of class (leading, trailing) on [lo, hi] without coefficients (for the node sets).
jacobi_density<double> class_density(const abel_parameters<double>& par, double lo, double hi, edge leading,
                                     edge trailing) {
  jacobi_density<double> g;
  g.lo = lo;
  g.hi = hi;
  const auto e = par.exponents(leading, trailing);
  g.gam = e.gam;
  g.del = e.del;
  return g;
}

}  // namespace

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
    // condition of the collocation matrix (1/rcond): measured 1.1e3 (alpha 0.3) and 9.1e3 (0.7).
    CHECK(sol.condition < 1e5);
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
  double previous = 1e300;
  for (std::size_t degree : {16, 32, 64}) {
    multi_solve_options<double> options;
    options.degree = degree;
    const auto sol = solve_bounded_pair(par, 1e-6, options);
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
  multi_solve_options<double> options;
  options.degree = 128;
  const auto fine = solve_bounded_pair(par, gap, options);
  // 1e-12: measured residual 2.3e-14 at degree 128 (2.1e-11 at 96; the cross terms are nearly
  // singular on the scale of the gap).
  CHECK(fine.residual < 1e-12);
  CHECK(fine.status == solve_status::converged);
  for (std::size_t points : {16, 32}) {
    options.degree = 16;
    options.residual_points = points;
    const auto coarse = solve_bounded_pair(par, gap, options);
    const double error = std::abs(coarse.densities[0].integral() / fine.densities[0].integral() - 1);
    INFO("residual points " << points << ": error " << error << ", residual " << coarse.residual);
    CHECK(error > 1e-4);                      // the degree-16 solution is poor ...
    CHECK(coarse.residual > error / 10);      // ... and its residual says so
    CHECK(coarse.status == solve_status::not_converged);
  }
}

// Gap 1e-6 (relative to lengths 1): the polynomial degree the boundary layer needs (~ 8e3,
// extrapolated from the rate at gap 1e-4) is out of reach of the dense collocation. The solver
// must say so: status not_converged, the residual above the tolerance, and the adaptive loop
// stops at max_degree with the last degree reported.
TEST_CASE("gap 1e-6, alpha 0.3: not_converged with an honest residual, adaptive loop stops at max_degree") {
  abel_parameters<double> par(0.3, 0.2);
  const double gap = 1e-6;
  multi_solve_options<double> options;
  options.degree = 48;
  options.max_degree = 108;  // 48 -> 72 -> 108
  const auto sol = solve_bounded_pair(par, gap, options);
  INFO("residual=" << sol.residual);
  CHECK(sol.degree == 108);
  CHECK(sol.status == solve_status::not_converged);
  // Measured 2.6e-2 at degree 108 (study_union_convergence: 1e-1 ... 2e-7 at degree 512 over
  // alpha in [0, 0.9]); 1e-3 leaves room for a better method without hiding a false convergence.
  CHECK(sol.residual > 1e-3);
}

// Closed form (Muskhelishvili, finite Hilbert transform on a union of intervals): at alpha = 0,
// beta = 0 the operator is PV int g(t)/(t - s) dt on the union, and its null space with both
// intervals unbounded at both ends (nu = +1 on each) is sigma_i (c0 + c1 t)/sqrt|R(t)|,
// R = (t - a1)(t - b1)(t - a2)(t - b2), sigma_i = -1 on I_1, +1 on I_2 (the boundary values
// of 1/sqrt(R(z)) alternate in sign from cut to cut). The coupled homogeneous direction of
// interval 1 (unit load on I_1, zero on I_2) must be of that form: q(t) = sigma H(t) sqrt|R(t)|
// is ONE straight line across both intervals. The density has a boundary layer of width gap at
// the facing ends (the 1/sqrt(t - b1) factor on I_2 and 1/sqrt(a2 - t) on I_1).
TEST_CASE("gap 1e-4, alpha 0, beta 0: the coupled homogeneous density is (c0 + c1 t)/sqrt|R| (closed form)") {
  abel_parameters<double> par(0.0, 0.0);
  const double gap = 1e-4;
  const double a1 = -1.0, b1 = 0.0, a2 = gap, b2 = 1.0;
  std::vector<interval_spec<double>> intervals{{a1, b1, edge::unbounded, edge::unbounded},
                                               {a2, b2, edge::unbounded, edge::unbounded}};
  std::vector<std::function<double(double)>> F{[](double) { return 0.0; }, [](double) { return 0.0; }};
  multi_solve_options<double> options;
  options.degree = 1024;
  options.residual_points = 0;  // the closed form is the oracle here
  const auto sol = solve_union(par, intervals, F, options);
  REQUIRE(sol.homogeneous[0].size() == 2);
  const auto& H = sol.homogeneous[0];
  CHECK(H[0].integral() == doctest::Approx(1.0).epsilon(16 * eps));
  CHECK(std::abs(H[1].integral()) < 16 * eps);
  // sqrt|R| from the distances to the four ends (no cancellation next to an end).
  auto q = [&](std::size_t i, double from_lo, double to_hi) {
    const auto& g = H[i];
    const double t = g.lo + from_lo;
    const double R = i == 0 ? from_lo * to_hi * (a2 - t) * (b2 - t) : (t - a1) * (t - b1) * from_lo * to_hi;
    return (i == 0 ? -1.0 : 1.0) * g.value_at_distance(from_lo, to_hi) * std::sqrt(std::abs(R));
  };
  // The line through one point of each interval, checked at points spread over both intervals,
  // including 0.3 gap and 3 gap from the facing ends (inside the boundary layer).
  const double t_p = -0.5, t_r = 0.5 + gap / 2;
  const double q_p = q(0, t_p - a1, b1 - t_p), q_r = q(1, t_r - a2, b2 - t_r);
  const double slope = (q_r - q_p) / (t_r - t_p);
  const double size = std::max(std::abs(q_p), std::abs(q_r));
  struct probe {
    std::size_t i;
    double d;        // distance to the end named by from_lo
    bool from_lo;
  };
  const std::vector<probe> probes{{0, 1e-3, true},  {0, 0.3, false},    {0, 3 * gap, false}, {0, 0.3 * gap, false},
                                  {1, 0.3 * gap, true}, {1, 3 * gap, true}, {1, 0.25, true},    {1, 1e-3, false}};
  double worst = 0;
  for (const auto& pr : probes) {
    const double L = H[pr.i].hi - H[pr.i].lo;
    const double u = pr.from_lo ? pr.d : L - pr.d, v = pr.from_lo ? L - pr.d : pr.d;
    const double t = pr.from_lo ? H[pr.i].lo + u : H[pr.i].hi - v;
    worst = std::max(worst, std::abs(q(pr.i, u, v) - (q_p + slope * (t - t_p))) / size);
  }
  INFO("max deviation from one line: " << worst);
  // 1e-9: measured 1.9e-11 at degree 768 (1e-4 at degree 128); the line itself is O(1).
  CHECK(worst < 1e-9);
  CHECK(std::abs(slope) * 1 > 1e-3 * size);  // a genuine line, not a constant (c1 != 0)
}

// Regression "gap 1e-4": the layer of width 1e-4 needs an adaptive degree and cross blocks that
// stay cheap at high degree. Cross blocks by interpolation and re-expansion cost O(degree^3)
// each (degree 256 in 1.5 s), and at a fixed degree 256 the layer is not resolved (residual
// 2.6e-6; 3e-5 with points graded toward the facing ends); collocation with one matrix product
// per cross block reaches it. Oracle for int g: the same case at degree 1536 (residual
// 1.6e-14, against 1.8e-12 at degree 1024): a long-degree run, recorded here; reproduce with
// `build/bin/study_union_convergence out.csv 1536`, column loads of the row
// 2,1e-04,0.25,0.3,nu-1,1536.
TEST_CASE("gap 1e-4, alpha 0.25, beta 0.3, bounded ends: residual <= 1e-9 and int g to 1e-9 at degree 768") {
  abel_parameters<double> par(0.25, 0.3);
  const double gap = 1e-4;
  multi_solve_options<double> options;
  options.degree = 768;
  options.residual_points = 16;
  const auto sol = solve_bounded_pair(par, gap, options);
  const double reference[2] = {0.40988240595917425, 0.23221830030750071};  // degree 1536
  INFO("residual=" << sol.residual);
  // 1e-9: measured residual 3e-10 and int g errors 7e-11 at degree 768 (5e-8 and 2e-8 at 546).
  CHECK(sol.residual < 1e-9);
  for (std::size_t i = 0; i < 2; ++i) CHECK(std::abs(sol.densities[i].integral() / reference[i] - 1) < 1e-9);
}

// The adaptive degree (max_degree): three intervals, gap 1e-2, alpha 0.9, beta 0.3 (bounded
// leading, unbounded trailing edges: nu = 0), F = 1 - s^2/4. From degree 32 the loop must stop
// at the first degree whose independent residual is below the tolerance, and report it.
TEST_CASE("gap 1e-2, three intervals, alpha 0.9: the adaptive degree reaches the residual tolerance") {
  abel_parameters<double> par(0.9, 0.3);
  const double gap = 1e-2;
  std::vector<interval_spec<double>> intervals{{-1.0, 0.0, edge::bounded, edge::unbounded},
                                               {gap, 1.0, edge::bounded, edge::unbounded},
                                               {1.0 + gap, 2.0, edge::bounded, edge::unbounded}};
  std::vector<std::function<double(double)>> F(3, [](double s) { return 1 - s * s / 4; });
  multi_solve_options<double> options;
  options.degree = 32;
  options.max_degree = 512;
  options.residual_points = 16;
  const auto sol = solve_union(par, intervals, F, options);
  INFO("degree=" << sol.degree << " residual=" << sol.residual);
  CHECK(sol.status == solve_status::converged);
  CHECK(sol.residual <= options.residual_tolerance);
  CHECK(sol.degree > 32);    // degree 32 is not enough at this gap (measured residual ~ 1e-6) ...
  CHECK(sol.degree < 512);   // ... and the loop stops well before the cap
  // The previous rung (degree / 1.5) must not have converged: the loop stopped at the first success.
  multi_solve_options<double> previous = options;
  previous.degree = sol.degree * 2 / 3;
  previous.max_degree = 0;
  CHECK(solve_union(par, intervals, F, previous).status == solve_status::not_converged);
}

// 50 digits (regression: Eigen's rcond estimator needs NumTraits<Real>::infinity(), which the
// Boost.Multiprecision bindings lack, so solve_union did not compile for cpp_bin_float_50).
// Separated intervals (gap 0.5, lengths 1 and 0.5): the cross data are analytic in an ellipse
// of parameter ~ 3.7 around I_j, so degree 40 gives ~ 1e-25; the independent residual says so
// and int g agree with the double solve to double precision.
#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("50 digits: separated intervals converge far below double precision") {
  using R = boost::multiprecision::cpp_bin_float_50;
  abel_parameters<R> par(R(3) / 10, R(1) / 5);
  std::vector<interval_spec<R>> intervals{{R(-1), R(0), edge::bounded, edge::unbounded},
                                          {R(1) / 2, R(1), edge::bounded, edge::unbounded}};
  std::vector<std::function<R(R)>> F{[](R s) { return -s; }, [](R s) { return -s; }};
  multi_solve_options<R> options;
  options.degree = 40;
  options.residual_points = 6;
  options.residual_tolerance = R(1e-20);
  const auto sol = solve_union(par, intervals, F, options);
  // 1e-20: measured 7.7e-26 at degree 40.
  CHECK(sol.residual < R(1e-20));
  CHECK(sol.status == solve_status::converged);
  abel_parameters<double> par_d(0.3, 0.2);
  std::vector<interval_spec<double>> intervals_d{{-1.0, 0.0, edge::bounded, edge::unbounded},
                                                 {0.5, 1.0, edge::bounded, edge::unbounded}};
  std::vector<std::function<double(double)>> F_d{[](double s) { return -s; }, [](double s) { return -s; }};
  multi_solve_options<double> options_d;
  options_d.degree = 40;
  const auto sol_d = solve_union(par_d, intervals_d, F_d, options_d);
  for (std::size_t i = 0; i < 2; ++i) {
    const double exact = static_cast<double>(sol.densities[i].integral());
    // 16 eps: the double solve's rounding (collocation condition ~ 1e3; measured 1 eps).
    CHECK(std::abs(sol_d.densities[i].integral() - exact) <= 16 * eps * std::abs(exact));
  }
}
#endif  // RHABEL_TEST_MULTIPRECISION

// adapt_each_interval: a row of separated intervals with one nearly touching pair (gap 1e-3 of a
// length). Only the pair's degrees climb; the rest stay at the first degree. The answer is checked
// by apply_union (own term spectral, cross terms by pointwise exterior quadrature: not the solve's
// collocation nor its residual route) at points of every interval, and against the solve with one
// degree for all (the pair's), whose loads it must match within the residual tolerance's effect.
TEST_CASE("adapt_each_interval: only the nearly touching pair climbs; apply_union and the uniform solve agree") {
  const abel_parameters<double> par(0.3, 0.2);
  std::vector<interval_spec<double>> intervals;
  double x = 0;
  for (std::size_t k = 0; k < 10; ++k) {
    const double gap = k == 5 ? 1e-3 : 1.5;  // intervals 4 and 5 nearly touch
    x += k == 0 ? 0.0 : gap;
    intervals.push_back({x, x + 1, edge::bounded, edge::bounded});
    x += 1;
  }
  std::vector<std::function<double(double)>> F;
  for (std::size_t j = 0; j < intervals.size(); ++j)
    F.push_back([c = intervals[j].lo + 0.5](double s) { return c - s; });
  for (const std::size_t iterative_from : {std::size_t(0), std::size_t(6)}) {
    multi_solve_options<double> each;
    each.degree = 16;
    each.max_degree = 600;
    each.residual_tolerance = 1e-10;
    each.iterative_from = iterative_from;
    each.adapt_each_interval = true;
    const auto sol = solve_union(par, intervals, F, each);
    INFO("iterative_from " << iterative_from << ": residual " << sol.residual << ", degrees of the pair "
                           << sol.degrees[4] << " " << sol.degrees[5]);
    REQUIRE(sol.status == solve_status::converged);
    REQUIRE(sol.interval_residuals.size() == intervals.size());
    CHECK(sol.residual == *std::max_element(sol.interval_residuals.begin(), sol.interval_residuals.end()));
    for (std::size_t j = 0; j < intervals.size(); ++j) {
      if (j == 4 || j == 5)
        CHECK(sol.degrees[j] > 16);
      else
        CHECK(sol.degrees[j] == 16);
    }
    CHECK(sol.degree == std::max(sol.degrees[4], sol.degrees[5]));
    // apply_union at 40 points of each interval (another set than both grids), relative to the
    // data's size there: the residual tolerance times 10 (the residual is an estimate from 8
    // points a grid and the layer points; measured 1.2e-11 at the 400 points, the residual 9.4e-11).
    double worst = 0;
    for (std::size_t j = 0; j < intervals.size(); ++j) {
      double size = 0, miss = 0;
      for (int k = 0; k < 40; ++k) {
        const double s = intervals[j].lo + (intervals[j].hi - intervals[j].lo) * (0.013 + 0.974 * k / 39.0);
        const double h = (intervals[j].hi - intervals[j].lo) / 2;
        const double defect = std::pow(h, par.alpha()) * sol.solvability_defects[j];
        miss = std::max(miss, std::abs(apply_union(par, sol.densities, s) - (F[j](s) - defect)));
        size = std::max(size, std::abs(F[j](s)));
      }
      worst = std::max(worst, miss / size);
    }
    INFO("apply_union residual " << worst);
    CHECK(worst <= 10 * each.residual_tolerance);
    // One degree for all (the pair's, 271): the loads agree within the residual tolerance (the
    // separated intervals' series converge long before 16 there; measured 3e-15 relative).
    multi_solve_options<double> uniform = each;
    uniform.adapt_each_interval = false;
    uniform.degree = sol.degree;
    uniform.max_degree = 0;
    const auto all = solve_union(par, intervals, F, uniform);
    for (std::size_t j = 0; j < intervals.size(); ++j)
      CHECK(std::abs(sol.load(j) - all.load(j)) <= each.residual_tolerance * std::abs(all.load(j)));
  }
}

TEST_CASE("union: bad input") {
  abel_parameters<double> par(0.3, 0.2);
  std::vector<std::function<double(double)>> F{[](double) { return 1.0; }, [](double) { return 1.0; }};
  std::vector<interval_spec<double>> overlapping{{0.0, 1.0}, {0.5, 2.0}};
  CHECK_THROWS_AS(solve_union(par, overlapping, F), std::domain_error);
  std::vector<interval_spec<double>> one{{0.0, 1.0}};
  CHECK_THROWS_AS(solve_union(par, one, F), std::domain_error);
  std::vector<interval_spec<double>> two{{0.0, 1.0}, {1.5, 2.0}};
  multi_solve_options<double> options;
  options.degree = 64;
  options.max_degree = 32;  // below degree
  CHECK_THROWS_AS(solve_union(par, two, F, options), std::domain_error);
  options.max_degree = 128;
  options.residual_points = 0;  // nothing to drive the adaptive degree
  CHECK_THROWS_AS(solve_union(par, two, F, options), std::domain_error);
  // degrees: one per interval, each in [2, max_degree]
  options.residual_points = 8;
  options.degrees = {32};
  CHECK_THROWS_AS(solve_union(par, two, F, options), std::domain_error);
  options.degrees = {32, 1};
  CHECK_THROWS_AS(solve_union(par, two, F, options), std::domain_error);
  options.degrees = {32, 256};  // above max_degree 128
  CHECK_THROWS_AS(solve_union(par, two, F, options), std::domain_error);
}

// Memory guard (multi_interval.hpp, "Memory"): a degree whose dense system would exceed
// options.max_memory_bytes is refused with std::domain_error naming the option, its value and
// the largest admissible degree, before anything is allocated (regression: max_degree = 1e6
// must not start allocating a 3e13-byte matrix); the bound is sharp at the limit it reports.
TEST_CASE("union: memory guard refuses a degree beyond options.max_memory_bytes") {
  abel_parameters<double> par(0.3, 0.2);
  const std::vector<interval_spec<double>> two{{0.0, 1.0}, {1.5, 2.0}};
  const auto F = minus_s(2);
  multi_solve_options<double> options;
  options.degree = 32;
  options.max_degree = 1000000;  // (2e6)^2 doubles
  try {
    (void)solve_union(par, two, F, options);
    FAIL("no exception");
  } catch (const std::domain_error& e) {
    const std::string what = e.what();
    CHECK(what.find("solve_union") != std::string::npos);
    CHECK(what.find("options.max_degree") != std::string::npos);
    CHECK(what.find("1000000") != std::string::npos);
    CHECK(what.find("[2, 5181]") != std::string::npos);  // the default 2 GiB, two intervals
    CHECK(what.find("max_memory_bytes") != std::string::npos);
  }
  // No overflow of (K M)^2 in size_t: the largest degree is refused, not wrapped around.
  options.max_degree = std::numeric_limits<std::size_t>::max();
  CHECK_THROWS_AS(solve_union(par, two, F, options), std::domain_error);
  options.max_degree = 0;
  options.degree = std::numeric_limits<std::size_t>::max() / 2;
  CHECK_THROWS_AS(solve_union(par, two, F, options), std::domain_error);
  // Sharp at the reported limit: a bound of exactly the estimate at degree 24 admits 24 and
  // refuses 25 (one solve of 48 unknowns, no residual).
  options.degree = 24;
  options.residual_points = 0;
  options.max_memory_bytes = static_cast<std::size_t>(union_memory_bytes<double>(2, 24));
  CHECK(union_degree_limit<double>(2, options.max_memory_bytes) == 24);
  CHECK(solve_union(par, two, F, options).degree == 24);
  options.degree = 25;
  CHECK_THROWS_AS(solve_union(par, two, F, options), std::domain_error);
}

// detail::degree_graded_cross_nodes (the assembly's cross quadrature) and panel_integrator
// (numerics.hpp, behind make_cross_nodes, the residual's cross quadrature) grade the same way
// (union_assembly.hpp: same breaks 0, d, 3d, ..., same rules per panel); only the node count per
// panel differs (degree-dependent there, one count here). At degree 0 every panel gets 24 nodes,
// so the two node sets must coincide up to rounding, and the total count must be 24 per panel.
// Facing right, panel_integrator grades towards its len end: its panel ends there are stored as
// distances from 0 (2 - u, rounded), so its node distances to the facing end carry absolute
// errors ~ eps, i.e. relative ~ eps/d next to it (measured 2.3e-13 at gap 1e-4, d = 2e-4);
// degree_graded_cross_nodes measures u from the facing end itself.
TEST_CASE("cross nodes: degree_graded_cross_nodes at degree 0 == panel_integrator's nodes (same grading)") {
  const double x_tolerance = 4 * eps;  // absolute: one rounding of a distance <= 2
  const abel_parameters<double> par(0.3, 0.3);
  for (const auto& [leading, trailing] : {std::pair{edge::bounded, edge::unbounded}, std::pair{edge::unbounded, edge::bounded}})
    for (double gap : {1e-4, 0.3})
      for (bool facing_left : {true, false}) {
        const auto g = class_density(par, 2.0, 3.0, leading, trailing);
        auto graded = detail::degree_graded_cross_nodes(g, gap, facing_left, 0);
        auto fixed = make_cross_nodes(g, gap, facing_left, 24);
        INFO("gap " << gap << " facing_left " << facing_left << " gam " << g.gam);
        REQUIRE(graded.x.size() == fixed.x.size());
        CHECK(graded.x.size() % 24 == 0);
        // order by x (the two walk the panels in opposite directions when facing right)
        auto order = [](const cross_nodes<double>& c) {
          std::vector<std::size_t> idx(c.x.size());
          for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
          std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return c.x[a] < c.x[b]; });
          return idx;
        };
        const auto ig = order(graded), jf = order(fixed);
        double worst_x = 0, worst_w = 0;
        for (std::size_t r = 0; r < ig.size(); ++r) {
          worst_x = std::max(worst_x, std::abs(graded.x[ig[r]] - fixed.x[jf[r]]));
          worst_w = std::max(worst_w, std::abs(graded.weight[ig[r]] / fixed.weight[jf[r]] - 1));
        }
        // pow of a distance with <= 2 eps relative error times a few roundings (16 eps); facing
        // right, times 2/d for panel_integrator's distances near its len end (above).
        const double weight_tolerance = facing_left ? 16 * eps : 16 * eps * 2 / (gap / g.half_length());
        CHECK(worst_x <= x_tolerance);
        CHECK(worst_w <= weight_tolerance);
      }
}

// The degree-dependent node counts resolve P_n: with a constant kernel the cross integral is
// int w P_n = h_0 delta_n0 (orthogonality; an exact identity sharing no code with the node
// construction), for every n < degree, at the nearly-touching gap 1e-4 and degree 1024 (the
// regime the counts were designed for), relative to h sqrt(h_0 h_n) (the Cauchy-Schwarz size).
TEST_CASE("cross nodes: degree_graded_cross_nodes integrate w P_n exactly up to rounding, n < 1024, gap 1e-4") {
  const abel_parameters<double> par(0.3, 0.3);
  const std::size_t degree = 1024;
  for (const auto& [leading, trailing] : {std::pair{edge::bounded, edge::unbounded}, std::pair{edge::unbounded, edge::unbounded}})
    for (bool facing_left : {true, false}) {
      const auto g = class_density(par, 0.0, 1.0, leading, trailing);
      const auto nodes = detail::degree_graded_cross_nodes(g, 1e-4, facing_left, degree);
      std::vector<double> moments(degree, 0.0);
      for (std::size_t q = 0; q < nodes.x.size(); ++q) {
        const auto P = rhabel::quadrature::jacobi_p_all(degree - 1, g.del, g.gam, nodes.x[q]);
        for (std::size_t n = 0; n < degree; ++n) moments[n] += nodes.weight[q] * P[n];
      }
      const double h = g.half_length(), h0 = rhabel::quadrature::jacobi_norm_squared(0, g.del, g.gam);
      double worst = std::abs(moments[0] / (h * h0) - 1);
      std::size_t worst_n = 0;
      for (std::size_t n = 1; n < degree; ++n) {
        const double scale = h * std::sqrt(h0 * rhabel::quadrature::jacobi_norm_squared(n, g.del, g.gam));
        if (std::abs(moments[n]) / scale > worst) {
          worst = std::abs(moments[n]) / scale;
          worst_n = n;
        }
      }
      INFO("gam " << g.gam << " del " << g.del << " facing_left " << facing_left << ": worst n = " << worst_n);
      // 1e-11: the cross blocks feed a solve whose target is the residual 1e-10 (the default
      // residual_tolerance). Measured 1.9e-14 (bounded/unbounded) and 3.9e-12 (unbounded at both
      // ends, gam = -0.95, at the top degrees n = 1022, 1023).
      CHECK(worst <= 1e-11);
    }
}

namespace {
/// The largest coefficient of a's densities and the largest difference from b's coefficients
/// (a's count on each interval).
std::pair<double, double> coefficient_difference(const multi_solution<double>& a, const multi_solution<double>& b) {
  double size = 0, worst = 0;
  for (std::size_t j = 0; j < a.densities.size(); ++j)
    for (std::size_t n = 0; n < a.densities[j].coefficients.size(); ++n) {
      size = std::max(size, std::abs(a.densities[j].coefficients[n]));
      worst = std::max(worst, std::abs(a.densities[j].coefficients[n] - b.densities[j].coefficients[n]));
    }
  return {size, worst};
}

}  // namespace

// The iterative route (multi_solve_options::iterative_from; detail/block_gmres.hpp) solves the
// same collocation system as the LU: six intervals of all three classes (bounded/bounded nu = -1,
// bounded/unbounded nu = 0, unbounded/unbounded nu = +1 with a load), gaps from 0.2 to 2 of a
// length, so that the preconditioned coupling is not small. GMRES stops at |b - A x| <= 1e-14
// |b|; the coefficients then differ from the LU's by at most ~ condition x 1e-14 of their size.
TEST_CASE("iterative_from: block-preconditioned GMRES gives the LU's coefficients, defects and homogeneous solutions") {
  // condition (measured 2.0e2 at alpha 0, 1.5e3 at 0.3) x GMRES's 1e-14, with a margin; measured
  // differences 2.5e-15 and 4.2e-15 of the largest coefficient.
  const double coefficient_tolerance = 1e-11;
  // Both with one degree for all and with a degree per interval (options.degrees: the diagonal
  // blocks of unequal sizes, M_j x M_i cross blocks).
  for (const bool mixed : {false, true})
  for (double alpha : {0.0, 0.3}) {
    const abel_parameters<double> par(alpha, 0.2);
    const std::vector<interval_spec<double>> intervals{{-4.0, -3.0, edge::bounded, edge::bounded},
                                                       {-2.8, -2.0, edge::unbounded, edge::unbounded},
                                                       {-1.0, 0.0, edge::bounded, edge::unbounded},
                                                       {1.5, 2.0, edge::bounded, edge::bounded},
                                                       {2.1, 3.2, edge::unbounded, edge::unbounded},
                                                       {5.0, 5.7, edge::bounded, edge::bounded}};
    std::vector<std::function<double(double)>> F;
    for (std::size_t j = 0; j < intervals.size(); ++j)
      F.push_back([j](double s) { return std::cos(s + 0.3 * static_cast<double>(j)) - 0.1 * s; });
    multi_solve_options<double> direct;
    direct.degree = 24;
    if (mixed) direct.degrees = {24, 17, 32, 20, 24, 28};
    direct.loads = {std::nullopt, 0.4, std::nullopt, std::nullopt, 0.9, std::nullopt};
    multi_solve_options<double> iterative = direct;
    iterative.iterative_from = 2;
    const auto a = solve_union(par, intervals, F, direct);
    const auto b = solve_union(par, intervals, F, iterative);
    INFO("alpha " << alpha << ", a degree per interval: " << mixed << ", residual " << a.residual);
    if (mixed) {
      CHECK(a.degrees == direct.degrees);
      CHECK(a.degree == 32);
      for (std::size_t j = 0; j < intervals.size(); ++j)  // nu = -1: M - 1 coefficients; 0: M; +1: M + 1
        CHECK(static_cast<long>(a.densities[j].coefficients.size()) ==
              static_cast<long>(direct.degrees[j]) + a.exponents[j].nu);
    }
    CHECK(std::abs(b.residual - a.residual) <= 1e-12);
    CHECK(std::isnan(b.condition));
    const auto [size, worst] = coefficient_difference(a, b);
    CHECK(worst <= coefficient_tolerance * size);
    for (std::size_t j = 0; j < intervals.size(); ++j)
      CHECK(std::abs(a.solvability_defects[j] - b.solvability_defects[j]) <= coefficient_tolerance * size);
    for (std::size_t k : {std::size_t(1), std::size_t(4)}) {
      REQUIRE(b.homogeneous[k].size() == intervals.size());
      for (std::size_t j = 0; j < intervals.size(); ++j)
        for (std::size_t n = 0; n < a.homogeneous[k][j].coefficients.size(); ++n)
          CHECK(std::abs(a.homogeneous[k][j].coefficients[n] - b.homogeneous[k][j].coefficients[n]) <=
                coefficient_tolerance * size);
    }
  }
}

namespace {
/// A row of 40 intervals of the three classes with loads on the nu = +1 ones, gaps of 0.4 ... 2.5
/// lengths (near pairs and far ones); every interval's upper end moved by `stretch` of its length.
struct separated_row {
  std::vector<interval_spec<double>> intervals;
  std::vector<std::optional<double>> loads;
  std::vector<std::function<double(double)>> F;

  explicit separated_row(double stretch = 0) {
    double x = 0;
    for (std::size_t k = 0; k < 40; ++k) {
      const double L = 1 + 0.5 * std::sin(1.7 * double(k));
      const edge e1 = k % 3 == 2 ? edge::unbounded : edge::bounded, e2 = k % 3 == 0 ? edge::bounded : edge::unbounded;
      intervals.push_back({x, x + L * (1 + stretch), e1, e2});
      loads.push_back(k % 3 == 2 ? std::optional<double>(0.2 + 0.01 * double(k)) : std::nullopt);
      x += L * (1.4 + 1.1 * (1 + std::cos(2.3 * double(k))));
    }
    for (std::size_t j = 0; j < intervals.size(); ++j)
      F.push_back([j](double s) { return std::cos(0.1 * s + 0.3 * static_cast<double>(j)) - 0.01 * s; });
  }
};
}  // namespace

// Many intervals with separated pairs: the far-field route (only own and near blocks assembled,
// the rest applied through far_field.hpp inside GMRES) solves the same collocation system
// as the LU on the assembled matrix (separated_row).
TEST_CASE("iterative_from with separated intervals: the far-field route gives the LU's coefficients and defects") {
  // GMRES's 1e-14 relative residual times the condition (~1e3 here, as in the test above) plus
  // the far field's relative error (residual_tolerance/1000 = 1e-13), with a margin.
  const double coefficient_tolerance = 1e-10;
  const abel_parameters<double> par(0.3, 0.2);
  const separated_row row_problem;
  const auto& [intervals, loads, F] = row_problem;
  multi_solve_options<double> direct;
  direct.degree = 24;
  direct.loads = loads;
  direct.homogeneous = false;
  multi_solve_options<double> far = direct;
  far.iterative_from = 6;
  const auto a = solve_union(par, intervals, F, direct);
  const auto b = solve_union(par, intervals, F, far);
  INFO("residuals " << a.residual << " (LU), " << b.residual << " (far field)");
  CHECK(a.residual < 1e-9);
  CHECK(b.residual < 1e-9);
  CHECK(std::abs(a.residual - b.residual) <= 1e-12);
  CHECK(std::isnan(b.condition));  // the iterative route was taken
  const auto [size, worst] = coefficient_difference(a, b);
  INFO("largest coefficient difference " << worst << " of " << size);
  CHECK(worst <= coefficient_tolerance * size);
  for (std::size_t j = 0; j < intervals.size(); ++j)
    CHECK(std::abs(a.solvability_defects[j] - b.solvability_defects[j]) <= coefficient_tolerance * size);
  // Memory: the far route's estimate at 1000 such intervals is tens of megabytes (measured 39 MB,
  // mostly the pairs' 20 x 20 kernel matrices), the dense matrix's gigabytes.
  std::vector<far_field<double>::box> boxes;
  for (std::size_t k = 0; k < 1000; ++k) boxes.push_back({1.5 * double(k), 1.5 * double(k) + 1});
  const far_field<double> row(par, boxes, 20);
  CHECK(union_far_memory_bytes(row, 16) < 50e6);
  CHECK(union_memory_bytes<double>(1000, 16) > 2e9);
  CHECK(union_far_degree_limit(row, std::size_t(1) << 30) > 100);
}

// multi_solve_options::first_guess: GMRES on the far-field route started from the unknowns of a
// nearby solve (every upper end moved by 1e-6 of its length, as a Newton iteration's differences
// move edges) takes fewer products and reaches the same answer; a guess at other degrees is not
// used (the same products as from zero, the same coefficients bit for bit).
TEST_CASE("first_guess: a nearby solve's unknowns start the far-field GMRES, the answer unchanged") {
  // Both solves meet GMRES's 1e-14 relative residual: their coefficients differ by ~ the
  // condition (~1e3) times that, as the LU's and GMRES's do above.
  const double coefficient_tolerance = 1e-10;
  const abel_parameters<double> par(0.3, 0.2);
  const separated_row base, moved(1e-6);
  multi_solve_options<double> options;
  options.degree = 24;
  options.loads = base.loads;
  options.homogeneous = false;
  options.iterative_from = 6;
  const auto at_base = solve_union(par, base.intervals, base.F, options);
  REQUIRE(at_base.unknowns);
  CHECK(at_base.unknowns->degrees == at_base.degrees);
  const auto from_zero = solve_union(par, moved.intervals, moved.F, options);
  auto guessed = options;
  guessed.first_guess = at_base.unknowns;
  const auto from_base = solve_union(par, moved.intervals, moved.F, guessed);
  INFO("GMRES products: " << from_zero.gmres_products << " from zero, " << from_base.gmres_products << " from the base");
  CHECK(from_zero.gmres_products > 0);
  CHECK(from_base.gmres_products < from_zero.gmres_products);
  CHECK(std::abs(from_base.residual - from_zero.residual) <= 1e-12);
  const auto [size, worst] = coefficient_difference(from_zero, from_base);
  CHECK(worst <= coefficient_tolerance * size);
  // Other degrees: the guess is not used.
  auto other = options;
  other.degree = 20;
  const auto plain = solve_union(par, moved.intervals, moved.F, other);
  other.first_guess = at_base.unknowns;
  const auto ignored = solve_union(par, moved.intervals, moved.F, other);
  CHECK(ignored.gmres_products == plain.gmres_products);
  for (std::size_t j = 0; j < base.intervals.size(); ++j)
    CHECK(ignored.densities[j].coefficients == plain.densities[j].coefficients);
}

// multi_solve_options::homogeneous = false leaves the homogeneous solutions out and changes
// nothing else (the particular solve is the same solve, bit for bit).
TEST_CASE("homogeneous = false: no homogeneous solutions, the same densities") {
  const abel_parameters<double> par(0.3, 0.2);
  const std::vector<interval_spec<double>> intervals{{-1.0, 0.0, edge::unbounded, edge::unbounded},
                                                     {0.5, 1.5, edge::unbounded, edge::unbounded}};
  multi_solve_options<double> options;
  options.degree = 16;
  options.loads = {0.5, 0.7};
  auto without = options;
  without.homogeneous = false;
  const auto a = solve_union(par, intervals, minus_s(2), options);
  const auto b = solve_union(par, intervals, minus_s(2), without);
  CHECK(b.homogeneous[0].empty());
  CHECK(b.homogeneous[1].empty());
  CHECK(a.densities[0].coefficients == b.densities[0].coefficients);
  CHECK(a.densities[1].coefficients == b.densities[1].coefficients);
}

// Separated pairs (gap >= the source's half-length h): the cross block's single-panel rule of
// separated_cross_nodes (n/2 + ~20 nodes at gap = h, fewer farther away) against the
// graded rule at 4x the resolution (make_cross_nodes, 4 degree + 64 nodes per panel), for both
// classes of the source, both sides, gaps 1, 2.5 and 40 half-lengths.
TEST_CASE("cross nodes: separated pairs reach rounding with separated_cross_nodes") {
  // relative to the block's largest entry: a few roundings (measured 3.7e-16 .. 1.7e-15 with 40,
  // 36, 28 nodes at gap/h 1, 2.5, 40, degree 40; the graded rule's single panel would take 88)
  const double entry_tolerance = 1e-14;
  const abel_parameters<double> par(0.3, 0.2);
  const std::size_t degree = 40;
  for (const auto& [leading, trailing] : {std::pair{edge::bounded, edge::bounded}, std::pair{edge::unbounded, edge::unbounded}})
    for (double gap_over_h : {1.0, 2.5, 40.0})
      for (bool right : {true, false}) {
        const auto g = class_density(par, 2.0, 3.0, leading, trailing);  // h = 0.5
        const double gap = gap_over_h * g.half_length();
        CHECK(separated_cross_nodes(gap_over_h, degree) < detail::cross_panel_nodes(0.0, 2.0, degree));
        std::vector<double> dist;
        for (int k = 0; k < 12; ++k) dist.push_back(0.1 * k * k);  // target points 0 .. 12 from the facing end
        auto kernel = [&](double t_minus_s) { return cross_kernel(par, t_minus_s); };
        const auto B = detail::cross_block(g, gap, right, dist, degree, 1.0, kernel);
        const auto fine = make_cross_nodes(g, gap, right, 4 * degree + 64);
        double size = 0, worst = 0;
        for (std::size_t k = 0; k < dist.size(); ++k) {
          std::vector<double> reference(degree, 0.0);
          for (std::size_t q = 0; q < fine.x.size(); ++q) {
            const double t_minus_s = right ? fine.t_minus_lo[q] + gap + dist[k] : -(fine.hi_minus_t[q] + gap + dist[k]);
            const auto P = rhabel::quadrature::jacobi_p_all(degree - 1, g.del, g.gam, fine.x[q]);
            for (std::size_t n = 0; n < degree; ++n) reference[n] += fine.weight[q] * kernel(t_minus_s) * P[n];
          }
          for (std::size_t n = 0; n < degree; ++n) {
            size = std::max(size, std::abs(reference[n]));
            worst = std::max(worst, std::abs(B(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(n)) - reference[n]));
          }
        }
        INFO("gam " << g.gam << " gap/h " << gap_over_h << " right " << right << ": worst " << worst / size);
        CHECK(worst <= entry_tolerance * size);
      }
}
