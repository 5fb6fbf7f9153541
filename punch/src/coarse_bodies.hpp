// punch/src/coarse_bodies.hpp: a coarse non-negative solve of several independent indentors on
// one boundary-element grid, the start of solve_coupled when its continuations fail (internal to
// punch/src).
//
// WHAT IT COMPUTES. Indentors k = 0 .. K-1 (parabolas; the grid needs a profile defined
// everywhere on its window, which a sampled profile is not), each
// pressed with its own load P_k and free to take its own level D_k, on one surface. Unknowns: the
// density g >= 0 on the panels of a window (panel_grid.hpp's discretisation, finite), which
// indentor owns each loaded panel, and the levels:
//     w = A g;   w - z_o = D_o on the panels o owns;   w - z_k >= D_k everywhere, for every k;
//     h sum_{panels of k} g = P_k,
// z_k the indentor's rigid profile (surface::rise from its apex). A panel belongs to the indentor
// that penetrates it most: the contact set and who carries it are found together, with no path in
// the load and no assumption of one interval per indentor on the way.
// WHY. solve_coupled's starts all follow the contacts from small loads (or from equal loads) with
// one interval per indentor. That path may not exist: three parabolas at alpha 0.6 with apexes out
// of order (radii 1, 0.8, 1.2; loads 1, 0.6, 1.4; apexes 0, -0.05, 0.7332) have separated contacts
// at their loads, but below ~0.14 of the loads contact 0 lies on both sides of contact 1, and the
// continuation in the load ends in contacts_merge at 1/16 (measured with a windowless
// boundary-element solver written apart from this one; the separated solution is checked against
// tests/punch/bem_oracle.hpp in test_coupled_bem.cpp; docs/theory.md section 7).
//
// HOW. The levels are the unknowns: at given levels D the surface is pressed by the single obstacle
// phi = max_k (z_k + D_k) (each panel owned by the maximising k), an active set like panel_grid.hpp's
// settle (one LU of the active panels a step: drop every panel with g < 0; when none, add every
// panel where w < phi), started from the last set; the loads P_k(D) then come from the owners'
// panels. D solves P_k(D) = P_k by Newton's method (forward-difference Jacobian, steps halved
// until the mismatch falls), with Gauss-Seidel sweeps on one level at a time (the others fixed,
// P_k grows with D_k: a bracket and regula falsi) where an indentor carries nothing or Newton
// stalls at a kink. WHY not the loads imposed directly, with the owners iterated: tried first,
// the owners cycled (two states of one indentor's share, 9 and 20 panels, alternating).
// Two windows: the isolated contacts' hull and its length on each side (first_window_panels,
// started from each isolated contact alone on the grid), then the contact set's hull and a quarter
// of its length on each side (second_window_panels, started from the first window's set); a
// window whose end panel is in contact is widened twice over and solved again.
//
// ACCURACY. First order: edges to about a panel (the three parabolas above: 1/340 of their hull on
// the second window), which is what the coupled Newton iteration needs as a start; nothing of
// this solve is reported.
// COST. Dense: an LU of the active panels (up to second_window_panels) per active-set step, a few
// steps per evaluation of the loads, K + 1 evaluations per Newton step. Measured (one core):
// 0.07 s for the three parabolas above, 4 ms for two parabolas of loads 100 : 1 at alpha 0.4; on
// random triples of parabolas whose continuations fail, 3 ms - 0.21 s to give up.
#pragma once

#include "internal.hpp"

#include <optional>
#include <utility>
#include <vector>

namespace rhabel::punch::detail {

/// The start of a coupled solve of the independent indentors st (every one a parabola;
/// target_load their loads) from the coarse solve above: one interval [a, b] per
/// indentor, in the states' frame, in the order of st. Nothing when an indentor's panels do not
/// form one interval, when two indentors' panels touch (their contacts merge at this resolution),
/// when an indentor has fewer than min_owned_panels panels (not resolved), when the loads are
/// not matched, or for more than max_bodies (16) indentors. `isolated`: each indentor's isolated
/// contact (the first window and start).
/// Each active-set step checks solve_options::time_limit; out of time, nothing.
std::optional<std::vector<std::pair<double, double>>> coarse_bodies(const std::vector<indentor_state>& st,
                                                                    const std::vector<std::pair<double, double>>& isolated,
                                                                    const context& cx);

}  // namespace rhabel::punch::detail
