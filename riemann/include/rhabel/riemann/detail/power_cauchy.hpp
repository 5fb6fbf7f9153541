// rhabel/riemann/detail/power_cauchy.hpp  (private: no stability promise)
//
// The one special function the Riemann-Hilbert route needs: the Cauchy integral of a single
// power on [0, 1],
//
//     K(q, rho) = int_0^1 v^q / (v - rho) dv ,        -1 < q < 1 ,
//
// for complex rho off [0, 1] (an analytic function of rho in C \ [0, 1]) and, for real
// rho in (0, 1), its principal value (the mean of the two boundary values); for real rho > 1
// and rho < 0 it is an ordinary integral. K(q, 1) is infinite (logarithmic).
//
// Three representations, each used where it converges geometrically with ratio <= 1/2 or
// better, so that the cost is O(digits) and nothing depends on q being away from 0:
//  (A) |rho| <= 1/2 (expansion at rho = 0, from int_0^inf s^q/(s+e) ds = -pi e^q / sin(pi q)
//      for -1 < q < 0, continued analytically in q):
//          K = [1 - (pi q / sin(pi q)) (-rho)^q] / q  -  sum_{k>=1} rho^k / (k - q).
//      The bracket is evaluated in the form  -(expm1(q L)/q + (T/q)(1 + expm1(q L))),
//      L = log(-rho), T = pi q / sin(pi q) - 1 = (x - sin x)/sin x (x = pi q), both uniform
//      through q = 0 (where K = -log(-rho) - sum rho^k / k, the log case).
//      For real rho in (0, 1/2] the principal value replaces (-rho)^q by rho^q cos(pi q) and
//      L by log(rho):  bracket/q = -expm1(q log rho)/q + rho^q U/q,  U = 1 - pi q cot(pi q),
//      used for |q| < 1/4; for |q| >= 1/4 the equal direct form 1/q - pi cot(pi q) rho^q with
//      cot from cos_pi/sin_pi (exactly 0 at q = -1/2: no cancellation of two rho^q-sized terms).
//  (B) |rho| >= 2 (expansion at infinity):  K = - sum_{k>=0} rho^(-k-1) / (q + k + 1).
//  (C) otherwise (1/2 < |rho| < 2):
//          K = int_0^{1/4} v^q/(v - rho) dv + int_{1/4}^1 (v^q - rho^q)/(v - rho) dv
//              + rho^q [log(1 - rho) - log(1/4 - rho)]
//      (any fixed determination of rho^q works: it cancels; principal logs are correct since
//      their cuts on rho > 1 cancel). The first integral has its pole at distance >= 1/4 from
//      [0, 1/4] (Gauss-Jacobi with weight v^q, Bernstein ratio >= 3 + sqrt 8); the second has
//      an entire-in-rho, analytic-in-v integrand whose only singularity is v = 0 (Gauss-Legendre
//      on [1/4, 1], ratio 3); both rules are rhabel::quadrature::gauss_jacobi mapped to their
//      intervals. The divided difference (v^q - rho^q)/(v - rho) is taken from the binomial
//      series of ((1 + d)^q - 1)/d, d = (v - rho)/rho, when |d| < 1/8, so there is no
//      cancellation near v = rho. For real rho in (1/4, 1) the PV takes log|.|.
//
// Accuracy: a few ulps relative to max(|K|, 1) for q in (-1, 1) away from +-1 (the series
// terms 1/(k - q) and 1/(q + k + 1) amplify rounding by 1/(1 - |q|)); near rho = 0 the PV
// ~ rho^q is computed as a difference of terms of that size, so the error is relative to
// max(|K|, rho^q). tests/riemann/test_cauchy_integral.cpp checks 8 eps against the elementary
// closed forms for q = 0, -1/2, 1/2 (real and complex rho, rho within 1e-6 of 1) and the
// continuity through q = 0 (this file was also checked against 30-digit mpmath while written).
#pragma once

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"  // detail::throw_bad_parameter

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/cos_pi.hpp>
#include <boost/math/special_functions/sin_pi.hpp>

