// punch/src/profile_curve.cpp: the natural cubic spline of a sampled profile and its bumps.
#include "profile_curve.hpp"

#include <gsl/gsl_spline.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace rhabel::punch::detail {

profile_curve::profile_curve(const sampled_profile& p)
    : x_(p.x), z_(p.z), corners_(p.corners), period_(p.period), wrap_(p.period), wrap_lo_(p.x.front()) {
  if (period_ > 0) {
    // One periodic piece through the closing knot (x_0 + period, z_0) (corners are refused with a
    // period: validate_profile).
    std::vector<double> x = x_, z = z_;
    x.push_back(x_.front() + period_);
    z.push_back(z_.front());
    piece pc;
    pc.lo = x.front();
    pc.hi = x.back();
    pc.spline.reset(gsl_spline_alloc(gsl_interp_cspline_periodic, x.size()), gsl_spline_free);
    if (!pc.spline) throw std::bad_alloc();
    gsl_spline_init(pc.spline.get(), x.data(), z.data(), x.size());
    pieces_.push_back(std::move(pc));
    return;
  }
  std::sort(corners_.begin(), corners_.end());
  // Piece boundaries: the ends and the corners (each a sample abscissa, validated).
  std::vector<std::size_t> cuts{0};
  for (const double c : corners_)
    cuts.push_back(static_cast<std::size_t>(std::lower_bound(x_.begin(), x_.end(), c) - x_.begin()));
  cuts.push_back(x_.size() - 1);
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const std::size_t i0 = cuts[k], n = cuts[k + 1] - i0 + 1;
    piece pc;
    pc.lo = x_[i0];
    pc.hi = x_[cuts[k + 1]];
    pc.spline.reset(gsl_spline_alloc(gsl_interp_cspline, n), gsl_spline_free);
    if (!pc.spline) throw std::bad_alloc();
    gsl_spline_init(pc.spline.get(), x_.data() + i0, z_.data() + i0, n);
    pieces_.push_back(std::move(pc));
  }
}

profile_curve::profile_curve(const profile_curve& periodic, std::size_t first, std::function<double(double)> c,
                             std::function<double(double)> dc)
    : period_(0), wrap_(periodic.wrap_), wrap_lo_(periodic.wrap_lo_), correction_(std::move(c)),
      correction_slope_(std::move(dc)), pieces_(periodic.pieces_) {
  const auto& x = periodic.x_;
  const std::size_t n = x.size();
  for (std::size_t k = 0; k <= n; ++k) {
    const std::size_t i = (first + k) % n;
    x_.push_back(x[i] + (first + k >= n ? wrap_ : 0.0));
  }
  for (const double at : x_) z_.push_back(value(at));
}

const profile_curve::piece& profile_curve::piece_at(double x) const {
  // The piece whose upper end is the first >= x (a corner belongs to the piece on its left for the
  // value, which both pieces share; the slope there is one-sided either way).
  for (const auto& pc : pieces_)
    if (x <= pc.hi) return pc;
  return pieces_.back();
}

double profile_curve::reduce(double x) const {
  if (wrap_ <= 0) return x;
  const double r = x - wrap_ * std::floor((x - wrap_lo_) / wrap_);
  return std::clamp(r, wrap_lo_, wrap_lo_ + wrap_);
}

double profile_curve::value(double x) const {
  if (correction_) return spline_value(reduce(x)) - correction_(x);
  return spline_value(reduce(x));
}

double profile_curve::spline_value(double x) const {
  const piece& pc = piece_at(x);
  // Linear continuation beyond the data with the end slope (gsl_spline_eval refuses x outside).
  const double at = std::clamp(x, pc.lo, pc.hi);
  const double v = gsl_spline_eval(pc.spline.get(), at, nullptr);
  return at == x ? v : v + (x - at) * gsl_spline_eval_deriv(pc.spline.get(), at, nullptr);
}

double profile_curve::slope(double x) const {
  const double correction = correction_slope_ ? correction_slope_(x) : 0.0;
  x = reduce(x);
  const piece& pc = piece_at(x);
  return gsl_spline_eval_deriv(pc.spline.get(), std::clamp(x, pc.lo, pc.hi), nullptr) - correction;
}

std::vector<std::pair<double, double>> profile_curve::knots(double lo, double hi) const {
  std::vector<std::pair<double, double>> out;
  const std::size_t n = x_.size();
  // z'' at x on the piece of the interval whose midpoint is mid (a corner's two pieces differ).
  auto second = [&](double x, double mid) {
    const piece& pc = piece_at(reduce(mid));
    return gsl_spline_eval_deriv2(pc.spline.get(), std::clamp(reduce(x), pc.lo, pc.hi), nullptr);
  };
  auto third = [&](double from, double to) {
    const double mid = (from + to) / 2;
    return (second(to, mid) - second(from, mid)) / (to - from);
  };
  const auto first = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), lo) - x_.begin());
  for (std::size_t i = first; i < n && x_[i] < hi; ++i) {
    if (std::binary_search(corners_.begin(), corners_.end(), x_[i])) continue;
    const bool periodic = period_ > 0;
    if (!periodic && (i == 0 || i + 1 == n)) continue;
    const double left = i > 0 ? x_[i - 1] : x_[n - 1] - period_, right = i + 1 < n ? x_[i + 1] : x_[0] + period_;
    out.push_back({x_[i], third(x_[i], right) - third(left, x_[i])});
  }
  return out;
}

std::vector<bump> find_bumps(const std::vector<double>& z) {
  std::vector<std::size_t> tips;
  for (std::size_t i = 1; i + 1 < z.size(); ++i) {
    if (!(z[i] > z[i - 1])) continue;
    // Past a plateau: the top is a tip only if the samples fall after it.
    std::size_t j = i + 1;
    while (j < z.size() && z[j] == z[i]) ++j;
    if (j < z.size() && z[j] < z[i]) tips.push_back(i);
  }
  std::vector<bump> out(tips.size());
  for (std::size_t k = 0; k < tips.size(); ++k) {
    out[k].tip = tips[k];
    out[k].first = k == 0 ? 0 : out[k - 1].last;
    if (k + 1 == tips.size()) {
      out[k].last = z.size() - 1;
    } else {
      const auto from = z.begin() + static_cast<std::ptrdiff_t>(tips[k]);
      const auto to = z.begin() + static_cast<std::ptrdiff_t>(tips[k + 1]);
      out[k].last = static_cast<std::size_t>(std::min_element(from, to) - z.begin());
    }
  }
  return out;
}

}  // namespace rhabel::punch::detail
