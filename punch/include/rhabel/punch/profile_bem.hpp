// rhabel/punch/profile_bem.hpp: a sampled (measured, rough) profile on one rigid body solved by the
// boundary-element method: finite windows and periodic profiles, any number of contact patches.
//
// WHAT IS COMPUTED
//   The scene of rhabel/punch/profile.hpp (a rigid profile given by samples, sliding at speed U
//   towards -x over the power-law viscoelastic half-space and pressed with the load P per unit
//   length; the contacts unknown), with the profile either
//     * a finite window: the natural cubic spline of the samples on [x_0, x_n]; or
//     * periodic (sampled_profile::period = lambda > 0): the periodic cubic spline of samples in
//       [x_0, x_0 + lambda) closed by (x_0 + lambda, z_0), repeated; P is the load per period and
//       the half-space is loaded by every period (the kernel summed over the periods exactly).
//   Reported: every contact patch (of one period) with its edges, load and C_f; the body's C_f
//   (tangential over normal force, per period), the mean pressure and the contact fraction; each
//   value extrapolated over the last three grids with an ERROR ESTIMATE (not a bound).
//
// THE METHOD (docs/theory.md sections 9 and 10)
//   The pressure piecewise constant on n uniform panels over the window (one period), collocation
//   at 3/4 of each panel, the panel influences in closed form (periodic: plus the images' Taylor
//   series summed by Hurwitz zeta values), an active set on the panels (every panel with negative
//   pressure dropped, every penetrating panel added, until neither happens) with one rigid level,
//   every product with the influence matrix by FFT. Grids: from 256 panels by factors of 4 up to
//   n0 = the samples' intervals doubled to >= 256 (panel ends on the knots of uniform samples),
//   then n0, 2 n0, 4 n0, ...; each grid starts from the last one's contact set and pressure. Each
//   patch of the finest grid carrying more than acceptance x P is matched to the patch of each of
//   the two coarser grids that overlaps it most; each matched load and C_f is extrapolated from
//   its three values (observed geometric convergence: the Richardson limit; error estimate = that
//   correction plus the last difference; without an observed order: the last value, error twice
//   the larger difference). A patch at or below acceptance x P (one that may or may not exist
//   within the acceptance: such patches come and go as the grid is refined) is reported with its
//   own load as its error.
//
// STATUS
//   ok when every patch above acceptance x P on the last three grids is matched one to one (none
//   split, merged or vanished between them), the body's C_f error estimate is at most
//   solve_options::acceptance x max |z'| (C_f is a mean of z' weighted by the pressure: max |z'|
//   bounds it) and every patch's load error estimate at most acceptance x P. The grids are refined
//   until that holds, the next grid would exceed max_panels, or solve_options::time_limit runs out
//   (checked at every product of the active set's linear solves): then not_converged, with the estimates of the last grids
//   and the reason in the status. The edges are those of the finest grid, within one panel
//   (edge_error); patches narrower than a panel of the finest grid are not seen.
//
// ACCURACY AND COST (measured: tests/punch/test_profile_bem.cpp, studies; docs/accuracy.md)
//   C_f converges like h^2 once a panel is a fraction of the smallest patch; the error estimate
//   is a few times the error. Each grid costs O(n log n) per product (a periodic grid's circulant
//   by FFTs of length n); the active set's linear solves are one LU up to 600 active panels, else
//   GMRES with a two-level preconditioner (exact blocks of up to 100 active panels and one coarse
//   unknown per block: ~10-40 products a solve whatever the number of patches), each started from
//   the last solve. Measured on one core (study_rough_profile): 96 patches (1000 samples) to C_f
//   +- 6e-7 in 0.96 s; 1303 patches (1e5 samples) to C_f +- 1.3e-4 on 1.6e6 panels in 27 s.
//   Use acceptance 1e-4 .. 1e-6 (the default 1e-9 of solve_options is far below what a
//   first-order method reaches in reasonable time and the solve runs to max_panels).
//
// LIMITS
//   Any alpha in [0, 1) and beta of the material (contact.hpp). No corners (sampled_profile::
//   corners are refused only with a period; a finite window's corners are points of the spline
//   like any other here). A finite window whose contacts reach an end of the samples is refused
//   (std::domain_error naming body.load: beyond the samples nothing is known; give the period).
//   No pressure or displacement samples (the spectral solver, profile.hpp, gives them).
#pragma once

#include "rhabel/punch/profile.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace rhabel::punch {

/// A value and its error estimate (an estimate from the grids' differences, not a bound).
struct bem_estimate {
  double value = 0;
  double error = 0;
};

/// One contact patch (of one period).
struct bem_patch {
  double a = 0;           ///< leading edge [m] (periodic: in [x_0, x_0 + period))
  double b = 0;           ///< trailing edge [m] (periodic: may exceed x_0 + period: the patch wraps)
  double edge_error = 0;  ///< the edges' accuracy: one panel of the finest grid [m]
  bem_estimate load;      ///< [N/m]
  bem_estimate hysteretic_friction;  ///< C_f of the patch: int z' p / int p over it
  double peak_pressure = 0;  ///< largest panel pressure of the finest grid [Pa] (a panel mean)
  /// 4 standard deviations of the patch's pressure distribution on the finest grid [m]: the width
  /// b - a for the Hertzian ellipse, and, unlike the panel edges a, b, continuous in the scene
  /// (the characteristic length of a master-curve fit, omega0 = U/L).
  double pressure_width = 0;
};

struct bem_options {
  /// Panels at most on the finest grid (memory ~130 bytes a panel: measured 214 MB at 1.6e6, 420 MB
  /// at 3.2e6; the scene field profile.max_panels).
  std::size_t max_panels = std::size_t{1} << 21;
};

struct profile_bem_result {
  double beta = 0;
  double kappa = 0;
  regime_kind regime = regime_kind::below;
  double period = 0;  ///< the profile's period (0: finite window)
  std::vector<bem_patch> patches;    ///< in the order of a
  bem_estimate hysteretic_friction;  ///< C_f of the body (per period): int z' p / int p
  double total_friction = 0;         ///< C_f + k (material.coulomb)
  double mean_pressure = 0;          ///< P / window length (periodic: per period) [Pa]
  bem_estimate contact_fraction;     ///< patches' total width / window length (error: their edges')
  struct diagnostics_t {
    status_code code = status_code::ok;
    std::string status;              ///< "ok" or what failed, with the numbers
    double seconds = 0;              ///< wall-clock time [s]
    std::size_t panels = 0;          ///< panels of the finest grid
    std::size_t active_set_steps = 0;  ///< summed over the grids
    /// The grids n0 2^k solved: panels, patches and body C_f of each (the evidence of the
    /// extrapolation).
    std::vector<std::size_t> level_panels, level_patches;
    std::vector<double> level_friction;
  } diagnostics;
};

/// Solves a sampled profile on one rigid body by the boundary-element method (see the top of this
/// header). Validates every field first and throws std::invalid_argument naming it (as
/// solve_profile); throws std::domain_error when a finite window's contacts reach an end of the
/// samples. Uses solve_options::acceptance and time_limit (the other options are the spectral
/// solver's).
profile_bem_result solve_profile_bem(const profile_scene& s, const solve_options& options = {},
                                     const bem_options& bem = {});

}  // namespace rhabel::punch
