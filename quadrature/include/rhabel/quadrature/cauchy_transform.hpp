// rhabel/quadrature/cauchy_transform.hpp
//
// Cauchy transforms of Jacobi-weighted densities  rho(t) = w(t) h(t),
//     w(t) = (1 - t)^p (1 + t)^q ,  p, q > -1 ,  t in [-1, 1],
// with h smooth on [-1, 1] (a polynomial, a Jacobi series sum c_k P_k^(p,q), or any callable
// that is analytic on a neighbourhood of [-1, 1]).
//
//   cauchy_principal_value(h, p, q, x)  = (1/pi) PV int_{-1}^{1} w(t) h(t) / (t - x) dt,  -1 < x < 1
//   cauchy_transform(h, p, q, z)        = Phi(z) = (1/(2 pi i)) int_{-1}^{1} w(t) h(t) / (t - z) dt,
//                                          z in C \ [-1, 1]
//   cauchy_plemelj(h, p, q, x)          = Phi_+(x), Phi_-(x): the limits from Im z > 0 and Im z < 0,
//                                          Phi_+- (x) = +- rho(x)/2 + (1/(2 pi i)) PV int rho/(t - x) dt
//                                          (Sokhotski-Plemelj; Muskhelishvili, "Singular Integral
//                                          Equations", sec. 17; Gakhov, "Boundary Value Problems", 4.2)
// and the *_series variants for h = sum_k c[k] P_k^(p,q) (coefficients in the family of the weight).
//
//   jacobi_q_all(n_max, p, q, z)         Jacobi functions of the second kind
//                                          Q_k(z) = int_{-1}^{1} w(t) P_k^(p,q)(t) / (z - t) dt, k <= n_max
//   jacobi_q_all_on_cut(n_max, p, q, x)  their principal values on the cut (the mean of the two
//                                          boundary values), -1 < x < 1
// (Szego ch. 4.61; note the sign: Q_k(z) = -2 pi i Phi[P_k](z)). They satisfy the three-term
// recurrence of P_k for k >= 1, and Q_1 = (A_0 z + B_0) Q_0 - A_0 h_0 (A_0 = (p+q+2)/2,
// h_0 = int w). Q_0 comes from the graded quadrature below. For non-integer p it also has the
// closed form (Euler's integral of 2F1 in zeta = 2/(1+z), then the zeta -> 1 - zeta connection
// formula and a Pfaff transformation; checked to 30 digits with mpmath)
//     Q_0(z) = -(pi / sin(pi p)) (z-1)^p (z+1)^q + 2^(p+q) B(p, q+1) 2F1(1, -p-q; 1-p; (1-z)/2),
// with (z-1)^p (z+1)^q := ((z-1)/(z+1))^p (z+1)^(p+q) (principal branches), whose mean on the cut is
//     PV int w/(t - x) dt = pi cot(pi p) w(x) - 2^(p+q) B(p, q+1) 2F1(1, -p-q; 1-p; (1-x)/2).
// It degenerates (poles of Gamma(p), sin(pi p)) at integer p, which are hard cases here, and a
// complex 2F1 is not in Boost, so the library does not use it: it is a test oracle
// (test_cauchy_transform.cpp). Off the cut Q_k decays
// like rho^(-k), rho = |z + sqrt(z^2 - 1)| > 1: it is the minimal solution, and the forward
// recurrence amplifies errors by ~rho^(2k); we run it forward only while rho^(2 n_max) <= 16,
// and otherwise use Miller's backward recurrence from N = n_max + ceil(ln(8/eps)/(2 ln rho)),
// normalised by Q_0 (Gautschi, SIAM Rev. 9 (1967) 24-82). On the cut both solutions are of
// the same size and the forward recurrence is stable.
//
// Method. No subtraction of the pole and no closed form: the integral is split where the
// kernel is singular and each piece is integrated by composite Gauss rules geometrically graded
// towards the singular point (detail/jacobi_graded_integral.hpp). For the principal value at x,
// with d = min(1 - x, 1 + x)/2,
//     PV int_{-1}^{1} = int_{-1}^{x-d} + int_{x+d}^{1} + int_0^d [rho(x+s) - rho(x-s)] / s ds ,
// the last (symmetric) piece being the PV of the middle interval with the pole cancelled
// exactly by symmetry; rho is analytic on [x-2d, x+2d] so it converges geometrically. The
// end factors (1-t)^p, (1+t)^q are carried by Gauss-Jacobi weights on the panels that touch
// the ends, so p, q down to -0.999 (where endpoint-blind rules need thousands of nodes) cost
// nothing extra, and x within 1e-12 of an end costs ~40 more panels (log2 of the distance),
// not accuracy. For complex z the interval is split at c = clamp(Re z, -1, 1) and graded
// towards c on the scale min(|z - c|, distance from c to the other end).
//
// Accuracy. Each routine returns value, error_estimate and the number of evaluations of h.
// The estimate is |I(n) - I(n')| for two panel orders n < n' (n' is returned): an ESTIMATE,
// not a bound. Measured in double against the 40-digit tables of
// tools/reference/cauchy_abel_reference.cpp (tests/quadrature/test_cauchy_transform*.cpp):
//   principal value, 252 cases (h of degree 7, a Jacobi series of degree 6, h = 1;
//   p, q in {-0.999, -0.5, 0, 0.5, 5, 30}; x in {-1 + 2^-40, ..., 1 - 2^-40}): worst error
//   38.6 eps relative to the condition scale |PV| + |w(x) h(x)| + int w |h|;
//   transform off the cut, 56 cases (z 1e-12 and 1e-9 from the cut, at and beyond the ends,
//   far away): worst 3.6 eps on the same scale;
//   Real = cpp_bin_float_50: agreement with the tables to 1e-38 (their accuracy).
// The PV grows like w(x) log at the ends; errors are relative to the scale above, which is
// the condition of the problem (the PV itself can vanish).
//
// Cost: O(n log(1/d)) evaluations of h (n ~ 14 in double), O(K) each for a series of length K;
// the Gauss rules are cached per thread (detail::cached_gauss_jacobi). Measured (g++ -O2, one
// core, h quadratic): ~11 us per principal value, ~5 us per Abel integral, ~28 us for an Abel
// integral of a 20-term series. Half of it is the error estimate (second panel order).
//
// Parameters: p, q > -1 finite; x in (-1, 1) for the PV and Plemelj limits; z not on [-1, 1].
// Bad input throws std::domain_error naming function, parameter, value and range.
#pragma once

