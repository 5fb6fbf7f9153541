// A sampled profile with its contact set unknown (rhabel/punch/profile.hpp) against oracles that
// share no code with its active set: the closed-form single parabola (via the parabolic
// indentor's own closed-form path, which the profile's spline and general-profile path do not
// use), and the independent boundary-element oracle of bem_oracle.hpp, which finds the contact
// set of a rigid body by its own active set on panels.
#include <doctest/doctest.h>

#include "bem_oracle.hpp"
#include "rhabel/punch.hpp"

#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {
namespace pu = rhabel::punch;
constexpr double pi = 3.141592653589793238462643383279502884;

// (pi/2) E_U for E1 = 1, speed 1, nu = 0: loads in units of int g are load / this.
double pressure_scale(double alpha) { return pi / 2 * boost::math::tgamma(1 - alpha); }

pu::solve_options profile_options() {
  pu::solve_options o;
  o.tolerance = 1e-10;
  // The spline of a sampled surface is C2: the density converges like degree^-3 (profile.hpp), so
  // the residual of (8) against the spline reaches ~1e-8 at 150 samples per unit, not 1e-12.
  o.acceptance = 1e-6;
  return o;
}
}  // namespace

TEST_CASE("a profile sampled from a parabola gives the parabola's answer") {
  // The natural spline of a parabola is the parabola away from its ends (the end's error decays
  // by 0.27 per sample): 600 samples on [-3, 3], the contact (L ~ 1) hundreds of samples from
  // the ends. The general-profile path then solves the same equation as the parabolic one, to the
  // degree-128 series of a forcing that is linear: edges to the root tolerance.
  constexpr double edge_tol = 1e-9;  // relative to L: root tolerance 1e-10 of both paths, x10
  for (const double alpha : {0.0, 0.3, 0.7}) {
    CAPTURE(alpha);
    const double R = 1, apex = 0.3, load = 0.3 * pressure_scale(alpha);
    pu::profile_scene ps;
    ps.material.alpha = alpha;
    ps.load = load;
    for (int i = 0; i <= 600; ++i) {
      const double x = -3 + 6.0 * i / 600;
      ps.profile.x.push_back(x);
      ps.profile.z.push_back(-(x - apex) * (x - apex) / (2 * R));
    }
    const auto o = profile_options();
    const auto ours = pu::solve_profile(ps, o);
    REQUIRE(ours.contacts.size() == 1);
    CHECK(ours.diagnostics.code == pu::status_code::ok);
    pu::scene sc;
    sc.material.alpha = alpha;
    sc.indentors.push_back({pu::parabolic{R}, load, apex});
    const auto ref = pu::solve(sc, o);
    const auto& c = ours.contacts[0];
    const auto& r = ref.indentors[0];
    CHECK(c.shape == pu::shape_kind::general);  // a profile's contact
    CHECK(r.shape == pu::shape_kind::parabolic);
    CHECK(std::abs(c.a - r.a) <= edge_tol * r.contact_length);
    CHECK(std::abs(c.b - r.b) <= edge_tol * r.contact_length);
    CHECK(std::abs(c.load - load) <= 1e-9 * load);  // the body's load, matched to the acceptance
    CHECK(std::abs(c.hysteretic_friction - r.hysteretic_friction) <= 1e-9 * std::abs(r.hysteretic_friction) + 1e-15);
  }
}

