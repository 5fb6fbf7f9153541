// Several contacts at once (paper system 41, punch/src/coupled_solve.cpp) against oracles that
// share no code with the solver: the semi-closed two-parabola solution on the boundary
// alpha + beta/2 = 1/2 (one-sided Abel equation, inverted by Abel's formula and integrated by
// boost::math tanh-sinh), mirror symmetry of the elastic frictionless half-plane, the decay of the
// coupling with the distance, and the honest status of scenes the former block Gauss-Seidel
// reported as `ok` while wrong (issue 13).
#include <doctest/doctest.h>

#include "bem_oracle.hpp"
#include "rhabel/punch.hpp"

#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

using namespace rhabel::punch;

namespace {
constexpr double pi = 3.141592653589793238462643383279502884;

// Edges of the coupled solve are converged to 10 tolerance L (1e-11 L) and the oracle's roots to
// 1e-14 relative; its tanh-sinh integrals to ~1e-13. Measured agreement: see the test.
constexpr double semi_closed_tol = 1e-9;

// On the boundary (alpha = 1/2, beta = 0, kappa = 0) equation (8) is one-sided: s feels only t > s.
// The trailing parabola (apex at D) is the isolated one: b2 = D, g2 = (b2 - t)^(1/2)/(pi R Gamma(3/2)),
// int g2 = L2^(3/2) (2/3)/(pi R Gamma(3/2)). The leading one solves int_s^b1 g1 (t - s)^(-1/2) dt =
// F1(s) = -s/(R Gamma(1/2)) - A g2(s), with A g2(s) = c (theta - sin theta cos theta)/(pi R
// Gamma(3/2)), c = b2 - s, sin^2 theta = L2/c (closed form of int_0^L2 sqrt(u/(c - u)) du). Abel's
// inversion g1 = -(1/pi) d/dt int_t^b1 F1(s)(s - t)^(-1/2) ds is bounded at b1 iff F1(b1) = 0, and
// int g1 = (1/pi) int_a1^b1 F1(s)(s - a1)^(-1/2) ds: two scalar equations for b1 and a1.
struct boundary_pair {
  double R, D, load_g;  // radius of both, trailing apex, load of each in units of int g
  double L2 = 0;
  boundary_pair(double R_, double D_, double load_g_) : R(R_), D(D_), load_g(load_g_) {
    L2 = std::pow(load_g * pi * R * boost::math::tgamma(1.5) * 1.5, 2.0 / 3.0);
  }
  double action2(double s) const {
    const double c = D - s, th = std::asin(std::sqrt(L2 / c));
    return c * (th - std::sin(th) * std::cos(th)) / (pi * R * boost::math::tgamma(1.5));
  }
  double F1(double s) const { return -s / (R * boost::math::tgamma(0.5)) - action2(s); }
  double b1() const {
    std::uintmax_t it = 200;
    const auto r = boost::math::tools::toms748_solve([&](double s) { return F1(s); }, -1.0, 0.0, boost::math::tools::eps_tolerance<double>(50), it);
    return (r.first + r.second) / 2;
  }
  double load1(double a, double b) const {
    // s = a + u^2 removes the (s - a)^(-1/2): (1/pi) int_0^sqrt(b - a) 2 F1(a + u^2) du.
    boost::math::quadrature::tanh_sinh<double> ts;
    return ts.integrate([&](double u) { return 2 * F1(a + u * u); }, 0.0, std::sqrt(b - a)) / pi;
  }
  double a1(double b) const {
    std::uintmax_t it = 200;
    const auto r = boost::math::tools::toms748_solve([&](double a) { return load1(a, b) - load_g; }, b - 10.0, b - 1e-6,
                                                     boost::math::tools::eps_tolerance<double>(50), it);
    return (r.first + r.second) / 2;
  }
};

scene two(const material& m, indentor first, indentor second) { return scene{m, 1.0, {first, second}}; }

/// Two parabolas R = 1 at alpha 0.3 on one rigid body with unit load, 3 apart, the second raised by
/// 0.05: the trailing one sits in the leading one's wake and carries less.
scene raised_pair() {
  scene s = two(material{0.3, 1.0, 0.3, 0.0}, indentor{parabolic{1.0}, 1.0, 0.0}, indentor{parabolic{1.0}, 1.0, 3.0});
  s.indentors[1].height = 0.05;
  s.body = rigid_body{1.0};
  return s;
}
}  // namespace

TEST_CASE("alpha = 1/2: two parabolas against the semi-closed solution (trailing one independent)") {
  const material m{0.5, 1.0, 0.0, 0.0};  // alpha + beta/2 = 1/2: kappa = 0
  const double ps = pi / 2 * m.effective_modulus(1.0);
  for (double gap_ratio : {1.0, 0.1, 0.01}) {
    CAPTURE(gap_ratio);
    const double R = 1, load = 1;
    boundary_pair oracle(R, 0, load / ps);
    oracle.D = oracle.L2 * (1 + gap_ratio);  // the leading contact ends near 0: gap ~ gap_ratio L2
    const auto r = solve(two(m, indentor{parabolic{R}, load, 0.0}, indentor{parabolic{R}, load, oracle.D}));
    REQUIRE(r.diagnostics.code == status_code::ok);
    const double b1 = oracle.b1(), a1 = oracle.a1(b1);
    CHECK(std::abs(r.indentors[1].b - oracle.D) < semi_closed_tol * oracle.L2);
    CHECK(std::abs(r.indentors[1].contact_length - oracle.L2) < semi_closed_tol * oracle.L2);
    CHECK(std::abs(r.indentors[0].b - b1) < semi_closed_tol * oracle.L2);
    CHECK(std::abs(r.indentors[0].a - a1) < semi_closed_tol * oracle.L2);
    CHECK(r.indentors[0].a < r.indentors[1].a);
  }
}

