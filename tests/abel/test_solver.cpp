// Tests of rhabel/abel/abel_solver.hpp: the closed forms of docs/theory.md section 5 reproduced by the
// generic solver, independent residuals on smooth data over the hard parameter grid and over
// interval lengths 1e-9 .. 1e6, and the evidence fields (defect, homogeneous solution, load).
#include <doctest/doctest.h>

#include "rhabel/abel.hpp"
#include "support.hpp"

#include <boost/math/special_functions/beta.hpp>

#include <cmath>
#include <limits>
#include <vector>

using namespace rhabel::abel;
using namespace abel_test;

// Parabolic punch (docs/theory.md section 5): f' = -s/R, nu = -1, b = L (1 - 2 alpha - beta)/(2 (1 - alpha)),
// g = cos(beta pi/2) (t-a)^gam (b-t)^del / (pi R Gamma(2 - alpha)), C_f = (alpha+beta)(2-alpha) L/((1-alpha)(3-alpha) R).
TEST_CASE("parabolic punch closed form (nu = -1) reproduced by the generic solver, all hard alphas and betas") {
  for (double alpha : hard_alphas) {
    for (double beta : betas) {
      const double L = 2.0, R = 1.5;
      const double b = L * (1 - 2 * alpha - beta) / (2 * (1 - alpha)), a = b - L;
      abel_operator<double> op(alpha, beta, a, b);
      const double G = std::tgamma(1 - alpha);
      const auto sol = solve(op, edge::bounded, edge::bounded, [&](double s) { return -s / (R * G); });
      INFO("alpha=" << alpha << " beta=" << beta);
      CHECK(sol.exponents.nu == -1);
      CHECK(sol.status == solve_status::converged);
      // The contact interval of the closed form satisfies the solvability condition:
      // defect relative to max|F~| ~ 1, 64 eps (interpolation + re-expansion rounding).
      // Scale: max|F~|; for alpha -> 1 the interval moves to |s| ~ L/(1-alpha) and F is a large
      // constant plus an O(L) variation, which is what determines g: conditioning max|s|/L.
      const double conditioning = 1 + std::max(std::abs(a), std::abs(b)) / L;
      // The image basis of nu = -1 has p + q + 2 = 1 - alpha: P_1 = (1-alpha)/2 x + (p-q)/2, so
      // re-expanding x costs a further factor 1/(1 - alpha) in the defect.
      CHECK(std::abs(sol.solvability_defect) <=
            64 * eps * conditioning / (1 - alpha) * std::abs(std::pow(op.half_length(), -alpha) * L / (R * G)));
      // A few ulps on the density (64 eps: pow, tgamma, the eigenvalue product, re-expansion).
      for (double t : {a + 1e-9, a + 0.1, a + 1.0, b - 0.3, b - 1e-7}) {
        const auto e = sol.exponents;
        const double exact = std::cos(beta * pi / 2) * std::pow(t - a, e.gam) * std::pow(b - t, e.del) /
                             (pi * R * std::tgamma(2 - alpha));
        CHECK(sol.density(t) == doctest::Approx(exact).epsilon(64 * eps * conditioning));
      }
      // Hysteretic friction coefficient C_f = int f' g / int g (f' = -s/R); 64 eps: quadrature of a
      // polynomial times the weight, exact up to rounding.
      const double Cf = sol.density.integrate([&](double s) { return -s / R; }) / sol.density.integral();
      const double Cf_exact = (alpha + beta) * (2 - alpha) * L / ((1 - alpha) * (3 - alpha) * R);
      CHECK(Cf == doctest::Approx(Cf_exact).epsilon(64 * eps * conditioning).scale(L / R));
      // Independent residual (direct quadrature of the one-sided integrals).
      CHECK(sol.residual <= 1e-13 * conditioning);
    }
  }
}

