// The references of test_rough_profile.cpp's 4000-sample periodic scenes (seeds 4 and 15 at load
// 6e-3: 74 and 86 patches) and its 16000-sample one (seed 4 at 2e-3: 60 patches), by the test
// suite's boundary-element oracle alone
// (bem_profile_oracle.hpp; no rhabel header is included: the test's reference shares no code with
// the code under test). A generator and a check: it prints each scene's patches, C_f with its bar,
// the levels and the time, and checks that the oracle settles and reproduces the numbers committed
// in rough_profile_references.hpp (a change to the oracle or to rough_profiles.hpp that moves them
// fails here, and the new numbers are in the output). ~12 min on one core in Release, so CTest
// label `long` (tests/CMakeLists.txt; outside the default run):
//     ctest --test-dir build -R punch.test_rough_profile_reference -V
// Not under the sanitizers (minutes of the same arithmetic; the oracle's code paths run in
// test_bem_profile_oracle.cpp there).
#include <doctest/doctest.h>

#include "punch/bem_profile_oracle.hpp"
#include "punch/rough_profile_references.hpp"
#include "punch/rough_profiles.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace {
namespace bp = punch_test::bem_profile;

/// The oracle's options for a scene. Up to 2^20 panels for 4000 samples (levels 4000 .. 1024000),
/// 2^22 for 16000 (16000 .. 4096000: at 2^20 its C_f bar was 1.2e-4, 1e-4 of it the narrow
/// patches' share, and the oracle did not settle); 256 panels a sample either way. The patches
/// narrower than 16 panels bounded rather than refined away (`bound_narrow`: four to five of them
/// carry 1e-4 .. 2e-4 of the load each, 2e-5 wide, still < 16 panels at 2^20); periodic products
/// by FFT (`fft_products`: the level values the same to 12 digits, 11.5 s instead of 44 s to
/// 256000 panels, seed 4); C_f's bar below 1e-5 x max |z'| (1.4e-6) instead of 1e-4 (which settles
/// at 512000 panels with bars 9e-6: 30x the difference from rhabel's spectral result).
bp::options reference_options(const punch_test::rough_reference& ref) {
  bp::options o;
  o.max_panels = ref.samples > 4000 ? 1 << 22 : 1 << 20;
  o.bound_narrow = true;
  o.fft_products = true;
  // 16000 samples: 5e-5 (x max |z'| ~ 0.2: a bar under 1e-5). It settles at 2^22 panels: 60
  // patches from 128000 panels on, C_f 0.0322900805 +- 5.8e-6 (3 narrow patches, 4.6e-6 of the
  // bar), 9 min on a shared core (2^22 alone: 6-7 min).
  o.friction_tol = ref.samples > 4000 ? 5e-5 : 1e-5;
  return o;
}

void check_reference_scene(const punch_test::rough_reference& ref) {
  const auto samples = punch_test::self_affine(ref.samples, ref.seed);
  // test_rough_profile.cpp's scene_of: alpha 0.3, nu 0, k 0, E1 = U = 1, one period of length 1.
  const auto sc = bp::make_scene_physical(samples.x, samples.z, 1, 0.3, 0, 0, 1, ref.load, 1.0);
  const auto r = bp::solve(sc, reference_options(ref));
  std::string levels;
  for (std::size_t k = 0; k < r.panels.size(); ++k) {
    char line[160];
    std::snprintf(line, sizeof line, "    %7d panels: %3d patches, C_f %.10f, %5.1f s\n", r.panels[k], r.patch_counts[k],
                  r.level_friction[k], r.level_seconds[k]);
    levels += line;
  }
  char head[320];
  std::snprintf(head, sizeof head,
                "seed %llu, load %g: %zu patches, C_f %.10f +- %.3g (Richardson order %.2f; %d narrow patches, "
                "their share of the bar %.3g), converged %d, %.1f s\n",
                static_cast<unsigned long long>(ref.seed), ref.load, r.patches.size(), r.friction.value, r.friction.error,
                r.friction.order, r.narrow_patches, r.narrow_share, static_cast<int>(r.converged), r.seconds);
  const std::string report = std::string(head) + levels;
  MESSAGE(report);
  REQUIRE(r.converged);
  CHECK(r.min_density >= 0);
  CHECK(r.min_gap > -1e-12);
  CHECK(r.patches.size() == ref.patches);
  // The committed numbers are these, printed to 10 and 3 digits (1e-9: rounding elsewhere moves
  // the extrapolated C_f by far less, and 1e-9 is under a thousandth of the bar).
  CHECK(std::abs(r.friction.value - ref.friction) <= 1e-9);
  CHECK(std::abs(r.friction.error - ref.bar) <= 0.01 * ref.bar);
}
}  // namespace

TEST_CASE("references of the periodic rough profiles of test_rough_profile.cpp by the oracle alone") {
  if (bp::sanitizer_build) return;
  for (const auto& ref : {punch_test::rough_reference_seed4, punch_test::rough_reference_seed15,
                          punch_test::rough_reference_16000_seed4}) {
    CAPTURE(ref.seed);
    check_reference_scene(ref);
  }
}