TEST_CASE("elastic frictionless half-plane: identical indentors give mirror-symmetric contacts") {
  // alpha = 0, beta = 0: the kernel is odd, so the scene mirrored about the midpoint is itself.
  const material m{0.0, 1.0, 0.3, 0.0};
  constexpr double mirror_tol = 1e-9;  // edges converged to 1e-11 L, symmetry is not imposed
  SUBCASE("parabolas") {
    for (double D : {3.0, 1.5, 1.2}) {
      CAPTURE(D);
      const auto r = solve(two(m, indentor{parabolic{1.0}, 0.5, 0.0}, indentor{parabolic{1.0}, 0.5, D}));
      REQUIRE(r.diagnostics.code == status_code::ok);
      const auto& p = r.indentors[0];
      const auto& q = r.indentors[1];
      CHECK(std::abs((p.a + q.b) - D) < mirror_tol * p.contact_length);
      CHECK(std::abs((p.b + q.a) - D) < mirror_tol * p.contact_length);
      CHECK(std::abs(p.hysteretic_friction + q.hysteretic_friction) < mirror_tol);
    }
  }
  SUBCASE("flat punches: corner intensities exchange, all four singular with exponent -1/2") {
    // The former Gauss-Seidel reported (721.1, 44.8) and (175.5, 690.2), residual 0.0095, `ok`.
    const scene s{material{0.0, 1.0, 0.0, 0.0}, 1.0, {indentor{flat{0.004}, 100.0, 0.0}, indentor{flat{0.004}, 100.0, 0.0044}}};
    const auto r = solve(s);
    REQUIRE(r.diagnostics.code == status_code::ok);
    const auto& p = r.indentors[0];
    const auto& q = r.indentors[1];
    CHECK(p.residual < 1e-10);
    CHECK(std::abs(p.edges[0].intensity_factor / q.edges[1].intensity_factor - 1) < mirror_tol);
    CHECK(std::abs(p.edges[1].intensity_factor / q.edges[0].intensity_factor - 1) < mirror_tol);
    for (const auto& e : {p.edges[0], p.edges[1], q.edges[0], q.edges[1]}) {
      CHECK(e.exponent == doctest::Approx(-0.5).epsilon(1e-15));
      CHECK(e.intensity_factor > 0);
    }
    // The facing corners carry less than the outer ones (the neighbour lifts them).
    CHECK(p.edges[1].intensity_factor < p.edges[0].intensity_factor);
  }
}

TEST_CASE("rows of parabolas: mirror symmetry of an elastic row, few Newton iterations for a viscoelastic one") {
  // Six identical elastic frictionless parabolas 1.2 isolated lengths apart: the scene mirrored
  // about the row's centre is itself, so contact k and contact 5 - k are mirror images. Nothing in
  // the solver imposes it (the contacts are iterated with their loads imposed, then re-solved in
  // the bounded class).
  constexpr double mirror_tol = 1e-9;  // edges converged to 1e-11 L
  const material elastic{0.0, 1.0, 0.3, 0.0};
  const indentor one{parabolic{1.0}, 0.5, 0.0};
  const double L = solve_single(elastic, 1.0, one).contact_length;
  scene row{elastic, 1.0, {}};
  for (int k = 0; k < 6; ++k) row.indentors.push_back({one.shape, one.load, 1.2 * L * k});
  const auto r = solve(row);
  REQUIRE(r.diagnostics.code == status_code::ok);
  const double centre2 = 1.2 * L * 5;  // twice the centre
  for (int k = 0; k < 3; ++k) {
    CAPTURE(k);
    const auto& p = r.indentors[static_cast<std::size_t>(k)];
    const auto& q = r.indentors[static_cast<std::size_t>(5 - k)];
    CHECK(std::abs((p.a + q.b) - centre2) < mirror_tol * L);
    CHECK(std::abs((p.b + q.a) - centre2) < mirror_tol * L);
    CHECK(std::abs(p.load - q.load) < mirror_tol * p.load);
  }
  // The inner contacts are squeezed by both neighbours: shorter than the outer ones.
  CHECK(r.indentors[2].contact_length < r.indentors[0].contact_length);

  // Viscoelastic row of 10 (alpha 0.3) 1.5 lengths apart. Every load acts on every contact with
  // a far field decaying only like distance^(alpha - 1); iterated with the loads imposed, the
  // banded Jacobian stays accurate and Newton converges in 13 iterations (27 when the loads are
  // conditions of the iteration). Bound with a margin for other platforms' rounding.
  constexpr std::size_t row_iterations = 16;
  const material visco{0.3, 1.0, 0.3, 0.0};
  const double Lv = solve_single(visco, 1.0, one).contact_length;
  scene vrow{visco, 1.0, {}};
  for (int k = 0; k < 10; ++k) vrow.indentors.push_back({one.shape, one.load, 1.5 * Lv * k});
  const auto v = solve(vrow);
  REQUIRE(v.diagnostics.code == status_code::ok);
  CHECK(v.diagnostics.iterations <= row_iterations);
  for (const auto& c : v.indentors) CHECK(std::abs(c.load / one.load - 1) < 1e-9);
}

