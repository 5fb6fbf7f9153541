// Placeholder smoke test of the interim rule; replaced by the quadrature suite.
#include <doctest/doctest.h>
#include <rhabel/quadrature.hpp>
#include <cmath>

TEST_CASE("gauss_jacobi: Chebyshev weights sum to pi") {
  const auto rule = rhabel::quadrature::gauss_jacobi<double>(7, -0.5, -0.5);
  double sum = 0;
  for (double w : rule.weight) sum += w;
  CHECK(std::abs(sum - M_PI) < 8 * 2.220446049250313e-16 * M_PI);
}
