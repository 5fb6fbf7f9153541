// rhabel/quadrature/detail/jacobi_projection.hpp
//
// jacobi_coefficients(f, p, q, n): the first n Jacobi coefficients of a function by
// Gauss-Jacobi projection,
//     c_k = (1/h_k) sum_{i=1}^{n} w_i f(x_i) P_k^(p,q)(x_i),   k = 0..n-1,
// with the n-point Gauss-Jacobi rule of the weight (1-x)^p (1+x)^q. This is exact (to
// rounding) when f is a polynomial of degree < n, because f P_k then has degree < 2n - 1;
// for f analytic in the Bernstein ellipse E_rho the coefficients are accurate to O(rho^(-n))
// (aliasing error; Trefethen, ATAP ch. 8 and 19). f is called as f(x), or as f(x, 1 + x, 1 - x)
// when it takes three arguments: the rule's distances to the ends, without the rounding of x (a
// factor with a pole at distance d beyond an end needs them to ~eps relative instead of eps/d).
// Cost O(n^2): P_0..P_{n-1} at each node by jacobi_p_all's recurrences (the plain three-term one
// for |x| < 1/2, Reinsch's difference form near the nearer end for |x| >= 1/2, from the rule's
// distance to that end), their coefficients computed once for all nodes (computed at every node,
// they cost about as much as the sums themselves).
//
// It lives in detail/ only because it needs gauss_jacobi.hpp, which itself includes
// jacobi_polynomial.hpp; it is public API in namespace rhabel::quadrature, included by the
// umbrella rhabel/quadrature.hpp (and by cauchy_transform.hpp).
#pragma once

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <cstddef>
#include <type_traits>
#include <vector>

namespace rhabel::quadrature {

namespace detail {

/// sum_i f_i P_k^(p,q)(x_i), k = 0..n-1, over the nodes of `rule` (see the top of this header).
template <class Real>
std::vector<Real> jacobi_sums_at_nodes(const quadrature_rule<Real>& rule, const std::vector<Real>& f, std::size_t n,
                                       const Real& p, const Real& q) {
  std::vector<jacobi_recurrence<Real>> plain(n);
  std::vector<difference_form_step<Real>> at_plus(n), at_minus(n);
  std::vector<Real> rise_plus(n), rise_minus(n);  // pi_(k+1)/pi_k, pi_k = P_k(1), at each end
  for (std::size_t k = 0; k < n; ++k) {
    plain[k] = jacobi_recurrence_coefficients(k, p, q);
    if (k >= 1) {
      at_plus[k] = difference_form_coefficients(k, p, q);
      at_minus[k] = difference_form_coefficients(k, q, p);
    }
    rise_plus[k] = (Real(k) + 1 + p) / (Real(k) + 1);
    rise_minus[k] = (Real(k) + 1 + q) / (Real(k) + 1);
  }
  std::vector<Real> c(n, Real(0));
  for (std::size_t i = 0; i < rule.size(); ++i) {
    const Real& x = rule.x[i];
    const Real& fi = f[i];
    c[0] += fi;
    if (n < 2) continue;
    if (x >= Real(0.5) || x <= Real(-0.5)) {
      // jacobi_p_visit_near_one: near +1 with (p, q) and u = 1 - x; near -1 with (q, p), u = 1 + x
      // and the sign (-1)^k.
      const bool plus = x >= Real(0.5);
      const Real& a = plus ? p : q;
      const Real& b = plus ? q : p;
      const Real& u = plus ? rule.hi_minus_x[i] : rule.x_minus_lo[i];
      const auto& steps = plus ? at_plus : at_minus;
      const auto& rise = plus ? rise_plus : rise_minus;
      Real D = -(a + b + 2) * u / (2 * (a + 1));
      Real R = 1 + D, pi_k = rise[0];
      Real signed_f = plus ? fi : Real(-fi);
      c[1] += signed_f * pi_k * R;
      for (std::size_t k = 1; k + 1 < n; ++k) {
        D = steps[k].b * D - steps[k].a * u * R;
        R += D;
        pi_k *= rise[k];
        if (!plus) signed_f = -signed_f;
        c[k + 1] += signed_f * pi_k * R;
      }
      continue;
    }
    Real previous = 1, current = (p + q + 2) / 2 * x + (p - q) / 2;
    c[1] += fi * current;
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const Real next = (plain[k].A * x + plain[k].B) * current - plain[k].C * previous;
      previous = current;
      current = next;
      c[k + 1] += fi * current;
    }
  }
  return c;
}

}  // namespace detail

/// c_0..c_{n-1} with f ~ sum c_k P_k^(p,q); f: callable Real -> Real, or (x, 1 + x, 1 - x) -> Real;
/// n >= 1.
template <class Real, class F>
std::vector<Real> jacobi_coefficients(F&& f, Real p, Real q, std::size_t n) {
  detail::check_jacobi_exponents("rhabel::quadrature::jacobi_coefficients", p, q);
  if (n == 0) detail::throw_bad_parameter("rhabel::quadrature::jacobi_coefficients", "n", 0, "[1, inf)");
  const quadrature_rule<Real> rule = gauss_jacobi<Real>(n, p, q);
  std::vector<Real> fw(n);
  for (std::size_t i = 0; i < n; ++i) {
    if constexpr (std::is_invocable_v<F&, const Real&, const Real&, const Real&>)
      fw[i] = rule.weight[i] * Real(f(rule.x[i], rule.x_minus_lo[i], rule.hi_minus_x[i]));
    else
      fw[i] = rule.weight[i] * Real(f(rule.x[i]));
  }
  std::vector<Real> c = detail::jacobi_sums_at_nodes(rule, fw, n, p, q);
  for (std::size_t k = 0; k < n; ++k) c[k] /= jacobi_norm_squared(k, p, q);
  return c;
}

}  // namespace rhabel::quadrature
