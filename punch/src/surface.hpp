// punch/src/surface.hpp: the surface displacement of a solved scene (internal to punch/src: the
// displacement grid of report.cpp and the penetration check of the coupled contacts).
#pragma once

#include "far_action.hpp"
#include "internal.hpp"

#include "rhabel/abel.hpp"
#include "rhabel/riemann/abel_solver.hpp"

#include <boost/math/special_functions/digamma.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <utility>
#include <optional>
#include <vector>

namespace rhabel::punch::detail {

// Surface displacement w (downward positive: w = f(x) - f(a) + w(a) in contact, f the profile,
// so that outside a contact w >= f - f(a) + w(a) means the surface clears the indentor) from the
// slope field Gamma(1-alpha) A g (s) integrated in closed form in s (psi), relative to its value at
// the leading edge a_i of contact i:
//   x in contact i:        f_i(x) - f_i(a_i)                          (the indentor's profile),
//   x in another contact j: f_j(x) - f_j(a_j) + Gamma (E_j - E_i),
//   elsewhere:              Gamma (sum_o int g_o Psi(t, x) dt - E_i),
// E_k = sum_o int g_o Psi(t, a_k) dt (the datum at a_k: the own contact's integral, singular at
// t = a_k, exactly by one Gauss-Jacobi sum from alpha = 1e-2 on (Psi(t, a_k) is a power of t - a_k
// there), by closed-form moments of the logarithm at alpha = 0, else by tanh-sinh in offsets from
// its singular ends; the others' by Gauss-Jacobi). Every
// moment by Gauss-Jacobi for the regular part (smooth in t when x is off the interval) and abel's
// composite rule for the apex part. E_k is computed once, on first use. With many contacts the
// sums over contacts (height, datum, others_action) take the far ones through far_action's tree.
class surface {
 public:
  surface(const std::vector<indentor_state>& st, const context& cx)
      : st_(st), cx_(cx), omk_(cx.par.one_minus_kappa_over_alpha()), edge_(st.size()), nodes_(st.size()),
        far_nodes_(st.size()), far_kinks_(st.size()) {}

  /// f_k(to) - f_k(from): the rise of indentor k's rigid profile (each shape's closed form; a
  /// general profile's from its `value` when it has one, else int_from^to f' by Gauss-Legendre
  /// between its corners).
  double rise(std::size_t k, double from, double to) const {
    const auto& s = st_[k];
    switch (s.k) {
      case kind::parabola: {
        const double R = std::get<parabolic>(s.source->shape).radius;
        return -((to - s.apex) * (to - s.apex) - (from - s.apex) * (from - s.apex)) / (2 * R);
      }
      case kind::wedge: {
        const auto& w = std::get<wedge>(s.source->shape);
        auto f = [&](double y) { return y < s.apex ? w.slope_leading * (y - s.apex) : -w.slope_trailing * (y - s.apex); };
        return f(to) - f(from);
      }
      case kind::flat: return 0.0;
      case kind::general: {
        const auto& gp = std::get<general_profile>(s.source->shape);
        if (gp.value) return gp.value(to - s.apex) - gp.value(from - s.apex);
        // Piecewise between the corners inside (f' jumps there: one rule across a jump would be
        // first-order accurate, measured 1e-2 of the span on a sampled profile's valley).
        const auto rule_ptr = abel::cached_gauss_jacobi_rule<double>(32, 0.0, 0.0);
        const auto& rule = *rule_ptr;
        std::vector<double> cuts{from};
        for (const double c : gp.corners)
          if ((c + s.apex - from) * (c + s.apex - to) < 0) cuts.push_back(c + s.apex);
        cuts.push_back(to);
        std::sort(cuts.begin(), cuts.end(), [&](double p, double q) { return from < to ? p < q : p > q; });
        double total = 0;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
          const double lo = cuts[k], hi = cuts[k + 1];
          double sum = 0;
          for (std::size_t q = 0; q < rule.size(); ++q) sum += rule.weight[q] * own_slope(s, lo + (hi - lo) * (1 + rule.x[q]) / 2);
          total += sum * (hi - lo) / 2;
        }
        return total;
      }
    }
    return 0.0;
  }

