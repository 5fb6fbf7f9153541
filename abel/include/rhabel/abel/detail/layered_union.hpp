// rhabel/abel/detail/layered_union.hpp: the boundary-layer route of abel::solve_union
// (abel::solve_union_layered, multi_interval.hpp), for nearly touching intervals.
//
// Why. Next to a neighbour at distance `gap`, the data of I_j carries the neighbour's edge
// behaviour: a branch point at distance gap beyond the facing end. The density then has a layer
// of width ~ gap there, and a polynomial of degree M resolves it only once M sqrt(gap/L) is
// large (the degree grows like sqrt(L/gap): ~10^3 at gap 1e-4 L, ~10^4 at 1e-6 L).
//
// Basis. On each interval the density is w (S + sum_k a_k d_k/(d_k + 1 - x) + ...), S a
// polynomial of degree < M in the Jacobi basis (as on the polynomial route) and one simple pole
// beyond every facing end at each distance d_k (reference units) of the fixed geometric ladder
// 4 x 10^(-k/poles_per_decade), k = 0, 1, ..., down to the first at or below gap/(2h)
// (layer_pole_distances). This is the "lightning" idea (Gopal and Trefethen, PNAS 116 (2019)
// 10223; SIAM J. Numer. Anal. 57 (2019) 2074): rational functions with poles clustered
// exponentially toward a branch point approximate it root-exponentially, uniformly in its
// distance, so the unknowns grow like log(L/gap) instead of sqrt(L/gap). The pole columns'
// own images are computed by the operator's independent quadrature (abel_operator::
// quadrature_evaluator, panels graded toward the pole), the polynomial columns' by the spectral
// relation, the cross terms by quadrature on panels graded toward both ends of the source.
//
// System. Rational bases are redundant, so the equations are imposed in the least-squares sense
// at more points than unknowns: on every interval 2 M + 8 Chebyshev points plus points at
// distances 0.9 h x 1.2^(-k) down to gap/100 from every facing end (the layer: ~2 per pole),
// columns scaled to unit norm, solved by column-pivoted Householder QR
// (Eigen::ColPivHouseholderQR). Both ladders are fixed relative to h (the gap only says where
// they stop), so the poles' own images at the layer points depend on the material, the class
// and the degree alone: they could be computed once for all the solves of a Newton iteration
// (not done yet; they are about half of a solve's time). The nu = -1 defects and the
// nu = +1 fixed constants enter as on the polynomial route; the homogeneous solutions are more
// right-hand sides of the same factorisation.
//
// Evidence: union_layered_residual, the residual of the ORIGINAL equation at points of other
// grids (Chebyshev of another size, distances 0.37 gap 3^k from the facing ends), own term by
// quadrature_evaluator with another node count, cross terms by panel_integrator nodes of another
// count than the assembly's. An estimate, not a bound.
//
// Measured (study_union_convergence - 1024 layered, studies/results/union_convergence.csv: F = -s
// on [-1, 0], [gap, 1] (, [1 + gap, 2]), alpha in {0, 0.25, 0.5, 0.9}, beta in {0, 0.3}, classes
// nu = 0 and -1; one core). At M = 24 and 8 poles a decade:
//   two intervals, gap 1e-2 / 1e-4 / 1e-6: 46 / 62 / 78 unknowns an interval, residual <= 7.6e-13
//   / 1.2e-11 / 4.1e-12, 5-7 / 12-18 / 21-25 ms with the residual;
//   three intervals, gap 1e-6: 132 unknowns on the middle one, residual <= 3.2e-12, 79-88 ms;
//   int g within 8.7e-13 of (M, poles a decade) = (32, 12), and within 1.1e-10 of the polynomial
//   route where that converges (gap 1e-4: degree 546-1024, 0.55-3.4 s).
// Tests (tests/abel/test_layered_union.cpp): the converged polynomial route at gap 1e-2 (every
// class), its recorded degree-1536 int g at gap 1e-4, densities given in advance at gap 1e-6,
// the alpha = 0 closed form of the two-interval null space at gap 1e-6 (3e-12).
// Limits: unbounded facing ends with imposed loads (nu = +1) leave residuals of ~1e-8 ... 1e-7 of
// the data at gap 1e-6 (the terms next to the gap are ~1e3 times the data); the solve is dense
// (no far field: the intervals' count should be small); tested in double only.
//
// Not a standalone header: multi_interval.hpp includes it after its own types (interval_spec,
// multi_solve_options, layer_density, multi_solution) and helpers (union_points, union_gap,
// zero_density, cross_sum).
#pragma once