TEST_CASE("a row of 40 contacts (80 edges: Broyden's updates by the Woodbury identity) converges to its tolerance") {
  // Above 64 unknowns a Newton step solves with the last finite-difference Jacobian's factors and
  // Broyden's updates by the Woodbury identity (abel/broyden_matrix.hpp; its singular
  // updates are tested in tests/abel/test_broyden_matrix.cpp): a wrong step would stall the
  // iteration or stop it early. The residual of (8) of a converged row is at the tolerance's
  // level (measured 2.8e-13 at 1e-12); 100 times it is the bar.
  const material visco{0.3, 1.0, 0.3, 0.0};
  const indentor one{parabolic{1.0}, 0.5, 0.0};
  const double L = solve_single(visco, 1.0, one).contact_length;
  scene row{visco, 1.0, {}};
  for (int k = 0; k < 40; ++k) row.indentors.push_back({one.shape, one.load, 1.5 * L * k});
  solve_options o;
  const auto r = solve(row, o);
  REQUIRE(r.diagnostics.code == status_code::ok);
  CHECK(r.diagnostics.residual < 100 * o.tolerance);
  for (const auto& c : r.indentors) CHECK(std::abs(c.load / one.load - 1) < 1e-9);
}

TEST_CASE("viscoelastic sliding breaks the mirror symmetry") {
  const material m{0.3, 1.0, 0.3, 0.0};
  const auto r = solve(two(m, indentor{parabolic{1.0}, 0.1, 0.0}, indentor{parabolic{1.0}, 0.1, 1.5}));
  REQUIRE(r.diagnostics.code == status_code::ok);
  const auto& p = r.indentors[0];
  const auto& q = r.indentors[1];
  CHECK(std::abs((p.a + q.b) - 1.5) > 1e-3 * p.contact_length);
  CHECK(std::abs(p.contact_length - q.contact_length) > 1e-3 * p.contact_length);
}

TEST_CASE("the coupling decays like distance^(alpha - 1)") {
  // Far apart, the neighbour's action on a contact is ~ P D^(alpha - 1) (the kernel's far field),
  // so the contact's shift from its isolated position falls by 10^(alpha - 1) per decade of D.
  for (double alpha : {0.25, 0.6}) {
    CAPTURE(alpha);
    const material m{alpha, 1.0, 0.3, 0.0};
    const indentor lone{parabolic{1.0}, 0.1, 0.0};
    const auto single = solve_single(m, 1.0, lone);
    auto shift = [&](double D) {
      const auto r = solve(two(m, lone, indentor{parabolic{1.0}, 0.1, D}));
      REQUIRE(r.diagnostics.code == status_code::ok);
      return std::abs(r.indentors[0].b - single.b) + std::abs(r.indentors[0].a - single.a);
    };
    const double s1 = shift(100.0), s2 = shift(1000.0);
    CHECK(s2 < s1);
    CHECK(std::log10(s2 / s1) == doctest::Approx(alpha - 1).epsilon(0.05));
  }
}

TEST_CASE("contacts need not come in the order of their apexes") {
  // alpha = 0.75: a contact lies about a contact length ahead of its apex, so the blunt indentor's
  // contact (R = 10 at 0) lies AHEAD of the sharp one's (R = 1 at -1.5). Refused as overlapping
  // by the former solver, which ordered contacts by apex.
  const material m{0.75, 1.0, 0.3, 0.0};
  const auto r = solve(scene{m, 1.0, {indentor{parabolic{10.0}, 1.0, 0.0}, indentor{parabolic{1.0}, 1.0, -1.5}}});
  REQUIRE(r.diagnostics.code == status_code::ok);
  CHECK(r.indentors[0].b < r.indentors[1].a);
  CHECK(r.diagnostics.residual < 1e-10);
  for (const auto& c : r.indentors) CHECK(std::abs(c.load - 1) < 1e-10);
}

TEST_CASE("close contacts are solved, not refused") {
  // Two parabolas whose isolated contacts would overlap are started by load continuation. Gaps
  // of 0.1 and 0.01 of a contact length were refused ("the contacts ... overlap") before.
  const material m{0.3, 1.0, 0.3, 0.0};
  const indentor lone{parabolic{1.0}, 0.1, 0.0};
  const double L = solve_single(m, 1.0, lone).contact_length;
  for (double D : {0.95 * L, 0.9 * L}) {
    CAPTURE(D / L);
    const auto r = solve(two(m, lone, indentor{parabolic{1.0}, 0.1, D}));
    REQUIRE(r.diagnostics.code == status_code::ok);
    const double gap = r.indentors[1].a - r.indentors[0].b;
    CHECK(gap > 0);
    CHECK(gap < 0.5 * L);
    CHECK(r.diagnostics.residual < 1e-10);
  }
}

