// rhabel/abel/multi_interval.hpp
//
// The operator of paper eq. 8 on a UNION of disjoint intervals I_1 < I_2 < ... (paper eq. 41:
// several indentors or contact patches). For s in I_j the equation reads
//
//   A_j g_j(s) + sum_{i > j} int_{I_i} g_i(t) (t - s)^(alpha-1) dt
//              - kappa sum_{i < j} int_{I_i} g_i(t) (s - t)^(alpha-1) dt  =  F_j(s),
//
// A_j the single-interval operator of abel_operator.hpp. Every interval has its own edge classes
// (so its own nu_j) and its own data F_j. The cross terms are smooth on I_j when the intervals
// are disjoint; they become nearly singular at the facing ends when the gap is small.
//
// Method (collocation in Jacobi bases). g_i = w_i sum_n c^i_n P_n^(del_i, gam_i), degree M per
// interval (options.degree). The equation is imposed at the M Chebyshev points of the first kind
// of every interval I_j (in units of (L_j/2)^alpha):
//   own term:   A_j(w P_n) = (L_j/2)^alpha lambda_n P_{n-nu_j}^(gam_j+nu_j, del_j+nu_j)
//               (spectral relation, exact; all lambda_n at once by abel_operator::eigenvalues, O(M));
//   cross term: B(k, n) = int_{I_i} w_i P_n K(t - s_k) dt by composite Gauss-Jacobi quadrature
//               graded geometrically toward the end of I_i facing I_j (uniform in the gap), with
//               panel node counts that follow the resolution P_n needs (detail/union_assembly.hpp),
//               evaluated as ONE matrix product (kernel values x basis values) per block; a
//               separated pair (gap >= the half-length of I_i) by one Gauss-Jacobi panel of
//               n/2 + O(log(1/eps)/log rho(gap)) nodes (separated_cross_nodes), whose basis
//               values are shared by all separated blocks of the solve.
// Collocation at M points of a degree-(M-1) image is the same linear system as interpolating
// the data at those points and re-expanding it in the image basis (the method of the
// single-interval solver), without the O(M^3)-per-block re-expansion: cost O(M^2 x nodes) per
// cross block plus the LU, so degrees of 10^3 take seconds. Per interval:
//   nu_j = -1: the data has one component outside the range; an unknown d_j (the coefficient
//              of P_0 of the image family) takes it: A g + d_j (L_j/2)^alpha = F on I_j, and
//              d_j is reported as solvability_defects[j] (same normalisation as
//              abel_solution::solvability_defect);
//   nu_j = +1: c^j_0 is the free constant, fixed by options.loads[j] (int_{I_j} g_j) or 0;
//              homogeneous[k] is the COUPLED solution with F = 0 and unit load on interval k
//              (zero load on the other nu = +1 intervals): g + sum_k (P_k - int_{I_k} g) H_k
//              has loads P_k on every nu = +1 interval; homogeneous_defects[k][j] is the
//              solvability defect that H_k produces on a nu = -1 interval j (so that a caller can
//              impose loads and solvability together: defect_j + sum_k x_k defect_kj = 0).
// The square system (M unknowns and M equations per interval) is solved by LU with partial
// pivoting: a direct block solve; or, from options.iterative_from intervals on, by GMRES with the
// block-diagonal preconditioner (the intervals' own blocks; detail/block_gmres.hpp): many
// separated intervals (rows of 10-300 contacts 1.5 lengths apart: 11-19 iterations to a relative
// residual of 1e-14).
// Many intervals: on that route, when some pairs of intervals are well separated (gap >= the
// larger extent of two groups of consecutive intervals: far_field.hpp), the system is
// never assembled. Only the own blocks and the blocks of NEAR pairs (on a row at any pitch: the
// two neighbours) are, and the rest of A x is applied through the far field: the coefficients'
// moments on every interval, a binary tree of the intervals, p x p kernel matrices between
// admissible boxes, interpolation back to the collocation points. A product then costs
// O(K (near + 1) M^2 + K p M + pairs p^2) instead of (K M)^2, and memory is
// union_far_memory_bytes (O(K M^2 + K p^2)) instead of (K M)^2: K = 1000 at M = 16 and p = 20
// needs ~40 MB, mostly the pairs' kernel matrices (the dense matrix: 2 GB). The far field's relative accuracy is options.residual_tolerance/1000
// (far_field::order_for; or the caller's options.far_field); the independent residual below
// takes the far intervals' action through the same far field (its own accuracy is the test
// tests/abel/test_far_field.cpp against direct quadrature) and the near ones by quadrature. If
// GMRES does not converge there, the assembled system (if it fits in max_memory_bytes).
// Block Gauss-Seidel between the intervals (solve each alone
// with the neighbour's image subtracted) was measured and rejected (study_union_convergence
// out.csv 1024 gauss_seidel: contraction factor of int g_1 per sweep, two intervals, beta 0.3):
// 0.16 ... 0.34 for alpha in [0.25, 0.5] at every gap, 0.84 ... 0.89 at alpha = 0.9, 0.56 at
// alpha = 0, gap 1e-2, and DIVERGENT at alpha = 0 for smaller gaps (factor -1.24 at 1e-4, -1.40
// at 1e-6). `condition` is the 1-norm condition number of the collocation matrix: Eigen's rcond
// estimate in float/double, exact (via the inverse) for multiprecision types. It grows like
// M^2 ... M^3 and with alpha (1e4 at M = 256, alpha = 0; 1e9 at alpha = 0.9, bounded ends); at
// that conditioning the measured int g still agree with a higher degree to within ~50 x the
// residual (study below).
//
// Residual (the evidence; an estimate, not a bound): the ORIGINAL equation at residual_points
// Chebyshev points of every interval (a grid of another power of 2 than the collocation points,
// detail::residual_grid_size: at the collocation points it is ~ rounding whatever the error)
// AND at points 0.37 gap 3^k (k = 0, 1, ...) from every facing end (the boundary layer, which a
// coarse grid steps over), relative to max |F_j| on the grid; own term by direct quadrature
// (apply_by_quadrature), cross terms by make_cross_nodes quadrature of the density (another node
// set than the assembly's). status = not_converged when it exceeds options.residual_tolerance.
// Adaptive degree: with options.max_degree > degree the solve is repeated at degree x 1.5 until
// the residual is below the tolerance or max_degree is reached (the last solve dominates the
// cost); default max_degree = 0: one solve at `degree`. A degree per interval: options.degrees
// (the first degrees; multi_solution::degrees the ones solved, interval_residuals each
// interval's residual). With adapt_each_interval only the intervals whose own residual misses
// the tolerance grow: the union's system then has blocks of M_i unknowns (square per interval),
// M_j x M_i cross blocks, and the cost of the many intervals that need few points stays small
// (twelve unit intervals 0.5 apart but one pair 1e-3 apart, alpha = beta = 0.3, tolerance
// 1e-10: the pair at 271, the rest at 16, 0.09 s against 0.45 s with 271 for all, loads within
// 7e-12; a 230-patch rough profile's corrections: 0.03 s against 0.9 s an evaluation).
//
// Accuracy and cost. Nearly touching intervals: the neighbour's density behaves like
// (t - lo_i)^gam_i at its facing end, so the cross data on I_j have a branch point at distance
// gap outside I_j, and the densities a boundary layer of width ~ gap at the facing ends. A
// polynomial of degree M resolves it once M sqrt(gap/L) is large: measured, the residual falls
// by about a decade per sqrt(L/gap) degrees (per ~10 degrees at gap 1e-2, per ~100 at 1e-4),
// so the degree for 1e-10 grows like sqrt(L/gap).
// Measured (build-union4/bin/study_union_convergence, intervals [-1,0], [gap,1] (, [1+gap,2]),
// F = -s, classes bounded/unbounded (nu = 0) and bounded/bounded (nu = -1), alpha in
// {0, 0.25, 0.5, 0.9}, beta in {0, 0.3}; 16 residual points; one core of a shared machine):
//   gap 1e-2: residual <= 1e-10 at degree 72 ... 108 in all 32 cases (2 and 3 intervals),
//             <= 1e-13 at 256; int g within 2.3e-11 of degree 256 at the first converged degree;
//             0.02 s per solve (degree 108, 2 or 3 intervals).
//   gap 1e-4: residual <= 1e-10 at degree 546 (alpha 0.9, nu = 0) ... 819 (alpha >= 0.25) ...
//             1024 (alpha 0, bounded ends; alpha 0.25, nu = 0); alpha = 0 with the unbounded
//             end facing the neighbour (nu = 0): 1.1e-10 ... 3.5e-10 at 1024, 3.7e-12 at 1228
//             (adaptive from 32 with max_degree 2048: 5.2 s CPU for the whole ladder). int g
//             within 1.6e-10 of degree 1024 at the first converged degree. One solve
//             with its residual: 0.45 s at degree 546, 1.1 s at 819, 2 s at 1024 for two
//             intervals, about 3x that for three; the adaptive ladder 32 -> 819 (alpha 0.5,
//             beta 0.3, nu = 0): 2.1 s CPU for two intervals, 4.5 s for three.
//   gap 1e-6: NOT reached. Residual 4e-1 (alpha 0, unbounded facing ends) ... 2e-7 (alpha 0.9) at
//             degree 512; at a decade per ~1000 degrees 1e-10 would need degree ~ 8e3 ... 1e4,
//             i.e. a 1.6e4-unknown dense system (2 GB, minutes): out of reach of this method. The
//             solver reports not_converged with that residual.
// Boundary-layer route (solve_union_layered; detail/layered_union.hpp): the
// Jacobi series of every interval with a near neighbour is augmented by simple poles beyond the
// facing end, clustered geometrically toward it, and the system is solved in least squares. The
// unknowns grow like log(L/gap) instead of sqrt(L/gap): gap 1e-6 at ~80 unknowns an interval,
// residual <= 4e-12 (two intervals, nu = -1 and 0), in 21-25 ms; measured against this route in
// study_union_convergence ... layered (that header has the figures).
// Memory (guarded). The dense solve holds the (K M)^2 collocation matrix (K intervals, M =
// degree), factorised in place, and during the assembly one cross block's transients (~ 6 M^2
// numbers); for non-IEEE types also the inverse (for `condition`); the iterative route
// (iterative_from) keeps the matrix unfactorised and adds its Krylov basis and the diagonal
// blocks' LUs, 61 K M + K M^2 numbers beyond the estimate (a fraction 61/(K M) + 1/K of
// (K M)^2: 5 % at K = 100, M = 16). union_memory_bytes
// estimates the peak as sizeof(Real) max((K M)^2 + 6 M^2 [K > 1], (1 or 2) (K M)^2). Measured
// peak resident set of a whole double solve without residual (F = -s, gap 1e-4, this machine)
// against the estimate: K = 2, M = 1024: 81 MB (84); K = 3, M = 1024: 123 MB (126);
// K = 2, M = 2048: 268 MB (336); K = 1, M = 4096: 143 MB (134; the process itself ~9 MB).
// solve_union throws std::domain_error BEFORE allocating anything when the estimate at the
// largest degree it may use, max(degree, max_degree), exceeds options.max_memory_bytes (default
// 2 GiB: K = 1 up to M = 16384, K = 2 up to 5181, K = 3 up to 4230); the message gives the
// largest admissible degree. Raise max_memory_bytes deliberately for larger systems.
#pragma once