// Wedge with alpha + beta/2 >= 1/2: contact ends at the apex b = 0, nu = 0 (bounded at a,
// unbounded at b), F = S1/Gamma(1-alpha), g = S1 cos(beta pi/2) (t-a)^gam (b-t)^del/(pi Gamma(1-alpha)).
TEST_CASE("wedge closed form for alpha + beta/2 >= 1/2 (nu = 0)") {
  for (double alpha : {0.5, 0.5 + 1e-9, 0.7, 0.9, 0.999}) {
    for (double beta : betas) {
      const double S1 = 0.8, L = 3.0, a = -L, b = 0.0;
      abel_operator<double> op(alpha, beta, a, b);
      const double G = std::tgamma(1 - alpha);
      const auto sol = solve(op, edge::bounded, edge::unbounded, [&](double) { return S1 / G; });
      CHECK(sol.exponents.nu == 0);
      for (double t : {a + 1e-6, -1.5, b - 1e-8}) {
        const double exact = S1 * std::cos(beta * pi / 2) * std::pow(t - a, sol.exponents.gam) *
                             std::pow(b - t, sol.exponents.del) / (pi * G);
        CHECK(sol.density(t) == doctest::Approx(exact).epsilon(64 * eps));
      }
      // Also for alpha + beta/2 = 1/2 exactly kappa = 0 (alpha = 0.5, beta = 0 above).
    }
  }
}

// Flat punch (alpha + beta/2 < 1/2): nu = +1, the homogeneous solution w = (t-a)^gam (b-t)^del.
TEST_CASE("flat punch: homogeneous solution (nu = +1), unit load, A w = 0 by the independent route") {
  for (double alpha : {0.0, 1e-8, 0.25, 0.45}) {
    for (double beta : {0.0, 0.05}) {
      abel_operator<double> op(alpha, beta, -0.5, 1.5);
      solve_options<double> options;
      options.load = 2.5;
      const auto sol = solve(op, edge::unbounded, edge::unbounded, [](double) { return 0.0; }, options);
      CHECK(sol.exponents.nu == 1);
      CHECK(sol.homogeneous.integral() == doctest::Approx(1.0).epsilon(8 * eps));
      CHECK(sol.density.integral() == doctest::Approx(2.5).epsilon(8 * eps));
      // Shape: g/(w) constant.
      const auto& e = sol.exponents;
      const double r1 = sol.density(-0.4) / (std::pow(0.1, e.gam) * std::pow(1.9, e.del));
      const double r2 = sol.density(1.2) / (std::pow(1.7, e.gam) * std::pow(0.3, e.del));
      CHECK(r1 == doctest::Approx(r2).epsilon(8 * eps));
      // A w = 0, by direct quadrature; scale: the size of the one-sided terms |g(s)| (L/2)^alpha.
      for (double s : {-0.3, 0.5, 1.4}) {
        const double Aw = op.apply_by_quadrature([](double) { return 1.0; }, e.gam, e.del, s, 4);
        CHECK(std::abs(Aw) <= 1e-13 * sol.homogeneous(s) / sol.homogeneous.coefficients[0]);
      }
      // with_load adds the homogeneous solution.
      CHECK(sol.with_load(-1.0).integral() == doctest::Approx(-1.0).epsilon(8 * eps));
    }
  }
}

// Wedge with alpha + beta/2 < 1/2 (nu = -1): the solvability (orthogonality) condition becomes
// I_eps((1+beta)/2, (1-2alpha-beta)/2) = S2/(S1+S2), eps = -a/L (docs/theory.md section 5).
TEST_CASE("wedge nu = -1: the incomplete-beta condition makes the solvability defect vanish") {
  for (double alpha : {0.0, 1e-3, 0.2, 0.4}) {
    for (double beta : {0.0, 0.3}) {
      if (alpha + beta / 2 >= 0.5) continue;
      const double S1 = 1.0, S2 = 0.6, L = 2.0;
      const double e = boost::math::ibeta_inv((1 + beta) / 2, (1 - 2 * alpha - beta) / 2, S2 / (S1 + S2));
      const double a = -e * L, b = a + L;
      abel_operator<double> op(alpha, beta, a, b);
      const double G = std::tgamma(1 - alpha);
      auto F = [&](double s) { return s < 0 ? S1 / G : -S2 / G; };
      solve_options<double> options;
      options.degree = 64;
      const auto sol = solve_piecewise(op, edge::bounded, edge::bounded, F, {0.0}, options);
      // The defect is an integral of exact piecewise-constant data: 64 eps of max|F~|.
      CHECK(std::abs(sol.solvability_defect) <= 64 * eps * std::pow(op.half_length(), -alpha) * S1 / G);
      // A wrong interval gives a clearly nonzero defect.
      abel_operator<double> shifted(alpha, beta, a + 0.1, b + 0.1);
      const auto wrong = solve_piecewise(shifted, edge::bounded, edge::bounded, F, {0.0}, options);
      CHECK(std::abs(wrong.solvability_defect) > 1e-3);
    }
  }
}