#include "rhabel/abel/abel_operator.hpp"
#include "rhabel/abel/far_field.hpp"
#include "rhabel/abel/detail/numerics.hpp"
#include "rhabel/abel/detail/union_assembly.hpp"
#include "rhabel/abel/detail/union_core.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <sstream>
#include <vector>

namespace rhabel::abel::detail {

/// Number of poles for a facing end at `gap_over_h` (gap / h of the interval): the ladder of
/// layer_pole_distances down to gap_over_h / 2, at least 4 (a double: checked against memory
/// before use).
template <class Real>
double layer_pole_count(const Real& gap_over_h, std::size_t per_decade) {
  return std::max(4.0, std::ceil(double(per_decade) * std::log10(8 / double(gap_over_h))) + 1);
}

/// Pole distances (reference units beyond an end), nearest first: the fixed ladder
/// 4 x 10^(-k/per_decade), k = 0, 1, ..., down to the first at or below gap_over_h / 2
/// (layer_pole_count of them). The ladder does not depend on the gap (only where it stops), so
/// the poles' own images at the fixed rows of layered_rows depend on the material and the class
/// alone.
template <class Real>
std::vector<Real> layer_pole_distances(const Real& gap_over_h, std::size_t per_decade) {
  using std::pow;
  const auto count = static_cast<std::size_t>(layer_pole_count(gap_over_h, per_decade));
  std::vector<Real> out(count);
  for (std::size_t k = 0; k < count; ++k)
    out[count - 1 - k] = 4 * pow(Real(10), -Real(k) / Real(std::max<std::size_t>(per_decade, 1)));
  return out;
}

/// Nodes on I_i (cross_nodes, multi_interval.hpp) for the cross integrals when the density has
/// poles: panel_integrator's nodes (one count for every panel) graded toward both ends, each
/// toward the nearest singularity beyond it (kernel or pole).
template <class Real>
cross_nodes<Real> make_layered_nodes(const Real& h, const Real& gam, const Real& del, const Real& beyond_lo,
                                     const Real& beyond_hi, std::size_t count) {
  cross_nodes<Real> out;
  const panel_integrator<Real> rule(del, gam, count);
  rule.for_each_node(Real(2), beyond_lo, beyond_hi, [&](const Real& u, const Real& v, const Real& weight) {
    out.x.push_back(u <= v ? u - 1 : 1 - v);
    out.weight.push_back(h * weight);
    out.t_minus_lo.push_back(h * u);
    out.hi_minus_t.push_back(h * v);
  });
  return out;
}

/// Value of the smooth factor of g_i (series + poles) at a node given by 1 + x and 1 - x;
/// series: g_i.series_evaluator().
template <class Real>
Real layered_factor(const rhabel::quadrature::jacobi_series<Real>& series, const layer_density<Real>& layer,
                    const Real& one_plus_x, const Real& one_minus_x) {
  const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
  return series(x) + layer.factor_at_distance(one_plus_x, one_minus_x);
}

/// Poles of interval i of a sorted union: beyond lo when the left neighbour is nearer than h_i,
/// beyond hi likewise (none for a separated neighbour: the polynomial resolves its action).
template <class Real>
layer_density<Real> layer_for(const std::vector<interval_spec<Real>>& intervals, std::size_t i,
                              const edge_exponents<Real>& e, std::size_t per_decade) {
  layer_density<Real> out;
  out.lo = intervals[i].lo;
  out.hi = intervals[i].hi;
  out.gam = e.gam;
  out.del = e.del;
  const Real h = out.half_length();
  if (i > 0) {
    const Real gap = union_gap(intervals, i - 1, i);
    if (gap < h) out.lo_distances = layer_pole_distances(gap / h, per_decade);
  }
  if (i + 1 < intervals.size()) {
    const Real gap = union_gap(intervals, i + 1, i);
    if (gap < h) out.hi_distances = layer_pole_distances(gap / h, per_decade);
  }
  out.lo_coefficients.assign(out.lo_distances.size(), Real(0));
  out.hi_coefficients.assign(out.hi_distances.size(), Real(0));
  return out;
}

/// A row of the layered system: interval j, reference point by 1 + x and 1 - x (no cancellation
/// next to an end), physical s.
template <class Real>
struct layered_row {
  std::size_t j;
  Real one_plus_x, one_minus_x, s;
};

/// Rows of interval j: `chebyshev` Chebyshev points and the layer points at distances
/// first x h x ratio^(-k), k = 0, 1, ..., down to gap/100, from every facing end with poles.
template <class Real>
std::vector<layered_row<Real>> layered_rows(const std::vector<interval_spec<Real>>& intervals,
                                            const layer_density<Real>& layer, std::size_t j, std::size_t chebyshev,
                                            const Real& first, const Real& ratio) {
  std::vector<layered_row<Real>> out;
  const interval_spec<Real>& iv = intervals[j];
  const Real h = (iv.hi - iv.lo) / 2;
  // The distances to the ends from the rounded s (exact differences next to an end), so that
  // the own term (quadrature_evaluator, which takes s) and the cross terms (distances) see the
  // same point: a mismatch of one rounding of s is ~ eps/gap relative in the cross term.
  auto add = [&](const Real& s) { out.push_back({j, (s - iv.lo) / h, (iv.hi - s) / h, s}); };
  for (const auto& p : union_points(iv, chebyshev_grid<Real>(chebyshev))) add(p.s);
  for (int side = 0; side < 2; ++side) {
    const bool at_lo = side == 0;
    if ((at_lo ? layer.lo_distances : layer.hi_distances).empty()) continue;
    const Real gap = at_lo ? union_gap(intervals, j - 1, j) : union_gap(intervals, j + 1, j);
    // From first x h inward by the ratio down to gap/100 (inside the layer the density of an
    // unbounded end varies on the scale of its distance to the end): a ladder fixed relative to
    // h, so the rows do not depend on the gap (only where they stop).
    for (Real d = first * h; d > gap / 100; d /= ratio) add(at_lo ? iv.lo + d : iv.hi - d);
  }
  return out;
}

/// Memory guard of the layered system, before anything is allocated: the system (R x N, QR in
/// a copy: twice) and the right-hand sides with the images of c_0 (R x (K + 2)), R and N
/// estimated from the pole counts (layer rows: log(200 h/gap)/log 1.2 + 2 an end, above the
/// log(90 h/gap)/log 1.2 of layered_rows' ladder 0.9 h ... gap/100).
/// Throws std::domain_error naming poles_per_decade.
template <class Real>
void check_layered_memory(const std::vector<interval_spec<Real>>& intervals, const multi_solve_options<Real>& options,
                          std::size_t M, std::size_t per_decade) {
  const std::size_t K = intervals.size();
  double N_est = 0, R_est = 0;
  for (std::size_t i = 0; i < K; ++i) {
    const Real h = (intervals[i].hi - intervals[i].lo) / 2;
    N_est += double(M);
    R_est += double(2 * M + 8);
    for (const std::size_t other : {i - 1, i + 1}) {
      if (other >= K) continue;  // no neighbour (i - 1 wraps around for i = 0)
      const double gap_over_h = double(union_gap(intervals, other, i) / h);
      if (!(gap_over_h < 1)) continue;
      N_est += layer_pole_count(gap_over_h, per_decade);
      R_est += (std::log(4 / gap_over_h) + std::log(50.0)) / std::log(1.2) + 2;
    }
  }
  const double bytes = double(sizeof(Real)) * R_est * (2 * N_est + double(K) + 2);
  if (bytes > double(options.max_memory_bytes)) {
    std::ostringstream range;
    range << "a smaller value or wider gaps: ~" << N_est << " unknowns at ~" << R_est << " points would need ~"
          << bytes << " bytes > options.max_memory_bytes = " << options.max_memory_bytes;
    throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union_layered", "poles_per_decade", double(per_decade), range.str().c_str());
  }
}

/// The layered least-squares system of one solve at M polynomial unknowns per interval (the top
/// of this header): its layout (unknowns and rows), its assembly and the unpacking of a solution.
/// Unknowns of interval i, from offset[i]: M polynomial ones as on the polynomial route (the
/// coefficients, c_0 excluded for nu = +1, and the defect for nu = -1, last), then the poles
/// beyond lo, then those beyond hi. Rows: 2 M + 8 Chebyshev points (the poles act in the layer,
/// which has its own points: 2 x the unknowns instead gave the same residuals, measured, at 1.3x
/// the time) plus the layer points (0.9 h x 1.2^(-k) down to gap/100). Equations of interval j in
/// units of h_j^alpha.
template <class Real>
class layered_system {
 public:
  using matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;

