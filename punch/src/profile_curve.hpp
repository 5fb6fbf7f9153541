// punch/src/profile_curve.hpp: the interpolant of a sampled profile and its bumps (internal to
// punch/src: used by contact_set.cpp).
//
// The profile is the natural cubic spline of the samples (GSL cspline), one spline per piece
// between declared corners (rhabel/punch/profile.hpp, "THE INTERPOLANT" for why). Outside the
// samples it is continued linearly with the end slope, so that a quadrature point that strays
// beyond the data gets a finite value (a contact must not reach there: contact_set.cpp checks).
// A periodic profile (sampled_profile::period > 0) is GSL's periodic cubic spline of the samples
// closed by the knot (x_0 + period, z_0), evaluated at any x by reduction into one period.
#pragma once

#include "rhabel/punch/profile.hpp"

#include <gsl/gsl_spline.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace rhabel::punch::detail {

class profile_curve {
 public:
  /// p validated (solve_profile's validate_profile).
  explicit profile_curve(const sampled_profile& p);
  /// The periodic curve `periodic` over one period from its sample `first` on, as a finite
  /// window: samples x_first .. x_{n-1}, x_0 + period .. x_first + period (n + 1), its values
  /// those of the periodic spline minus a correction c (and its slope dc), both functions of the
  /// window's abscissa (periodic_profile.cpp: the images' displacement). period() is 0.
  profile_curve(const profile_curve& periodic, std::size_t first, std::function<double(double)> c,
                std::function<double(double)> dc);
  double value(double x) const;
  double slope(double x) const;
  /// The spline's knots strictly inside (lo, hi) with the jump of its third derivative there,
  /// z'''(x+) - z'''(x-) (z''' is constant between knots: (z''(x_k+1) - z''(x_k))/(x_k+1 - x_k)).
  /// Corners and the data's ends are not knots in this sense (the slope jumps or the data stop);
  /// a window's correction is smooth and adds none.
  std::vector<std::pair<double, double>> knots(double lo, double hi) const;
  double lo() const { return x_.front(); }
  double hi() const { return x_.back(); }
  /// The period (> 0) of a periodic profile; 0 for a finite window.
  double period() const { return period_; }
  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& z() const { return z_; }
  const std::vector<double>& corners() const { return corners_; }

 private:
  struct piece {
    double lo = 0, hi = 0;
    std::shared_ptr<gsl_spline> spline;
  };
  const piece& piece_at(double x) const;
  double spline_value(double x) const;  // x reduced
  /// x reduced into [x_0, x_0 + period) (periodic profiles; x itself otherwise).
  double reduce(double x) const;
  std::vector<double> x_, z_, corners_;
  double period_ = 0;
  // The spline's period and first knot (period_ or, for a window of a periodic curve, its
  // source's), and the window's correction (empty: none).
  double wrap_ = 0, wrap_lo_ = 0;
  std::function<double(double)> correction_, correction_slope_;
  std::vector<piece> pieces_;
};

/// Validates a profile scene (every field; std::invalid_argument "caller: field ..." naming it);
/// shared by solve_profile (contact_set.cpp) and solve_profile_bem (profile_bem.cpp).
void validate_profile(const profile_scene& s, const char* caller);

/// A bump of the profile: its tip (a sample that is a local maximum of z) and its basin, the
/// samples between the lowest samples towards the neighbouring tips (the data's ends for the
/// first and the last bump).
struct bump {
  std::size_t tip = 0;              // sample index
  std::size_t first = 0, last = 0;  // sample indices of the basin's ends
};

/// The bumps of the samples in the order of x. A tip at the data's end is not a bump (a contact
/// there would leave the data). Plateaus: the first sample of a flat top is the tip.
std::vector<bump> find_bumps(const std::vector<double>& z);

}  // namespace rhabel::punch::detail
