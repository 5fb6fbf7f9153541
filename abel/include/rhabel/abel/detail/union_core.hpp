// rhabel/abel/detail/union_core.hpp: the types of the union solver (interval_spec,
// multi_solve_options, layer_density, multi_solution) and its polynomial route's pieces (the
// collocation assembly, the solve at one degree, the independent residual), shared by the
// public header rhabel/abel/multi_interval.hpp (solve_union; the theory, accuracy and cost are
// documented there) and the boundary-layer route detail/layered_union.hpp. Not included directly.
#pragma once

#include "rhabel/abel/abel_solver.hpp"
#include "rhabel/abel/detail/block_gmres.hpp"
#include "rhabel/abel/far_field.hpp"
#include "rhabel/abel/detail/union_assembly.hpp"
#include "rhabel/abel/union_memory.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <utility>
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

/// The unknowns of one matrix-free solve of solve_union (detail/block_gmres.hpp's vector: every
/// interval's collocation unknowns in order) with the degrees they belong to.
template <class Real>
struct union_unknowns {
  std::vector<std::size_t> degrees;
  Eigen::Matrix<Real, Eigen::Dynamic, 1> x;
};

template <class Real>
struct multi_solve_options {
  std::size_t degree = 32;              ///< collocation points (= unknowns) per interval; the first degree tried
  /// Adaptive degree: while the residual exceeds residual_tolerance the degree grows by 1.5x up
  /// to max_degree (0: no adaptation, only `degree`). Needs residual_points > 0. Memory and time
  /// grow like max_degree^2 and ^3 (header: 2 s and a 81 MB peak at 1024 for two intervals;
  /// bounded by max_memory_bytes).
  std::size_t max_degree = 0;
  /// Per interval: the first degree of each (empty: `degree` for all; else one per interval, each
  /// in [2, max_degree], or any >= 2 when max_degree = 0). A caller that knows which intervals need high degrees
  /// (nearly touching neighbours) passes them here, the rest stay cheap.
  std::vector<std::size_t> degrees;
  /// Adaptive degree per interval: only the intervals whose own residual (at their points)
  /// exceeds residual_tolerance grow by 1.5x; false: all grow together while the largest residual
  /// exceeds it. WHY: on a union of many intervals, a few nearly touching pairs need high degrees
  /// (gap 1e-4 L: ~800) and the rest ~16; growing all of them made the solve cost K M^3 for the
  /// largest M (a 230-contact profile: 0.9 s an evaluation at degree 168 for all).
  bool adapt_each_interval = false;
  std::size_t residual_points = 8;      ///< per interval; 0 = skip the residual
  std::vector<std::optional<Real>> loads;  ///< per interval, used for nu = +1 intervals only
  /// status = not_converged when the independent residual exceeds this (only if it is computed).
  Real residual_tolerance = Real(1e-10);
  /// Bound on the estimated peak memory of one dense solve (union_memory_bytes, bytes):
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
  /// The far field of exactly these intervals for that route (far_field.hpp), when the
  /// caller has one (the punch layer builds it for its data anyway); null: solve_union builds it
  /// with order_for(residual_tolerance / 1000) points per box.
  std::shared_ptr<const rhabel::abel::far_field<Real>> far_field;
  /// The first guess of the matrix-free route's GMRES (multi_solution::unknowns of an earlier
  /// solve of nearby data on nearby intervals); used only where its degrees equal the solve's,
  /// else (and when null) GMRES starts from zero. It changes the iterations, not the tolerance
  /// the solution meets. WHY: the finite differences of a Newton iteration on the intervals' edges
  /// (the punch layer's coupled solve) solve systems within ~1e-7 .. 1e-5 of their base point's,
  /// whose solution then starts GMRES that much nearer its answer.
  std::shared_ptr<const union_unknowns<Real>> first_guess;
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
    const panel_integrator<Real> rule(del, gam, 24);
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
  std::size_t degree = 0;                            ///< the largest of `degrees`
  std::vector<std::size_t> degrees;                  ///< collocation points of each interval in the returned solve
  /// Per interval: its part of `residual` (the same definition at the interval's points; empty
  /// when no residual was computed).
  std::vector<Real> interval_residuals;
  /// not_converged: residual > options.residual_tolerance (typically nearly touching intervals,
  /// see the header); converged otherwise, or when no residual was computed.
  solve_status status = solve_status::converged;
  /// The matrix-free route's unknowns of the returned solve (multi_solve_options::first_guess of
  /// a later one); null on the other routes.
  std::shared_ptr<const union_unknowns<Real>> unknowns;
  /// The products of the matrix-free route's GMRES in the returned solve, its homogeneous
  /// solutions included (0 on the other routes).
  std::size_t gmres_products = 0;
};

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

