// rhabel solve SCENE.json [--grid N] [--grid-spacing uniform|graded] [--csv PREFIX] [--acceptance TOL]
//              [--tolerance TOL] [--threads N] [--time-limit S] [--profile-knots] [--compact]
//
// Reads a scene (a JSON file, or stdin for "-"), validates all of it, solves it with the punch
// layer and prints the result as JSON on stdout. Schemas: rhabel/scene/scene.hpp (scene) and
// examples/README.md (scene and result).
//
//   --grid N       adds to each indentor "pressure" (N points strictly inside its contact
//                  interval) and "displacement" (N points on [a - L, b + L]), 2 <= N <= 1e6;
//                  several contacts: "surface" (the whole surface, N points a contact).
//   --grid-spacing uniform (default) or graded: the pressure samples at midpoints of equal
//                  cells or at Chebyshev points (dense next to the edges).
//   --csv PREFIX   also writes PREFIX_pressure.csv (indentor,x,pressure) and
//                  PREFIX_displacement.csv (indentor,x,displacement): all indentors in one file;
//                  several contacts: PREFIX_surface.csv (x,displacement), the whole surface
//                  each, `indentor` is the index in the scene; implies --grid 201 unless given.
//   --acceptance TOL  the bar of status "ok" (punch::solve_options::acceptance, default 1e-9; 1e-4 for
//                     profile.solver boundary_element).
//   --tolerance TOL   relative tolerance of the root finders and expansions
//                  (punch::solve_options::tolerance, default 1e-12, in [1e-15, 1e-2]).
//   --threads N    threads for the Jacobian columns of several contacts (punch::solve_options::threads;
//                  default 0: every core); the result does not depend on N.
//   --time-limit S seconds after which a solve of several contacts stops and reports what it
//                  reached with status not_converged (punch::solve_options::time_limit; default 0:
//                  no limit).
//   --profile-knots  a sampled profile's spline knots inside each contact as singular terms of its
//                  density (punch::solve_options::profile_knots; default off).
//   --compact      one-line JSON instead of the indented form.
//
// Output discipline: everything is computed in memory first; on any error nothing is written to
// stdout and no CSV file is left behind; the error is one line on stderr (exit code 2 for bad
// input, a scene that cannot be solved, or a failed write; 1 for an internal error such as a
// non-finite solver result). The CSV files are written to temporaries in their directory and
// renamed into place only after stdout was written and flushed successfully; a failed write
// (of a CSV file, or of stdout: a full disk, /dev/full) removes the temporaries. If the final
// rename fails, stdout already holds the result, but no CSV file is left (exit code 2). Numbers
// are printed in the shortest form that reads back to the same double (at most 17 significant
// digits: lossless round trip): by nlohmann-json in the JSON, by std::to_chars in the CSV files.
#include "commands.hpp"

