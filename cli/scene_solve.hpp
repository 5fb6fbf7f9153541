// cli/scene_solve.hpp: runs a validated scene through the punch layer and renders the result
// as JSON (and, on request, sampled fields for CSV). The only file of the command line that
// depends on the physics API is scene_solve.cpp.
#pragma once

#include "scene_json.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rhabel::cli {

/// What `rhabel solve` was asked to add to the summary.
struct run_request {
  std::size_t grid = 0;  ///< 0: no sampled fields; otherwise points per field (>= 2)
  /// punch::solve_options::acceptance, the bar of status "ok"; 0: the solver's default,
  /// default_acceptance (1e-9; 1e-4 for a profile by the boundary-element method).
  double acceptance = 0;
  std::size_t threads = 1;   ///< punch::solve_options::threads (rhabel sweep keeps 1: it runs rows in parallel)
  double time_limit = 0;     ///< punch::solve_options::time_limit (seconds; 0 = none)
  double tolerance = 1e-12;  ///< punch::solve_options::tolerance (--tolerance; commands.hpp)
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

/// Everything `rhabel solve` outputs, computed before anything is written. The sampled arrays
/// live once, in `pressure` and `displacement`: the document holds a placeholder string for each
/// (an unguessable token, grid_token), which write_document replaces by the array itself, so that
/// a 10^6-point grid is never copied into the JSON tree.
struct run_outcome {
  nlohmann::ordered_json result;  ///< the result document (finite numbers only)
  sampled_table pressure;         ///< indentor,x,pressure (empty unless grid > 0)
  sampled_table displacement;     ///< indentor,x,displacement (empty unless grid > 0)
  std::string grid_token;         ///< placeholder prefix of the arrays in `result`
  bool ok = true;                 ///< the result's status is "ok" (else `rhabel solve` exits 3)
};

/// The result document as text (indented by 2, or compact), the sampled arrays in their places:
/// the same bytes as dumping a document that held the arrays. `write` receives consecutive
/// pieces of it.
void write_document(const run_outcome& outcome, bool compact, const std::function<void(std::string_view)>& write);

/// The bar of status "ok" when none is given: 1e-9, or 1e-4 for a profile solved by the
/// boundary-element method (first order: 1e-9 would refine to its panel limit and never be ok).
double default_acceptance(const scene_spec& scene);

/// Solves `scene`. Throws input_error if the solver rejects the scene (e.g. indentors whose
/// contact intervals would overlap), std::runtime_error if it fails or produces a non-finite
/// number (nothing is printed then: no NaN or Inf ever reaches the output).
run_outcome run_scene(const scene_spec& scene, const run_request& request);

}  // namespace rhabel::cli
