// punch/src/profile_search.hpp: the spectral contact search of a finite window of a sampled
// profile (contact_set.cpp), shared with the periodic profile's iteration (periodic_profile.cpp).
// Internal to punch/src.
#pragma once

#include "coarse_contact.hpp"
#include "internal.hpp"
#include "profile_curve.hpp"

#include <cstddef>
#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace rhabel::punch::detail {

// Panels a sample of the coarse solve that seeds the search (finite and periodic), and up to how
// many it refines while a contact has fewer than 4 panels (coarse_contact.hpp; at most 2^21
// panels): its edges start the first round's coupled solve. WHY refined: a contact narrower than a sample has only a few panels
// at 8 a sample, and its level condition starts far off (self-affine profiles, 1000 / 4000
// samples, seeds 1-3, loads 5e-4 .. 2e-3 at acceptance 1e-6: 10 of 14 ok at 8 panels a sample, 12
// at 32, and 0.45-0.6 s where 8 took 1.8-3.3 s for those whose seeded Newton then converges
// without offset_continuation). WHY not 32 everywhere: the wide contacts of smooth bumps need no
// more than 8, and 32 made 50 cosine bumps (4000 samples) 1.6 s instead of 0.4 s.
inline constexpr std::size_t seed_panels = 8;
inline constexpr std::size_t seed_panels_fine = 32;

// A contact whose residual of (8) is within this fraction of the acceptance keeps its series'
// degree when the search is solved again at a higher one (contact_set.cpp, raise_degree) or in the
// next pass of a periodic profile (periodic_profile.cpp); the others may climb.
// WHY: a rough profile's contacts need such different degrees that most of them are far within the
// acceptance where a few reach it (1e5-sample periodic profile, 233 contacts: 229 at degree 1023
// with median residual 1.7e-9, the largest 1e-6), and each evaluation solved every contact's
// series to the top degree. The margin covers the edges' moves in the new search.
inline constexpr double capped_below = 0.25;

/// A searched window: its reported result and the reported contacts' densities, densities[k] that
/// of result.contacts[k] (abscissae in the states' frame: add `origin` for the window's), and the
/// top series degree (solve_options::max_degree) of the search that gave them.
struct window_solution {
  profile_result result;
  std::vector<contact_density> densities;
  double origin = 0;
  std::size_t max_degree = 0;
  /// Contacts its search lost once at the full load and did not restore: the bump (an index of
  /// this window's bumps) -> the seed it was lost with (contact_set.cpp, restore_lost).
  std::map<std::size_t, coarse_patch> lost;
  /// Its search kept light contacts far from the solution (contact_set.cpp, search_start::spare).
  bool spare = false;
  /// Its search stopped to search again with spare (contact_set.cpp, search_result::respare).
  bool respare = false;
  /// The seeds of `lost` (absolute edges), for a search of the same window whose bumps may differ.
  std::vector<coarse_patch> lost_seeds() const {
    std::vector<coarse_patch> out;
    for (const auto& entry : lost) out.push_back(entry.second);
    return out;
  }
  /// The solved contacts as seeds of another search: absolute edges, loads in units of int g.
  std::vector<coarse_patch> contacts() const {
    std::vector<coarse_patch> out;
    for (const auto& g : densities) out.push_back({g.a() + origin, g.b() + origin, g.integral()});
    return out;
  }
  /// contacts(), each that is ok with its residual of (8) at most `keep_below` keeping its series'
  /// degree as its cap (coarse_patch::degree) in the search they seed.
  std::vector<coarse_patch> contacts_capped(double keep_below) const {
    std::vector<coarse_patch> out = contacts();
    for (std::size_t k = 0; k < out.size() && k < result.contacts.size(); ++k) {
      const indentor_result& c = result.contacts[k];
      if (c.code == status_code::ok && c.residual <= keep_below) out[k].degree = c.degree + 1;
    }
    return out;
  }
};

/// The contact search of solve_profile on the finite window `window` (material, speed, load; its
/// profile.x, profile.z those of `curve`, whose spline and slope the contacts are solved on), the
/// first round from `seeds` (absolute edges, loads in units of int g) or, when empty, from the
/// coarse boundary-element solve. Reported as solve_profile's result (seconds not set). Throws
/// std::domain_error when the curve has no tip inside the window. `memo`: the Jacobian its
/// rounds keep for one another (coupled::jacobian_memo), shared with other searches of the same
/// window (a periodic profile's passes); null: its own. `lost`: contacts an earlier search of the
/// same window and load lost once and did not restore (window_solution::lost_seeds), each on the
/// bump that holds its middle, as lost once in this search (restore_lost gives it back where the
/// profile penetrates there). `spare`: an earlier search of the same window spared light contacts
/// (window_solution::spare), and so does this one from its start.
window_solution search_window(const profile_scene& window, const profile_curve& curve, const context& cx,
                              const std::vector<coarse_patch>& seeds,
                              std::shared_ptr<coupled::jacobian_memo> memo = nullptr,
                              const std::vector<coarse_patch>& lost = {}, bool spare = false);

/// A seeded contact (seed: absolute edges, its load) whose density g (abscissae of the solve:
/// `origin` added for absolute ones) is negative on [lo, hi] inside it, as the two contacts either
/// side, [seed.a, lo] and [hi, seed.b]: seed.load shared in the ratio of int_a^lo g to int_hi^b g
/// (by the parts' lengths when either integral is not positive), both loads solved
/// (coarse_patch::load_solved) and no degree cap (contact_set.cpp, repair_tension).
std::pair<coarse_patch, coarse_patch> split_seed(const coarse_patch& seed, const contact_density& g, double lo, double hi,
                                                 double origin);
/// A result that is not ok when cx's time has run out: its status gets cx.time_limit_message()
/// appended unless it names it already (solve_profile's last step, contact_set.cpp).
void say_time_limit(profile_result& r, const context& cx);

/// solve_profile for a periodic profile (periodic_profile.cpp; s validated, period > 0).
profile_result solve_periodic_profile(const profile_scene& s, const context& cx);

}  // namespace rhabel::punch::detail
