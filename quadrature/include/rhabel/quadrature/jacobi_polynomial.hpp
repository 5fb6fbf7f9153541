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
//    zeros of P_n (absolute error O(n eps) max|P_n| near them). In the boundary layers
//    n^2 (1 -+ x) <= 2, where the recurrence loses up to n^2 eps when p or q is near -1,
//    jacobi_p sums the endpoint hypergeometric series instead (relative error a few eps;
//    measured, tests/quadrature/test_jacobi_polynomial.cpp), and for |x| >= 1/2 it runs the
//    recurrence in Reinsch's difference form (see jacobi_p_visit_near_one). Measured
//    against a 100-digit table: <= 0.3 (n + 10) eps relative to the local scale for n <= 10^6,
//    except in the transition zone 1 < n^2 (1 -+ x) < n with the exponent at that end near -1
//    (<= 640 n eps there; e.g. n = 10^6, p = -0.999, 1 - x = 2^-30).
//  * jacobi_p_derivative: d/dx P_n^(p,q) = (n + p + q + 1)/2 P_{n-1}^(p+1,q+1)  (DLMF 18.9.15).
//  * jacobi_norm_squared: h_n = int w P_n^2, through lgamma, so nothing overflows; relative
//    error a few eps for any n.
//  * jacobi_clenshaw: sum_k c_k P_k(x) by Clenshaw's algorithm for |x| < 1/2, by the forward
//    difference-form recurrence near the ends; O(K). Any finite x; a sum beyond the range of Real
//    (|x| far beyond 1) is std::overflow_error, as in jacobi_series, never inf or NaN.
//  * jacobi_series<Real>: the same sum with the recurrence coefficients computed once (O(K)
//    setup, then O(K) multiply-adds per point, no divisions): for many evaluations of one series.
//    Same algorithms, switches and operation order as jacobi_clenshaw (the difference-form
//    coefficients of both come from detail::difference_form_coefficients), so the sums are the
//    same (tested in tests/quadrature/test_jacobi_series.cpp). Overload (one_minus_x, one_plus_x) takes exact
//    complements near the ends (u = 1 -+ x is then not re-rounded). evaluate(x, out, n): the same
//    values at n points, four recurrences interleaved (~3x fewer ns a point; bench_jacobi_series).
//  * jacobi_weight(p, q, 1 - x, 1 + x): the weight from the complements, full relative accuracy
//    at 1e-300 from an end when the complements are exact.
//  * connection coefficients (DLMF 18.9.5-6): P_n^(p,q) in the families (p+1, q) and (p, q+1)
//    (two terms each), and the lowering identities (1 - x) P_n^(p+1,q), (1 + x) P_n^(p,q+1) in
//    the family (p, q); jacobi_series_raise_p/q and jacobi_series_times_one_minus_x/one_plus_x
//    apply them to coefficient vectors (exact up to rounding; O(K)).
//  * jacobi_coefficients(f, p, q, n): c_k = (1/h_k) sum_i w_i f(x_i) P_k(x_i) with the n-point
//    Gauss-Jacobi rule: exact for polynomials of degree < n, spectrally accurate for analytic f;
//    f may take (x, 1 + x, 1 - x), the rule's exact distances to the ends (declared in detail/jacobi_projection.hpp because it needs gauss_jacobi.hpp; the umbrella
//    rhabel/quadrature.hpp includes it).
//  * jacobi_integral_below(m, p, q, x0) = int_{-1}^{x0} w P_m by the Rodrigues-type identity
//        d/dx[(1-x)^(p+1) (1+x)^(q+1) P_{m-1}^(p+1,q+1)] = -2m (1-x)^p (1+x)^q P_m^(p,q)   (m >= 1)
//    (DLMF 18.9.16 with n = m - 1), so int_{-1}^{x0} w P_m = -(1/(2m)) (1-x0)^(p+1) (1+x0)^(q+1)
//    P_{m-1}^(p+1,q+1)(x0), and for m = 0 the incomplete beta function
//        int_{-1}^{x0} w = 2^(p+q+1) B_{(1+x0)/2}(q+1, p+1)         (t = 2u - 1).
//    jacobi_step_coefficients / jacobi_ramp_coefficients: exact Jacobi coefficients of the
//    indicator 1_{x < x0} and of the kink (x0 - x)_+ (one more integration of the same identity).
//    These expansions converge slowly (the functions are not smooth); they are exact term by term.
// Every function is a template on Real so that tests can run at 50 digits (Boost.Multiprecision).
#pragma once

#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <algorithm>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
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

// A sum that is not finite (the polynomial beyond the range of Real: |x| well beyond 1, or
// coefficients near overflow; NaN from inf - inf) is reported as std::overflow_error naming the
// function and x, never returned.
template <class Real>
Real finite_sum(const char* function, const Real& x, const Real& sum) {
  using std::isfinite;
  if (!isfinite(sum)) {
    std::ostringstream message;
    message.precision(17);
    message << function << ": the sum at x = " << x << " is " << sum
            << ", beyond the range of the type (|x| too far beyond 1 for this degree, or coefficients near overflow)";
    throw std::overflow_error(message.str());
  }
  return sum;
}