/// Gap between intervals i and j (i != j), sorted and disjoint.
template <class Real>
Real union_gap(const std::vector<interval_spec<Real>>& intervals, std::size_t i, std::size_t j) {
  return i > j ? intervals[i].lo - intervals[j].hi : intervals[j].lo - intervals[i].hi;
}

/// The coupled system of solve_union_at_degree at M[i] collocation points on interval i: the
/// unknowns' layout, the own and cross blocks, the right-hand side, and the linear solve (dense:
/// LU or GMRES on the assembled matrix; matrix-free: own and near blocks plus the far field).
/// Holds the solution being built (sol); not copyable (the solvers refer to its members).
template <class Real>
class union_degree_system {
 public:
  using matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  using vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;

  multi_solution<Real> sol;

  union_degree_system(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals,
                      const std::vector<std::function<Real(Real)>>& F, const multi_solve_options<Real>& options,
                      const std::vector<std::size_t>& M, const far_field<Real>* far)
      : par_(par), intervals_(intervals), options_(options), far_(far), K_(intervals.size()), M_(M) {
    sol.degrees = M;
    sol.degree = *std::max_element(M.begin(), M.end());
    for (const std::size_t m : M) grids_.try_emplace(m, m);
    lay_out();
    collocate(F);
    if (!far_)
      assemble_dense();
    else
      assemble_matrix_free();
  }
  union_degree_system(const union_degree_system&) = delete;
  union_degree_system& operator=(const union_degree_system&) = delete;

  /// The scaled data at the collocation points (equations of interval j in units of h_j^alpha).
  const vector& rhs() const { return rhs_; }

  /// The fixed c_0 of interval i (nu = +1: from its load, 0 without one; 0 for nu != +1).
  Real fixed_c0(std::size_t i) const {
    if (sol.exponents[i].nu != 1) return Real(0);
    if (i < options_.loads.size() && options_.loads[i]) {
      const Real h0 = rhabel::quadrature::jacobi_norm_squared(0, sol.exponents[i].del, sol.exponents[i].gam);
      return *options_.loads[i] / (ops_[i].half_length() * h0);
    }
    return Real(0);
  }

  /// c_0 of the homogeneous solution of interval k (nu = +1), unit load: 1/(h_k ||P_0||^2).
  Real unit_c0(std::size_t k) const {
    const Real h0 = rhabel::quadrature::jacobi_norm_squared(0, sol.exponents[k].del, sol.exponents[k].gam);
    return 1 / (ops_[k].half_length() * h0);
  }

  /// The densities with the unknowns x and the fixed c_0 values c0s.
  std::vector<jacobi_density<Real>> unpack(const vector& x, const std::vector<Real>& c0s) const {
    std::vector<jacobi_density<Real>> out = sol.densities;
    for (std::size_t i = 0; i < K_; ++i)
      for (std::size_t n = 0; n < n_basis_[i]; ++n) {
        const long u = local_index(i, n);
        out[i].coefficients[n] = u >= 0 ? x[static_cast<Eigen::Index>(offset_[i]) + u] : c0s[i];
      }
    return out;
  }

  /// The solvability defects d_j (nu = -1; 0 otherwise) among the unknowns x.
  std::vector<Real> defects(const vector& x) const {
    std::vector<Real> out(K_, Real(0));
    for (std::size_t j = 0; j < K_; ++j)
      if (sol.exponents[j].nu == -1) out[j] = x[static_cast<Eigen::Index>(offset_[j]) + defect_column(j)];
    return out;
  }

  /// x = A^-1 right; nothing when the matrix-free GMRES does not reach its tolerance (the dense
  /// route's GMRES falls back to the LU).
  std::optional<vector> linear_solve(const vector& right, const vector* guess = nullptr) {
    if (far_) {
      vector x;
      if (guess && guess->size() == right.size()) x = *guess;
      std::size_t products = 0;
      const bool reached = gmres_->solve(right, x, Real(1e-14), !x.isZero(0), &products);
      sol.gmres_products += products;
      if (reached) return x;
      return std::nullopt;
    }
    if (gmres_) {
      vector x;
      if (gmres_->solve(right, x, Real(1e-14))) return x;
      factorise();
    }
    return vector(lu_->solve(right));
  }

