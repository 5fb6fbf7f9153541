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
//               n/2 + O(log(1/eps)/log rho(gap)) nodes (detail::separated_cross_nodes), whose basis
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
// larger extent of two groups of consecutive intervals: detail/far_field.hpp), the system is
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
// cost); default max_degree = 0: one solve at `degree`.
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
// (K M)^2: 5 % at K = 100, M = 16). detail::union_memory_bytes
// estimates the peak as sizeof(Real) max((K M)^2 + 6 M^2 [K > 1], (1 or 2) (K M)^2). Measured
// peak resident set of a whole double solve without residual (F = -s, gap 1e-4, this machine)
// against the estimate: K = 2, M = 1024: 81 MB (84); K = 3, M = 1024: 123 MB (126);
// K = 2, M = 2048: 268 MB (336); K = 1, M = 4096: 143 MB (134; the process itself ~9 MB).
// solve_union throws std::domain_error BEFORE allocating anything when the estimate at the
// largest degree it may use, max(degree, max_degree), exceeds options.max_memory_bytes (default
// 2 GiB: K = 1 up to M = 16384, K = 2 up to 5181, K = 3 up to 4230); the message gives the
// largest admissible degree. Raise max_memory_bytes deliberately for larger systems.
#pragma once

#include "rhabel/abel/abel_solver.hpp"
#include "rhabel/abel/detail/block_gmres.hpp"
#include "rhabel/abel/detail/far_field.hpp"
#include "rhabel/abel/detail/union_assembly.hpp"

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

/// One interval of a union with its edge behaviour.
template <class Real>
struct interval_spec {
  Real lo, hi;
  edge leading = edge::bounded, trailing = edge::bounded;
};

template <class Real>
struct multi_solve_options {
  std::size_t degree = 32;              ///< collocation points (= unknowns) per interval; the first degree tried
  /// Adaptive degree: while the residual exceeds residual_tolerance the degree grows by 1.5x up
  /// to max_degree (0: no adaptation, only `degree`). Needs residual_points > 0. Memory and time
  /// grow like max_degree^2 and ^3 (header: 2 s and a 81 MB peak at 1024 for two intervals;
  /// bounded by max_memory_bytes).
  std::size_t max_degree = 0;
  std::size_t residual_points = 8;      ///< per interval; 0 = skip the residual
  std::vector<std::optional<Real>> loads;  ///< per interval, used for nu = +1 intervals only
  /// status = not_converged when the independent residual exceeds this (only if it is computed).
  Real residual_tolerance = Real(1e-10);
  /// Bound on the estimated peak memory of one dense solve (detail::union_memory_bytes, bytes):
  /// solve_union throws std::domain_error, before allocating, when max(degree, max_degree)
  /// would exceed it. Default 2 GiB (two intervals: degree <= 5181).
  std::size_t max_memory_bytes = std::size_t(1) << 31;
  /// Compute multi_solution::homogeneous and homogeneous_defects (one more solve with the
  /// factorised matrix per nu = +1 interval); false: they stay empty / zero.
  bool homogeneous = true;
  /// K >= iterative_from intervals (and K > 1; 0: never): the collocation system by GMRES with the
  /// block-diagonal preconditioner (detail/block_gmres.hpp; LU if it does not reach its tolerance)
  /// instead of LU; multi_solution::condition is then NaN. Floating-point Real only.
  std::size_t iterative_from = 0;
  /// The far field of exactly these intervals for that route (detail/far_field.hpp), when the
  /// caller has one (the punch layer builds it for its data anyway); null: solve_union builds it
  /// with order_for(residual_tolerance / 1000) points per box.
  std::shared_ptr<const detail::far_field<Real>> far_field;
};

/// The boundary-layer part of a density on [lo, hi] (solve_union_layered):
/// g(t) = (1 - x)^del (1 + x)^gam [ sum_k a_k d_k/(d_k + 1 + x) + sum_k b_k e_k/(e_k + 1 - x) ],
/// poles at x = -1 - d_k (lo_distances) and x = 1 + e_k (hi_distances), reference units.
/// The whole density of interval i is multi_solution::densities[i] + layers[i].
template <class Real>
struct layer_density {
  Real lo = -1, hi = 1;
  Real gam = 0, del = 0;
  std::vector<Real> lo_distances, lo_coefficients;
  std::vector<Real> hi_distances, hi_coefficients;

