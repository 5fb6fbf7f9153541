// libFuzzer target for the scene parser and the solve entry of `rhabel solve`
// (tests/fuzz/README.md: how it is built, run and bounded).
//
// Each input is a scene text. It goes through the same parse_scene as `rhabel solve`; a scene
// refused by the parser must be refused with an input_error (exit code 2 of the program). A scene
// that parses is solved through run_scene (the punch layer plus the result document, with a
// 7-point field grid), which may refuse it (input_error) or return a result of any status.
// Anything else is a finding: a sanitizer report, an escaped exception, or a std::runtime_error
// out of run_scene, which the program turns into exit code 1 "internal error" on a valid scene.
//
// The solve cost per input is bounded so that a 60 s run explores many inputs: each indentor is
// solved alone (a one-indentor copy of the scene). A coupled solve of several contacts can take
// seconds (closeness costs degree ~ sqrt(L/gap)), and its paths are covered by the punch tests; the
// isolated path, where hostile numbers meet the solver, costs milliseconds. A sampled profile is
// solved whole (its contact search is a coupled solve) under solve_options::time_limit
// (fuzz_time_limit), so that a slow input ends in a result rather than in libFuzzer's timeout.
// Master-curve materials are parsed but not solved (they read a file).
#include "commands.hpp"
#include "fuzz_support.hpp"

#include <rhabel/scene.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>

namespace {

[[noreturn]] void finding(const char* what, const char* message) { rhabel::fuzz::finding("fuzz_scene", what, message); }

constexpr std::size_t fuzz_grid = 7;  // samples per field: exercises the sampling, costs little
constexpr std::size_t max_fuzz_samples = 12;  // profile samples solved per input
// Seconds of a profile's contact search. WHY 1: the run is for crashes, not speed; a slow
// profile input costs the limit plus at most one Newton step (under ASan at -O1 up to ~3 s for two
// nearly touching contacts at degree ~180), well inside libFuzzer's 30 s timeout
// (tests/fuzz/run.sh), and leaves time for other inputs (with 5 s: 28,000 inputs in 60 s instead
// of ~300,000). Measured on corpus/slow_profile_closing.json: 29 s with no limit.
constexpr double fuzz_time_limit = 1;

// A valid scene either solves or is refused cleanly (an input_error: exit code 2); anything else
// is a finding.
void solve_checked(const rhabel::cli::scene_spec& scene) {
  try {
    rhabel::cli::run_request request;
    request.grid = fuzz_grid;
    request.time_limit = fuzz_time_limit;
    (void)rhabel::cli::run_scene(scene, request);
  } catch (const rhabel::cli::input_error&) {
  } catch (const std::exception& e) {
    finding("run_scene: internal error on a valid scene", e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rhabel::cli;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  scene_spec scene;
  if (!rhabel::fuzz::accepted<input_error>("fuzz_scene", "parse_scene", [&] { scene = parse_scene(text, "(fuzz)"); })) {
    return 0;  // refused cleanly
  }
  if (scene.material.curve) return 0;
  if (scene.profile) {
    // A sampled profile: small ones without corners only. The contact search runs one coupled
    // solve per round, and a failing round is costly: a 17-sample profile with a corner inside a
    // contact and a spike took 16 s in Release (over the 30 s timeout under ASan), a slow input,
    // not a hang (tests/fuzz/corpus/hostile_profile_spike.json keeps the crash it found first).
    if (scene.profile->x.size() > max_fuzz_samples || !scene.profile->corners.empty()) return 0;
    solve_checked(scene);
    return 0;
  }
  for (const auto& indentor : scene.indentors) {
    scene_spec alone = scene;
    alone.indentors = {indentor};
    solve_checked(alone);
  }
  return 0;
}
