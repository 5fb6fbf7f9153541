// punch/src/fields.cpp: what is sampled or read off a solved density: edge intensities, the
// peak pressure, the Riemann-Hilbert pressure samples, the kernel Psi of the surface displacement.
// The surface class itself is in surface.hpp. See internal.hpp for the layout of punch/src.
#include "internal.hpp"

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"
#include "rhabel/riemann/abel_solver.hpp"

#include <Eigen/Dense>
#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rhabel::punch::detail {

// K = lim g (distance to the edge)^-exponent at the leading or trailing edge, with g's exponents
// (contact_density::exponents). The series' and the apex part's intensities add up, except at the
// edge next to the apex of the split form (contact_density::physical): there both parts carry the
// singular exponent of the class nu = 0 and cancel, and K is that of the next term, from g at
// distances delta = 1e-3 d, d/2, d/4 (d = the apex's distance to that edge, the scale on which g
// varies there): g/delta^exponent = K + K1 delta + K2 delta^2 + ..., Richardson-extrapolated twice
// (truncation ~ (delta/d)^3 ~ 1e-9, the cancellation ~ eps d/delta ~ 1e-12: an estimate).
double edge_intensity(const contact_density& g, bool trailing) {
  const double parts = g.intensity(trailing);
  if (!g.physical || g.jacobi.coefficients.empty()) return parts;
  const double h = g.jacobi.half_length(), x_apex = g.apex.apex_reference();
  const double d = trailing ? 1 - x_apex : 1 + x_apex;  // reference units
  if (trailing ? !(g.jacobi.del < 0) : !(g.jacobi.gam < 0)) return parts;  // the far edge
  const double exponent = trailing ? g.physical->del : g.physical->gam;
  auto ratio = [&](double delta) {
    const double near = delta, far = 2 - delta;
    const double value = trailing ? g.jacobi.value_at_distance(far * h, near * h) + g.apex.value_at_distance(far, near)
                                  : g.jacobi.value_at_distance(near * h, far * h) + g.apex.value_at_distance(near, far);
    return value / std::pow(near * h, exponent);
  };
  const double delta = 1e-3 * d;
  const double r1 = ratio(delta), r2 = ratio(delta / 2), r4 = ratio(delta / 4);
  const double e12 = 2 * r2 - r1, e24 = 2 * r4 - r2;
  return (4 * e24 - e12) / 3;
}

// Non-const: Boost 1.74 defines tanh_sinh::integrate(f, a, b) without the const of its declaration.
boost::math::quadrature::tanh_sinh<double>& tanh_sinh_rule() {
  thread_local boost::math::quadrature::tanh_sinh<double> rule;
  return rule;
}

