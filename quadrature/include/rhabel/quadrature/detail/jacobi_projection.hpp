// rhabel/quadrature/detail/jacobi_projection.hpp
//
// jacobi_coefficients(f, p, q, n): the first n Jacobi coefficients of a function by
// Gauss-Jacobi projection,
//     c_k = (1/h_k) sum_{i=1}^{n} w_i f(x_i) P_k^(p,q)(x_i),   k = 0..n-1,
// with the n-point Gauss-Jacobi rule of the weight (1-x)^p (1+x)^q. This is exact (to
// rounding) when f is a polynomial of degree < n, because f P_k then has degree < 2n - 1;
// for f analytic in the Bernstein ellipse E_rho the coefficients are accurate to O(rho^(-n))
// (aliasing error; Trefethen, ATAP ch. 8 and 19). Cost O(n^2) (P_0..P_{n-1} at each node).
//
// It lives in detail/ only because it needs gauss_jacobi.hpp, which itself includes
// jacobi_polynomial.hpp; it is public API in namespace rhabel::quadrature, included by the
// umbrella rhabel/quadrature.hpp (and by cauchy_transform.hpp).
#pragma once

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <cstddef>
#include <vector>

namespace rhabel::quadrature {

/// c_0..c_{n-1} with f ~ sum c_k P_k^(p,q); f: callable Real -> Real; n >= 1.
template <class Real, class F>
std::vector<Real> jacobi_coefficients(F&& f, Real p, Real q, std::size_t n) {
  detail::check_jacobi_exponents("jacobi_coefficients", p, q);
  if (n == 0) detail::throw_bad_parameter("jacobi_coefficients", "n", 0, "[1, inf)");
  const quadrature_rule<Real> rule = gauss_jacobi<Real>(n, p, q);
  std::vector<Real> c(n, Real(0));
  for (std::size_t i = 0; i < n; ++i) {
    const Real fw = rule.weight[i] * Real(f(rule.x[i]));
    const std::vector<Real> values = jacobi_p_all(n - 1, p, q, rule.x[i]);
    for (std::size_t k = 0; k < n; ++k) c[k] += fw * values[k];
  }
  for (std::size_t k = 0; k < n; ++k) c[k] /= jacobi_norm_squared(k, p, q);
  return c;
}

}  // namespace rhabel::quadrature