template <class Real>
void check_jacobi_exponents(const char* function, const Real& p, const Real& q) {
  using std::isfinite;
  if (!(p > -1) || !isfinite(p)) throw_bad_parameter(function, "p", p, "(-1, inf)");
  if (!(q > -1) || !isfinite(q)) throw_bad_parameter(function, "q", q, "(-1, inf)");
}

// A complement 1 - x or 1 + x of a point x of [-1, 1] must lie in [0, 2] (NaN fails too).
template <class Real>
void check_complement(const char* function, const char* parameter, const Real& value) {
  if (!(value >= 0) || !(value <= 2)) throw_bad_parameter(function, parameter, value, "[0, 2]");
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

namespace detail {

/// P_n^(p,q)(x) near x = +1 from u = (1 - x)/2 by the terminating hypergeometric series
///   P_n^(p,q)(x) = (p+1)_n / n! * 2F1(-n, n+p+q+1; p+1; u)          (DLMF 18.5.7)
/// For n^2 u <= 1 the terms behave like those of the Bessel series of J_p(2 n sqrt(u)) and
/// decrease after k ~ n sqrt(u) <= 1: at most a factor e^2 of cancellation, so the relative
/// error is a few eps (the recurrence loses up to n^2 eps relative there when p is near -1).
/// (p+1)_n/n! = Gamma(n+p+1)/(Gamma(p+1) n!) uses tgamma_delta_ratio (a few ulps at any n).
template <class Real>
Real jacobi_p_endpoint_series(std::size_t n, const Real& p, const Real& q, const Real& u) {
  using std::abs;
  const Real eps = std::numeric_limits<Real>::epsilon();
  const Real N = Real(n);
  Real term = 1, sum = 1;
  for (std::size_t k = 0; k < n; ++k) {
    const Real K = Real(k);
    term *= (K - N) * (K + N + p + q + 1) / ((K + 1) * (K + p + 1)) * u;
    sum += term;
    if (abs(term) <= eps / 8 * abs(sum) && K * K >= N * N * u) break;
  }
  const Real end_value = 1 / (boost::math::tgamma_delta_ratio(N + 1, p) * boost::math::tgamma(p + 1));
  return end_value * sum;
}

/// Three-term recurrence, forward (see the header).
template <class Real>
Real jacobi_p_recurrence(std::size_t n, const Real& p, const Real& q, const Real& x) {
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

/// Calls visit(k, P_k(x)) for k = 0..n_max, x = 1 - u near +1, by the recurrence for the
/// normalised R_k = P_k(x) / P_k(1) (P_k(1) = pi_k = (p+1)_k / k!, R_k(1) = 1) in Reinsch's
/// difference form. With P_{k+1} = (A_k x + B_k) P_k - C_k P_{k-1} one gets
///   R_{k+1} = a_k R_k - b_k R_{k-1},  a_k = (A_k x + B_k)(k+1)/(k+1+p),  b_k = C_k (k+1) k / ((k+1+p)(k+p)),
/// and a_k - b_k = 1 at x = 1, so D_{k+1} = R_{k+1} - R_k satisfies
///   D_{k+1} = b_k D_k - A_k u (k+1)/(k+1+p) R_k,   D_1 = -(p+q+2) u / (2 (p+1)).
/// Near x = 1 the characteristic roots of the recurrence coalesce and rounding errors of the
/// plain form grow linearly, O(n^2 eps) in all; here each step commits errors relative to the
/// small D_k (the analogue of the Goertzel-Reinsch modification of Chebyshev sums). The
/// normalisation by pi_k removes the cancellation of the unnormalised form when p is near -1
/// (P_k(1) = (p+1)_k/k! is then 1e-3 of the intermediate terms).
/// Step k >= 1 of that difference form: D_{k+1} = b D_k - a u R_k with
///   b = C_k (k+1) k / ((k+1+p)(k+p)),  a = A_k (k+1)/(k+1+p);
/// shared by jacobi_p_visit_near_one and jacobi_series (which stores them for many x).
template <class Real>
struct difference_form_step {
  Real a, b;
};

template <class Real>
difference_form_step<Real> difference_form_coefficients(std::size_t k, const Real& p, const Real& q) {
  const auto r = jacobi_recurrence_coefficients(k, p, q);
  const Real K = Real(k);
  return {r.A * (K + 1) / (K + 1 + p), r.C * (K + 1) * K / ((K + 1 + p) * (K + p))};
}

template <class Real, class Visit>
void jacobi_p_visit_near_one(std::size_t n_max, const Real& p, const Real& q, const Real& u, Visit&& visit) {
  Real R = 1, pi_k = 1;
  visit(std::size_t(0), Real(1));
  if (n_max == 0) return;
  Real D = -(p + q + 2) * u / (2 * (p + 1));
  R += D;
  pi_k = p + 1;
  visit(std::size_t(1), Real(pi_k * R));
  for (std::size_t k = 1; k < n_max; ++k) {
    const auto step = difference_form_coefficients(k, p, q);
    D = step.b * D - step.a * u * R;
    R += D;
    pi_k *= (Real(k) + 1 + p) / (Real(k) + 1);
    visit(k + 1, Real(pi_k * R));
  }
}

/// P_n^(p,q)(1 - u) by jacobi_p_visit_near_one.
template <class Real>
Real jacobi_p_recurrence_near_one(std::size_t n, const Real& p, const Real& q, const Real& u) {
  Real value = 1;
  jacobi_p_visit_near_one(n, p, q, u, [&](std::size_t k, const Real& v) {
    if (k == n) value = v;
  });
  return value;
}

}  // namespace detail

/// P_n^(p,q)(x), p, q > -1, any finite x. For x in [-1, 1] with n^2 (1 -+ x)/2 <= 1 (the
/// boundary layer of width O(1/n^2) at an end) the endpoint hypergeometric series is used, at
/// the end -1 through P_n^(p,q)(x) = (-1)^n P_n^(q,p)(-x); elsewhere the forward recurrence.
template <class Real>
Real jacobi_p(std::size_t n, const Real& p, const Real& q, const Real& x) {
  using std::isfinite;
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_p", p, q);
  if (!isfinite(x)) detail::throw_bad_parameter("rhabel::quadrature::jacobi_p", "x", x, "finite");
  if (n >= 2 && x >= 0 && x <= 1) {
    const Real u = (1 - x) / 2;  // exact for x >= 1/2 (Sterbenz)
    if (Real(n) * Real(n) * u <= 1) return detail::jacobi_p_endpoint_series(n, p, q, u);
  }
  if (n >= 2 && x < 0 && x >= -1) {
    const Real u = (1 + x) / 2;
    if (Real(n) * Real(n) * u <= 1) {
      const Real value = detail::jacobi_p_endpoint_series(n, q, p, u);
      return n % 2 == 0 ? value : Real(-value);
    }
  }
  // |x| >= 1/2: the difference form near the nearer end (angle <= 60 degrees from it).
  if (x >= Real(0.5) && x <= 1) return detail::jacobi_p_recurrence_near_one(n, p, q, Real(1 - x));
  if (x <= Real(-0.5) && x >= -1) {
    const Real value = detail::jacobi_p_recurrence_near_one(n, q, p, Real(1 + x));
    return n % 2 == 0 ? value : Real(-value);
  }
  return detail::jacobi_p_recurrence(n, p, q, x);
}

/// Values P_0(x), ..., P_n_max(x) in one pass (n_max + 1 entries): the forward recurrence,
/// in the difference form near the nearer end for |x| >= 1/2 (as jacobi_p, without the
/// endpoint series).
template <class Real>
std::vector<Real> jacobi_p_all(std::size_t n_max, const Real& p, const Real& q, const Real& x) {
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_p_all", p, q);
  std::vector<Real> values(n_max + 1);
  if (x >= Real(0.5) && x <= 1) {
    detail::jacobi_p_visit_near_one(n_max, p, q, Real(1 - x), [&](std::size_t k, const Real& v) { values[k] = v; });
    return values;
  }
  if (x <= Real(-0.5) && x >= -1) {
    detail::jacobi_p_visit_near_one(n_max, q, p, Real(1 + x),
                                    [&](std::size_t k, const Real& v) { values[k] = k % 2 == 0 ? v : Real(-v); });
    return values;
  }
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
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_p_derivative", p, q);
  if (n == 0) return Real(0);
  return (Real(n) + p + q + 1) / 2 * jacobi_p(n - 1, p + 1, q + 1, x);
}

/// log h_n, h_n = int_{-1}^{1} (1-x)^p (1+x)^q P_n^(p,q)(x)^2 dx  (DLMF 18.3, table 18.3.1).
template <class Real>
Real log_jacobi_norm_squared(std::size_t n, const Real& p, const Real& q) {
  using boost::math::lgamma;
  using std::log;
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_norm_squared", p, q);
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

/// sum_{k=0}^{K-1} c[k] P_k^(p,q)(x): Clenshaw's backward recurrence for |x| < 1/2; for
/// |x| >= 1/2 the forward difference-form recurrence summed term by term (Clenshaw inherits the
/// plain recurrence's cancellation near the ends: 2.5e-11 relative error at x = -0.9999 for
/// p = q = -0.999, K = 7, which the difference form avoids).
template <class Real>
Real jacobi_clenshaw(const std::vector<Real>& c, const Real& p, const Real& q, const Real& x) {
  using std::isfinite;
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_clenshaw", p, q);
  if (!isfinite(x)) detail::throw_bad_parameter("rhabel::quadrature::jacobi_clenshaw", "x", x, "finite");
  if (c.empty()) return Real(0);
  if ((x >= Real(0.5) && x <= 1) || (x <= Real(-0.5) && x >= -1)) {
    const bool upper = x > 0;
    Real sum = 0;
    detail::jacobi_p_visit_near_one(c.size() - 1, upper ? p : q, upper ? q : p, Real(upper ? 1 - x : 1 + x),
                                    [&](std::size_t k, const Real& v) {
                                      sum += (upper || k % 2 == 0) ? Real(c[k] * v) : Real(-c[k] * v);
                                    });
    return detail::finite_sum("rhabel::quadrature::jacobi_clenshaw", x, sum);
  }
  Real b1 = 0, b2 = 0;  // b_{k+1}, b_{k+2}
  for (std::size_t k = c.size(); k-- > 0;) {
    const auto r = detail::jacobi_recurrence_coefficients(k, p, q);
    const Real C_next = c.size() > k + 1 ? detail::jacobi_recurrence_coefficients(k + 1, p, q).C : Real(0);
    const Real b0 = c[k] + (r.A * x + r.B) * b1 - C_next * b2;
    b2 = b1;
    b1 = b0;
  }
  return detail::finite_sum("rhabel::quadrature::jacobi_clenshaw", x, b1);
}

/// (1 - x)^p (1 + x)^q from the complements one_minus_x = 1 - x, one_plus_x = 1 + x, both in
/// [0, 2] (std::domain_error naming the complement otherwise, NaN included).
template <class Real>
Real jacobi_weight(const Real& p, const Real& q, const Real& one_minus_x, const Real& one_plus_x) {
  using std::pow;
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_weight", p, q);
  // Complements outside [0, 2] (NaN included) are refused, as the message says.
  detail::check_complement("rhabel::quadrature::jacobi_weight", "one_minus_x", one_minus_x);
  detail::check_complement("rhabel::quadrature::jacobi_weight", "one_plus_x", one_plus_x);
  Real value = 1;
  if (p != 0) value *= pow(one_minus_x, p);
  if (q != 0) value *= pow(one_plus_x, q);
  return value;
}

/// Two-term connection P_n^(p,q) = first * P_n^(p+1,q) + second * P_{n-1}^(p+1,q)
/// (DLMF 18.9.5): first = (n+p+q+1)/(2n+p+q+1), second = -(n+q)/(2n+p+q+1); n = 0: (1, 0).
template <class Real>
std::pair<Real, Real> jacobi_connection_raise_p(std::size_t n, const Real& p, const Real& q) {
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_connection_raise_p", p, q);
  if (n == 0) return {Real(1), Real(0)};
  const Real m = Real(n), s = 2 * m + p + q + 1;
  return {(m + p + q + 1) / s, -(m + q) / s};
}

/// P_n^(p,q) = first * P_n^(p,q+1) + second * P_{n-1}^(p,q+1)  (DLMF 18.9.5 reflected):
/// first = (n+p+q+1)/(2n+p+q+1), second = +(n+p)/(2n+p+q+1); n = 0: (1, 0).
template <class Real>
std::pair<Real, Real> jacobi_connection_raise_q(std::size_t n, const Real& p, const Real& q) {
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_connection_raise_q", p, q);
  if (n == 0) return {Real(1), Real(0)};
  const Real m = Real(n), s = 2 * m + p + q + 1;
  return {(m + p + q + 1) / s, (m + p) / s};
}

/// Lowering: (1 - x) P_n^(p+1,q) = first * P_n^(p,q) + second * P_{n+1}^(p,q)  (DLMF 18.9.6):
/// first = 2(n+p+1)/(2n+p+q+2), second = -2(n+1)/(2n+p+q+2).
template <class Real>
std::pair<Real, Real> jacobi_lowering_one_minus_x(std::size_t n, const Real& p, const Real& q) {
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_lowering_one_minus_x", p, q);
  const Real m = Real(n), s = 2 * m + p + q + 2;
  return {2 * (m + p + 1) / s, -2 * (m + 1) / s};
}

/// Lowering: (1 + x) P_n^(p,q+1) = first * P_n^(p,q) + second * P_{n+1}^(p,q):
/// first = 2(n+q+1)/(2n+p+q+2), second = +2(n+1)/(2n+p+q+2).
template <class Real>
std::pair<Real, Real> jacobi_lowering_one_plus_x(std::size_t n, const Real& p, const Real& q) {
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_lowering_one_plus_x", p, q);
  const Real m = Real(n), s = 2 * m + p + q + 2;
  return {2 * (m + q + 1) / s, 2 * (m + 1) / s};
}

/// Coefficients in P_k^(p+1,q) of sum_n c[n] P_n^(p,q) (same length).
template <class Real>
std::vector<Real> jacobi_series_raise_p(const std::vector<Real>& c, const Real& p, const Real& q) {
  std::vector<Real> d(c.size(), Real(0));
  for (std::size_t n = 0; n < c.size(); ++n) {
    const auto [first, second] = jacobi_connection_raise_p(n, p, q);
    d[n] += first * c[n];
    if (n > 0) d[n - 1] += second * c[n];
  }
  return d;
}

/// Coefficients in P_k^(p,q+1) of sum_n c[n] P_n^(p,q) (same length).
template <class Real>
std::vector<Real> jacobi_series_raise_q(const std::vector<Real>& c, const Real& p, const Real& q) {
  std::vector<Real> d(c.size(), Real(0));
  for (std::size_t n = 0; n < c.size(); ++n) {
    const auto [first, second] = jacobi_connection_raise_q(n, p, q);
    d[n] += first * c[n];
    if (n > 0) d[n - 1] += second * c[n];
  }
  return d;
}

/// Coefficients in P_k^(p,q) of (1 - x) sum_n c[n] P_n^(p+1,q) (length + 1).
template <class Real>
std::vector<Real> jacobi_series_times_one_minus_x(const std::vector<Real>& c, const Real& p, const Real& q) {
  std::vector<Real> d(c.size() + 1, Real(0));
  for (std::size_t n = 0; n < c.size(); ++n) {
    const auto [first, second] = jacobi_lowering_one_minus_x(n, p, q);
    d[n] += first * c[n];
    d[n + 1] += second * c[n];
  }
  return d;
}

/// Coefficients in P_k^(p,q) of (1 + x) sum_n c[n] P_n^(p,q+1) (length + 1).
template <class Real>
std::vector<Real> jacobi_series_times_one_plus_x(const std::vector<Real>& c, const Real& p, const Real& q) {
  std::vector<Real> d(c.size() + 1, Real(0));
  for (std::size_t n = 0; n < c.size(); ++n) {
    const auto [first, second] = jacobi_lowering_one_plus_x(n, p, q);
    d[n] += first * c[n];
    d[n + 1] += second * c[n];
  }
  return d;
}

/// int_{-1}^{x0} (1-x)^p (1+x)^q P_m^(p,q)(x) dx from the complements 1 - x0, 1 + x0 (see header).
template <class Real>
Real jacobi_integral_below(std::size_t m, const Real& p, const Real& q, const Real& one_minus_x0,
                           const Real& one_plus_x0) {
  using std::ldexp;
  using std::pow;
  constexpr const char* name = "jacobi_integral_below";
  detail::check_jacobi_exponents(name, p, q);
  detail::check_complement(name, "one_minus_x0", one_minus_x0);
  detail::check_complement(name, "one_plus_x0", one_plus_x0);
  if (m == 0) {
    // 2^(p+q+1) B_u(q+1, p+1), u = (1 + x0)/2; for u > 1/2 the complement form
    // B_u(a, b) = B(a, b) - B_{1-u}(b, a) = betac(b, a, 1 - u) keeps full accuracy near x0 = 1.
    const Real u = one_plus_x0 / 2, v = one_minus_x0 / 2;
    const Real incomplete = u <= v ? boost::math::beta(q + 1, p + 1, u) : boost::math::betac(p + 1, q + 1, v);
    return pow(Real(2), p + q + 1) * incomplete;
  }
  const Real x0 = one_plus_x0 <= one_minus_x0 ? one_plus_x0 - 1 : 1 - one_minus_x0;
  return -jacobi_weight(p + 1, q + 1, one_minus_x0, one_plus_x0) * jacobi_p(m - 1, p + 1, q + 1, x0) /
         (2 * Real(m));
}

/// int_{-1}^{x0} (1-x)^p (1+x)^q P_m^(p,q)(x) dx, -1 <= x0 <= 1.
template <class Real>
Real jacobi_integral_below(std::size_t m, const Real& p, const Real& q, const Real& x0) {
  using std::isfinite;
  if (!isfinite(x0) || x0 < -1 || x0 > 1) detail::throw_bad_parameter("rhabel::quadrature::jacobi_integral_below", "x0", x0, "[-1, 1]");
  return jacobi_integral_below(m, p, q, Real(1 - x0), Real(1 + x0));
}

/// Jacobi coefficients c_0..c_{n-1} (family (p,q)) of the indicator 1_{x < x0}:
/// c_m = jacobi_integral_below(m, p, q, x0) / h_m. Overload with complements for x0 near +-1.
template <class Real>
std::vector<Real> jacobi_step_coefficients(std::size_t n, const Real& p, const Real& q, const Real& one_minus_x0,
                                           const Real& one_plus_x0) {
  // Validated here so that a bad argument is reported under this function's own name.
  constexpr const char* name = "jacobi_step_coefficients";
  detail::check_jacobi_exponents(name, p, q);
  detail::check_complement(name, "one_minus_x0", one_minus_x0);
  detail::check_complement(name, "one_plus_x0", one_plus_x0);
  std::vector<Real> c(n);
  for (std::size_t m = 0; m < n; ++m)
    c[m] = jacobi_integral_below(m, p, q, one_minus_x0, one_plus_x0) / jacobi_norm_squared(m, p, q);
  return c;
}

template <class Real>
std::vector<Real> jacobi_step_coefficients(std::size_t n, const Real& p, const Real& q, const Real& x0) {
  using std::isfinite;
  if (!isfinite(x0) || x0 < -1 || x0 > 1) detail::throw_bad_parameter("rhabel::quadrature::jacobi_step_coefficients", "x0", x0, "[-1, 1]");
  return jacobi_step_coefficients(n, p, q, Real(1 - x0), Real(1 + x0));
}

/// int_{-1}^{x0} (x0 - x) (1-x)^p (1+x)^q P_m^(p,q)(x) dx (the moments of the kink (x0 - x)_+):
///   m >= 2: w_(p+2,q+2)(x0) P_{m-2}^(p+2,q+2)(x0) / (4 m (m-1))
///   m = 1 : -(1/2) int_{-1}^{x0} w_(p+1,q+1)
///   m = 0 : (1 + x0) int_{-1}^{x0} w_(p,q) - int_{-1}^{x0} w_(p,q+1)
/// (integrate int_{-1}^{y} w P_m = -(1/(2m)) w_(p+1,q+1)(y) P_{m-1}^(p+1,q+1)(y) once more in y).
template <class Real>
Real jacobi_ramp_moment(std::size_t m, const Real& p, const Real& q, const Real& one_minus_x0, const Real& one_plus_x0) {
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_ramp_moment", p, q);
  if (m == 0)
    return one_plus_x0 * jacobi_integral_below(0, p, q, one_minus_x0, one_plus_x0) -
           jacobi_integral_below(0, p, q + 1, one_minus_x0, one_plus_x0);
  if (m == 1) return -jacobi_integral_below(0, p + 1, q + 1, one_minus_x0, one_plus_x0) / 2;
  const Real x0 = one_plus_x0 <= one_minus_x0 ? one_plus_x0 - 1 : 1 - one_minus_x0;
  return jacobi_weight(p + 2, q + 2, one_minus_x0, one_plus_x0) * jacobi_p(m - 2, p + 2, q + 2, x0) /
         (4 * Real(m) * Real(m - 1));
}

/// Jacobi coefficients c_0..c_{n-1} of the kink (x0 - x)_+ = max(x0 - x, 0).
/// |x - x0| = (x - x0) + 2 (x0 - x)_+ gives the absolute-value kink.
template <class Real>
std::vector<Real> jacobi_ramp_coefficients(std::size_t n, const Real& p, const Real& q, const Real& one_minus_x0,
                                           const Real& one_plus_x0) {
  // Validated here so that a bad argument is reported under this function's own name.
  constexpr const char* name = "jacobi_ramp_coefficients";
  detail::check_jacobi_exponents(name, p, q);
  detail::check_complement(name, "one_minus_x0", one_minus_x0);
  detail::check_complement(name, "one_plus_x0", one_plus_x0);
  std::vector<Real> c(n);
  for (std::size_t m = 0; m < n; ++m)
    c[m] = jacobi_ramp_moment(m, p, q, one_minus_x0, one_plus_x0) / jacobi_norm_squared(m, p, q);
  return c;
}

template <class Real>
std::vector<Real> jacobi_ramp_coefficients(std::size_t n, const Real& p, const Real& q, const Real& x0) {
  using std::isfinite;
  if (!isfinite(x0) || x0 < -1 || x0 > 1) detail::throw_bad_parameter("rhabel::quadrature::jacobi_ramp_coefficients", "x0", x0, "[-1, 1]");
  return jacobi_ramp_coefficients(n, p, q, Real(1 - x0), Real(1 + x0));
}


/// sum_{k=0}^{K-1} c[k] P_k^(p,q)(x) for many x: jacobi_clenshaw with the recurrence coefficients
/// precomputed (see the header). Holds c, p, q, the three-term coefficients A_k, B_k, C_k and, for
/// each end, the difference-form coefficients of jacobi_p_visit_near_one
///   b_k = C_k (k+1) k / ((k+1+p)(k+p)),  a_k = A_k (k+1)/(k+1+p),  pi_k = (p+1)_k / k!
/// (with p and q exchanged for the end -1, where P_k^(p,q)(x) = (-1)^k P_k^(q,p)(-x)).
template <class Real>
class jacobi_series {
 public:
  jacobi_series() = default;
  jacobi_series(std::vector<Real> c, const Real& p, const Real& q) : c_(std::move(c)), p_(p), q_(q) {
    detail::check_jacobi_exponents("rhabel::quadrature::jacobi_series", p, q);
    const std::size_t K = c_.size();
    A_.resize(K);
    B_.resize(K);
    C_.resize(K + 1, Real(0));  // C_[K] = 0 closes Clenshaw's recurrence
    for (std::size_t k = 0; k < K; ++k) {
      const auto r = detail::jacobi_recurrence_coefficients(k, p, q);
      A_[k] = r.A;
      B_[k] = r.B;
      C_[k] = r.C;
    }
    make_end(upper_, p, q);
    make_end(lower_, q, p);
  }

  const std::vector<Real>& coefficients() const { return c_; }
  const Real& p() const { return p_; }
  const Real& q() const { return q_; }
  std::size_t size() const { return c_.size(); }

  /// The sum at x (any finite x, else std::domain_error; the difference form is used for 1/2 <= |x| <= 1;
  /// a sum beyond the range of Real, possible for |x| > 1: std::overflow_error, never inf or NaN).
  Real operator()(const Real& x) const {
    using std::isfinite;
    if (!isfinite(x)) detail::throw_bad_parameter("rhabel::quadrature::jacobi_series", "x", x, "finite");
    if (c_.empty()) return Real(0);
    if (x >= Real(0.5) && x <= 1) return detail::finite_sum("rhabel::quadrature::jacobi_series", x, near_end(upper_, p_, q_, Real(1 - x), false));
    if (x <= Real(-0.5) && x >= -1) return detail::finite_sum("rhabel::quadrature::jacobi_series", x, near_end(lower_, q_, p_, Real(1 + x), true));
    return detail::finite_sum("rhabel::quadrature::jacobi_series", x, clenshaw(x));
  }

  /// The sum at x given the complements one_minus_x = 1 - x and one_plus_x = 1 + x (both in
  /// [0, 2]); near an end the small complement is used as it is.
  Real operator()(const Real& one_minus_x, const Real& one_plus_x) const {
    detail::check_complement("rhabel::quadrature::jacobi_series", "one_minus_x", one_minus_x);
    detail::check_complement("rhabel::quadrature::jacobi_series", "one_plus_x", one_plus_x);
    if (c_.empty()) return Real(0);
    const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
    if (one_minus_x <= Real(0.5)) return detail::finite_sum("rhabel::quadrature::jacobi_series", x, near_end(upper_, p_, q_, one_minus_x, false));
    if (one_plus_x <= Real(0.5)) return detail::finite_sum("rhabel::quadrature::jacobi_series", x, near_end(lower_, q_, p_, one_plus_x, true));
    return detail::finite_sum("rhabel::quadrature::jacobi_series", x, clenshaw(x));
  }

  /// The sum at the n points x[0], ..., x[n-1] (each finite, else std::domain_error before anything
  /// is written; a sum that overflows: std::overflow_error after, as operator() would throw it),
  /// into out[0], ..., out[n-1]: the values of operator()(x[i]), bit for bit (the
  /// same operations in the same order per point). The points are sorted by branch
  /// (difference form at each end, Clenshaw in the middle) and summed `lanes` at a time with the
  /// recurrences interleaved: one sum is a chain of dependent multiply-adds that leaves the
  /// floating-point units idle most of the time, several independent chains keep them busy
  /// (measured 164 -> 56 ns a point at K = 84: bench/jacobi_series.cpp). For the many points of
  /// a sampled field.
  void evaluate(const Real* x, Real* out, std::size_t n) const {
    using std::isfinite;
    for (std::size_t i = 0; i < n; ++i)
      if (!isfinite(x[i])) detail::throw_bad_parameter("rhabel::quadrature::jacobi_series::evaluate", "x", x[i], "finite");
    if (c_.empty()) {
      std::fill(out, out + n, Real(0));
      return;
    }
    // Indices per branch, as operator()(x) chooses it.
    std::vector<std::size_t> upper, lower, middle;
    for (std::size_t i = 0; i < n; ++i) (x[i] >= Real(0.5) && x[i] <= 1 ? upper : x[i] <= Real(-0.5) && x[i] >= -1 ? lower : middle).push_back(i);
    Real arg[lanes], value[lanes];
    auto run = [&](const std::vector<std::size_t>& idx, auto&& argument, auto&& sum_lanes, auto&& sum_one) {
      std::size_t j = 0;
      for (; j + lanes <= idx.size(); j += lanes) {
        for (std::size_t l = 0; l < lanes; ++l) arg[l] = argument(x[idx[j + l]]);
        sum_lanes(arg, value);
        for (std::size_t l = 0; l < lanes; ++l) out[idx[j + l]] = value[l];
      }
      for (; j < idx.size(); ++j) out[idx[j]] = sum_one(argument(x[idx[j]]));
    };
    run(upper, [](const Real& xi) { return Real(1 - xi); },
        [&](const Real* u, Real* v) { near_end_lanes(upper_, p_, q_, u, false, v); },
        [&](const Real& u) { return near_end(upper_, p_, q_, u, false); });
    run(lower, [](const Real& xi) { return Real(1 + xi); },
        [&](const Real* u, Real* v) { near_end_lanes(lower_, q_, p_, u, true, v); },
        [&](const Real& u) { return near_end(lower_, q_, p_, u, true); });
    run(middle, [](const Real& xi) { return xi; }, [&](const Real* xs, Real* v) { clenshaw_lanes(xs, v); },
        [&](const Real& xi) { return clenshaw(xi); });
    for (std::size_t i = 0; i < n; ++i) detail::finite_sum("rhabel::quadrature::jacobi_series::evaluate", x[i], out[i]);
  }

 private:
  static constexpr std::size_t lanes = 4;

  struct end_coefficients {
    std::vector<Real> a, b, pi;  // index k: a_k, b_k (k >= 1), pi_k (k >= 0)
  };

  void make_end(end_coefficients& e, const Real& p, const Real& q) const {
    const std::size_t K = c_.size();
    e.a.assign(K, Real(0));
    e.b.assign(K, Real(0));
    e.pi.assign(K, Real(1));
    if (K >= 2) e.pi[1] = p + 1;
    for (std::size_t k = 1; k + 1 < K; ++k) {
      const auto step = detail::difference_form_coefficients(k, p, q);
      e.a[k] = step.a;
      e.b[k] = step.b;
      e.pi[k + 1] = e.pi[k] * ((Real(k) + 1 + p) / (Real(k) + 1));  // the same products as jacobi_p_visit_near_one
    }
  }

  // jacobi_p_visit_near_one summed against c (u = distance from the end, exponents (p, q) of that end).
  Real near_end(const end_coefficients& e, const Real& p, const Real& q, const Real& u, bool alternate) const {
    const std::size_t K = c_.size();
    Real R = 1, sum = c_[0];
    if (K == 1) return sum;
    Real D = -(p + q + 2) * u / (2 * (p + 1));
    R += D;
    sum += alternate ? Real(-c_[1] * Real(e.pi[1] * R)) : Real(c_[1] * Real(e.pi[1] * R));
    for (std::size_t k = 1; k + 1 < K; ++k) {
      D = e.b[k] * D - e.a[k] * u * R;
      R += D;
      const Real v = e.pi[k + 1] * R;
      sum += (alternate && (k + 1) % 2 == 1) ? Real(-c_[k + 1] * v) : Real(c_[k + 1] * v);
    }
    return sum;
  }

  // near_end at `lanes` points at once: the same operations per lane.
  void near_end_lanes(const end_coefficients& e, const Real& p, const Real& q, const Real* u, bool alternate, Real* out) const {
    const std::size_t K = c_.size();
    Real R[lanes], D[lanes], sum[lanes];
    for (std::size_t l = 0; l < lanes; ++l) R[l] = 1, sum[l] = c_[0];
    if (K > 1) {
      for (std::size_t l = 0; l < lanes; ++l) {
        D[l] = -(p + q + 2) * u[l] / (2 * (p + 1));
        R[l] += D[l];
        sum[l] += alternate ? Real(-c_[1] * Real(e.pi[1] * R[l])) : Real(c_[1] * Real(e.pi[1] * R[l]));
      }
      for (std::size_t k = 1; k + 1 < K; ++k) {
        const bool negate = alternate && (k + 1) % 2 == 1;
        for (std::size_t l = 0; l < lanes; ++l) {
          D[l] = e.b[k] * D[l] - e.a[k] * u[l] * R[l];
          R[l] += D[l];
          const Real v = e.pi[k + 1] * R[l];
          sum[l] += negate ? Real(-c_[k + 1] * v) : Real(c_[k + 1] * v);
        }
      }
    }
    for (std::size_t l = 0; l < lanes; ++l) out[l] = sum[l];
  }

  // clenshaw at `lanes` points at once: the same operations per lane.
  void clenshaw_lanes(const Real* x, Real* out) const {
    Real b1[lanes], b2[lanes];
    for (std::size_t l = 0; l < lanes; ++l) b1[l] = 0, b2[l] = 0;
    for (std::size_t k = c_.size(); k-- > 0;) {
      for (std::size_t l = 0; l < lanes; ++l) {
        const Real b0 = c_[k] + (A_[k] * x[l] + B_[k]) * b1[l] - C_[k + 1] * b2[l];
        b2[l] = b1[l];
        b1[l] = b0;
      }
    }
    for (std::size_t l = 0; l < lanes; ++l) out[l] = b1[l];
  }

  Real clenshaw(const Real& x) const {
    Real b1 = 0, b2 = 0;  // b_{k+1}, b_{k+2}
    for (std::size_t k = c_.size(); k-- > 0;) {
      const Real b0 = c_[k] + (A_[k] * x + B_[k]) * b1 - C_[k + 1] * b2;
      b2 = b1;
      b1 = b0;
    }
    return b1;
  }

  std::vector<Real> c_;
  Real p_ = 0, q_ = 0;
  std::vector<Real> A_, B_, C_;
  end_coefficients upper_, lower_;
};

}  // namespace rhabel::quadrature
