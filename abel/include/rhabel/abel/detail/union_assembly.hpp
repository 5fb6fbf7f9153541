// rhabel/abel/detail/union_assembly.hpp: private assembly kernels of abel::solve_union
// (multi_interval.hpp) for high degrees (nearly touching intervals need 10^3 coefficients).
//
//  * degree_graded_cross_nodes: composite Gauss-Jacobi nodes on interval I_i for the cross
//    integrals int_{I_i} w_i(t) P_n(t) K(t - s) dt, n < degree, s outside I_i at distance
//    >= gap from the facing end. Panels in u = distance from the facing end (reference units,
//    u in [0, 2]) with breaks 0, d, 3d, 7d, ... (widths doubling, d = gap/h_i) up to u = 1,
//    then one panel over the far half: a kernel singularity at distance >= d from the facing
//    end sits at least one panel width away from every panel (panel_integrator's argument).
//    The node count of a panel follows the resolution P_n needs there, not its degree: near
//    x = 1 P_n(cos theta) oscillates like J_0(n theta), so a panel spanning the angles
//    [theta_a, theta_b] (theta = arccos(1 - u)) carries ~ n (theta_b - theta_a)/pi half-waves;
//    it gets 20 + n (theta_b - theta_a)/2 nodes, rounded up to a multiple of 8 (cross_panel_nodes):
//    pi/2 nodes per half-wave, 3x the rate at which an n/2-point Gauss rule integrates P_n
//    exactly over the whole interval, plus the 20 the kernel and the endpoint weights need
//    (panel_integrator's measured 16 nodes ~ 1e-24, plus a margin). The total is
//    ~ 24 (log2(h/gap) + 2) + pi n/2 nodes, against ~ (log2(h/gap) + 2)(n/2 + 16) for
//    make_cross_nodes: 3-4x fewer at degree 1024 and gap 1e-4 (1912 against 6864), which is what
//    makes degree >= 1000 affordable (a cross block costs degree^2 x nodes multiply-adds, done
//    as one matrix product). Accuracy: int w P_n = h_0 delta_n0 for all n < 1024 at gap 1e-4 to
//    <= 3.9e-12 relative to h sqrt(h_0 h_n) (1.9e-14 unless both ends are unbounded; the worst
//    at the top degrees), and through the solver (tests/abel/test_multi_interval.cpp:
//    forward/inverse consistency to 1e-11, the alpha = 0 closed form to 8e-11 at gap 1e-4).
//    Relation to panel_integrator::for_each_node (numerics.hpp), deliberately NOT used
//    here: the GRADING is the same (its breaks for len = 2, d_left = d, d_right = inf are these,
//    and so are its four rules: Gauss-Jacobi with the facing end's exponent on the first panel,
//    the far end's on the last, Gauss-Legendre between; at degree 0 the two node sets coincide
//    to rounding, tests/abel/test_multi_interval.cpp). What differs is the NODE COUNT: a
//    panel_integrator carries ONE count for all its panels (its rules are fixed at
//    construction), which here would have to be the far panel's ~ 20 + n pi/4 on each of the
//    log2(1/d) + 2 panels (11960 nodes instead of 1912 at degree 1024, gap 1e-4: 6x); so the
//    panels are walked here with a count each. A second, smaller difference: panel_integrator
//    stores the breaks graded towards its len end as distances from 0 (len - u, rounded), so
//    with the facing end on the right its node distances to that end are off by ~eps absolute,
//    ~eps/d relative (2.3e-13 in the weights at d = 2e-4); here u is measured from the facing
//    end on either side.
//  * separated_cross_nodes (rhabel/abel/cross_nodes.hpp): the node count of the one panel a
//    separated pair (gap >= the source's half-length) gets instead.
//  * cross_block: the matrix B(k, n) = scale int_{I_i} w_i P_n K(t - s_k) dt at collocation
//    points s_k of I_j given by their distance to the end of I_j facing I_i (no cancellation
//    in t - s: t - s = (distance of t to its facing end) + gap + (distance of s to its facing end)).
#pragma once

#include "rhabel/abel/abel_operator.hpp"
#include "rhabel/abel/cross_nodes.hpp"
#include "rhabel/abel/detail/numerics.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <tuple>
#include <vector>