  /// The image under A of the fixed c_0 values c0s (subtracted from the data).
  vector c0_image(const std::vector<Real>& c0s) const {
    if (far_) {
      vector out = far_part(vector::Zero(T_), c0s);
      for (std::size_t j = 0; j < K_; ++j)
        for (const auto& [i, column] : near_c0_[j])
          if (sol.exponents[i].nu == 1) out.segment(static_cast<Eigen::Index>(offset_[j]), size(j)) += c0s[i] * column;
      return out;
    }
    vector out = vector::Zero(T_);
    for (std::size_t i = 0; i < K_; ++i)
      if (sol.exponents[i].nu == 1) out += c0s[i] * c0_columns_[i];
    return out;
  }

 private:
  // The intervals' operators, classes, basis sizes, block offsets and zero densities.
  // Unknowns of interval i: the coefficients c^i_n (n_basis[i] of them; for nu = +1 c^i_0 is
  // fixed by the load and not an unknown) and, for nu = -1, the defect d_i. Rows: the M_i
  // collocation equations of interval i. Both number M_i on interval i: the system is square.
  void lay_out() {
    n_basis_.resize(K_);
    offset_.resize(K_);
    std::size_t offset = 0;
    for (std::size_t i = 0; i < K_; ++i) {
      ops_.emplace_back(par_, intervals_[i].lo, intervals_[i].hi);
      const auto e = par_.exponents(intervals_[i].leading, intervals_[i].trailing);
      sol.exponents.push_back(e);
      n_basis_[i] = e.nu == -1 ? M_[i] - 1 : (e.nu == 0 ? M_[i] : M_[i] + 1);
      offset_[i] = offset;
      offset += M_[i];
      sol.densities.push_back(zero_density(intervals_[i], e, n_basis_[i]));
    }
    T_ = static_cast<Eigen::Index>(offset);
  }

  // Interval i's block size (collocation points = unknowns), its grid and its defect's column
  // (nu = -1: the last unknown of the block).
  Eigen::Index size(std::size_t i) const { return static_cast<Eigen::Index>(M_[i]); }
  const chebyshev_grid<Real>& grid(std::size_t i) const { return grids_.at(M_[i]); }
  Eigen::Index defect_column(std::size_t i) const { return size(i) - 1; }

  // The collocation points of each interval, the equations' scales h_j^-alpha and the scaled data.
  void collocate(const std::vector<std::function<Real(Real)>>& F) {
    using std::pow;
    pts_.resize(K_);
    scale_.resize(K_);
    rhs_.resize(T_);
    for (std::size_t j = 0; j < K_; ++j) {
      scale_[j] = pow(ops_[j].half_length(), -par_.alpha());
      pts_[j] = union_points(intervals_[j], grid(j));
      for (std::size_t k = 0; k < M_[j]; ++k) {
        const Real v = F[j](pts_[j][k].s);
        check_finite_value("rhabel::abel::solve_union", v, pts_[j][k].s);
        rhs_[static_cast<Eigen::Index>(offset_[j] + k)] = scale_[j] * v;
      }
    }
  }

  // Column of c^i_n within interval i's block (-1: the fixed c_0 of nu = +1).
  long local_index(std::size_t i, std::size_t n) const {
    if (sol.exponents[i].nu == 1) return n == 0 ? -1 : static_cast<long>(n - 1);
    return static_cast<long>(n);
  }

  // Own block of interval j (M x M, j's unknowns): A(w P_n) = h^alpha lambda_n P_{n - nu}^(gam + nu,
  // del + nu) (spectral relation); nu = -1: F - A g = d_j P_0 (the part of the data outside the range).
  matrix own_block(std::size_t j) const {
    const auto& e = sol.exponents[j];
    const Real p = e.gam + Real(e.nu), q = e.del + Real(e.nu);
    const std::vector<Real> lambda = ops_[j].eigenvalues(n_basis_[j], e);  // O(n_basis) in all
    matrix B = matrix::Zero(size(j), size(j));
    for (std::size_t k = 0; k < M_[j]; ++k) {
      const auto r = static_cast<Eigen::Index>(k);
      const auto image = jacobi_values_any(M_[j], p, q, grid(j).x[k]);
      for (std::size_t n = 0; n < n_basis_[j]; ++n) {
        const long m = static_cast<long>(n) - e.nu;
        if (m < 0) continue;  // nu = +1, n = 0: the homogeneous solution, image 0
        const long c = local_index(j, n);
        if (c >= 0) B(r, c) += lambda[n] * image[static_cast<std::size_t>(m)];
      }
      if (e.nu == -1) B(r, defect_column(j)) += Real(1);
    }
    return B;
  }