TEST_CASE("several bumps: the contact set and the contacts of the boundary-element oracle") {
  // The profile: the upper envelope of four parabolic caps (tips at c_j, heights h_j, radii R_j),
  // sampled uniformly on each piece between the envelope's corners, which are declared (the
  // spline keeps them). The third cap is 0.3 lower and stays clear at this load; the others touch.
  struct cap {
    double c, h, R;
  };
  const std::vector<cap> caps{{0, 0, 1}, {2, -0.02, 0.8}, {4, -0.3, 1.2}, {6, -0.01, 1}};
  auto cap_z = [](const cap& k, double x) { return k.h - (x - k.c) * (x - k.c) / (2 * k.R); };
  // Corner between caps p and q: where the two are equal (a quadratic; the root between tips).
  auto corner = [&](const cap& p, const cap& q) {
    double lo = p.c, hi = q.c;
    for (int it = 0; it < 200; ++it) {
      const double mid = (lo + hi) / 2;
      (cap_z(p, mid) > cap_z(q, mid) ? lo : hi) = mid;
    }
    return (lo + hi) / 2;
  };
  std::vector<double> cuts{-3};
  for (std::size_t k = 0; k + 1 < caps.size(); ++k) cuts.push_back(corner(caps[k], caps[k + 1]));
  cuts.push_back(9);
  const double alpha = 0.3, load_g = 0.6;
  pu::profile_scene ps;
  ps.material.alpha = alpha;
  ps.load = load_g * pressure_scale(alpha);
  for (std::size_t k = 0; k < caps.size(); ++k) {
    const int n = 300;
    for (int i = k == 0 ? 0 : 1; i <= n; ++i) {
      const double x = cuts[k] + (cuts[k + 1] - cuts[k]) * i / n;
      ps.profile.x.push_back(x);
      ps.profile.z.push_back(cap_z(caps[k], x));
    }
    if (k > 0) ps.profile.corners.push_back(cuts[k]);
  }
  const auto ours = pu::solve_profile(ps, profile_options());
  CAPTURE(ours.diagnostics.status);
  REQUIRE(ours.diagnostics.code == pu::status_code::ok);

  namespace bem = punch_test::bem;
  bem::scene bs;
  bs.alpha = alpha;
  bs.beta = 0;
  bs.one_body = true;
  bs.total_load = load_g;
  for (std::size_t k = 0; k < caps.size(); ++k) {
    bem::indentor I{bem::parabola{caps[k].R}, caps[k].c, 0.0, cuts[k], cuts[k + 1]};
    I.offset = caps[k].h;  // the oracle's profile f + z
    bs.indentors.push_back(I);
  }
  const auto oracle = bem::solve(bs, bem::test_options(bem::options{}.levels));
  REQUIRE(oracle.converged);
  std::vector<std::size_t> touching;
  for (std::size_t k = 0; k < caps.size(); ++k)
    if (oracle.contacts[k].in_contact) touching.push_back(k);
  REQUIRE(touching.size() == ours.contacts.size());
  CHECK(touching == std::vector<std::size_t>{0, 1, 3});  // the scene's design: the low cap stays clear
  for (std::size_t m = 0; m < touching.size(); ++m) {
    CAPTURE(m);
    const auto& theirs = oracle.contacts[touching[m]];
    const auto& c = ours.contacts[m];
    CHECK(ours.tips[m] == doctest::Approx(caps[touching[m]].c).epsilon(0.02));
    // Twice the oracle's bar (an estimate: test_coupled_bem.cpp) plus the spline's effect on the
    // edges: the caps are exact parabolas on samples 1/100 apart, the natural ends at the corners
    // decay to 1e-14 within 25 samples, and the contacts lie > 60 samples from the corners.
    CHECK(std::abs(c.a - theirs.a.value) <= 2 * theirs.a.error + 1e-9 * c.contact_length);
    CHECK(std::abs(c.b - theirs.b.value) <= 2 * theirs.b.error + 1e-9 * c.contact_length);
    CHECK(std::abs(c.load / pressure_scale(alpha) - theirs.load.value) <= 2 * theirs.load.error + 1e-8 * theirs.load.value);
    CHECK(theirs.a.error < 2e-3 * c.contact_length);  // the comparison is not vacuous
  }
  CHECK(ours.clearance >= -1e-6);
}

