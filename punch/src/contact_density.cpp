// Evaluation of the density of one contact (see detail/contact_density.hpp): the Jacobi series by
// rhabel::abel::jacobi_density, the apex enrichment by rhabel::abel::enriched_density.
#include "rhabel/punch/detail/contact_density.hpp"

#include "rhabel/quadrature/detail/jacobi_projection.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rhabel::punch::detail {

namespace {
// int_s^b of the Jacobi series, directly (no subtraction from the total): with X the reference
// abscissa of s, int_X^1 w P_0 = 2^(del+gam+1) B(del+1, gam+1) I_{(1-X)/2}(del+1, gam+1) and, for
// n >= 1, int_X^1 w P_n = (1/(2n)) (1-X)^(del+1) (1+X)^(gam+1) P_{n-1}^(del+1,gam+1)(X) (Rodrigues,
// DLMF 18.9.16; the sign is that of jacobi_density::integral_to reversed since int_-1^1 w P_n = 0).
double series_integral_from(const abel::jacobi_density<double>& j, double s) {
  const auto& c = j.coefficients;
  if (c.empty() || !(s < j.hi)) return 0;
  if (!(s > j.lo)) return j.integral();
  const double h = j.half_length(), gam = j.gam, del = j.del;
  const double one_plus_x = (s - j.lo) / h, one_minus_x = (j.hi - s) / h;
  const double x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
  const double scale = std::pow(2.0, del + gam + 1) * boost::math::beta(del + 1, gam + 1);
  const double part = one_minus_x <= one_plus_x ? boost::math::ibeta(del + 1, gam + 1, one_minus_x / 2)
                                                : 1 - boost::math::ibeta(gam + 1, del + 1, one_plus_x / 2);
  double total = c[0] * scale * part;
  if (c.size() > 1) {
    std::vector<double> shifted(c.size() - 1);
    for (std::size_t n = 1; n < c.size(); ++n) shifted[n - 1] = c[n] / (2 * static_cast<double>(n));
    total += std::pow(one_minus_x, del + 1) * std::pow(one_plus_x, gam + 1) *
             rhabel::quadrature::jacobi_clenshaw(shifted, del + 1, gam + 1, x);
  }
  return h * total;
}
// The layer part's int_a^s (toward_lo) or int_s^b, by abel's panel rule graded toward the poles
// beyond the end it starts from; the other end's weight rides in the integrand with its branch
// point at the distance from s to that end.
double layer_partial(const abel::layer_density<double>& layer, double s, bool toward_lo) {
  if (layer.empty()) return 0;
  const double h = layer.half_length();
  const double one_plus = (s - layer.lo) / h, one_minus = (layer.hi - s) / h;
  if (toward_lo) {
    const abel::panel_integrator<double> rule(0.0, layer.gam, 24);
    return h * rule.integrate(one_plus, layer.nearest_lo(), one_minus, [&](double u, double rest) {
      const double v = rest + one_minus;  // 1 - x
      return std::pow(v, layer.del) * layer.factor_at_distance(u, v);
    });
  }
  const abel::panel_integrator<double> rule(0.0, layer.del, 24);
  return h * rule.integrate(one_minus, layer.nearest_hi(), one_plus, [&](double v, double rest) {
    const double u = rest + one_plus;  // 1 + x
    return std::pow(u, layer.gam) * layer.factor_at_distance(u, v);
  });
}

}  // namespace

abel::enrichment_rule<double> contact_density::kink_rule(double beyond_lo, double beyond_hi) const {
  abel::enrichment_rule<double> out;
  for (const auto& term : kinks) {
    auto rule = abel::enrichment_nodes(term, beyond_lo, beyond_hi);
    out.one_plus_x.insert(out.one_plus_x.end(), rule.one_plus_x.begin(), rule.one_plus_x.end());
    out.one_minus_x.insert(out.one_minus_x.end(), rule.one_minus_x.begin(), rule.one_minus_x.end());
    out.value.insert(out.value.end(), rule.value.begin(), rule.value.end());
  }
  return out;
}