  /// f_k(x) - f_k(a_k): the rigid profile of indentor k relative to its leading edge.
  double profile(std::size_t k, double x) const { return rise(k, st_[k].g.jacobi.lo, x); }

  /// The rigid approach of indentor i: w - f_i on its contact, w = Gamma sum_o int g_o Psi(t, x) dt
  /// (the absolute displacement of this Psi), f_i the profile with f_i(apex) = 0.
  double approach(std::size_t i) const {
    return cx_.gamma_factor * datum(i) - rise(i, st_[i].apex, st_[i].g.jacobi.lo);
  }

  /// Surface displacement at x relative to its value at a_i (see the class comment).
  double height(std::size_t i, double x) const {
    if (const auto in = in_contact(i, x)) return *in;
    const double h = psi_field().sum(x, [&](std::size_t o) { return moment(o, x); });
    return cx_.gamma_factor * (h - datum(i));
  }

  /// The surface displacement w at every x of xs in the datum of approach(): w = f_j + approach(j)
  /// on contact j (f_j with f_j(apex) = 0), heights(i, xs) + Gamma datum(i) for any i.
  std::vector<double> absolute(const std::vector<double>& xs) const {
    std::vector<double> out = heights(0, xs);
    const double base = cx_.gamma_factor * datum(0);
    for (double& w : out) w += base;
    return out;
  }

  /// sum_{j != i} A g_j (s): the other contacts' action at s (apply_outside each), the far ones
  /// through far_action's tree (many contacts).
  double others_action(std::size_t i, double s) const {
    if (!cross_)
      cross_ = std::make_unique<far_action>(st_, [par = cx_.par](const double& d) { return abel::cross_kernel(par, d); });
    return cross_->sum(s, [&](std::size_t j) { return j == i ? 0.0 : apply_outside(st_[j].g, s, cx_.par); });
  }

  /// height(i, x) at every x of xs: the same, with the moments of each contact interpolated
  /// over the samples off the contacts (moments), so that the cost per sample is a few
  /// Chebyshev sums, not a quadrature per contact.
  std::vector<double> heights(std::size_t i, const std::vector<double>& xs) const {
    return heights(xs, std::vector<std::size_t>(xs.size(), i));
  }

  /// height(reference[k], xs[k]) for every k: one pass over the contacts for all the points, each
  /// relative to its own reference contact. WHY: the penetration check refers each sample to its
  /// nearest contact; a pass per reference contact cost N^2 moment sweeps (a 1e5-sample profile,
  /// 233 contacts: 21 % of its search). Sorted xs are cheapest (moments).
  std::vector<double> heights(const std::vector<double>& xs, const std::vector<std::size_t>& reference) const {
    std::vector<double> out(xs.size());
    std::vector<double> off;  // the samples outside every contact
    std::vector<std::size_t> where;
    for (std::size_t k = 0; k < xs.size(); ++k) {
      if (const auto in = in_contact(reference[k], xs[k])) {
        out[k] = *in;
      } else {
        off.push_back(xs[k]);
        where.push_back(k);
      }
    }
    std::vector<double> sum(off.size(), 0.0), part;
    for (std::size_t o = 0; o < st_.size(); ++o) {
      moments(o, off, part);
      for (std::size_t m = 0; m < off.size(); ++m) sum[m] += part[m];
    }
    for (std::size_t m = 0; m < off.size(); ++m) out[where[m]] = cx_.gamma_factor * (sum[m] - datum(reference[where[m]]));
    return out;
  }


 private:
  // height(i, x) for x in some contact j (the rigid profile there, from j's datum), else nothing.
  std::optional<double> in_contact(std::size_t i, double x) const {
    for (std::size_t j = 0; j < st_.size(); ++j) {
      const auto& g = st_[j].g;
      if (g.line_load || !(x >= g.jacobi.lo && x <= g.jacobi.hi)) continue;
      return j == i ? profile(i, x) : profile(j, x) + cx_.gamma_factor * (datum(j) - datum(i));
    }
    return std::nullopt;
  }