  layered_system(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals, std::size_t M,
                 std::size_t per_decade)
      : par_(par), intervals_(intervals), M_(M), K_(intervals.size()), n_basis_(K_), offset_(K_ + 1, 0) {
    using std::pow;
    skeleton_.degree = M;
    skeleton_.degrees.assign(K_, M);
    skeleton_.condition = std::numeric_limits<Real>::quiet_NaN();
    for (std::size_t i = 0; i < K_; ++i) {
      ops_.emplace_back(par, intervals[i].lo, intervals[i].hi);
      const auto e = par.exponents(intervals[i].leading, intervals[i].trailing);
      skeleton_.exponents.push_back(e);
      n_basis_[i] = e.nu == -1 ? M - 1 : (e.nu == 0 ? M : M + 1);
      skeleton_.densities.push_back(zero_density(intervals[i], e, n_basis_[i]));
      skeleton_.layers.push_back(layer_for(intervals, i, e, per_decade));
      offset_[i + 1] = offset_[i] + M + skeleton_.layers[i].lo_distances.size() + skeleton_.layers[i].hi_distances.size();
      scale_.push_back(pow(ops_[i].half_length(), -par.alpha()));
      const auto r = layered_rows(intervals, skeleton_.layers[i], i, 2 * M + 8, Real(0.9), Real(1.2));
      rows_.insert(rows_.end(), r.begin(), r.end());
    }
  }

