// rhabel/scene/sweep.hpp: the sweep file of `rhabel sweep` and `rhabel.sweep`, the rows it
// produces (schema in examples/README.md, "Sweeps"), and the pool of threads that solves them.
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

#include "rhabel/scene/solve.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace rhabel::scene {

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

/// The scene of row i: the base with the row's values set (parse_scene takes it as it is).
nlohmann::json row_scene(const sweep_spec& sweep, std::size_t row);

/// Output format of the rows.
enum class row_format { csv, jsonl };

/// Column names of a row (CSV header, JSON-lines keys), in order.
std::vector<std::string> row_columns(const sweep_spec& sweep);

/// The CSV header line (with '\n'); empty for JSON lines.
std::string header_line(const sweep_spec& sweep, row_format format);

/// The deterministic beginning of row i's line: its index and swept values, up to and including
/// the separator before the solve options (used to recognise rows already written when resuming).
std::string row_prefix(const sweep_spec& sweep, std::size_t row, row_format format);

/// The solve options every row records after its swept values, up to and including the separator
/// before the status: tolerance, acceptance (empty in CSV, null in JSON: the solver's default) and,
/// for a sampled profile, profile_knots. A row solved under other options is not resumed
/// (sweep_output). time_limit is not among them: a budget, not a bar (a row that ran out of time
/// says so in its status).
std::string row_options(const sweep_spec& sweep, row_format format, const run_request& request);

/// Whether `line` (with its '\n') is a whole row as solve_row writes it: CSV with exactly the
/// columns' count of fields (quoted fields as csv_field writes them), or a JSON object with exactly
/// the columns as keys. A torn line (a killed writer, a full disk) is not.
bool is_complete_row(const sweep_spec& sweep, row_format format, std::string_view line);

/// Solves row i and returns its whole line (with '\n'); never throws for a failed scene (the row
/// then carries its status and message). `ok` is set to whether the status is "ok". request: the
/// options of each row's solve (time_limit, tolerance, acceptance; grid 0, one thread).
std::string solve_row(const sweep_spec& sweep, std::size_t row, row_format format, bool& ok, const run_request& request);

/// A row solved by a sweep_pool: its index and its whole line.
struct finished_row {
  std::size_t row;
  std::string line;
};

/// Worker threads solving `rows` of a sweep (solve_row, each row's solve on one thread); the
/// caller collects the finished lines with take() in the order they finish. The destructor stops
/// the workers after the rows under way (request.interrupt ends those early).
class sweep_pool {
 public:
  sweep_pool(const sweep_spec& sweep, row_format format, std::vector<std::size_t> rows, std::size_t threads,
             const run_request& request);
  ~sweep_pool();
  sweep_pool(const sweep_pool&) = delete;
  sweep_pool& operator=(const sweep_pool&) = delete;
  std::size_t size() const { return rows_.size(); }
  /// Waits up to `wait` for finished rows and moves them out.
  std::vector<finished_row> take(std::chrono::milliseconds wait);

 private:
  void work();
  const sweep_spec& sweep_;
  row_format format_;
  std::vector<std::size_t> rows_;
  run_request request_;  // each row's solve options
  std::atomic<std::size_t> next_{0};
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<finished_row> done_;
  std::vector<std::thread> workers_;
};

/// The output file of a sweep (`rhabel sweep --out`, `rhabel.sweep(out=...)`), resumable: the
/// constructor reads FILE if it exists (its header must be this sweep's and every complete line one
/// of its rows solved under `request`'s options (row_options), else input_error naming the file,
/// the line and, for a row of other options, both options; a torn last line is cut off), opens
/// it for appending and writes the header when missing; append() writes each new row as one whole
/// write; finish() rewrites FILE with every row once, in row order (a temporary in the same
/// directory, then rename). Write failures are write_error, naming the file.
class sweep_output {
 public:
  sweep_output(const sweep_spec& sweep, row_format format, std::string file, const run_request& request);
  ~sweep_output();
  sweep_output(const sweep_output&) = delete;
  sweep_output& operator=(const sweep_output&) = delete;
  /// The rows not yet in FILE, in row order.
  std::vector<std::size_t> missing() const;
  void append(finished_row&& row);
  void finish();
  /// Every row's line, by row (those found in FILE and those appended).
  const std::map<std::size_t, std::string>& lines() const { return lines_; }
  /// Whether every row's status is "ok".
  bool all_ok() const;

 private:
  const sweep_spec& sweep_;
  row_format format_;
  std::string file_, header_, options_;
  std::map<std::size_t, std::string> lines_;
  int fd_ = -1;
};

}  // namespace rhabel::scene
