// cli/scene_solve.hpp: runs a validated scene through the punch layer and renders the result
// as JSON (and, on request, sampled fields for CSV). The only file of the command line that
// depends on the physics API is scene_solve.cpp.
#pragma once

#include "scene_json.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace rhabel::cli {

/// What `rhabel solve` was asked to add to the summary.
struct run_request {
  std::size_t grid = 0;  ///< 0: no sampled fields; otherwise points per field (>= 2)
};

/// A table of sampled values, written as CSV with `columns` as header.
struct sampled_table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

/// Everything `rhabel solve` outputs, computed before anything is written.
struct run_outcome {
  nlohmann::ordered_json result;  ///< the result document (finite numbers only)
  sampled_table pressure;         ///< indentor,x,pressure (empty unless grid > 0)
  sampled_table displacement;     ///< indentor,x,displacement (empty unless grid > 0)
  bool ok = true;                 ///< the result's status is "ok" (else `rhabel solve` exits 3)
};

/// Solves `scene`. Throws input_error if the solver rejects the scene (e.g. indentors whose
/// contact intervals would overlap), std::runtime_error if it fails or produces a non-finite
/// number (nothing is printed then: no NaN or Inf ever reaches the output).
run_outcome run_scene(const scene_spec& scene, const run_request& request);

}  // namespace rhabel::cli
