// Tests of rhabel/abel/elementary.hpp: the one-sided Abel equation on either side, against its
// classical closed form and against the derivative-free primitive (composition rule
// I^(1-alpha) I^alpha = I^1), which shares no code with the spectral solver.
#include <doctest/doctest.h>

#include "rhabel/abel.hpp"
#include "support.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

using namespace rhabel::abel;
using namespace abel_test;

TEST_CASE("F = 1: g = (sin(pi alpha)/pi) (b - t)^(-alpha) (right), (t - a)^(-alpha) (left)") {
  for (double alpha : {1e-3, 0.25, 0.5, 0.75, 0.999}) {
    const double a = -0.5, b = 2.0;
    const auto right = solve_elementary_abel(alpha, side::right, a, b, [](double) { return 1.0; });
    const auto left = solve_elementary_abel(alpha, side::left, a, b, [](double) { return 1.0; });
    for (double t : {-0.4999, 0.3, 1.9999}) {
      const double c = std::sin(pi * alpha) / pi;
      // 64 eps: pow and the single eigenvalue.
      CHECK(right.density(t) == doctest::Approx(c * std::pow(b - t, -alpha)).epsilon(64 * eps));
      CHECK(left.density(t) == doctest::Approx(c * std::pow(t - a, -alpha)).epsilon(64 * eps));
    }
  }
}

TEST_CASE("smooth F: int g from the Jacobi solution == derivative-free primitive, both sides") {
  for (double alpha : {0.1, 0.5, 0.8}) {
    const double a = 1.0, b = 3.0;
    auto F = [](double s) { return std::cos(s) + 0.3 * s * s; };
    const auto right = solve_elementary_abel(alpha, side::right, a, b, F);
    const auto left = solve_elementary_abel(alpha, side::left, a, b, F);
    CHECK(right.residual < 1e-13);
    CHECK(left.residual < 1e-13);
    for (double x : {1.2, 2.0, 2.9}) {
      const double pr = elementary_abel_primitive(alpha, side::right, a, b, F, x);
      const double pl = elementary_abel_primitive(alpha, side::left, a, b, F, x);
      // 256 eps: spectral solution (degree ~ 20) against 32-point Gauss-Jacobi of an entire function.
      CHECK(right.density.integral() - right.density.integral_to(x) == doctest::Approx(pr).epsilon(256 * eps));
      CHECK(left.density.integral_to(x) == doctest::Approx(pl).epsilon(256 * eps));
    }
  }
}

TEST_CASE("elementary equation: bad alpha") {
  CHECK_THROWS_AS(solve_elementary_abel(0.0, side::right, 0.0, 1.0, [](double) { return 1.0; }), std::domain_error);
  CHECK_THROWS_AS(elementary_abel_primitive(1.0, side::left, 0.0, 1.0, [](double) { return 1.0; }, 0.5),
                  std::domain_error);
  CHECK_THROWS_AS(elementary_abel_primitive(0.5, side::left, 0.0, 1.0, [](double) { return 1.0; }, 1.5),
                  std::domain_error);
}
