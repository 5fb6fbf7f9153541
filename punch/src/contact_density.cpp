// Evaluation of the density of one contact (see detail/contact_density.hpp): the Jacobi series is
// evaluated by rhabel::abel::jacobi_density, the apex part by detail::apex_part.
#include "rhabel/punch/detail/contact_density.hpp"

#include <cmath>

namespace rhabel::punch::detail {

double contact_density::value(double t) const {
  if (line_load || !(t > a()) || !(t < b())) return 0;
  const double regular = jacobi(t);
  if (!has_apex) return regular;
  const double L = length();
  // x - x0 from the distances to the ends (full relative accuracy next to the edges).
  const double one_plus_x = 2 * (t - a()) / L, one_minus_x = 2 * (b() - t) / L;
  const double x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
  return regular + apex.sigma * apex.h(x);
}

double contact_density::integral() const {
  if (line_load) return line_weight;
  const double regular = jacobi.integral();
  return has_apex ? regular + length() / 2 * apex.sigma * apex.integral(-1, 1) : regular;
}

double contact_density::integral_from(double s) const {
  if (line_load) return s <= a() ? line_weight : 0;
  if (s <= a()) return integral();
  if (s >= b() || jacobi.coefficients.empty()) return 0;
  double sum = jacobi.integral() - jacobi.integral_to(s);
  if (has_apex) {
    const double L = length();
    const double one_plus_x = 2 * (s - a()) / L, one_minus_x = 2 * (b() - s) / L;
    const double x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
    sum += L / 2 * apex.sigma * apex.integral(x, 1);
  }
  return sum;
}

}  // namespace rhabel::punch::detail