#include "rhabel/quadrature/detail/jacobi_graded_integral.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <vector>

namespace rhabel::quadrature {

/// A real value with its evidence: an error estimate (heuristic, see header) and the number
/// of evaluations of the density factor h that produced it.
template <class Real>
struct integral_result {
  Real value;
  Real error_estimate;
  std::size_t evaluations;
};

/// A complex value with its evidence (as integral_result).
template <class Real>
struct complex_integral_result {
  std::complex<Real> value;
  Real error_estimate;
  std::size_t evaluations;
};

/// The two boundary values of Phi on the cut.
template <class Real>
struct plemelj_result {
  std::complex<Real> plus;   ///< limit from Im z > 0
  std::complex<Real> minus;  ///< limit from Im z < 0
  Real error_estimate;       ///< estimate of the error of each limit
  std::size_t evaluations;
};

namespace detail {

template <class Real>
void check_open_interval_point(const char* function, const Real& x) {
  using std::isfinite;
  if (!isfinite(x) || !(x > -1) || !(x < 1)) throw_bad_parameter(function, "x", x, "(-1, 1)");
}

/// Panel order for an h of polynomial degree `degree` (0 for a callable of unknown degree)
/// and end exponents p, q: large exponents make the weight a high-degree factor on the
/// interior panels ((1 + t)^30 on a panel is a degree-30-like polynomial).
template <class Real>
std::size_t cauchy_panel_order(std::size_t degree, const Real& p, const Real& q, std::size_t order) {
  if (order != 0) return order;
  const double pp = std::max(0.0, static_cast<double>(p)), qq = std::max(0.0, static_cast<double>(q));
  return panel_order_for<Real>() + degree / 2 + static_cast<std::size_t>(std::min(200.0, (pp + qq) / 4));
}

/// h(t) = sum_k c[k] P_k^(p,q)(t) as a callable, Clenshaw at each point.
template <class Real>
auto jacobi_series_callable(const std::vector<Real>& c, const Real& p, const Real& q) {
  return [&c, p, q](const Real& t) { return jacobi_clenshaw(c, p, q, t); };
}

template <class Real>
std::size_t series_degree(const std::vector<Real>& c) {
  return c.empty() ? 0 : c.size() - 1;
}

/// The common body of the *_series variants: validates p, q under the public name `function`
/// (before anything reads them), then returns routine(h, n) with
///   h = sum_k c[k] P_k^(p,q) as a callable (jacobi_series_callable: Clenshaw at each point; it
///       refers to c, which outlives the call), and
///   n = the panel order raised for the series degree (cauchy_panel_order), or `order` if the
///       caller fixed it.
/// `routine` forwards h and n to the callable-h routine; the evaluation point stays in its capture.
template <class Real, class Routine>
auto with_jacobi_series(const char* function, const std::vector<Real>& c, const Real& p, const Real& q,
                        std::size_t order, Routine&& routine) {
  check_jacobi_exponents(function, p, q);
  return routine(jacobi_series_callable(c, p, q), cauchy_panel_order(series_degree(c), p, q, order));
}

}  // namespace detail

/// (1/pi) PV int_{-1}^{1} (1-t)^p (1+t)^q h(t) / (t - x) dt for -1 < x < 1.
/// h: callable Real -> Real, analytic near [-1, 1]. `order` = Gauss nodes per panel (0: automatic,
/// enough for machine precision when h is a polynomial of modest degree; raise it for an h with
/// nearby complex singularities and check error_estimate).
template <class Real, class H>
integral_result<Real> cauchy_principal_value(const H& h, Real p, Real q, Real x, std::size_t order = 0) {
  using std::abs;
  using std::min;
  using std::pow;
  constexpr const char* name = "cauchy_principal_value";
  detail::check_jacobi_exponents(name, p, q);
  detail::check_open_interval_point(name, x);
  const std::size_t n = detail::cauchy_panel_order(0, p, q, order);
  const Real inf = std::numeric_limits<Real>::infinity();
  const Real one_minus_x = 1 - x, one_plus_x = 1 + x;  // exact near the respective end (Sterbenz)
  const Real d = min(one_minus_x, one_plus_x) / 2;

  // [-1, x - d]: a = -1, u = 1 + t, v = x - d - t; t - x = -(v + d); 1 - t = one_minus_x + d + v.
  auto left = detail::graded_estimate<Real>(one_plus_x - d, q, Real(0), inf, d, n, [&](const Real& u, const Real& v) {
    const Real t = u <= v ? u - 1 : x - d - v;
    const Real w_other = p == 0 ? Real(1) : Real(pow(one_minus_x + d + v, p));
    return w_other * h(t) / (-(v + d));
  });
  // [x + d, 1]: u = t - x - d, v = 1 - t; t - x = d + u; 1 + t = one_plus_x + d + u.
  auto right = detail::graded_estimate<Real>(one_minus_x - d, Real(0), p, d, inf, n, [&](const Real& u, const Real& v) {
    const Real t = u <= v ? x + d + u : 1 - v;
    const Real w_other = q == 0 ? Real(1) : Real(pow(one_plus_x + d + u, q));
    return w_other * h(t) / (d + u);
  });
  // int_0^d [rho(x+s) - rho(x-s)]/s ds; rho(x +- s) with 1 - t and 1 + t formed from the complements.
  auto rho = [&](const Real& t, const Real& omt, const Real& opt) {
    Real value = h(t);
    if (p != 0) value *= pow(omt, p);
    if (q != 0) value *= pow(opt, q);
    return value;
  };
  auto middle = detail::graded_estimate<Real>(d, Real(0), Real(0), inf, inf, n, [&](const Real& s, const Real&) {
    return (rho(x + s, one_minus_x - s, one_plus_x + s) - rho(x - s, one_minus_x + s, one_plus_x - s)) / s;
  });
  const Real pi = boost::math::constants::pi<Real>();
  return {(left.value + right.value + middle.value) / pi,
          (left.error_estimate + right.error_estimate + middle.error_estimate) / pi,
          left.evaluations + right.evaluations + 2 * middle.evaluations};
}

/// (1/pi) PV int w(t) h(t)/(t - x) dt for h = sum_k c[k] P_k^(p,q) (the weight's own family).
/// `order` = 0 raises the automatic panel order by deg/2 for a series of degree deg.
template <class Real>
integral_result<Real> cauchy_principal_value_series(const std::vector<Real>& c, Real p, Real q, Real x,
                                                    std::size_t order = 0) {
  return detail::with_jacobi_series("rhabel::quadrature::cauchy_principal_value_series", c, p, q, order, [&](const auto& h, std::size_t n) {
    return cauchy_principal_value(h, p, q, x, n);
  });
}

/// Phi(z) = (1/(2 pi i)) int_{-1}^{1} (1-t)^p (1+t)^q h(t) / (t - z) dt for z in C \ [-1, 1].
/// h: callable Real -> Real (evaluated on [-1, 1] only).
template <class Real, class H>
complex_integral_result<Real> cauchy_transform(const H& h, Real p, Real q, std::complex<Real> z,
                                               std::size_t order = 0) {
  using std::abs;
  using std::isfinite;
  using std::max;
  using std::min;
  using std::pow;
  using complex = std::complex<Real>;
  constexpr const char* name = "cauchy_transform";
  detail::check_jacobi_exponents(name, p, q);
  if (!isfinite(z.real())) detail::throw_bad_parameter(name, "Re z", z.real(), "finite");
  if (!isfinite(z.imag())) detail::throw_bad_parameter(name, "Im z", z.imag(), "finite");
  if (z.imag() == 0 && z.real() >= -1 && z.real() <= 1)
    detail::throw_bad_parameter(name, "z (real, on the cut [-1, 1])", z.real(),
                                "C \\ [-1, 1]; use cauchy_plemelj for the boundary values");
  const std::size_t n = detail::cauchy_panel_order(0, p, q, order);
  const Real inf = std::numeric_limits<Real>::infinity();
  const Real c = min(Real(1), max(Real(-1), z.real()));
  const complex c_minus_z = complex(c - z.real(), -z.imag());
  const Real delta = abs(c_minus_z);
  detail::graded_result<complex, Real> total{complex(0), Real(0), 0};
  auto add = [&](const detail::graded_result<complex, Real>& part) {
    total.value += part.value;
    total.error_estimate += part.error_estimate;
    total.evaluations += part.evaluations;
  };
  if (c > -1 && c < 1) {
    // [-1, c]: t - z = (c - z) - v, 1 - t = (1 - c) + v.
    // Grading scales: the pole, and the other end's algebraic singularity ((1 - t)^p at
    // distance 1 - c beyond c for the left part, (1 + t)^q at 1 + c for the right part).
    add(detail::graded_estimate<Real>(1 + c, q, Real(0), inf, min(delta, Real(1 - c)), n, [&](const Real& u, const Real& v) {
      const Real t = u <= v ? u - 1 : c - v;
      const Real w_other = p == 0 ? Real(1) : Real(pow((1 - c) + v, p));
      return complex(w_other * h(t)) / (c_minus_z - v);
    }));
    // [c, 1]: t - z = (c - z) + u, 1 + t = (1 + c) + u.
    add(detail::graded_estimate<Real>(1 - c, Real(0), p, min(delta, Real(1 + c)), inf, n, [&](const Real& u, const Real& v) {
      const Real t = u <= v ? c + u : 1 - v;
      const Real w_other = q == 0 ? Real(1) : Real(pow((1 + c) + u, q));
      return complex(w_other * h(t)) / (c_minus_z + u);
    }));
  } else {
    // Re z <= -1 (c = -1: t - z = (c - z) + u) or Re z >= 1 (c = 1: t - z = (c - z) - v).
    const bool at_lower = c < 0;
    add(detail::graded_estimate<Real>(Real(2), q, p, at_lower ? delta : inf, at_lower ? inf : delta, n,
                                      [&](const Real& u, const Real& v) {
                                        const Real t = u <= v ? u - 1 : 1 - v;
                                        return complex(h(t)) / (at_lower ? c_minus_z + u : c_minus_z - v);
                                      }));
  }
  const Real two_pi = 2 * boost::math::constants::pi<Real>();
  const complex factor = complex(0, -1) / two_pi;  // 1/(2 pi i)
  return {factor * total.value, total.error_estimate / two_pi, total.evaluations};
}

/// Phi(z) for h = sum_k c[k] P_k^(p,q) (panel order as cauchy_principal_value_series).
template <class Real>
complex_integral_result<Real> cauchy_transform_series(const std::vector<Real>& c, Real p, Real q,
                                                      std::complex<Real> z, std::size_t order = 0) {
  return detail::with_jacobi_series("rhabel::quadrature::cauchy_transform_series", c, p, q, order, [&](const auto& h, std::size_t n) {
    return cauchy_transform(h, p, q, z, n);
  });
}

/// Boundary values Phi_+(x), Phi_-(x) of Phi (see cauchy_transform) at -1 < x < 1:
/// Phi_+- = +- w(x) h(x) / 2 + (1/(2 pi i)) PV int w h/(t - x) dt  (so Phi_+ - Phi_- = w h).
template <class Real, class H>
plemelj_result<Real> cauchy_plemelj(const H& h, Real p, Real q, Real x, std::size_t order = 0) {
  using std::pow;
  using complex = std::complex<Real>;
  detail::check_jacobi_exponents("rhabel::quadrature::cauchy_plemelj", p, q);
  detail::check_open_interval_point("rhabel::quadrature::cauchy_plemelj", x);
  const auto pv = cauchy_principal_value(h, p, q, x, order);  // (1/pi) PV int
  const Real rho = pow(1 - x, p) * pow(1 + x, q) * h(x);
  // (1/(2 pi i)) PV int = -(i/2) (1/pi) PV int.
  const complex principal(0, -pv.value / 2);
  return {complex(rho / 2) + principal, complex(-rho / 2) + principal, pv.error_estimate / 2, pv.evaluations + 1};
}

/// Phi_+-(x) for h = sum_k c[k] P_k^(p,q) (panel order as cauchy_principal_value_series).
template <class Real>
plemelj_result<Real> cauchy_plemelj_series(const std::vector<Real>& c, Real p, Real q, Real x,
                                           std::size_t order = 0) {
  return detail::with_jacobi_series("rhabel::quadrature::cauchy_plemelj_series", c, p, q, order, [&](const auto& h, std::size_t n) {
    return cauchy_plemelj(h, p, q, x, n);
  });
}

/// Q_k(z) = int_{-1}^{1} (1-t)^p (1+t)^q P_k^(p,q)(t) / (z - t) dt for k = 0..n_max, z off [-1, 1].
template <class Real>
std::vector<std::complex<Real>> jacobi_q_all(std::size_t n_max, Real p, Real q, std::complex<Real> z) {
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_q_all", p, q);
  using std::abs;
  using std::ceil;
  using std::log;
  using std::sqrt;
  using complex = std::complex<Real>;
  const Real two_pi = 2 * boost::math::constants::pi<Real>();
  // Q_0 = -2 pi i Phi[1](z) (cauchy_transform validates z).
  const complex q0 = complex(0, -two_pi) * cauchy_transform([](const Real&) { return Real(1); }, p, q, z).value;
  std::vector<complex> Q(n_max + 1);
  Q[0] = q0;
  if (n_max == 0) return Q;
  const Real rho = abs(z + sqrt(z - Real(1)) * sqrt(z + Real(1)));  // > 1 off the cut
  const Real A0 = (p + q + 2) / 2, B0 = (p - q) / 2;
  const bool forward = 2 * Real(n_max) * log(rho) <= log(Real(16));
  if (forward) {
    Q[1] = (A0 * z + B0) * q0 - A0 * jacobi_norm_squared(0, p, q);
    for (std::size_t k = 1; k < n_max; ++k) {
      const auto r = detail::jacobi_recurrence_coefficients(k, p, q);
      Q[k + 1] = (r.A * z + r.B) * Q[k] - r.C * Q[k - 1];
    }
    return Q;
  }
  // Miller: f_{N+1} = 0, f_N = 1, f_{k-1} = ((A_k z + B_k) f_k - f_{k+1}) / C_k, k = N..1.
  const Real eps = std::numeric_limits<Real>::epsilon();
  const auto extra = static_cast<std::size_t>(ceil(log(8 / eps) / (2 * log(rho)))) + 2;
  const std::size_t N = n_max + extra;
  complex f_next = 0, f = 1;
  for (std::size_t k = N; k >= 1; --k) {
    const auto r = detail::jacobi_recurrence_coefficients(k, p, q);
    const complex f_previous = ((r.A * z + r.B) * f - f_next) / r.C;
    f_next = f;
    f = f_previous;
    if (k - 1 <= n_max) Q[k - 1] = f;
    if (abs(f) > Real(1e100)) {  // rescale to avoid overflow (ratios are all that matter)
      const Real scale = 1 / abs(f);
      f *= scale;
      f_next *= scale;
      for (std::size_t j = k - 1; j <= n_max && j < Q.size(); ++j) Q[j] *= scale;
    }
  }
  const complex normalisation = q0 / Q[0];
  for (auto& value : Q) value *= normalisation;
  return Q;
}

/// Principal values Q_k(x) = PV int_{-1}^{1} w(t) P_k^(p,q)(t) / (x - t) dt, k = 0..n_max,
/// -1 < x < 1 (forward recurrence, stable on the cut).
template <class Real>
std::vector<Real> jacobi_q_all_on_cut(std::size_t n_max, Real p, Real q, Real x) {
  constexpr const char* name = "jacobi_q_all_on_cut";
  detail::check_jacobi_exponents(name, p, q);
  detail::check_open_interval_point(name, x);
  const Real pi = boost::math::constants::pi<Real>();
  std::vector<Real> Q(n_max + 1);
  Q[0] = -pi * cauchy_principal_value([](const Real&) { return Real(1); }, p, q, x).value;
  if (n_max == 0) return Q;
  const Real A0 = (p + q + 2) / 2, B0 = (p - q) / 2;
  Q[1] = (A0 * x + B0) * Q[0] - A0 * jacobi_norm_squared(0, p, q);
  for (std::size_t k = 1; k < n_max; ++k) {
    const auto r = detail::jacobi_recurrence_coefficients(k, p, q);
    Q[k + 1] = (r.A * x + r.B) * Q[k] - r.C * Q[k - 1];
  }
  return Q;
}

}  // namespace rhabel::quadrature