  // The regular part of contact o's density as weights on nodes: sum_q w_q Psi(t_q, x) is its
  // moment, by Gauss-Jacobi with the density's own end exponents (so the series alone is
  // integrated: exact for polynomials, and psi is smooth in t when x is off the interval). Built
  // once per contact: the series is summed at each node once, not once per x.
  struct weighted_nodes {
    std::vector<double> t, w;
  };
  const weighted_nodes& regular_nodes(std::size_t o) const {
    if (!nodes_[o].t.empty() || st_[o].g.line_load) return nodes_[o];
    const contact_density& d = st_[o].g;
    const auto rule_ptr = abel::cached_gauss_jacobi_rule<double>(
        std::max<std::size_t>(d.jacobi.coefficients.size() + 64, 96), d.jacobi.del, d.jacobi.gam);
    nodes_[o] = weighted(d, *rule_ptr);
    return nodes_[o];
  }
  // The nodes of `rule` on d's interval, each weighted by the series there and its rule weight.
  template <class Rule>
  static weighted_nodes weighted(const contact_density& d, const Rule& rule) {
    weighted_nodes out;
    out.t.resize(rule.size());
    out.w.resize(rule.size());
    // The series summed at all nodes in one call, its recurrence coefficients computed once.
    d.jacobi.series_evaluator().evaluate(rule.x.data(), out.w.data(), rule.size());
    for (std::size_t q = 0; q < rule.size(); ++q) {
      out.t[q] = rule.x_minus_lo[q] <= rule.hi_minus_x[q] ? d.jacobi.lo + d.length() * rule.x_minus_lo[q] / 2
                                                          : d.jacobi.hi - d.length() * rule.hi_minus_x[q] / 2;
      out.w[q] *= rule.weight[q] * d.length() / 2;
    }
    return out;
  }

  // The same as regular_nodes with far_extra nodes beyond half the series' length M: for x at
  // least far_lengths of the contact's length L from it. WHY enough: Psi(t, x)'s only singularity
  // in t is t = x, at 1 + 2 r/L >= 5 in the interval's coordinate (r the distance to the near
  // edge), so it is analytic inside the Bernstein ellipse rho = 5 + sqrt 24 = 9.9; Gauss-Jacobi of
  // M/2 + far_extra nodes is exact for the series times polynomials of degree 2 far_extra, and errs
  // by ~rho^-24 < 1e-23 of the moment. The general nodes (M + 64) serve x down to the edge. Used by
  // moments' panels only (the clearance check of a sampled profile, 9 % of a 1e5-sample search
  // with the general nodes): ~half the kernel values.
  static constexpr std::size_t far_extra = 12;
  static constexpr double far_lengths = 2;
  const weighted_nodes& far_nodes(std::size_t o) const {
    if (!far_nodes_[o].t.empty() || st_[o].g.line_load) return far_nodes_[o];
    const contact_density& d = st_[o].g;
    const auto rule_ptr =
        abel::cached_gauss_jacobi_rule<double>(d.jacobi.coefficients.size() / 2 + far_extra, d.jacobi.del, d.jacobi.gam);
    far_nodes_[o] = weighted(d, *rule_ptr);
    return far_nodes_[o];
  }

  // int g_o(t) Psi(t, x) dt for x off contact o's interval (at most on its edge); by far_nodes
  // when `far` (x at least far_lengths of the contact's length from it).
  double moment(std::size_t o, double x, bool far = false) const {
    const contact_density& d = st_[o].g;
    if (d.line_load) return d.line_weight * psi(d.jacobi.lo, x, cx_.alpha, omk_, cx_.kappa);
    const weighted_nodes& nodes = far ? far_nodes(o) : regular_nodes(o);
    double sum = 0;
    for (std::size_t q = 0; q < nodes.t.size(); ++q) sum += nodes.w[q] * psi(nodes.t[q], x, cx_.alpha, omk_, cx_.kappa);
    // Apex enrichment: abel's composite Gauss-Jacobi, cut and graded at the apex (psi is smooth
    // in t on the interval when x is outside it).
    if (d.has_apex) sum += d.apex.integrate([&](double t) { return psi(t, x, cx_.alpha, omk_, cx_.kappa); });
    if (!d.kinks.empty()) sum += kink_moment(o, x, far);
    return sum;
  }

