// The sampled profile's contact search (punch/src/contact_set.cpp).
// - Stopped by its time limit, what it reports says so, whichever stage the limit cut (a round,
//   the series-degree ladder, the continuation, a periodic pass). No oracle: the claim is the
//   status's, and the search run without the limit is ok, so any result that is not ok under a
//   limit must owe it to the limit.
// - A contact split around its negative part (split_seed) shares its load as its density's
//   integrals over the two parts do. Oracle: the density written out from its definition (a
//   Jacobi weight), integrated by Boost's tanh-sinh quadrature.
#include <doctest/doctest.h>

#include "../punch/src/internal.hpp"
#include "../punch/src/profile_search.hpp"
#include "punch/rough_profiles.hpp"
#include "rhabel/punch.hpp"

#include <boost/math/quadrature/tanh_sinh.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <thread>

namespace {
namespace pu = rhabel::punch;
namespace pd = rhabel::punch::detail;

const std::string limit_words = "stopped at the time limit of ";
constexpr double eps = std::numeric_limits<double>::epsilon();
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

TEST_CASE("split_seed: the two parts share the load as the density's integrals over them do") {
  // A contact on [-0.3, 1.7] (abscissae of the solve) whose density is the Jacobi weight alone,
  // bounded at the leading edge and singular at the trailing one (gam = 0.35, del = -0.65: alpha
  // 0.3): most of its load lies near b, so a share by length would be far off.
  pd::contact_density g;
  g.jacobi.lo = -0.3;
  g.jacobi.hi = 1.7;
  g.jacobi.gam = 0.35;
  g.jacobi.del = -0.65;
  g.jacobi.coefficients = {2.0};
  g.nu = 0;
  const double origin = 1e3;  // the window far from x = 0
  const double lo = 0.9, hi = 0.95;
  const pd::coarse_patch seed{g.a() + origin, g.b() + origin, 3e-4, 511, false};
  const auto [before, after] = pd::split_seed(seed, g, lo, hi, origin);

  // The oracle: the weight (u/h)^gam (v/h)^del, u = t - a, v = b - t, integrated by tanh-sinh on
  // each part in the distance to its own end (the edges' singularities at an end of the variable).
  boost::math::quadrature::tanh_sinh<double> rule;
  const double h = g.length() / 2;
  const auto w = [&](double u, double v) { return std::pow(u / h, g.jacobi.gam) * std::pow(v / h, g.jacobi.del); };
  const double int_before = rule.integrate([&](double u) { return w(u, g.length() - u); }, 0.0, lo - g.a());
  const double int_after = rule.integrate([&](double v) { return w(g.length() - v, v); }, 0.0, g.b() - hi);
  const double share = int_after / (int_before + int_after);
  // WHY 64 eps: Boost's ibeta behind integral_to and integral_from (a few tens of ulps), the
  // quadrature's error (~1e-16 here) and the ratio's rounding; a share by length is off by 0.41.
  constexpr double share_tolerance = 64 * eps;
  CHECK(after.load / seed.load == doctest::Approx(share).epsilon(share_tolerance));
  CHECK(before.load + after.load == doctest::Approx(seed.load).epsilon(4 * eps));
  CHECK(share > 0.75);  // the case tells the integrals from the lengths (share 0.794; by length 0.385)
  // Edges: the contact's outer ones, the negative part's as inner ones (absolute abscissae).
  CHECK(before.a == seed.a);
  CHECK(before.b == lo + origin);
  CHECK(after.a == hi + origin);
  CHECK(after.b == seed.b);
  // Solved loads, no degree cap (the parts' series start free).
  CHECK(before.load_solved);
  CHECK(after.load_solved);
  CHECK(before.degree == 0);
  CHECK(after.degree == 0);
}

TEST_CASE("split_seed: a part whose integral is not positive shares the load by length") {
  // A density negative all over (the coefficient -1): neither integral gives a share, and the
  // load is shared by the parts' lengths, never by a ratio of negative numbers or 0/0.
  pd::contact_density g;
  g.jacobi.lo = 0;
  g.jacobi.hi = 2;
  g.jacobi.gam = 0.35;
  g.jacobi.del = 0.35;
  g.jacobi.coefficients = {-1.0};
  g.nu = 0;
  const pd::coarse_patch seed{g.a(), g.b(), 1e-3, 0, true};
  const auto [before, after] = pd::split_seed(seed, g, 0.4, 0.5, 0.0);
  // WHY 4 eps: the lengths' differences and one division.
  CHECK(after.load / seed.load == doctest::Approx(1.5 / 1.9).epsilon(4 * eps));
  CHECK(before.load + after.load == doctest::Approx(seed.load).epsilon(4 * eps));
  CHECK(std::isfinite(before.load));
}
