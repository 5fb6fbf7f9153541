// rhabel/abel/far_field.hpp: the action of many disjoint intervals' densities on one
// another through the smooth far field of the kernel, in O(K p^2) operations and O(K p^2) numbers
// for K intervals (a one-dimensional interpolative fast multipole method). Used by
// abel::solve_union (multi_interval.hpp) from multi_solve_options::iterative_from intervals on,
// and by the punch layer for the data of its coupled solve.
//
// THE SUM. For densities g_i on sorted disjoint intervals I_i (the LEAVES) and a point s of I_j,
//     far_j(s) = sum over i "well separated" from j of int_{I_i} K(t - s) g_i(t) dt,
// K the cross kernel of multi_interval.hpp, (t - s)^(alpha - 1) for t > s and
// -kappa (s - t)^(alpha - 1) for t < s; the other pairs (near_leaves) the caller couples directly.
//
// THE TREE. A binary tree on the leaves in their order (a node: a run of consecutive intervals,
// its box [lo of the first, hi of the last]; split at the middle index). Two boxes S and T are
// ADMISSIBLE when their gap is at least eta = 1 times the larger width. Every pair of leaves is
// covered exactly once: by one admissible pair of boxes containing them (found by the usual dual
// traversal: split the wider box until the pair is admissible or both are leaves), or else it is
// a near pair of leaves. On a row of equal intervals at any pitch a node meets at most ~3
// admissible partners, so there are O(K) pairs and O(K) near pairs.
//
// THE EXPANSIONS. Every box carries p Chebyshev points of the first kind (p = order()).
//   * moments (source side): W_l(S) = int over the sources in S of l_l^S(t) g(t) dt, l_l^S the
//     Lagrange polynomials of S's points. A leaf's moments come from its density (moment_matrix:
//     exact Gauss-Jacobi quadrature of w P_n l_l); a parent's from its children exactly (l_l^S
//     restricted to a child is a polynomial of degree p - 1, which the child's p points
//     interpolate exactly): W(S) = sum_children T_c W(c), T_c(l, m) = l_l^S(child point m).
//   * interactions: for an admissible pair, K(t - s) is interpolated in t on S and in s on T,
//     so the field of S at T's points is sum_l K(tau_l - sigma_k) W_l(S) (one p x p matrix of
//     kernel values per pair, computed without cancellation from the distances to the facing ends).
//   * local values (target side): the far field at T's points; a child receives its parent's by
//     interpolation (the transpose of T_c), and a leaf's far field at any s is the interpolant
//     of its local values (barycentric formula).
// ACCURACY (an a priori estimate; tests/abel/test_far_field.cpp measures it against the direct
// sum). For an admissible pair the kernel is analytic in t over S's box inside the Bernstein
// ellipse through the nearest target point, 2 eta half-widths beyond the box: parameter
// rho = 1 + 2 eta + sqrt(2 eta (2 + 2 eta)) = 5.83 at eta = 1, and likewise in s. The
// interpolation error of each variable falls like rho^-p: p = 26 makes it ~eps/100 of the kernel's
// size at the nearest point with the 10 % of the ellipse kept off the singularity as in
// cross_nodes.hpp's separated_cross_nodes. order_for(tolerance) takes the p for a looser
// relative tolerance (the punch layer asks 1e-3 of its requested tolerance).
// ONE TREE, MOVING INTERVALS. far_field(boxes, intervals) reuses a built tree for densities on
// intervals inside its leaf boxes (the exact re-expansion at that constructor), so that a caller
// whose intervals move a little (the edges of a Newton iteration) pays for the kernel matrices once.
// COST per far_values call: (number of boxes + admissible pairs) p^2 multiply-adds; building the
// pairs' kernel matrices costs p^2 kernel evaluations per pair (the only powers).
#pragma once

#include "rhabel/abel/abel_operator.hpp"
#include "rhabel/abel/numerics.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace rhabel::abel {

/// Cross-term kernel for t in I_i, s outside I_i: (t-s)^(alpha-1) for t > s, -kappa (s-t)^(alpha-1) for t < s.
template <class Real>
Real cross_kernel(const abel_parameters<Real>& par, const Real& t_minus_s) {
  using std::pow;
  if (t_minus_s > 0) return pow(t_minus_s, par.alpha() - 1);
  return -par.kappa() * pow(-t_minus_s, par.alpha() - 1);
}

template <class Real>
class far_field {
 public:
  using matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  using vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;

