// The Jacobian a rigid body's coupled solve keeps for the next (punch/src/coupled_problem.hpp,
// jacobian_memo; internal): a sampled profile's rounds solve nearly the same contacts again and
// again, and start from it instead of differencing a new one. Checked on seven general profiles
// (parabolas given by their slope, so that the seeded path of a sampled profile's round is taken)
// on one body: the solve from a kept Jacobian takes fewer finite-difference Jacobians and ends on
// the same edges; a wrong kept Jacobian costs a new one and changes nothing of the result; one
// taken at other edges, or a start from guessed loads, does not read it. Cheap enough for the
// sanitizer build (seven contacts, a few Newton steps each).
#include <doctest/doctest.h>

#include "../punch/src/coupled_problem.hpp"
#include "../punch/src/internal.hpp"
#include "rhabel/punch.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

namespace {
using namespace rhabel::punch;
namespace d = rhabel::punch::detail;

/// Seven parabolic profiles (radii 1 and 1.5) 6 apart on one body, heights a few 1e-3: the scene
/// of test_coupled.cpp's coloured body Jacobian, as general profiles.
scene seven() {
  scene s{material{0.3, 1.0, 0.3, 0.0}, 1.0, {}};
  const double heights[] = {0.0, 0.004, -0.003, 0.002, 0.0, -0.002, 0.003};
  for (int k = 0; k < 7; ++k) {
    const double R = k % 2 == 0 ? 1.0 : 1.5;
    general_profile gp;
    gp.slope = [R](double u) { return -u / R; };
    gp.value = [R](double u) { return -u * u / (2 * R); };
    gp.search_lo = -3;
    gp.search_hi = 3;
    s.indentors.push_back(indentor{gp, 1.0, 6.0 * k});
    s.indentors.back().height = heights[k];
  }
  s.body = rigid_body{1.0};
  return s;
}

struct outcome {
  d::coupled_outcome out;
  std::vector<std::pair<double, double>> edges;  // the states' frame, in the states' order
  std::vector<double> loads;                     // units of int g
};

/// The body's coupled solve of `s`, from `seeds` (states' frame; none: the solver's own start)
/// with the loads `loads`, sharing `memo`. `solved`: the loads are a solve's (indentor_state::
/// seed_load, as a profile round's from a converged round), imposed first; else a guess (a
/// repaired contact's), only the starting split.
outcome solve_body(const scene& s, const std::vector<std::pair<double, double>>& seeds, const std::vector<double>& loads,
                   std::shared_ptr<d::coupled::jacobian_memo> memo, bool solved = true) {
  const auto cx = d::make_context(s.material, s.speed, solve_options{});
  auto ss = d::prepare_states(s, cx);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    ss.st[i].seed = seeds[i];
    ss.st[i].target_load = loads[i];
    ss.st[i].seed_load = solved;
  }
  outcome o;
  o.out = d::solve_coupled(ss.st, cx, s.body->load / cx.pressure_scale, std::move(memo));
  for (const auto& st : ss.st) o.edges.emplace_back(st.g.a(), st.g.b()), o.loads.push_back(st.target_load);
  return o;
}

/// Each contact's edges moved outwards by `fraction` of its length.
std::vector<std::pair<double, double>> widened(const std::vector<std::pair<double, double>>& e, double fraction) {
  std::vector<std::pair<double, double>> out;
  for (const auto& [a, b] : e) out.emplace_back(a - fraction * (b - a), b + fraction * (b - a));
  return out;
}

/// The largest distance of corresponding edges relative to the contact's length.
double edge_distance(const outcome& p, const outcome& q) {
  double worst = 0;
  for (std::size_t i = 0; i < p.edges.size(); ++i) {
    const double L = p.edges[i].second - p.edges[i].first;
    worst = std::max({worst, std::abs(p.edges[i].first - q.edges[i].first) / L,
                      std::abs(p.edges[i].second - q.edges[i].second) / L});
  }
  return worst;
}
}  // namespace

TEST_CASE("a kept Jacobian starts the next solve of the same contacts; a wrong or far one changes no result") {
  // Edges agree to 1e-8 of a length: each solve converges its edge conditions to the tolerance
  // 1e-12 (Newton's last step below 10x it), and the conditions' sensitivity to an edge is of
  // order one relative to the length; 1e-8 leaves four orders for the conditioning of seven
  // coupled contacts (test_coupled.cpp compares the same scene's edges at 1e-8 of a length).
  constexpr double edge_tol = 1e-8;
  const scene s = seven();
  const auto first = solve_body(s, {}, {}, nullptr);
  REQUIRE(first.out.code == status_code::ok);
  // Seeds 2 % wider than the solution: Newton steps, and a Jacobian at their start.
  const auto seeds = widened(first.edges, 0.02);

  const auto memo = std::make_shared<d::coupled::jacobian_memo>();
  const auto a = solve_body(s, seeds, first.loads, memo);
  REQUIRE(a.out.code == status_code::ok);
  REQUIRE(a.out.jacobians >= 1);
  REQUIRE(memo->J.rows() == 14);  // kept: two edges a contact
  CHECK(edge_distance(a, first) < edge_tol);

  SUBCASE("from the kept Jacobian: fewer differenced Jacobians, the same edges") {
    const auto b = solve_body(s, seeds, first.loads, memo);
    REQUIRE(b.out.code == status_code::ok);
    CHECK(b.out.jacobians < a.out.jacobians);
    CHECK(edge_distance(b, a) < edge_tol);
  }
  SUBCASE("a wrong kept Jacobian at these edges: replaced by a differenced one, the same edges") {
    memo->J = 1e3 * Eigen::MatrixXd::Identity(14, 14);
    const auto c = solve_body(s, seeds, first.loads, memo);
    REQUIRE(c.out.code == status_code::ok);
    CHECK(c.out.jacobians >= 1);
    CHECK(edge_distance(c, a) < edge_tol);
    CHECK(!memo->J.isApprox(1e3 * Eigen::MatrixXd::Identity(14, 14)));
  }
  SUBCASE("a start from guessed loads (a repaired contact's) does not read the kept Jacobian") {
    // (coupled_newton.cpp, memo_serves: from a kept Jacobian, a round after a repair closed two
    // contacts of a rough profile until they merged.) The same path as without a memo.
    const auto fresh = solve_body(s, seeds, first.loads, nullptr, false);
    const auto g = solve_body(s, seeds, first.loads, memo, false);
    REQUIRE(fresh.out.code == status_code::ok);
    REQUIRE(g.out.code == status_code::ok);
    CHECK(g.out.jacobians == fresh.out.jacobians);
    CHECK(g.out.iterations == fresh.out.iterations);
    CHECK(edge_distance(g, fresh) == 0.0);
  }
  SUBCASE("a Jacobian kept at edges a fifth of a length away is not read") {
    // memo_shift is a tenth of a length: the wrong matrix is never the start, so the solve
    // differences its own and takes the same path as the first seeded one.
    memo->J = 1e3 * Eigen::MatrixXd::Identity(14, 14);
    const auto far = widened(seeds, 0.2);
    for (std::size_t i = 0; i < far.size(); ++i) memo->a[i] = far[i].first, memo->b[i] = far[i].second;
    const auto e = solve_body(s, seeds, first.loads, memo);
    REQUIRE(e.out.code == status_code::ok);
    CHECK(e.out.jacobians == a.out.jacobians);
    CHECK(e.out.iterations == a.out.iterations);
    CHECK(edge_distance(e, a) == 0.0);
  }
}