  Real half_length() const { return (hi - lo) / 2; }
  bool empty() const { return lo_distances.empty() && hi_distances.empty(); }
  Real nearest_lo() const { return lo_distances.empty() ? std::numeric_limits<Real>::infinity() : lo_distances.front(); }
  Real nearest_hi() const { return hi_distances.empty() ? std::numeric_limits<Real>::infinity() : hi_distances.front(); }
  /// The bracket at 1 + x, 1 - x (accurate next to either end).
  Real factor_at_distance(const Real& one_plus_x, const Real& one_minus_x) const {
    Real sum = 0;
    for (std::size_t k = 0; k < lo_distances.size(); ++k) sum += lo_coefficients[k] * lo_distances[k] / (lo_distances[k] + one_plus_x);
    for (std::size_t k = 0; k < hi_distances.size(); ++k) sum += hi_coefficients[k] * hi_distances[k] / (hi_distances[k] + one_minus_x);
    return sum;
  }
  /// g at the point with distances u = t - lo, v = hi - t.
  Real value_at_distance(const Real& u, const Real& v) const {
    using std::pow;
    if (empty()) return Real(0);
    const Real h = half_length();
    return pow(v / h, del) * pow(u / h, gam) * factor_at_distance(u / h, v / h);
  }
  /// g(t) for lo < t < hi (0 outside).
  Real operator()(const Real& t) const {
    if (!(t > lo) || !(t < hi)) return Real(0);
    return value_at_distance(t - lo, hi - t);
  }
  /// int_lo^hi g by Gauss-Jacobi panels graded toward the nearest poles (~ eps relative).
  Real integral() const {
    if (empty()) return Real(0);
    const detail::panel_integrator<Real> rule(del, gam, 24);
    return half_length() * rule.integrate(Real(2), nearest_lo(), nearest_hi(),
                                          [&](const Real& u, const Real& v) { return factor_at_distance(u, v); });
  }
};

template <class Real>
struct multi_solution {
  std::vector<jacobi_density<Real>> densities;      ///< g_i on I_i
  std::vector<edge_exponents<Real>> exponents;      ///< (gam, del, nu) per interval
  std::vector<Real> solvability_defects;            ///< nu = -1 intervals (0 elsewhere)
  std::vector<std::vector<jacobi_density<Real>>> homogeneous;  ///< per interval: empty unless nu = +1 (and options.homogeneous)
  std::vector<std::vector<Real>> homogeneous_defects;  ///< [k][j]: defect of homogeneous[k] on nu = -1 interval j
  Real residual = std::numeric_limits<Real>::quiet_NaN();  ///< max relative residual, independent route
  /// 1-norm condition number of the collocation matrix: Eigen's rcond estimate for float and
  /// double, exact for other types (see the header).
  Real condition = 0;
  /// Boundary-layer parts (solve_union_layered; empty from solve_union): g_i = densities[i] +
  /// layers[i]; homogeneous_layers[k][i] likewise for homogeneous[k][i].
  std::vector<layer_density<Real>> layers;
  std::vector<std::vector<layer_density<Real>>> homogeneous_layers;
  /// int g_i: densities[i].integral() plus the layer's.
  Real load(std::size_t i) const {
    return densities[i].integral() + (i < layers.size() ? layers[i].integral() : Real(0));
  }
  std::size_t degree = 0;                            ///< collocation points per interval of the returned solve
  /// not_converged: residual > options.residual_tolerance (typically nearly touching intervals,
  /// see the header); converged otherwise, or when no residual was computed.
  solve_status status = solve_status::converged;
};

namespace detail {

/// Nodes of I_i (physical t, weight including w_i and dt = (L/2) dx, reference x) graded toward
/// the end of I_i facing the point set at distance `gap` (left if facing_left); `nodes` per
/// panel (cross_nodes: detail/union_assembly.hpp). The independent route of the residual (the
/// assembly uses degree_graded_cross_nodes).
template <class Real>
cross_nodes<Real> make_cross_nodes(const jacobi_density<Real>& g, const Real& gap, bool facing_left, std::size_t nodes) {
  const Real h = g.half_length();
  const panel_integrator<Real> rule(g.del, g.gam, nodes);
  const Real inf = std::numeric_limits<Real>::infinity();
  const Real d = gap / h;
  cross_nodes<Real> out;
  rule.for_each_node(Real(2), facing_left ? d : inf, facing_left ? inf : d,
                     [&](const Real& u, const Real& v, const Real& weight) {
                       out.x.push_back(u <= v ? u - 1 : 1 - v);
                       out.weight.push_back(h * weight);
                       out.t_minus_lo.push_back(h * u);
                       out.hi_minus_t.push_back(h * v);
                     });
  return out;
}

}  // namespace detail

/// A g at s for densities on a union of disjoint intervals (each with its own class). Own
/// interval: spectral relation; others: graded quadrature. Any s (also outside every interval).
template <class Real>
Real apply_union(const abel_parameters<Real>& par, const std::vector<jacobi_density<Real>>& densities, const Real& s) {
  Real total = 0;
  for (const auto& g : densities) total += abel_operator<Real>(par, g.lo, g.hi).apply(g, s);
  return total;
}

