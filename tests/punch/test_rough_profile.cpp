// Self-affine rough profiles, the workload most users bring (rhabel/punch/profile.hpp), against
// the boundary-element oracle for sampled profiles (bem_profile_oracle.hpp), which shares no code
// with rhabel: its own splines, its own active set on uniform panels, Richardson extrapolation.
//
// The contract checked is the product's: a result that says ok agrees with the oracle (patch
// count and C_f within the oracle's error bar), and a result that is not ok says what is wrong (a
// partial load is named as such, never presented as the answer to the full load). How many of
// these scenes are ok is pinned below as measured, so that a regression of the search shows.
#include <doctest/doctest.h>

#include "punch/bem_profile_oracle.hpp"
#include "punch/rough_profile_references.hpp"
#include "punch/rough_profiles.hpp"
#include "rhabel/punch.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace pu = rhabel::punch;
namespace bp = punch_test::bem_profile;

// The acceptance a measured profile is worth (profile.hpp: the spline's forcing is only C1).
constexpr double acceptance = 1e-6;
// C_f of an ok result against the oracle's: the oracle's bar (an estimate) twice, plus what the
// acceptance allows of rhabel's own C_f (its residual and error estimate are within 1e-6).
constexpr double bar_factor = 2;

struct outcome {
  bool ok = false, refused = false;
  std::vector<std::size_t> degrees;  // an ok result's contacts' series degrees
  std::size_t rounds = 0;            // an ok result's rounds of the contact search, in all
};

/// The scene of `samples` under `load` (alpha 0.3; nu 0, k 0, E1 1, speed 1: the defaults), a
/// finite window (period 0) or one period.
pu::profile_scene scene_of(const punch_test::sampled& samples, double load, double period) {
  pu::profile_scene ps;
  ps.material.alpha = 0.3;
  ps.load = load;
  ps.profile.x = samples.x;
  ps.profile.z = samples.z;
  ps.profile.period = period;
  return ps;
}

/// The search's options in these tests: tolerance 1e-10, the acceptance above.
pu::solve_options search_options() {
  pu::solve_options o;
  o.tolerance = 1e-10;
  o.acceptance = acceptance;
  return o;
}

/// One profile, a finite window (period 0) or periodic (period 1: rhabel's spectral search on one
/// period, the other periods' displacement by fixed-point passes, against the oracle's periodic
/// kernel and active set).
outcome check_scene(std::size_t n, std::uint64_t seed, double load, double period = 0, bp::options oracle_options = {}) {
  CAPTURE(n);
  CAPTURE(seed);
  CAPTURE(load);
  CAPTURE(period);
  const auto samples = punch_test::self_affine(n, seed);
  const pu::profile_scene ps = scene_of(samples, load, period);
  outcome out;
  pu::profile_result r;
  try {
    r = pu::solve_profile(ps, search_options());
  } catch (const std::domain_error& e) {
    // Contacts at an end of the samples: refused naming body.load (the oracle's first level finds
    // the end panel loaded too, and a finite window has nothing beyond it).
    const std::string message = e.what();
    CAPTURE(message);
    CHECK(message.find("body.load") != std::string::npos);
    out.refused = true;
    return out;
  }
  CAPTURE(r.diagnostics.status);
  if (r.diagnostics.load_fraction < 1) {
    CHECK(r.diagnostics.code != pu::status_code::ok);
    CHECK(r.diagnostics.status.rfind("the search reached only", 0) == 0);
  }
  if (r.diagnostics.code != pu::status_code::ok) {
    CHECK(!r.diagnostics.status.empty());
    return out;
  }
  out.ok = true;
  out.rounds = r.diagnostics.rounds;
  for (const auto& c : r.contacts) out.degrees.push_back(c.degree);
  // ok includes the levels of the rigid body, evaluated afresh from the reported pressures.
  CHECK(r.level_mismatch <= acceptance);
  const double E_U = ps.material.effective_modulus(ps.speed);
  // The oracle's default grids also under the sanitizers: test_options()' coarser ones (2^13
  // panels at most) do not settle on this profile (measured under ASan: converged = false).
  const auto oracle = bp::solve(
      bp::make_scene(samples.x, samples.z, 0.3, 0.0, bp::load_from_pressure(load, E_U), period), oracle_options);
  REQUIRE(oracle.converged);
  CHECK(r.contacts.size() == oracle.patches.size());
  double moment = 0, total = 0;
  for (const auto& c : r.contacts) moment += c.hysteretic_friction * c.load, total += c.load;
  const double cf = moment / total;
  CHECK(total == doctest::Approx(load).epsilon(acceptance));
  CHECK(std::abs(cf - oracle.friction.value) <= bar_factor * oracle.friction.error + acceptance * std::abs(cf));
  CHECK(r.hysteretic_friction == doctest::Approx(cf).epsilon(1e-14));
  if (period > 0) {
    CHECK(r.mean_pressure == doctest::Approx(load / period).epsilon(1e-15));
    // Every contact inside the reported window of one period.
    for (const auto& c : r.contacts) CHECK((c.a > r.window_start && c.b < r.window_start + period));
  }
  return out;
}

