// rhabel/quadrature/detail/jacobi_graded_integral.hpp
//
// The one integration engine behind cauchy_transform.hpp and abel_integral.hpp.
//
// It computes
//
//     I = int_a^b (t - a)^ea (b - t)^eb g(t) dt ,      ea, eb > -1,
//
// where g is analytic on a neighbourhood of [a, b] except for singularities that lie at
// distance >= d_a from the end a (on a's side) and >= d_b from the end b. Typical g:
// (1 + t)^q h(t) on [x, 1] (singular at t = -1, d_a = 1 + x), h(t)/(t - z) (pole at z),
// (t - x)^(mu - 1) h(t) on [-1, 1] for x < -1 (d_a = -1 - x).
//
// Method: composite Gauss with geometric grading (Schwab; Babuska-Guo "hp" grading). The
// interval is cut into panels [a + d_a (2^k - 1), a + d_a (2^(k+1) - 1)] that double in length
// away from a (likewise from b), so that every panel has length <= its distance from the
// nearest singularity of g; the remainder at the far end is merged into the last panel when
// it is shorter than that panel, so that no Gauss-Legendre panel is longer than twice its
// distance to the far end either (where (b - t)^eb is singular). Mapped to [-1, 1], a panel then sees the singularity at distance
// >= 1 beyond its end, i.e. outside the Bernstein ellipse rho = 3 + sqrt(8) ~ 5.83, and an
// n-point Gauss rule has error O(rho^(-2n)) ~ 10^(-1.53 n) on every panel, uniformly in d_a,
// d_b (this is what makes x within 1e-12 of an end no harder than x = 0: ~log2(1/d) panels).
// The panels that touch a or b carry the end factor in their Gauss-Jacobi weight
// (exact for the algebraic singularity, any ea, eb > -1, including -0.999); on the other panels
// (t - a)^ea and (b - t)^eb are analytic and evaluated pointwise.
//
// Accuracy: with n = panel_order_for<Real>() the per-panel truncation error is below the
// unit roundoff of Real for g analytic as described and of moderate size on the ellipse;
// polynomial factors of degree K in g need about K/2 more nodes (callers add them). The
// caller obtains an error ESTIMATE by comparing two orders (see graded_estimate).
//
// Distances are passed to g as the pair (u, v) = (t - a, b - t), each computed without
// cancellation from the panel's nearer end, so that g can evaluate (1 + t)^q etc. to full
// relative accuracy even when t is 1e-12 from an end.
#pragma once

#include "rhabel/quadrature/gauss_jacobi.hpp"

#include <boost/math/tools/precision.hpp>

#include <cmath>
#include <cstddef>
#include <deque>
#include <limits>
#include <vector>