Eigen::VectorXd contact_density::kink_moments(const abel::far_field<double>& field) const {
  if (kinks.empty()) return Eigen::VectorXd::Zero(static_cast<Eigen::Index>(field.order()));
  const double inf = std::numeric_limits<double>::infinity();
  const auto rule = kink_rule(inf, inf);
  std::vector<double> x(rule.size());
  for (std::size_t j = 0; j < rule.size(); ++j) x[j] = rule.x(j);
  return field.interpolation(x).transpose() *
         Eigen::Map<const Eigen::VectorXd>(rule.value.data(), static_cast<Eigen::Index>(rule.size()));
}

void contact_density::set_interval(double lo, double hi) {
  // int C phi scales with the half-length (phi lives on the reference axis).
  if (length() > 0) {
    if (has_apex) apex_integral *= (hi - lo) / length();
    kinks_integral *= (hi - lo) / length();
  }
  jacobi.lo = apex.smooth.lo = layer.lo = lo;
  jacobi.hi = apex.smooth.hi = layer.hi = hi;
  for (auto& term : kinks) term.smooth.lo = lo, term.smooth.hi = hi;
}

void contact_density::scale(double factor) {
  for (auto& term : kinks) term.enrichment *= factor;
  kinks_integral *= factor;
  for (double& c : jacobi.coefficients) c *= factor;
  for (double& c : apex.smooth.coefficients) c *= factor;  // empty unless mapped
  apex.enrichment *= factor;
  apex_integral *= factor;
  for (double& c : layer.lo_coefficients) c *= factor;
  for (double& c : layer.hi_coefficients) c *= factor;
}

double contact_density::value(double t) const {
  if (line_load || !(t > a()) || !(t < b())) return 0;
  double regular = jacobi(t) + layer(t);
  for (const auto& term : kinks) regular += term(t);
  return has_apex ? regular + apex(t) : regular;
}

double contact_density::integral() const {
  if (line_load) return line_weight;
  const double regular = jacobi.integral() + layer.integral() + kinks_integral;
  return has_apex ? regular + apex_integral : regular;
}

double contact_density::integral_to(double s) const {
  if (line_load) return s > a() ? line_weight : 0;
  if (!(s > a())) return 0;
  if (!(s < b())) return integral();
  double regular = jacobi.integral_to(s) + layer_partial(layer, s, true);
  for (const auto& term : kinks) regular += term.integral_to(s);
  return has_apex ? regular + apex.integral_to(s) : regular;
}

double contact_density::integral_from(double s) const {
  if (line_load) return s <= a() ? line_weight : 0;
  if (!(s > a())) return integral();
  if (!(s < b())) return 0;
  double sum = series_integral_from(jacobi, s) + layer_partial(layer, s, false);
  // The enrichment's composite rule cut at s (integrate_between: pieces right of s only).
  if (has_apex) sum += apex.integral_from(s);
  for (const auto& term : kinks) sum += term.integral_from(s);
  return sum;
}

double contact_density::intensity(bool trailing) const {
  double K = trailing ? jacobi.intensity_trailing() : jacobi.intensity_leading();
  if (has_apex) K += trailing ? apex.intensity_trailing() : apex.intensity_leading();
  for (const auto& term : kinks) K += trailing ? term.intensity_trailing() : term.intensity_leading();
  if (!layer.empty()) {
    // The layer's factor at the edge, in jacobi_density's normalisation (2/L)^exponent 2^other.
    const double L = length();
    K += trailing ? std::pow(2 / L, layer.del) * std::pow(2.0, layer.gam) * layer.factor_at_distance(2, 0)
                  : std::pow(2 / L, layer.gam) * std::pow(2.0, layer.del) * layer.factor_at_distance(0, 2);
  }
  return K;
}

