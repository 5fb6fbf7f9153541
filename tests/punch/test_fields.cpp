// Tests of the fields a solve reports besides its numbers: the pressure as a function
// (indentor_result::pressure_at), the graded pressure grid (sample_spacing::graded) and the
// surface of several contacts on one grid (scene_result::surface). Oracles: Hertz's closed form
// (elastic line contact), each shape's closed-form profile f (the surface equals f + approach on
// a contact), and the identity with the samples of the same solve.
#include <doctest/doctest.h>

#include "rhabel/punch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

using namespace rhabel::punch;

namespace {
constexpr double pi = 3.141592653589793238462643383279502884;
constexpr double eps = std::numeric_limits<double>::epsilon();
// Hertz's pressure against the Jacobi series of the elastic parabola (class nu = -1, degree ~2):
// the contact half-width comes from a root finder polished to 1e-12 (solve_options::tolerance),
// which moves p by ~1e-12 of the peak; sqrt(a^2 - x^2) loses a few more ulps next to the edges.
constexpr double hertz_tol = 1e4 * eps;

double largest(const std::vector<double>& v) {
  double m = 0;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}

double worst_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double w = 0;
  for (std::size_t k = 0; k < a.size(); ++k) w = std::max(w, std::abs(a[k] - b[k]));
  return w;
}

std::vector<double> even_points(double a, double b, std::size_t n) {
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k) x[k] = a + (b - a) * static_cast<double>(k) / static_cast<double>(n - 1);
  return x;
}
}  // namespace

TEST_CASE("pressure_at: Hertz's elastic line contact at points of one's own, 0 outside the contact") {
  // alpha = 0, k = 0: p(x) = (2P/(pi c^2)) sqrt(c^2 - (x - x0)^2), c the half-width (Johnson 5.2).
  const material m{0.0, 1.0, 0.0, 0.0};
  const double R = 1.0, P = 1e-3;
  const auto r = solve_single(m, 1.0, indentor{parabolic{R}, P, 0.5});
  const double c = r.contact_length / 2, x0 = (r.a + r.b) / 2, p0 = 2 * P / (pi * c);
  std::vector<double> xs = even_points(r.a - c, r.b + c, 301);
  xs.push_back(r.a + 1e-9 * c);  // next to the edges: p ~ sqrt of the distance
  xs.push_back(r.b - 1e-9 * c);
  const std::vector<double> p = r.pressure_at(xs);
  REQUIRE(p.size() == xs.size());
  double worst = 0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const double d = xs[k] - x0;
    const double hertz = std::abs(d) < c ? 2 * P / (pi * c * c) * std::sqrt((c - d) * (c + d)) : 0.0;
    worst = std::max(worst, std::abs(p[k] - hertz));
  }
  CAPTURE(worst / p0);
  CHECK(worst < hertz_tol * p0);
  CHECK(r.pressure_at({r.a - 1e-9 * c, r.b + 1e-9 * c, r.a - 1, r.b + 1}) == std::vector<double>{0, 0, 0, 0});
}

TEST_CASE("pressure_at equals the pressure samples: parabola, wedge, wedge by the Riemann-Hilbert route, uniform and graded") {
  const material m{0.3, 1.0, 0.3, 0.5};
  solve_options o;
  o.grid_points = 257;
  o.displacement = false;
  struct item {
    indentor ind;
    bool split;
  };
  for (const item& it : {item{{parabolic{1.0}, 1.0, 0.0}, true}, item{{wedge{0.1, 0.3}, 1.0, 0.0}, true},
                         item{{wedge{0.1, 10.0}, 1.0, 0.0}, false}}) {
    for (const sample_spacing spacing : {sample_spacing::uniform, sample_spacing::graded}) {
      o.spacing = spacing;
      o.wedge_apex_split = it.split;
      const auto r = solve_single(m, 1.0, it.ind, o);
      REQUIRE(r.pressure.size() == o.grid_points);
      CAPTURE(it.split);
      CAPTURE(static_cast<int>(spacing));
      CAPTURE(worst_difference(r.pressure_at(r.grid_x), r.pressure) / largest(r.pressure));
      // The same evaluation at the same abscissae (the solve is at the origin: no shift).
      CHECK(r.pressure_at(r.grid_x) == r.pressure);
    }
  }
}

TEST_CASE("pressure_at of contacts far from the origin: the samples to the rounding of the shift") {
  // The solve works relative to the first apex (1e6 L away from 0): x -> x - origin rounds by
  // ~eps 1e6 L, which moves p by that times |p'| <~ p0 / (distance to the edge) at the samples.
  const material m{0.4, 1.0, 0.5, 0.0};
  const double far = 1e6;
  scene s{m, 1.0, {indentor{parabolic{1.0}, 1.0, far}, indentor{parabolic{1.0}, 0.5, far + 2.0}}};
  solve_options o;
  o.grid_points = 101;
  const auto r = solve(s, o);
  REQUIRE(r.diagnostics.code == status_code::ok);
  for (const auto& c : r.indentors) {
    const double nearest = c.contact_length / 200;  // the first uniform sample's distance to an edge
    const double shift_rounding = eps * far;
    CHECK(worst_difference(c.pressure_at(c.grid_x), c.pressure) <
          16 * shift_rounding / nearest * largest(c.pressure));
  }
}