// The types and the polynomial route's pieces (detail/union_core.hpp), the boundary-layer route
// (detail/layered_union.hpp).
#include "rhabel/abel/detail/layered_union.hpp"
#include "rhabel/abel/detail/union_core.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace rhabel::abel {

/// Solves the coupled system (paper 41) on the union of `intervals` (sorted, disjoint) with data
/// F[j] on interval j. See the header comment for the method, the evidence returned and the
/// measured accuracy and cost. Throws std::domain_error (naming the parameter, its value and
/// the valid range) for no intervals, a data count != interval count, unsorted or overlapping
/// intervals, max_degree in (0, degree), adaptation without residual points, and a degree
/// whose dense system would exceed options.max_memory_bytes (header, "Memory").
template <class Real>
multi_solution<Real> solve_union(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals,
                                 const std::vector<std::function<Real(Real)>>& F,
                                 const multi_solve_options<Real>& options = {}) {
  const std::size_t K = intervals.size();
  detail::check_union_arguments(par, intervals, F, options);
  std::vector<std::size_t> M = options.degrees;
  if (M.empty()) M.assign(K, std::max<std::size_t>(options.degree, 2));
  const std::size_t M_max = std::max(*std::max_element(M.begin(), M.end()), options.max_degree);
  // Many intervals: the far field (header, "Many intervals"), for the solves and the residual.
  std::shared_ptr<const far_field<Real>> far;
  if (std::is_floating_point_v<Real> && K > 1 && options.iterative_from > 1 && K >= options.iterative_from) {
    far = options.far_field;
    if (far && far->leaves() != K)
      detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union", "options.far_field leaves", far->leaves(),
                                  "the number of intervals");
    if (!far) {
      std::vector<typename far_field<Real>::box> boxes;
      for (const auto& iv : intervals) boxes.push_back({iv.lo, iv.hi});
      far = std::make_shared<const far_field<Real>>(
          par, boxes, far_field<Real>::order_for(double(options.residual_tolerance) * 1e-3));
    }
    if (far->pairs() == 0) far.reset();  // nothing far: the assembled matrix
  }
  // Memory guard (header, "Memory"): refuse before allocating the system.
  const double bytes = far ? union_far_memory_bytes(*far, M_max) : union_memory_bytes<Real>(K, M_max);
  if (bytes > double(options.max_memory_bytes)) {
    std::ostringstream range;
    range << "[2, " << union_degree_limit<Real>(K, options.max_memory_bytes) << "] for " << K
          << " interval(s): the solve would need ~" << bytes
          << " bytes > options.max_memory_bytes = " << options.max_memory_bytes
          << " (raise it deliberately for a larger system)";
    detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union",
                                options.max_degree < M_max ? "options.degree" : "options.max_degree", M_max,
                                range.str().c_str());
  }
  for (;;) {
    std::optional<multi_solution<Real>> attempt;
    if (far) attempt = detail::solve_union_at_degree(par, intervals, F, options, M, far.get());
    // The matrix-free GMRES did not converge: the assembled system, if it fits.
    if (!attempt && far && union_memory_bytes<Real>(K, *std::max_element(M.begin(), M.end())) > double(options.max_memory_bytes))
      throw std::domain_error("rhabel::abel::solve_union: GMRES on the far-field system did not converge and the dense "
                              "system exceeds options.max_memory_bytes");
    if (!attempt) attempt = detail::solve_union_at_degree(par, intervals, F, options, M);
    auto sol = std::move(*attempt);
    if (options.residual_points == 0) return sol;
    sol.interval_residuals = detail::union_residuals(par, intervals, F, sol, options.residual_points, far.get());
    sol.residual = *std::max_element(sol.interval_residuals.begin(), sol.interval_residuals.end());
    if (sol.residual <= options.residual_tolerance) return sol;
    sol.status = solve_status::not_converged;
    if (options.max_degree == 0) return sol;  // no adaptation
    // x 1.5: the last solve dominates the cost (~ M^3); every interval, or (adapt_each_interval)
    // those whose own residual is above the tolerance.
    bool grown = false;
    for (std::size_t i = 0; i < K; ++i) {
      if (M[i] >= M_max || (options.adapt_each_interval && !(sol.interval_residuals[i] > options.residual_tolerance)))
        continue;
      M[i] = std::min(M_max, M[i] + M[i] / 2);
      grown = true;
    }
    if (!grown) return sol;
  }
}

