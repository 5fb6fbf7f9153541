// rhabel/abel/numerics.hpp: numerical kernels of the abel module that the punch layer uses as
// well: Jacobi polynomial values for any exponents, cached Gauss-Jacobi rules, Chebyshev
// interpolation at the points of the first kind, and a composite quadrature graded toward
// singularities outside the interval. Real: float, double, long double or a Boost.Multiprecision
// floating-point type.
//
//  * plain_jacobi_values(n, p, q, x): P_0(x), ..., P_n(x) of P^(p,q) by the forward three-term
//    recurrence (DLMF 18.9.1-2), for ANY real p, q with p + q != -2, -3, ... (also p, q <= -1,
//    where quadrature::jacobi_p_all refuses: the weight is not integrable, the polynomials exist).
//    Accuracy: the recurrence's, a few eps times the size of the largest P_k(x) in the interior;
//    near x = +-1 at large n prefer quadrature::jacobi_p_all (difference forms) when p, q > -1.
//  * cached_gauss_jacobi_rule(n, p, q): quadrature::gauss_jacobi(n, p, q) (accuracy: that
//    function's, nodes and weights to a few eps) from a process-wide thread-safe cache.
//  * chebyshev_grid(m), chebyshev_coefficients(f): the m Chebyshev points of the first kind,
//    x_j = cos(pi (j + 1/2)/m), with 1 -+ x_j free of cancellation, and the coefficients
//    a_0..a_{m-1} of the polynomial interpolating values f_j there, f ~ sum_k a_k T_k (Trefethen,
//    "Approximation Theory and Approximation Practice", SIAM 2013, chapters 3-4). O(m^2)
//    operations with correctly rounded cosines: each a_k is within ~eps m max|f_j| of exact.
//  * panel_integrator(p, q, nodes): int_0^len (len - u)^p u^q f(u, len - u) du for p, q > -1 and
//    f with singularities at known distances d_left, d_right outside [0, len]: geometric panels
//    (ratio 2) toward each near singularity, Gauss-Jacobi (quadrature::gauss_jacobi) on the
//    panels that touch an end, Gauss-Legendre elsewhere. A singularity at distance d from an end
//    sits 3 panel half-widths from the centre of every panel, so each panel converges like
//    (3 + sqrt 8)^(-2 nodes) (the Bernstein ellipse through the singularity; Trefethen, chapter
//    19): 16 nodes give ~ 1e-24 relative to the integrand's size, 24 nodes reach double rounding
//    with a wide margin.
#pragma once

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <boost/math/constants/constants.hpp>

#include <cmath>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <utility>
#include <vector>

namespace rhabel::abel {

/// P_0(x), ..., P_n(x) of P^(p,q) by the plain forward three-term recurrence, for ANY real p, q
/// with p + q != -2, -3, ... (no difference forms near the ends, no exponent check).
template <class Real>
std::vector<Real> plain_jacobi_values(std::size_t n, const Real& p, const Real& q, const Real& x) {
  std::vector<Real> v(n + 1);
  v[0] = 1;
  if (n >= 1) v[1] = (p + q + 2) / 2 * x + (p - q) / 2;
  for (std::size_t k = 1; k < n; ++k) {
    const auto r = rhabel::quadrature::detail::jacobi_recurrence_coefficients(k, p, q);
    v[k + 1] = (r.A * x + r.B) * v[k] - r.C * v[k - 1];
  }
  return v;
}

/// quadrature::gauss_jacobi(n, p, q) from a process-wide cache keyed by (n, p, q) (exact keys: the
/// rule depends on the exact exponents). Building a rule costs O(n^2)-O(n^3) operations
/// (quadrature::gauss_jacobi); the abel quadratures (panel_integrator, jacobi_density::integrate,
/// abel_operator::apply outside [lo, hi], the enrichment of step_enrichment.hpp) need the same few
/// rules thousands of times per solve. Thread-safe (one mutex; the rules are immutable and
/// shared). The cache is emptied when it holds more than 512 rules, so memory stays bounded when
/// the exponents sweep a continuum (a rule of n nodes holds 4n numbers).
template <class Real>
std::shared_ptr<const rhabel::quadrature::quadrature_rule<Real>> cached_gauss_jacobi_rule(std::size_t n, const Real& p,
                                                                                         const Real& q) {
  using rule_type = rhabel::quadrature::quadrature_rule<Real>;
  static std::mutex mutex;
  static std::map<std::tuple<std::size_t, Real, Real>, std::shared_ptr<const rule_type>> cache;
  const auto key = std::make_tuple(n, p, q);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  // Built outside the lock (two threads may build the same rule once each; both are identical).
  auto rule = std::make_shared<const rule_type>(rhabel::quadrature::gauss_jacobi<Real>(n, p, q));
  const std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() >= 512) cache.clear();
  return cache.emplace(key, std::move(rule)).first->second;
}