TEST_CASE("nearly touching contacts: the inexact Newton iteration ends on an evaluation at the tolerance") {
  // Two parabolas (alpha 0.3, R = 1, loads 0.3 pi/2 Gamma(1 - alpha)) whose coupled contacts are
  // ~1e-2 and ~1e-3 of a contact length apart (apex distances from study_multi_contact). Far
  // from the solution the conditions are evaluated only to 1e-3 of their size (at most 1e-5); the
  // result must still be the solution at the tolerance. Oracle: the same scene at a tolerance ten
  // times tighter (self-convergence; the reference's own error is <= 3e-11 L at these gaps,
  // studies/README.md), and the report's independent residual of (8).
  // The iteration count guards the re-evaluation of a point whose conditions came out below the
  // accuracy they were evaluated at (without it, alpha 0.7 at 1e-3 L stalled in every continuation
  // step: 212 iterations instead of 68).
  struct close_case {
    double alpha, D, gap;
  };
  constexpr double self_convergence_tol = 1e-10;  // of L: 100 x the tolerance, above the reference's error
  for (const close_case c : {close_case{0.3, 0.258122412302, 1e-2}, close_case{0.7, 0.00985230297261, 1e-3}}) {
    CAPTURE(c.alpha);
    if (c.gap < 1e-2 && punch_test::bem::sanitizer_build) continue;  // 1.6 s in Release, ~20 s under ASan
    const double load = 0.3 * pi / 2 * boost::math::tgamma(1 - c.alpha);
    const scene s = two(material{c.alpha, 1.0, 0.0, 0.0}, indentor{parabolic{1.0}, load, 0.0},
                        indentor{parabolic{1.0}, load, c.D});
    solve_options tight;
    tight.tolerance = 1e-13;
    const auto r = solve(s), ref = solve(s, tight);
    REQUIRE(r.diagnostics.code == status_code::ok);
    REQUIRE(ref.diagnostics.code == status_code::ok);
    const double L = std::min(r.indentors[0].contact_length, r.indentors[1].contact_length);
    const double gap = r.indentors[1].a - r.indentors[0].b;
    CHECK(gap > 0.5 * c.gap * L);
    CHECK(gap < 2 * c.gap * L);
    for (std::size_t i = 0; i < 2; ++i) {
      CHECK(std::abs(r.indentors[i].a - ref.indentors[i].a) < self_convergence_tol * L);
      CHECK(std::abs(r.indentors[i].b - ref.indentors[i].b) < self_convergence_tol * L);
    }
    CHECK(r.diagnostics.residual < 1e-10);
    CHECK(r.diagnostics.iterations < 100);
  }
}

TEST_CASE("nearly touching contacts: the boundary-layer basis agrees with the Jacobi series alone") {
  // Two parabolas (alpha 0.3, R = 1, loads 0.3 pi/2 Gamma(1 - alpha)) whose coupled contacts are
  // ~1.1e-3 of a contact length apart (apex distance from study_multi_contact). By default the
  // coupling correction is solved with poles beyond the facing ends (solve_options::layered_below
  // = 3e-3); layered_below = 0 solves it in the Jacobi series alone (degree ~400 here). The two
  // discretisations share the particular solutions and the Newton iteration, not the correction:
  // their contacts and C_f must agree to the edge tolerance, and each must pass its independent
  // residual.
  constexpr double route_tol = 1e-10;  // of L / of C_f: 100 x the tolerance (the series alone
                                       // reaches a residual of ~1e-11 at this gap)
  const double alpha = 0.3, D = 0.118494666741;
  if (punch_test::bem::sanitizer_build) return;  // the series alone: ~1.5 s in Release, ~30 s under ASan
  const double load = 0.3 * pi / 2 * boost::math::tgamma(1 - alpha);
  const scene s = two(material{alpha, 1.0, 0.0, 0.0}, indentor{parabolic{1.0}, load, 0.0}, indentor{parabolic{1.0}, load, D});
  solve_options series_only;
  series_only.layered_below = 0;
  const auto layered = solve(s), series = solve(s, series_only);
  REQUIRE(layered.diagnostics.code == status_code::ok);
  REQUIRE(series.diagnostics.code == status_code::ok);
  const double L = std::min(layered.indentors[0].contact_length, layered.indentors[1].contact_length);
  const double gap = layered.indentors[1].a - layered.indentors[0].b;
  CHECK(gap > 5e-4 * L);
  CHECK(gap < 2e-3 * L);
  for (std::size_t i = 0; i < 2; ++i) {
    CAPTURE(i);
    CHECK(std::abs(layered.indentors[i].a - series.indentors[i].a) < route_tol * L);
    CHECK(std::abs(layered.indentors[i].b - series.indentors[i].b) < route_tol * L);
    CHECK(std::abs(layered.indentors[i].hysteretic_friction - series.indentors[i].hysteretic_friction) < route_tol);
  }
  CHECK(layered.diagnostics.residual < 1e-12);
  CHECK(series.diagnostics.residual < 1e-10);
}

TEST_CASE("nearly touching elastic parabolas, a few 1e-6 of a contact length apart: solved and mirror-symmetric") {
  // Two identical parabolas at alpha = 0, beta = 0 (R = 1, loads 0.3 pi/2): the physics is
  // symmetric about the midpoint of the apexes, which the solver does not impose, so the edges
  // must be mirror images, a_0 + b_1 = D = b_0 + a_1. Apex distances 0.27 and 0.25 put the
  // coupled contacts ~8e-6 and ~3e-6 of a contact length apart (measured): the boundary-layer
  // route with its density projected onto Jacobi series of degree ~5000 and ~8000.
  constexpr double mirror_tol = 1e-10;  // of L: 100 x the tolerance (edges reach ~1e-15 measured)
  if (punch_test::bem::sanitizer_build) return;  // ~1-2 s each in Release
  for (const double D : {0.27, 0.25}) {
    CAPTURE(D);
    const double load = 0.3 * pi / 2;
    const scene s = two(material{0.0, 1.0, 0.0, 0.0}, indentor{parabolic{1.0}, load, 0.0}, indentor{parabolic{1.0}, load, D});
    const auto r = solve(s);
    REQUIRE(r.diagnostics.code == status_code::ok);
    const double L = std::min(r.indentors[0].contact_length, r.indentors[1].contact_length);
    const double gap = r.indentors[1].a - r.indentors[0].b;
    CAPTURE(gap / L);
    CHECK(gap > 1e-6 * L);
    CHECK(gap < 1e-5 * L);
    CHECK(std::abs(r.indentors[0].a + r.indentors[1].b - D) < mirror_tol * L);
    CHECK(std::abs(r.indentors[0].b + r.indentors[1].a - D) < mirror_tol * L);
    CHECK(std::abs(r.indentors[0].hysteretic_friction + r.indentors[1].hysteretic_friction) < mirror_tol);
    CHECK(r.diagnostics.residual < 1e-10);
  }
}

