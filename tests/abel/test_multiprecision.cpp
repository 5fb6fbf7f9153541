// The abel module at 50 decimal digits (boost::multiprecision::cpp_bin_float_50): the spectral
// relation against the independent one-sided quadrature, and the parabolic closed form
// reproduced by the generic solver, both to ~1e-40. Shows that every routine is generic in Real.
#include <doctest/doctest.h>

#include "rhabel/abel.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <limits>

using namespace rhabel::abel;
using real50 = boost::multiprecision::cpp_bin_float_50;

TEST_CASE("50 digits: spectral relation == one-sided quadrature (alpha = 0.3 and alpha = 0)") {
  const real50 eps50 = std::numeric_limits<real50>::epsilon();
  for (const real50& alpha : {real50(3) / 10, real50(0)}) {
    abel_operator<real50> op(alpha, real50(1) / 5, real50(-1), real50(2));
    const auto e = op.exponents(edge::bounded, edge::unbounded);
    jacobi_density<real50> g{real50(-1), real50(2), e.gam, e.del, {real50(1), real50(-1) / 3, real50(1) / 7}};
    // degree hint 80 -> 52 nodes per panel: measured 1e-28 with 32 nodes, 1e-45 with 52.
    const typename abel_operator<real50>::quadrature_evaluator direct(op, e.gam, e.del, 80);
    for (const real50& s : {real50(-1) / 2, real50(1), real50(19) / 10}) {
      const real50 spectral = op.apply(g, s);
      const real50 quadrature = direct([&](const real50& x) { return g.series(x); }, s);
      // 1e10 eps (~1e-40); measured <= 5e-45 relative.
      CHECK(abs(spectral - quadrature) <= 1e10 * eps50 * (abs(spectral) + abs(g(s))));
    }
  }
}

TEST_CASE("50 digits: parabolic punch closed form (nu = -1)") {
  const real50 eps50 = std::numeric_limits<real50>::epsilon();
  const real50 pi = boost::math::constants::pi<real50>();
  const real50 alpha = real50(1) / 4, beta = real50(3) / 10, L = 2, R = 1;
  const real50 b = L * (1 - 2 * alpha - beta) / (2 * (1 - alpha)), a = b - L;
  abel_operator<real50> op(alpha, beta, a, b);
  const real50 G = boost::math::tgamma(1 - alpha);
  solve_options<real50> options;
  options.residual_points = 0;  // the 50-digit residual is exercised by the test above
  const auto sol = solve(op, edge::bounded, edge::bounded, [&](const real50& s) { return -s / (R * G); }, options);
  const auto& e = sol.exponents;
  for (const real50& t : {a + real50(1) / 10, real50(0), b - real50(1) / 100}) {
    const real50 exact = cos(beta * pi / 2) * pow(t - a, e.gam) * pow(b - t, e.del) / (pi * R * boost::math::tgamma(2 - alpha));
    // 1e4 eps (~1e-46): a handful of pow/gamma evaluations and one re-expansion.
    CHECK(abs(sol.density(t) / exact - 1) <= 1e4 * eps50);
  }
  CHECK(abs(sol.solvability_defect) <= 1e4 * eps50);
}

TEST_CASE("regression: double Gauss-Jacobi rule with both exponents at -1 + 1e-9 against 50 digits") {
  // The abel module reaches this corner (class nu = +1 as alpha -> 1, beta -> -1; step enrichment
  // as alpha -> 0, 2 alpha + beta -> 1). Recurrence constants expanded in p and q cancel there
  // (1.6e5 eps in the weights); the quadrature module's own table test covers the corner, this
  // pins the case as abel uses it. Oracle: the 50-digit
  // recurrence path of quadrature::gauss_jacobi (another algorithm: n = 80 takes the asymptotic path in double).
  const double eps = std::numeric_limits<double>::epsilon();
  // 45 eps: the quadrature module's contract (1e-14 relative) for p, q in (-1, 5].
  constexpr double contract = 45;
  for (const double p : {-1 + 1e-9, -1 + 1e-6}) {
    const double q = -1 + 1e-9;
    for (const std::size_t n : {std::size_t(16), std::size_t(40), std::size_t(80)}) {
      const auto rule = cached_gauss_jacobi_rule<double>(n, p, q);
      const auto ref = rhabel::quadrature::gauss_jacobi<real50>(n, real50(p), real50(q));
      REQUIRE(rule->size() == n);
      for (std::size_t i = 0; i < n; ++i) {
        CHECK(abs(real50(rule->weight[i]) - ref.weight[i]) <= contract * eps * ref.weight[i]);
        CHECK(abs(real50(rule->x_minus_lo[i]) - ref.x_minus_lo[i]) <= contract * eps * ref.x_minus_lo[i]);
        CHECK(abs(real50(rule->hi_minus_x[i]) - ref.hi_minus_x[i]) <= contract * eps * ref.hi_minus_x[i]);
      }
    }
  }
}
