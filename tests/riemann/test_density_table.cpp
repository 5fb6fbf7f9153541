// Issue #3 for the density: g(y) and int_a^y g of rhabel/riemann/abel_solver.hpp against the
// committed 45-digit table tests/data/riemann_density_reference.hpp (rhabel::abel, a different
// method, at 50 digits, accepted by this route at 50 digits to 1e-40; generator:
// tools/reference/riemann_density_reference.cpp). Smooth F on [-0.8, 1.3], every index class,
// alpha in {0, 0.2, 0.45, 0.5, 0.6, 0.8, 0.9}, beta in {0, 0.35, 0.9}, seven points from
// 1e-6 after a to 1e-6 before b. The double-precision spectral solver is compared in
// test_abel_solver.cpp; this table also serves where it is the weaker side (alpha = beta = 0.9).
#include <doctest/doctest.h>

#include "density_table_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

using namespace rhabel::riemann;

TEST_CASE("g(y), int_a^y g, int g against the 50-digit table: every class, alpha to 0.9, 1e-6 from the ends") {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double a = rhabel::riemann::test::density_table_a, b = rhabel::riemann::test::density_table_b, L = b - a;
  // int g, int_a^y g: issue #3 target, relative to |int g| (measured <= 133 eps)
  constexpr double integral_tolerance = 1e-13;
  // g(y), relative to max(|g(y)|, |int g|/L), d = min(y - a, b - y):
  //  * the route's law (abel_solver.hpp): the rounding of A~ is amplified by ~ (n/H)^alpha,
  //    H = d/3, so the error grows like (L/d)^alpha; measured <= 133 eps (L/d)^alpha;
  //  * issue #3 target 1e-13 where it is met: alpha <= 0.6 and d >= 0.3 (measured <= 50 eps;
  //    alpha = 0.8, 0.9 reach 260 and 550 eps there);
  //  * next to b in the classes bounded at b, the DOCUMENTED LIMIT: g -> 0 while A~ = O(1), and
  //    the first-row representation leaves its (b-t)^((beta-1)/2) component at rounding level:
  //    measured <= 12 eps (L/d)^(alpha + (1-beta)/2).
  constexpr double law_factor = 512;
  constexpr double density_target = 1e-13;
  constexpr double near_b_bounded_factor = 64;
  for (const auto& c : rhabel_test_data::riemann_density_cases) {
    CAPTURE(c.alpha);
    CAPTURE(c.beta);
    CAPTURE(c.cls);
    const bool bounded_at_b = (c.cls & 2) == 0;
    const auto sol = rhabel::riemann::test::solve_density_table_case(c);
    const double total = std::stod(c.total);
    CHECK(std::abs(sol.total().value - total) <= integral_tolerance * std::abs(total));
    for (int k = 0; k < 7; ++k) {
      const double y = c.y[k], g = std::stod(c.density[k]), G = std::stod(c.integral[k]);
      CAPTURE(y);
      CHECK(std::abs(sol.integral(y).value - G) <= integral_tolerance * std::abs(total));
      const double d = std::min(y - a, b - y);
      double tolerance = law_factor * eps * std::pow(L / d, c.alpha);
      if (c.alpha <= 0.6 && d >= 0.3) tolerance = std::min(tolerance, density_target);
      if (bounded_at_b && b - y < 1e-3)
        tolerance = near_b_bounded_factor * eps * std::pow(L / d, c.alpha + (1 - c.beta) / 2);
      CHECK(std::abs(sol.density(y).value - g) <= tolerance * std::max(std::abs(g), std::abs(total) / L));
    }
  }
}