#include <rhabel/scene.hpp>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace rhabel::cli {
namespace {

constexpr std::size_t default_csv_grid = 201;
constexpr std::size_t max_grid = 1'000'000;

struct solve_arguments {
  std::string scene_path;
  std::size_t grid = 0;
  std::string spacing = "uniform";  // --grid-spacing: "uniform" or "graded"
  std::string csv_prefix;
  bool csv = false;  // --csv given (an empty prefix is an error, not "no CSV")
  bool compact = false;
  double acceptance = 0;  // 0: not given, the solver's default (run_request::acceptance)
  double tolerance = 1e-12;
  std::size_t threads = 0;  // every core
  double time_limit = 0;    // none
  bool profile_knots = false;
};

std::string read_scene(const std::string& path) {
  try {
    return materials::read_text_file(path, path == "-" ? "the scene from" : "scene file", materials::max_text_file_bytes,
                                     true);
  } catch (const std::invalid_argument& e) {
    throw input_error(std::string("solve: ") + e.what());
  }
}

void write_table(std::FILE* out, const sampled_table& table) {
  for (std::size_t j = 0; j < table.columns.size(); ++j) {
    std::fputs(j ? "," : "", out);
    std::fputs(table.columns[j].c_str(), out);
  }
  std::fputc('\n', out);
  // Numbers in the shortest form that reads back to the same double (std::to_chars), as in the
  // JSON; lines gathered in a buffer (fprintf's "%.17g" cost ~1 us a number).
  std::string buffer;
  char number[64];
  auto append = [&](double v) { buffer.append(number, std::to_chars(number, number + sizeof number, v).ptr); };
  // A table of one curve (the surface) has no index column.
  const bool indexed = table.columns.size() == 3;
  for (const auto& field : table.fields) {
    const std::string indentor = indexed ? std::to_string(field.indentor) + "," : std::string();
    for (std::size_t k = 0; k < field.x.size(); ++k) {
      buffer += indentor;
      append(field.x[k]);
      buffer += ',';
      append(field.value[k]);
      buffer += '\n';
      if (buffer.size() > (1u << 20)) {
        std::fwrite(buffer.data(), 1, buffer.size(), out);
        buffer.clear();
      }
    }
  }
  std::fwrite(buffer.data(), 1, buffer.size(), out);
}

// The CSV files (PREFIX_pressure.csv, PREFIX_displacement.csv, and PREFIX_surface.csv for
// several contacts) as one transaction: write() puts each into a fresh temporary file in the
// same directory (PREFIX_pressure.csv.XXXXXX, mkstemp, so nothing of the user's is overwritten
// before the end), commit() renames them into place. Until commit() succeeds the destructor
// removes every temporary, on any error or exception, so a failed run leaves no CSV file and no
// temporary (only a signal that kills the process can leave a temporary behind).
class csv_transaction {
 public:
  csv_transaction(std::string prefix, const run_outcome& outcome) : prefix_(std::move(prefix)) {
    add("_pressure.csv", outcome.pressure);
    add("_displacement.csv", outcome.displacement);
    if (!outcome.surface.fields.empty()) add("_surface.csv", outcome.surface);
  }
  csv_transaction(const csv_transaction&) = delete;
  csv_transaction& operator=(const csv_transaction&) = delete;
  ~csv_transaction() {
    for (const auto& t : temporaries_) {
      if (!t.empty()) std::remove(t.c_str());
    }
  }

  void write() {
    for (std::size_t i = 0; i < names_.size(); ++i) write_one(i);
  }

  // Renames the temporaries into place; if a rename fails the files already renamed are removed.
  void commit() {
    for (std::size_t i = 0; i < names_.size(); ++i) {
      if (std::rename(temporaries_[i].c_str(), names_[i].c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        for (std::size_t j = 0; j < i; ++j) std::remove(names_[j].c_str());
        fail("cannot create '" + names_[i] + "': " + reason);
      }
      temporaries_[i].clear();
    }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw write_error("solve: --csv " + prefix_ + ": " + what);
  }

  void add(const char* suffix, const sampled_table& table) {
    names_.push_back(prefix_ + suffix);
    tables_.push_back(&table);
    temporaries_.emplace_back();
  }

  void write_one(std::size_t i) {
    std::string pattern = names_[i] + ".XXXXXX";
    errno = 0;
    const int fd = ::mkstemp(pattern.data());
    if (fd < 0) fail("cannot write '" + names_[i] + "': " + std::strerror(errno));
    temporaries_[i] = pattern;
    // mkstemp creates the file with mode 0600; give it the mode a plain open would have.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    std::FILE* out = ::fdopen(fd, "wb");
    if (out == nullptr) {
      const std::string reason = std::strerror(errno);
      ::close(fd);
      fail("cannot write '" + names_[i] + "': " + reason);
    }
    errno = 0;
    write_table(out, *tables_[i]);
    const bool written = !std::ferror(out) && std::fflush(out) == 0;
    const int error = errno;
    const bool closed = std::fclose(out) == 0;
    if (!written || !closed) {
      fail("writing '" + names_[i] + "' failed: " + (error != 0 ? std::strerror(error) : std::strerror(errno)));
    }
  }

  std::string prefix_;
  std::vector<std::string> names_;
  std::vector<const sampled_table*> tables_;
  std::vector<std::string> temporaries_;
};

// Writes the document and a newline to stdout and flushes; throws write_error on any failure
// (a full disk, /dev/full, a closed descriptor).
void write_stdout(const run_outcome& outcome, bool compact) {
  errno = 0;
  write_document(outcome, compact, [](std::string_view piece) { std::fwrite(piece.data(), 1, piece.size(), stdout); });
  std::fputc('\n', stdout);
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    const int error = errno;
    throw write_error(std::string("solve: cannot write the result to stdout: ") +
                      (error != 0 ? std::strerror(error) : "write error") + " (no CSV file written)");
  }
}

int run(const solve_arguments& args) {
  if (args.csv && args.csv_prefix.empty()) throw input_error("solve: --csv needs a non-empty PREFIX");
  const std::string source = args.scene_path == "-" ? "(stdin)" : "'" + args.scene_path + "'";
  // A relative "master_curve" path is relative to the scene file (to the working directory for stdin).
  const std::string base_dir =
      args.scene_path == "-" ? std::string() : std::filesystem::path(args.scene_path).parent_path().string();
  const scene_spec scene = parse_scene(read_scene(args.scene_path), source, base_dir);

  run_request request;
  request.grid = args.grid;
  request.spacing = args.spacing == "graded" ? punch::sample_spacing::graded : punch::sample_spacing::uniform;
  request.acceptance = args.acceptance;
  request.tolerance = args.tolerance;
  request.threads = args.threads;
  request.time_limit = args.time_limit;
  request.profile_knots = args.profile_knots;
  if (request.grid == 0 && args.csv) request.grid = default_csv_grid;
  std::string warning;
  const run_outcome outcome = run_scene_with_material(scene, request, &warning);
  // A master-curve fit that is not ok is never silent: one warning line (and exit code 3).
  if (!warning.empty()) std::cerr << "rhabel: solve: warning: " << one_line(warning) << '\n';

  // Everything is computed and checked (finite numbers) before anything is written, so that only
  // a failed write can leave partial output. Order: CSV temporaries, stdout (flushed and checked),
  // then the renames: a CSV file appears only when the whole result was written.
  // 3: the result is written but its status is not "ok" (examples/README.md, "Exit codes").
  const int code = outcome.ok ? exit_ok : exit_not_ok;
  if (!args.csv) {
    write_stdout(outcome, args.compact);
    return code;
  }
  csv_transaction csv(args.csv_prefix, outcome);
  csv.write();
  write_stdout(outcome, args.compact);
  csv.commit();
  return code;
}

}  // namespace

