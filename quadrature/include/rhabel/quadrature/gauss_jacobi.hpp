// rhabel/quadrature/gauss_jacobi.hpp
//
// INTERIM IMPLEMENTATION (to be replaced by the O(n) asymptotic algorithm): Golub-Welsch
// initial nodes, Newton polish on the recurrence, weights from the derivative formula.
// The public interface below is the contract other modules build on.
#pragma once

#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstddef>
#include <vector>

namespace rhabel::quadrature {

/// A quadrature rule on [lo, hi]: sum_i weight[i] f(x[i]) ~ int_lo^hi w(t) f(t) dt.
/// Beside each node it carries its distances to both ends, computed without cancellation,
/// so that callers can evaluate endpoint weight factors (hi - t)^p (t - lo)^q to full
/// relative accuracy even where x[i] itself holds only a few digits of hi - x[i].
template <class Real>
struct quadrature_rule {
  std::vector<Real> x;           ///< nodes, strictly increasing
  std::vector<Real> hi_minus_x;  ///< hi - x[i]  (1 - x[i] on [-1, 1])
  std::vector<Real> x_minus_lo;  ///< x[i] - lo  (1 + x[i] on [-1, 1])
  std::vector<Real> weight;      ///< positive weights

  std::size_t size() const { return x.size(); }

  /// sum_i weight[i] f(x[i]).
  template <class F>
  Real integrate(F&& f) const {
    Real sum = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sum += weight[i] * f(x[i]);
    return sum;
  }
};

/// n-point Gauss-Jacobi rule for the weight (1 - x)^p (1 + x)^q on [-1, 1]:
/// exact for polynomials of degree <= 2n - 1.
template <class Real>
quadrature_rule<Real> gauss_jacobi(std::size_t n, Real p, Real q) {
  using boost::math::lgamma;
  using std::abs;
  using std::exp;
  using std::log;
  using std::sqrt;
  detail::check_jacobi_exponents("gauss_jacobi", p, q);
  if (n == 0) detail::throw_bad_parameter("gauss_jacobi", "n", 0, "[1, inf)");

  // Golub-Welsch: eigenvalues of the symmetric Jacobi matrix of the orthonormal polynomials.
  Eigen::VectorXd diagonal(static_cast<Eigen::Index>(n));
  Eigen::VectorXd off_diagonal(static_cast<Eigen::Index>(n > 1 ? n - 1 : 0));
  const double pd = static_cast<double>(p), qd = static_cast<double>(q);
  for (std::size_t k = 0; k < n; ++k) {
    const double s = 2.0 * static_cast<double>(k) + pd + qd;
    diagonal[static_cast<Eigen::Index>(k)] =
        k == 0 ? (qd - pd) / (pd + qd + 2) : (qd * qd - pd * pd) / (s * (s + 2));
  }
  for (std::size_t k = 1; k < n; ++k) {
    const double m = static_cast<double>(k), s = 2 * m + pd + qd;
    const double b2 = k == 1 ? 4 * (1 + pd) * (1 + qd) / ((2 + pd + qd) * (2 + pd + qd) * (3 + pd + qd))
                             : 4 * m * (m + pd) * (m + qd) * (m + pd + qd) / (s * s * (s + 1) * (s - 1));
    off_diagonal[static_cast<Eigen::Index>(k - 1)] = std::sqrt(b2);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
  eigen.computeFromTridiagonal(diagonal, off_diagonal, Eigen::EigenvaluesOnly);

  quadrature_rule<Real> rule;
  rule.x.resize(n);
  rule.hi_minus_x.resize(n);
  rule.x_minus_lo.resize(n);
  rule.weight.resize(n);
  const Real m = Real(n);
  const Real log_constant = (p + q + 1) * log(Real(2)) + lgamma(m + p + 1) + lgamma(m + q + 1) -
                            lgamma(m + p + q + 1) - lgamma(m + 1);
  for (std::size_t i = 0; i < n; ++i) {
    Real x = Real(eigen.eigenvalues()[static_cast<Eigen::Index>(i)]);
    for (int iteration = 0; iteration < 3; ++iteration) {
      const Real value = jacobi_p(n, p, q, x);
      const Real slope = jacobi_p_derivative(n, p, q, x);
      x -= value / slope;
    }
    const Real slope = jacobi_p_derivative(n, p, q, x);
    rule.x[i] = x;
    rule.hi_minus_x[i] = 1 - x;
    rule.x_minus_lo[i] = 1 + x;
    rule.weight[i] = exp(log_constant) / ((1 - x) * (1 + x) * slope * slope);
  }
  return rule;
}

/// n-point Gauss-Jacobi rule for the weight (hi - t)^p (t - lo)^q on [lo, hi].
template <class Real>
quadrature_rule<Real> gauss_jacobi(std::size_t n, Real p, Real q, Real lo, Real hi) {
  using std::isfinite;
  using std::pow;
  if (!isfinite(lo)) detail::throw_bad_parameter("gauss_jacobi", "lo", lo, "finite, lo < hi");
  if (!isfinite(hi) || !(hi > lo)) detail::throw_bad_parameter("gauss_jacobi", "hi", hi, "finite, hi > lo");
  quadrature_rule<Real> rule = gauss_jacobi(n, p, q);
  const Real half_length = (hi - lo) / 2;
  const Real scale = pow(half_length, p + q + 1);
  for (std::size_t i = 0; i < rule.size(); ++i) {
    rule.hi_minus_x[i] *= half_length;
    rule.x_minus_lo[i] *= half_length;
    // Take the node from the nearer end so that it inherits that distance's accuracy.
    rule.x[i] = rule.x_minus_lo[i] <= rule.hi_minus_x[i] ? lo + rule.x_minus_lo[i] : hi - rule.hi_minus_x[i];
    rule.weight[i] *= scale;
  }
  return rule;
}

}  // namespace rhabel::quadrature