/// Chebyshev points of the first kind x_j = cos(pi (j + 1/2)/m), j = 0..m-1, with 1 -+ x_j
/// computed as 2 sin^2 / 2 cos^2 of the half angle (no cancellation near the ends).
template <class Real>
struct chebyshev_grid {
  std::vector<Real> x, one_minus_x, one_plus_x;
  explicit chebyshev_grid(std::size_t m) : x(m), one_minus_x(m), one_plus_x(m) {
    using std::cos;
    using std::sin;
    const Real pi = boost::math::constants::pi<Real>();
    for (std::size_t j = 0; j < m; ++j) {
      const Real theta = pi * (Real(j) + Real(0.5)) / Real(m);
      x[j] = cos(theta);
      const Real s = sin(theta / 2), c = cos(theta / 2);
      one_minus_x[j] = 2 * s * s;
      one_plus_x[j] = 2 * c * c;
    }
  }
};

/// A process-wide thread-safe cache of immutable tables keyed by `Key`, built by `build` on first
/// use (outside the lock: two threads may build the same table once each; both are identical).
/// Emptied when the entries' sizes (size() of each table) add up to more than `max_total`, so
/// memory stays bounded when the keys sweep a continuum.
template <class Table, class Key, class Build>
std::shared_ptr<const Table> cached_table(const Key& key, Build&& build, std::size_t max_total) {
  static std::mutex mutex;
  static std::map<Key, std::shared_ptr<const Table>> cache;
  static std::size_t total = 0;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  auto table = std::make_shared<const Table>(build());
  const std::lock_guard<std::mutex> lock(mutex);
  if (total + table->size() > max_total) cache.clear(), total = 0;
  const auto [it, inserted] = cache.emplace(key, std::move(table));
  if (inserted) total += it->second->size();
  return it->second;
}

/// Chebyshev coefficients a_0..a_{m-1} of the interpolant of values f_j at chebyshev_grid(m).
/// T_k(x_j) = cos(pi k (2j+1)/(2m)) is taken from a table of cos(pi r/(2m)) at r = k (2j+1)
/// modulo 4m: every entry is a correctly rounded cosine (no recurrence drift). The m x m matrix
/// of those entries is built once per m (cached_table, up to 2^23 entries in all: the solvers
/// use a few m, each up to ~1000), so that a call passes over contiguous rows, four at a time (m =
/// 513: 241 -> ~80 us); each sum takes the same products in the same order as entry by entry.
template <class Real>
std::vector<Real> chebyshev_coefficients(const std::vector<Real>& f) {
  using std::cos;
  const std::size_t m = f.size();
  const auto matrix = cached_table<std::vector<Real>>(m, [m] {
    const Real pi = boost::math::constants::pi<Real>();
    const std::size_t period = 4 * m;
    std::vector<Real> table(period);
    for (std::size_t r = 0; r < period; ++r) table[r] = cos(pi * Real(r) / Real(2 * m));
    std::vector<Real> out(m * m);
    for (std::size_t k = 0; k < m; ++k)
      for (std::size_t j = 0; j < m; ++j) out[k * m + j] = table[(k * (2 * j + 1)) % period];
    return out;
  }, std::size_t(1) << 23);
  std::vector<Real> sums(m, Real(0));
  // Four rows at a time: four independent sums, each still in the order of j.
  std::size_t k = 0;
  for (; k + 4 <= m; k += 4) {
    const Real *r0 = matrix->data() + k * m, *r1 = r0 + m, *r2 = r1 + m, *r3 = r2 + m;
    Real s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    for (std::size_t j = 0; j < m; ++j) {
      s0 += f[j] * r0[j];
      s1 += f[j] * r1[j];
      s2 += f[j] * r2[j];
      s3 += f[j] * r3[j];
    }
    sums[k] = s0, sums[k + 1] = s1, sums[k + 2] = s2, sums[k + 3] = s3;
  }
  for (; k < m; ++k) {
    const Real* row = matrix->data() + k * m;
    Real sum = 0;
    for (std::size_t j = 0; j < m; ++j) sum += f[j] * row[j];
    sums[k] = sum;
  }
  std::vector<Real> a(m);
  for (std::size_t i = 0; i < m; ++i) a[i] = sums[i] * (i == 0 ? Real(1) : Real(2)) / Real(m);
  return a;
}

