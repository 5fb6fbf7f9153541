// rhabel/scene/scene.hpp: the scene file of `rhabel solve` and `rhabel.solve`, parsed and validated.
//
// A scene is one JSON object (SI or any consistent units; the schema is documented in
// examples/README.md and in `rhabel solve --help`):
//
//   {"description": "optional free text",
//    "material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.5, "coulomb": 0.0, "name": "optional"},
//    "speed": 0.01,
//    "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 100.0, "apex": 0.0},
//                  {"shape": "wedge", "slope_leading": 0.1, "slope_trailing": 0.1, "load": 50.0},
//                  {"shape": "flat", "width": 0.004, "load": 20.0, "apex": 0.05}]}
//
// Instead of alpha and E1 the material may name a measured master curve (see master_curve_spec):
//   "material": {"master_curve": "FILE.csv", "temperature": 40, "wlf": {"C1": 8.86, "C2": 101.6,
//                "T_ref": 20}, "nu": 0.5, "coulomb": 0.3}
//
// Field            valid range        meaning
// material.alpha   [0, 1)             power-law exponent, E(t) = E1 t^-alpha (0: elastic)
// material.E1      (0, inf)           modulus coefficient, unit stress * time^alpha
// material.nu      [0, 0.5]           Poisson ratio, as rhabel::punch (0.5: incompressible: beta = 0)
// material.coulomb [0, inf)           Coulomb friction coefficient k at the interface
// speed            (0, inf)           sliding speed U; the indentors move towards -x
// indentors        non-empty array    rigid indentors sliding together on one half-space
//   shape          "parabolic" | "wedge" | "flat"
//   load           (0, inf)           normal force per unit length (plane strain)
//   apex           finite, default 0  position of the apex (wedge tip, parabola vertex,
//                                     centre of the flat face)
//   radius         (0, inf)           parabolic only: radius of curvature, f = -(x-apex)^2/(2R)
//   slope_leading  (0, inf)           wedge only: slope of the face ahead of the tip (x < apex)
//   slope_trailing (0, inf)           wedge only: slope of the face behind the tip (x > apex)
//   width          (0, inf)           flat only: width of the face, centred at apex
//   name           string, optional   label used in tables and plots
//   height         finite, default 0  with a body only: height of the apex on the body (upward)
// body             object, optional   {"load": P}: all indentors on one rigid body pressed with the
//                                     total load P in (0, inf); the indentors then have no `load`
//                                     (the split is solved) and may have a `height`
// profile          object, optional   instead of indentors (with a body): a sampled rigid profile
//                                     whose contacts are found, {"x": [..], "z": [..]} or
//                                     {"file": "FILE.csv"}, optional "corners": [..], "period" (0, inf)
//                                     and "solver" ("spectral" | "boundary_element"), "max_panels"
//                                     (boundary_element: the finest grid, 256 .. 2^23) (profile_spec)
//
// Policy (decided deliberately, each one is tested in tests/cli/test_solve_errors.sh):
// - Every field listed is required except `apex`, `name`, `description` (and `material.name`),
//   `body` and `height`; with a body an indentor's `load` is an error, without one its `height`.
//   Unknown fields are errors, including a field of another shape (a `radius` on a wedge):
//   a misspelt optional field must not be silently ignored.
// - Duplicate keys are errors (nlohmann-json would keep the last one silently).
// - Numbers that overflow a double (1e400) are errors: nlohmann-json reads them as +-inf.
//   Numbers that underflow (1e-400) read as 0 or a subnormal and are then judged by their range.
//   Integers (100) are accepted wherever a number is expected. Booleans and strings are not numbers.
// - The whole input is parsed: a NUL byte anywhere, or anything but white space after the
//   object, is an error naming its byte offset (from 0).
// - Arrays and objects may nest at most max_scene_depth = 256 levels (a scene needs 3; any
//   value, also inside "description", counts): deeper input is refused before it is parsed,
//   at any depth (a value nested 75,000 deep crashed the program: issue 14).
// - The message of every error is one line that names the field as a path
//   (`indentors[0].radius`), the offending value and the valid range.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rhabel::scene {

/// Deepest nesting of arrays and objects accepted in a scene (the top-level object is level 1).
inline constexpr std::size_t max_scene_depth = 256;

