// rhabel/scene/solve.hpp: runs a validated scene through the punch layer and renders the result
// as JSON (and, on request, sampled fields for CSV), with the solver's typed result beside it (the
// command line's sweep rows and the master-curve fixed point read that, not the document). The
// only file of the scene layer that calls the physics API (rhabel::punch) is scene/src/solve.cpp.
#pragma once

#include "rhabel/scene/scene.hpp"

#include "rhabel/punch/contact.hpp"
#include "rhabel/punch/profile.hpp"
#include "rhabel/punch/profile_bem.hpp"
#include "rhabel/materials/master_curve.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rhabel::scene {

/// What `rhabel solve` was asked to add to the summary.
struct run_request {
  std::size_t grid = 0;  ///< 0: no sampled fields; otherwise points per field (>= 2)
  /// How the front end spells the option behind `grid`, for its refusal (a boundary-element
  /// profile has no fields): the command line's "--grid and --csv", Python's "grid".
  std::string grid_option = "--grid and --csv";
  /// punch::solve_options::acceptance, the bar of status "ok"; 0: the solver's default,
  /// default_acceptance (1e-9; 1e-4 for a profile by the boundary-element method).
  double acceptance = 0;
  std::size_t threads = 1;   ///< punch::solve_options::threads (rhabel sweep keeps 1: it runs rows in parallel)
  double time_limit = 0;     ///< punch::solve_options::time_limit (seconds; 0 = none)
  double tolerance = 1e-12;  ///< punch::solve_options::tolerance (--tolerance of the command line)
  bool displacement = true;  ///< punch::solve_options::displacement: with grid > 0, also the displacement samples
  punch::sample_spacing spacing = punch::sample_spacing::uniform;  ///< punch::solve_options::spacing
  bool residual = true;      ///< punch::solve_options::residual (false: not computed; the document has null)
  double layered_below = punch::solve_options{}.layered_below;  ///< punch::solve_options::layered_below
  /// punch::solve_options::profile_knots: a sampled profile's spline knots inside a contact as
  /// singular terms of its density (the spectral search; the command line's --profile-knots).
  bool profile_knots = false;
  /// punch::solve_options::interrupt: polled during a solve; returning true stops it with
  /// punch::interrupted (the Python package's Ctrl-C). Empty: never.
  std::function<bool()> interrupt;
};

/// One indentor's samples of a field: abscissae and values (finite), of equal sizes.
struct sampled_field {
  std::size_t indentor = 0;
  std::vector<double> x, value;
};

/// A table of sampled values, written as CSV with `columns` as header (indentor,x,value): the
/// rows of each field in turn.
struct sampled_table {
  std::vector<std::string> columns;
  std::vector<sampled_field> fields;
};

/// A master-curve material's fit (material.hpp), typed; the document's "material_fit".
struct material_fit_report {
  materials::local_fit fit;      ///< the converged power law at omega0 (alpha, E1, its evidence)
  double contact_length = 0;     ///< the L of omega0 = U/L at the fixed point
  std::size_t iterations = 0;    ///< solves of the fixed point
  std::optional<double> log10_aT;  ///< the WLF shift, when a temperature was given
  materials::fit_status status = materials::fit_status::ok;  ///< the fit's, or not_converged
  std::string warning;           ///< why, when status is not "ok"
};

/// Everything `rhabel solve` outputs, computed before anything is written. The sampled arrays
/// live once, in `pressure` and `displacement`: the document holds a placeholder string for each
/// (an unguessable token, grid_token), which write_document replaces by the array itself, so that
/// a 10^6-point grid is never copied into the JSON tree.
struct run_outcome {
  /// The solver's result, typed (the document below is written from it): punch::scene_result for
  /// indentors, punch::profile_result for a profile by the spectral search,
  /// punch::profile_bem_result by the boundary-element method. Its sampled fields, when asked
  /// for, have moved to `pressure` and `displacement`.
  std::variant<punch::scene_result, punch::profile_result, punch::profile_bem_result> solved;
  std::optional<material_fit_report> fit;  ///< a master-curve material's fit (run_scene_with_material)
  nlohmann::ordered_json result;  ///< the result document (finite numbers only)
  sampled_table pressure;         ///< indentor,x,pressure (empty unless grid > 0)
  sampled_table displacement;     ///< indentor,x,displacement (empty unless grid > 0)
  /// x,displacement: the surface of several contacts on one grid (punch::scene_result::surface;
  /// one field, empty unless grid > 0 and the scene has several contacts)
  sampled_table surface;
  std::string grid_token;         ///< placeholder prefix of the arrays in `result`
  bool ok = true;                 ///< the result's status is "ok" (else `rhabel solve` exits 3)

  /// The sampled array that a string of `result` stands for (grid_token, then "p", "d" or "s"
  /// for the pressure, displacement or surface table, the field's index, and "x" or "v" for abscissae or values),
  /// or nullptr when `text` is no placeholder of this outcome. write_document and the Python
  /// package put the arrays in their places with it.
  const std::vector<double>* array(std::string_view text) const;
  std::vector<double>* array(std::string_view text);
};

/// The result document as text (indented by 2, or compact), the sampled arrays in their places:
/// the same bytes as dumping a document that held the arrays. `write` receives consecutive
/// pieces of it.
void write_document(const run_outcome& outcome, bool compact, const std::function<void(std::string_view)>& write);

/// The bar of status "ok" when none is given: 1e-9, or 1e-4 for a profile solved by the
/// boundary-element method (first order: 1e-9 would refine to its panel limit and never be ok).
double default_acceptance(const scene_spec& scene);

/// The punch layer's scene of a validated scene of indentors (not a profile), as run_scene solves it.
punch::scene punch_scene(const scene_spec& scene);

/// The validated scene as the result document's "scene" echoes it (defaults filled in); a
/// profile's samples stand as their count and range, or with `samples` as the arrays "x" and "z".
nlohmann::ordered_json scene_json(const scene_spec& scene, bool samples = false);

/// Solves `scene`. Throws input_error if the solver rejects the scene (e.g. indentors whose
/// contact intervals would overlap), std::runtime_error if it fails or produces a non-finite
/// number (nothing is printed then: no NaN or Inf ever reaches the output).
run_outcome run_scene(const scene_spec& scene, const run_request& request);

}  // namespace rhabel::scene