  // The knots' terms' part of moment(o, x): their composite rules graded toward x (at distance r
  // beyond an end) unless x is `far` (rules without grading, built once per contact). WHY graded:
  // a term is large next to the edge away from its knot (its factor q), where the series cancels
  // it; an ungraded rule erred there by ~3e-3 of the profile's span at L/128 from the edge (the
  // penetration check of a 4000-sample periodic profile), the series' Gauss-Jacobi sum far less.
  double kink_moment(std::size_t o, double x, bool far) const {
    const contact_density& d = st_[o].g;
    const double inf = std::numeric_limits<double>::infinity(), h = d.length() / 2;
    if (far && far_kinks_[o].value.empty()) far_kinks_[o] = d.kink_rule(inf, inf);
    const auto graded =
        far ? abel::enrichment_rule<double>{} : d.kink_rule(x < d.a() ? (d.a() - x) / h : inf, x > d.b() ? (x - d.b()) / h : inf);
    const auto& rule = far ? far_kinks_[o] : graded;
    double sum = 0;
    for (std::size_t j = 0; j < rule.size(); ++j)
      sum += rule.value[j] * psi(rule.t(j, d.a(), d.b()), x, cx_.alpha, omk_, cx_.kappa);
    return sum;
  }

  // moment(o, x) at every x of xs (all off contact o's interval), written to out. On each side of
  // the interval the moment is analytic in the distance r from the near edge except at r = 0 and
  // across the interval (r in [-L, 0]): panels [r/2, r] halving towards the edge see their nearest
  // singularity at a distance >= their length (Bernstein ratio >= 3 + sqrt 8), so Chebyshev
  // interpolation on 20 first-kind points is good to ~(3 + sqrt 8)^-20 ~ 5e-16 of the panel's
  // values. Grading stops once fewer samples than 2 panels' nodes remain nearer the edge; those,
  // and the samples of a side with few of them, are direct quadratures.
  void moments(std::size_t o, const std::vector<double>& xs, std::vector<double>& out) const {
    constexpr std::size_t points = 20;
    const contact_density& d = st_[o].g;
    out.assign(xs.size(), 0.0);
    if (d.line_load) {  // one kernel value a sample
      for (std::size_t k = 0; k < xs.size(); ++k) out[k] = moment(o, xs[k]);
      return;
    }
    const abel::chebyshev_grid<double> grid(points);
    std::vector<double> values(points), coefficients;
    for (const int side : {-1, 1}) {
      // distances from the near edge of the samples on this side (index, r), r > 0
      std::vector<std::pair<double, std::size_t>> near;
      for (std::size_t k = 0; k < xs.size(); ++k) {
        const double r = side < 0 ? d.jacobi.lo - xs[k] : xs[k] - d.jacobi.hi;
        if (r > 0) near.push_back({r, k});
      }
      if (near.empty()) continue;
      if (side < 0) std::reverse(near.begin(), near.end());  // ascending xs: ascending r, no sort
      if (!std::is_sorted(near.begin(), near.end())) std::sort(near.begin(), near.end());
      std::size_t end = near.size();  // samples near[0, end) still to serve
      double top = near.back().first;
      while (end > 2 * points) {
        const double bottom = top / 2;
        const std::size_t begin = static_cast<std::size_t>(
            std::lower_bound(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(end), std::pair<double, std::size_t>{bottom, 0}) -
            near.begin());
        const double half = (top - bottom) / 2;
        for (std::size_t j = 0; j < points; ++j) {
          const double r = grid.one_plus_x[j] <= grid.one_minus_x[j] ? bottom + half * grid.one_plus_x[j] : top - half * grid.one_minus_x[j];
          values[j] = moment(o, side < 0 ? d.jacobi.lo - r : d.jacobi.hi + r, bottom >= far_lengths * d.length());
        }
        coefficients = abel::chebyshev_coefficients(values);
        for (std::size_t m = begin; m < end; ++m) {
          const double r = near[m].first;
          out[near[m].second] = riemann::detail::chebyshev_fit<double>::clenshaw(coefficients, ((r - bottom) - (top - r)) / (top - bottom));
        }
        end = begin;
        top = bottom;
      }
      for (std::size_t m = 0; m < end; ++m) out[near[m].second] = moment(o, xs[near[m].second]);
    }
  }