// Pressure samples of an isolated wedge from its Riemann-Hilbert solution g_1 on the unit interval
// [lo, hi] = [-eps, 1 - eps], apex at 0 (wedge_by_rh): p(t) = scale g_1((t - apex)/L), scale =
// (pi/2) E_U L^-alpha. g_1 costs ~50-130 us per point of these near-edge wedges even from
// abel_rh_solution::densities (13-115 us per point on 1000-point grids with the apex 0.5 .. 0.01 L from an edge,
// riemann/abel_solver.hpp; A~
// interpolated once; most of it the far part next to the apex), so 1000 samples come from a
// piecewise Chebyshev interpolant of g_1 built from one densities call at its ~100-200 nodes.
// Structure of g_1 (the class nu = -1 with F constant next to either edge, docs/theory.md sections 3-5):
// (t - lo)^gam times an analytic function next to lo, (hi - t)^del times one next to hi, and
// |t|^-alpha A(t) + B(t) (log|t| A + B at alpha = 0) with A, B analytic on either side of the apex.
// Panels: [lo, lo/2] carrying (t - lo)^gam, [hi/2, hi] carrying (hi - t)^del, and [lo/2, 0],
// [0, hi/2] graded geometrically (ratio 1/2) towards the apex; each panel sees its nearest
// singularity at a distance >= its length (Bernstein ratio >= 3 + sqrt 8), so 16 first-kind
// points resolve g_1 to ~1e-13 of the panel's scale (measured: 2e-14 .. 7e-14 of the peak against
// the pointwise density, tests/punch/test_wedge.cpp, study_wedge_near_edge). Samples nearer to the
// apex than the innermost panel take g_1 directly, and so do the samples of a side of the apex that
// has fewer of them than interpolation nodes; the apex itself gets +inf (|t - apex|^-alpha, log at
// alpha = 0).
// Returns the largest error estimate of the g_1 values used (densities' two orders), relative to
// max g_1.
namespace {
double rh_pressure(const rh_wedge& wedge, double gam, double del, double L, const std::vector<double>& x,
                   std::vector<double>& p) {
  const riemann::abel_rh_solution<double>& unit = *wedge.unit;
  const double lo = -wedge.eps, hi = wedge.one_minus_eps, apex = wedge.apex, scale = wedge.scale;
  constexpr std::size_t points = 16;
  struct panel {
    double u, v;
    int weight;  // -1: (t - lo)^gam, +1: (hi - t)^del, 0: none
    std::vector<double> c;  // Chebyshev coefficients on [u, v]
  };
  // Unit abscissae of the samples. The graded panels stop at 2^-6 of the segment (or half the
  // nearest sample's distance from the apex): the few samples nearer to the apex are taken
  // directly, which is cheaper than the 16 nodes of each further panel (g_1 costs most next to
  // the apex, where densities() grades its far part deeply towards the log singularity of A~).
  std::vector<double> u(x.size());
  double nearest_left = -lo, nearest_right = hi;
  for (std::size_t k = 0; k < u.size(); ++k) {
    u[k] = (x[k] - apex) / L;
    if (u[k] < 0) nearest_left = std::min(nearest_left, -u[k]);
    if (u[k] > 0) nearest_right = std::min(nearest_right, u[k]);
  }
  std::vector<panel> left{{lo, lo / 2, -1, {}}};
  for (double e = lo / 2; -e / 2 >= std::max(nearest_left / 2, -lo * 0x1p-6); e /= 2) left.push_back({e, e / 2, 0, {}});
  std::vector<panel> right;
  for (double e = hi / 2; e / 2 >= std::max(nearest_right / 2, hi * 0x1p-6); e /= 2) right.push_back({e / 2, e, 0, {}});
  std::reverse(right.begin(), right.end());  // increasing abscissae, as in left
  right.push_back({hi / 2, hi, 1, {}});
  // A side with fewer samples than interpolation nodes (the short side of an apex next to an
  // edge; any side of a small grid) takes its samples directly: a sample costs as much as a node.
  const auto on_left = static_cast<std::size_t>(std::count_if(u.begin(), u.end(), [](double t) { return t < 0; }));
  const bool interpolate_left = on_left > left.size() * points;
  const bool interpolate_right = u.size() - on_left > right.size() * points;
  // Abscissae served by the interpolant: (lo, covered_left) and (covered_right, hi).
  const double covered_left = interpolate_left ? left.back().v : lo;
  const double covered_right = interpolate_right ? right.front().u : hi;
  std::vector<panel> panels;
  if (interpolate_left) panels = left;
  if (interpolate_right) panels.insert(panels.end(), right.begin(), right.end());
  // Nodes of every panel (abel's first-kind grid, offsets from the nearer end), then the samples
  // outside the panels, in one densities call.
  const abel::chebyshev_grid<double> grid(points);
  std::vector<double> nodes;
  for (const auto& p : panels) {
    const double half = (p.v - p.u) / 2;
    for (std::size_t j = 0; j < points; ++j)
      nodes.push_back(grid.one_plus_x[j] <= grid.one_minus_x[j] ? p.u + half * grid.one_plus_x[j] : p.v - half * grid.one_minus_x[j]);
  }
  std::vector<std::size_t> direct;
  for (std::size_t k = 0; k < u.size(); ++k) {
    if (u[k] == 0) {
      p[k] = std::numeric_limits<double>::infinity();
    } else if (u[k] > lo && u[k] < hi && u[k] >= covered_left && u[k] <= covered_right) {
      direct.push_back(k);
      nodes.push_back(u[k]);
    }
  }
  const auto g = unit.densities(nodes);
  double largest = 0, estimate = 0;
  for (const auto& v : g) {
    largest = std::max(largest, std::abs(v.value));
    estimate = std::max(estimate, v.error_estimate);
  }
  auto weight = [&](const panel& p, double t) {
    return p.weight < 0 ? std::pow(t - lo, gam) : (p.weight > 0 ? std::pow(hi - t, del) : 1.0);
  };
  std::vector<double> values(points);
  for (std::size_t i = 0; i < panels.size(); ++i) {
    for (std::size_t j = 0; j < points; ++j) values[j] = g[i * points + j].value / weight(panels[i], nodes[i * points + j]);
    panels[i].c = abel::chebyshev_coefficients(values);
  }
  for (std::size_t j = 0; j < direct.size(); ++j) p[direct[j]] = scale * g[panels.size() * points + j].value;
  for (std::size_t k = 0; k < u.size(); ++k) {
    const double t = u[k];
    if (!(t > lo && t < hi) || (t >= covered_left && t <= covered_right)) continue;
    const auto it = std::upper_bound(panels.begin(), panels.end(), t, [](double x, const panel& p) { return x < p.v; });
    if (it == panels.end()) continue;
    const double y = ((t - it->u) - (it->v - t)) / (it->v - it->u);
    p[k] = scale * weight(*it, t) * riemann::detail::chebyshev_fit<double>::clenshaw(it->c, y);
  }
  return largest > 0 ? estimate / largest : estimate;
}
}  // namespace

