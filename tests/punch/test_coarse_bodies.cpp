// The coarse solve of several independent indentors on one grid (punch/src/coarse_bodies.hpp,
// internal): the start of a coupled solve whose continuations fail. Its intervals are only a start
// (edges to about a panel), so they are checked against solutions within a few panels; whether the
// coupled solve from them is right is test_coupled_bem.cpp's (the boundary-element oracle).
// Cheap enough for the sanitizer build (a few dense solves of <= 512 panels).
#include <doctest/doctest.h>

#include "../punch/src/coarse_bodies.hpp"
#include "rhabel/punch.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace {
using namespace rhabel::punch;
namespace d = rhabel::punch::detail;

/// The states of the scene, their isolated contacts, and the coarse solve's intervals (absolute
/// abscissae, in the order of the scene's indentors).
struct coarse_outcome {
  bool found = false;
  std::vector<std::pair<double, double>> interval;  // by scene index
  std::vector<std::pair<double, double>> isolated;  // by scene index
};

coarse_outcome coarse(const scene& s) {
  const auto cx = d::make_context(s.material, s.speed, solve_options{});
  auto ss = d::prepare_states(s, cx);
  std::vector<std::pair<double, double>> iso;
  for (auto& st : ss.st) {
    d::solve_isolated(st, cx);
    iso.emplace_back(st.g.a(), st.g.b());
  }
  coarse_outcome out;
  out.interval.resize(s.indentors.size());
  out.isolated.resize(s.indentors.size());
  for (std::size_t i = 0; i < ss.st.size(); ++i)
    out.isolated[ss.st[i].scene_index] = {iso[i].first + ss.origin, iso[i].second + ss.origin};
  const auto start = d::coarse_bodies(ss.st, iso, cx);
  if (!start) return out;
  out.found = true;
  for (std::size_t i = 0; i < ss.st.size(); ++i)
    out.interval[ss.st[i].scene_index] = {(*start)[i].first + ss.origin, (*start)[i].second + ss.origin};
  return out;
}
}  // namespace

TEST_CASE("three parabolas out of apex order: one interval each, within two panels of the separated solution") {
  // Alpha 0.6, radii 1, 0.8, 1.2, loads 1, 0.6, 1.4, apexes 0, -0.05, 0.7332 (coarse_bodies.hpp):
  // the isolated contacts overlap and the continuation in the load ends in a merge. The reference
  // edges are rhabel's coupled solution from this start (ok, residual ~3e-13), which agrees with
  // the independent boundary-element oracle within its error bar (1.4e-4 at most; the same scene
  // in test_coupled_bem.cpp). Tolerance: two panels of the second window (1.5 x the contacts'
  // hull of 2.3 over 512 panels: 0.0068 each).
  constexpr double two_panels = 2 * 1.5 * 2.31 / 512;
  const material m{0.6, 1.0, 0.5, 0.0};
  const scene s{m, 1.0, {indentor{parabolic{1.0}, 1.0, 0.0}, indentor{parabolic{0.8}, 0.6, -0.05},
                         indentor{parabolic{1.2}, 1.4, 0.7332}}};
  const std::vector<std::pair<double, double>> solved{
      {-2.0907651187, -1.5518725389}, {-1.4923149168, -1.1415841610}, {-1.0993731532, 0.2124202806}};
  const auto c = coarse(s);
  REQUIRE(c.found);
  for (std::size_t i = 0; i < 3; ++i) {
    CAPTURE(i);
    CHECK(std::abs(c.interval[i].first - solved[i].first) < two_panels);
    CHECK(std::abs(c.interval[i].second - solved[i].second) < two_panels);
  }
  // Not the isolated contacts (which overlap): the start the continuations lacked.
  CHECK(std::max(c.isolated[0].first, c.isolated[1].first) < std::min(c.isolated[0].second, c.isolated[1].second));
}

TEST_CASE("contacts that merge give no start") {
  // Two identical elastic parabolas 0.2 apart (R = 1, loads 0.3 pi/2): the coupled solve's gap closes
  // (contacts_merge, test_coupled.cpp); on the coarse grid the two indentors' panels touch.
  const double load = 0.3 * 3.141592653589793 / 2;
  const scene s{material{0.0, 1.0, 0.0, 0.0}, 1.0,
                {indentor{parabolic{1.0}, load, 0.0}, indentor{parabolic{1.0}, load, 0.2}}};
  CHECK_FALSE(coarse(s).found);
}

TEST_CASE("contacts far apart: the coupled contacts, to two panels") {
  // Two parabolas 6 apart at alpha 0.3 (R = 1, loads 0.3; contacts ~0.9 long, ~5 lengths apart):
  // the coupled solve converges directly from the isolated contacts (milliseconds) and its edges
  // (checked against the oracle for such gaps in test_coupled_bem.cpp) are the reference; the
  // second window (1.5 x a hull of ~6.9 over 512 panels) puts the edges within two panels.
  const scene s{material{0.3, 1.0, 0.3, 0.0}, 1.0,
                {indentor{parabolic{1.0}, 0.3, 0.0}, indentor{parabolic{1.0}, 0.3, 6.0}}};
  const auto r = solve(s);
  REQUIRE(r.diagnostics.code == status_code::ok);
  const auto c = coarse(s);
  REQUIRE(c.found);
  const double hull = r.indentors[1].b - r.indentors[0].a, two_panels = 2 * 1.5 * hull / 512;
  for (std::size_t i = 0; i < 2; ++i) {
    CAPTURE(i);
    CHECK(std::abs(c.interval[i].first - r.indentors[i].a) < two_panels);
    CHECK(std::abs(c.interval[i].second - r.indentors[i].b) < two_panels);
  }
}
