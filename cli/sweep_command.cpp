// rhabel sweep SWEEP.json --out FILE.csv [--jsonl] [--threads N] [--time-limit S] [--tolerance TOL]
//              [--acceptance TOL] [--profile-knots] [--print-scenes] [--quiet]
//
// Solves every scene of a sweep (rhabel/scene/sweep.hpp) and writes one row per scene: CSV with a header, or
// JSON lines (--jsonl: one object per line, the same keys). Rows: row, the swept values, the solve
// options (tolerance, acceptance: empty when the solver's default; profile_knots for a sampled
// profile), status, alpha, E1, omega0 and alpha_tan_delta (master-curve materials), per indentor
// i: ind<i>_a, _b, _contact_length, _load, _C_f, _total_friction, then residual, seconds (solve time of the row,
// the only column that differs between runs) and message. Numbers in the shortest form that reads
// back to the same double (as `rhabel solve` prints them: a row equals the single solve bit for bit).
// A failed scene is a row too (status invalid_scene, no_solution or error, and its message).
//
// Resuming: rows are appended to FILE as they complete, each as one whole line written with one
// write() and flushed, so a killed run leaves a readable file (at worst a last partial line, which
// the next run cuts off). Rerunning the same command reads FILE, keeps the rows it recognises (same
// index, the same swept values and the same solve options; another sweep's file, or a row solved
// with another --tolerance, --acceptance or --profile-knots, is refused, exit 2), solves only the
// missing ones and, when all are there, rewrites FILE in row order (temporary + rename): every row
// exactly once, in scene order.
//
// Parallelism: --threads N worker threads (default 0: all cores; under MPI, the cores divided by the
// ranks on the node). When built with RHABEL_WITH_MPI and started by mpirun, the rows still missing
// are dealt cyclically over the ranks (row k of the missing list to rank k mod size); the ranks send
// their lines to rank 0, the only one that touches FILE, so the output is the same as one process's
// (same rows, same order, same bits but the seconds column).
//
// --time-limit S: each row's solve of several contacts stops after S seconds and its row reports
// what it reached (status not_converged; punch::solve_options::time_limit), so one slow scene does
// not hold up a long sweep. Such a row depends on the machine's speed. --tolerance and --acceptance:
// each row's punch::solve_options::tolerance and acceptance, as in `rhabel solve` (a row still equals
// that solve). --profile-knots: a sampled profile's spline knots as singular terms of each row's
// densities (punch::solve_options::profile_knots), as `rhabel solve --profile-knots`.
//
// Progress (rows done, rate, remaining time) goes to stderr only when stderr is a terminal
// (--quiet silences it). Exit codes: 0 every row ok, 3 every row written but some not ok, 2 bad
// sweep file, arguments, a FILE from another sweep, or a failed write. Under mpirun every rank ends
// with MPI_Finalize and the same code, and only rank 0 prints the message (mpirun passes the code
// on; it adds its own note on stderr when the code is not 0 unless run with --quiet).
#include "commands.hpp"

#include <rhabel/scene.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#ifdef RHABEL_WITH_MPI
#include <mpi.h>
#endif

namespace rhabel::cli {
namespace {

struct sweep_arguments {
  std::string sweep_path;
  std::string out;
  bool jsonl = false;
  std::size_t threads = 0;
  double time_limit = 0;  // seconds per row's solve; 0 = none
  double tolerance = 1e-12;
  double acceptance = 0;  // 0: not given, the solver's default (run_request::acceptance)
  bool profile_knots = false;
  bool print_scenes = false;
  bool quiet = false;
};

// ---- MPI (a no-op without RHABEL_WITH_MPI or outside mpirun) --------------------------------------
struct mpi_context {
  int rank = 0, size = 1;
  bool active = false;
  // While the ranks exchange rows, a failure of one cannot be told to the others (they would wait
  // for it forever): only then is the job aborted (MPI_Abort). Before and after, every rank ends
  // with MPI_Finalize and the same exit code, and rank 0 alone prints the message.
  bool rows_in_flight = false;
#ifdef RHABEL_WITH_MPI
  static bool launched_by_mpirun() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"}) {
      if (std::getenv(v)) return true;
    }
    return false;
  }
  mpi_context() {
    if (!launched_by_mpirun()) return;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    active = true;
  }
  ~mpi_context() {
    if (active) MPI_Finalize();
  }
#endif
  mpi_context(const mpi_context&) = delete;
  mpi_context& operator=(const mpi_context&) = delete;
#ifndef RHABEL_WITH_MPI
  mpi_context() = default;
#endif
};

constexpr int tag_line = 1;

