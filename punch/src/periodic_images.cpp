// punch/src/periodic_images.cpp: the images' displacement on one period (periodic_images.hpp).
#include "periodic_images.hpp"

#include "panel_grid.hpp"

#include "rhabel/abel.hpp"

#include <boost/math/special_functions/chebyshev.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace rhabel::punch::detail {
namespace {

constexpr std::size_t image_first_panels = 16;
// A panel is not halved below this fraction of the period (the images' singularities lie beyond
// the window's ends, at the gap to the nearest contact: a table that needs finer panels than
// this has a contact at an end of the window).
constexpr double image_smallest_panel = 1e-9;

// THE SOURCES' PROXIES. A table node x sees each source through R((t - x)/lambda), analytic in t
// on the window but at t = x -+ lambda, just beyond its ends. So the sources of a bin of the window
// act at x as proxies_per_bin weights at the bin's Chebyshev points (first kind; the weights the
// sources' Lagrange interpolation onto them), whenever the bin is at least proxy_separation of its
// widths from both singular points: the interpolation error is then below rho^-16 with
// rho = 2 proxy_separation + 1 + sqrt((2 proxy_separation + 1)^2 - 1) = 9.9 for 2 widths, ~1e-16 of
// the bin's sum of |w| max |R|; nearer bins (those at the far end of the window from x) act by
// their sources. WHY: a 1e5-sample profile's 233 contacts are 1.4e5 sources (Gauss-Jacobi nodes),
// and the direct sums over them at every table node took 10 % of its search.
constexpr std::size_t proxies_per_bin = 16;
constexpr double proxy_separation = 2;
// The bins: this many across the window, when there are more than direct_sources sources.
constexpr std::size_t proxy_bins = 64;
constexpr std::size_t direct_sources = 4 * proxy_bins * proxies_per_bin;

/// T_j at the first-kind Chebyshev points x_k = cos(pi (k + 1/2)/P) (abel::chebyshev_grid):
/// out[j][k] = cos(pi j (k + 1/2)/P).
template <std::size_t P>
std::array<std::array<double, P>, P> chebyshev_at_points() {
  std::array<std::array<double, P>, P> out{};
  for (std::size_t j = 0; j < P; ++j)
    for (std::size_t k = 0; k < P; ++k) out[j][k] = std::cos(pi * static_cast<double>(j) * (static_cast<double>(k) + 0.5) / P);
  return out;
}

/// The sources in bins of the window: each bin's sources (sorted by t: [first[b], first[b + 1])) and
/// their proxies (see above). Without bins (few sources): one bin, no proxies.
struct binned_sources {
  point_sources sorted;
  std::vector<std::size_t> first;
  std::vector<double> bin_lo, bin_hi;
  std::vector<std::array<double, proxies_per_bin>> proxy_t, proxy_w;
  std::vector<char> inside;  // every source of the bin within it (else the bin acts by its sources)