namespace {
/// The cosine bumps of studies/scenes/cosine_profile.py: `periods` bumps of period 1 and height
/// 0.05 (varying by 20 %), 80 samples per period, E1 = 1, speed 1, the body's load periods/200.
pu::profile_scene cosine_bumps(int periods, double alpha) {
  pu::profile_scene ps;
  ps.material.alpha = alpha;
  ps.load = periods / 200.0;
  const int n = 80 * periods;
  for (int i = 0; i < n; ++i) {
    const double x = -0.5 + periods * static_cast<double>(i) / (n - 1);
    ps.profile.x.push_back(x);
    ps.profile.z.push_back(0.05 * std::cos(2 * pi * x) * (1 + 0.2 * std::sin(2 * pi * x / 3.7)));
  }
  return ps;
}
}  // namespace

TEST_CASE("many bumps: the set of 25 cosine bumps, checked by the surface its pressure makes") {
  // This scene ended not_converged (a contact with a negative load, the profile penetrating by
  // 2.4e-3 of its span) when the search grew the set from the highest tip by load continuation;
  // it now starts from the coarse boundary-element solve's set (contact_set.cpp).
  const double alpha = 0.3;
  const auto ps = cosine_bumps(25, alpha);
  auto o = profile_options();
  o.grid_points = 401;
  const auto r = pu::solve_profile(ps, o);
  CAPTURE(r.diagnostics.status);
  REQUIRE(r.diagnostics.code == pu::status_code::ok);
  CHECK(r.contacts.size() > 10);  // most bumps touch (14 at this load)
  // Independent evidence from the reported pressure samples alone (no rhabel code): the density
  // g = p/((pi/2) E_U) piecewise constant between the samples, its surface displacement
  // w = Gamma(1 - alpha) int g Psi by the oracle's closed-form panel integrals. On the contacts
  // w - z is one level D; off them w - z >= D. check_tol: the piecewise-constant quadrature of
  // a density with square-root edges on 400 intervals, ~(1/400)^1.5 of Gamma P / alpha ~ 1e-4
  // of the span 0.1, times 10 (measured: levels within 1.6e-4 of the span, clearance >= -6.5e-5).
  constexpr double check_tol = 1e-3;
  const punch_test::bem::kernel K(alpha, 0.0);
  const double span = 0.12;  // max z - min z of the samples (0.05 (1 +- 0.2) on either side)
  auto w_minus_z = [&](double x, double z) {
    double w = 0;
    for (const auto& c : r.contacts)
      for (std::size_t k = 0; k + 1 < c.grid_x.size(); ++k) {
        const double g = (c.pressure[k] + c.pressure[k + 1]) / 2 / pressure_scale(alpha);
        w += g * K.panel(c.grid_x[k], c.grid_x[k + 1], x);
      }
    return K.gamma1 * w - z;
  };
  double total = 0;
  std::vector<double> levels;
  for (const auto& c : r.contacts) {
    double load = 0;
    for (std::size_t k = 0; k + 1 < c.grid_x.size(); ++k) load += (c.pressure[k] + c.pressure[k + 1]) / 2 * (c.grid_x[k + 1] - c.grid_x[k]);
    CHECK(load > 0);
    CHECK(*std::min_element(c.pressure.begin(), c.pressure.end()) >= 0);
    total += load;
    const double mid = (c.a + c.b) / 2;
    levels.push_back(w_minus_z(mid, 0.05 * std::cos(2 * pi * mid) * (1 + 0.2 * std::sin(2 * pi * mid / 3.7))));
  }
  // The trapezoid rule on 401 points of a density with square-root edges: measured 5.9e-4.
  CHECK(std::abs(total - ps.load) <= 2e-3 * ps.load);
  const double D = levels[0];
  for (const double l : levels) CHECK(std::abs(l - D) <= check_tol * span);
  double worst = 0;
  for (std::size_t q = 0; q < ps.profile.x.size(); q += 4) {
    const double x = ps.profile.x[q];
    bool inside = false;
    for (const auto& c : r.contacts) inside = inside || (x >= c.a && x <= c.b);
    if (!inside) worst = std::min(worst, w_minus_z(x, ps.profile.z[q]) - D);
  }
  CHECK(worst >= -check_tol * span);
}