  Eigen::Index rows() const { return static_cast<Eigen::Index>(rows_.size()); }
  Eigen::Index unknowns() const { return static_cast<Eigen::Index>(offset_[K_]); }
  const multi_solution<Real>& skeleton() const { return skeleton_; }
  const std::vector<layered_row<Real>>& row_points() const { return rows_; }
  Real scale(std::size_t j) const { return scale_[j]; }
  Real half_length(std::size_t i) const { return ops_[i].half_length(); }

  /// Column of c^i_n; -1 for the fixed c_0 of nu = +1.
  long poly_column(std::size_t i, std::size_t n) const {
    if (skeleton_.exponents[i].nu == 1) return n == 0 ? -1 : static_cast<long>(offset_[i] + n - 1);
    return static_cast<long>(offset_[i] + n);
  }
  Eigen::Index pole_column(std::size_t i, bool at_lo, std::size_t k) const {
    return static_cast<Eigen::Index>(offset_[i] + M_ + (at_lo ? 0 : skeleton_.layers[i].lo_distances.size()) + k);
  }
  Eigen::Index defect_column(std::size_t i) const { return static_cast<Eigen::Index>(offset_[i] + M_ - 1); }

  /// Own blocks: polynomial columns by the spectral relation, poles by quadrature; the image of
  /// the fixed c_0 = 1 of a nu = +1 interval into c0_columns (zero: A w = 0 for that class).
  void add_own(matrix& A, matrix& c0_columns) const {
    for (std::size_t j = 0; j < K_; ++j) {
      const auto& e = skeleton_.exponents[j];
      const std::vector<Real> lambda = ops_[j].eigenvalues(n_basis_[j], e);
      // Degree hint 8: 16 nodes a panel (the poles are smooth on the panels graded toward them;
      // panel_integrator: ~1e-24 a panel at 16), against the residual's M/2 + 24.
      const typename abel_operator<Real>::quadrature_evaluator own(ops_[j], e.gam, e.del, 8);
      for (Eigen::Index r = 0; r < rows(); ++r) {
        const auto& row = rows_[static_cast<std::size_t>(r)];
        if (row.j != j) continue;
        const Real x = row.one_plus_x <= row.one_minus_x ? row.one_plus_x - 1 : 1 - row.one_minus_x;
        const auto image = jacobi_values_any(M_, e.gam + Real(e.nu), e.del + Real(e.nu), x);
        for (std::size_t n = 0; n < n_basis_[j]; ++n) {
          const long m = static_cast<long>(n) - e.nu;
          if (m < 0) continue;  // nu = +1, n = 0: image 0
          const long c = poly_column(j, n);
          (c >= 0 ? A(r, c) : c0_columns(r, static_cast<Eigen::Index>(j))) += lambda[n] * image[static_cast<std::size_t>(m)];
        }
        if (e.nu == -1) A(r, defect_column(j)) += Real(1);
        add_own_poles(A, own, j, r);
      }
    }
  }

