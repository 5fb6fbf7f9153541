// rhabel/quadrature/jacobi_polynomial.hpp
//
// Jacobi polynomials P_n^(p,q)(x), orthogonal on [-1, 1] with weight (1 - x)^p (1 + x)^q,
// p, q > -1 (Szego, "Orthogonal Polynomials", ch. 4; DLMF 18.3, 18.9).
//
// Notation. Throughout rhabel the Jacobi exponents are called (p, q): p belongs to the end
// x = +1, q to the end x = -1. The letters alpha and beta are reserved for the paper's
// material exponent and friction parameter, and [a, b] for the contact interval.
//
// What is computed, and how accurately:
//  * jacobi_p, jacobi_p_all: the three-term recurrence (DLMF 18.9.1-2) run forward. It is
//    forward stable for x in [-1, 1]; the relative error of P_n(x) is O(n eps) away from the
//    zeros of P_n (absolute error O(n eps) max|P_n| near them).
//  * jacobi_p_derivative: d/dx P_n^(p,q) = (n + p + q + 1)/2 P_{n-1}^(p+1,q+1)  (DLMF 18.9.15).
//  * jacobi_norm_squared: h_n = int w P_n^2, through lgamma, so nothing overflows; relative
//    error a few eps for any n.
//  * jacobi_clenshaw: sum_k c_k P_k(x) by Clenshaw's algorithm, O(K) and backward stable.
// Every function is a template on Real so that tests can run at 50 digits (Boost.Multiprecision).
#pragma once

#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rhabel::quadrature {

namespace detail {

// Throws std::domain_error naming the function, the parameter, its value and the valid range.
template <class Real>
[[noreturn]] void throw_bad_parameter(const char* function, const char* parameter, const Real& value,
                                      const char* valid_range) {
  std::ostringstream message;
  message.precision(17);
  message << function << ": " << parameter << " = " << value << " is outside the valid range "
          << valid_range;
  throw std::domain_error(message.str());
}

template <class Real>
void check_jacobi_exponents(const char* function, const Real& p, const Real& q) {
  using std::isfinite;
  if (!(p > -1) || !isfinite(p)) throw_bad_parameter(function, "p", p, "(-1, inf)");
  if (!(q > -1) || !isfinite(q)) throw_bad_parameter(function, "q", q, "(-1, inf)");
}

// Coefficients of P_{k+1} = (A_k x + B_k) P_k - C_k P_{k-1}  (DLMF 18.9.1-2).
template <class Real>
struct jacobi_recurrence {
  Real A, B, C;
};

template <class Real>
jacobi_recurrence<Real> jacobi_recurrence_coefficients(std::size_t k, const Real& p, const Real& q) {
  if (k == 0) {
    // P_1 = (p + q + 2)/2 x + (p - q)/2; the general formula is 0/0 when p + q = -1.
    return {(p + q + 2) / 2, (p - q) / 2, Real(0)};
  }
  const Real n = Real(k);
  const Real s = 2 * n + p + q;  // > 0 for k >= 1
  const Real denominator = 2 * (n + 1) * (n + p + q + 1) * s;
  const Real A = (s + 1) * (s + 2) * s / denominator;
  const Real B = (s + 1) * (p * p - q * q) / denominator;
  const Real C = 2 * (n + p) * (n + q) * (s + 2) / denominator;
  return {A, B, C};
}

}  // namespace detail

/// P_n^(p,q)(x) by the forward three-term recurrence. p, q > -1; any finite x.
template <class Real>
Real jacobi_p(std::size_t n, const Real& p, const Real& q, const Real& x) {
  detail::check_jacobi_exponents("jacobi_p", p, q);
  Real previous = 1;  // P_0
  if (n == 0) return previous;
  Real current = (p + q + 2) / 2 * x + (p - q) / 2;  // P_1
  for (std::size_t k = 1; k < n; ++k) {
    const auto r = detail::jacobi_recurrence_coefficients(k, p, q);
    const Real next = (r.A * x + r.B) * current - r.C * previous;
    previous = current;
    current = next;
  }
  return current;
}

/// Values P_0(x), ..., P_n_max(x) in one pass (n_max + 1 entries).
template <class Real>
std::vector<Real> jacobi_p_all(std::size_t n_max, const Real& p, const Real& q, const Real& x) {
  detail::check_jacobi_exponents("jacobi_p_all", p, q);
  std::vector<Real> values(n_max + 1);
  values[0] = 1;
  if (n_max >= 1) values[1] = (p + q + 2) / 2 * x + (p - q) / 2;
  for (std::size_t k = 1; k < n_max; ++k) {
    const auto r = detail::jacobi_recurrence_coefficients(k, p, q);
    values[k + 1] = (r.A * x + r.B) * values[k] - r.C * values[k - 1];
  }
  return values;
}

/// d/dx P_n^(p,q)(x) = (n + p + q + 1)/2 P_{n-1}^(p+1,q+1)(x).
template <class Real>
Real jacobi_p_derivative(std::size_t n, const Real& p, const Real& q, const Real& x) {
  detail::check_jacobi_exponents("jacobi_p_derivative", p, q);
  if (n == 0) return Real(0);
  return (Real(n) + p + q + 1) / 2 * jacobi_p(n - 1, p + 1, q + 1, x);
}

/// log h_n, h_n = int_{-1}^{1} (1-x)^p (1+x)^q P_n^(p,q)(x)^2 dx  (DLMF 18.3, table 18.3.1).
template <class Real>
Real log_jacobi_norm_squared(std::size_t n, const Real& p, const Real& q) {
  using boost::math::lgamma;
  using std::log;
  detail::check_jacobi_exponents("jacobi_norm_squared", p, q);
  const Real ln2 = log(Real(2));
  if (n == 0) {
    return (p + q + 1) * ln2 + lgamma(p + 1) + lgamma(q + 1) - lgamma(p + q + 2);
  }
  const Real m = Real(n);
  return (p + q + 1) * ln2 - log(2 * m + p + q + 1) + lgamma(m + p + 1) + lgamma(m + q + 1) -
         lgamma(m + p + q + 1) - lgamma(m + 1);
}

/// h_n = int_{-1}^{1} (1-x)^p (1+x)^q P_n^(p,q)(x)^2 dx.
template <class Real>
Real jacobi_norm_squared(std::size_t n, const Real& p, const Real& q) {
  using std::exp;
  return exp(log_jacobi_norm_squared(n, p, q));
}

/// sum_{k=0}^{K-1} c[k] P_k^(p,q)(x) by Clenshaw's backward recurrence.
template <class Real>
Real jacobi_clenshaw(const std::vector<Real>& c, const Real& p, const Real& q, const Real& x) {
  detail::check_jacobi_exponents("jacobi_clenshaw", p, q);
  Real b1 = 0, b2 = 0;  // b_{k+1}, b_{k+2}
  for (std::size_t k = c.size(); k-- > 0;) {
    const auto r = detail::jacobi_recurrence_coefficients(k, p, q);
    const Real C_next = c.size() > k + 1 ? detail::jacobi_recurrence_coefficients(k + 1, p, q).C : Real(0);
    const Real b0 = c[k] + (r.A * x + r.B) * b1 - C_next * b2;
    b2 = b1;
    b1 = b0;
  }
  return b1;
}

}  // namespace rhabel::quadrature
