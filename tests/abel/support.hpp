// tests/abel/support.hpp: constants, parameter grids and oracles shared by the abel test suites
// (one definition instead of a copy per file).
#pragma once

#include "rhabel/abel.hpp"

#include <limits>
#include <vector>

namespace abel_test {

inline constexpr double eps = std::numeric_limits<double>::epsilon();
inline constexpr double pi = 3.141592653589793238462643383279502884;

/// The hard alphas of issue 3 and the betas, on both sides of alpha + beta/2 = 1/2.
inline const std::vector<double> hard_alphas{0.0, 1e-8, 1e-3, 0.25, 0.5 - 1e-9, 0.5, 0.5 + 1e-9, 0.9, 0.999};
inline const std::vector<double> betas{0.0, 0.3, 0.9};

/// Oracle for step (piecewise constant) data with one breakpoint t0: the plain solver's image
/// coefficients computed by Gauss-Jacobi on each piece, which for piecewise constant F are the
/// exact Rodrigues values. Only c_0 (int g) and, for nu = -1, the solvability defect are exact
/// here (4 coefficients); the enrichment of solve_step plays no part in it.
template <class F>
rhabel::abel::abel_solution<double> rodrigues_step_solution(const rhabel::abel::abel_operator<double>& op,
                                                            rhabel::abel::edge leading, rhabel::abel::edge trailing,
                                                            F&& f, double t0) {
  rhabel::abel::solve_options<double> plain;
  plain.degree = 4;
  plain.residual_points = 0;
  return rhabel::abel::solve_piecewise(op, leading, trailing, f, {t0}, plain);
}

}  // namespace abel_test
