// The density of one contact with a boundary-layer part (punch/detail/contact_density.hpp: the
// poles of abel::solve_union_layered that the coupled solve carries while it iterates on nearly
// touching contacts): its value, integrals and edge intensity with the layer, and the projection of
// the layer onto the Jacobi series (absorb_layer) that the report sees.
//
// Oracles, none of them the code under test: the layer written out here from its definition
// w(x) sum_k a_k d_k/(d_k + 1 -+ x); integrals by Boost's tanh-sinh quadrature of the values
// (double exponential: it takes the edges' power singularities); the intensity from the
// definition lim g(t) |t - edge|^(-exponent) evaluated in closed form.
#include <doctest/doctest.h>

#include "rhabel/punch/detail/contact_density.hpp"

#include <boost/math/quadrature/tanh_sinh.hpp>

#include <cmath>
#include <limits>
#include <vector>

namespace {
using rhabel::punch::detail::contact_density;

constexpr double eps = std::numeric_limits<double>::epsilon();

/// A contact on [-0.3, 1.7] in the class bounded at the leading edge, singular at the trailing
/// one (gam = 0.35, del = -0.65: alpha = 0.3, nu = 0), a short series and poles beyond both ends,
/// the nearest 5e-3 of the half-length beyond the trailing edge (a gap of ~5e-3 L).
contact_density layered_contact() {
  contact_density g;
  g.jacobi.lo = -0.3;
  g.jacobi.hi = 1.7;
  g.jacobi.gam = 0.35;
  g.jacobi.del = -0.65;
  g.jacobi.coefficients = {0.8, -0.1, 0.05};
  g.nu = 0;
  g.layer.lo = g.jacobi.lo;
  g.layer.hi = g.jacobi.hi;
  g.layer.gam = g.jacobi.gam;
  g.layer.del = g.jacobi.del;
  g.layer.lo_distances = {0.1};
  g.layer.lo_coefficients = {0.2};
  g.layer.hi_distances = {5e-3, 0.05, 0.5};
  g.layer.hi_coefficients = {0.1, -0.2, 0.3};
  return g;
}

/// The layer's factor sum_k a_k d_k/(d_k + 1 -+ x) of layered_contact() from its definition, at
/// 1 + x = u/h and 1 - x = v/h.
double layer_factor_by_definition(const contact_density& g, double u, double v) {
  const double h = (g.b() - g.a()) / 2;
  double factor = 0;
  for (std::size_t k = 0; k < g.layer.lo_distances.size(); ++k)
    factor += g.layer.lo_coefficients[k] * g.layer.lo_distances[k] / (g.layer.lo_distances[k] + u / h);
  for (std::size_t k = 0; k < g.layer.hi_distances.size(); ++k)
    factor += g.layer.hi_coefficients[k] * g.layer.hi_distances[k] / (g.layer.hi_distances[k] + v / h);
  return factor;
}

/// The density of layered_contact() from its definition at the distances u = t - a, v = b - t;
/// with_series false: the layer alone.
double density_by_definition(const contact_density& g, double u, double v, bool with_series = true) {
  const double h = (g.b() - g.a()) / 2;
  const double x = u <= v ? u / h - 1 : 1 - v / h;
  const double factor = (with_series ? g.jacobi.series(x) : 0.0) + layer_factor_by_definition(g, u, v);
  return std::pow(v / h, g.jacobi.del) * std::pow(u / h, g.jacobi.gam) * factor;
}

/// int_lo^hi g by tanh-sinh in the distance to the nearer end on each half of the contact, so
/// that the edges' singularities sit at an end of the variable (no rounding of t next to b).
double tanh_sinh(const contact_density& g, double lo, double hi) {
  boost::math::quadrature::tanh_sinh<double> rule;
  const double L = g.length(), mid = g.a() + L / 2;
  double sum = 0;
  if (lo < mid)  // u = t - a from lo - a to min(hi, mid) - a
    sum += rule.integrate([&](double u) { return density_by_definition(g, u, L - u); }, lo - g.a(),
                          std::min(hi, mid) - g.a(), std::sqrt(eps));
  if (hi > mid)  // v = b - t from b - hi to b - max(lo, mid)
    sum += rule.integrate([&](double v) { return density_by_definition(g, L - v, v); }, g.b() - hi,
                          g.b() - std::max(lo, mid), std::sqrt(eps));
  return sum;
}
}  // namespace