  // Cross block of interval i acting on j's collocation points (M_j x M_i in i's unknowns) and
  // the column of i's fixed c_0 (nu = +1).
  matrix cross(std::size_t j, std::size_t i, vector& c0_column) {
    const bool right = i > j;
    std::vector<Real> dist(M_[j]);
    for (std::size_t k = 0; k < M_[j]; ++k) dist[k] = right ? pts_[j][k].to_hi : pts_[j][k].from_lo;
    const auto& par = par_;
    const auto B = cross_block(sol.densities[i], union_gap(intervals_, i, j), right, dist, n_basis_[i], scale_[j],
                               [&](const Real& t_minus_s) { return cross_kernel(par, t_minus_s); }, &basis_cache_);
    matrix out = matrix::Zero(size(j), size(i));
    c0_column = vector::Zero(size(j));
    for (std::size_t n = 0; n < n_basis_[i]; ++n) {
      const long c = local_index(i, n);
      if (c >= 0)
        out.col(c) += B.col(static_cast<Eigen::Index>(n));
      else
        c0_column += B.col(static_cast<Eigen::Index>(n));
    }
    return out;
  }

  // Dense route: A assembled, then GMRES (options.iterative_from) or its LU.
  // Many intervals (options.iterative_from): GMRES with the block-diagonal preconditioner
  // (detail/block_gmres.hpp), O(T^2) per iteration against the LU's 2/3 T^3; `condition` is
  // then not computed (NaN). Otherwise, or when GMRES does not reach its tolerance: LU.
  void assemble_dense() {
    A_ = matrix::Zero(T_, T_);
    c0_columns_.assign(K_, vector::Zero(T_));
    for (std::size_t j = 0; j < K_; ++j) {
      const auto row0 = static_cast<Eigen::Index>(offset_[j]);
      A_.block(row0, row0, size(j), size(j)) = own_block(j);
      for (std::size_t i = 0; i < K_; ++i) {
        if (i == j) continue;
        vector c0_column;
        A_.block(row0, static_cast<Eigen::Index>(offset_[i]), size(j), size(i)) += cross(j, i, c0_column);
        c0_columns_[i].segment(row0, size(j)) += c0_column;
      }
    }
    // 1-norm of A for the exact condition of non-IEEE types (A is overwritten below).
    if constexpr (!std::is_floating_point_v<Real>) norm_A_ = A_.cwiseAbs().colwise().sum().maxCoeff();
    if (std::is_floating_point_v<Real> && K_ > 1 && options_.iterative_from > 1 && K_ >= options_.iterative_from) {
      std::vector<Eigen::Index> blocks;
      for (std::size_t j = 0; j < K_; ++j) blocks.push_back(size(j));
      gmres_ = std::make_unique<block_gmres<Real>>(A_, blocks);
      sol.condition = std::numeric_limits<Real>::quiet_NaN();
    } else {
      factorise();
    }
  }

  // LU of the dense A in place, and its condition number.
  // LU in place (Eigen::Ref): A holds the factors from then on. With a
  // copy of A (PartialPivLU of a matrix; its rcond() then also allocated a T x T temporary) the
  // peak was 3 (K M)^2 numbers: 405 MB against 143 MB now at K = 1, M = 4096; 410 MB against
  // 268 MB at K = 2, M = 2048. The factorisation is the same, bit for bit (checked on a random
  // 2000 x 2000).
  void factorise() {
    gmres_.reset();  // it refers to A, which the LU overwrites
    lu_ = std::make_unique<Eigen::PartialPivLU<Eigen::Ref<matrix>>>(A_);
    if constexpr (std::is_floating_point_v<Real>) {
      sol.condition = 1 / lu_->rcond();
    } else {
      // Eigen's estimator needs NumTraits<Real>::infinity(), which the Boost.Multiprecision
      // bindings lack: the exact 1-norm condition instead (O(size^3), like the LU itself).
      const matrix inverse = lu_->inverse();
      sol.condition = norm_A_ * inverse.cwiseAbs().colwise().sum().maxCoeff();
    }
  }