/// A material given by its measured master curve instead of (alpha, E1) (rhabel/scene/material.hpp):
///   "material": {"master_curve": "FILE.csv", "temperature": T, "wlf": {"C1": .., "C2": .., "T_ref": ..},
///                "nu": .., "coulomb": .., "name": ".."}
/// The path is relative to the scene file's directory (to the working directory for stdin).
/// `temperature` and `wlf` go together (both or neither); without them the curve is used as is.
struct master_curve_spec {
  std::string path;           ///< as written in the scene
  std::string resolved_path;  ///< path joined to the scene's directory
  bool shifted = false;       ///< temperature and wlf given
  double temperature = 0;     ///< finite
  double C1 = 0;              ///< (0, inf)
  double C2 = 0;              ///< (0, inf)
  double T_ref = 0;           ///< finite
};

/// Power-law viscoelastic half-space, E(t) = E1 t^-alpha, and its interface friction.
/// With a master curve, alpha and E1 are 0 until the master-curve fit (material.hpp) sets them.
struct material_spec {
  double alpha = 0;    ///< material exponent, [0, 1)
  double E1 = 0;       ///< modulus coefficient, > 0
  double nu = 0;       ///< Poisson ratio, [0, 0.5]
  double coulomb = 0;  ///< Coulomb coefficient k >= 0
  std::string name;    ///< optional label
  std::optional<master_curve_spec> curve;  ///< set when the scene gives "master_curve"
};

enum class shape_kind { parabolic, wedge, flat };

/// Name of a shape as written in the scene ("parabolic", "wedge", "flat").
const char* shape_name(shape_kind shape) noexcept;

/// One rigid indentor. Only the geometry fields of its own shape are meaningful (others are 0).
struct indentor_spec {
  shape_kind shape = shape_kind::parabolic;
  double load = 0;            ///< force per unit length, > 0 (0 on a rigid body: an unknown)
  double apex = 0;            ///< apex position
  double height = 0;          ///< rigid body only: height of the apex on the body (upward)
  double radius = 0;          ///< parabolic
  double slope_leading = 0;   ///< wedge, face at x < apex
  double slope_trailing = 0;  ///< wedge, face at x > apex
  double width = 0;           ///< flat
  std::string name;           ///< optional label ("" if absent)
};

/// A sampled rigid profile (rhabel::punch::solve_profile): "profile": {"x": [...], "z": [...]}
/// or {"file": "FILE.csv"} (two columns x,z; a header line and lines starting with # are
/// skipped; the path relative to the scene file's directory), with optional "corners": [...].
/// The samples' own rules (increasing x, corners on samples) are the solver's, named by it.
struct profile_spec {
  std::vector<double> x, z, corners;
  std::string file;  ///< as written in the scene ("" for inline samples)
  double period = 0;  ///< "period" (> 0: periodic; 0: a finite window)
  /// "solver": "boundary_element" (punch::solve_profile_bem; the default with a period) or
  /// "spectral" (punch::solve_profile; the default without).
  bool boundary_element = false;
  /// "max_panels" (boundary_element only; 0: punch::bem_options' default, 2^21).
  std::size_t max_panels = 0;
};

/// A validated scene: every number finite and inside its documented range.
struct scene_spec {
  std::string description;
  material_spec material;
  double speed = 0;
  std::optional<double> body_load;  ///< "body": {"load": P}: all indentors (or the profile) on one rigid body
  std::vector<indentor_spec> indentors;  ///< empty when `profile` is given
  std::optional<profile_spec> profile;   ///< a sampled profile instead of indentors (needs the body)
};

/// Parses and validates a scene. `source` names the input in messages (a file name or "stdin").
/// Throws rhabel::scene::input_error (one line, naming the field and its valid range) on any
/// syntax, type, range, missing-field, unknown-field or duplicate-key error. Never partial.
/// `base_dir` is the directory that a relative "master_curve" path is resolved against.
scene_spec parse_scene(std::string_view text, const std::string& source, const std::string& base_dir = {});

/// parse_scene for a scene already parsed (a sweep's row: its base scene with the axes' values set),
/// with the same checks and messages, but those of the text itself (NUL bytes, syntax, duplicate
/// keys), which a value cannot have.
scene_spec parse_scene_value(const nlohmann::json& scene, const std::string& source, const std::string& base_dir = {});

}  // namespace rhabel::scene