namespace rhabel::abel::detail {

/// Nodes graded toward the end of I_i facing the other interval (the lo end if facing_left),
/// at distance `gap`; resolve P_n for n < degree (see the top of this header).
template <class Real>
cross_nodes<Real> degree_graded_cross_nodes(const jacobi_density<Real>& g, const Real& gap, bool facing_left,
                                                  std::size_t degree) {
  using std::pow;
  const Real h = g.half_length();
  const Real d = gap / h;
  // Exponent of the weight at the facing end and at the far end (w = (1-x)^del (1+x)^gam).
  const Real e_face = facing_left ? g.gam : g.del;
  const Real e_far = facing_left ? g.del : g.gam;
  // panel_integrator::for_each_node's breaks for (len = 2, d_left = d, d_right = inf).
  std::vector<Real> breaks{Real(0)};
  if (d > 0 && d < 1) {
    Real w = d;
    for (Real pos = d; pos < 1; w *= 2, pos += w) breaks.push_back(pos);
  }
  breaks.push_back(Real(2));
  cross_nodes<Real> out;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const Real ua = breaks[k], ub = breaks[k + 1];
    // One panel (d >= 1): a separated pair, whose kernel is smooth on all of I_i.
    const std::size_t nodes = breaks.size() == 2 && d >= 1 ? separated_cross_nodes(d, degree) : cross_panel_nodes(ua, ub, degree);
    const bool touches_face = k == 0, touches_far = k + 2 == breaks.size();
    // Gauss-Jacobi on [ua, ub] for the weight (ub - u)^P (u - ua)^Q: Q = e_face on the first
    // panel, P = e_far on the last.
    const Real P = touches_far ? e_far : Real(0), Q = touches_face ? e_face : Real(0);
    const auto rule = cached_gauss_jacobi_rule<Real>(nodes, P, Q);
    const Real half = (ub - ua) / 2;
    const Real scale = pow(half, P + Q + 1);
    for (std::size_t r = 0; r < rule->size(); ++r) {
      const Real u = ua + half * rule->x_minus_lo[r];       // distance from the facing end
      const Real v = touches_far ? half * rule->hi_minus_x[r] : Real(2) - u;  // from the far end
      Real weight = scale * rule->weight[r];
      if (!touches_face && e_face != 0) weight *= pow(u, e_face);
      if (!touches_far && e_far != 0) weight *= pow(v, e_far);
      const Real x = facing_left ? (u <= v ? u - 1 : 1 - v) : (u <= v ? 1 - u : v - 1);
      out.x.push_back(x);
      out.weight.push_back(h * weight);
      out.t_minus_lo.push_back(h * (facing_left ? u : v));
      out.hi_minus_t.push_back(h * (facing_left ? v : u));
    }
  }
  return out;
}

/// Basis values P_n^(del, gam)(x_q) (Q x n_basis) of a separated pair's one-panel rule, shared by
/// all separated blocks of one solve with the same source class and count: the nodes x_q of
/// separated_cross_nodes do not depend on d (only their number does), so the Q x n_basis values,
/// O(Q n_basis) each, are computed once per (Q, facing side, n_basis, del, gam).
template <class Real>
using separated_basis_cache =
    std::map<std::tuple<std::size_t, bool, std::size_t, Real, Real>, Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>>;

/// B(k, n) = scale int_{I_i} w_i(t) P_n^(del_i, gam_i)(t) K(t - s_k) dt, n < n_basis, for
/// points s_k of I_j given by dist_to_facing[k] (distance of s_k to the end of I_j that faces
/// I_i). i_right_of_j: I_i lies to the right of I_j. K: multi_interval.hpp's cross_kernel
/// (passed in to keep one definition). basis_cache (optional): separated_basis_cache.
template <class Real, class Kernel>
Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> cross_block(const jacobi_density<Real>& g_i, const Real& gap,
                                                                bool i_right_of_j,
                                                                const std::vector<Real>& dist_to_facing,
                                                                std::size_t n_basis, const Real& scale,
                                                                Kernel&& kernel,
                                                                separated_basis_cache<Real>* basis_cache = nullptr) {
  using matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  const auto nodes = degree_graded_cross_nodes(g_i, gap, i_right_of_j, n_basis);
  const auto Q = static_cast<Eigen::Index>(nodes.x.size());
  const auto M = static_cast<Eigen::Index>(dist_to_facing.size());
  const auto N = static_cast<Eigen::Index>(n_basis);
  matrix kernel_values(M, Q);
  for (Eigen::Index q = 0; q < Q; ++q) {
    const auto qs = static_cast<std::size_t>(q);
    for (Eigen::Index k = 0; k < M; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      const Real t_minus_s = i_right_of_j ? nodes.t_minus_lo[qs] + gap + dist_to_facing[ks]
                                          : -(nodes.hi_minus_t[qs] + gap + dist_to_facing[ks]);
      kernel_values(k, q) = scale * nodes.weight[qs] * kernel(t_minus_s);
    }
  }
  auto basis_values = [&] {
    matrix basis(Q, N);
    for (Eigen::Index q = 0; q < Q; ++q) {
      const auto P = rhabel::quadrature::jacobi_p_all(n_basis - 1, g_i.del, g_i.gam, nodes.x[static_cast<std::size_t>(q)]);
      for (Eigen::Index n = 0; n < N; ++n) basis(q, n) = P[static_cast<std::size_t>(n)];
    }
    return basis;
  };
  if (basis_cache && gap >= g_i.half_length()) {  // separated: one panel, nodes independent of gap
    const auto key = std::make_tuple(nodes.x.size(), i_right_of_j, n_basis, g_i.del, g_i.gam);
    auto it = basis_cache->find(key);
    if (it == basis_cache->end()) it = basis_cache->emplace(key, basis_values()).first;
    return kernel_values * it->second;
  }
  return kernel_values * basis_values();
}

}  // namespace rhabel::abel::detail
