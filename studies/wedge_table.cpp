// study_wedge_table: the sliding wedge on a power-law viscoelastic half-space, tabulated against
// the material exponent alpha (CSV on stdout), then accuracy against solve time (second CSV block).
//
// Table 1 ("table"): S1 = S2 = 0.1 and S2/S1 = 3, k = 0 and k = 0.5 (nu = 0.3), unit load per
// length, E_U = 1 (E1 = (1 - nu^2)/Gamma(1 - alpha), U = 1). Columns: alpha, beta, kappa, regime,
// S2/S1, eps = (apex - a)/L, L, L_scaled = L (S1 E_U / load)^(1/(1-alpha)) (dimensionless, depends
// only on alpha, beta and S2/S1: int p is proportional to S1 E_U L^(1-alpha)), C_f/S1,
// error_estimate (of the density; an estimate), degree.
//   eps and L are exact to rounding (incomplete-beta inversion and the closed-form load moment);
//   C_f below the boundary is converged to the error estimate.
// Table 2 ("timing"): for alpha in {0, 0.2} the same scene with 1000 pressure samples at increasing
// degree, with and without the apex split; time = median wall clock of 5 solves after a warm-up
// (Gauss-Jacobi rules are cached per thread); errors against the highest-degree split solution.
//
// Usage: study_wedge_table [> wedge_table.csv]
#include "rhabel/punch.hpp"

#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <chrono>
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
                    regime(m).c_str(), ratio, r.epsilon.value_or(1.0), r.contact_length, scaled,
                    r.hysteretic_friction / S1, r.error_estimate, r.degree);
      }
    }
  }

  std::printf("\n# timing\nalpha,split,degree,median_ms,Cf_error,max_pressure_rel_error,error_estimate\n");
  for (double alpha : {0.0, 0.2}) {
    const material m = unit_material(alpha, 0.5);
    const indentor ind{wedge{0.1, 0.3}, 1.0, 0.0};
    solve_options ref_opt;
    ref_opt.grid_points = 1000;
    ref_opt.max_degree = 512;
    ref_opt.displacement = false;
    const auto ref = solve_single(m, 1.0, ind, ref_opt);
    double pmax = 0;
    for (double p : ref.pressure) pmax = std::max(pmax, std::abs(p));
    for (bool split : {false, true}) {
      for (std::size_t degree : {16, 32, 64, 128, 256}) {  // reference: degree 512
        solve_options o;
        o.grid_points = 1000;
        o.max_degree = degree;
        o.wedge_apex_split = split;
        o.displacement = false;  // the target: eps, L, C_f and 1000 pressure samples
        auto r = solve_single(m, 1.0, ind, o);  // warm-up: builds and caches the rules
        std::vector<double> ms;
        for (int rep = 0; rep < 5; ++rep) {
          const auto t0 = std::chrono::steady_clock::now();
          r = solve_single(m, 1.0, ind, o);
          ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        }
        std::sort(ms.begin(), ms.end());
        double perr = 0;
        for (std::size_t i = 0; i < r.pressure.size(); ++i)
          perr = std::max(perr, std::abs(r.pressure[i] - ref.pressure[i]) / pmax);
        std::printf("%.2f,%d,%zu,%.3f,%.2e,%.2e,%.2e\n", alpha, split ? 1 : 0, degree, ms[2],
                    std::abs(r.hysteretic_friction - ref.hysteretic_friction), perr, r.error_estimate);
      }
    }
  }
  return 0;
}