namespace rhabel::quadrature::detail {

/// Gauss nodes per panel that reach the unit roundoff of Real for the ratio-1 panels above:
/// rho^(-2n) <= eps with rho = 5.83 gives n >= digits10 / 1.53; +3 nodes of margin.
template <class Real>
std::size_t panel_order_for() {
  const int digits10 = std::numeric_limits<Real>::digits10 > 0 ? std::numeric_limits<Real>::digits10 : 15;
  return static_cast<std::size_t>(digits10 * 2 / 3 + 4);
}

/// gauss_jacobi<Real>(n, p, q) through a small per-thread cache (the graded integrals ask for
/// the same few rules at every call; building one costs O(n^2)). Returns a copy, so no
/// reference into the cache outlives an eviction. FIFO of 64 entries.
template <class Real>
quadrature_rule<Real> cached_gauss_jacobi(std::size_t n, const Real& p, const Real& q) {
  struct entry {
    std::size_t n;
    Real p, q;
    quadrature_rule<Real> rule;
  };
  thread_local std::deque<entry> cache;
  for (const auto& e : cache)
    if (e.n == n && e.p == p && e.q == q) return e.rule;
  quadrature_rule<Real> rule = gauss_jacobi<Real>(n, p, q);
  if (cache.size() >= 64) cache.pop_front();
  cache.push_back({n, p, q, rule});
  return rule;
}

/// One panel [off, off + length], measured from the end a (from_a = true) or from b.
template <class Real>
struct graded_panel {
  bool from_a;
  Real offset;  ///< distance of the panel's near edge from its end (a or b)
  Real length;
  bool touches_a, touches_b;
};

/// Panel partition of [a, b] (length L = b - a > 0) graded towards a with scale d_a and
/// towards b with scale d_b (pass +inf for no grading). If both ends are graded, each grading
/// covers half of the interval.
template <class Real>
std::vector<graded_panel<Real>> graded_panels(const Real& L, const Real& d_a, const Real& d_b) {
  using std::isfinite;
  std::vector<graded_panel<Real>> panels;
  const bool grade_a = isfinite(d_a) && d_a < L;
  const bool grade_b = isfinite(d_b) && d_b < L;
  if (!grade_a && !grade_b) {
    panels.push_back({true, Real(0), L, true, true});
    return panels;
  }
  // Offsets of the breakpoints from one end, up to `limit`.
  auto breakpoints = [](const Real& d, const Real& limit) {
    std::vector<Real> s{Real(0)};
    Real next = d;
    while (next < limit) {
      s.push_back(next);
      next = 2 * next + d;  // d (2^(k+1) - 1)
    }
    // If the remainder up to `limit` is shorter than the last panel, merge it into that panel:
    // otherwise the last full panel would be longer than its distance to the far end, where
    // an algebraic end factor (evaluated pointwise on that panel) is singular.
    if (s.size() >= 2 && limit - s.back() < s.back() - s[s.size() - 2]) s.pop_back();
    s.push_back(limit);
    return s;
  };
  if (grade_a && grade_b) {
    const Real half = L / 2;
    const auto sa = breakpoints(d_a, half);
    const auto sb = breakpoints(d_b, L - half);
    for (std::size_t k = 0; k + 1 < sa.size(); ++k)
      panels.push_back({true, sa[k], sa[k + 1] - sa[k], k == 0, false});
    for (std::size_t k = sb.size() - 1; k-- > 0;)
      panels.push_back({false, sb[k], sb[k + 1] - sb[k], false, k == 0});
  } else if (grade_a) {
    const auto sa = breakpoints(d_a, L);
    for (std::size_t k = 0; k + 1 < sa.size(); ++k)
      panels.push_back({true, sa[k], sa[k + 1] - sa[k], k == 0, k + 2 == sa.size()});
  } else {
    const auto sb = breakpoints(d_b, L);
    for (std::size_t k = sb.size() - 1; k-- > 0;)
      panels.push_back({false, sb[k], sb[k + 1] - sb[k], k + 2 == sb.size(), k == 0});
  }
  return panels;
}

/// int_a^b (t-a)^ea (b-t)^eb g(u, v) dt with u = t - a, v = b - t (L = b - a), n nodes per panel.
/// Result type follows g (Real or std::complex<Real>).
template <class Real, class G>
auto graded_jacobi_integral(const Real& L, const Real& ea, const Real& eb, const Real& d_a, const Real& d_b,
                            std::size_t n, G&& g) -> decltype(g(Real(0), Real(0))) {
  using std::pow;
  using Result = decltype(g(Real(0), Real(0)));
  const auto panels = graded_panels(L, d_a, d_b);
  // Reference rules on [-1, 1]; weight (1 - x)^p (1 + x)^q, so "touches a" is the q slot.
  const quadrature_rule<Real> legendre = cached_gauss_jacobi<Real>(n, Real(0), Real(0));
  quadrature_rule<Real> rule_a, rule_b, rule_ab;
  Result total = Result(0);
  for (const auto& panel : panels) {
    const quadrature_rule<Real>* rule = &legendre;
    if (panel.touches_a && panel.touches_b) {
      if (rule_ab.size() == 0) rule_ab = cached_gauss_jacobi<Real>(n, eb, ea);
      rule = &rule_ab;
    } else if (panel.touches_a) {
      if (rule_a.size() == 0) rule_a = cached_gauss_jacobi<Real>(n, Real(0), ea);
      rule = &rule_a;
    } else if (panel.touches_b) {
      if (rule_b.size() == 0) rule_b = cached_gauss_jacobi<Real>(n, eb, Real(0));
      rule = &rule_b;
    }
    const Real half = panel.length / 2;
    // Jacobian (half)^(1 + exponents carried by the rule's weight).
    Real scale = half;
    if (panel.touches_a && ea != 0) scale *= pow(half, ea);
    if (panel.touches_b && eb != 0) scale *= pow(half, eb);
    Result sum = Result(0);
    for (std::size_t i = 0; i < rule->size(); ++i) {
      Real u, v;
      if (panel.from_a) {
        u = panel.offset + half * rule->x_minus_lo[i];
        v = L - u;
        if (panel.touches_b) v = half * rule->hi_minus_x[i];  // single panel: v from b directly
      } else {
        v = panel.offset + half * rule->hi_minus_x[i];
        u = L - v;
        if (panel.touches_a) u = half * rule->x_minus_lo[i];
      }
      Real factor = rule->weight[i];
      if (!panel.touches_a && ea != 0) factor *= pow(u, ea);
      if (!panel.touches_b && eb != 0) factor *= pow(v, eb);
      sum += factor * g(u, v);
    }
    total += scale * sum;
  }
  return total;
}

/// Value with an error estimate: the integral at `n` and at n + n/2 + 2 nodes per panel.
/// The estimate is |difference|, a heuristic (not a bound): with geometric convergence it
/// overestimates the error of the higher-order value, which is the one returned.
template <class Result, class Real>
struct graded_result {
  Result value;
  Real error_estimate;
  std::size_t evaluations;
};

template <class Real, class G>
auto graded_estimate(const Real& L, const Real& ea, const Real& eb, const Real& d_a, const Real& d_b,
                     std::size_t n, G&& g) {
  using std::abs;
  using Result = decltype(g(Real(0), Real(0)));
  std::size_t count = 0;
  auto counted = [&](const Real& u, const Real& v) {
    ++count;
    return g(u, v);
  };
  const Result low = graded_jacobi_integral(L, ea, eb, d_a, d_b, n, counted);
  const Result high = graded_jacobi_integral(L, ea, eb, d_a, d_b, n + n / 2 + 2, counted);
  return graded_result<Result, Real>{high, Real(abs(high - low)), count};
}

}  // namespace rhabel::quadrature::detail
