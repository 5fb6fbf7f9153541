// cli/sweep.hpp: the sweep file of `rhabel sweep` and the rows it produces (schema in
// examples/README.md, "Sweeps").
//
//   {"description": "optional",
//    "scene": "default_scene.json"  or  {... a scene object ...},
//    "axes": [{"path": "speed", "log_range": {"from": 1e-6, "to": 1e2, "count": 33}},
//             {"path": "indentors[0].load", "values": [100, 200]},
//             {"path": "material.coulomb", "range": {"from": 0, "to": 1, "count": 5}}],
//    "combine": "product" (default) | "zip"}
//
// - `path` names any scalar field of the scene by its JSON path (`speed`, `indentors[0].load`,
//   `material.temperature`: letters, digits, _, . and [index]); its parent must exist in the base
//   scene (the field itself may be absent, e.g. an `apex` left at its default, but must be one the
//   scene knows: otherwise the sweep is refused up front). The swept values are judged like any scene value:
//   a value outside its valid range makes that row's status "invalid_scene", the sweep goes on.
// - `log_range`: count values from * (to/from)^(i/(count-1)), i = 0 .. count-1, computed as
//   exp(ln from + i (ln to - ln from)/(count - 1)) with both ends exact; `range`: the same linearly;
//   `values`: a list of numbers (or strings, booleans). count >= 1 (1: just `from`).
// - product: rows in C order, the LAST axis varying fastest; zip: all axes of one length, row i takes
//   value i of each. At most max_rows rows.
// - A relative scene path is relative to the sweep file; a relative master_curve path to the file
//   that holds the scene (made absolute in the rows' scenes, so each row's scene stands alone).
#pragma once

#include <rhabel/scene.hpp>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rhabel::cli {

using namespace rhabel::scene;  // as commands.hpp

inline constexpr std::size_t max_sweep_rows = 100'000'000;

struct sweep_axis {
  std::string path;                        ///< as written: "indentors[0].load"
  nlohmann::json::json_pointer pointer;    ///< /indentors/0/load
  std::vector<nlohmann::json> values;      ///< scalars
};

struct sweep_spec {
  nlohmann::json base;            ///< the base scene (master_curve made absolute)
  std::vector<sweep_axis> axes;
  bool zip = false;
  std::size_t rows = 0;
  std::size_t indentors = 0;      ///< of the base scene (every row has as many)
  bool profile = false;           ///< the base scene is a sampled profile (its own columns)
};

/// Reads and validates a sweep file (and its base scene). Throws input_error ("sweep: ...").
sweep_spec read_sweep(const std::string& path);

/// The same for the sweep file's text: `source` names it in messages, relative file names are
/// relative to `directory`.
sweep_spec parse_sweep(const std::string& text, const std::string& source, const std::string& directory);

/// Values of the axes for row i (one per axis).
std::vector<nlohmann::json> row_values(const sweep_spec& sweep, std::size_t row);

/// The scene of row i as JSON text (compact): the base with the row's values set.
std::string row_scene(const sweep_spec& sweep, std::size_t row);

/// Output format of the rows.
enum class row_format { csv, jsonl };

/// Column names of a row (CSV header, JSON-lines keys), in order.
std::vector<std::string> row_columns(const sweep_spec& sweep);

/// The CSV header line (with '\n'); empty for JSON lines.
std::string header_line(const sweep_spec& sweep, row_format format);

/// The deterministic beginning of row i's line: its index and inputs, up to and including the
/// separator before the status (used to recognise rows already written when resuming).
std::string row_prefix(const sweep_spec& sweep, std::size_t row, row_format format);

/// Whether `line` (with its '\n') is a whole row as solve_row writes it: CSV with exactly the
/// columns' count of fields (quoted fields as csv_field writes them), or a JSON object with exactly
/// the columns as keys. A torn line (a killed writer, a full disk) is not.
bool is_complete_row(const sweep_spec& sweep, row_format format, std::string_view line);

/// Solves row i and returns its whole line (with '\n'); never throws for a failed scene (the row
/// then carries its status and message). `ok` is set to whether the status is "ok". request: the
/// options of each row's solve (time_limit, tolerance, acceptance; grid 0, one thread).
std::string solve_row(const sweep_spec& sweep, std::size_t row, row_format format, bool& ok, const run_request& request);

}  // namespace rhabel::cli