/// The spectral search on n samples of self_affine(n, seed) as one period (alpha 0.3, tolerance
/// 1e-10, the acceptance above), for the cases whose oracle run is too long for this file (their
/// references are committed: rough_profile_references.hpp).
pu::profile_result solve_periodic(std::size_t n, std::uint64_t seed, double load) {
  return pu::solve_profile(scene_of(punch_test::self_affine(n, seed), load, 1.0), search_options());
}

/// A result of solve_periodic against a committed reference of the test oracle
/// (rough_profile_references.hpp): ok, the oracle's patch count, level mismatch within the
/// acceptance, C_f within twice the oracle's bar (plus the acceptance's share, as check_scene).
void check_reference(const pu::profile_result& r, const punch_test::rough_reference& ref) {
  CAPTURE(r.diagnostics.status);
  CAPTURE(r.hysteretic_friction);
  CAPTURE(ref.friction);
  CAPTURE(ref.bar);
  REQUIRE(r.diagnostics.code == pu::status_code::ok);
  CHECK(r.contacts.size() == ref.patches);
  CHECK(r.level_mismatch <= acceptance);
  CHECK(std::abs(r.hysteretic_friction - ref.friction) <= bar_factor * ref.bar + acceptance * ref.friction);
}
}  // namespace

TEST_CASE("self-affine profiles: ok agrees with the boundary-element oracle, anything else says what is missing") {
  // 1000 samples of H = 0.8, rms 1e-3 on a unit length (rough_profiles.hpp), alpha 0.3, loads
  // giving 3 to 10 patches; three seeds.
  std::size_t ok = 0;
  for (const std::uint64_t seed : {1, 2, 3})
    for (const double load : {3e-4, 1e-3}) {
      if (bp::sanitizer_build && !(seed == 3 && load == 3e-4)) continue;  // the oracle: minutes under ASan
      ok += check_scene(1000, seed, load).ok ? 1 : 0;
    }
  // Measured: all three seeds at 3e-4 and seeds 1 and 3 at 1e-3 are ok (3 to 10 patches, C_f
  // within twice the oracle's bar); seed 2 at 1e-3 is refused (contacts at x = 0). Seed 1 at 1e-3
  // is the case of a spline's rise between contacts: integrated from its slope by one Gauss rule
  // across the knots, the levels of its contacts were off by ~4e-5 of the span, and three of its
  // ten contacts reported a penetration that the oracle does not see.
  CHECK(ok >= (bp::sanitizer_build ? 1u : 5u));
}