// Smooth, non-polynomial data: independent residual over the whole parameter grid, every
// class, and interval lengths from 1e-9 to 1e6.
TEST_CASE("independent residual on smooth data: hard alphas x betas x classes x interval lengths") {
  struct cls {
    edge leading, trailing;
  };
  const std::vector<cls> classes{{edge::bounded, edge::bounded},
                                 {edge::bounded, edge::unbounded},
                                 {edge::unbounded, edge::bounded},
                                 {edge::unbounded, edge::unbounded}};
  int solved = 0;
  for (double length : {1e-9, 1.0, 1e6}) {
    for (double alpha : hard_alphas) {
      for (double beta : betas) {
        const double lo = 0.3 * length, hi = lo + length;
        abel_operator<double> op(alpha, beta, lo, hi);
        for (const auto& c : classes) {
          if (c.leading == edge::unbounded && 2 * alpha + beta >= 1) continue;
          // exp and cos of the normalised abscissa: entire, needs ~ 20-30 Chebyshev points.
          auto F = [&](double s) {
            const double u = (s - lo) / length;
            return std::exp(0.7 * u) * std::cos(3 * u + 0.4) + 0.2;
          };
          const auto sol = solve(op, c.leading, c.trailing, F);
          INFO("length=" << length << " alpha=" << alpha << " beta=" << beta << " nu=" << sol.exponents.nu);
          CHECK(sol.status == solve_status::converged);
          CHECK(sol.degree <= 65);
          // 2e-13 relative to max|F|; the near-degenerate classes (gam + 1 ~ 1e-9) are limited by the
          // conditioning of the double exponent, see test_operator.cpp.
          const double conditioning = 100 * eps * std::abs(op.parameters().kappa()) /
                                      ((sol.exponents.gam + 1) * (sol.exponents.gam + 1));
          // alpha -> 1: lambda_n ~ (1 - alpha)/n for n >= 1 and the image basis has p < -1: the
          // coefficients grow like 1/(1 - alpha) and the residual (a difference of such terms) with
          // them; measured 4.6e-10 at alpha = 0.999 (beta = 0.9, nu = -1).
          const double near_one = 1 + std::pow(0.1 / (1 - alpha), 2);
          CHECK(sol.residual <= 1000 * eps * near_one + conditioning);
          ++solved;
        }
      }
    }
  }
  CHECK(solved > 200);
}

// Polynomial data is solved exactly (no truncation): the density of F = 1 + s in class nu = 0
// against the spectral forward map of the returned coefficients at interior points.
TEST_CASE("solve_polynomial and solve_image_series are exact") {
  abel_operator<double> op(0.35, 0.2, -1.0, 2.0);
  const auto sol = solve_polynomial(op, edge::bounded, edge::unbounded, std::vector<double>{1.0, 1.0, -0.5});
  CHECK(sol.density.coefficients.size() == 3);
  CHECK(sol.residual <= 1e-14);
  // image series: one image coefficient d_2 gives exactly c_2 = d_2/lambda_2 (nu = 0).
  const auto e = op.exponents(edge::bounded, edge::unbounded);
  const auto s2 = solve_image_series(op, edge::bounded, edge::unbounded, std::vector<double>{0.0, 0.0, 1.0});
  CHECK(s2.density.coefficients[2] == doctest::Approx(1.0 / op.eigenvalue(2, e)).epsilon(2 * eps));
}