#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

namespace rhabel::riemann::detail {

template <class Real>
using complex_t = std::complex<Real>;

/// Number of significant decimal digits the numerics aim at.
template <class Real>
int target_digits() {
  return std::numeric_limits<Real>::digits10 + 2;
}

/// Gauss nodes needed for an integrand analytic inside the Bernstein ellipse of ratio rho_b.
template <class Real>
std::size_t nodes_for_ratio(double rho_b) {
  const double n = target_digits<Real>() * std::log(10.0) / (2.0 * std::log(rho_b));
  return static_cast<std::size_t>(n) + 4;
}

// Elementary complex functions written with Real's own functions (found by ADL), so that
// std::complex<multiprecision> works without relying on the library's generic complex code.
template <class Real>
Real modulus(const complex_t<Real>& z) {
  using std::abs;
  using std::sqrt;
  const Real re = abs(z.real()), im = abs(z.imag());
  const Real big = re > im ? re : im;
  if (big == 0) return Real(0);
  const Real r = re / big, i = im / big;
  return big * sqrt(r * r + i * i);
}
template <class Real>
Real modulus(const Real& x) {
  using std::abs;
  return abs(x);
}

/// Principal logarithm (argument in (-pi, pi]).
template <class Real>
complex_t<Real> log_principal(const complex_t<Real>& z) {
  using std::atan2;
  using std::log;
  return {log(modulus(z)), atan2(z.imag(), z.real())};
}

template <class Real>
complex_t<Real> exp_complex(const complex_t<Real>& z) {
  using std::cos;
  using std::exp;
  using std::sin;
  const Real r = exp(z.real());
  return {r * cos(z.imag()), r * sin(z.imag())};
}

/// Principal power z^q = exp(q Log z); 0^q = 0 for q > 0.
template <class Real>
complex_t<Real> pow_principal(const complex_t<Real>& z, const Real& q) {
  if (z.real() == 0 && z.imag() == 0) return complex_t<Real>(0);
  return exp_complex<Real>(q * log_principal(z));
}

template <class T>
struct real_of {
  using type = T;
};
template <class Real>
struct real_of<std::complex<Real>> {
  using type = Real;
};

/// (e^(q L) - 1)/q, uniform through q = 0 (value L); L real or complex.
template <class T, class Real>
T expm1_over(const Real& q, const T& L) {
  const T z = q * L;
  if (modulus(z) < Real(1) / 2) {
    // sum_{k>=1} q^(k-1) L^k / k!  =  L sum_{k>=0} z^k/(k+1)!
    T term = L, sum = L;
    for (int k = 1; k < 200; ++k) {
      term *= z / Real(k + 1);
      sum += term;
      if (modulus(term) <= std::numeric_limits<Real>::epsilon() * modulus(sum) / 4) break;
    }
    return sum;
  }
  if constexpr (std::is_same_v<T, Real>) {
    using std::exp;
    return (exp(z) - 1) / q;
  } else {
    return (exp_complex<Real>(z) - Real(1)) / q;
  }
}

/// x - sin x, without cancellation for small x.
template <class Real>
Real x_minus_sin(const Real& x) {
  using std::abs;
  using std::sin;
  if (abs(x) >= Real(1) / 2) return x - sin(x);
  // sum_{k>=1} (-1)^(k+1) x^(2k+1)/(2k+1)!
  const Real x2 = x * x;
  Real term = x * x2 / 6, sum = term;
  for (int k = 2; k < 100; ++k) {
    term *= -x2 / Real((2 * k) * (2 * k + 1));
    sum += term;
    if (abs(term) <= std::numeric_limits<Real>::epsilon() * abs(sum) / 4) break;
  }
  return sum;
}

/// sin x - x cos x, without cancellation for small x.
template <class Real>
Real sin_minus_x_cos(const Real& x) {
  using std::abs;
  using std::cos;
  using std::sin;
  if (abs(x) >= Real(1) / 2) return sin(x) - x * cos(x);
  // sum_{k>=1} (-1)^(k+1) 2k x^(2k+1)/(2k+1)!
  const Real x2 = x * x;
  Real power_over_factorial = x * x2 / 6;  // x^(2k+1)/(2k+1)! at k = 1
  Real sum = 2 * power_over_factorial;
  for (int k = 2; k < 100; ++k) {
    power_over_factorial *= -x2 / Real((2 * k) * (2 * k + 1));
    const Real term = Real(2 * k) * power_over_factorial;
    sum += term;
    if (abs(term) <= std::numeric_limits<Real>::epsilon() * abs(sum) / 4) break;
  }
  return sum;
}

/// ((1 + d)^q - 1)/d = sum_{k>=1} binom(q, k) d^(k-1), for |d| <= 1/8.
template <class T, class Real>
T binomial_difference_series(const Real& q, const T& d) {
  T term = T(q), sum = term;  // binom(q,1)
  for (int k = 2; k < 400; ++k) {
    term *= d * (q - Real(k - 1)) / Real(k);
    sum += term;
    if (modulus(term) <= std::numeric_limits<Real>::epsilon() * modulus(sum) / 8) break;
  }
  return sum;
}

/// Single-power Cauchy integral K(q, rho) = int_0^1 v^q/(v - rho) dv (see file header).
/// Holds the two small Gauss rules of representation (C); construct once per exponent q.
template <class Real>
class power_cauchy {
 public:
  explicit power_cauchy(Real q) : q_(q) {
    if (!(q > -1) || !(q < 1)) quadrature::detail::throw_bad_parameter("rhabel::riemann::power_cauchy", "q", q, "(-1, 1)");
    near_rule_ = quadrature::gauss_jacobi<Real>(nodes_for_ratio<Real>(5.8), Real(0), q, Real(0), Real(1) / 4);
    far_rule_ = quadrature::gauss_jacobi<Real>(nodes_for_ratio<Real>(3.0), Real(0), Real(0), Real(1) / 4, Real(1));
    const Real pi = boost::math::constants::pi<Real>();
    const Real x = pi * q;
    using std::sin;
    // T/q = pi (x - sin x)/(x sin x) and U/q = pi (sin x - x cos x)/(x sin x), both -> 0 at q = 0.
    if (q == 0) {
      t_over_q_ = 0;
      u_over_q_ = 0;
    } else {
      t_over_q_ = pi * x_minus_sin(x) / (x * sin(x));
      u_over_q_ = pi * sin_minus_x_cos(x) / (x * sin(x));
    }
    using std::abs;
    direct_pv_ = abs(q) >= Real(1) / 4;  // 1/q <= 4: no loss of uniformity through q = 0
    if (direct_pv_) pi_cot_ = pi * boost::math::cos_pi(q) / boost::math::sin_pi(q);
  }

