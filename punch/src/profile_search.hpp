// punch/src/profile_search.hpp: the spectral contact search of a finite window of a sampled
// profile (contact_set.cpp), shared with the periodic profile's iteration (periodic_profile.cpp).
// Internal to punch/src.
#pragma once

#include "coarse_contact.hpp"
#include "internal.hpp"
#include "profile_curve.hpp"

#include <vector>

namespace rhabel::punch::detail {

/// A searched window: its reported result and the reported contacts' densities (abscissae in the
/// states' frame: add `origin` for the window's).
struct window_solution {
  profile_result result;
  std::vector<contact_density> densities;
  double origin = 0;
};

/// The contact search of solve_profile on the finite window `window` (material, speed, load; its
/// profile.x, profile.z those of `curve`, whose spline and slope the contacts are solved on), the
/// first round from `seeds` (absolute edges, loads in units of int g) or, when empty, from the
/// coarse boundary-element solve. Reported as solve_profile's result (seconds not set). Throws
/// std::domain_error when the curve has no tip inside the window.
window_solution search_window(const profile_scene& window, const profile_curve& curve, const context& cx,
                              const std::vector<coarse_patch>& seeds);

/// solve_profile for a periodic profile (periodic_profile.cpp; s validated, period > 0).
profile_result solve_periodic_profile(const profile_scene& s, const context& cx);

}  // namespace rhabel::punch::detail
