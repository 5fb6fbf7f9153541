// Translation invariance of single contacts: a scene does not depend on where it sits on the x
// axis. The same indentor with its apex at 0, 1, 100 and 1e6 must give the same contact relative
// to the apex, the same load, C_f and pressure samples, wherever the contact spans at least 1e-3 of
// |apex|; below that, either the same result (exact) or a named non-ok status, never ok and
// different. The oracle is the scene at apex 0, where absolute and relative coordinates agree.
#include <doctest/doctest.h>

#include "rhabel/punch.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

using namespace rhabel::punch;

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
// The bound asked of the results: 1e-12 (~4500 eps) relative. The apex's own rounding in the
// reported abscissae (edges, grid) is ulp(apex)/L <= 1.1e-16 * 1e3 ~ 1e-13 of L where the contact
// spans >= 1e-3 |apex|; everything else is computed relative to the apex and should agree to a
// few eps.
constexpr double translation_tol = 1e-12;
// Where the bound applies: contact length >= this fraction of |apex|.
constexpr double resolved_fraction = 1e-3;
constexpr std::size_t samples = 9;

struct outcome {
  indentor_result r;
  bool ok;
};

outcome solve_at(const material& m, indentor ind, double apex) {
  ind.apex = apex;
  solve_options o;
  o.grid_points = samples;
  o.displacement = false;
  const scene_result s = solve(scene{m, 0.01, {ind}}, o);
  return {s.indentors.front(), s.diagnostics.code == status_code::ok};
}

double relative(double x, double y, double scale) { return std::abs(x - y) / scale; }

// The worst relative difference of `shifted` (apex at `apex`) from `origin` (apex at 0). Positions
// are reported in absolute coordinates, rounded to the doubles near the apex: a position counts as
// the same when it is within the rounding of apex + (its position at apex 0), 2 eps |apex|.
double worst_difference(const indentor_result& origin, const indentor_result& shifted, double apex) {
  // A line load has no length: its scale is the distance of its corner from the apex.
  const double length_scale = origin.contact_length > 0 ? origin.contact_length : std::abs(origin.a) + std::abs(origin.b);
  auto position = [&](double x_shifted, double x_origin) {
    return std::max(0.0, std::abs(x_shifted - apex - x_origin) - 2 * eps * apex) / length_scale;
  };
  double worst = 0;
  worst = std::max(worst, position(shifted.a, origin.a));
  worst = std::max(worst, position(shifted.b, origin.b));
  worst = std::max(worst, relative(shifted.load, origin.load, origin.load));
  worst = std::max(worst, relative(shifted.hysteretic_friction, origin.hysteretic_friction,
                                   std::max(std::abs(origin.hysteretic_friction), eps)));
  double peak = 0;
  for (double p : origin.pressure) peak = std::max(peak, std::abs(p));
  if (shifted.pressure.size() != origin.pressure.size()) return std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < origin.pressure.size(); ++k) {
    worst = std::max(worst, relative(shifted.pressure[k], origin.pressure[k], peak > 0 ? peak : 1.0));
    worst = std::max(worst, position(shifted.grid_x[k], origin.grid_x[k]));
  }
  return worst;
}

void check_translations(const material& m, const indentor& ind) {
  const outcome origin = solve_at(m, ind, 0.0);
  REQUIRE(origin.ok);
  for (const double apex : {1.0, 100.0, 1e6}) {
    CAPTURE(apex);
    const outcome shifted = solve_at(m, ind, apex);
    const double difference = worst_difference(origin.r, shifted.r, apex);
    CAPTURE(difference);
    CAPTURE(shifted.r.status);
    if (origin.r.contact_length >= resolved_fraction * apex) {
      CHECK(shifted.ok);
      CHECK(difference <= translation_tol);
    } else {
      // Below the resolved fraction: never ok and wrong.
      CHECK((!shifted.ok || difference <= translation_tol));
    }
  }
}

material rubber(double alpha, double coulomb) {
  material m;
  m.alpha = alpha;
  m.E1 = 5e6;
  m.poisson = 0.3;  // beta > 0 when coulomb > 0
  m.coulomb = coulomb;
  return m;
}
}  // namespace

TEST_CASE("single contacts are invariant under translation of the apex (0, 1, 100, 1e6)") {
  // Contacts from ~1e-10 m (the wedges at loads 1e-3 and 0.01: issue 14's case, a wedge contact
  // of 1.9e-9 m at apex 100 that lost 3.3e-6 of its load and 1.6e-4 of C_f with status ok) to
  // ~2 m (the wide flat punch): resolved at every apex, at some, or at none.
  for (const double alpha : {0.25, 0.6}) {
    for (const double coulomb : {0.0, 0.3}) {
      CAPTURE(alpha);
      CAPTURE(coulomb);
      const material m = rubber(alpha, coulomb);
      for (const double load : {100.0, 1e5}) {
        CAPTURE(load);
        check_translations(m, indentor{parabolic{0.01}, load, 0.0});
      }
      for (const double load : {1e-3, 0.01, 300.0}) {
        CAPTURE(load);
        check_translations(m, indentor{wedge{0.02, 0.03}, load, 0.0});
      }
      for (const double width : {0.004, 2.0}) {
        CAPTURE(width);
        check_translations(m, indentor{flat{width}, 100.0, 0.0});
      }
    }
  }
}