std::size_t contact_density::absorb_layer(double relative_accuracy, std::size_t max_degree) {
  if (layer.empty()) return 0;
  const double del = jacobi.del, gam = jacobi.gam;
  // The density's scale: the series' largest coefficient and the layer's factor at the ends and
  // at nine points between (not the pole weights, which a least-squares fit may leave large and
  // cancelling).
  double scale = 0;
  for (double c : jacobi.coefficients) scale = std::max(scale, std::abs(c));
  for (int k = 0; k <= 10; ++k) scale = std::max(scale, std::abs(layer.factor_at_distance(0.2 * k, 2 - 0.2 * k)));
  const auto zero = [](const std::vector<double>& a) { return std::all_of(a.begin(), a.end(), [](double c) { return c == 0; }); };
  if (!(scale > 0) || (zero(layer.lo_coefficients) && zero(layer.hi_coefficients))) {  // nothing to project
    layer = {};
    return 0;
  }
  const std::size_t poles = layer.lo_distances.size() + layer.hi_distances.size();
  const double target = std::max(relative_accuracy, 1e-16) * scale / static_cast<double>(poles);
  // log rho of a pole d beyond an end: its coefficients decay like rho^-n.
  const auto log_rho = [](double d) { return std::log1p(d + std::sqrt(d * (d + 2))); };
  double needed = 32;
  auto need = [&](const std::vector<double>& d, const std::vector<double>& a) {
    for (std::size_t k = 0; k < d.size(); ++k)
      if (std::abs(a[k]) > target) needed = std::max(needed, std::log(std::abs(a[k]) / target) / log_rho(d[k]));
  };
  need(layer.lo_distances, layer.lo_coefficients);
  need(layer.hi_distances, layer.hi_coefficients);
  const auto n = static_cast<std::size_t>(std::min(double(std::min(max_degree, max_absorbed_degree)), std::ceil(needed) + 16));
  // At the cap the projection misses the poles' coefficients beyond n: their size, relative to
  // the density's scale, joins the error estimate (never an ok status with a truncated layer).
  double missed = 0;
  auto miss = [&](const std::vector<double>& d, const std::vector<double>& a) {
    for (std::size_t k = 0; k < d.size(); ++k)
      missed = std::max(missed, std::abs(a[k]) * std::exp(-double(n) * log_rho(d[k])) / scale);
  };
  miss(layer.lo_distances, layer.lo_coefficients);
  miss(layer.hi_distances, layer.hi_coefficients);
  tail = std::max(tail, missed);
  const std::vector<double> before = jacobi.coefficients;
  // The factor from the rule's distances to the ends (poles within ~1e-6 of an end).
  const std::vector<double> c = rhabel::quadrature::jacobi_coefficients(
      [&](double, double one_plus_x, double one_minus_x) { return layer.factor_at_distance(one_plus_x, one_minus_x); },
      del, gam, n);
  auto& coefficients = jacobi.coefficients;
  if (coefficients.size() < n) coefficients.resize(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) coefficients[k] += c[k];
  // The projection's error, measured: the new series against the old one plus the poles at 64
  // Chebyshev points and, at each end with poles, at the end and at 4^-5, 4^-4, ... times the
  // nearest pole's distance from it (where the layer varies and a truncated series errs most),
  // relative to the density's scale; into `tail`.
  const rhabel::quadrature::jacobi_series<double> old_series(before, del, gam), new_series(coefficients, del, gam);
  double worst = 0;
  const auto compare = [&](double u, double v) {
    const double x = u <= v ? u - 1 : 1 - v;
    worst = std::max(worst, std::abs(new_series(x) - old_series(x) - layer.factor_at_distance(u, v)));
  };
  for (int k = 0; k < 64; ++k) {
    const double theta = boost::math::constants::pi<double>() * (k + 0.5) / 64;
    compare(1 + std::cos(theta), 1 - std::cos(theta));
  }
  if (!layer.lo_distances.empty()) {
    compare(0, 2);
    for (double d = layer.nearest_lo() / 1024; d < 1; d *= 4) compare(d, 2 - d);
  }
  if (!layer.hi_distances.empty()) {
    compare(2, 0);
    for (double d = layer.nearest_hi() / 1024; d < 1; d *= 4) compare(2 - d, d);
  }
  tail = std::max(tail, worst / scale);
  layer = {};
  return n;
}

}  // namespace rhabel::punch::detail