/// Composite integrator for int_0^len (len - u)^p u^q f(u, len - u) du where f may be
/// singular at u = -d_left and u = len + d_right (pass +inf when absent).
template <class Real>
class panel_integrator {
 public:
  /// The four rules come from cached_gauss_jacobi_rule: constructing an integrator is cheap
  /// after the first use of (nodes, p, q).
  panel_integrator(const Real& p, const Real& q, std::size_t nodes = 16)
      : p_(p), q_(q),
        legendre_(cached_gauss_jacobi_rule<Real>(nodes, Real(0), Real(0))),
        left_(cached_gauss_jacobi_rule<Real>(nodes, Real(0), q)),
        right_(cached_gauss_jacobi_rule<Real>(nodes, p, Real(0))),
        both_(cached_gauss_jacobi_rule<Real>(nodes, p, q)) {}

  template <class F>
  Real integrate(const Real& len, const Real& d_left, const Real& d_right, F&& f) const {
    Real sum = 0;
    for_each_node(len, d_left, d_right, [&](const Real& u, const Real& v, const Real& weight) { sum += weight * f(u, v); });
    return sum;
  }

  /// Calls visit(u, len - u, weight) for every node of the composite rule (weight includes
  /// (len-u)^p u^q and the panel scaling).
  template <class Visit>
  void for_each_node(const Real& len, const Real& d_left, const Real& d_right, Visit&& visit) const {
    visit_nodes<false>(len, d_left, d_right, visit);
  }

  /// for_each_node with the powers that the Gauss-Jacobi weights do not carry left to the
  /// visitor: visit(u, len - u, weight, q_here, p_here), where weight has the rule weight and the
  /// panel scaling, and the node's full weight is weight u^q_here (len - u)^p_here (q_here = 0 on
  /// the panel touching 0, where u^q is the rule's weight, else q; p_here likewise). For visitors
  /// that fold these powers into a detail::power_product of their own: one log each and a shared
  /// exp instead of a pow each (the quadrature of A[phi] in solve_step, ~4 powers a node).
  template <class Visit>
  void for_each_node_deferred(const Real& len, const Real& d_left, const Real& d_right, Visit&& visit) const {
    visit_nodes<true>(len, d_left, d_right, visit);
  }

 private:
  template <bool deferred, class Visit>
  void visit_nodes(const Real& len, const Real& d_left, const Real& d_right, Visit& visit) const {
    using std::pow;
    // Breakpoints as pairs (distance from 0, distance from len): 0, then d, 3d, 7d, ... (panel
    // widths doubling) up to the middle, graded toward a singularity at distance d from that end.
    const Real half = len / 2;
    const auto graded_breaks = [&half](const Real& d) {
      std::vector<Real> breaks{Real(0)};
      if (d > 0 && d < half) {
        Real w = d;
        for (Real pos = d; pos < half; w *= 2, pos += w) breaks.push_back(pos);
      }
      return breaks;
    };
    const std::vector<Real> from_left = graded_breaks(d_left);
    const std::vector<Real> from_right = graded_breaks(d_right);
    // Assemble panels [u_k, u_{k+1}] with both distances.
    struct point {
      Real left, right;
    };
    std::vector<point> pts;
    for (const auto& v : from_left) pts.push_back({v, len - v});
    for (std::size_t k = from_right.size(); k-- > 0;) pts.push_back({len - from_right[k], from_right[k]});
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      const point a = pts[k], b = pts[k + 1];
      // The width from the distances to the nearer end: the breaks graded toward len are exact as
      // distances from len and rounded as distances from 0, so b.left - a.left would be off by
      // ~eps len there, ~eps len/d relative next to a singularity at distance d from len (the
      // quadrature of A g at 1e-8 from an unbounded end was off by 1e-6 relative at alpha = 0).
      const Real width = b.right < a.left ? a.right - b.right : b.left - a.left;
      if (!(width > 0)) continue;
      const bool touches_left = k == 0, touches_right = k + 2 == pts.size();
      const auto& rule = *(touches_left ? (touches_right ? both_ : left_) : (touches_right ? right_ : legendre_));
      const Real h = width / 2;
      const Real scale = pow(h, (touches_left ? q_ : Real(0)) + (touches_right ? p_ : Real(0)) + 1);
      for (std::size_t i = 0; i < rule.size(); ++i) {
        const Real from_a = rule.x_minus_lo[i] * h, to_b = rule.hi_minus_x[i] * h;
        const Real u = a.left + from_a;              // distance from 0
        const Real v = b.right + to_b;               // distance from len
        Real weight = rule.weight[i];
        if constexpr (deferred) {
          visit(u, v, scale * weight, touches_left ? Real(0) : q_, touches_right ? Real(0) : p_);
        } else {
          if (!touches_left && q_ != 0) weight *= pow(u, q_);  // (the exponent is often exactly 0)
          if (!touches_right && p_ != 0) weight *= pow(v, p_);
          visit(u, v, scale * weight);
        }
      }
    }
  }

  Real p_, q_;
  std::shared_ptr<const rhabel::quadrature::quadrature_rule<Real>> legendre_, left_, right_, both_;
};

}  // namespace rhabel::abel