  binned_sources(const point_sources& src, double lo, double period) {
    std::vector<std::size_t> order(src.t.size());
    for (std::size_t q = 0; q < order.size(); ++q) order[q] = q;
    std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return src.t[p] < src.t[q]; });
    for (const std::size_t q : order) sorted.t.push_back(src.t[q]), sorted.w.push_back(src.w[q]);
    const std::size_t bins = src.t.size() > direct_sources ? proxy_bins : 0;
    first.assign(1, 0);
    if (bins == 0) {
      first.push_back(sorted.t.size());
      return;
    }
    constexpr std::size_t Q = proxies_per_bin;
    const abel::chebyshev_grid<double> grid(Q);
    const auto at_node = chebyshev_at_points<Q>();  // at_node[k][j] = T_k(x_j)
    std::array<double, Q> T{};
    for (std::size_t b = 0; b < bins; ++b) {
      const double a = lo + period * static_cast<double>(b) / static_cast<double>(bins);
      const double e = b + 1 == bins ? lo + period : lo + period * static_cast<double>(b + 1) / static_cast<double>(bins);
      std::size_t end = first.back();
      while (end < sorted.t.size() && (sorted.t[end] < e || b + 1 == bins)) ++end;
      first.push_back(end);
      bin_lo.push_back(a);
      bin_hi.push_back(e);
      std::array<double, Q> t{}, w{};
      for (std::size_t j = 0; j < Q; ++j) t[j] = (a + e) / 2 + (e - a) / 2 * grid.x[j];
      // l_j(xi) = (1 + 2 sum_{k >= 1} T_k(xi_j) T_k(xi)) / Q: the Lagrange basis at the nodes.
      inside.push_back(end == first[b] || (sorted.t[first[b]] >= a && sorted.t[end - 1] <= e));
      for (std::size_t q = first[b]; q < end; ++q) {
        const double xi = (2 * sorted.t[q] - a - e) / (e - a);
        T[0] = 1;
        T[1] = xi;
        for (std::size_t k = 2; k < Q; ++k) T[k] = 2 * xi * T[k - 1] - T[k - 2];
        for (std::size_t j = 0; j < Q; ++j) {
          double sum = 0.5;
          for (std::size_t k = 1; k < Q; ++k) sum += at_node[k][j] * T[k];
          w[j] += sorted.w[q] * 2 * sum / Q;
        }
      }
      proxy_t.push_back(t);
      proxy_w.push_back(w);
    }
  }

  /// sum_q w_q f((t_q - x)/period) and the same of df, f = periodic_panel_kernel::images.
  std::pair<double, double> at(double x, double period, const periodic_panel_kernel& kernel) const {
    double value = 0, slope = 0;
    const auto add = [&](double t, double w) {
      const double u = std::clamp((t - x) / period, -1 + 1e-15, 1 - 1e-15);
      const auto [r, dr] = kernel.images(u);
      value += w * r;
      slope += w * dr;
    };
    for (std::size_t b = 0; b + 1 < first.size(); ++b) {
      if (first[b] == first[b + 1]) continue;
      const bool far = !bin_lo.empty() && inside[b] && std::min(x + period - bin_hi[b], bin_lo[b] - (x - period)) >=
                                               proxy_separation * (bin_hi[b] - bin_lo[b]);
      if (far) {
        for (std::size_t j = 0; j < proxies_per_bin; ++j) add(proxy_t[b][j], proxy_w[b][j]);
      } else {
        for (std::size_t q = first[b]; q < first[b + 1]; ++q) add(sorted.t[q], sorted.w[q]);
      }
    }
    return {value, slope};
  }
};

}  // namespace

point_sources density_sources(const contact_density& d, double origin) {
  point_sources out;
  if (d.line_load) {
    out.t.push_back(d.jacobi.lo + origin);
    out.w.push_back(d.line_weight);
    return out;
  }
  // Exact for the series times a polynomial of its degree + 64 (the kernel is analytic on the
  // contact with its singularities beyond the window's ends).
  const auto rule_ptr = abel::cached_gauss_jacobi_rule<double>(
      std::max<std::size_t>(d.jacobi.coefficients.size() + 64, 96), d.jacobi.del, d.jacobi.gam);
  const auto& rule = *rule_ptr;
  std::vector<double> values(rule.size());
  d.jacobi.series_evaluator().evaluate(rule.x.data(), values.data(), rule.size());
  for (std::size_t q = 0; q < rule.size(); ++q) {
    out.t.push_back(origin + (rule.x_minus_lo[q] <= rule.hi_minus_x[q] ? d.jacobi.lo + d.length() * rule.x_minus_lo[q] / 2
                                                                       : d.jacobi.hi - d.length() * rule.hi_minus_x[q] / 2));
    out.w.push_back(values[q] * rule.weight[q] * d.length() / 2);
  }
  // The knots' terms by their composite rules (the kernel is analytic on the contact).
  const double inf = std::numeric_limits<double>::infinity();
  const auto kinks = d.kink_rule(inf, inf);
  for (std::size_t j = 0; j < kinks.size(); ++j) {
    out.t.push_back(origin + kinks.t(j, d.a(), d.b()));
    out.w.push_back(kinks.value[j]);
  }
  return out;
}

