// libFuzzer target for the sweep schema of `rhabel sweep` (rhabel/scene/sweep.hpp; tests/fuzz/README.md).
//
// Each input is the text of a sweep file (its scene inline: a scene named by file is read from the
// working directory, which holds none of the fuzzer's names). parse_sweep must either refuse it
// with an input_error (exit code 2, "sweep: ...") or return a sweep whose promises hold: between 1
// and max_sweep_rows rows, at least one axis, every axis path a scalar field of the base scene.
// For a few rows (the first, the last and one in between) the row's scene is built and parsed
// (parse_scene may refuse it: that row's status is invalid_scene), its CSV and JSON-lines prefix
// written, and a whole row line recognised by is_complete_row while a torn one is not. Rows are
// not solved (the solve entry has its own target, fuzz_scene). Anything else is a finding.
#include "commands.hpp"
#include "fuzz_support.hpp"

#include <rhabel/scene.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

namespace {

[[noreturn]] void finding(const char* what, const char* message = "") { rhabel::fuzz::finding("fuzz_sweep", what, message); }

void check_row(const rhabel::cli::sweep_spec& sweep, std::size_t row) {
  using namespace rhabel::cli;
  try {
    (void)parse_scene_value(row_scene(sweep, row), "(fuzz row)");
  } catch (const input_error&) {  // the row's status would be invalid_scene
  }
  for (const auto format : {row_format::csv, row_format::jsonl}) {
    // A made-up whole row: the prefix, then every output column empty (CSV) or null (JSON).
    const auto columns = row_columns(sweep);
    std::string line = row_prefix(sweep, row, format);
    for (std::size_t j = 1 + sweep.axes.size(); j < columns.size(); ++j) {
      const bool first = j == 1 + sweep.axes.size();
      line += format == row_format::csv ? (first ? "" : ",")
                                        : (first ? "" : ",") + nlohmann::json(columns[j]).dump() + ":null";
    }
    line += format == row_format::csv ? "\n" : "}\n";
    if (!is_complete_row(sweep, format, line)) finding("a whole row is not recognised as one", line.c_str());
    const std::string torn = line.substr(0, line.size() / 2) + "\n";
    if (is_complete_row(sweep, format, torn)) finding("a torn row is taken for a whole one", torn.c_str());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rhabel::cli;
  const std::string text(reinterpret_cast<const char*>(data), size);
  sweep_spec sweep;
  auto parse = [&] { sweep = parse_sweep(text, "fuzz sweep", "/nonexistent-fuzz-directory"); };
  if (!rhabel::fuzz::accepted<input_error>("fuzz_sweep", "parse_sweep", parse)) return 0;  // refused: exit code 2
  if (sweep.rows < 1 || sweep.rows > max_sweep_rows || sweep.axes.empty()) finding("a sweep of no rows or no axes");
  for (const auto& axis : sweep.axes) {
    if (axis.values.empty()) finding("an axis without values");
    if (sweep.base.contains(axis.pointer) && !sweep.base.at(axis.pointer).is_primitive()) {
      finding("an axis path that is not a scalar field", axis.path.c_str());
    }
  }
  try {
    (void)header_line(sweep, row_format::csv);
    check_row(sweep, 0);
    check_row(sweep, sweep.rows / 2);
    check_row(sweep, sweep.rows - 1);
  } catch (const std::exception& e) {
    finding("building a row threw", e.what());
  }
  return 0;
}