  const Real& exponent() const { return q_; }

  /// K(q, rho) for complex rho not in [0, 1].
  complex_t<Real> operator()(const complex_t<Real>& rho) const { return evaluate<complex_t<Real>>(rho, Real(1) - rho); }
  /// The same with 1 - rho supplied by the caller (exactly, from a difference of end points:
  /// near rho = 1 forming 1 - rho from rho would lose all the digits of the logarithm).
  complex_t<Real> operator()(const complex_t<Real>& rho, const complex_t<Real>& one_minus_rho) const {
    return evaluate<complex_t<Real>>(rho, one_minus_rho);
  }

  /// K(q, rho) for real rho: principal value for 0 < rho < 1, ordinary integral otherwise.
  /// rho = 1 (and rho = 0 when q <= 0) is a singularity: returns +-infinity is avoided by
  /// the callers, which never ask for it.
  Real principal_value(const Real& rho) const { return evaluate<Real>(rho, 1 - rho); }
  /// The same with 1 - rho supplied exactly by the caller.
  Real principal_value(const Real& rho, const Real& one_minus_rho) const { return evaluate<Real>(rho, one_minus_rho); }

 private:
  template <class T>
  T evaluate(const T& rho, const T& one_minus_rho) const {
    using std::log;
    const Real r = modulus(rho);
    const Real eps = std::numeric_limits<Real>::epsilon();
    if (r <= Real(1) / 2) {
      // (A)
      T bracket;
      if constexpr (std::is_same_v<T, Real>) {
        if (rho > 0) {
          // PV on the cut: (-rho)^q -> rho^q cos(pi q)
          using std::pow;
          if (direct_pv_) {
            // = 1/q - pi cot(pi q) rho^q exactly; with cot from cos_pi/sin_pi the coefficient is
            // exactly 0 at q = -1/2 (beta = 0 in the Abel route), where the form below would
            // cancel two terms of size 2 rho^(-1/2) and leave noise eps rho^q.
            bracket = 1 / q_ - pi_cot_ * pow(rho, q_);
          } else {
            const Real L = log(rho);
            bracket = -expm1_over(q_, L) + pow(rho, q_) * u_over_q_;
          }
        } else {
          const Real L = log(-rho);
          const Real e = expm1_over(q_, L) * q_;  // expm1(q L)
          bracket = -(expm1_over(q_, L) + t_over_q_ * (1 + e));
        }
      } else {
        const T L = log_principal<Real>(-rho);
        const T em1q = expm1_over(q_, L);
        bracket = -(em1q + t_over_q_ * (Real(1) + q_ * em1q));
      }
      T power = rho, sum = T(0);
      for (int k = 1; k < 10000; ++k) {
        const T term = power / (Real(k) - q_);
        sum += term;
        if (modulus(term) <= eps * (modulus(sum) + modulus(bracket)) / 8) break;
        power *= rho;
      }
      return bracket - sum;
    }
    if (r >= 2) {
      // (B)
      const T inverse = T(1) / rho;
      T power = inverse, sum = T(0);
      for (int k = 0; k < 10000; ++k) {
        const T term = power / (q_ + Real(k + 1));
        sum += term;
        if (modulus(term) <= eps * modulus(sum) / 8) break;
        power *= inverse;
      }
      return -sum;
    }
    // (C)
    T rho_q;
    T logs;
    if constexpr (std::is_same_v<T, Real>) {
      using std::abs;
      using std::pow;
      // rho real, 1/2 < |rho| < 2. For rho < 0 use the real determination |rho|^q: any fixed
      // determination cancels between the two terms below.
      rho_q = pow(abs(rho), q_);
      logs = log(abs(one_minus_rho)) - log(abs(Real(1) / 4 - rho));
    } else {
      rho_q = pow_principal<Real>(rho, q_);
      logs = log_principal<Real>(one_minus_rho) - log_principal<Real>(Real(1) / 4 - rho);
    }
    T near = T(0);
    for (std::size_t i = 0; i < near_rule_.size(); ++i) near += near_rule_.weight[i] / (near_rule_.x[i] - rho);
    T far = T(0);
    for (std::size_t i = 0; i < far_rule_.size(); ++i) {
      const Real v = far_rule_.x[i];
      const T d = (v - rho) / rho;
      T divided;
      if (modulus(d) < Real(1) / 8) {
        // (v^q - rho^q)/(v - rho) = rho^(q-1) ((1+d)^q - 1)/d
        divided = rho_q / rho * binomial_difference_series(q_, d);
        // (real negative rho never gets here: |d| >= 1 then)
      } else {
        using std::pow;
        divided = (pow(v, q_) - rho_q) / (v - rho);
      }
      far += far_rule_.weight[i] * divided;
    }
    return near + far + rho_q * logs;
  }

  Real q_;
  Real t_over_q_, u_over_q_;
  bool direct_pv_ = false;
  Real pi_cot_ = 0;  // pi cot(pi q), for |q| >= 1/4
  quadrature::quadrature_rule<Real> near_rule_, far_rule_;
};

}  // namespace rhabel::riemann::detail
