// punch/src/coarse_contact.hpp: a coarse non-negative solve of a sampled profile pressed by a
// rigid body, the first guess of contact_set.cpp's search (internal to punch/src).
//
// WHAT IT COMPUTES. The contact set and each contact's load of the profile z(x) on one rigid body
// with the total load P (in units of int g), by panel_grid.hpp's boundary-element discretisation
// and active set: every panel active on a grid of 256 panels, then grids refined four times at a
// time up to `panels`, and on up to `fine_panels` while a contact has fewer than 4 panels (at
// most 2^21), each level starting from the last level's set.
//
// ACCURACY. A first-order method: edges to a panel, loads to O(h) of the contacts' loads, so a
// contact whose load is a few percent of the others' may be missing or extra. That is what the
// search corrects; nothing of this solve is reported.
//
// COST. O(n log n) per product (n panels), the blocks' LU, O(600^2 m) at most; memory
// O(n + 600 m). Measured (rhabel/punch/profile.hpp): a few ms to 40 ms for 800 .. 4000 samples
// and 6 .. 49 contacts.
#pragma once

#include "internal.hpp"
#include "periodic_images.hpp"
#include "profile_curve.hpp"

#include <cstddef>
#include <vector>

namespace rhabel::punch::detail {

/// One contact of the coarse solve: [a, b] (panel edges, absolute abscissae) and its load (units
/// of int g). As the seed of a search from solved contacts (profile_search.hpp), `degree` caps its
/// series' degree there (0: solve_options::max_degree).
struct coarse_patch {
  double a = 0, b = 0, load = 0;
  std::size_t degree = 0;
  // The load is a solve's (this one's or a converged round's: indentor_state::seed_load); false: a
  // guess (a contact search's new or repaired contact).
  bool load_solved = true;
};

/// The contacts of the coarse solve in the order of x, on `panels` panels, refined on (by 4 at a
/// time) up to `fine_panels` while a contact has fewer than 4 panels (both clamped to 256 ..
/// 2^21); empty when its active set did not settle (the caller then searches without it).
/// With `sources`: the finest grid's active panels as point sources too (midpoints, h g: units of
/// int g; periodic_images.hpp).
std::vector<coarse_patch> coarse_contacts(const profile_curve& curve, double load, const context& cx,
                                          std::size_t panels, std::size_t fine_panels,
                                          point_sources* sources = nullptr);

}  // namespace rhabel::punch::detail