  // The sums over contacts of int g_o Psi(t, x) dt (far_action: a tree for many contacts).
  const far_action& psi_field() const {
    if (!psi_)
      psi_ = std::make_unique<far_action>(st_, [alpha = cx_.alpha, omk = omk_, kappa = cx_.kappa](const double& t_minus_x) {
        return psi_distance(-t_minus_x, alpha, omk, kappa);
      });
    return *psi_;
  }

  double datum(std::size_t k) const {
    if (edge_[k]) return *edge_[k];
    const auto& g = st_[k].g;
    double value = psi_field().sum(g.jacobi.lo, [&](std::size_t o) { return o == k ? 0.0 : moment(o, g.jacobi.lo); });
    if (g.line_load) {
      value += moment(k, g.jacobi.lo);  // w Psi(a, a): the kernel's continuous value w/alpha there
    } else {
      // In offsets from the nearer end, so that the end singularities (t-a)^gam log(t-a) and
      // (b-t)^del are evaluated from exact distances (tanh-sinh clusters its nodes there).
      const double Lg = g.length();
      // density from u = t - a, v = b - t and dx0 = x - x0 (reference axis), whichever are exact.
      auto density_at = [&](double u, double v, double dx0) {
        const double one_plus = 2 * u / Lg, one_minus = 2 * v / Lg;
        const double xr = one_plus <= one_minus ? one_plus - 1 : 1 - one_minus;
        double val = std::pow(one_minus, g.jacobi.del) * std::pow(one_plus, g.jacobi.gam) * g.jacobi.series(xr);
        if (g.has_apex) val += g.apex.value_with_offset(one_plus, one_minus, dx0);
        return val;
      };
      auto weight = [&](double u) { return psi_distance(-u, cx_.alpha, omk_, cx_.kappa); };
      if (!g.has_apex && cx_.alpha == 0) {
        value += log_datum(g.jacobi);
      } else if (!g.has_apex && cx_.alpha >= exact_datum_alpha) {
        // Psi(t, a) = -((t - a)^alpha - 1)/alpha on the whole contact (t >= a), and t - a =
        // (L/2)(1 + x): the integral is -(I_alpha - int g)/alpha with I_alpha = (L/2)^(1 + alpha)
        // int (1-x)^del (1+x)^(gam + alpha) S(x) dx, exact by Gauss-Jacobi with that weight for the
        // series S of degree M - 1 (M/2 + 1 nodes), the series summed at all nodes in one call (the
        // same sums bit for bit, interleaved: a call a node was 15 % of a 1e5-sample profile's
        // search, 233 contacts). Relative error ~ eps/alpha from the difference.
        // WHY not the moments int w P_n (1+x)^alpha in closed form (Rodrigues' formula, O(M)): they
        // differ from this sum by roundings, which steer a rough profile's Newton path through the
        // levels (16000 samples, periodic, seed 3, load 3e-3: 54 iterations and 48 s instead of 39
        // and 21 s).
        const auto& j = g.jacobi;
        const auto rule_ptr = abel::cached_gauss_jacobi_rule<double>(j.coefficients.size() / 2 + 2, j.del, j.gam + cx_.alpha);
        const auto& rule = *rule_ptr;
        std::vector<double> S(rule.size());
        j.series_evaluator().evaluate(rule.x.data(), S.data(), rule.size());
        double sum = 0;
        for (std::size_t q = 0; q < rule.size(); ++q) sum += rule.weight[q] * S[q];
        value -= (std::pow(Lg / 2, 1 + cx_.alpha) * sum - j.integral()) / cx_.alpha;
        // The knots' terms the same way: C phi (1 + x)^alpha is the term with gam + alpha (its
        // factor q is kept), whose integral is abel's composite rule.
        for (auto term : g.kinks) {
          const double plain = term.integral();
          term.smooth.gam += cx_.alpha;
          value -= (std::pow(Lg / 2, cx_.alpha) * term.integral() - plain) / cx_.alpha;
        }
      } else if (!g.has_apex) {
        const double half = Lg / 2;
        value += tanh_sinh_rule().integrate([&](double u) { return density_at(u, Lg - u, 0) * weight(u); }, 0.0, half, 1e-12) +
                 tanh_sinh_rule().integrate([&](double v) { return density_at(Lg - v, v, 0) * weight(Lg - v); }, 0.0, half, 1e-12);
      } else {
        // Four pieces, each parametrised by the offset from its singular end (a, apex, apex, b).
        const double ua = st_[k].apex - g.jacobi.lo, vb = g.jacobi.hi - st_[k].apex, x0 = g.apex.apex_reference();
        auto piece = [&](auto&& f, double length) { return tanh_sinh_rule().integrate(f, 0.0, length, 1e-12); };
        value += piece([&](double u) { return density_at(u, Lg - u, 2 * u / Lg - 1 - x0) * weight(u); }, ua / 2);
        value += piece([&](double o) { return density_at(ua - o, vb + o, -2 * o / Lg) * weight(ua - o); }, ua / 2);
        value += piece([&](double o) { return density_at(ua + o, vb - o, 2 * o / Lg) * weight(ua + o); }, vb / 2);
        value += piece([&](double v) { return density_at(Lg - v, v, 1 - 2 * v / Lg - x0) * weight(Lg - v); }, vb / 2);
      }
    }
    edge_[k] = value;
    return value;
  }