TEST_CASE("pressure_at refuses a non-finite abscissa; an empty field refuses to evaluate") {
  const auto r = solve_single(material{0.3, 1.0, 0.3, 0.0}, 1.0, indentor{parabolic{1.0}, 1.0, 0.0});
  CHECK_THROWS_AS(r.pressure_at({0.0, std::numeric_limits<double>::quiet_NaN()}), std::invalid_argument);
  CHECK_THROWS_AS(r.pressure_at({std::numeric_limits<double>::infinity()}), std::invalid_argument);
  CHECK(static_cast<bool>(r.pressure_at));
  const pressure_field empty;
  CHECK(!empty);
  CHECK_THROWS_AS(empty({0.0}), std::logic_error);
}

TEST_CASE("graded samples: Chebyshev points, the first at L sin^2(pi/(4n)) from the edge, where p follows the edge law") {
  const material m{0.4, 1.0, 0.3, 0.5};
  solve_options o;
  o.grid_points = 400;
  o.displacement = false;
  o.spacing = sample_spacing::graded;
  const auto r = solve_single(m, 1.0, indentor{parabolic{1.0}, 1.0, 0.0}, o);
  const double L = r.contact_length, n = 400;
  CHECK(std::is_sorted(r.grid_x.begin(), r.grid_x.end()));
  const double first = r.grid_x.front() - r.a, last = r.b - r.grid_x.back();
  const double expected = L * std::pow(std::sin(pi / (4 * n)), 2);
  CHECK(std::abs(first - expected) < 1e3 * eps * L);  // a - x rounds to eps L; sin^2 is exact
  CHECK(std::abs(last - expected) < 1e3 * eps * L);
  // p ~ K d^e at both ends (edge_report), the next term O(d/L) ~ 4e-6 relative.
  const auto& lead = r.edges.front();
  const auto& trail = r.edges.back();
  CHECK(std::abs(r.pressure.front() / (lead.intensity_factor * std::pow(first, lead.exponent)) - 1) < 1e-4);
  CHECK(std::abs(r.pressure.back() / (trail.intensity_factor * std::pow(last, trail.exponent)) - 1) < 1e-4);
}

TEST_CASE("the surface of several contacts on one grid: the profile plus the approach on each contact, clear outside") {
  // Two parabolas (alpha 0.3, k 0.3) 0.2 contact lengths apart, and a wedge beside them: on
  // contact i the surface is f_i(x) + approach_i (f_i(apex) = 0, the closed-form profile), and
  // off the contacts the surface is above every indentor (no penetration).
  const material m{0.3, 1.0, 0.3, 0.3};
  scene s{m, 1.0,
          {indentor{parabolic{1.0}, 1.0, 0.0}, indentor{parabolic{0.5}, 0.5, 1.6}, indentor{wedge{0.2, 0.2}, 0.3, 3.5}}};
  solve_options o;
  o.grid_points = 200;
  const auto r = solve(s, o);
  REQUIRE(r.diagnostics.code == status_code::ok);
  REQUIRE(r.surface.size() == 600);
  REQUIRE(r.surface_x.size() == 600);
  CHECK(std::is_sorted(r.surface_x.begin(), r.surface_x.end()));
  auto profile = [&](std::size_t i, double x) {
    const auto& ind = s.indentors[i];
    if (const auto* p = std::get_if<parabolic>(&ind.shape)) return -(x - ind.apex) * (x - ind.apex) / (2 * p->radius);
    const auto& w = std::get<wedge>(ind.shape);
    return x < ind.apex ? -w.slope_leading * (ind.apex - x) : -w.slope_trailing * (x - ind.apex);
  };
  const double scale = largest(r.surface);
  std::size_t inside = 0;
  double worst_inside = 0, lowest_clearance = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < r.surface_x.size(); ++k) {
    const double x = r.surface_x[k];
    for (std::size_t i = 0; i < s.indentors.size(); ++i) {
      const auto& c = r.indentors[i];
      const double rigid = profile(i, x) + c.approach;
      if (x > c.a && x < c.b) {
        ++inside;
        worst_inside = std::max(worst_inside, std::abs(r.surface[k] - rigid));
      } else if (x > c.a - c.contact_length && x < c.b + c.contact_length) {
        lowest_clearance = std::min(lowest_clearance, r.surface[k] - rigid);
      }
    }
  }
  CHECK(inside > 100);
  CAPTURE(worst_inside / scale);
  CHECK(worst_inside < 1e-9 * scale);  // the profile itself in contact (surface.hpp's in_contact)
  CHECK(lowest_clearance > -1e-9 * scale);
  // Without several contacts, or without the displacement, there is no surface.
  o.displacement = false;
  CHECK(solve(s, o).surface.empty());
  o.displacement = true;
  CHECK(solve_single(m, 1.0, s.indentors[0], o).displacement.size() == 200);
  CHECK(solve(scene{m, 1.0, {s.indentors[0]}}, o).surface.empty());
}
