// punch/src/periodic_images.cpp: the images' displacement on one period (periodic_images.hpp).
#include "periodic_images.hpp"

#include "panel_grid.hpp"

#include "rhabel/abel.hpp"

#include <boost/math/special_functions/chebyshev.hpp>

#include <algorithm>
#include <cmath>
#include <deque>

namespace rhabel::punch::detail {
namespace {

constexpr std::size_t image_first_panels = 16;
// A panel is not halved below this fraction of the period (the images' singularities lie beyond
// the window's ends, at the gap to the nearest contact: a table that needs finer panels than
// this has a contact at an end of the window).
constexpr double image_smallest_panel = 1e-9;

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
  const double scale = cx.gamma_factor * std::pow(period, cx.alpha), slope_scale = scale / period;
  constexpr std::size_t P = points;
  // The nodes x_k = cos(pi (k + 1/2)/P) and T_j(x_k) = cos(pi j (k + 1/2)/P).
  std::array<double, P> node{};
  std::array<std::array<double, P>, P> cosine{};
  for (std::size_t k = 0; k < P; ++k) node[k] = std::cos(pi * (static_cast<double>(k) + 0.5) / P);
  for (std::size_t j = 0; j < P; ++j)
    for (std::size_t k = 0; k < P; ++k) cosine[j][k] = std::cos(pi * static_cast<double>(j) * (static_cast<double>(k) + 0.5) / P);
  // One panel's coefficients from its values at the nodes.
  auto fit = [&](double a, double b, panel& out) {
    cx.check_time();
    out.lo = a;
    out.hi = b;
    std::array<double, P> v{}, s{};
    for (std::size_t k = 0; k < P; ++k) {
      const double x = (a + b) / 2 + (b - a) / 2 * node[k];
      double value = 0, slope = 0;
      for (std::size_t q = 0; q < src.t.size(); ++q) {
        const double u = std::clamp((src.t[q] - x) / period, -1 + 1e-15, 1 - 1e-15);
        const auto [r, dr] = kernel.images(u);
        value += src.w[q] * r;
        slope += src.w[q] * dr;
      }
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
