// rhabel/abel/elementary.hpp
//
// The elementary (one-sided) Abel equation, kappa = 0 in paper eq. 8, alpha in (0, 1):
//
//   side::right:  int_s^b g(t) (t - s)^(alpha-1) dt = F(s),   a < s < b
//   side::left:   int_a^s g(t) (s - t)^(alpha-1) dt = F(s),   a < s < b
//
// Its unique integrable solution for smooth F is
//   right: g(t) = -(sin(pi alpha)/pi) d/dt int_t^b F(u) (u - t)^(-alpha) du  ~ (b - t)^(-alpha),
//   left:  g(t) =  (sin(pi alpha)/pi) d/dt int_a^t F(u) (t - u)^(-alpha) du  ~ (t - a)^(-alpha),
// (Abel 1823; Gorenflo & Vessella, "Abel integral equations", LNM 1461, ch. 2). No derivative
// is taken here:
//  * solve_elementary_abel: the generalized operator with kappa = 0 (beta = 1 - 2 alpha, which is
//    negative for alpha > 1/2: abel_parameters accepts beta in (-1, 1)) in the class
//    (bounded, unbounded) = exponents (gam, del) = (0, -alpha), nu = 0; the left-sided equation
//    by reflection t -> a + b - t (P_n^(p,q)(-x) = (-1)^n P_n^(q,p)(x)), giving exponents
//    (gam, del) = (-alpha, 0). Spectral accuracy for smooth F, same evidence as solve().
//  * elementary_abel_primitive: the primitive int_x^b g (right) or int_a^x g (left) from the
//    composition rule I^(1-alpha) I^alpha = I^1:
//        int_x^b g = (sin(pi alpha)/pi) int_x^b F(u) (u - x)^(-alpha) du,
//    by Gauss-Jacobi with the weight (u - x)^(-alpha): exact for polynomial F of degree < 2 nodes;
//    an independent route (no Jacobi series of g) used by the tests.
#pragma once

#include "rhabel/abel/abel_solver.hpp"

#include <boost/math/constants/constants.hpp>

#include <cmath>
#include <cstddef>

namespace rhabel::abel {

enum class side { left, right };

/// Solves the one-sided Abel equation on [lo, hi] (see header). alpha in (0, 1).
template <class Real, class F>
abel_solution<Real> solve_elementary_abel(const Real& alpha, side which, const Real& lo, const Real& hi, F&& f,
                                          const solve_options<Real>& options = {}) {
  using std::isfinite;
  if (!isfinite(alpha) || !(alpha > 0) || !(alpha < 1))
    detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_elementary_abel", "alpha", alpha, "(0, 1)");
  const auto par = abel_parameters<Real>::from_kappa(alpha, Real(0));
  if (which == side::right) {
    const abel_operator<Real> op(par, lo, hi);
    return solve(op, edge::bounded, edge::unbounded, f, options);
  }
  // Reflection: s' = -s on [-hi, -lo]; G(t') = g(-t') solves the right-sided equation with F(-s').
  const abel_operator<Real> op(par, -hi, -lo);
  abel_solution<Real> sol = solve(op, edge::bounded, edge::unbounded, [&](const Real& s) { return f(-s); }, options);
  jacobi_density<Real>& g = sol.density;
  g.lo = lo;
  g.hi = hi;
  const Real gam = g.gam;
  g.gam = g.del;
  g.del = gam;
  for (std::size_t n = 1; n < g.coefficients.size(); n += 2) g.coefficients[n] = -g.coefficients[n];
  sol.exponents.gam = g.gam;
  sol.exponents.del = g.del;
  return sol;
}

/// int_x^hi g (side::right) or int_lo^x g (side::left) for the solution g of the one-sided
/// equation with data F, without differentiating: (sin(pi alpha)/pi) int F(u) |u - x|^(-alpha) du
/// by `nodes`-point Gauss-Jacobi. lo <= x <= hi, alpha in (0, 1).
template <class Real, class F>
Real elementary_abel_primitive(const Real& alpha, side which, const Real& lo, const Real& hi, F&& f, const Real& x,
                               std::size_t nodes = 32) {
  using std::isfinite;
  using std::sin;
  if (!isfinite(alpha) || !(alpha > 0) || !(alpha < 1))
    detail::throw_bad_parameter("rhabel::abel::rhabel::abel::elementary_abel_primitive", "alpha", alpha, "(0, 1)");
  if (!(hi > lo)) detail::throw_bad_parameter("rhabel::abel::rhabel::abel::elementary_abel_primitive", "hi", hi, "> lo");
  if (!(x >= lo) || !(x <= hi)) detail::throw_bad_parameter("rhabel::abel::rhabel::abel::elementary_abel_primitive", "x", x, "[lo, hi]");
  const Real pi = boost::math::constants::pi<Real>();
  if ((which == side::right && x == hi) || (which == side::left && x == lo)) return Real(0);
  const auto rule = which == side::right ? rhabel::quadrature::gauss_jacobi<Real>(nodes, Real(0), -alpha, x, hi)
                                         : rhabel::quadrature::gauss_jacobi<Real>(nodes, -alpha, Real(0), lo, x);
  Real sum = 0;
  for (std::size_t i = 0; i < rule.size(); ++i) sum += rule.weight[i] * f(rule.x[i]);
  return sin(pi * alpha) / pi * sum;
}

}  // namespace rhabel::abel