  struct box {
    Real lo, hi;
  };

  /// Admissibility: gap >= eta x the larger width (the header).
  static constexpr double eta = 1.0;

  /// Points per box for a relative accuracy `tolerance` of the far field (the header's estimate,
  /// rho^(0.9 p) >= 100/tolerance at eta = 1), between 8 and 26 (26: eps/100 in double).
  static std::size_t order_for(double tolerance) {
    const double rho = 1 + 2 * eta + std::sqrt(2 * eta * (2 + 2 * eta));
    const double eps = static_cast<double>(std::numeric_limits<Real>::epsilon());
    const double target = std::max(tolerance, eps);
    const auto p = static_cast<std::size_t>(std::ceil(std::log(100 / target) / (0.9 * std::log(rho))));
    return std::clamp<std::size_t>(p, 8, 26);
  }

  /// leaves: sorted disjoint intervals; p points per box (order_for); the cross kernel of par.
  far_field(const abel_parameters<Real>& par, const std::vector<box>& leaves, std::size_t p)
      : far_field([par](const Real& t_minus_s) { return cross_kernel(par, t_minus_s); }, leaves, p) {}

  /// The same for another kernel k(t - s), analytic off t = s (the punch layer's displacement
  /// kernel Psi, whose interpolation error obeys the same estimate). with_pairs = false: only
  /// the tree and its transfers, for at_point (no admissible pairs, near lists or their kernel
  /// matrices: far_values and near_leaves are then not available).
  far_field(std::function<Real(const Real&)> kernel, const std::vector<box>& leaves, std::size_t p,
            bool with_pairs = true)
      : kernel_(std::move(kernel)), grid_(p), leaf_node_(leaves.size()) {
    using std::sin;
    const Real pi = boost::math::constants::pi<Real>();
    bary_.resize(p);
    for (std::size_t k = 0; k < p; ++k)
      bary_[k] = (k % 2 == 0 ? Real(1) : Real(-1)) * sin(pi * (Real(k) + Real(0.5)) / Real(p));
    if (leaves.empty()) return;
    build(leaves, 0, leaves.size(), -1);
    auto transfers = std::make_shared<std::vector<matrix>>();
    for (std::size_t n = 1; n < nodes_.size(); ++n) transfers->push_back(transfer(nodes_[n].parent, n));
    transfer_ = std::move(transfers);
    near_.assign(leaves.size(), {});
    auto pairs = std::make_shared<std::vector<pair>>();
    if (with_pairs) interact(0, 0, *pairs);
    pairs_ = std::move(pairs);
    for (auto& list : near_) std::sort(list.begin(), list.end());
  }

  /// The far field of `boxes`' tree for densities on other intervals, interval i inside box i
  /// (covers()): the boxes, admissible pairs, near lists and kernel matrices are shared with
  /// `boxes`, not recomputed (the punch layer keeps one tree while a Newton run moves the edges
  /// inside it). Exact re-expansion, no new approximation: box i's Lagrange polynomials restricted
  /// to interval i are polynomials of degree p - 1, which interval i's own p points interpolate
  /// exactly, so its moments enter box i by inner(l, m) = l_l^box(point m of the interval) and the
  /// box's local values reach the interval's points by the transpose (as a child's do). Moments
  /// (moment_matrix, density_moments), local values (far_values) and reference coordinates
  /// (interpolation, interpolate) are then those of the intervals; admissibility, near_leaves and
  /// the accuracy estimate are the boxes' (a target point of interval i lies in box i).
  far_field(const far_field& boxes, const std::vector<box>& intervals) : far_field(boxes) {
    if (!boxes.covers(intervals))
      throw std::invalid_argument("rhabel::abel::far_field: every interval must lie inside its box (covers())");
    interval_ = intervals;
    inner_.assign(intervals.size(), matrix());
    const std::size_t p = order();
    std::vector<Real> l(p);
    for (std::size_t i = 0; i < intervals.size(); ++i) {
      const auto& B = nodes_[leaf_node_[i]];
      if (intervals[i].lo == B.lo && intervals[i].hi == B.hi) continue;
      const Real hb = half_width(leaf_node_[i]), hi = (intervals[i].hi - intervals[i].lo) / 2;
      const Real offset = intervals[i].lo - B.lo;
      matrix& T = inner_[i];
      T.resize(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(p));
      for (std::size_t m = 0; m < p; ++m) {
        lagrange((offset + hi * grid_.one_plus_x[m]) / hb - 1, l.data());
        for (std::size_t k = 0; k < p; ++k) T(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(m)) = l[k];
      }
    }
  }

