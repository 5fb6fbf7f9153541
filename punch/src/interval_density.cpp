// Evaluation of the spectral density of one contact interval (see detail/interval_density.hpp).
#include "rhabel/punch/detail/interval_density.hpp"

#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <boost/math/special_functions/beta.hpp>

#include <cmath>

namespace rhabel::punch::detail {

double interval_density::smooth_factor(double x) const {
  if (c.empty()) return 0;
  return quadrature::jacobi_clenshaw(c, e.del, e.gam, x);
}

double interval_density::value(double t) const {
  if (line_load || !(t > a) || !(t < b)) return 0;
  const double L = length();
  // Distances to both ends computed directly, not through x, so that the weight keeps full
  // relative accuracy next to the edges.
  const double one_plus_x = 2 * (t - a) / L, one_minus_x = 2 * (b - t) / L;
  const double x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
  const double regular = std::pow(one_minus_x, e.del) * std::pow(one_plus_x, e.gam) * smooth_factor(x);
  return has_apex ? regular + apex.sigma * apex.h(x) : regular;
}

double interval_density::integral() const {
  if (line_load) return line_weight;
  if (c.empty()) return 0;
  // int_{-1}^{1} (1-x)^del (1+x)^gam dx = 2^(del+gam+1) B(del+1, gam+1); P_n, n >= 1, integrate to 0.
  const double L = length();
  const double regular = L / 2 * c[0] * std::pow(2.0, e.del + e.gam + 1) * boost::math::beta(e.del + 1, e.gam + 1);
  return has_apex ? regular + L / 2 * apex.sigma * apex.integral(-1, 1) : regular;
}

double interval_density::integral_from(double s) const {
  if (line_load) return s <= a ? line_weight : 0;
  if (s <= a) return integral();
  if (s >= b || c.empty()) return 0;
  const double L = length();
  const double one_plus_x = 2 * (s - a) / L, one_minus_x = 2 * (b - s) / L;
  const double x0 = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
  // n = 0: 2^(del+gam+1) B(del+1, gam+1) I_{(1-x0)/2}(del+1, gam+1).
  double sum = c[0] * std::pow(2.0, e.del + e.gam + 1) * boost::math::beta(e.del + 1, e.gam + 1, one_minus_x / 2);
  // n >= 1 (Rodrigues, DLMF 18.9.16): int_{x0}^1 w P_n^(del,gam) =
  //     (1/(2n)) (1-x0)^(del+1) (1+x0)^(gam+1) P_{n-1}^(del+1,gam+1)(x0).
  if (c.size() > 1) {
    std::vector<double> shifted(c.size() - 1);
    for (std::size_t n = 1; n < c.size(); ++n) shifted[n - 1] = c[n] / (2.0 * static_cast<double>(n));
    sum += std::pow(one_minus_x, e.del + 1) * std::pow(one_plus_x, e.gam + 1) *
           quadrature::jacobi_clenshaw(shifted, e.del + 1, e.gam + 1, x0);
  }
  if (has_apex) sum += apex.sigma * apex.integral(x0, 1);
  return L / 2 * sum;
}

}  // namespace rhabel::punch::detail
