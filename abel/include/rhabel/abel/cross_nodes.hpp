// rhabel/abel/cross_nodes.hpp: quadrature nodes on an interval I = [lo, hi] of length L = 2h for
// the integrals int_I w(t) P_n(t) K(t - s) dt of a Jacobi density's basis against the cross kernel
// K (far_field.hpp's cross_kernel: |t - s|^(alpha - 1) with the factor -kappa for t < s) at points
// s OUTSIDE I, at least `gap` from the end of I facing them; w = (1 - x)^gam (1 + x)^del, the
// density's weight (abel_operator.hpp), gam, del > -1. The interaction of disjoint intervals
// (abel::solve_union, multi_interval.hpp) and of the punch layer's contacts.
//
//  * cross_nodes<Real>: the nodes x (reference variable), their weights (w and dt included) and
//    the distances t - lo, hi - t without cancellation, so that t - s is formed from distances.
//  * make_cross_nodes(g, gap, facing_left, nodes): panels graded geometrically (ratio 2) toward the
//    facing end from d = gap/h on, `nodes` Gauss(-Jacobi) nodes per panel (panel_integrator,
//    numerics.hpp). The kernel's singularity at distance >= d sits 3 panel half-widths from every
//    panel's centre, so each panel's error falls like (3 + sqrt 8)^(-2 nodes) relative to the
//    integrand (Trefethen, "Approximation Theory and Approximation Practice", SIAM 2013, chapter
//    19); for w P_n with n < nodes the polynomial factor costs about n/2 of the nodes. Any gap > 0;
//    (log2(h/gap) + 2) panels.
//  * separated_cross_nodes(d, degree): the node count of ONE Gauss-Jacobi panel over all of I that
//    integrates w P_n K, n < degree, to ~eps/100 of K's size when every s is at least d >= 1
//    half-lengths from the facing end (a separated pair); 0 when d < 1. Derivation: its comment.
#pragma once

#include "rhabel/abel/abel_operator.hpp"
#include "rhabel/abel/numerics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace rhabel::abel {

/// Quadrature nodes on an interval I_i for the cross integrals: reference x, weight (including
/// w_i and dt = h dx), t - lo, hi - t (the distances without cancellation).
template <class Real>
struct cross_nodes {
  std::vector<Real> x, weight, t_minus_lo, hi_minus_t;
};

namespace detail {

/// Gauss nodes for the panel [ua, ub] of u = distance from the facing end (reference units,
/// u in [0, 2]) so that P_n, n < degree, is resolved: 20 + degree (theta_b - theta_a)/2,
/// theta = arccos(1 - u), rounded up to a multiple of 8 so that few distinct rules enter the
/// cache (the top of this header). THE difference from panel_integrator (one count for all).
template <class Real>
std::size_t cross_panel_nodes(const Real& ua, const Real& ub, std::size_t degree) {
  using std::acos;
  const double extra = static_cast<double>(Real(degree) * (acos(1 - ub) - acos(1 - ua)) / 2);
  const std::size_t nodes = 20 + static_cast<std::size_t>(std::ceil(extra));
  return (nodes + 7) / 8 * 8;
}

}  // namespace detail

/// Gauss-Jacobi nodes that integrate w P_n K(t - s), n < degree, over the whole of I_i in ONE
/// panel when every point s is at least d = gap/h >= 1 half-lengths h of I_i from its facing end
/// (a separated pair). K(t - s) = |t - s|^(alpha-1) is then analytic in x (t = centre + h x) inside
/// the Bernstein ellipse through the singular point x0 = -(1 + d') (d' >= d), whose parameter is
/// rho(d) = 1 + d + sqrt(d (2 + d)). A Q-point Gauss rule for the weight w is exact for polynomials
/// of degree 2Q - 1, so its error on P_n K is that of the best approximation of K by degree
/// 2Q - 1 - n, <= C rho'^-(2Q - 1 - n) for any rho' < rho (C ~ max |K| on that ellipse, which is
/// of the size of K at the facing end for rho' = rho^0.9, the 10 % kept off the singularity).
/// So Q = ceil(degree/2) + ceil(ln(100/eps) / (2 x 0.9 ln rho)) + 2 nodes (eps: Real's machine
/// epsilon) reach eps/100 relative to K's size; in double: n/2 + 20 at d = 1 (neighbours one half-length apart), n/2 + 13 at d = 4, n/2 + 7 at
/// d = 100, against 20 + pi n/4 + margin of cross_panel_nodes over the same panel, whose count is
/// for a kernel singularity next to the panel (gap -> 0). Rounded up to a multiple of 4 (few
/// distinct cached rules) and never more than cross_panel_nodes(0, 2, degree). 0 if d < 1 (not
/// separated: the graded panels of degree_graded_cross_nodes).
template <class Real>
std::size_t separated_cross_nodes(const Real& d, std::size_t degree) {
  if (!(d >= 1)) return 0;
  const double dd = static_cast<double>(d);
  const double log_rho = std::log(1 + dd + std::sqrt(dd * (2 + dd)));
  const double log_target = std::log(100 / static_cast<double>(std::numeric_limits<Real>::epsilon()));
  const auto kernel_nodes = static_cast<std::size_t>(std::ceil(log_target / (2 * 0.9 * log_rho)));
  const std::size_t nodes = (degree + 1) / 2 + kernel_nodes + 2;
  return std::min((nodes + 3) / 4 * 4, detail::cross_panel_nodes(Real(0), Real(2), degree));
}

/// Nodes of I_i (physical t, weight including w_i and dt = (L/2) dx, reference x) graded toward
/// the end of I_i facing the point set at distance `gap` (left if facing_left); `nodes` per
/// panel. The independent route of abel::solve_union's residual (the
/// assembly uses degree_graded_cross_nodes).
template <class Real>
cross_nodes<Real> make_cross_nodes(const jacobi_density<Real>& g, const Real& gap, bool facing_left, std::size_t nodes) {
  const Real h = g.half_length();
  const panel_integrator<Real> rule(g.del, g.gam, nodes);
  const Real inf = std::numeric_limits<Real>::infinity();
  const Real d = gap / h;
  cross_nodes<Real> out;
  rule.for_each_node(Real(2), facing_left ? d : inf, facing_left ? inf : d,
                     [&](const Real& u, const Real& v, const Real& weight) {
                       out.x.push_back(u <= v ? u - 1 : 1 - v);
                       out.weight.push_back(h * weight);
                       out.t_minus_lo.push_back(h * u);
                       out.hi_minus_t.push_back(h * v);
                     });
  return out;
}

}  // namespace rhabel::abel
