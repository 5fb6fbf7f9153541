// The other periods' displacement on one period (punch/src/periodic_images.hpp, internal): its
// table of w_img and dw_img/dx, whose node values sum many sources through per-bin proxies, against
// the plain sum over every source of the images' kernel (periodic_panel_kernel::images, tested on
// its own in test_profile_bem.cpp) at points that are not table nodes. The sources are clusters
// like a rough profile's contacts (Gauss-Jacobi nodes of a few hundred contacts), some next to
// the window's ends, where the images' kernel is nearly singular (the proxies may not be used
// there). alpha 0.3 (kappa 0.5 and 0) and 0 (kappa 1).
#include <doctest/doctest.h>

#include "../punch/src/panel_grid.hpp"
#include "../punch/src/periodic_images.hpp"

#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

namespace {
namespace d = rhabel::punch::detail;

// The table is asked for 1e-13 of the sums' size (its panels' last Chebyshev coefficients), and
// the proxies add ~1e-16 of a bin's sum of |w| max |R| (periodic_images.cpp): 4e-13 of the size
// leaves a margin of 4 for the interpolation between the table's nodes.
constexpr double asked = 1e-13;
constexpr double tolerance = 4 * asked;

d::context make_context(double alpha, double kappa) {
  d::context cx;
  cx.alpha = alpha;
  cx.beta = 0;
  // alpha 0: the logarithmic kernel (kappa is then 1; beta 0)
  cx.par = alpha > 0 ? rhabel::abel::abel_parameters<double>::from_kappa(alpha, kappa)
                     : rhabel::abel::abel_parameters<double>(0.0, 0.0);
  cx.kappa = cx.par.kappa();
  cx.gamma_factor = boost::math::tgamma(1 - alpha);
  return cx;
}

/// Clusters of sources in [lo, lo + period): `clusters` contacts of 40 .. 200 nodes each (lengths
/// 1e-4 .. 3e-3 of the period), the first and the last within 1e-4 of the window's ends.
d::point_sources clusters_of(std::size_t clusters, double lo, double period, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  d::point_sources out;
  for (std::size_t c = 0; c < clusters; ++c) {
    const double length = period * std::pow(10.0, -4 + 1.5 * u(rng));
    double start = lo + (period - length) * u(rng);
    if (c == 0) start = lo + 1e-4 * period;
    if (c + 1 == clusters) start = lo + period - length - 1e-4 * period;
    const auto nodes = static_cast<std::size_t>(40 + 160 * u(rng));
    const double load = std::pow(10.0, -2 + 2 * u(rng));
    for (std::size_t q = 0; q < nodes; ++q) {
      const double s = (static_cast<double>(q) + 0.5) / static_cast<double>(nodes);
      out.t.push_back(start + length * s);
      out.w.push_back(load / static_cast<double>(nodes) * std::sqrt(s * (1 - s)) * 4);
    }
  }
  return out;
}
}  // namespace

TEST_CASE("image_field: the table of many sources (proxies per bin) == the plain sum over every source") {
  std::mt19937 rng(7);
  for (const auto& [alpha, kappa] : {std::pair{0.3, 0.5}, std::pair{0.3, 0.0}, std::pair{0.0, 1.0}}) {
    CAPTURE(alpha);
    CAPTURE(kappa);
    const d::context cx = make_context(alpha, kappa);
    const double lo = -0.37, period = 1.7;
    const d::point_sources src = clusters_of(300, lo, period, rng);
    REQUIRE(src.t.size() > 20000);  // far more than periodic_images.cpp's direct_sources
    const d::periodic_panel_kernel kernel(alpha, cx.kappa, cx.par.one_minus_kappa_over_alpha());
    const double scale = cx.gamma_factor * std::pow(period, alpha);
    // The sizes of the sums (for the tolerance and the table's accuracy): sum |w| max |R|, |R'|.
    double size = 0, slope_size = 0;
    for (const double v : {-0.999, -0.5, 0.0, 0.5, 0.999}) {
      const auto [r, dr] = kernel.images(v);
      size = std::max(size, std::abs(r));
      slope_size = std::max(slope_size, std::abs(dr));
    }
    double total = 0;
    for (const double w : src.w) total += std::abs(w);
    size *= scale * total;
    slope_size *= scale / period * total;
    const d::image_field field(src, lo, period, cx, asked * size, asked * slope_size);
    std::uniform_real_distribution<double> u(0, 1);
    double worst = 0, worst_slope = 0;
    for (std::size_t k = 0; k < 60; ++k) {
      // Most points anywhere; some within 1e-3 of an end (the nearly singular images).
      const double x = k % 4 == 0 ? lo + period * (k % 8 == 0 ? 1e-3 * u(rng) : 1 - 1e-3 * u(rng)) : lo + period * u(rng);
      double value = 0, slope = 0;
      for (std::size_t q = 0; q < src.t.size(); ++q) {
        const auto [r, dr] = kernel.images((src.t[q] - x) / period);
        value += src.w[q] * r;
        slope += src.w[q] * dr;
      }
      worst = std::max(worst, std::abs(field.value(x) - scale * value) / size);
      worst_slope = std::max(worst_slope, std::abs(field.slope(x) + scale / period * slope) / slope_size);
    }
    CHECK(worst < tolerance);
    CHECK(worst_slope < tolerance);
    MESSAGE("alpha " << alpha << " kappa " << kappa << ": value " << worst << ", slope " << worst_slope
                     << " of the sums' size; " << field.panels() << " panels");
  }
}