TEST_CASE("a result that is not ok is reported from a coarse projection of its boundary layers") {
  // Two identical elastic parabolas 0.2 apart (the scene of the mirror-symmetric test above, closer):
  // their contacts close to ~7e-7 L on the way to the full load (contacts_merge), and the coarse
  // solve of both at once sees them touch, so the merge stands. The layers' projection at the
  // acceptance would need degree ~2^15 and seconds a contact for the projection and the report; a
  // result that is not ok is projected at most to degree 1024 (coupled_solve.cpp, coarse_degree):
  // the whole solve then takes ~1.2 s in Release.
  if (punch_test::bem::sanitizer_build) return;  // ~1-4 s in Release
  const double load = 0.3 * pi / 2;
  const scene s = two(material{0.0, 1.0, 0.0, 0.0}, indentor{parabolic{1.0}, load, 0.0}, indentor{parabolic{1.0}, load, 0.2});
  const auto r = solve(s);
  CAPTURE(r.diagnostics.status);
  CHECK(r.diagnostics.code == status_code::contacts_merge);
  for (const auto& c : r.indentors) CHECK(c.degree <= 1024);
}

TEST_CASE("solve_options::layered_below is checked") {
  solve_options o;
  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    o.layered_below = bad;
    CHECK_THROWS_WITH_AS(solve(two(material{0.3, 1.0, 0.3, 0.0}, indentor{parabolic{1.0}, 0.1, 0.0},
                                   indentor{parabolic{1.0}, 0.1, 3.0}), o),
                         doctest::Contains("options.layered_below"), std::invalid_argument);
  }
}

TEST_CASE("solve_options::time_limit stops a coupled solve with not_converged and says so; interrupt throws") {
  const material m{0.3, 1.0, 0.3, 0.0};
  const indentor lone{parabolic{1.0}, 0.1, 0.0};
  const double L = solve_single(m, 1.0, lone).contact_length;
  const scene sc = two(m, lone, indentor{parabolic{1.0}, 0.1, 0.9 * L});
  solve_options o;
  o.time_limit = 1e-9;  // out of time before the first Newton step: the outcome is the machine's
  const auto r = solve(sc, o);
  CAPTURE(r.diagnostics.status);
  CHECK(r.diagnostics.code == status_code::not_converged);
  CHECK(r.diagnostics.status.find("stopped at the time limit of 1e-09 s") != std::string::npos);
  CHECK(r.diagnostics.status.find("solve_options") == std::string::npos);  // no C++ member for users
  o.time_limit = 0;  // no limit: the scene of "close contacts are solved, not refused"
  CHECK(solve(sc, o).diagnostics.code == status_code::ok);
  // One contact does not check the limit (milliseconds): ok.
  o.time_limit = 1e-9;
  CHECK(solve(scene{m, 1.0, {lone}}, o).diagnostics.code == status_code::ok);
  o.time_limit = -1;
  CHECK_THROWS_AS(solve(sc, o), std::invalid_argument);
  // solve_options::interrupt, polled at the same checks: punch::interrupted, polled no more once
  // it fired; never firing, the result unchanged; one contact never polls (milliseconds).
  o.time_limit = 0;
  std::size_t calls = 0;
  o.interrupt = [&calls] { return ++calls >= 3; };
  CHECK_THROWS_AS(solve(sc, o), interrupted);
  CHECK(calls == 3);
  calls = 0;
  o.interrupt = [&calls] { return ++calls == 0; };
  CHECK(solve(sc, o).diagnostics.code == status_code::ok);
  CHECK(calls > 0);
  o.interrupt = [] { return true; };
  CHECK(solve(scene{m, 1.0, {lone}}, o).diagnostics.code == status_code::ok);
}

TEST_CASE("a solution of the slope equations whose surface penetrates an indentor is never ok") {
  // Elastic, R = 10 at 0 and R = 1 at -1.5, loads 1: the isolated contacts overlap; the coupled
  // slope equations, edge conditions and loads are solved (residual ~4e-13), but the surface rises
  // through an indentor next to its contact: status penetration, not ok.
  const material m{0.0, 1.0, 0.3, 0.0};
  const auto r = solve(scene{m, 1.0, {indentor{parabolic{10.0}, 1.0, 0.0}, indentor{parabolic{1.0}, 1.0, -1.5}}});
  CHECK(r.diagnostics.residual < 1e-10);
  CHECK(r.diagnostics.code == status_code::penetration);
  CHECK(std::string(to_string(r.diagnostics.code)) == "penetration");
}

TEST_CASE("contacts that pass each other: the surface stays on the right side of both indentors") {
  // Apexes 0.5 apart, isolated contacts 1.3 long (the isolated contacts overlap): the first
  // contact lies wholly ahead of its apex, the second covers that apex, and the surface clears the
  // first indentor there. Checked on the displacement grid: gap = w - (f - f(a)) >= 0 outside each
  // contact (w is the surface height relative to the contact's leading edge).
  const material m{0.3, 1.0, 0.3, 0.0};
  solve_options o;
  o.grid_points = 201;
  const auto r = solve(two(m, indentor{parabolic{1.0}, 1.0, 0.0}, indentor{parabolic{1.0}, 1.0, 0.5}), o);
  REQUIRE(r.diagnostics.code == status_code::ok);
  const double apex[2] = {0.0, 0.5};
  for (int i = 0; i < 2; ++i) {
    const auto& c = r.indentors[static_cast<std::size_t>(i)];
    for (double p : c.pressure) CHECK(p >= 0);
    for (std::size_t k = 0; k < c.displacement_x.size(); ++k) {
      const double x = c.displacement_x[k];
      const double f = -((x - apex[i]) * (x - apex[i]) - (c.a - apex[i]) * (c.a - apex[i])) / 2;
      CHECK(c.displacement[k] - f >= -1e-9);
    }
  }
  CHECK(r.indentors[0].b < 0.0);  // wholly ahead of its apex
}