  /// Cross blocks: source i on the rows of j, by quadrature on nodes graded toward both ends of
  /// I_i (the kernel's singularity and i's poles), one matrix product per block.
  void add_cross(matrix& A, matrix& c0_columns) const {
    for (std::size_t i = 0; i < K_; ++i)
      for (std::size_t j = 0; j < K_; ++j)
        if (i != j) add_cross_block(A, c0_columns, i, j);
  }

  /// A solution (column `col` of X, in the unknowns) with the fixed constants c0s, after the
  /// elimination of c_0 by the loads (pole_integrals, unit_c0: see solve_union_layered).
  void unpack(const matrix& X, Eigen::Index col, const std::vector<Real>& c0s, const std::vector<Real>& unit_c0,
              const std::vector<std::vector<Real>>& pole_integrals, std::vector<jacobi_density<Real>>& g,
              std::vector<layer_density<Real>>& layers, std::vector<Real>& defects) const {
    g = skeleton_.densities;
    layers = skeleton_.layers;
    defects.assign(K_, Real(0));
    for (std::size_t i = 0; i < K_; ++i) {
      for (std::size_t n = 0; n < n_basis_[i]; ++n) {
        const long c = poly_column(i, n);
        g[i].coefficients[n] = c >= 0 ? X(c, col) : c0s[i];
      }
      if (skeleton_.exponents[i].nu == -1) defects[i] = X(defect_column(i), col);
      for (std::size_t k = 0; k < layers[i].lo_distances.size(); ++k) layers[i].lo_coefficients[k] = X(pole_column(i, true, k), col);
      for (std::size_t k = 0; k < layers[i].hi_distances.size(); ++k) layers[i].hi_coefficients[k] = X(pole_column(i, false, k), col);
      if (skeleton_.exponents[i].nu == 1 && !g[i].coefficients.empty()) {  // c_0 eliminated by the load
        const std::size_t n_lo = layers[i].lo_distances.size();
        for (std::size_t k = 0; k < pole_integrals[i].size(); ++k)
          g[i].coefficients[0] -= unit_c0[i] * pole_integrals[i][k] *
                                  (k < n_lo ? layers[i].lo_coefficients[k] : layers[i].hi_coefficients[k - n_lo]);
      }
    }
  }

 private:
  /// All poles of I_j at row r in one pass over the nodes (graded toward the nearest at each end).
  void add_own_poles(matrix& A, const typename abel_operator<Real>::quadrature_evaluator& own, std::size_t j,
                     Eigen::Index r) const {
    const auto& layer = skeleton_.layers[j];
    if (layer.empty()) return;
    const std::size_t n_lo = layer.lo_distances.size(), n_poles = n_lo + layer.hi_distances.size();
    const auto images = own.many(
        [&](const Real&, const Real& p, const Real& m) {
          Eigen::Array<Real, Eigen::Dynamic, 1> out(static_cast<Eigen::Index>(n_poles));
          for (std::size_t k = 0; k < n_lo; ++k) out[static_cast<Eigen::Index>(k)] = layer.lo_distances[k] / (layer.lo_distances[k] + p);
          for (std::size_t k = n_lo; k < n_poles; ++k)
            out[static_cast<Eigen::Index>(k)] = layer.hi_distances[k - n_lo] / (layer.hi_distances[k - n_lo] + m);
          return out;
        },
        rows_[static_cast<std::size_t>(r)].s, layer.nearest_lo(), layer.nearest_hi());
    for (std::size_t k = 0; k < n_poles; ++k)
      A(r, pole_column(j, k < n_lo, k < n_lo ? k : k - n_lo)) += scale_[j] * images[static_cast<Eigen::Index>(k)];
  }