void add_solve_command(CLI::App& app, command_action& action) {
  auto args = std::make_shared<solve_arguments>();
  auto* solve = app.add_subcommand(
      "solve",
      "Solve a scene: rigid indentors sliding over a power-law viscoelastic half-space.\n"
      "Prints the result as JSON on stdout (schema: examples/README.md).");
  solve->footer(exit_code_help);
  solve->add_option("SCENE", args->scene_path, "scene file (JSON), or - for stdin")->required();
  solve
      ->add_option("--grid", args->grid,
                   "sample pressure (N points in each contact interval) and surface displacement (N points; "
                   "several contacts: also the whole surface on N points a contact)")
      ->check(CLI::Range(std::size_t{2}, max_grid));
  solve
      ->add_option("--grid-spacing", args->spacing,
                   "where the pressure samples lie: uniform (midpoints of equal cells, the default) or graded "
                   "(Chebyshev points, dense next to the edges)")
      ->check(CLI::IsMember({"uniform", "graded"}));
  auto* csv = solve->add_option("--csv", args->csv_prefix,
                    "also write PREFIX_pressure.csv (indentor,x,pressure), PREFIX_displacement.csv "
                    "(indentor,x,displacement) and, for several contacts, PREFIX_surface.csv (x,displacement); "
                    "implies --grid 201");
  add_acceptance_option(solve, args->acceptance);
  add_tolerance_option(solve, args->tolerance);
  solve
      ->add_option("--threads", args->threads,
                   "threads for the finite-difference Jacobian of several contacts (default 0: every core; the "
                   "result does not depend on it)")
      ->check(CLI::Range(std::size_t{0}, std::size_t{1024}));
  solve
      ->add_option("--time-limit", args->time_limit,
                   "seconds after which a solve of several contacts stops and reports what it reached, status "
                   "not_converged (default 0: no limit)")
      ->check(number_in(0.0, 1e9));
  solve->add_flag("--profile-knots", args->profile_knots,
                  "a sampled profile (spectral search): build the spline's knots inside each contact into its "
                  "density (residual of (8) ~1e-8 where the series alone ends at ~4e-7; slower where the series "
                  "would climb to degree 2048, and not yet for 1e5 samples: docs/theory.md section 9)");
  solve->add_flag("--compact", args->compact, "print the JSON on one line");
  solve->callback([&action, args, csv] {
    args->csv = csv->count() > 0;
    action = [args] { return run(*args); };
  });
}

}  // namespace rhabel::cli
