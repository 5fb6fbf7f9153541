// rhabel/scene/material.hpp: solving a scene whose material is a measured master curve.
//
// A scene with "material": {"master_curve": ...} is solved by the self-consistent fit of
// rhabel::materials (rhabel/materials/master_curve.hpp): the curve (shifted by WLF to the scene's
// temperature if given) is fitted by a local power law at omega0, the scene is solved with it, and
// omega0 = U / L is iterated to a fixed point, L being the mean contact length of the indentors
// (a flat punch counts with its width: at and above alpha + beta/2 = 1/2 it touches only with its
// leading corner)
// (with several indentors: first with each indentor solved alone, which is fast, then on the whole
// scene from there: the coupled solve can take seconds at a trial material far from the answer).
// The final solve, with the converged (alpha, E1), is the written result; it gains
//   "material_fit": {"master_curve", "temperature", "log10_aT", "alpha", "E1", "omega0",
//                    "alpha_slope", "alpha_tan_delta", "modulus", "window": [lo, hi],
//                    "contact_length", "iterations", "status", "warning"}
// and its "scene" echoes the fitted alpha and E1. The fit's status is "ok", "poor_power_law"
// (the two alpha estimates differ by more than 0.05), "window_clipped" (the window reached the end
// of the measured range) or "not_converged" (no fixed point in 60 steps); anything but "ok" makes
// run_outcome::ok false (`rhabel solve` exits 3) and is also returned in `warning`.
#pragma once

#include "rhabel/scene/scene.hpp"
#include "rhabel/scene/solve.hpp"

#include <rhabel/materials.hpp>

#include <optional>
#include <string>

namespace rhabel::scene {

/// The master curve of `spec`, read once per resolved path and process (thread-safe cache), shifted
/// to its temperature. Throws input_error with one line naming the file, row and column.
materials::master_curve load_master_curve(const master_curve_spec& spec, const std::string& command);

/// The fixed point above alone, for a scene with a master curve (std::invalid_argument without):
/// the fitted power law and its evidence. Its trial solves take request's tolerance, interrupt and,
/// for a profile, acceptance and time limit. Throws input_error naming material.master_curve when
/// the fixed point leaves the curve's range.
material_fit_report fit_scene_material(const scene_spec& scene, const run_request& request);

/// The result document's "material_fit" of `report` (the fields listed at the top).
nlohmann::ordered_json material_fit_json(const master_curve_spec& spec, const material_fit_report& report);

/// `rhabel fit-material` and rhabel.fit_material: the local power law of a master curve at
/// omega0 = speed / length, without a scene (rhabel/materials/master_curve.hpp, fit_at).
struct material_fit_request {
  std::string curve_path;           ///< the master curve (CSV)
  double speed = 0, length = 0;     ///< U and L, > 0
  std::optional<materials::wlf_shift> wlf;  ///< with `temperature`: the curve shifted to it
  double temperature = 0;
  double window_decades = 0.5;      ///< materials::fit_options::half_window_decades
  double threshold = 0.05;          ///< materials::fit_options::warning_threshold
};

struct fitted_material {
  materials::master_curve curve;    ///< as read, shifted when a temperature was given
  materials::local_fit fit;
  std::optional<double> log10_aT;   ///< the WLF shift, when given
};

/// Reads, shifts and fits (input_error "fit-material: ..." naming the file, row and column, or
/// the WLF constants).
fitted_material fit_material(const material_fit_request& request);

/// The JSON of `rhabel fit-material --json`: alpha, E1, omega0, alpha_slope, alpha_tan_delta,
/// modulus, window, status, warning, master_curve, points (and temperature, log10_aT when shifted).
nlohmann::ordered_json fitted_material_json(const material_fit_request& request, const fitted_material& fitted);

/// run_scene for any scene: with a master curve, the fixed point above first. `warning` receives the
/// fit's warning (empty when it is ok or the scene has an explicit material).
run_outcome run_scene_with_material(const scene_spec& scene, const run_request& request, std::string* warning = nullptr);

}  // namespace rhabel::scene