// ---- progress ----------------------------------------------------------------------------------------
class progress {
 public:
  progress(bool on, std::size_t total) : on_(on), total_(total), start_(clock::now()), last_(start_) {}
  void update(std::size_t done, bool final = false) {
    if (!on_) return;
    const auto now = clock::now();
    if (!final && now - last_ < std::chrono::milliseconds(200)) return;
    last_ = now;
    const double s = std::chrono::duration<double>(now - start_).count();
    const double rate = s > 0 ? static_cast<double>(done) / s : 0;
    const double eta = rate > 0 ? static_cast<double>(total_ - done) / rate : 0;
    const int width = 30;
    const int filled = total_ ? static_cast<int>(width * static_cast<double>(done) / static_cast<double>(total_)) : width;
    std::fprintf(stderr, "\r[%s%s] %zu/%zu rows  %.1f rows/s  %s %.0f s   ", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), done, total_, rate, final ? "took" : "ETA", final ? s : eta);
    if (final) std::fputc('\n', stderr);
    std::fflush(stderr);
  }
 private:
  using clock = std::chrono::steady_clock;
  bool on_;
  std::size_t total_;
  clock::time_point start_, last_;
};


std::size_t default_threads(const mpi_context& mpi) {
  std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  if (mpi.active) {
    const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
    const long ranks_here = local ? std::strtol(local, nullptr, 10) : mpi.size;
    cores = std::max<std::size_t>(1, cores / static_cast<std::size_t>(std::max(1L, ranks_here)));
  }
  return cores;
}

int run_sweep(const sweep_arguments& args, mpi_context& mpi) {
  const row_format format = args.jsonl ? row_format::jsonl : row_format::csv;
  const sweep_spec sweep = read_sweep(args.sweep_path);
  if (args.print_scenes) {
    if (mpi.rank != 0) return exit_ok;
    std::string text;
    for (std::size_t i = 0; i < sweep.rows; ++i) text += row_scene(sweep, i).dump() + "\n";
    std::fwrite(text.data(), 1, text.size(), stdout);
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) throw write_error("sweep: cannot write to stdout");
    return exit_ok;
  }
  if (args.out.empty()) throw input_error("sweep: --out FILE is required (or --print-scenes)");
  run_request request;  // grid 0, one thread per row (the rows run in parallel)
  request.time_limit = args.time_limit;
  request.tolerance = args.tolerance;
  request.acceptance = args.acceptance;
  request.profile_knots = args.profile_knots;
  // Rank 0 reads what is there and decides what is missing; the list goes to every rank.
  std::optional<sweep_output> output;
  std::vector<std::size_t> missing;
  std::string scan_error;
  if (mpi.rank == 0) {
    try {
      output.emplace(sweep, format, args.out, request);
      missing = output->missing();
    } catch (const std::exception& e) {
      scan_error = e.what();
    }
  }