TEST_CASE("regression: close viscoelastic flat punches are never `ok` with tension or a large residual") {
  // The former block Gauss-Seidel stopped after one sweep (flat edges never move) and reported
  // `ok` with the pressure down to -12 ... -82 % of its peak and residuals up to 0.02. Under the
  // full-contact assumption of the flat punch class the trailing corner of the leading punch
  // carries a NEGATIVE intensity here (the punch behind lifts the surface): status tension.
  const material m{0.3, 1.0, 0.0, 0.0};
  const auto r = solve(two(m, indentor{flat{1.0}, 1.0, 0.0}, indentor{flat{1.0}, 1.0, 1.1}));
  CHECK(r.diagnostics.residual < 1e-10);
  CHECK(r.diagnostics.code != status_code::ok);
  CHECK(r.indentors[0].code == status_code::tension);
  CHECK(r.indentors[0].edges[1].intensity_factor < 0);
}

TEST_CASE("a status is ok only with evidence within the acceptance") {
  // The demo scene (parabola + wedge, coupled) is ok with its evidence...
  const material m{0.25, 5e6, 0.5, 0.3};
  const scene s{m, 0.01, {indentor{parabolic{0.01}, 500.0, 0.0}, indentor{wedge{0.02, 0.03}, 300.0, 0.015}}};
  const auto r = solve(s);
  REQUIRE(r.diagnostics.code == status_code::ok);
  for (const auto& c : r.indentors) {
    CHECK(c.residual <= solve_options{}.acceptance);
    CHECK(c.error_estimate <= solve_options{}.acceptance);
  }
  // ... and the same solve judged against an acceptance below its residual is not.
  solve_options strict;
  strict.acceptance = r.diagnostics.residual / 2;
  const auto q = solve(s, strict);
  CHECK(q.diagnostics.code == status_code::not_converged);
  // The status names the first indentor not ok with its own status, and how many are not ok.
  std::vector<std::size_t> bad;
  for (std::size_t i = 0; i < q.indentors.size(); ++i)
    if (q.indentors[i].code != status_code::ok) bad.push_back(i);
  REQUIRE(!bad.empty());
  CAPTURE(q.diagnostics.status);
  const std::string first = "see indentors[" + std::to_string(bad[0]) + "].status: " + q.indentors[bad[0]].status;
  CHECK(q.diagnostics.status.rfind(first, 0) == 0);
  CHECK((q.diagnostics.status.find(std::to_string(bad.size()) + " of 2 indentors are not ok") != std::string::npos) ==
        (bad.size() > 1));
}

