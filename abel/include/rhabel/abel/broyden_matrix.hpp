// rhabel/abel/broyden_matrix.hpp: the matrix of a quasi-Newton iteration, a factorised
// Jacobian J0 plus Broyden's rank-one updates, solved without a new factorisation. Used by the punch
// layer's edge iteration (punch/src/coupled_solve.cpp) for many contacts.
//
// THE UPDATES. Broyden's ("good") update after a step s that changed the residual by dr makes the
// matrix reproduce that change, J s = dr, and leaves it unchanged on the complement of s:
//     J <- J + u s^T,   u = (dr - J s) / |s|^2.
// After k updates J = J0 + U S^T (columns u_i, s_i), and by the Woodbury identity
//     J^-1 r = y - Z (I + S^T Z)^-1 S^T y,   y = J0^-1 r,   Z = J0^-1 U,
// so a solve costs two triangular solves with J0's factors and O(m k) more, instead of a new
// O(m^3) factorisation (m unknowns; each update adds one triangular solve for its column of Z).
//
// SINGULAR UPDATES. An update can cancel J along its step: a step that no longer changes the
// residual (dr ~ 0, as at the noise floor of the conditions) gives u = -J s/|s|^2, and J + u s^T
// annihilates s. The capacitance matrix I + S^T Z is then singular too, and a solve through it
// returns a meaningless, typically tiny, step that a caller testing "step below tolerance" would
// take for convergence (det J = det J0 det(I + S^T Z)). solve() therefore returns nothing when the
// smallest pivot of the capacitance matrix's LU (full pivoting) is below min_pivot times
// max(1, its largest): the identity's unit is the scale, since a single update's 1 x 1 matrix
// has a reciprocal condition number of 1 however small it is. The caller takes a new Jacobian. (With few unknowns,
// up to full_pivoting_up_to, the updated matrix itself is factorised with full pivoting at every
// solve, as robust for nearly singular Jacobians as it is cheap there.)
//
// ACCURACY. A solve is backward stable like the LU of J0 (partial pivoting) as long as the
// capacitance matrix is well conditioned; its pivot test (above) refuses the ill-conditioned
// cases instead of returning an inaccurate step. Real: float, double, long double.
// REFERENCES. C. G. Broyden, "A class of methods for solving nonlinear simultaneous equations",
// Math. Comp. 19 (1965) 577-593; J. E. Dennis and R. B. Schnabel, "Numerical Methods for
// Unconstrained Optimization and Nonlinear Equations", SIAM 1996, section 8.1; the Woodbury
// identity: Golub and Van Loan, "Matrix Computations", 4th ed., section 2.1.4.
#pragma once

#include <Eigen/Dense>

#include <optional>
#include <utility>

namespace rhabel::abel {

template <class Real>
class broyden_matrix {
 public:
  using matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  using vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;

  /// Up to this many unknowns: the updated matrix, full pivoting, at every solve.
  static constexpr Eigen::Index full_pivoting_up_to = 64;
  /// Below this relative pivot of I + S^T Z, solve() gives up (the header): J then has lost 8
  /// digits of conditioning against J0 along some direction.
  static constexpr double min_pivot = 1e-8;

  explicit broyden_matrix(matrix J0) { reset(std::move(J0)); }

  /// A new Jacobian (the updates are dropped).
  void reset(matrix J0) {
    J_ = std::move(J0);
    U_.resize(J_.rows(), 0);
    S_.resize(J_.rows(), 0);
    Z_.resize(J_.rows(), 0);
    if (J_.rows() > full_pivoting_up_to) lu0_.compute(J_);
  }

  /// J^-1 r with the current updates; nothing when they made J singular (the header).
  std::optional<vector> solve(const vector& r) const {
    if (J_.rows() <= full_pivoting_up_to) return vector(J_.fullPivLu().solve(r));
    const vector y = lu0_.solve(r);
    if (U_.cols() == 0) return y;
    const Eigen::Index k = U_.cols();
    const Eigen::FullPivLU<matrix> C(matrix::Identity(k, k) + S_.transpose() * Z_);
    const auto pivots = C.matrixLU().diagonal().cwiseAbs();
    using std::max;
    if (!(pivots.minCoeff() >= Real(min_pivot) * max(Real(1), pivots.maxCoeff()))) return std::nullopt;
    return vector(y - Z_ * C.solve(S_.transpose() * y));
  }

  /// Broyden's update with the step s and the change dr of the residual it caused.
  void update(const vector& s, const vector& dr) {
    const vector u = (dr - J_ * s) / s.squaredNorm();
    J_ += u * s.transpose();
    if (J_.rows() <= full_pivoting_up_to) return;
    const Eigen::Index k = U_.cols();
    U_.conservativeResize(Eigen::NoChange, k + 1);
    S_.conservativeResize(Eigen::NoChange, k + 1);
    Z_.conservativeResize(Eigen::NoChange, k + 1);
    U_.col(k) = u;
    S_.col(k) = s;
    Z_.col(k) = lu0_.solve(u);
  }

  /// The updated matrix J0 + U S^T.
  const matrix& current() const { return J_; }
  /// Number of updates since the last reset.
  Eigen::Index updates() const { return U_.cols(); }

 private:
  matrix J_;                          // the updated matrix
  Eigen::PartialPivLU<matrix> lu0_;   // J0's factors (many unknowns)
  matrix U_, S_, Z_;                  // the updates' u_i, s_i and J0^-1 u_i
};

}  // namespace rhabel::abel
