// rhabel/quadrature/abel_integral.hpp
//
// One-sided Abel (Riemann-Liouville) integrals of Jacobi-weighted densities
//     rho(t) = w(t) h(t),  w(t) = (1 - t)^p (1 + t)^q,  p, q > -1,  0 < mu <= 1:
//
//   abel_integral_right(h, p, q, mu, x) = int_x^1    (t - x)^(mu - 1) rho(t) dt ,  x < 1
//                                          (x <= -1 allowed: then the integral runs over all of
//                                          [-1, 1]; x = -1 needs q + mu > 0)
//   abel_integral_left (h, p, q, mu, x) = int_{-1}^x (x - t)^(mu - 1) rho(t) dt ,  x > -1
//                                          (x >= 1 allowed; x = 1 needs p + mu > 0)
//
// These are the two halves of the generalized Abel operator (docs/theory.md section 1, paper eq. 8,
// mu = alpha) mapped to [-1, 1]; x outside [-1, 1] gives the surface slope outside the contact.
// The *_series variants take h = sum_k c[k] P_k^(p,q).
//
// Method. The kernel singularity (t - x)^(mu-1) and the end singularity (1 + t)^q coalesce as
// x -> -1. Both are handled exactly by Gauss-Jacobi weights on the end panels of a composite
// rule geometrically graded towards the coalescence (detail/jacobi_graded_integral.hpp):
// for -1 < x < 1, int_x^1 is integrated with weight (t - x)^(mu-1) at x and (1 - t)^p at 1,
// panels doubling away from x on the scale 1 + x (the distance to the other singular point
// t = -1 of (1 + t)^q). For x < -1 the weight is (1 + t)^q (1 - t)^p, and (t - x)^(mu-1) is
// analytic with its singularity at distance -1 - x from the end: panels graded on that scale.
// The left integral is the right one of the reflected density: t -> -t swaps p and q and
// maps h(t) to h(-t). No hypergeometric closed form is used in the library; the closed form
//     int_{-1}^{1} (t - x)^(mu-1) (1-t)^p (1+t)^q dt
//         = 2^(p+q+1) (-1-x)^(mu-1) B(p+1, q+1) 2F1(1-mu, q+1; p+q+2; 2/(1+x))   (x < -1)
// (Euler's integral; t = 2s - 1) is used as an independent oracle by the tests.
//
// Accuracy: value, error_estimate (|I(n) - I(n')| for two panel orders, an ESTIMATE not a
// bound) and evaluations of h. Measured in double against the 40-digit table of
// tools/reference/cauchy_abel_reference.cpp (tests/quadrature/test_abel_integral.cpp, 228
// cases: h of degree 7 and a Jacobi series of degree 6, p, q in {-0.999, -0.5, 0, 0.5, 5, 30},
// mu in {0.01, 0.5, 0.999}, x = -1.5, -1 -+ 2^-40, 0, 0.7, 1 - 2^-40 and mirrored): worst
// 34.7 eps relative to |value| + int w; closed forms (1-x)^(mu+p) B(mu, p+1) to 128 eps
// RELATIVE at 1e-12 from the ends; Real = cpp_bin_float_50 to 1e-38. The spectral relation
// of docs/theory.md section 4 (all three index classes, n <= 6) holds to 64 eps.
//
// Bad input (p, q <= -1, mu outside (0, 1], x NaN or on the wrong side, divergent end cases)
// throws std::domain_error naming function, parameter, value and valid range.
#pragma once

#include "rhabel/quadrature/cauchy_transform.hpp"
#include "rhabel/quadrature/detail/jacobi_graded_integral.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace rhabel::quadrature {

