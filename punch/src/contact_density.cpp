// Evaluation of the density of one contact (see detail/contact_density.hpp): the Jacobi series by
// rhabel::abel::jacobi_density, the apex enrichment by rhabel::abel::enriched_density.
#include "rhabel/punch/detail/contact_density.hpp"

#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <boost/math/special_functions/beta.hpp>

#include <cmath>

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
}  // namespace

void contact_density::set_interval(double lo, double hi) {
  // int C phi scales with the half-length (phi lives on the reference axis).
  if (has_apex && length() > 0) apex_integral *= (hi - lo) / length();
  jacobi.lo = apex.smooth.lo = lo;
  jacobi.hi = apex.smooth.hi = hi;
}

void contact_density::scale(double factor) {
  for (double& c : jacobi.coefficients) c *= factor;
  for (double& c : apex.smooth.coefficients) c *= factor;  // empty unless mapped
  apex.enrichment *= factor;
  apex_integral *= factor;
}

double contact_density::value(double t) const {
  if (line_load || !(t > a()) || !(t < b())) return 0;
  const double regular = jacobi(t);
  return has_apex ? regular + apex(t) : regular;
}

double contact_density::integral() const {
  if (line_load) return line_weight;
  return has_apex ? jacobi.integral() + apex_integral : jacobi.integral();
}

double contact_density::integral_to(double s) const {
  if (line_load) return s > a() ? line_weight : 0;
  if (!(s > a())) return 0;
  if (!(s < b())) return integral();
  return has_apex ? jacobi.integral_to(s) + apex.integral_to(s) : jacobi.integral_to(s);
}

double contact_density::integral_from(double s) const {
  if (line_load) return s <= a() ? line_weight : 0;
  if (!(s > a())) return integral();
  if (!(s < b())) return 0;
  double sum = series_integral_from(jacobi, s);
  // The enrichment's composite rule cut at s (integrate_between: pieces right of s only).
  if (has_apex) sum += apex.integral_from(s);
  return sum;
}

}  // namespace rhabel::punch::detail