point_sources joined(const std::vector<point_sources>& parts) {
  point_sources out;
  for (const auto& p : parts) {
    out.t.insert(out.t.end(), p.t.begin(), p.t.end());
    out.w.insert(out.w.end(), p.w.begin(), p.w.end());
  }
  return out;
}

image_field::image_field(const point_sources& src, double lo, double period, const context& cx, double value_accuracy,
                         double slope_accuracy)
    : lo_(lo), hi_(lo + period) {
  const periodic_panel_kernel kernel(cx.alpha, cx.kappa, cx.par.one_minus_kappa_over_alpha());
  const binned_sources sources(src, lo, period);
  const double scale = cx.gamma_factor * std::pow(period, cx.alpha), slope_scale = scale / period;
  constexpr std::size_t P = points;
  // The nodes x_k = cos(pi (k + 1/2)/P) and T_j(x_k).
  const abel::chebyshev_grid<double> grid(P);
  const auto cosine = chebyshev_at_points<P>();
  // One panel's coefficients from its values at the nodes.
  auto fit = [&](double a, double b, panel& out) {
    cx.check_time();
    out.lo = a;
    out.hi = b;
    std::array<double, P> v{}, s{};
    for (std::size_t k = 0; k < P; ++k) {
      const double x = (a + b) / 2 + (b - a) / 2 * grid.x[k];
      const auto [value, slope] = sources.at(x, period, kernel);
      v[k] = scale * value;
      s[k] = -slope_scale * slope;  // d/dx of R((t - x)/period)
    }
    for (std::size_t j = 0; j < P; ++j) {
      double cv = 0, cs = 0;
      for (std::size_t k = 0; k < P; ++k) cv += v[k] * cosine[j][k], cs += s[k] * cosine[j][k];
      // Boost's Clenshaw sum takes c_0 / 2: every coefficient is 2/P of its cosine sum.
      out.value[j] = 2 * cv / P;
      out.slope[j] = 2 * cs / P;
    }
    const double tail_v = std::max(std::abs(out.value[P - 1]), std::abs(out.value[P - 2]));
    const double tail_s = std::max(std::abs(out.slope[P - 1]), std::abs(out.slope[P - 2]));
    return tail_v <= value_accuracy && tail_s <= slope_accuracy;
  };
  // Depth-first in the order of x: a panel that is not resolved is replaced by its halves.
  std::deque<std::pair<double, double>> todo;
  for (std::size_t k = 0; k < image_first_panels; ++k)
    todo.emplace_back(lo + period * static_cast<double>(k) / image_first_panels, lo + period * static_cast<double>(k + 1) / image_first_panels);
  while (!todo.empty()) {
    const auto [a, b] = todo.front();
    todo.pop_front();
    panel p;
    if (fit(a, b, p) || b - a < 2 * image_smallest_panel * period) {
      panels_.push_back(p);
      continue;
    }
    todo.emplace_front((a + b) / 2, b);
    todo.emplace_front(a, (a + b) / 2);
  }
}

const image_field::panel& image_field::panel_at(double x) const {
  const auto it = std::upper_bound(panels_.begin(), panels_.end(), x, [](double v, const panel& p) { return v < p.hi; });
  return it == panels_.end() ? panels_.back() : *it;
}

double image_field::value(double x) const {
  if (panels_.empty()) return 0;
  x = std::clamp(x, lo_, hi_);
  const panel& p = panel_at(x);
  return boost::math::chebyshev_clenshaw_recurrence(p.value.data(), p.value.size(), (2 * x - p.lo - p.hi) / (p.hi - p.lo));
}

double image_field::slope(double x) const {
  if (panels_.empty()) return 0;
  x = std::clamp(x, lo_, hi_);
  const panel& p = panel_at(x);
  return boost::math::chebyshev_clenshaw_recurrence(p.slope.data(), p.slope.size(), (2 * x - p.lo - p.hi) / (p.hi - p.lo));
}

}  // namespace rhabel::punch::detail
