// Built against an installed rhabel through find_package: uses every module's umbrella header.
#include <rhabel/quadrature.hpp>
#include <rhabel/abel.hpp>
#include <rhabel/riemann.hpp>
#include <rhabel/punch.hpp>
#include <cmath>
#include <cstdio>

int main() {
  // int_{-1}^{1} (1-x)^{-1/2} (1+x)^{-1/2} dx = pi, exactly integrated by any Gauss-Jacobi rule.
  const auto rule = rhabel::quadrature::gauss_jacobi<double>(5, -0.5, -0.5);
  double sum = 0;
  for (double w : rule.weight) sum += w;
  const double error = std::abs(sum - 3.14159265358979323846);
  std::printf("installed rhabel: sum of Gauss-Chebyshev weights - pi = %.3g\n", error);
  return error < 1e-14 ? 0 : 1;
}