namespace detail {

/// The density of class e on the interval with n zero coefficients (to be filled by a solve).
template <class Real>
jacobi_density<Real> zero_density(const interval_spec<Real>& iv, const edge_exponents<Real>& e, std::size_t n) {
  jacobi_density<Real> g;
  g.lo = iv.lo;
  g.hi = iv.hi;
  g.gam = e.gam;
  g.del = e.del;
  g.coefficients.assign(n, Real(0));
  return g;
}

/// Signed distance bookkeeping of a collocation/residual point s of I_j: distances to lo_j and hi_j.
template <class Real>
struct union_point {
  Real s, from_lo, to_hi;
};

/// Points of I_j at the Chebyshev grid `grid` (distances to both ends without cancellation).
template <class Real>
std::vector<union_point<Real>> union_points(const interval_spec<Real>& iv, const chebyshev_grid<Real>& grid) {
  const Real h = (iv.hi - iv.lo) / 2;
  std::vector<union_point<Real>> out;
  for (std::size_t k = 0; k < grid.x.size(); ++k) {
    const Real u = h * grid.one_plus_x[k], v = h * grid.one_minus_x[k];
    out.push_back({u <= v ? iv.lo + u : iv.hi - v, u, v});
  }
  return out;
}

/// Estimated peak memory (bytes, as a double: no overflow for any size_t arguments) of
/// solve_union_at_degree for K intervals at M collocation points each, T = K M unknowns: the
/// larger of the assembly phase, T^2 + 6 M^2 numbers (the matrix plus one cross block's kernel
/// values M x Q, basis values Q x M and their M x M product; Q ~ 2M nodes at gaps down to 1e-4,
/// 2.5M at 1e-12), and the factorisation phase, T^2 numbers (LU in place) or 2 T^2 for non-IEEE
/// types (the inverse, see `condition`). Measured peaks: the header's "Memory" paragraph.
template <class Real>
double union_memory_bytes(std::size_t K, std::size_t M) {
  const double T = double(K) * double(M), m = double(M);
  const double assembly = T * T + (K > 1 ? 6 * m * m : 0);
  const double factorisation = (std::is_floating_point_v<Real> ? 1 : 2) * T * T;
  return double(sizeof(Real)) * std::max(assembly, factorisation);
}

/// The largest M with union_memory_bytes<Real>(K, M) <= bytes (K >= 1; bisection, the estimate
/// is increasing in M and >= sizeof(Real) (K M)^2).
template <class Real>
std::size_t union_degree_limit(std::size_t K, std::size_t bytes) {
  using std::sqrt;
  std::size_t lo = 0;  // union_memory_bytes(K, lo) <= bytes
  std::size_t hi = static_cast<std::size_t>(sqrt(double(bytes) / (double(sizeof(Real)) * double(K) * double(K)))) + 1;
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    (union_memory_bytes<Real>(K, mid) <= double(bytes) ? lo : hi) = mid;
  }
  return lo;
}

/// Gap between intervals i and j (i != j), sorted and disjoint.
template <class Real>
Real union_gap(const std::vector<interval_spec<Real>>& intervals, std::size_t i, std::size_t j) {
  return i > j ? intervals[i].lo - intervals[j].hi : intervals[j].lo - intervals[i].hi;
}

/// Estimated peak memory (bytes) of the matrix-free route (far field, far_field.hpp) for K
/// intervals at M points each with `near` near pairs in all: the own and near blocks and the
/// diagonal blocks' LUs ((2 K + near) M^2), the Krylov basis and work vectors (64 K M), the
/// moment matrices (K p M) and the pairs' kernel matrices (pairs p^2).
template <class Real>
double union_far_memory_bytes(const far_field<Real>& far, std::size_t M) {
  const double K = double(far.leaves()), m = double(M), p = double(far.order());
  double near = 0;
  for (std::size_t j = 0; j < far.leaves(); ++j) near += double(far.near_leaves(j).size());
  return double(sizeof(Real)) * ((2 * K + near) * m * m + 64 * K * m + K * p * m + double(far.pairs()) * p * p);
}

/// The largest M (>= 1) with union_far_memory_bytes(far, M) <= bytes (0 if none: the estimate is
/// increasing in M).
template <class Real>
std::size_t union_far_degree_limit(const far_field<Real>& far, std::size_t bytes) {
  if (union_far_memory_bytes(far, 1) > double(bytes)) return 0;
  std::size_t lo = 1, hi = 2;
  while (union_far_memory_bytes(far, hi) <= double(bytes)) lo = hi, hi *= 2;
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    (union_far_memory_bytes(far, mid) <= double(bytes) ? lo : hi) = mid;
  }
  return lo;
}

