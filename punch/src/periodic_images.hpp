// punch/src/periodic_images.hpp: the surface displacement that the other periods' loads add on one
// period (internal to punch/src: the spectral solve of a periodic profile, periodic_profile.cpp).
//
// WHAT IT COMPUTES. A periodic density g (period lambda) whose one period lies in the window
// [lo, lo + lambda] loads the half-space in every period. On the window the surface displacement
// is the window's own (the finite kernel of docs/theory.md section 7) plus the images'
//     w_img(x) = Gamma(1 - alpha) lambda^alpha int_window g(t) R((t - x)/lambda) dt,
//     R(v) = sum over j != 0 of Psi(v + j), regularised (section 10; panel_grid.hpp's
//            periodic_panel_kernel::images), up to a constant (it only moves the rigid level),
// and its slope dw_img/dx. R is smooth on (-1, 1): the nearest images of a contact near one end
// of the window are singular just beyond the other end. So when the window's ends lie in a gap of
// the contacts, w_img is analytic on the window and the periodic problem on the window is the
// finite one with the profile z replaced by z - w_img: what periodic_profile.cpp iterates.
//
// HOW. The density enters as point sources (abscissa, weight = its share of int g): a contact's
// Jacobi series by Gauss-Jacobi nodes of its own exponents, a boundary-element solve's panels by
// their midpoints. w_img and its slope are tabulated on the window by piecewise Chebyshev
// interpolation (16 points a panel), panels halved until the last coefficients of both are below
// the requested accuracy (finer towards the ends, next to the images' singularities); a value is
// then O(16) flops. Each table node sums the sources of 64 bins of the window, a bin far from the
// node's singular points (t - x = -+lambda) through 16 proxies (periodic_images.cpp): cost of the
// table ~(panels x 16) x (64 x 16 + the sources of the bins near the window's far end) kernel
// values, not (panels x 16) x sources.
#pragma once

#include "internal.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace rhabel::punch::detail {

/// Point sources of a density: abscissae and weights (units of int g).
struct point_sources {
  std::vector<double> t, w;
};

/// A contact's density (its Jacobi series, or a line load) as point sources, absolute abscissae
/// (origin added).
point_sources density_sources(const contact_density& d, double origin);

/// All of `parts` as one set of sources.
point_sources joined(const std::vector<point_sources>& parts);

class image_field {
 public:
  static constexpr std::size_t points = 16;

  image_field() = default;
  /// w_img and its slope on [lo, lo + period] from `src` (abscissae inside the window), each
  /// tabulated to `value_accuracy` and `slope_accuracy` (absolute, in m and in slope units).
  image_field(const point_sources& src, double lo, double period, const context& cx, double value_accuracy,
              double slope_accuracy);
  /// w_img(x) (x clamped into the window) [m].
  double value(double x) const;
  /// dw_img/dx (x clamped into the window).
  double slope(double x) const;
  /// Panels of the table.
  std::size_t panels() const { return panels_.size(); }
  /// The panels' ends (for comparisons of two fields at their nodes).
  double lo() const { return lo_; }
  double hi() const { return hi_; }

 private:
  struct panel {
    double lo = 0, hi = 0;
    std::array<double, points> value{}, slope{};  // Chebyshev coefficients
  };
  const panel& panel_at(double x) const;
  double lo_ = 0, hi_ = 0;
  std::vector<panel> panels_;  // in the order of x, covering [lo_, hi_]
};

}  // namespace rhabel::punch::detail