  void add_cross_block(matrix& A, matrix& c0_columns, std::size_t i, std::size_t j) const {
    const Real inf = std::numeric_limits<Real>::infinity();
    const auto& gi = skeleton_.densities[i];
    const auto& li = skeleton_.layers[i];
    const Real h_i = gi.half_length(), h_j = ops_[j].half_length();
    const bool right = i > j;  // I_i to the right of I_j: it faces j with its lo end
    const Real gap = union_gap(intervals_, i, j);
    const auto nodes = make_layered_nodes(h_i, gi.gam, gi.del, std::min(li.nearest_lo(), right ? gap / h_i : inf),
                                          std::min(li.nearest_hi(), right ? inf : gap / h_i), M_ / 2 + 20);
    const auto Q = static_cast<Eigen::Index>(nodes.x.size());
    std::vector<Eigen::Index> row_index;
    for (Eigen::Index r = 0; r < rows(); ++r)
      if (rows_[static_cast<std::size_t>(r)].j == j) row_index.push_back(r);
    const auto Rj = static_cast<Eigen::Index>(row_index.size());
    matrix kernel(Rj, Q);
    for (Eigen::Index a = 0; a < Rj; ++a) {
      const auto& row = rows_[static_cast<std::size_t>(row_index[static_cast<std::size_t>(a)])];
      const Real ds = right ? h_j * row.one_minus_x : h_j * row.one_plus_x;  // to j's end facing i
      for (Eigen::Index q = 0; q < Q; ++q) {
        const auto qs = static_cast<std::size_t>(q);
        const Real t_minus_s = right ? nodes.t_minus_lo[qs] + gap + ds : -(nodes.hi_minus_t[qs] + gap + ds);
        kernel(a, q) = scale_[j] * nodes.weight[qs] * cross_kernel(par_, t_minus_s);
      }
    }
    matrix basis(Q, static_cast<Eigen::Index>(n_basis_[i] + li.lo_distances.size() + li.hi_distances.size()));
    for (Eigen::Index q = 0; q < Q; ++q) {
      const auto qs = static_cast<std::size_t>(q);
      const Real u = nodes.t_minus_lo[qs] / h_i, v = nodes.hi_minus_t[qs] / h_i;  // 1 + x, 1 - x
      const auto P = rhabel::quadrature::jacobi_p_all(n_basis_[i] - 1, gi.del, gi.gam, nodes.x[qs]);
      Eigen::Index c = 0;
      for (std::size_t n = 0; n < n_basis_[i]; ++n) basis(q, c++) = P[n];
      for (const Real& d : li.lo_distances) basis(q, c++) = d / (d + u);
      for (const Real& d : li.hi_distances) basis(q, c++) = d / (d + v);
    }
    const matrix block = kernel * basis;
    for (Eigen::Index a = 0; a < Rj; ++a) {
      const Eigen::Index r = row_index[static_cast<std::size_t>(a)];
      Eigen::Index c = 0;
      for (std::size_t n = 0; n < n_basis_[i]; ++n, ++c) {
        const long col = poly_column(i, n);
        (col >= 0 ? A(r, col) : c0_columns(r, static_cast<Eigen::Index>(i))) += block(a, c);
      }
      for (std::size_t k = 0; k < li.lo_distances.size(); ++k, ++c) A(r, pole_column(i, true, k)) += block(a, c);
      for (std::size_t k = 0; k < li.hi_distances.size(); ++k, ++c) A(r, pole_column(i, false, k)) += block(a, c);
    }
  }

