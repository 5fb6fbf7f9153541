// study_wedge_stationarity: paper section 4 conjectures that, at fixed load, the hysteretic friction
// C_f is stationary at the true contact interval when considered over the trial intervals [a, a+L]
// whose density is the solution of (8) bounded at a and unbounded at b (rhabel::punch::trial_interval).
// The paper checks it for the frictionless parabola; tests/punch/test_contact.cpp checks it for the
// parabola with friction. This study asks the same question for the wedge below the boundary.
//
// Along the load constraint, parametrised by L (at fixed a the load is stationary in L at the true
// interval for the parabola, so a is solved for), it prints dC_f/dL by central differences
// at the true L (steps 4d and 2d, d = 1e-3 L, and their Richardson extrapolation dCf_dL_true) and
// at 1.2 L (step d). ratio = |dCf_dL_true / dCf_dL_at_1.2L|. CSV on stdout:
//   shape,alpha,k,S2_over_S1,L_true,Cf_true,Cf_trial_at_true,dCf_dL_4d,dCf_dL_2d,dCf_dL_true,dCf_dL_at_1.2L,ratio,status
#include "rhabel/punch.hpp"

#include <cmath>
#include <cstdio>

using namespace rhabel::punch;

namespace {
// C_f of the trial interval of length L carrying `load` (leading edge by bisection around a_guess).
double trial_friction(const material& m, const indentor& ind, double L, double a_guess) {
  double lo = a_guess - 0.2 * L, hi = a_guess + 0.2 * L;
  const double f_lo = trial_interval(m, 1.0, ind, lo, lo + L).load - ind.load;
  for (int it = 0; it < 60; ++it) {
    const double mid = (lo + hi) / 2;
    const double f = trial_interval(m, 1.0, ind, mid, mid + L).load - ind.load;
    ((f > 0) == (f_lo > 0) ? lo : hi) = mid;
  }
  const double a = (lo + hi) / 2;
  return trial_interval(m, 1.0, ind, a, a + L).hysteretic_friction;
}
}  // namespace

int main() {
  std::printf("shape,alpha,k,S2_over_S1,L_true,Cf_true,Cf_trial_at_true,dCf_dL_4d,dCf_dL_2d,dCf_dL_true,dCf_dL_at_1.2L,ratio,status\n");
  for (int shape = 0; shape < 2; ++shape) {
    for (double alpha : {0.0, 0.1, 0.2}) {
      for (double k : {0.0, 0.5}) {
       for (double ratio : {1.0, 3.0}) {
        if (shape == 0 && ratio != 1.0) continue;
        const material m{alpha, 1.0, 0.3, k};
        const indentor ind = shape == 0 ? indentor{parabolic{1.0}, 1.0, 0.0} : indentor{wedge{0.1, 0.1 * ratio}, 1.0, 0.0};
        const auto r = solve_single(m, 1.0, ind);
        const double L = r.contact_length, d = 1e-3 * L;
        const double at = trial_friction(m, ind, L, r.a);
        // Central differences with steps 4d and 2d, then Richardson (error O(d^2) removed): a
        // stationary C_f gives an extrapolated slope at the level of the trial's rounding.
        auto central = [&](double h) {
          return (trial_friction(m, ind, L + h, r.a) - trial_friction(m, ind, L - h, r.a)) / (2 * h);
        };
        const double slope_4d = central(4 * d), slope_2d = central(2 * d);
        const double slope_true = (4 * slope_2d - slope_4d) / 3;
        const double slope_off =
            (trial_friction(m, ind, 1.2 * L + d, r.a) - trial_friction(m, ind, 1.2 * L - d, r.a)) / (2 * d);
        std::printf("%s,%.2f,%.1f,%g,%.12g,%.12g,%.12g,%.3e,%.3e,%.3e,%.3e,%.2e,%s\n", shape == 0 ? "parabola" : "wedge", alpha,
                    k, shape == 0 ? 0.0 : ratio, L, r.hysteretic_friction, at, slope_4d, slope_2d, slope_true, slope_off,
                    std::abs(slope_true / slope_off), r.status.substr(0, 2).c_str());
        std::fflush(stdout);
       }
      }
    }
  }
  return 0;
}