#ifdef RHABEL_WITH_MPI
  if (mpi.active) {
    int failed = scan_error.empty() ? 0 : 1;
    MPI_Bcast(&failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (failed) {
      if (mpi.rank == 0) throw input_error(scan_error);
      return exit_bad_input;
    }
    unsigned long long count = missing.size();
    MPI_Bcast(&count, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    std::vector<unsigned long long> list(missing.begin(), missing.end());
    list.resize(count);
    if (count) MPI_Bcast(list.data(), static_cast<int>(count), MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    missing.assign(list.begin(), list.end());
  }
#endif
  if (!scan_error.empty()) throw input_error(scan_error);
  const std::size_t total_missing = missing.size();
  std::vector<std::size_t> mine;
  for (std::size_t k = 0; k < missing.size(); ++k) {
    if (static_cast<int>(k % static_cast<std::size_t>(mpi.size)) == mpi.rank) mine.push_back(missing[k]);
  }

  const std::size_t threads = args.threads ? args.threads : default_threads(mpi);
  progress bar(mpi.rank == 0 && !args.quiet && ::isatty(2), total_missing);
  std::size_t received = 0;
  {
    mpi.rows_in_flight = mpi.active;
    sweep_pool pool(sweep, format, mine, threads, request);
    std::size_t local_done = 0;
    auto store = [&](finished_row&& r) {  // rank 0 only
      output->append(std::move(r));
      ++received;
    };
    while (mpi.rank == 0 ? received < total_missing : local_done < mine.size()) {
      auto batch = pool.take(std::chrono::milliseconds(mpi.active ? 2 : 200));
      local_done += batch.size();
      for (auto& r : batch) {
        if (mpi.rank == 0) {
          store(std::move(r));
        } else {
#ifdef RHABEL_WITH_MPI
          std::string msg = std::to_string(r.row) + " " + r.line;
          MPI_Send(msg.data(), static_cast<int>(msg.size()), MPI_CHAR, 0, tag_line, MPI_COMM_WORLD);
#endif
        }
      }
#ifdef RHABEL_WITH_MPI
      if (mpi.active && mpi.rank == 0) {
        for (;;) {
          int flag = 0;
          MPI_Status status;
          MPI_Iprobe(MPI_ANY_SOURCE, tag_line, MPI_COMM_WORLD, &flag, &status);
          if (!flag) break;
          int count = 0;
          MPI_Get_count(&status, MPI_CHAR, &count);
          std::string msg(static_cast<std::size_t>(count), '\0');
          MPI_Recv(msg.data(), count, MPI_CHAR, status.MPI_SOURCE, tag_line, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          const auto space = msg.find(' ');
          store({std::stoull(msg.substr(0, space)), msg.substr(space + 1)});
        }
      }
#endif
      bar.update(received);
    }
  }
  mpi.rows_in_flight = false;
  bar.update(received, true);

  int code = exit_ok;
  std::exception_ptr failure;
  if (mpi.rank == 0) {
    try {
      // Every row exactly once, in row order.
      output->finish();
      if (!output->all_ok()) code = exit_not_ok;
    } catch (const std::exception& e) {
      failure = std::current_exception();
      code = exit_code_of(e);
    }
  }
#ifdef RHABEL_WITH_MPI
  // Every rank ends with rank 0's code (its rows are in FILE; rank 0 alone prints).
  if (mpi.active) MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
#endif
  if (failure) std::rethrow_exception(failure);
  return code;
}

}  // namespace

void add_sweep_command(CLI::App& app, command_action& action) {
  auto args = std::make_shared<sweep_arguments>();
  auto* cmd = app.add_subcommand(
      "sweep",
      "Solve every scene of a sweep (a base scene and axes of values; schema: examples/README.md)\n"
      "and write one row per scene to FILE (CSV, or JSON lines with --jsonl). Rerunning the same\n"
      "command resumes: rows already in FILE are kept, the missing ones solved (a FILE solved with\n"
      "another --tolerance, --acceptance or --profile-knots is refused). Under mpirun (when built\n"
      "with RHABEL_WITH_MPI) the rows are distributed over the ranks.");
  cmd->footer(exit_code_help);
  cmd->add_option("SWEEP", args->sweep_path, "sweep file (JSON)")->required();
  cmd->add_option("--out", args->out, "output file (rows appended as they complete, sorted at the end)");
  cmd->add_flag("--jsonl", args->jsonl, "write JSON lines instead of CSV");
  cmd->add_option("--threads", args->threads, "worker threads (default 0: every core)")->check(CLI::Range(0, 4096));
  cmd->add_option("--time-limit", args->time_limit,
                  "seconds after which a row's solve of several contacts stops and its row reports what it "
                  "reached, status not_converged (default 0: no limit)")
      ->check(number_in(0.0, 1e9));
  add_tolerance_option(cmd, args->tolerance);
  add_acceptance_option(cmd, args->acceptance);
  cmd->add_flag("--profile-knots", args->profile_knots,
                "each row as rhabel solve --profile-knots: a sampled profile's spline knots inside each contact "
                "built into its density (docs/theory.md section 9)");
  cmd->add_flag("--print-scenes", args->print_scenes, "print each row's scene as one JSON line and stop");
  cmd->add_flag("--quiet", args->quiet, "no progress bar");
  cmd->callback([&action, args] {
    action = [args] {
      // Rank 0's context outlives main's report of a failure (below): MPI_Finalize, which waits
      // for every rank, then runs at exit, so no rank ends (and mpirun tears the job down) before
      // rank 0 has printed its line (measured: under load the line was sometimes lost).
      static std::unique_ptr<mpi_context> kept;
      auto owned = std::make_unique<mpi_context>();
      mpi_context& mpi = *owned;
      if (!mpi.active) return run_sweep(*args, mpi);
      try {
        return run_sweep(*args, mpi);
      } catch (const std::exception& e) {
#ifdef RHABEL_WITH_MPI
        if (mpi.rows_in_flight) {  // the other ranks cannot be told: the job must end here
          std::cerr << "rhabel: " << one_line(e.what()) << '\n';
          std::cerr.flush();
          MPI_Abort(MPI_COMM_WORLD, exit_code_of(e));
        }
#endif
        // Bad input is found alike on every rank (the sweep file) or by rank 0 and sent to all
        // (the existing output): each rank ends with MPI_Finalize (~mpi_context) and the same
        // code; rank 0 alone prints the line (main).
        if (mpi.rank != 0) return exit_code_of(e);
        kept = std::move(owned);
        throw;
      }
    };
  });
}

}  // namespace rhabel::cli