  /// Whether every interval lies inside its box (as many intervals as leaves, in their order).
  bool covers(const std::vector<box>& intervals) const {
    if (intervals.size() != leaf_node_.size()) return false;
    for (std::size_t i = 0; i < intervals.size(); ++i) {
      const auto& B = nodes_[leaf_node_[i]];
      if (!(intervals[i].lo >= B.lo && intervals[i].hi <= B.hi && intervals[i].lo < intervals[i].hi)) return false;
    }
    return true;
  }

  std::size_t order() const { return grid_.x.size(); }
  std::size_t leaves() const { return leaf_node_.size(); }
  /// near_leaves(j): the leaves i != j whose action on j is NOT in far_values (sorted).
  const std::vector<std::size_t>& near_leaves(std::size_t j) const { return near_[j]; }
  /// Number of admissible pairs (each one p x p kernel matrix).
  std::size_t pairs() const { return pairs_ ? pairs_->size() : 0; }

  /// S(l, n) = int_{I_i} l_l(t) w(t) P_n^(del, gam)(x(t)) dt, n < count: leaf i's moments of a
  /// Jacobi series are S c. Gauss-Jacobi with (p + count)/2 + 1 nodes, exact for the degree
  /// p - 1 + count - 1 polynomial.
  /// The reference part (h = 1) is computed once per (del, gam, count) and kept (a leaf's is h
  /// times it); not for concurrent use of one far_field.
  matrix moment_matrix(std::size_t i, const Real& del, const Real& gam, std::size_t count) const {
    const auto key = std::make_tuple(del, gam, count);
    auto it = reference_moments_.find(key);
    if (it == reference_moments_.end()) it = reference_moments_.emplace(key, reference_moment_matrix(del, gam, count)).first;
    return leaf_half_width(i) * it->second;
  }

  /// Leaf i's moments of a Jacobi density on it: moment_matrix times its coefficients (zero for
  /// an empty series).
  vector density_moments(std::size_t i, const jacobi_density<Real>& g) const {
    const auto& c = g.coefficients;
    if (c.empty()) return vector::Zero(static_cast<Eigen::Index>(order()));
    return moment_matrix(i, g.del, g.gam, c.size()) * Eigen::Map<const vector>(c.data(), static_cast<Eigen::Index>(c.size()));
  }

  /// Every box's moments from the leaves' (the upward pass; input of at_point).
  std::vector<vector> upward(const std::vector<vector>& leaf_moments) const {
    const auto P = static_cast<Eigen::Index>(order());
    std::vector<vector> W(nodes_.size(), vector::Zero(P));
    for (std::size_t i = 0; i < leaf_node_.size(); ++i)
      W[leaf_node_[i]] = inner(i) ? vector(inner_[i] * leaf_moments[i]) : leaf_moments[i];
    for (std::size_t n = nodes_.size(); n-- > 1;) W[nodes_[n].parent].noalias() += (*transfer_)[n - 1] * W[n];
    return W;
  }

  /// The sum at ONE point x (anywhere) by the tree alone, without local values: the boxes
  /// admissible for x (gap to x >= eta x width) through their moments (p kernel values each),
  /// every other leaf i by direct(i) (the caller's own quadrature, or 0 for a leaf it excludes).
  /// O(p log K) kernel values per point (a treecode): for points off the leaves or few points.
  template <class Direct>
  Real at_point(const std::vector<vector>& box_moments, const Real& x, Direct&& direct) const {
    const std::size_t p = order();
    Real sum = 0;
    std::vector<std::size_t> stack{0};
    while (!stack.empty()) {
      const std::size_t n = stack.back();
      stack.pop_back();
      const auto& B = nodes_[n];
      const Real h = half_width(n);
      const bool right = B.lo > x, left = B.hi < x;  // the box lies right / left of x
      const Real gap = right ? B.lo - x : (left ? x - B.hi : Real(-1));
      if (gap >= Real(eta) * 2 * h) {
        for (std::size_t l = 0; l < p; ++l) {
          const Real d = right ? gap + h * grid_.one_plus_x[l] : -(gap + h * grid_.one_minus_x[l]);
          sum += kernel_(d) * box_moments[n][static_cast<Eigen::Index>(l)];
        }
      } else if (B.leaf()) {
        sum += direct(B.first);
      } else {
        stack.push_back(static_cast<std::size_t>(B.child[0]));
        stack.push_back(static_cast<std::size_t>(B.child[1]));
      }
    }
    return sum;
  }

