// The sampled profile's contact search (punch/src/contact_set.cpp) stopped by its time limit: what
// it reports says so, whichever stage the limit cut (a round, the series-degree ladder, the
// continuation, a periodic pass). No oracle: the claim is the status's, and the search run without
// the limit is ok, so any result that is not ok under a limit must owe it to the limit.
#include <doctest/doctest.h>

#include "../punch/src/internal.hpp"
#include "../punch/src/profile_search.hpp"
#include "punch/rough_profiles.hpp"
#include "rhabel/punch.hpp"

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>

namespace {
namespace pu = rhabel::punch;
namespace pd = rhabel::punch::detail;

const std::string limit_words = "stopped at the time limit of ";
}  // namespace

TEST_CASE("say_time_limit: a result that is not ok, out of time, names the limit once") {
  pu::solve_options o;
  o.time_limit = 1e-9;
  const pd::context cx = pd::make_context(pu::material{}, 1.0, o);
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  REQUIRE(cx.out_of_time());

  pu::profile_result r;
  r.diagnostics.code = pu::status_code::not_converged;
  r.diagnostics.status = "see contacts[3].status: residual of (8) 2e-06 > acceptance 1e-06";
  pd::say_time_limit(r, cx);
  CHECK(r.diagnostics.status ==
        "see contacts[3].status: residual of (8) 2e-06 > acceptance 1e-06; " + cx.time_limit_message());
  CHECK(r.diagnostics.code == pu::status_code::not_converged);
  const std::string once = r.diagnostics.status;
  pd::say_time_limit(r, cx);  // named already: unchanged
  CHECK(r.diagnostics.status == once);

  pu::profile_result ok;  // ok stays ok: it met its evidence, whatever the clock
  ok.diagnostics.status = "ok";
  pd::say_time_limit(ok, cx);
  CHECK(ok.diagnostics.status == "ok");

  o.time_limit = 0;  // no limit: never out of time
  const pd::context unlimited = pd::make_context(pu::material{}, 1.0, o);
  pu::profile_result failed;
  failed.diagnostics.code = pu::status_code::tension;
  failed.diagnostics.status = "tension";
  pd::say_time_limit(failed, unlimited);
  CHECK(failed.diagnostics.status == "tension");
}

TEST_CASE("a profile search cut by its time limit at any point says so (periodic self-affine, 4000 samples)") {
  // The profile climbs the series degrees (contacts over several samples: 128, then 512), so the
  // cuts fall in rounds, between rounds and between the degrees' searches. Unlimited it is ok;
  // under each limit (fractions of that run's time) the result is ok or names the limit.
  const auto samples = punch_test::self_affine(4000, 1);
  pu::profile_scene ps;
  ps.material.alpha = 0.3;
  ps.load = 2e-3;
  ps.profile.x = samples.x;
  ps.profile.z = samples.z;
  ps.profile.period = 1;
  pu::solve_options o;
  o.tolerance = 1e-10;
  o.acceptance = 1e-6;
  o.threads = 1;
  const auto full = pu::solve_profile(ps, o);
  REQUIRE(full.diagnostics.code == pu::status_code::ok);
  CHECK(std::any_of(full.contacts.begin(), full.contacts.end(), [](const pu::indentor_result& c) { return c.degree > 127; }));
  for (const double fraction : {0.05, 0.15, 0.3, 0.45, 0.6, 0.75, 0.9}) {
    o.time_limit = fraction * full.diagnostics.seconds;
    CAPTURE(fraction);
    const auto r = pu::solve_profile(ps, o);
    CAPTURE(r.diagnostics.status);
    CAPTURE(r.diagnostics.seconds);
    CHECK((r.diagnostics.code == pu::status_code::ok || r.diagnostics.status.find(limit_words) != std::string::npos));
  }
}