TEST_CASE("periodic self-affine profiles by the spectral search agree with the oracle's periodic solve") {
  std::size_t ok = 0;
  // Whether an ok result has contacts at degree 127 beside contacts at 511 or more: the search
  // went to a higher degree for some contacts and the others, within the acceptance at the
  // first degree, kept theirs (contact_set.cpp, capped_below). Solved again at the higher degree,
  // every contact spanning the spline's knots climbed to it (its series converges algebraically).
  bool kept = false;
  std::size_t rounds = 0;
  for (const std::uint64_t seed : {1, 2, 3})
    for (const double load : {5e-4, 3e-3}) {
      if (bp::sanitizer_build && !(seed == 2 && load == 5e-4)) continue;  // the oracle: minutes under ASan
      const outcome o = check_scene(1000, seed, load, 1.0);
      ok += o.ok ? 1 : 0;
      rounds += o.rounds;
      const auto count = [&](auto predicate) { return std::count_if(o.degrees.begin(), o.degrees.end(), predicate); };
      if (count([](std::size_t d) { return d == 127; }) > 0 && count([](std::size_t d) { return d >= 511; }) > 0)
        kept = true;
    }
  // Measured: seed 2 at 5e-4 (5 contacts): degrees 15, 127, 127, 511, 511.
  CHECK(kept);
  // A pass after the first (the other periods' displacement of the solution) searches at the
  // degree the last pass reached, its contacts within a quarter of the acceptance holding theirs
  // (periodic_profile.cpp). Measured: 2, 2, 3, 4, 1, 3 rounds (15); when each pass climbed the
  // degrees again from 128: 2, 2, 4, 6, 1, 3 (18). One round of slack for a path that roundings
  // change. (Not under the sanitizers: one scene, whose rounds 3 and 4 leave no slack.)
  if (!bp::sanitizer_build) CHECK(rounds <= 16u);
  // Measured: 6 of 6 ok (3 to 28 contacts at tolerance 1e-10), each within twice the oracle's bar.
  // Seed 3 at 3e-3 needs the coloured Jacobian's far model of every contact's load change
  // (coupled_newton.cpp, body_far_model).
  CHECK(ok >= (bp::sanitizer_build ? 1u : 6u));
}

TEST_CASE("two contacts a sample apart across a shallow valley stay two (periodic, 4000 samples)") {
  // Seed 4 at load 6e-3 (74 patches): two of them, [0.26592, 0.26702] and [0.26728, 0.26797], lie
  // a sample spacing apart across a valley that the first reaches into. Merged into one contact
  // (the search's widening once did), the coupled solve converged to a root with a negative
  // pressure between them (status tension). The reference is the test oracle's, committed
  // (rough_profile_references.hpp; regenerated by test_rough_profile_reference.cpp, label long,
  // ~1 min a scene): levels 4000 .. 1024000 panels, its patches narrower than 16 panels (one on
  // the finest level) bounded rather than refined away (bem_profile_oracle.hpp, bound_narrow),
  // 74 patches and C_f 0.0244682934 +- 1.24e-6 (an estimate; the spectral result 0.0244683239,
  // 3.0e-8 from it; rhabel's own boundary-element solver gave 0.0244683204 +- 8.3e-8). A C_f off
  // by 2.5e-6 (twice the bar, plus 1e-6 of C_f) fails.
  if (bp::sanitizer_build) return;  // ~30 s in Release
  const auto r = solve_periodic(4000, 4, 6e-3);
  check_reference(r, punch_test::rough_reference_seed4);
  std::size_t near = 0;  // the two patches of the valley, each a contact of its own
  for (const auto& c : r.contacts) {
    const double a = std::fmod(c.a, 1.0), b = a + c.contact_length;  // in the samples' period [0, 1)
    if (b > 0.2659 && a < 0.2680) ++near;
  }
  CHECK(near == 2);
}