  // Matrix-free route: own and near blocks, moment matrices, the far field's interpolation, and
  // GMRES on their product.
  void assemble_matrix_free() {
    own_.resize(K_);
    moment_.resize(K_);
    near_.resize(K_);
    near_c0_.resize(K_);
    for (const auto& [m, g] : grids_) interpolation_.emplace(m, far_->interpolation(g.x));
    for (std::size_t j = 0; j < K_; ++j) {
      own_[j] = own_block(j);
      moment_[j] = far_->moment_matrix(j, sol.densities[j].del, sol.densities[j].gam, n_basis_[j]);
      for (std::size_t i : far_->near_leaves(j)) {
        vector c0_column;
        near_[j].emplace_back(i, cross(j, i, c0_column));
        near_c0_[j].emplace_back(i, std::move(c0_column));
      }
    }
    const std::vector<Real> no_c0(K_, Real(0));
    auto apply = [this, no_c0](const vector& x) {
      vector out = far_part(x, no_c0);
      for (std::size_t j = 0; j < K_; ++j) {
        const auto row0 = static_cast<Eigen::Index>(offset_[j]);
        out.segment(row0, size(j)) += own_[j] * x.segment(row0, size(j));
        for (const auto& [i, B] : near_[j])
          out.segment(row0, size(j)) += B * x.segment(static_cast<Eigen::Index>(offset_[i]), size(i));
      }
      return out;
    };
    gmres_ = std::make_unique<block_gmres<Real>>(apply, own_);
    sol.condition = std::numeric_limits<Real>::quiet_NaN();
  }

  // The far part of A x (coefficients from x and the fixed c_0 values c0s).
  vector far_part(const vector& x, const std::vector<Real>& c0s) const {
    std::vector<vector> W(K_);
    for (std::size_t i = 0; i < K_; ++i) {
      vector c(static_cast<Eigen::Index>(n_basis_[i]));
      for (std::size_t n = 0; n < n_basis_[i]; ++n) {
        const long u = local_index(i, n);
        c[static_cast<Eigen::Index>(n)] = u >= 0 ? x[static_cast<Eigen::Index>(offset_[i]) + u] : c0s[i];
      }
      W[i] = moment_[i] * c;
    }
    const auto local = far_->far_values(W);
    vector out(T_);
    for (std::size_t j = 0; j < K_; ++j)
      out.segment(static_cast<Eigen::Index>(offset_[j]), size(j)) = scale_[j] * (interpolation_.at(M_[j]) * local[j]);
    return out;
  }

  const abel_parameters<Real>& par_;
  const std::vector<interval_spec<Real>>& intervals_;
  const multi_solve_options<Real>& options_;
  const far_field<Real>* far_;
  std::size_t K_;
  std::vector<std::size_t> M_;  // collocation points (= unknowns) of each interval
  Eigen::Index T_ = 0;          // their sum
  std::map<std::size_t, chebyshev_grid<Real>> grids_;  // one Chebyshev grid per distinct M_i
  std::vector<abel_operator<Real>> ops_;
  std::vector<std::size_t> n_basis_, offset_;
  separated_basis_cache<Real> basis_cache_;
  std::vector<std::vector<union_point<Real>>> pts_;
  std::vector<Real> scale_;  // equations of interval j in units of h_j^alpha
  vector rhs_;
  // Dense route: A (then its LU factors), the images of the fixed c_0 of nu = +1 intervals.
  matrix A_;
  std::vector<vector> c0_columns_;
  Real norm_A_ = 0;  // 1-norm of A before the LU (non-IEEE types only)
  std::unique_ptr<Eigen::PartialPivLU<Eigen::Ref<matrix>>> lu_;
  std::unique_ptr<block_gmres<Real>> gmres_;
  // Matrix-free route: own and near blocks, moment matrices, the far field's interpolation.
  std::vector<matrix> own_, moment_;
  std::vector<std::vector<std::pair<std::size_t, matrix>>> near_;  // near_[j]: (i, block)
  std::vector<std::vector<std::pair<std::size_t, vector>>> near_c0_;
  std::map<std::size_t, matrix> interpolation_;  // the far field's interpolation to each grid
};