TEST_CASE("indentors on one rigid body: the loads' split, the common approach, contact_lost, bad input") {
  // The split and the approaches are checked against the boundary-element oracle in
  // test_coupled_bem.cpp; here the relations that hold whatever the numbers.
  constexpr double level_tol = 1e-9;  // the acceptance: levels agree to it relative to max|f'| L
  SUBCASE("identical elastic parabolas at one height share the load equally (mirror symmetry)") {
    scene s = two(material{0.0, 1.0, 0.3, 0.0}, indentor{parabolic{1.0}, 1.0, 0.0}, indentor{parabolic{1.0}, 1.0, 3.0});
    s.body = rigid_body{1.0};
    const auto r = solve(s);
    REQUIRE(r.diagnostics.code == status_code::ok);
    CHECK(std::abs(r.indentors[0].load - 0.5) < level_tol);
    CHECK(std::abs(r.indentors[1].load - 0.5) < level_tol);
    REQUIRE(r.body_approach.has_value());
    CHECK(std::abs(*r.body_approach - r.indentors[1].approach) < level_tol);
  }
  SUBCASE("the per-indentor solve with the body's loads has the body's relative offsets") {
    const scene s = raised_pair();
    const auto r = solve(s);
    REQUIRE(r.diagnostics.code == status_code::ok);
    CHECK(r.indentors[1].load < r.indentors[0].load);
    CHECK(std::abs(r.indentors[0].load + r.indentors[1].load - 1.0) < level_tol);
    const double L = r.indentors[0].contact_length;  // max|f'| L = L^2/(2R) scale, R = 1
    CHECK(std::abs((r.indentors[0].approach + 0.0) - (r.indentors[1].approach + 0.05)) < level_tol * L * L);
    scene per = s;
    per.body.reset();
    per.indentors[0].load = r.indentors[0].load;
    per.indentors[1].load = r.indentors[1].load;
    const auto q = solve(per);
    REQUIRE(q.diagnostics.code == status_code::ok);
    CHECK(!q.body_approach.has_value());
    // The relative vertical offset of the two indentors (paper, end of section 3) is the height.
    CHECK(std::abs((q.indentors[0].approach - q.indentors[1].approach) - 0.05) < 1e-8);
    CHECK(std::abs(q.indentors[0].a - r.indentors[0].a) < 1e-8 * L);
  }
  SUBCASE("general profiles with and without their value give the parabolas' body solve") {
    // The levels of a body compare the profile at different contacts: a general profile's rise
    // from its `value` (a constant offset of which must not matter), else from its slope (exact
    // here: the slope is linear). A sign or offset error in either moves the split of the load.
    const scene s = raised_pair();
    const auto r = solve(s);
    REQUIRE(r.diagnostics.code == status_code::ok);
    const double L = r.indentors[0].contact_length;
    for (const bool with_value : {false, true}) {
      CAPTURE(with_value);
      scene g = s;
      for (auto& ind : g.indentors) {
        general_profile gp;
        gp.slope = [](double u) { return -u; };  // R = 1
        if (with_value) gp.value = [](double u) { return 7.0 - u * u / 2; };
        ind.shape = gp;
      }
      const auto q = solve(g);
      REQUIRE(q.diagnostics.code == status_code::ok);
      for (std::size_t k = 0; k < 2; ++k) {
        CHECK(std::abs(q.indentors[k].load - r.indentors[k].load) < level_tol);
        CHECK(std::abs(q.indentors[k].a - r.indentors[k].a) < 1e-8 * L);
        CHECK(std::abs(q.indentors[k].b - r.indentors[k].b) < 1e-8 * L);
      }
    }
  }
  SUBCASE("an indentor raised above the surface is contact_lost, never ok") {
    scene s = two(material{0.0, 1.0, 0.3, 0.0}, indentor{parabolic{1.0}, 1.0, 0.0}, indentor{parabolic{1.0}, 1.0, 3.0});
    s.indentors[1].height = 5.0;  // far above what a unit load presses into the surface
    s.body = rigid_body{1.0};
    const auto r = solve(s);
    CHECK(r.diagnostics.code == status_code::contact_lost);
    CHECK(r.diagnostics.status.find("indentors[1]") != std::string::npos);
  }
  SUBCASE("seven indentors (the coloured Jacobian with the loads' far monopoles) agree with the per-indentor solve") {
    // More than five smooth contacts on a body: the Jacobian is coloured and its far entries come
    // from body_far_model (coupled_newton.cpp). The per-indentor solve with the body's loads runs
    // another iteration (loads imposed, the relative intensities as conditions): its edges and
    // relative offsets must be the body's, and the loads must add up.
    const material m{0.3, 1.0, 0.3, 0.0};
    scene s{m, 1.0, {}};
    const double heights[] = {0.0, 0.004, -0.003, 0.002, 0.0, -0.002, 0.003};
    for (int k = 0; k < 7; ++k) {
      s.indentors.push_back(indentor{parabolic{k % 2 == 0 ? 1.0 : 1.5}, 1.0, 6.0 * k});
      s.indentors.back().height = heights[k];
    }
    s.body = rigid_body{1.0};
    solve_options o;
    o.grid_points = 2001;
    const auto r = solve(s, o);
    REQUIRE(r.diagnostics.code == status_code::ok);
    double total = 0;
    for (const auto& c : r.indentors) total += c.load;
    CHECK(std::abs(total - 1) < level_tol);
    {
      // Independent evidence (no rhabel code): the surface made by the reported pressure samples
      // alone, the density p/((pi/2) E_U) piecewise constant between them and integrated against
      // Psi by the boundary-element oracle's closed-form panels, has one level approach + height
      // at the middle of every contact. quadrature_tol: a density with square-root edges on 2000
      // intervals, ~(1/2000)^1.5 of the scale, times 10 (measured 9.2e-6).
      constexpr double quadrature_tol = 1e-4;  // relative to max|f'| L = L^2/(2R)
      const punch_test::bem::kernel K(0.3, 0.0);
      const double pressure_scale = pi / 2 * boost::math::tgamma(0.7) / (1 - 0.3 * 0.3);  // E1 = 1, U = 1, nu = 0.3
      std::vector<double> levels;
      for (std::size_t k = 0; k < 7; ++k) {
        const double x = (r.indentors[k].a + r.indentors[k].b) / 2, R = k % 2 == 0 ? 1.0 : 1.5, u = x - 6.0 * k;
        double w = 0;
        for (const auto& c : r.indentors)
          for (std::size_t q = 0; q + 1 < c.grid_x.size(); ++q)
            w += (c.pressure[q] + c.pressure[q + 1]) / 2 / pressure_scale * K.panel(c.grid_x[q], c.grid_x[q + 1], x);
        levels.push_back(K.gamma1 * w + u * u / (2 * R) + heights[k]);  // w - f_k + height_k
      }
      const double L0 = r.indentors[0].contact_length, scale = L0 * L0 / 2;
      double spread = 0;
      for (const double l : levels) spread = std::max(spread, std::abs(l - levels[0]));
      CHECK(spread < quadrature_tol * scale);
    }
    scene per = s;
    per.body.reset();
    for (std::size_t k = 0; k < 7; ++k) per.indentors[k].load = r.indentors[k].load;
    const auto q = solve(per);
    REQUIRE(q.diagnostics.code == status_code::ok);
    const double L = r.indentors[0].contact_length;
    for (std::size_t k = 0; k < 7; ++k) {
      CHECK(std::abs(q.indentors[k].a - r.indentors[k].a) < 1e-8 * L);
      CHECK(std::abs(q.indentors[k].b - r.indentors[k].b) < 1e-8 * L);
      // The relative vertical offsets of the per-indentor solve are the heights (paper, end of section 3).
      CHECK(std::abs((q.indentors[k].approach - q.indentors[0].approach) + (heights[k] - heights[0])) < 1e-8 * L * L);
    }
  }
  SUBCASE("the approach's quadratures agree where they meet (alpha = 1e-2 and alpha = 0)") {
    // The own contact's datum int g Psi(t, a) dt is one Gauss-Jacobi sum of weight
    // (1-x)^del (1+x)^(gam + alpha) from alpha = 1e-2 on, tanh-sinh in the offsets from the ends
    // below (surface.hpp): the two routes share no quadrature. Across the switch alpha moves by
    // 2e-9 relative, which moves the approaches by ~1e-11 of max|f'| L; the tanh-sinh route is
    // good to ~1e-12 and the Gauss-Jacobi one to eps/alpha ~ 2e-14.
    constexpr double routes_tol = 1e-9;  // relative to the approach's scale max|f'| L = L^2/(2R)
    auto approaches = [&](double alpha) {
      scene s = two(material{alpha, 1.0, 0.3, 0.0}, indentor{parabolic{1.0}, 1.0, 0.0}, indentor{parabolic{2.0}, 0.5, 3.0});
      const auto r = solve(s);
      REQUIRE(r.diagnostics.code == status_code::ok);
      return std::array<double, 3>{r.indentors[0].approach, r.indentors[1].approach, r.indentors[0].contact_length};
    };
    const auto below = approaches(1e-2 * (1 - 1e-9)), above = approaches(1e-2 * (1 + 1e-9));
    const double scale = above[2] * above[2] / 2;
    CHECK(std::abs(below[0] - above[0]) < routes_tol * scale);
    CHECK(std::abs(below[1] - above[1]) < routes_tol * scale);
    // At alpha = 0 the datum is -log(L/2) int g minus the closed-form moments of log(1 + x)
    // (surface.hpp, log_datum); at alpha = 1e-12 it is tanh-sinh again. The solutions differ by
    // ~1e-12 log^2 of the lengths; both routes are good to ~1e-12 (measured 3.9e-13 and 1.2e-12 of
    // the scale; the moments n >= 1 off by 1e-6 relative give 1.6e-9).
    const auto elastic = approaches(0.0), nearly = approaches(1e-12);
    CHECK(std::abs(elastic[0] - nearly[0]) < routes_tol * scale);
    CHECK(std::abs(elastic[1] - nearly[1]) < routes_tol * scale);
  }
  SUBCASE("bad input names the scene field") {
    scene s = two(material{0.0, 1.0, 0.3, 0.0}, indentor{parabolic{1.0}, 1.0, 0.0}, indentor{flat{1.0}, 1.0, 3.0});
    s.body = rigid_body{1.0};
    CHECK_THROWS_WITH_AS(solve(s), doctest::Contains("indentors[1].shape"), std::invalid_argument);
    s.indentors[1] = indentor{parabolic{1.0}, 1.0, 3.0};
    s.body = rigid_body{-1.0};
    CHECK_THROWS_WITH_AS(solve(s), doctest::Contains("body.load"), std::invalid_argument);
    s.body = rigid_body{1.0};
    s.indentors[0].height = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH_AS(solve(s), doctest::Contains("indentors[0].height"), std::invalid_argument);
  }
}

