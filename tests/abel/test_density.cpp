// Tests of jacobi_density (abel_operator.hpp): values, int g, int_lo^x g, moments, int h g with
// breakpoints and the intensity factors, each against an independent route (Beta-function closed
// forms for the weight alone, Gauss-Jacobi on pieces for the Rodrigues partial integrals).
#include <doctest/doctest.h>

#include "rhabel/abel.hpp"
#include "support.hpp"

#include <boost/math/special_functions/beta.hpp>

#include <cmath>
#include <limits>
#include <vector>

using namespace rhabel::abel;
using namespace abel_test;

TEST_CASE("int g and moments of the bare weight: Beta-function closed forms") {
  // g(t) = (1-x)^del (1+x)^gam on [lo, hi]: int t^k g = (L/2) int ((lo+hi)/2 + (L/2) x)^k w dx; for
  // lo = 0 (t = (L/2)(1+x)): int t^k g = (L/2)^(k+1) 2^(del+gam+k+1) B(gam+k+1, del+1).
  for (double gam : {-0.7, 0.0, 0.35}) {
    for (double del : {-0.4, 0.6}) {
      const double L = 3.0;
      jacobi_density<double> g{0.0, L, gam, del, {1.0}};
      for (std::size_t k = 0; k < 5; ++k) {
        const double exact = std::pow(L / 2, double(k) + 1) * std::pow(2.0, del + gam + double(k) + 1) *
                             boost::math::beta(gam + double(k) + 1, del + 1);
        // 32 eps: Gauss-Jacobi nodes/weights and the Beta function.
        CHECK(g.moment(k) == doctest::Approx(exact).epsilon(32 * eps));
      }
      CHECK(g.integral() == doctest::Approx(g.moment(0)).epsilon(16 * eps));
    }
  }
}

TEST_CASE("int_lo^x g (incomplete beta + Rodrigues) == piecewise Gauss-Jacobi with a breakpoint at x") {
  for (double gam : {-0.65, 0.2}) {
    for (double del : {-0.45, 0.55}) {
      jacobi_density<double> g{-2.0, 1.0, gam, del, {0.9, -0.4, 0.3, 0.2, -0.1, 0.05}};
      for (double x : {-1.999, -1.2, -0.5, 0.0, 0.999}) {
        const double rodrigues = g.integral_to(x);
        const double quadrature = g.integrate([&](double t) { return t < x ? 1.0 : 0.0; }, {x});
        CHECK(rodrigues == doctest::Approx(quadrature).epsilon(64 * eps).scale(std::abs(g.integral())));
      }
      CHECK(g.integral_to(-2.0) == 0.0);
      CHECK(g.integral_to(1.0) == doctest::Approx(g.integral()).epsilon(4 * eps));
    }
  }
}

TEST_CASE("intensity factors are the limits g (t-a)^(-gam), g (b-t)^(-del)") {
  jacobi_density<double> g{1.0, 4.0, -0.3, 0.4, {1.0, 0.5, -0.25}};
  const double ta = 1.0 + 1e-10, tb = 4.0 - 1e-10;
  // The next term is O(t - a) relative: 1e-9 covers it.
  CHECK(g.intensity_leading() == doctest::Approx(g(ta) * std::pow(ta - 1.0, 0.3)).epsilon(1e-9));
  CHECK(g.intensity_trailing() == doctest::Approx(g(tb) * std::pow(4.0 - tb, -0.4)).epsilon(1e-9));
}

TEST_CASE("int h g with a breakpoint: a step h against int_lo^x g") {
  jacobi_density<double> g{0.0, 2.0, 0.25, -0.5, {1.0, 0.3}};
  const double x0 = 0.7;
  const double stepped = g.integrate([&](double t) { return t < x0 ? 2.0 : -1.0; }, {x0});
  const double exact = 2.0 * g.integral_to(x0) - (g.integral() - g.integral_to(x0));
  CHECK(stepped == doctest::Approx(exact).epsilon(64 * eps));
  // outside the interval the density is zero
  CHECK(g(-1.0) == 0.0);
  CHECK(g(3.0) == 0.0);
}
