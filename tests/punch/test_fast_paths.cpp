// The fast paths of rhabel::punch::solve used by the issue #4 speed target (study_scene_timing):
// the optional independent residual (solve_options::residual) and the pressure sampling with the
// series' recurrence coefficients precomputed (quadrature::jacobi_series).
// Oracles: the Riemann-Hilbert route (tests/punch/support.hpp: riemann::solve_abel_rh, no code
// shared with abel::solve_step or the spectral relation), and the same solve with the switch on.
#include <doctest/doctest.h>

#include "punch/support.hpp"

#include <algorithm>
#include <cmath>

using namespace rhabel::punch;

namespace {
material wedge_material(double alpha, double k) {
  return material{alpha, (1 - 0.09) / boost::math::tgamma(1 - alpha), 0.3, k};
}
}  // namespace

TEST_CASE("solve_options::residual = false changes nothing but the residual, which is NaN") {
  const material m = wedge_material(0.2, 0.0);
  const indentor ind{wedge{0.1, 0.1}, 1.0, 0.0};
  solve_options o;
  o.grid_points = 200;
  o.displacement = false;
  o.tolerance = 1e-10;
  const auto with = solve_single(m, 1.0, ind, o);
  o.residual = false;
  const auto without = solve_single(m, 1.0, ind, o);
  CHECK(std::isnan(without.residual));
  CHECK(with.residual < 1e-9);  // the evidence is there when asked: measured 1.2e-11
  CHECK(without.a == with.a);
  CHECK(without.b == with.b);
  CHECK(without.hysteretic_friction == with.hysteretic_friction);
  REQUIRE(without.pressure.size() == with.pressure.size());
  for (std::size_t k = 0; k < with.pressure.size(); ++k) CHECK(without.pressure[k] == with.pressure[k]);
  const auto scene_without = solve(scene{m, 1.0, {ind}}, o);
  CHECK(std::isnan(scene_without.diagnostics.residual));
}

TEST_CASE("issue 4 speed setting: wedge alpha = 0.2, S1 = S2, tolerance 1e-10 gives 1000 pressure samples to 1e-10 of the peak") {
  // The setting study_scene_timing reports for the speed target (measured 5.8e-12 of the peak sample).
  constexpr double issue_4_target = 1e-10;
  const material m = wedge_material(0.2, 0.0);
  solve_options o;
  o.grid_points = 1000;
  o.displacement = false;
  o.tolerance = 1e-10;
  o.residual = false;
  const auto r = solve_single(m, 1.0, indentor{wedge{0.1, 0.1}, 1.0, 0.0}, o);
  const punch_test::wedge_oracle oracle(m, 1.0, 0.1, 0.1, 0.0, r.a, r.b);
  double peak = 0, worst = 0;
  for (std::size_t k = 5; k < r.grid_x.size(); k += 10) peak = std::max(peak, std::abs(oracle.pressure(r.grid_x[k])));
  std::size_t compared = 0;
  for (std::size_t k = 5; k < r.grid_x.size(); k += 10) {
    // The oracle loses accuracy at isolated points (its two orders disagree there): skipped, as in the study.
    const auto d = oracle.sol.density(r.grid_x[k]);
    if (!(std::abs(d.error_estimate) < 1e-12 * std::abs(d.value))) continue;
    worst = std::max(worst, std::abs(r.pressure[k] - oracle.pressure(r.grid_x[k])));
    ++compared;
  }
  CHECK(compared >= 80);  // of 100 samples (the study keeps 95 here)
  CHECK(worst <= issue_4_target * peak);
}
