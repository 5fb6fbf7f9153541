// The singular apex part of the wedge density (see detail/contact_density.hpp, apex_part).
// Integrals use composite Gauss-Legendre on panels graded geometrically towards every point
// where the integrand is singular or non-smooth (hp quadrature: the error falls geometrically
// with the number of layers for integrable power and logarithmic singularities).
#include "rhabel/punch/detail/contact_density.hpp"

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace rhabel::punch::detail {

namespace {
constexpr double pi = boost::math::constants::pi<double>();

// 12-point Gauss-Legendre on [-1, 1] (nodes and weights to 17 digits).
constexpr std::array<double, 6> gl_x = {0.1252334085114689154724414, 0.3678314989981801937526915,
                                        0.5873179542866174472967024, 0.7699026741943046870368938,
                                        0.9041172563704748566784659, 0.9815606342467192506905491};
constexpr std::array<double, 6> gl_w = {0.2491470458134027850005624, 0.2334925365383548087608499,
                                        0.2031674267230659217490645, 0.1600783285433462263346525,
                                        0.1069393259953184309602547, 0.0471753363865118271946160};

// int_lo^hi f with panels graded geometrically (ratio 0.15, `layers` per side) towards both ends.
// f(x, dx0, dy) receives x - x0 and x - y computed exactly from the panel's end offset when that end
// is x0 or y: grading to 1e-24 is meaningless in absolute coordinates next to x0 = 0.2.
template <class F>
double graded(F&& f, double lo, double hi, double x0, double y, int layers) {
  if (!(hi > lo)) return 0;
  auto eval = [&](bool left, double off) {
    const double base = left ? lo : hi, signed_off = left ? off : -off;
    const double x = base + signed_off;
    const double dx0 = base == x0 ? signed_off : x - x0;
    const double dy = base == y ? signed_off : x - y;
    return f(x, dx0, dy);
  };
  auto panel = [&](bool left, double o_in, double o_out) {
    const double c = (o_in + o_out) / 2, h = (o_out - o_in) / 2;
    double s = 0;
    for (std::size_t i = 0; i < gl_x.size(); ++i) s += gl_w[i] * (eval(left, c - h * gl_x[i]) + eval(left, c + h * gl_x[i]));
    return s * h;
  };
  double s = 0;
  double outer = (hi - lo) / 2;
  for (int k = 0; k < layers; ++k) {
    const double inner = outer * 0.15;
    s += panel(true, inner, outer) + panel(false, inner, outer);
    outer = inner;
  }
  return s + panel(true, 0, outer) + panel(false, 0, outer);
}

// (r^a - 1)/a, stable for small a, = log r at a = 0.
double powm1_over(double r, double a) {
  const double l = std::log(r);
  return a == 0 ? l : std::expm1(a * l) / a;
}
}  // namespace

namespace {
double chi_of(double dx0, double r) {
  // chi = (1 - u^2)^4, u = (dx0/r)^2: 1 - chi = O(dx0^4) at the apex, so (1 - chi) psi is C^3 there,
  // and chi is C^3 at |dx0| = r. Flatter-topped bumps ((1 - u^3)^4, (1 - u^6)^8) were tried: their
  // larger derivatives delay convergence more than the extra flatness gains below degree 512.
  const double t = dx0 / r;
  const double u = t * t;
  if (!(u < 1)) return 0;
  const double v = 1 - u * u;
  const double v2 = v * v;
  return v2 * v2;
}
}  // namespace

double apex_part::chi(double x) const { return chi_of(x - x0, r); }

double apex_part::psi(double x) const { return psi_of(x - x0); }

// e(r) = (r^-alpha - 1)/alpha = -powm1_over(r, -alpha).
double apex_part::psi_of(double dx0) const {
  if (dx0 > 0) return -kappa * powm1_over(dx0, -alpha) - one_minus_kappa_over_alpha;
  return -powm1_over(-dx0, -alpha);
}

double apex_part::h_of(double dx0) const { return chi_of(dx0, r) * psi_of(dx0); }

double apex_part::jump() const {
  if (alpha == 0) return -pi * pi - one_minus_kappa_over_alpha * one_minus_kappa_over_alpha;
  const double s = std::sin(pi * alpha / 2);
  return -pi * (one_minus_kappa_over_alpha * one_minus_kappa_over_alpha * alpha + 4 * kappa * s * s / alpha) /
         std::sin(pi * alpha);
}

double apex_part::integral(double lo, double hi) const {
  lo = std::max(lo, x0 - r);
  hi = std::min(hi, x0 + r);
  if (!(hi > lo)) return 0;
  const int layers = static_cast<int>(std::ceil(18 / (1 - alpha))) + 2;
  auto f = [this](double, double dx0, double) { return h_of(dx0); };
  const double nowhere = std::numeric_limits<double>::quiet_NaN();
  if (lo < x0 && x0 < hi) return graded(f, lo, x0, x0, nowhere, layers) + graded(f, x0, hi, x0, nowhere, layers);
  return graded(f, lo, hi, x0, nowhere, layers);
}

double apex_part::apply(double y) const {
  const double u = x0 - r, v = x0 + r;
  const int layers = static_cast<int>(std::ceil(18 / (1 - alpha))) + 2;
  auto kernel = [&](double dy) { return dy > 0 ? std::pow(dy, alpha - 1) : -kappa * std::pow(-dy, alpha - 1); };
  if (!(y > u && y < v)) {
    auto f = [&](double, double dx0, double dy) { return h_of(dx0) * kernel(dy); };
    return graded(f, u, x0, x0, y, layers) + graded(f, x0, v, x0, y, layers);
  }
  // y inside the support: subtract h(y) so that the kernel's singularity is removed
  // ((h(x) - h(y)) K(x, y) = O(|x - y|^alpha)), and add h(y) int_u^v K(x, y) dx in closed form:
  //   [(v - y)^alpha - kappa (y - u)^alpha]/alpha
  //     = ((v-y)^alpha - 1)/alpha - kappa ((y-u)^alpha - 1)/alpha + (1 - kappa)/alpha.
  const double hy = h_of(y - x0);
  auto f = [&](double, double dx0, double dy) { return (h_of(dx0) - hy) * kernel(dy); };
  const double lo = std::min(x0, y), hi = std::max(x0, y);
  const double body = graded(f, u, lo, x0, y, layers) + graded(f, lo, hi, x0, y, layers) + graded(f, hi, v, x0, y, layers);
  const double local = powm1_over(v - y, alpha) - kappa * powm1_over(y - u, alpha) + one_minus_kappa_over_alpha;
  return body + hy * local;
}

}  // namespace rhabel::punch::detail
