// study_wedge_table: the sliding wedge on a power-law viscoelastic half-space, tabulated against
// the material exponent alpha (CSV on stdout). Accuracy against solve time: study_scene_timing.
//
// Table 1 ("table"): S1 = S2 = 0.1 and S2/S1 = 3, k = 0 and k = 0.5 (nu = 0.3), unit load per
// length, E_U = 1 (E1 = (1 - nu^2)/Gamma(1 - alpha), U = 1). Columns: alpha, beta, kappa, regime,
// S2/S1, eps = (apex - a)/L, L, L_scaled = L (S1 E_U / load)^(1/(1-alpha)) (dimensionless, depends
// only on alpha, beta and S2/S1: int p is proportional to S1 E_U L^(1-alpha)), C_f/S1,
// error_estimate (of the density; an estimate), degree.
//   eps and L are exact to rounding (incomplete-beta inversion and the closed-form load); C_f below
//   the boundary from the enriched density (apex >= 0.1 L from the edges) or the Riemann-Hilbert
//   route (nearer), see rhabel/punch/contact.hpp; error_estimate is the solver's.
// Usage: study_wedge_table [> wedge_table.csv]
#include "rhabel/punch.hpp"

#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace rhabel::punch;

namespace {
material unit_material(double alpha, double k) {
  const double nu = 0.3;
  return material{alpha, (1 - nu * nu) / boost::math::tgamma(1 - alpha), nu, k};
}
}  // namespace

int main() {
  std::printf("# table\nalpha,beta,kappa,regime,S2_over_S1,eps,L,L_scaled,Cf_over_S1,error_estimate,degree\n");
  std::vector<double> alphas;
  for (int i = 0; i <= 19; ++i) alphas.push_back(0.05 * i);
  alphas.push_back(0.99);
  for (double k : {0.0, 0.5}) {
    for (double ratio : {1.0, 3.0}) {
      for (double alpha : alphas) {
        const material m = unit_material(alpha, k);
        const double S1 = 0.1;
        const auto r = solve_single(m, 1.0, indentor{wedge{S1, S1 * ratio}, 1.0, 0.0});
        const double scaled = r.contact_length * std::pow(S1, 1 / (1 - alpha));  // E_U = 1, load = 1
        std::printf("%.2f,%.10f,%.10f,%s,%g,%.15g,%.15g,%.15g,%.12g,%.2e,%zu\n", alpha, m.beta(), m.kappa(),
                    to_string(regime(m)), ratio, r.epsilon.value_or(1.0), r.contact_length, scaled,
                    r.hysteretic_friction / S1, r.error_estimate, r.degree);
      }
    }
  }

  return 0;
}