std::vector<double> pressure_grid(double a, double b, std::size_t n, sample_spacing spacing) {
  std::vector<double> t(n);
  const double L = b - a, pi = boost::math::constants::pi<double>();
  for (std::size_t k = 0; k < n; ++k) {
    const double cell = (static_cast<double>(k) + 0.5) / static_cast<double>(n);
    if (spacing == sample_spacing::uniform) {
      t[k] = a + L * cell;
    } else {
      // (1 - cos(pi c))/2 = sin^2(pi c/2), from the nearer end without cancellation.
      const double near = std::sin(pi * std::min(cell, 1 - cell) / 2);
      t[k] = cell <= 0.5 ? a + L * near * near : b - L * near * near;
    }
  }
  return t;
}

std::vector<double> even_grid(double lo, double hi, std::size_t n) {
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k)
    x[k] = n == 1 ? (lo + hi) / 2 : lo + (hi - lo) * static_cast<double>(k) / static_cast<double>(n - 1);
  return x;
}

// g.value(t) at every sample through one abel::enriched_evaluator, in one values() call (the
// series' recurrence coefficients once, the series of four samples summed together, the weight
// w = (1-x)^del (1+x)^gam once per sample): without a map the density whose series is g.jacobi
// and whose enrichment is g.apex's; mapped (apex near an edge) g.apex itself, whose series lives
// in the mapped variable, plus g.jacobi's c_0; the knots' terms added one by one. An isolated
// wedge with a Riemann-Hilbert solution
// takes its samples from it (rh_pressure).
double sample_pressure(const pressure_field::source& field, const std::vector<double>& t, std::vector<double>& p) {
  const contact_density& g = field.g;
  p.assign(t.size(), 0.0);
  if (field.rh) return rh_pressure(*field.rh, g.jacobi.gam, g.jacobi.del, g.length(), t, p);
  if (g.line_load) return 0.0;
  const bool mapped = g.has_apex && g.apex.mobius != 0;
  abel::enriched_density<double> whole = g.apex;
  if (!mapped) whole.smooth = g.jacobi;
  if (!g.has_apex) whole.enrichment = 0;
  const abel::enriched_evaluator<double> density(whole);
  const double h = g.jacobi.half_length();
  std::vector<std::size_t> inside;  // samples strictly inside the contact, evaluated in one batch
  std::vector<double> one_plus, one_minus;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!(t[k] > g.a()) || !(t[k] < g.b())) continue;
    inside.push_back(k);
    one_plus.push_back((t[k] - g.jacobi.lo) / h);
    one_minus.push_back((g.jacobi.hi - t[k]) / h);
  }
  std::vector<double> values(inside.size());
  density.values(one_plus.data(), one_minus.data(), values.data(), inside.size());
  for (std::size_t j = 0; j < inside.size(); ++j) {
    const double x = t[inside[j]];
    double value = values[j];
    if (mapped) value += g.jacobi.value_at_distance(x - g.jacobi.lo, g.jacobi.hi - x);
    for (const auto& term : g.kinks) value += term.value_at_distance(one_plus[j], one_minus[j]);
    p[inside[j]] = field.scale * value;
  }
  return 0.0;
}

}  // namespace rhabel::punch::detail