  /// The far field's values at every leaf's p points from every leaf's moments (header).
  std::vector<vector> far_values(const std::vector<vector>& leaf_moments) const {
    const auto P = static_cast<Eigen::Index>(order());
    const std::vector<vector> W = upward(leaf_moments);
    std::vector<vector> L(nodes_.size(), vector::Zero(P));
    for (const auto& pr : *pairs_) L[pr.target].noalias() += pr.kernel * W[pr.source];
    for (std::size_t n = 1; n < nodes_.size(); ++n)
      L[n].noalias() += (*transfer_)[n - 1].transpose() * L[nodes_[n].parent];
    std::vector<vector> out(leaf_node_.size());
    for (std::size_t i = 0; i < leaf_node_.size(); ++i)
      out[i] = inner(i) ? vector(inner_[i].transpose() * L[leaf_node_[i]]) : std::move(L[leaf_node_[i]]);
    return out;
  }

  /// Interpolation matrix E (m x p) of the local values at reference points x of a leaf.
  matrix interpolation(const std::vector<Real>& x) const {
    const std::size_t p = order();
    matrix E(static_cast<Eigen::Index>(x.size()), static_cast<Eigen::Index>(p));
    std::vector<Real> l(p);
    for (std::size_t m = 0; m < x.size(); ++m) {
      lagrange(x[m], l.data());
      for (std::size_t k = 0; k < p; ++k) E(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(k)) = l[k];
    }
    return E;
  }

  /// The interpolant of a leaf's local values at reference coordinate x.
  Real interpolate(const vector& values, const Real& x) const {
    std::vector<Real> l(order());
    lagrange(x, l.data());
    Real sum = 0;
    for (std::size_t k = 0; k < l.size(); ++k) sum += l[k] * values[static_cast<Eigen::Index>(k)];
    return sum;
  }

 private:
  struct node {
    std::size_t first, last;  // leaves [first, last)
    Real lo, hi;
    long parent;
    long child[2] = {-1, -1};
    bool leaf() const { return child[0] < 0; }
  };
  struct pair {
    std::size_t target, source;
    matrix kernel;  // (k, l) = K(tau_l(source) - sigma_k(target))
  };

  Real half_width(std::size_t n) const { return (nodes_[n].hi - nodes_[n].lo) / 2; }
  /// Whether leaf i's interval is smaller than its box (the far_field(boxes, intervals) form).
  bool inner(std::size_t i) const { return i < inner_.size() && inner_[i].size() > 0; }
  /// Half width of leaf i's interval.
  Real leaf_half_width(std::size_t i) const {
    return inner(i) ? (interval_[i].hi - interval_[i].lo) / 2 : half_width(leaf_node_[i]);
  }

  /// moment_matrix on [-1, 1] (h = 1).
  matrix reference_moment_matrix(const Real& del, const Real& gam, std::size_t count) const {
    const std::size_t p = order();
    const auto rule = cached_gauss_jacobi_rule<Real>((p + count) / 2 + 1, del, gam);
    matrix S = matrix::Zero(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(count));
    std::vector<Real> l(p);
    for (std::size_t q = 0; q < rule->size(); ++q) {
      lagrange(rule->x[q], l.data());
      const auto P = rhabel::quadrature::jacobi_p_all(count == 0 ? 0 : count - 1, del, gam, rule->x[q]);
      for (std::size_t n = 0; n < count; ++n)
        for (std::size_t k = 0; k < p; ++k)
          S(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(n)) += rule->weight[q] * l[k] * P[n];
    }
    return S;
  }

  std::size_t build(const std::vector<box>& leaves, std::size_t first, std::size_t last, long parent) {
    const std::size_t n = nodes_.size();
    nodes_.push_back({first, last, leaves[first].lo, leaves[last - 1].hi, parent});
    if (last - first == 1) {
      leaf_node_[first] = n;
      return n;
    }
    const std::size_t mid = first + (last - first) / 2;
    const std::size_t left = build(leaves, first, mid, static_cast<long>(n));
    const std::size_t right = build(leaves, mid, last, static_cast<long>(n));
    nodes_[n].child[0] = static_cast<long>(left);
    nodes_[n].child[1] = static_cast<long>(right);
    return n;
  }