/// One solve of the coupled system at M[i] collocation points on interval i (no residual).
/// far: null for the dense system (LU, or GMRES on the assembled matrix from iterative_from on);
/// else the far field of these intervals: only the own and near blocks are assembled and the
/// far part is applied by the far field inside GMRES (the header, "Many intervals"). Returns
/// nothing when that GMRES does not reach its tolerance (the caller then solves densely).
template <class Real>
std::optional<multi_solution<Real>> solve_union_at_degree(const abel_parameters<Real>& par,
                                                          const std::vector<interval_spec<Real>>& intervals,
                                                          const std::vector<std::function<Real(Real)>>& F,
                                                          const multi_solve_options<Real>& options,
                                                          const std::vector<std::size_t>& M,
                                                          const far_field<Real>* far = nullptr) {
  const std::size_t K = intervals.size();
  union_degree_system<Real> system(par, intervals, F, options, M, far);
  multi_solution<Real>& sol = system.sol;
  std::vector<Real> c0(K, Real(0));
  for (std::size_t i = 0; i < K; ++i) c0[i] = system.fixed_c0(i);
  const bool guessed = far && options.first_guess && options.first_guess->degrees == M;
  const auto c = system.linear_solve(system.rhs() - system.c0_image(c0), guessed ? &options.first_guess->x : nullptr);
  if (!c) return std::nullopt;
  if (far) sol.unknowns = std::make_shared<const union_unknowns<Real>>(union_unknowns<Real>{M, *c});
  sol.densities = system.unpack(*c, c0);
  sol.solvability_defects = system.defects(*c);
  sol.homogeneous.assign(K, {});
  sol.homogeneous_defects.assign(K, std::vector<Real>(K, Real(0)));
  for (std::size_t k = 0; k < K && options.homogeneous; ++k) {
    if (sol.exponents[k].nu != 1) continue;
    std::vector<Real> c0k(K, Real(0));
    c0k[k] = system.unit_c0(k);
    const auto x = system.linear_solve(-system.c0_image(c0k));
    if (!x) return std::nullopt;
    sol.homogeneous[k] = system.unpack(*x, c0k);
    sol.homogeneous_defects[k] = system.defects(*x);
  }
  return std::move(sol);
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

/// Independent residual of the original equation (see the header), per interval j:
/// max_s |A g(s) - (F(s) - h^alpha d_j)| / max_s |F(s)| over s in I_j, at Chebyshev points of
/// another power of 2 than I_j's collocation grid and at points graded toward every facing end.
template <class Real>
std::vector<Real> union_residuals(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals,
                    const std::vector<std::function<Real(Real)>>& F, const multi_solution<Real>& sol,
                    std::size_t points, const far_field<Real>* far = nullptr) {
  using std::abs;
  using std::max;
  using std::pow;
  const std::size_t K = intervals.size();
  const Real alpha = par.alpha();
  std::vector<Real> out(K, Real(0));
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
    auto pts = union_points(intervals[j], chebyshev_grid<Real>(residual_grid_size(points, sol.degrees[j])));
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
    out[j] = scale_j > 0 ? worst_j / scale_j : worst_j;
  }
  return out;
}

/// The argument checks of solve_union and solve_union_layered (their comments list them).
template <class Real>
void check_union_arguments(const abel_parameters<Real>& par, const std::vector<interval_spec<Real>>& intervals,
                           const std::vector<std::function<Real(Real)>>& F, const multi_solve_options<Real>& options) {
  const std::size_t K = intervals.size();
  if (K == 0) throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union", "number of intervals", 0, "[1, inf)");
  if (F.size() != K)
    throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union", "number of data functions", F.size(), "equal to the number of intervals");
  for (std::size_t i = 0; i < K; ++i) {
    abel_operator<Real> check(par, intervals[i].lo, intervals[i].hi);  // validates lo < hi
    (void)check;
    if (i > 0 && !(intervals[i].lo > intervals[i - 1].hi))
      throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union", "interval lo", intervals[i].lo,
                          "> hi of the previous interval (sorted, disjoint intervals)");
  }
  if (!options.degrees.empty() && options.degrees.size() != K)
    throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union", "options.degrees size", options.degrees.size(),
                        "0 or the number of intervals");
  for (const std::size_t m : options.degrees)
    if (m < 2 || (options.max_degree != 0 && m > options.max_degree))
      throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union", "options.degrees", m,
                          "[2, options.max_degree] (or [2, inf) without adaptation)");
  if (options.max_degree != 0 && options.max_degree < options.degree)
    throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union", "options.max_degree", options.max_degree,
                        "0 (no adaptation) or >= options.degree");
  if (options.max_degree > options.degree && options.residual_points == 0)
    throw_bad_parameter("rhabel::abel::rhabel::abel::solve_union", "options.residual_points", 0,
                        "> 0 when options.max_degree > options.degree (the residual drives the degree)");
}

}  // namespace detail

}  // namespace rhabel::abel
