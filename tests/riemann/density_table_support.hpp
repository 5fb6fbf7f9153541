// tests/riemann/density_table_support.hpp: the problem behind the 45-digit density table
// (tests/data/riemann_density_reference.hpp, generator tools/reference/riemann_density_reference.cpp),
// shared by the suites that check the Riemann-Hilbert density against it.
#pragma once

#include "data/riemann_density_reference.hpp"
#include "rhabel/riemann/abel_solver.hpp"

#include <cmath>

namespace rhabel::riemann::test {

/// The table's interval [a, b].
inline constexpr double density_table_a = -0.8, density_table_b = 1.3;

/// Solves the table case c by the Riemann-Hilbert route in double, as the generator posed it:
/// F(s) = exp(s/2) - s^2 + 0.3 + lambda on [a, b]; class bits: 1 = unbounded at a, 2 = unbounded
/// at b; class 3 (nu = +1) with load 1.7.
inline abel_rh_solution<double> solve_density_table_case(const rhabel_test_data::riemann_density_case& c) {
  const double lambda = c.lambda;
  const piecewise_function<double> F{[lambda](double s) { return std::exp(0.5 * s) - s * s + 0.3 + lambda; }, {}};
  abel_rh_options<double> options;
  if (c.cls == 3) options.load = 1.7;
  return solve_abel_rh(c.alpha, c.beta, density_table_a, density_table_b, F,
                       (c.cls & 1) ? edge::unbounded : edge::bounded, (c.cls & 2) ? edge::unbounded : edge::bounded,
                       options);
}

}  // namespace rhabel::riemann::test
