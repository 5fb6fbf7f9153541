// rhabel solve SCENE.json [--grid N] [--csv PREFIX] [--compact]
//
// Reads a scene (a JSON file, or stdin for "-"), validates all of it, solves it with the punch
// layer and prints the result as JSON on stdout. Schemas: cli/scene_json.hpp (scene) and
// examples/README.md (scene and result).
//
//   --grid N       adds to each indentor "pressure" (N points strictly inside its contact
//                  interval) and "displacement" (N points on [a - L, b + L]), 2 <= N <= 1e6.
//   --csv PREFIX   also writes PREFIX_pressure.csv (indentor,x,pressure) and
//                  PREFIX_displacement.csv (indentor,x,displacement): all indentors in one file
//                  each, `indentor` is the index in the scene; implies --grid 201 unless given.
//   --compact      one-line JSON instead of the indented form.
//
// Output discipline: everything is computed in memory first; on any error nothing is written to
// stdout and no CSV file is left behind; the error is one line on stderr (exit code 2 for bad
// input, 1 for a solver failure). Numbers are printed by nlohmann-json in the shortest form that
// reads back to the same double (at most 17 significant digits: lossless round trip).
#include "commands.hpp"
#include "scene_json.hpp"
#include "scene_solve.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>

namespace rhabel::cli {
namespace {

constexpr std::size_t default_csv_grid = 201;
constexpr std::size_t max_grid = 1'000'000;

struct solve_arguments {
  std::string scene_path;
  std::size_t grid = 0;
  std::string csv_prefix;
  bool csv = false;  // --csv given (an empty prefix is an error, not "no CSV")
  bool compact = false;
};

std::string read_scene(const std::string& path) {
  if (path == "-") {
    std::ostringstream text;
    text << std::cin.rdbuf();
    if (std::cin.bad()) throw input_error("solve: cannot read the scene from stdin");
    return text.str();
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw input_error("solve: cannot read scene file '" + path + "': it is a directory");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw input_error("solve: cannot read scene file '" + path + "': " + std::strerror(errno));
  }
  try {
    std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
    if (!file.bad()) return text;
  } catch (const std::exception&) {  // libstdc++ throws from underflow on some read errors
  }
  throw input_error("solve: cannot read scene file '" + path + "': read error");
}

void write_table(std::ostream& out, const sampled_table& table) {
  for (std::size_t j = 0; j < table.columns.size(); ++j) out << (j ? "," : "") << table.columns[j];
  out << '\n';
  char buffer[32];
  for (const auto& row : table.rows) {
    for (std::size_t j = 0; j < row.size(); ++j) {
      std::snprintf(buffer, sizeof buffer, "%.17g", row[j]);
      out << (j ? "," : "") << buffer;
    }
    out << '\n';
  }
}

// Writes both CSV files or neither: each goes to a temporary name first and is renamed only
// once both are complete.
void write_csv_files(const std::string& prefix, const run_outcome& outcome) {
  const std::string names[2] = {prefix + "_pressure.csv", prefix + "_displacement.csv"};
  const sampled_table* tables[2] = {&outcome.pressure, &outcome.displacement};
  std::string temporaries[2];
  auto discard = [&] {
    for (const auto& t : temporaries) {
      if (!t.empty()) std::remove(t.c_str());
    }
  };
  for (int i = 0; i < 2; ++i) {
    temporaries[i] = names[i] + ".partial";
    std::ofstream out(temporaries[i], std::ios::binary | std::ios::trunc);
    if (!out) {
      const std::string reason = std::strerror(errno);
      temporaries[i].clear();
      discard();
      throw input_error("solve: --csv " + prefix + ": cannot write '" + names[i] + "': " + reason);
    }
    write_table(out, *tables[i]);
    out.close();
    if (!out) {
      discard();
      throw input_error("solve: --csv " + prefix + ": writing '" + names[i] + "' failed");
    }
  }
  for (int i = 0; i < 2; ++i) {
    if (std::rename(temporaries[i].c_str(), names[i].c_str()) != 0) {
      const std::string reason = std::strerror(errno);
      discard();
      if (i == 1) std::remove(names[0].c_str());
      throw input_error("solve: --csv " + prefix + ": cannot create '" + names[i] + "': " + reason);
    }
  }
}

int run(const solve_arguments& args) {
  if (args.csv && args.csv_prefix.empty()) throw input_error("solve: --csv needs a non-empty PREFIX");
  const std::string source = args.scene_path == "-" ? "(stdin)" : "'" + args.scene_path + "'";
  const scene_spec scene = parse_scene(read_scene(args.scene_path), source);

  run_request request;
  request.grid = args.grid;
  if (request.grid == 0 && args.csv) request.grid = default_csv_grid;
  const run_outcome outcome = run_scene(scene, request);

  // Serialise before writing anything so that a failure cannot leave partial output.
  const std::string document = args.compact ? outcome.result.dump() : outcome.result.dump(2);
  if (args.csv) write_csv_files(args.csv_prefix, outcome);
  std::fwrite(document.data(), 1, document.size(), stdout);
  std::fputc('\n', stdout);
  if (std::fflush(stdout) != 0) return 1;
  return outcome.ok ? 0 : 3;  // 3: the result is written but its status is not "ok"
}

}  // namespace

void add_solve_command(CLI::App& app, command_action& action) {
  auto args = std::make_shared<solve_arguments>();
  auto* solve = app.add_subcommand(
      "solve",
      "Solve a scene: rigid indentors sliding over a power-law viscoelastic half-space.\n"
      "Prints the result as JSON on stdout (schema: examples/README.md).");
  solve->add_option("SCENE", args->scene_path, "scene file (JSON), or - for stdin")->required();
  solve
      ->add_option("--grid", args->grid,
                   "sample pressure (N points in each contact interval) and surface displacement (N points)")
      ->check(CLI::Range(std::size_t{2}, max_grid));
  auto* csv = solve->add_option("--csv", args->csv_prefix,
                    "also write PREFIX_pressure.csv (indentor,x,pressure) and PREFIX_displacement.csv "
                    "(indentor,x,displacement); implies --grid 201");
  solve->add_flag("--compact", args->compact, "print the JSON on one line");
  solve->callback([&action, args, csv] {
    args->csv = csv->count() > 0;
    action = [args] { return run(*args); };
  });
}

}  // namespace rhabel::cli