namespace detail {

template <class Real, class H>
integral_result<Real> abel_right_impl(const char* name, const H& h, const Real& p, const Real& q, const Real& mu,
                                      const Real& x, std::size_t order, std::size_t degree) {
  using std::isfinite;
  using std::pow;
  check_jacobi_exponents(name, p, q);
  if (!isfinite(mu) || !(mu > 0) || !(mu <= 1)) throw_bad_parameter(name, "mu", mu, "(0, 1]");
  const Real inf = std::numeric_limits<Real>::infinity();
  const std::size_t n = cauchy_panel_order(degree, p, q, order);
  if (x > -1 && x < 1) {
    // [x, 1]: u = t - x, v = 1 - t; 1 + t = (1 + x) + u.
    const Real one_plus_x = 1 + x;
    auto r = graded_estimate<Real>(1 - x, mu - 1, p, one_plus_x, inf, n, [&](const Real& u, const Real& v) {
      const Real t = u <= v ? x + u : 1 - v;
      return q == 0 ? Real(h(t)) : Real(pow(one_plus_x + u, q) * h(t));
    });
    return {r.value, r.error_estimate, r.evaluations};
  }
  if (x < -1) {
    // [-1, 1] with the weight w; t - x = (-1 - x) + u is analytic, singular at distance -1 - x.
    const Real gap = -1 - x;
    auto r = graded_estimate<Real>(Real(2), q, p, gap, inf, n, [&](const Real& u, const Real& v) {
      const Real t = u <= v ? u - 1 : 1 - v;
      return mu == 1 ? Real(h(t)) : Real(pow(gap + u, mu - 1) * h(t));
    });
    return {r.value, r.error_estimate, r.evaluations};
  }
  if (x == -1) {
    // (t - x)^(mu-1) (1 + t)^q = (1 + t)^(q + mu - 1): integrable iff q + mu > 0.
    if (!(q + mu > 0)) throw_bad_parameter(name, "x (divergent at x = -1 unless q + mu > 0)", x, "(-inf, 1)");
    auto r = graded_estimate<Real>(Real(2), q + mu - 1, p, inf, inf, n, [&](const Real& u, const Real& v) {
      return Real(h(u <= v ? u - 1 : 1 - v));
    });
    return {r.value, r.error_estimate, r.evaluations};
  }
  if (x == 1) return {Real(0), Real(0), 0};  // empty interval
  throw_bad_parameter(name, "x", x, "(-inf, 1]");
}

}  // namespace detail

/// int_x^1 (t - x)^(mu-1) (1-t)^p (1+t)^q h(t) dt for x <= 1 (x < -1: the whole interval).
/// h: callable Real -> Real analytic near [-1, 1]; `order` Gauss nodes per panel (0: automatic).
template <class Real, class H>
integral_result<Real> abel_integral_right(const H& h, Real p, Real q, Real mu, Real x, std::size_t order = 0) {
  return detail::abel_right_impl("rhabel::quadrature::abel_integral_right", h, p, q, mu, x, order, 0);
}

/// int_{-1}^x (x - t)^(mu-1) (1-t)^p (1+t)^q h(t) dt for x >= -1 (x > 1: the whole interval).
/// Computed as the right integral of the reflection t -> -t (exponents swapped, h(-t)).
template <class Real, class H>
integral_result<Real> abel_integral_left(const H& h, Real p, Real q, Real mu, Real x, std::size_t order = 0) {
  using std::isnan;
  if (isnan(x)) detail::throw_bad_parameter("rhabel::quadrature::abel_integral_left", "x", x, "[-1, inf)");
  if (x < -1) detail::throw_bad_parameter("rhabel::quadrature::abel_integral_left", "x", x, "[-1, inf)");
  auto reflected = [&h](const Real& t) { return h(-t); };
  return detail::abel_right_impl("rhabel::quadrature::abel_integral_left", reflected, q, p, mu, Real(-x), order, 0);
}

/// abel_integral_right for h = sum_k c[k] P_k^(p,q).
template <class Real>
integral_result<Real> abel_integral_right_series(const std::vector<Real>& c, Real p, Real q, Real mu, Real x,
                                                 std::size_t order = 0) {
  detail::check_jacobi_exponents("rhabel::quadrature::abel_integral_right_series", p, q);
  return detail::abel_right_impl("rhabel::quadrature::abel_integral_right_series", detail::jacobi_series_callable(c, p, q), p, q, mu, x,
                                 order, detail::series_degree(c));
}

/// abel_integral_left for h = sum_k c[k] P_k^(p,q).
template <class Real>
integral_result<Real> abel_integral_left_series(const std::vector<Real>& c, Real p, Real q, Real mu, Real x,
                                                std::size_t order = 0) {
  using std::isnan;
  detail::check_jacobi_exponents("rhabel::quadrature::abel_integral_left_series", p, q);
  if (isnan(x) || x < -1) detail::throw_bad_parameter("rhabel::quadrature::abel_integral_left_series", "x", x, "[-1, inf)");
  auto h = detail::jacobi_series_callable(c, p, q);
  auto reflected = [&h](const Real& t) { return h(-t); };
  return detail::abel_right_impl("rhabel::quadrature::abel_integral_left_series", reflected, q, p, mu, Real(-x), order,
                                 detail::series_degree(c));
}

}  // namespace rhabel::quadrature