/// One solve of the coupled system at `degree` collocation points per interval (no residual).
/// far: null for the dense system (LU, or GMRES on the assembled matrix from iterative_from on);
/// else the far field of these intervals: only the own and near blocks are assembled and the
/// far part is applied by the far field inside GMRES (the header, "Many intervals"). Returns
/// nothing when that GMRES does not reach its tolerance (the caller then solves densely).
template <class Real>
std::optional<multi_solution<Real>> solve_union_at_degree(const abel_parameters<Real>& par,
                                                          const std::vector<interval_spec<Real>>& intervals,
                                                          const std::vector<std::function<Real(Real)>>& F,
                                                          const multi_solve_options<Real>& options, std::size_t M,
                                                          const far_field<Real>* far = nullptr) {
  using std::pow;
  const std::size_t K = intervals.size();
  const Real alpha = par.alpha();
  multi_solution<Real> sol;
  sol.degree = M;
  std::vector<abel_operator<Real>> ops;
  // Unknowns of interval i: the coefficients c^i_n (n_basis[i] of them; for nu = +1 c^i_0 is
  // fixed by the load and not an unknown) and, for nu = -1, the defect d_i. Rows: the M
  // collocation equations of interval i. Both number M per interval: the system is square.
  std::vector<std::size_t> n_basis(K), offset(K);
  for (std::size_t i = 0; i < K; ++i) {
    ops.emplace_back(par, intervals[i].lo, intervals[i].hi);
    const auto e = par.exponents(intervals[i].leading, intervals[i].trailing);
    sol.exponents.push_back(e);
    n_basis[i] = e.nu == -1 ? M - 1 : (e.nu == 0 ? M : M + 1);
    offset[i] = i * M;
    sol.densities.push_back(zero_density(intervals[i], e, n_basis[i]));
  }
  const std::size_t total = K * M;
  // Column of c^i_n within interval i's block (-1: the fixed c_0 of nu = +1).
  auto local_index = [&](std::size_t i, std::size_t n) -> long {
    if (sol.exponents[i].nu == 1) return n == 0 ? -1 : static_cast<long>(n - 1);
    return static_cast<long>(n);
  };
  // Column of the defect d_i (nu = -1): the last unknown of the block.
  const auto defect_column = static_cast<Eigen::Index>(M - 1);
  auto fixed_c0 = [&](std::size_t i) -> Real {
    if (sol.exponents[i].nu != 1) return Real(0);
    if (i < options.loads.size() && options.loads[i]) {
      const Real h0 = rhabel::quadrature::jacobi_norm_squared(0, sol.exponents[i].del, sol.exponents[i].gam);
      return *options.loads[i] / (ops[i].half_length() * h0);
    }
    return Real(0);
  };
  using matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  using vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
  const auto T = static_cast<Eigen::Index>(total);
  const auto Mi = static_cast<Eigen::Index>(M);
  const chebyshev_grid<Real> grid(M);
  separated_basis_cache<Real> basis_cache;
  std::vector<std::vector<union_point<Real>>> pts(K);
  std::vector<Real> scale(K);  // equations of interval j in units of h_j^alpha
  vector rhs(T);
  for (std::size_t j = 0; j < K; ++j) {
    scale[j] = pow(ops[j].half_length(), -alpha);
    pts[j] = union_points(intervals[j], grid);
    for (std::size_t k = 0; k < M; ++k) {
      const Real v = F[j](pts[j][k].s);
      check_finite_value("rhabel::abel::solve_union", v, pts[j][k].s);
      rhs[static_cast<Eigen::Index>(offset[j] + k)] = scale[j] * v;
    }
  }
  // Own block of interval j (M x M, j's unknowns): A(w P_n) = h^alpha lambda_n P_{n - nu}^(gam + nu,
  // del + nu) (spectral relation); nu = -1: F - A g = d_j P_0 (the part of the data outside the range).
  auto own_block = [&](std::size_t j) {
    const auto& e = sol.exponents[j];
    const Real p = e.gam + Real(e.nu), q = e.del + Real(e.nu);
    const std::vector<Real> lambda = ops[j].eigenvalues(n_basis[j], e);  // O(n_basis) in all
    matrix B = matrix::Zero(Mi, Mi);
    for (std::size_t k = 0; k < M; ++k) {
      const auto r = static_cast<Eigen::Index>(k);
      const auto image = jacobi_values_any(M, p, q, grid.x[k]);
      for (std::size_t n = 0; n < n_basis[j]; ++n) {
        const long m = static_cast<long>(n) - e.nu;
        if (m < 0) continue;  // nu = +1, n = 0: the homogeneous solution, image 0
        const long c = local_index(j, n);
        if (c >= 0) B(r, c) += lambda[n] * image[static_cast<std::size_t>(m)];
      }
      if (e.nu == -1) B(r, defect_column) += Real(1);
    }
    return B;
  };
  // Cross block of interval i acting on j's collocation points (M x M in i's unknowns) and the
  // column of i's fixed c_0 (nu = +1).
  auto cross = [&](std::size_t j, std::size_t i, vector& c0_column) {
    const bool right = i > j;
    std::vector<Real> dist(M);
    for (std::size_t k = 0; k < M; ++k) dist[k] = right ? pts[j][k].to_hi : pts[j][k].from_lo;
    const auto B = cross_block(sol.densities[i], union_gap(intervals, i, j), right, dist, n_basis[i], scale[j],
                               [&](const Real& t_minus_s) { return cross_kernel(par, t_minus_s); }, &basis_cache);
    matrix out = matrix::Zero(Mi, Mi);
    c0_column = vector::Zero(Mi);
    for (std::size_t n = 0; n < n_basis[i]; ++n) {
      const long c = local_index(i, n);
      if (c >= 0)
        out.col(c) += B.col(static_cast<Eigen::Index>(n));
      else
        c0_column += B.col(static_cast<Eigen::Index>(n));
    }
    return out;
  };
  std::vector<Real> c0(K, Real(0));
  for (std::size_t i = 0; i < K; ++i) c0[i] = fixed_c0(i);
  auto unpack = [&](const vector& x, const std::vector<Real>& c0s) {
    std::vector<jacobi_density<Real>> out = sol.densities;
    for (std::size_t i = 0; i < K; ++i)
      for (std::size_t n = 0; n < n_basis[i]; ++n) {
        const long u = local_index(i, n);
        out[i].coefficients[n] = u >= 0 ? x[static_cast<Eigen::Index>(offset[i]) + u] : c0s[i];
      }
    return out;
  };
  auto defects = [&](const vector& x) {
    std::vector<Real> out(K, Real(0));
    for (std::size_t j = 0; j < K; ++j)
      if (sol.exponents[j].nu == -1) out[j] = x[static_cast<Eigen::Index>(offset[j]) + defect_column];
    return out;
  };
  // The linear solve x = A^-1 right, and the image of fixed c_0 values (subtracted from the data).
  std::function<std::optional<vector>(const vector&)> linear_solve;
  std::function<vector(const std::vector<Real>&)> c0_image;
  // Dense route: A assembled. LU in place (Eigen::Ref): A holds the factors from then on. With a
  // copy of A (PartialPivLU of a matrix; its rcond() then also allocated a T x T temporary) the
  // peak was 3 (K M)^2 numbers: 405 MB against 143 MB now at K = 1, M = 4096; 410 MB against
  // 268 MB at K = 2, M = 2048. The factorisation is the same, bit for bit (checked on a random
  // 2000 x 2000).
  matrix A;
  std::vector<vector> c0_columns;  // dense route: image of the fixed c_0 of nu = +1 intervals
  std::unique_ptr<Eigen::PartialPivLU<Eigen::Ref<matrix>>> lu;
  std::unique_ptr<block_gmres<Real>> gmres;
  // Matrix-free route: own and near blocks, moment matrices, the far field's interpolation.
  std::vector<matrix> own(K), moment(K);
  std::vector<std::vector<std::pair<std::size_t, matrix>>> near(K);  // near[j]: (i, block)
  std::vector<std::vector<std::pair<std::size_t, vector>>> near_c0(K);
  matrix interpolation;
  if (!far) {
    A = matrix::Zero(T, T);
    c0_columns.assign(K, vector::Zero(T));
    for (std::size_t j = 0; j < K; ++j) {
      const auto row0 = static_cast<Eigen::Index>(offset[j]);
      A.block(row0, row0, Mi, Mi) = own_block(j);
      for (std::size_t i = 0; i < K; ++i) {
        if (i == j) continue;
        vector c0_column;
        A.block(row0, static_cast<Eigen::Index>(offset[i]), Mi, Mi) += cross(j, i, c0_column);
        c0_columns[i].segment(row0, Mi) += c0_column;
      }
    }
    // 1-norm of A for the exact condition of non-IEEE types (A is overwritten below).
    Real norm_A = 0;
    if constexpr (!std::is_floating_point_v<Real>) norm_A = A.cwiseAbs().colwise().sum().maxCoeff();
    auto factorise = [&, norm_A] {
      gmres.reset();  // it refers to A, which the LU overwrites
      lu = std::make_unique<Eigen::PartialPivLU<Eigen::Ref<matrix>>>(A);
      if constexpr (std::is_floating_point_v<Real>) {
        (void)norm_A;  // used for the exact condition of non-IEEE types only
        sol.condition = 1 / lu->rcond();
      } else {
        // Eigen's estimator needs NumTraits<Real>::infinity(), which the Boost.Multiprecision
        // bindings lack: the exact 1-norm condition instead (O(size^3), like the LU itself).
        const matrix inverse = lu->inverse();
        sol.condition = norm_A * inverse.cwiseAbs().colwise().sum().maxCoeff();
      }
    };
    // Many intervals (options.iterative_from): GMRES with the block-diagonal preconditioner
    // (detail/block_gmres.hpp), O(T^2) per iteration against the LU's 2/3 T^3; `condition` is
    // then not computed (NaN). Otherwise, or when GMRES does not reach its tolerance: LU.
    if (std::is_floating_point_v<Real> && K > 1 && options.iterative_from > 1 && K >= options.iterative_from) {
      gmres = std::make_unique<block_gmres<Real>>(A, Mi);
      sol.condition = std::numeric_limits<Real>::quiet_NaN();
    } else {
      factorise();
    }
    linear_solve = [&, factorise](const vector& right) -> std::optional<vector> {
      if (gmres) {
        vector x;
        if (gmres->solve(right, x, Real(1e-14))) return x;
        factorise();
      }
      return vector(lu->solve(right));
    };
    c0_image = [&](const std::vector<Real>& c0s) {
      vector out = vector::Zero(T);
      for (std::size_t i = 0; i < K; ++i)
        if (sol.exponents[i].nu == 1) out += c0s[i] * c0_columns[i];
      return out;
    };
  } else {
    interpolation = far->interpolation(grid.x);
    for (std::size_t j = 0; j < K; ++j) {
      own[j] = own_block(j);
      moment[j] = far->moment_matrix(j, sol.densities[j].del, sol.densities[j].gam, n_basis[j]);
      for (std::size_t i : far->near_leaves(j)) {
        vector c0_column;
        near[j].emplace_back(i, cross(j, i, c0_column));
        near_c0[j].emplace_back(i, std::move(c0_column));
      }
    }
    // The far part of A x (coefficients from x and the fixed c_0 values c0s).
    auto far_part = [&](const vector& x, const std::vector<Real>& c0s) {
      std::vector<vector> W(K);
      for (std::size_t i = 0; i < K; ++i) {
        vector c(static_cast<Eigen::Index>(n_basis[i]));
        for (std::size_t n = 0; n < n_basis[i]; ++n) {
          const long u = local_index(i, n);
          c[static_cast<Eigen::Index>(n)] = u >= 0 ? x[static_cast<Eigen::Index>(offset[i]) + u] : c0s[i];
        }
        W[i] = moment[i] * c;
      }
      const auto local = far->far_values(W);
      vector out(T);
      for (std::size_t j = 0; j < K; ++j) out.segment(static_cast<Eigen::Index>(offset[j]), Mi) = scale[j] * (interpolation * local[j]);
      return out;
    };
    const std::vector<Real> no_c0(K, Real(0));
    auto apply = [&, far_part, no_c0](const vector& x) {
      vector out = far_part(x, no_c0);
      for (std::size_t j = 0; j < K; ++j) {
        const auto row0 = static_cast<Eigen::Index>(offset[j]);
        out.segment(row0, Mi) += own[j] * x.segment(row0, Mi);
        for (const auto& [i, B] : near[j]) out.segment(row0, Mi) += B * x.segment(static_cast<Eigen::Index>(offset[i]), Mi);
      }
      return out;
    };
    gmres = std::make_unique<block_gmres<Real>>(apply, own);
    sol.condition = std::numeric_limits<Real>::quiet_NaN();
    linear_solve = [&](const vector& right) -> std::optional<vector> {
      vector x;
      if (gmres->solve(right, x, Real(1e-14))) return x;
      return std::nullopt;
    };
    c0_image = [&, far_part](const std::vector<Real>& c0s) {
      vector out = far_part(vector::Zero(T), c0s);
      for (std::size_t j = 0; j < K; ++j)
        for (const auto& [i, column] : near_c0[j])
          if (sol.exponents[i].nu == 1) out.segment(static_cast<Eigen::Index>(offset[j]), Mi) += c0s[i] * column;
      return out;
    };
  }
  const auto c = linear_solve(rhs - c0_image(c0));
  if (!c) return std::nullopt;
  sol.densities = unpack(*c, c0);
  sol.solvability_defects = defects(*c);
  sol.homogeneous.assign(K, {});
  sol.homogeneous_defects.assign(K, std::vector<Real>(K, Real(0)));
  for (std::size_t k = 0; k < K && options.homogeneous; ++k) {
    if (sol.exponents[k].nu != 1) continue;
    const Real h0 = rhabel::quadrature::jacobi_norm_squared(0, sol.exponents[k].del, sol.exponents[k].gam);
    std::vector<Real> c0k(K, Real(0));
    c0k[k] = 1 / (ops[k].half_length() * h0);
    const auto x = linear_solve(-c0_image(c0k));
    if (!x) return std::nullopt;
    sol.homogeneous[k] = unpack(*x, c0k);
    sol.homogeneous_defects[k] = defects(*x);
  }
  return sol;
}

