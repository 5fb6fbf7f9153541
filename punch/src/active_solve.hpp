// punch/src/active_solve.hpp: the linear solve of one active set of the boundary-element grid
// (panel_grid.hpp), internal to punch/src.
//
// WHAT IT SOLVES. On the m active panels idx of a grid: A g - D = z, h sum g = load (A: the
// grid's kernel restricted to idx, D the rigid level).
//
// The load row is scaled by sigma (the displacements' norm over the load) so that GMRES's residual
// weighs both; the unknowns are solved together as the bordered system
// [A, -1; sigma h 1^T, 0] (g, D) = (z, sigma load).
// HOW. Up to `dense_limit` active panels: one LU. Above: GMRES (abel/gmres.hpp's
// gmres), each product by FFT over the whole grid, or, when the active panels are few against the
// grid (m^2 below the FFT's cost), as the direct sum from the kernel's table; preconditioned by a
// two-level method:
//   - blocks: neighbouring runs of active panels grouped up to block_limit = 100 panels (longer
//     runs cut), each inverted exactly (LU);
//   - a coarse space of one vector per block, Z_k = B_k^-1 1 (the block pressed flat alone), and
//     the level D: the Galerkin matrix E(k, l) = 1_k^T A Z_l bordered by the load row, exact for a
//     block and its neighbours (the blocks next in order and those nearer than half their width),
//     by the monopole q_l A(i, c_l) for the others (q_l = sum Z_l, c_l its weighted centre panel;
//     the far field is smooth, so the error is second order in width / distance: the
//     preconditioner, not the solution, carries it);
//   - applied multiplicatively: (c, D) from the coarse system with the block sums of r, r1 = r -
//     AZ c + D with the same near/far AZ, g = Z c + B^-1 r1.
// Block-Jacobi alone leaves the split of the load between blocks to GMRES, about one iteration a
// block (measured on a 96-patch profile: 43 blocks on 128000 panels, ~108 products for each of
// two right-hand sides; with the coarse space ~20 for the bordered system).
// WARM START. `warm_start` keeps the last solve's density and level; the next solve (the same grid
// after a change of the set, or a refined grid: the density per unit x' is grid-independent)
// starts from them, a panel's density being that of the panel under its centre on the last grid.
// Each product checks solve_options::time_limit (time_limit_reached).
#pragma once

#include "internal.hpp"
#include "panel_grid.hpp"

#include <Eigen/Dense>

#include <cstddef>
#include <vector>

namespace rhabel::punch::detail {

/// The last solve's density g on its active panels idx of a grid of n panels, and its level D.
struct warm_start {
  std::size_t n = 0;
  std::vector<std::size_t> idx;
  Eigen::VectorXd g;
  double D = 0;
};

/// GMRES's relative residual for a solve that decides the set (far below the discretisation's
/// error), and for the steps that only move towards it (`settle`: a looser solve misplaces a few
/// marginal panels, which the following steps correct; measured at 1e-7, the set cycled on one
/// grid of a 1364-patch profile, at 1e-8 it did not and the solve took 0.6x the time).
constexpr double deciding_tolerance = 1e-11, moving_tolerance = 1e-8;

/// g on the active panels idx and the level D (see the top of the file), GMRES to the relative
/// residual rtol; false when the solve fails. span: the profile's (max z - min z). ws: the first
/// guess on entry, this solve on return.
bool solve_active(panel_grid& gr, const std::vector<std::size_t>& idx, double load, double span, Eigen::VectorXd& g,
                  double& D, const context& cx, warm_start& ws, double rtol = deciding_tolerance);

}  // namespace rhabel::punch::detail