TEST_CASE("a contact density with a boundary layer: values, integrals, intensity") {
  const contact_density g = layered_contact();
  contact_density series_only = g;
  series_only.layer = {};
  // Values: the series plus the layer as defined, down to 1e-9 of the half-length from the
  // trailing edge (inside the nearest pole's layer); 1000 eps of the value (powers of small
  // distances, the factor's sum).
  for (double t : {-0.29, 0.1, 0.9, 1.6, 1.69, 1.7 - 1e-5, 1.7 - 1e-9}) {
    CAPTURE(t);
    const double expected = series_only.value(t) + density_by_definition(g, t - g.a(), g.b() - t, false);
    CHECK(std::abs(g.value(t) - expected) <= 1000 * eps * std::abs(expected));
  }
  // Integrals against tanh-sinh of the values (its own error ~1e-13 here): 1e-11 relative.
  constexpr double integral_tol = 1e-11;
  const double total = tanh_sinh(g, g.a(), g.b());
  CHECK(std::abs(g.integral() - total) <= integral_tol * std::abs(total));
  for (double s : {0.2, 1.5, 1.7 - 1e-3}) {
    CAPTURE(s);
    const double to = tanh_sinh(g, g.a(), s), from = tanh_sinh(g, s, g.b());
    CHECK(std::abs(g.integral_to(s) - to) <= integral_tol * std::abs(total));
    CHECK(std::abs(g.integral_from(s) - from) <= integral_tol * std::abs(total));
  }
  // The trailing intensity (del < 0): lim g(t) (b - t)^(-del) = (2/L)^del 2^gam (S(1) + Phi(1)),
  // S the series and Phi the layer's factor at the edge, where every trailing pole gives its
  // coefficient and a leading pole d gives d/(d + 2).
  const double L = g.length();
  const double S1 = g.jacobi.series(1.0);
  const double Phi1 = 0.2 * 0.1 / (0.1 + 2) + 0.1 - 0.2 + 0.3;
  const double K = std::pow(2 / L, g.jacobi.del) * std::pow(2.0, g.jacobi.gam) * (S1 + Phi1);
  CHECK(std::abs(g.intensity(true) - K) <= 100 * eps * std::abs(K));
}

TEST_CASE("absorb_layer: the layer projected onto the Jacobi series keeps the density") {
  contact_density g = layered_contact();
  const contact_density before = g;
  const std::size_t n = g.absorb_layer(1e-13);
  CHECK(g.layer.empty());
  // The pole 5e-3 beyond the edge: rho - 1 ~ 0.1, so ~300 terms for 1e-13 (and the 16 added).
  CHECK(n > 200);
  CHECK(n < 600);
  // The density, away from the trailing edge where the factor (1 - x)^del grows: 1e-11 of the
  // largest value sampled (the projection's target 1e-13 of the scale, times the Lebesgue-like
  // growth of a truncated Jacobi series).
  double scale = 0;
  for (int k = 1; k < 100; ++k) scale = std::max(scale, std::abs(before.value(-0.3 + 0.02 * k)));
  for (int k = 1; k < 100; ++k) {
    const double t = -0.3 + 0.02 * k;
    CAPTURE(t);
    CHECK(std::abs(g.value(t) - before.value(t)) <= 1e-11 * scale);
  }
  CHECK(std::abs(g.integral() - before.integral()) <= 1e-12 * std::abs(before.integral()));
  CHECK(std::abs(g.intensity(true) - before.intensity(true)) <= 1e-11 * std::abs(before.intensity(true)));
  // Nothing left to absorb; a zero layer is dropped without a projection.
  CHECK(g.absorb_layer(1e-13) == 0);
  contact_density zero = layered_contact();
  for (double& c : zero.layer.lo_coefficients) c = 0;
  for (double& c : zero.layer.hi_coefficients) c = 0;
  CHECK(zero.absorb_layer(1e-13) == 0);
  CHECK(zero.layer.empty());
}

TEST_CASE("absorb_layer: its error estimate covers what the projection leaves out") {
  // The projection's error in the factor, against the poles written from their definition at 2000
  // points uniform in x and 40 more within 1e-3 of each end, relative to the scale absorb_layer
  // documents (the largest series coefficient, the layer's factor at 11 points). tail must cover
  // it: it is measured at other points (Chebyshev and a ladder at the ends), hence the factor 4.
  const contact_density before = layered_contact();
  double scale = 0;
  for (double c : before.jacobi.coefficients) scale = std::max(scale, std::abs(c));
  const double h = before.length() / 2;
  for (int k = 0; k <= 10; ++k) scale = std::max(scale, std::abs(layer_factor_by_definition(before, 0.2 * k * h, (2 - 0.2 * k) * h)));
  for (const double accuracy : {1e-13, 1e-8}) {
    contact_density g = before;
    g.absorb_layer(accuracy);
    CAPTURE(accuracy);
    double actual = 0;
    auto at = [&](double u, double v) {  // reference distances to the ends
      const double x = u <= v ? u - 1 : 1 - v;
      const double difference = g.jacobi.series(x) - before.jacobi.series(x) - layer_factor_by_definition(before, u * h, v * h);
      actual = std::max(actual, std::abs(difference) / scale);
    };
    for (int k = 1; k < 2000; ++k) at(2.0 * k / 2000, 2 - 2.0 * k / 2000);
    for (int k = 0; k < 40; ++k) {
      const double d = 1e-3 * std::pow(0.7, k);
      at(d, 2 - d);
      at(2 - d, d);
    }
    CAPTURE(actual);
    CAPTURE(g.tail);
    CHECK(actual <= 4 * g.tail);
    // ... and is of the size asked for (the projection's target over the poles' count, times the
    // growth of a truncated series toward a singular end).
    CHECK(g.tail <= 100 * accuracy);
  }
}