/// sum_q weight_q K(t_q - s) value_q: the action on a point s of I_j of a density of I_i given by
/// its values at `nodes` (i_right_of_j: I_i lies to the right; dist: distance of s to the end of
/// I_j facing I_i; t - s formed from the distances, without cancellation).
template <class Real>
Real cross_sum(const abel_parameters<Real>& par, const cross_nodes<Real>& nodes, const std::vector<Real>& values,
               bool i_right_of_j, const Real& gap, const Real& dist) {
  Real sum = 0;
  for (std::size_t q = 0; q < nodes.x.size(); ++q) {
    const Real t_minus_s = i_right_of_j ? nodes.t_minus_lo[q] + gap + dist : -(nodes.hi_minus_t[q] + gap + dist);
    sum += nodes.weight[q] * cross_kernel(par, t_minus_s) * values[q];
  }
  return sum;
}

/// Independent residual of the original equation (see the header): max over the intervals of
/// max_s |A g(s) - (F(s) - h^alpha d_j)| / max_s |F(s)|, at Chebyshev points of another power of
/// 2 than the collocation grid and at points graded toward every facing end.
template <class Real>
Real union_residual(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals,
                    const std::vector<std::function<Real(Real)>>& F, const multi_solution<Real>& sol,
                    std::size_t points, const far_field<Real>* far = nullptr) {
  using std::abs;
  using std::max;
  using std::pow;
  const std::size_t K = intervals.size();
  const Real alpha = par.alpha();
  Real worst = 0;
  // With a far field: the far intervals' action through it (the local values of every interval
  // from the densities' moments), the near ones by quadrature as below.
  std::vector<Eigen::Matrix<Real, Eigen::Dynamic, 1>> local;
  if (far) {
    std::vector<Eigen::Matrix<Real, Eigen::Dynamic, 1>> W;
    for (const auto& g : sol.densities) W.push_back(far->density_moments(W.size(), g));
    local = far->far_values(W);
  }
  auto coupled = [&](std::size_t j, std::size_t i) {
    if (i == j) return false;
    if (!far) return true;
    const auto& near = far->near_leaves(j);
    return std::binary_search(near.begin(), near.end(), i);
  };
  for (std::size_t j = 0; j < K; ++j) {
    const auto& gj = sol.densities[j];
    const abel_operator<Real> op(par, intervals[j].lo, intervals[j].hi);
    const typename abel_operator<Real>::quadrature_evaluator own(op, gj.gam, gj.del, gj.coefficients.size());
    const Real h = op.half_length();
    const Real defect = sol.exponents[j].nu == -1 ? pow(h, alpha) * sol.solvability_defects[j] : Real(0);
    // Never at the collocation points (residual_grid_size): there the residual is ~ rounding.
    auto pts = union_points(intervals[j], chebyshev_grid<Real>(residual_grid_size(points, sol.degree)));
    // Points at distances 0.37 gap 3^k (k = 0, 1, ... while < h/2) from each facing end: the
    // boundary layer of width ~ gap that a coarse Chebyshev grid would step over. (0.37: no
    // coincidence with collocation points or panel breaks.)
    for (int side = 0; side < 2; ++side) {
      if ((side == 0 && j == 0) || (side == 1 && j + 1 == K)) continue;
      const Real gap = side == 0 ? union_gap(intervals, j - 1, j) : union_gap(intervals, j + 1, j);
      for (Real d = Real(0.37) * gap; d < h / 2; d *= 3)
        pts.push_back(side == 0 ? union_point<Real>{intervals[j].lo + d, d, 2 * h - d}
                                : union_point<Real>{intervals[j].hi - d, 2 * h - d, d});
    }
    // Nodes per panel: n/2 + 24 (n coefficients); a separated pair (gap >= h_i: one panel) takes
    // 4 more than the assembly's separated_cross_nodes when that is fewer (the same analyticity
    // bound, eps/100; another node set than the assembly's all the same).
    std::vector<cross_nodes<Real>> nodes(K);
    for (std::size_t i = 0; i < K; ++i)
      if (coupled(j, i)) {
        const std::size_t n = sol.densities[i].coefficients.size();
        const Real gap = union_gap(intervals, i, j);
        std::size_t count = n / 2 + 24;
        if (const std::size_t separated = separated_cross_nodes(gap / sol.densities[i].half_length(), n); separated > 0)
          count = std::min(count, separated + 4);
        nodes[i] = make_cross_nodes(sol.densities[i], gap, i > j, count);
      }
    // g_i at the cross nodes once (the residual is O(points x nodes), the series O(nodes x degree)),
    // each series with its recurrence coefficients computed once (jacobi_density::series_evaluator).
    std::vector<std::vector<Real>> series(K);
    for (std::size_t i = 0; i < K; ++i) {
      if (!coupled(j, i)) continue;
      const auto gi = sol.densities[i].series_evaluator();
      for (const auto& x : nodes[i].x) series[i].push_back(gi(x));
    }
    const auto gj_series = gj.series_evaluator();
    Real worst_j = 0, scale_j = 0;
    for (const auto& pt : pts) {
      Real value = own([&](const Real& x) { return gj_series(x); }, pt.s);
      if (far) value += far->interpolate(local[j], pt.from_lo <= pt.to_hi ? pt.from_lo / h - 1 : 1 - pt.to_hi / h);
      for (std::size_t i = 0; i < K; ++i)
        if (coupled(j, i)) value += cross_sum(par, nodes[i], series[i], i > j, union_gap(intervals, i, j), i > j ? pt.to_hi : pt.from_lo);
      const Real Fs = F[j](pt.s);
      worst_j = max(worst_j, abs(value - (Fs - defect)));
      scale_j = max(scale_j, abs(Fs));
    }
    worst = max(worst, scale_j > 0 ? worst_j / scale_j : worst_j);
  }
  return worst;
}