TEST_CASE("an ok profile at acceptance 1e-6 lies within it of the same profile solved to 1e-9") {
  // The search solves a sampled profile's edges to 1e-3 of the acceptance (profile.hpp), not to
  // the tolerance: what it reports as ok must still be within the acceptance of the answer. The
  // reference is the same search at acceptance 1e-9 (edges to the tolerance 1e-10, series to the
  // degrees that acceptance needs). Edges relative to each contact's length, loads and C_f
  // relative to the body's.
  constexpr double acceptance = 1e-6;
  const auto ps = cosine_bumps(25, 0.3);
  auto o = profile_options();
  o.acceptance = acceptance;
  auto tight = o;
  tight.acceptance = 1e-9;
  const auto r = pu::solve_profile(ps, o);
  const auto t = pu::solve_profile(ps, tight);
  CAPTURE(r.diagnostics.status);
  CAPTURE(t.diagnostics.status);
  REQUIRE(r.diagnostics.code == pu::status_code::ok);
  REQUIRE(t.diagnostics.code == pu::status_code::ok);
  REQUIRE(r.contacts.size() == t.contacts.size());
  for (std::size_t k = 0; k < r.contacts.size(); ++k) {
    const auto& c = r.contacts[k];
    const auto& d = t.contacts[k];
    CAPTURE(k);
    CHECK(std::abs(c.a - d.a) <= acceptance * d.contact_length);
    CHECK(std::abs(c.b - d.b) <= acceptance * d.contact_length);
    CHECK(std::abs(c.load - d.load) <= acceptance * ps.load);
  }
  CHECK(std::abs(r.hysteretic_friction - t.hysteretic_friction) <= acceptance * std::abs(t.hysteretic_friction));
}