  // From this alpha on, the own contact's datum is one Gauss-Jacobi sum (datum); below, the
  // difference quotient (r^alpha - 1)/alpha would lose more than 2 digits: tanh-sinh on log-like
  // Psi, except at alpha = 0 (log_datum).
  static constexpr double exact_datum_alpha = 1e-2;

  /// alpha = 0: int_a^b g(t) Psi(t, a) dt with Psi(t, a) = -log(t - a) = -log(L/2) - log(1 + x), for
  /// g = w S, S = sum_n c_n P_n^(del,gam). The moments of log(1 + x) are in closed form (Rodrigues'
  /// formula w P_n = ((-1)^n/(2^n n!)) d^n/dx^n [(1-x)^(del+n) (1+x)^(gam+n)], n integrations by parts
  /// against log(1 + x), whose n-th derivative is (-1)^(n-1) (n-1)!/(1+x)^n):
  ///   mu_n = int w P_n log(1+x) dx = (-1)^(n-1)/n 2^(del+gam+1) B(del+n+1, gam+1)          (n >= 1),
  ///   mu_0 = 2^(del+gam+1) B(del+1, gam+1) (log 2 + psi(gam+1) - psi(del+gam+2))          (d/dgam of int w).
  /// The integral is -log(L/2) int g - (L/2) sum_n c_n mu_n: exact for the series, O(M) (the 50
  /// cosine bumps at alpha = 0: 13 s with tanh-sinh at every level).
  static double log_datum(const abel::jacobi_density<double>& j) {
    if (j.coefficients.empty()) return 0.0;
    const double del = j.del, gam = j.gam, h = j.half_length();
    // h0 = int w = 2^(del+gam+1) B(del+1, gam+1); the n-th moment's factor 2^(del+gam+1) B(del+n+1, gam+1)
    // follows from it by B(del+n+2, gam+1) = B(del+n+1, gam+1) (del+n+1)/(del+gam+n+2).
    const double h0 = quadrature::jacobi_norm_squared<double>(0, del, gam);
    double sum = j.coefficients[0] * h0 *
                 (std::log(2.0) + boost::math::digamma(gam + 1) - boost::math::digamma(del + gam + 2));
    double b = h0 * (del + 1) / (del + gam + 2);  // 2^(del+gam+1) B(del + n + 1, gam + 1) at n = 1
    for (std::size_t n = 1; n < j.coefficients.size(); ++n) {
      const double k = static_cast<double>(n);
      sum += j.coefficients[n] * (n % 2 == 1 ? 1.0 : -1.0) / k * b;
      b *= (del + k + 1) / (del + gam + k + 2);
    }
    return -std::log(h) * j.integral() - h * sum;
  }

  const std::vector<indentor_state>& st_;
  const context& cx_;
  double omk_;
  mutable std::vector<std::optional<double>> edge_;
  mutable std::vector<weighted_nodes> nodes_, far_nodes_;
  mutable std::vector<abel::enrichment_rule<double>> far_kinks_;  // kink_moment's rules for far x
  mutable std::unique_ptr<far_action> psi_, cross_;
};

}  // namespace rhabel::punch::detail