/// The argument checks of solve_union and solve_union_layered (their comments list them).
template <class Real>
void check_union_arguments(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals,
                           const std::vector<std::function<Real(Real)>>& F, const multi_solve_options<Real>& options) {
  const std::size_t K = intervals.size();
  if (K == 0) throw_bad_parameter("rhabel::abel::solve_union", "number of intervals", 0, "[1, inf)");
  if (F.size() != K)
    throw_bad_parameter("rhabel::abel::solve_union", "number of data functions", F.size(), "equal to the number of intervals");
  for (std::size_t i = 0; i < K; ++i) {
    abel_operator<Real> check(par, intervals[i].lo, intervals[i].hi);  // validates lo < hi
    (void)check;
    if (i > 0 && !(intervals[i].lo > intervals[i - 1].hi))
      throw_bad_parameter("rhabel::abel::solve_union", "interval lo", intervals[i].lo,
                          "> hi of the previous interval (sorted, disjoint intervals)");
  }
  if (options.max_degree != 0 && options.max_degree < options.degree)
    throw_bad_parameter("rhabel::abel::solve_union", "options.max_degree", options.max_degree,
                        "0 (no adaptation) or >= options.degree");
  if (options.max_degree > options.degree && options.residual_points == 0)
    throw_bad_parameter("rhabel::abel::solve_union", "options.residual_points", 0,
                        "> 0 when options.max_degree > options.degree (the residual drives the degree)");
}

}  // namespace detail

}  // namespace rhabel::abel