TEST_CASE("a profile whose contacts would reach the end of its samples is refused") {
  // At alpha 0.7 the surface far ahead of the loads rises like d^0.7 above any bounded profile:
  // 50 cosine bumps put most of the load on the samples' first panel (the search ran 124 s into
  // not_converged before this was recognised).
  const auto ps = cosine_bumps(50, 0.7);
  std::string message = "no exception";
  try {
    pu::solve_profile(ps, profile_options());
  } catch (const std::domain_error& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK(message.find("body.load = 0.25") != std::string::npos);
  CHECK(message.find("reach the end of the samples at x = -0.5") != std::string::npos);
  CHECK(message.find("extend profile.x and profile.z") != std::string::npos);
}

TEST_CASE("a profile whose two contacts close in on each other ends in few Newton iterations") {
  // Found by the fuzz target (tests/fuzz/corpus/slow_profile_closing.json): 12 samples, a deep
  // dip after the highest. The coupled solve of the two bumps' contacts crept toward a merge at
  // 0.009 of a contact length, its condition stuck at 6e-4 with accepted steps of 1e-5, for 60
  // iterations of 0.36 s each, and the search repeated that set round after round (minutes; the
  // search then reached its limit of 44 rounds). The flat-run rule (coupled_newton.cpp) ends such
  // an iteration and names the closing pair (contacts_merge). The result need not be ok; it must
  // be bounded and honest.
  pu::profile_scene ps;
  ps.material = {0.3, 1.0, 0.3, 0.2};
  ps.load = 0.001;
  ps.profile.x = {0.1, 0.4, 0.8, 1.2, 1.6, 2.0, 2.4, 2.8, 3.2, 3.6, 4.0, 4.4};
  ps.profile.z = {0.01, 0.0, -0.01, 0.0, 0.01, 0.0, 0.0, 0.0, 0.02, 0.0, -1.01, 0.0};
  if (punch_test::bem::sanitizer_build) return;  // 5 s in Release, ~30 s under ASan
  const auto r = pu::solve_profile(ps, profile_options());
  CAPTURE(r.diagnostics.status);
  CHECK(r.diagnostics.iterations < 300);  // measured 140 in 10 rounds; thousands without the rule
  CHECK(r.diagnostics.rounds < 20);
  if (r.diagnostics.code == pu::status_code::ok) CHECK(r.diagnostics.residual < profile_options().acceptance);
}

TEST_CASE("solve_options::time_limit: a search stopped by it reports not_converged and says why") {
  const auto ps = cosine_bumps(10, 0.3);
  auto o = profile_options();
  // 1 ns: out of time before the first Newton step of the first coupled round (the isolated
  // contacts and the coarse prediction take far longer), so the outcome does not depend on the
  // machine.
  o.time_limit = 1e-9;
  const auto r = pu::solve_profile(ps, o);
  CAPTURE(r.diagnostics.status);
  CHECK(r.diagnostics.code == pu::status_code::not_converged);
  CHECK(r.diagnostics.status.find("time limit of 1e-09 s") != std::string::npos);
  CHECK(r.diagnostics.status.find("solve_options") == std::string::npos);  // no C++ member for users
  CHECK(r.diagnostics.iterations == 0);
  // Out of time before the coarse solve's first step, the search starts from the highest tip
  // alone at 1/256 of the load: what it reports carries that fraction, and says so first.
  CHECK(r.diagnostics.load_fraction == doctest::Approx(1.0 / 256).epsilon(1e-15));
  CHECK(r.diagnostics.status.rfind("the search reached only 0.00391 of body.load", 0) == 0);
  // The same search without the limit (the cosine bumps of the test above) is ok, at the full
  // load, and finds no contact missing.
  o.time_limit = 0;
  const auto full = pu::solve_profile(ps, o);
  CHECK(full.diagnostics.code == pu::status_code::ok);
  CHECK(full.diagnostics.load_fraction == 1);
  CHECK(full.penetrations.empty());
  for (const double bad : {-1.0, std::nan(""), HUGE_VAL}) {
    o.time_limit = bad;
    CAPTURE(bad);
    CHECK_THROWS_AS(pu::solve_profile(ps, o), std::invalid_argument);
  }
}

TEST_CASE("a profile result with contacts not ok says which, the first one's status and how many") {
  // Judged against an acceptance below the residuals of (8) that the series reach at the default
  // degree (4e-9 .. 3.5e-8 for these bumps, profile.hpp), most contacts are not ok by their own
  // evidence: the body's status lists them (the first 8 indices), and leads with the first one's
  // status, so that a user of hundreds of contacts need not search them.
  auto strict = profile_options();
  strict.acceptance = 1e-11;
  const auto r = pu::solve_profile(cosine_bumps(10, 0.3), strict);
  std::vector<std::size_t> bad;
  for (std::size_t k = 0; k < r.contacts.size(); ++k)
    if (r.contacts[k].code != pu::status_code::ok) bad.push_back(k);
  CAPTURE(r.diagnostics.status);
  REQUIRE(bad.size() > 1);
  CHECK(r.diagnostics.code != pu::status_code::ok);
  const std::string first = "see contacts[" + std::to_string(bad[0]) + "].status: " + r.contacts[bad[0]].status;
  CHECK(r.diagnostics.status.rfind(first, 0) == 0);
  std::string listed = std::to_string(bad.size()) + " of " + std::to_string(r.contacts.size()) + " contacts are not ok: ";
  for (std::size_t k = 0; k < std::min<std::size_t>(bad.size(), 8); ++k) listed += (k ? ", " : "") + std::to_string(bad[k]);
  CHECK(r.diagnostics.status.find(listed) != std::string::npos);
  CHECK((r.diagnostics.status.find(", ...") != std::string::npos) == (bad.size() > 8));
}

TEST_CASE("solve_profile refuses bad input naming the field") {
  pu::profile_scene ps;
  ps.profile.x = {0, 1, 2, 3, 4};
  ps.profile.z = {0, 1, 2, 1, 0};
  auto message = [&](const pu::profile_scene& s) {
    try {
      pu::solve_profile(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  auto bad = ps;
  bad.profile.x[2] = 1;
  CHECK(message(bad).find("profile.x[2] = 1 must be > profile.x[1] = 1") != std::string::npos);
  bad = ps;
  bad.profile.z.pop_back();
  CHECK(message(bad).find("profile.x has 5 samples and profile.z 4") != std::string::npos);
  bad = ps;
  bad.profile.z[1] = std::nan("");
  CHECK(message(bad).find("profile.z[1] = nan must be finite") != std::string::npos);
  bad = ps;
  bad.load = -1;
  CHECK(message(bad).find("load = -1 must be finite and > 0") != std::string::npos);
  bad = ps;
  bad.profile.corners = {1.5};
  CHECK(message(bad).find("profile.corners (1.5) must each be one of profile.x[1]") != std::string::npos);
  bad = ps;
  bad.profile.z = {5, 1, 2, 1, 0};
  CHECK(message(bad).find("highest at an end") != std::string::npos);
  bad = ps;
  bad.material.alpha = 1;
  CHECK(message(bad).find("rhabel::punch::solve_profile: material.alpha = 1 must be in [0, 1)") != std::string::npos);
}

TEST_CASE("periodic elastic sinusoid: Westergaard's contact width, C_f = 0, by the spectral search") {
  // z = -(Delta/2)(1 - cos(2 pi x/lambda)), alpha = 0, nu = 0, E1 = 1 (E* = 1): the contact
  // [-a, a] (modulo lambda) at the mean pressure p_mean = (pi E* Delta/(2 lambda)) sin^2(pi a/lambda)
  // (Westergaard 1939; Johnson, Contact Mechanics, 13.2). 400 samples a period: the periodic
  // spline is within ~(2 pi/400)^4/384 ~ 2e-10 of Delta of the sinusoid, but its knots limit the
  // residual of (8) at the default degree to ~1e-7 (profile.hpp), and the edges follow it: measured
  // 3.8e-9, 1.3e-8, 4.8e-8 lambda at the three shares; asked to 5e-7 lambda.
  const double lambda = 2, Delta = 0.01;
  const std::size_t n = 400;
  pu::profile_scene ps;  // E1 1, nu 0, k 0, speed 1
  for (std::size_t i = 0; i < n; ++i) {
    const double x = -0.5 + lambda * static_cast<double>(i) / static_cast<double>(n);
    ps.profile.x.push_back(x);
    ps.profile.z.push_back(-Delta / 2 * (1 - std::cos(2 * pi * x / lambda)));
  }
  ps.profile.period = lambda;
  for (const double share : {0.05, 0.3, 0.8}) {  // p_mean over the full-contact pressure pi Delta/(2 lambda)
    CAPTURE(share);
    const double p_mean = share * pi * Delta / (2 * lambda);
    ps.load = p_mean * lambda;
    const auto r = pu::solve_profile(ps, profile_options());
    CAPTURE(r.diagnostics.status);
    CHECK(r.diagnostics.code == pu::status_code::ok);
    REQUIRE(r.contacts.size() == 1);
    const double a = lambda / pi * std::asin(std::sqrt(share));
    // The contact is reported on a window of one period starting in the widest gap: modulo lambda.
    CHECK(std::abs(std::remainder(r.contacts[0].a + a, lambda)) <= 5e-7 * lambda);
    CHECK(std::abs(std::remainder(r.contacts[0].b - a, lambda)) <= 5e-7 * lambda);
    CHECK(r.window_start <= r.contacts[0].a);
    CHECK(r.contacts[0].b <= r.window_start + lambda);
    CHECK(std::abs(r.hysteretic_friction) <= 1e-9);
    CHECK(r.contact_fraction == doctest::Approx(2 * a / lambda).epsilon(1e-6));
    CHECK(r.mean_pressure == doctest::Approx(p_mean).epsilon(1e-15));
    CHECK(r.contacts[0].load == doctest::Approx(ps.load).epsilon(1e-9));
  }
  // Above the full-contact pressure there is no gap to start the window in: refused naming the load.
  ps.load = 1.2 * pi * Delta / 2;
  CHECK_THROWS_WITH_AS(pu::solve_profile(ps, profile_options()), doctest::Contains("body.load"), std::domain_error);
}