  const abel_parameters<Real>& par_;
  const std::vector<interval_spec<Real>>& intervals_;
  std::size_t M_, K_;
  std::vector<abel_operator<Real>> ops_;
  std::vector<std::size_t> n_basis_, offset_;
  std::vector<Real> scale_;
  std::vector<layered_row<Real>> rows_;
  multi_solution<Real> skeleton_;  ///< exponents, zero densities and layers (their poles)
};

/// int_I w d/(d + 1 -/+ x) for every pole of the layer (poles beyond lo first), by panels graded
/// toward the pole.
template <class Real>
std::vector<Real> layer_pole_integrals(const layer_density<Real>& layer) {
  const Real inf = std::numeric_limits<Real>::infinity();
  const panel_integrator<Real> rule(layer.del, layer.gam, 24);
  std::vector<Real> out;
  for (int side = 0; side < 2; ++side) {
    const bool at_lo = side == 0;
    for (const Real& d : at_lo ? layer.lo_distances : layer.hi_distances)
      out.push_back(layer.half_length() * rule.integrate(Real(2), at_lo ? d : inf, at_lo ? inf : d,
                                                         [&](const Real& u, const Real& v) { return d / (d + (at_lo ? u : v)); }));
  }
  return out;
}

/// One least-squares solve of the layered system at M polynomial unknowns per interval (the
/// top of this header), per_decade poles a decade (> 0).
template <class Real>
multi_solution<Real> solve_union_layered(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals,
                                         const std::vector<std::function<Real(Real)>>& F,
                                         const multi_solve_options<Real>& options, std::size_t M, std::size_t per_decade) {
  using matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  const std::size_t K = intervals.size();
  check_layered_memory(intervals, options, M, per_decade);
  const layered_system<Real> system(par, intervals, M, per_decade);
  multi_solution<Real> sol = system.skeleton();
  const Eigen::Index R = system.rows(), N = system.unknowns();
  // Right-hand sides: the data, then one per nu = +1 interval (its homogeneous solution).
  std::vector<std::size_t> plus_one;
  for (std::size_t i = 0; i < K; ++i)
    if (sol.exponents[i].nu == 1 && options.homogeneous) plus_one.push_back(i);
  matrix A = matrix::Zero(R, N), B = matrix::Zero(R, static_cast<Eigen::Index>(1 + plus_one.size()));
  matrix c0_columns = matrix::Zero(R, static_cast<Eigen::Index>(K));  // image of c_0 = 1 (nu = +1)
  system.add_own(A, c0_columns);
  system.add_cross(A, c0_columns);
  for (Eigen::Index r = 0; r < R; ++r) {
    const auto& row = system.row_points()[static_cast<std::size_t>(r)];
    const Real v = F[row.j](row.s);
    check_finite_value("rhabel::abel::solve_union", v, row.s);
    B(r, 0) = system.scale(row.j) * v;
  }
  // nu = +1: the load fixes the WHOLE integral, c_0 h h_0 + sum_k a_k int w phi_k, so c_0 is
  // eliminated: c_0 = c0[i] - unit_c0[i] sum_k a_k I_k (c0[i], unit_c0[i]: the constant for the
  // load and per unit integral); the data lose c0[i] x c_0's column, every pole column
  // unit_c0[i] I_k x c_0's column.
  std::vector<Real> c0(K, Real(0)), unit_c0(K, Real(0));
  std::vector<std::vector<Real>> pole_integrals(K);
  for (std::size_t i = 0; i < K; ++i) {
    if (sol.exponents[i].nu != 1) continue;
    const Real h0 = rhabel::quadrature::jacobi_norm_squared(0, sol.exponents[i].del, sol.exponents[i].gam);
    unit_c0[i] = 1 / (system.half_length(i) * h0);
    if (i < options.loads.size() && options.loads[i]) c0[i] = *options.loads[i] * unit_c0[i];
    const auto column = c0_columns.col(static_cast<Eigen::Index>(i));
    B.col(0) -= c0[i] * column;
    pole_integrals[i] = layer_pole_integrals(sol.layers[i]);
    const std::size_t n_lo = sol.layers[i].lo_distances.size();
    for (std::size_t k = 0; k < pole_integrals[i].size(); ++k)
      A.col(system.pole_column(i, k < n_lo, k < n_lo ? k : k - n_lo)) -= unit_c0[i] * pole_integrals[i][k] * column;
  }
  for (std::size_t k = 0; k < plus_one.size(); ++k)
    B.col(static_cast<Eigen::Index>(k + 1)) = -unit_c0[plus_one[k]] * c0_columns.col(static_cast<Eigen::Index>(plus_one[k]));
  // Column-scaled least squares (rational bases are redundant: pivoted QR).
  Eigen::Matrix<Real, Eigen::Dynamic, 1> norms = A.colwise().norm();
  for (Eigen::Index c = 0; c < N; ++c)
    if (norms[c] > 0) A.col(c) /= norms[c]; else norms[c] = 1;
  const Eigen::ColPivHouseholderQR<matrix> qr(A);
  matrix X = qr.solve(B);
  for (Eigen::Index c = 0; c < N; ++c) X.row(c) /= norms[c];
  sol.homogeneous.assign(K, {});
  sol.homogeneous_layers.assign(K, {});
  sol.homogeneous_defects.assign(K, std::vector<Real>(K, Real(0)));
  for (std::size_t k = 0; k < plus_one.size(); ++k) {
    std::vector<Real> c0k(K, Real(0));
    c0k[plus_one[k]] = unit_c0[plus_one[k]];
    system.unpack(X, static_cast<Eigen::Index>(k + 1), c0k, unit_c0, pole_integrals, sol.homogeneous[plus_one[k]],
                  sol.homogeneous_layers[plus_one[k]], sol.homogeneous_defects[plus_one[k]]);
  }
  system.unpack(X, 0, c0, unit_c0, pole_integrals, sol.densities, sol.layers, sol.solvability_defects);
  return sol;
}

/// Independent residual of a layered solution (the top of this header): max over the intervals
/// of max |A g - (F - h^alpha d_j)| / max |F| at Chebyshev points of another size than the
/// rows' and at 0.37 gap 3^k from every facing end; own term by quadrature_evaluator (another
/// node count than the assembly's), cross terms on panel_integrator nodes of another count.
template <class Real>
Real union_layered_residual(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals,
                            const std::vector<std::function<Real(Real)>>& F, const multi_solution<Real>& sol,
                            std::size_t points) {
  using std::abs;
  using std::max;
  using std::pow;
  const std::size_t K = intervals.size();
  const Real inf = std::numeric_limits<Real>::infinity();
  const std::size_t M = sol.degree;
  Real worst = 0;
  for (std::size_t j = 0; j < K; ++j) {
    const auto& gj = sol.densities[j];
    const auto& lj = sol.layers[j];
    const abel_operator<Real> op(par, intervals[j].lo, intervals[j].hi);
    // degree hint M + 24: M/2 + 24 nodes a panel, against the assembly's 28 at M <= 32.
    const typename abel_operator<Real>::quadrature_evaluator own(op, gj.gam, gj.del, M + 24);
    const auto gj_series = gj.series_evaluator();
    const Real h = op.half_length();
    const Real defect = sol.exponents[j].nu == -1 ? pow(h, par.alpha()) * sol.solvability_defects[j] : Real(0);
    // Chebyshev points of another size than the rows' 2 M + 8 (residual_grid_size), and the layer
    // at 0.37 gap 3^k (k of either sign).
    const auto rows = layered_rows(intervals, lj, j, residual_grid_size(std::max(points, M) + 3, 2 * M + 8), Real(0.77), Real(3));
    std::vector<cross_nodes<Real>> nodes(K);
    std::vector<std::vector<Real>> factor(K);
    for (std::size_t i = 0; i < K; ++i) {
      if (i == j) continue;
      const auto& gi = sol.densities[i];
      const auto& li = sol.layers[i];
      const Real gap = union_gap(intervals, i, j), hi_ = gi.half_length();
      const Real d_lo = std::min(li.nearest_lo(), i > j ? gap / hi_ : inf);
      const Real d_hi = std::min(li.nearest_hi(), i > j ? inf : gap / hi_);
      nodes[i] = make_layered_nodes(hi_, gi.gam, gi.del, d_lo, d_hi, M / 2 + 28);
      const auto gi_series = gi.series_evaluator();
      for (std::size_t q = 0; q < nodes[i].x.size(); ++q)
        factor[i].push_back(layered_factor(gi_series, li, nodes[i].t_minus_lo[q] / hi_, nodes[i].hi_minus_t[q] / hi_));
    }
    Real worst_j = 0, scale_j = 0;
    for (const auto& row : rows) {
      Real value = own([&](const Real&, const Real& p, const Real& m) { return layered_factor(gj_series, lj, p, m); },
                       row.s, lj.nearest_lo(), lj.nearest_hi());
      for (std::size_t i = 0; i < K; ++i)
        if (i != j)
          value += cross_sum(par, nodes[i], factor[i], i > j, union_gap(intervals, i, j),
                             i > j ? h * row.one_minus_x : h * row.one_plus_x);
      const Real Fs = F[j](row.s);
      worst_j = max(worst_j, abs(value - (Fs - defect)));
      scale_j = max(scale_j, abs(Fs));
    }
    worst = max(worst, scale_j > 0 ? worst_j / scale_j : worst_j);
  }
  return worst;
}

}  // namespace rhabel::abel::detail