namespace rhabel::punch {

std::vector<double> pressure_field::operator()(const std::vector<double>& x) const {
  if (!source_) throw std::logic_error("rhabel::punch::pressure_field: empty (a field comes from a solve)");
  std::vector<double> t(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (!std::isfinite(x[k]))
      throw std::invalid_argument("rhabel::punch::pressure_field: x[" + std::to_string(k) + "] is not finite");
    t[k] = x[k] - origin_;
  }
  std::vector<double> p;
  detail::sample_pressure(*source_, t, p);
  return p;
}

}  // namespace rhabel::punch

namespace rhabel::punch::detail {

// Peak pressure on [a, b] of a bounded density: sampling + Brent refinement.
std::pair<double, double> peak_of(const contact_density& g) {
  const int n = 128;
  double best = -1, where = g.jacobi.lo;
  for (int k = 0; k <= n; ++k) {
    const double t = g.jacobi.lo + g.length() * (k + 0.5) / (n + 1);
    const double v = g.value(t);
    if (v > best) {
      best = v;
      where = t;
    }
  }
  const double h = g.length() / (n + 1);
  const auto r = boost::math::tools::brent_find_minima([&](double t) { return -g.value(t); },
                                                       std::max(g.jacobi.lo, where - h), std::min(g.jacobi.hi, where + h), 40);
  if (-r.second > best) return {-r.second, r.first};
  return {best, where};
}

// Surface height h(x) - h(a_ref) from the slope field Gamma(1-alpha) A g (s), integrated in closed
// form in s first: int_{a_ref}^x K(t, s) ds = Psi(t, x) - Psi(t, a_ref), with
//   Psi(t, s) = -((t - s)^alpha - 1)/alpha                              (s < t)
//   Psi(t, s) = -kappa ((s - t)^alpha - 1)/alpha + (1 - kappa)/alpha      (s > t),
// continuous at s = t and finite as alpha -> 0 (the log kernel of the elastic half-plane).
double psi(double t, double s, double alpha, double one_minus_kappa_over_alpha, double kappa);
double psi_distance(double d, double alpha, double one_minus_kappa_over_alpha, double kappa);
double psi(double t, double s, double alpha, double one_minus_kappa_over_alpha, double kappa) {
  return psi_distance(s - t, alpha, one_minus_kappa_over_alpha, kappa);
}
// Psi as a function of d = s - t (exact when the caller knows the distance).
double psi_distance(double d, double alpha, double one_minus_kappa_over_alpha, double kappa) {
  const double t = 0, s = d;
  auto em = [alpha](double r) {  // (r^alpha - 1)/alpha, stable for small alpha
    const double l = std::log(r);
    return alpha == 0 ? l : std::expm1(alpha * l) / alpha;
  };
  if (s < t) return -em(t - s);
  if (s > t) return -kappa * em(s - t) + one_minus_kappa_over_alpha;
  // d = 0: both sides tend to 1/alpha (a line load's own point; line loads exist only for
  // alpha + beta/2 >= 1/2, so alpha > 0 there): the continuous value keeps a line load's
  // displacement samples relative to its documented reference point, the load point.
  return alpha > 0 ? 1 / alpha : 0.0;
}



}  // namespace rhabel::punch::detail