TEST_CASE("solve_options::threads: the Jacobian's columns on several threads give the same result, bit for bit") {
  // Each finite-difference column is a function of its index alone (parallel.hpp), so any thread
  // count must reproduce the serial run exactly: a data race or an order-dependent cache would
  // show here as a difference in the last bits (or under the sanitizers).
  auto same = [](const scene_result& p, const scene_result& q) {
    REQUIRE(p.indentors.size() == q.indentors.size());
    for (std::size_t i = 0; i < p.indentors.size(); ++i) {
      CHECK(p.indentors[i].a == q.indentors[i].a);
      CHECK(p.indentors[i].b == q.indentors[i].b);
      CHECK(p.indentors[i].load == q.indentors[i].load);
      CHECK(p.indentors[i].hysteretic_friction == q.indentors[i].hysteretic_friction);
    }
    CHECK(p.diagnostics.iterations == q.diagnostics.iterations);
  };
  solve_options serial, parallel;
  parallel.threads = 3;
  SUBCASE("three parabolas on one rigid body (the full Jacobian, 6 columns)") {
    scene s{material{0.3, 1.0, 0.3, 0.0}, 1.0,
            {indentor{parabolic{1.0}, 1.0, 0.0}, indentor{parabolic{2.0}, 1.0, 3.0}, indentor{parabolic{1.0}, 1.0, 6.0}}};
    s.indentors[2].height = 0.01;
    s.body = rigid_body{1.0};
    const auto p = solve(s, serial), q = solve(s, parallel);
    REQUIRE(p.diagnostics.code == status_code::ok);
    same(p, q);
    CHECK(*p.body_approach == *q.body_approach);
  }
  SUBCASE("a row of eight parabolas (the coloured Jacobian)") {
    scene s{material{0.3, 1.0, 0.3, 0.0}, 1.0, {}};
    for (int k = 0; k < 8; ++k) s.indentors.push_back(indentor{parabolic{1.0}, 0.3, 2.0 * k});
    const auto p = solve(s, serial), q = solve(s, parallel);
    REQUIRE(p.diagnostics.code == status_code::ok);
    same(p, q);
  }
  SUBCASE("more than 1024 threads is refused, naming the option") {
    scene s = two(material{0.3, 1.0, 0.3, 0.0}, indentor{parabolic{1.0}, 0.3, 0.0}, indentor{parabolic{1.0}, 0.3, 3.0});
    solve_options o;
    o.threads = 1025;
    CHECK_THROWS_WITH_AS(solve(s, o), doctest::Contains("options.threads"), std::invalid_argument);
  }
}