// The boundary-layer route (solve_union_layered, below): uses the types and helpers above.
#include "rhabel/abel/detail/layered_union.hpp"

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
  std::size_t M = std::max<std::size_t>(options.degree, 2);
  const std::size_t M_max = std::max(M, options.max_degree);
  // Many intervals: the far field (header, "Many intervals"), for the solves and the residual.
  std::shared_ptr<const detail::far_field<Real>> far;
  if (std::is_floating_point_v<Real> && K > 1 && options.iterative_from > 1 && K >= options.iterative_from) {
    far = options.far_field;
    if (far && far->leaves() != K)
      detail::throw_bad_parameter("rhabel::abel::solve_union", "options.far_field leaves", far->leaves(),
                                  "the number of intervals");
    if (!far) {
      std::vector<typename detail::far_field<Real>::box> boxes;
      for (const auto& iv : intervals) boxes.push_back({iv.lo, iv.hi});
      far = std::make_shared<const detail::far_field<Real>>(
          par, boxes, detail::far_field<Real>::order_for(double(options.residual_tolerance) * 1e-3));
    }
    if (far->pairs() == 0) far.reset();  // nothing far: the assembled matrix
  }
  // Memory guard (header, "Memory"): refuse before allocating the system.
  const double bytes = far ? detail::union_far_memory_bytes(*far, M_max) : detail::union_memory_bytes<Real>(K, M_max);
  if (bytes > double(options.max_memory_bytes)) {
    std::ostringstream range;
    range << "[2, " << detail::union_degree_limit<Real>(K, options.max_memory_bytes) << "] for " << K
          << " interval(s): the solve would need ~" << bytes
          << " bytes > options.max_memory_bytes = " << options.max_memory_bytes
          << " (raise it deliberately for a larger system)";
    detail::throw_bad_parameter("rhabel::abel::solve_union", M_max == M ? "options.degree" : "options.max_degree",
                                M_max, range.str().c_str());
  }
  for (;;) {
    std::optional<multi_solution<Real>> attempt;
    if (far) attempt = detail::solve_union_at_degree(par, intervals, F, options, M, far.get());
    // The matrix-free GMRES did not converge: the assembled system, if it fits.
    if (!attempt && far && detail::union_memory_bytes<Real>(K, M) > double(options.max_memory_bytes))
      throw std::domain_error("rhabel::abel::solve_union: GMRES on the far-field system did not converge and the dense "
                              "system exceeds options.max_memory_bytes");
    if (!attempt) attempt = detail::solve_union_at_degree(par, intervals, F, options, M);
    auto sol = std::move(*attempt);
    if (options.residual_points == 0) return sol;
    sol.residual = detail::union_residual(par, intervals, F, sol, options.residual_points, far.get());
    if (sol.residual <= options.residual_tolerance) return sol;
    sol.status = solve_status::not_converged;
    if (M >= M_max) return sol;
    M = std::min(M_max, M + M / 2);  // x 1.5: the last solve dominates the cost (~ M^3)
  }
}

/// The boundary-layer route (detail/layered_union.hpp) for nearly touching intervals: the same
/// system as solve_union, but every end whose neighbour is nearer than the interval's
/// half-length gets simple poles beyond it, `poles_per_decade` a decade of distance from two
/// lengths down to gap/2, and the system is solved in least squares. The densities are then
/// densities[i] + layers[i] (multi_solution::load(i) sums both; homogeneous[k][i] +
/// homogeneous_layers[k][i] likewise). options as for solve_union: `degree` is the polynomial
/// part's and adapts with max_degree (the poles stay); the residual, its tolerance and status as
/// there; iterative_from and far_field are not used (dense); max_memory_bytes bounds the system.
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
    detail::throw_bad_parameter("rhabel::abel::solve_union_layered", "poles_per_decade", 0, "[1, inf)");
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