  /// Lagrange polynomials of the reference grid at x (barycentric formula of the first kind's
  /// points; exact 0/1 at a node).
  void lagrange(const Real& x, Real* l) const {
    const std::size_t p = order();
    Real sum = 0;
    for (std::size_t k = 0; k < p; ++k) {
      const Real d = x - grid_.x[k];
      if (d == 0) {
        std::fill(l, l + p, Real(0));
        l[k] = 1;
        return;
      }
      l[k] = bary_[k] / d;
      sum += l[k];
    }
    for (std::size_t k = 0; k < p; ++k) l[k] /= sum;
  }

  /// T(l, m) = l_l^parent(point m of child).
  matrix transfer(long parent, std::size_t child) const {
    const std::size_t p = order();
    const auto pa = static_cast<std::size_t>(parent);
    const Real hp = half_width(pa), hc = half_width(child), offset = nodes_[child].lo - nodes_[pa].lo;
    matrix T(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(p));
    std::vector<Real> l(p);
    for (std::size_t m = 0; m < p; ++m) {
      lagrange((offset + hc * grid_.one_plus_x[m]) / hp - 1, l.data());
      for (std::size_t k = 0; k < p; ++k) T(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(m)) = l[k];
    }
    return T;
  }

  bool admissible(std::size_t a, std::size_t b) const {
    const auto& A = nodes_[a];
    const auto& B = nodes_[b];
    const Real gap = A.lo > B.hi ? A.lo - B.hi : B.lo - A.hi;
    return gap >= Real(eta) * std::max(A.hi - A.lo, B.hi - B.lo);
  }

  /// Kernel values between the points of source box s and target box t, from the distances to
  /// the facing ends (no cancellation in t - s).
  matrix kernel(std::size_t t, std::size_t s) const {
    const std::size_t p = order();
    const auto& T = nodes_[t];
    const auto& S = nodes_[s];
    const bool right = S.lo > T.hi;
    const Real gap = right ? S.lo - T.hi : T.lo - S.hi;
    const Real hs = half_width(s), ht = half_width(t);
    matrix K(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(p));
    for (std::size_t l = 0; l < p; ++l)
      for (std::size_t k = 0; k < p; ++k) {
        const Real d = right ? hs * grid_.one_plus_x[l] + gap + ht * grid_.one_minus_x[k]
                             : -(hs * grid_.one_minus_x[l] + gap + ht * grid_.one_plus_x[k]);
        K(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l)) = kernel_(d);
      }
    return K;
  }

  /// The dual traversal (header): target box t, source box s.
  void interact(std::size_t t, std::size_t s, std::vector<pair>& pairs) {
    const auto& T = nodes_[t];
    const auto& S = nodes_[s];
    if (t == s) {
      if (T.leaf()) return;
      for (long a : T.child)
        for (long b : T.child) interact(static_cast<std::size_t>(a), static_cast<std::size_t>(b), pairs);
      return;
    }
    if (admissible(t, s)) {
      pairs.push_back({t, s, kernel(t, s)});
      return;
    }
    if (T.leaf() && S.leaf()) {
      near_[T.first].push_back(S.first);
      return;
    }
    const bool split_target = S.leaf() || (!T.leaf() && T.hi - T.lo >= S.hi - S.lo);
    if (split_target) {
      for (long c : T.child) interact(static_cast<std::size_t>(c), s, pairs);
    } else {
      for (long c : S.child) interact(t, static_cast<std::size_t>(c), pairs);
    }
  }

  std::function<Real(const Real&)> kernel_;
  chebyshev_grid<Real> grid_;
  std::vector<Real> bary_;
  std::vector<node> nodes_;
  std::vector<std::size_t> leaf_node_;
  // Shared between far_field(boxes, intervals) copies: the tree's matrices (the kernel values
  // are most of a build's cost).
  std::shared_ptr<const std::vector<matrix>> transfer_ = std::make_shared<const std::vector<matrix>>();  // [n - 1]: n to its parent
  std::shared_ptr<const std::vector<pair>> pairs_ = std::make_shared<const std::vector<pair>>();
  std::vector<box> interval_;  // far_field(boxes, intervals): leaf i's interval
  std::vector<matrix> inner_;  // ... and its re-expansion into box i (empty: the interval is the box)
  std::vector<std::vector<std::size_t>> near_;
  mutable std::map<std::tuple<Real, Real, std::size_t>, matrix> reference_moments_;
};

}  // namespace rhabel::abel
