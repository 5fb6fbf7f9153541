// punch/src/coarse_contact.hpp: a coarse non-negative solve of a sampled profile pressed by a
// rigid body, the first guess of contact_set.cpp's search (internal to punch/src).
//
// WHAT IT COMPUTES. The contact set and each contact's load of the profile z(x) on one rigid body
// with the total load P (in units of int g), by the usual boundary-element method: g piecewise
// constant on n uniform panels over the samples' range, collocation at 3/4 of each panel, the
// surface displacement w(x) = Gamma(1 - alpha) int g(t) Psi(t, x) dt (docs/theory.md section 7;
// Psi's panel integrals in closed form, so the matrix is Toeplitz: 2n - 1 kernel values), and the
// contact conditions of the rigid body (docs/theory.md section 9):
//     w(x_i) - z(x_i) = D on the active panels,   >= D on the others,   g >= 0,   h sum g = P,
// D unknown. Active set: every panel active on a grid of 256 panels; then repeatedly every panel
// with g < 0 is dropped, and when none is negative every panel that penetrates (w - z < D) is
// added, until neither happens; the grid is then refined four times at a time up to `panels`
// (at most 2^17), each level starting from the last level's set. The linear solve on the active
// panels: LU up to 600 of them, else GMRES (abel/detail/block_gmres.hpp) with one diagonal block
// per run of active panels (the contacts: their coupling is smooth), runs longer than 600 panels
// cut into blocks of 600. Every product with the Toeplitz matrix (GMRES's, the penetration
// check's) is a circulant convolution by FFT (toeplitz_product.hpp). Each active-set step checks
// solve_options::time_limit (time_limit_reached).
//
// ACCURACY. A first-order method: edges to a panel, loads to O(h) of the contacts' loads, so a
// contact whose load is a few percent of the others' may be missing or extra. That is what the
// search corrects; nothing of this solve is reported. The collocation at 3/4 (not the midpoint)
// keeps the checkerboard mode away from the odd part of Psi's null space at kappa = -1.
//
// COST. O(n log n) per product (n panels; the penetration check is one, GMRES a few tens), the
// blocks' LU, O(600^2 m) at most; memory O(n + 600 m). Measured (rhabel/punch/profile.hpp): a few
// ms to 40 ms for 800 .. 4000 samples and 6 .. 49 contacts.
#pragma once

#include "internal.hpp"
#include "profile_curve.hpp"

#include <cstddef>
#include <vector>

namespace rhabel::punch::detail {

/// One contact of the coarse solve: [a, b] (panel edges, absolute abscissae) and its load (units
/// of int g).
struct coarse_patch {
  double a = 0, b = 0, load = 0;
};

/// The contacts of the coarse solve in the order of x, on `panels` panels (clamped to 256 .. 4096);
/// empty when its active set did not settle (the caller then searches without it).
std::vector<coarse_patch> coarse_contacts(const profile_curve& curve, double load, const context& cx,
                                          std::size_t panels);

}  // namespace rhabel::punch::detail