/// The boundary-layer route (detail/layered_union.hpp) for nearly touching intervals: the same
/// system as solve_union, but every end whose neighbour is nearer than the interval's
/// half-length gets simple poles beyond it, `poles_per_decade` a decade of distance from two
/// lengths down to gap/2, and the system is solved in least squares. The densities are then
/// densities[i] + layers[i] (multi_solution::load(i) sums both; homogeneous[k][i] +
/// homogeneous_layers[k][i] likewise). options as for solve_union: `degree` is the polynomial
/// part's and adapts with max_degree (the poles stay); the residual, its tolerance and status as
/// there; iterative_from, far_field, degrees and adapt_each_interval are not used (dense, one
/// degree for all intervals); max_memory_bytes bounds the system.
/// 8 poles a decade at degree 24: residual ~1e-12 at gaps down to 1e-6 of the length (the
/// detail header has the measurements). A separate function so that programs which do not use
/// the route do not compile it. Throws std::domain_error as solve_union does, and for a basis
/// beyond max_memory_bytes (naming poles_per_decade) or poles_per_decade = 0.
template <class Real>
multi_solution<Real> solve_union_layered(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals,
                                         const std::vector<std::function<Real(Real)>>& F,
                                         const multi_solve_options<Real>& options = {}, std::size_t poles_per_decade = 8) {
  detail::check_union_arguments(par, intervals, F, options);
  if (poles_per_decade == 0)
    detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union_layered", "poles_per_decade", 0, "[1, inf)");
  std::size_t M = std::max<std::size_t>(options.degree, 2);
  const std::size_t M_max = std::max(M, options.max_degree);
  for (;;) {
    auto sol = detail::solve_union_layered(par, intervals, F, options, M, poles_per_decade);
    if (options.residual_points == 0) return sol;
    sol.residual = detail::union_layered_residual(par, intervals, F, sol, options.residual_points);
    if (sol.residual <= options.residual_tolerance) return sol;
    sol.status = solve_status::not_converged;
    if (M >= M_max) return sol;
    M = std::min(M_max, M + M / 2);  // as solve_union's ladder
  }
}

}  // namespace rhabel::abel