TEST_CASE("profile_knots: the spline's knots built into the densities (periodic, 4000 samples)") {
  // Seed 4 at load 6e-3, as above, with solve_options::profile_knots: the oracle's patches and
  // C_f, no contact's series beyond degree 127 (the knots are terms of their own), and the largest
  // residual of (8) well below the plain series' (measured: 1.3e-8 against 7.4e-7). ~10 s.
  if (bp::sanitizer_build) return;  // ~10 s in Release (both searches)
  auto o = search_options();
  o.profile_knots = true;
  const auto r = pu::solve_profile(scene_of(punch_test::self_affine(4000, 4), 6e-3, 1.0), o);
  check_reference(r, punch_test::rough_reference_seed4);
  double worst = 0;
  for (const auto& c : r.contacts) {
    CHECK(c.degree <= 127);
    worst = std::max(worst, c.residual);
  }
  const auto plain = solve_periodic(4000, 4, 6e-3);
  double worst_plain = 0;
  for (const auto& c : plain.contacts) worst_plain = std::max(worst_plain, c.residual);
  CAPTURE(worst);
  CAPTURE(worst_plain);
  CHECK(worst <= 0.1 * worst_plain);
}

TEST_CASE("a contact across the spline's knots climbs to degree 2048 (periodic, 4000 samples)") {
  // Seed 15 at load 6e-3 (86 patches): one contact of ~4.8 sample spacings converges
  // algebraically (the spline's f''' jumps at its knots): residual of (8) 1.13e-6 at degree 1023,
  // above the acceptance (the search ended not_converged there), 8.0e-8 at 2047: the search goes
  // on to 2048 (contact_set.cpp, profile_degrees). The reference, as for seed 4 above, is the
  // test oracle's, committed (rough_profile_references.hpp): 86 patches, C_f 0.0215062673 +-
  // 1.16e-6 (an estimate; the spectral result 0.0215062617, 5.6e-9 from it; rhabel's own
  // boundary-element solver gave 0.0215062538 +- 9.3e-8).
  if (bp::sanitizer_build) return;  // ~20 s in Release
  const auto r = solve_periodic(4000, 15, 6e-3);
  check_reference(r, punch_test::rough_reference_seed15);
  const auto at_2048 = std::count_if(r.contacts.begin(), r.contacts.end(), [](const pu::indentor_result& c) {
    return c.degree == 2047 && c.residual <= acceptance;
  });
  CHECK(at_2048 >= 1);
}

TEST_CASE("contacts narrower than a sample spacing that the first rounds lose come back (periodic, 16000 samples)") {
  // Seed 4 at load 2e-3 (60 patches): two of them, 2e-6 and 2.9e-6 wide (3 % and 5 % of a
  // spacing, 3e-5 and 1.2e-4 of the load), each beside a tip sample. The coarse solve seeds them;
  // the rigid body's iteration from the coarse seeds starves them (their seed loads are under a
  // hundredth of the mean), and once the others settle the profile penetrates the surface there by
  // 5.8e-6 and 7.6e-6 of its span between two samples that both clear it. The search gives them
  // back from their coarse edges (contact_set.cpp, restore_lost) and checks the clearance between
  // the samples as well (between_samples). Without both it ended ok with 58 contacts and C_f
  // 0.0322935, 3.4e-6 from the oracle's value below. The reference is the test oracle's, committed
  // (rough_profile_references.hpp; test_rough_profile_reference.cpp regenerates it).
  // At the library's default tolerance (1e-12, as the command line): ~80 s. At the other cases'
  // 1e-10 the rounds take another path (the search at degree 512 loses three more narrow contacts,
  // restores all four at once, and that round does not converge; the continuation then ends ok
  // with the 60) in ~8 min.
  if (bp::sanitizer_build) return;  // CTest label long (tests/CMakeLists.txt)
  pu::solve_options o;
  o.acceptance = acceptance;
  const auto r = pu::solve_profile(scene_of(punch_test::self_affine(16000, 4), 2e-3, 1.0), o);
  check_reference(r, punch_test::rough_reference_16000_seed4);
  CHECK(r.clearance >= -acceptance);
}

