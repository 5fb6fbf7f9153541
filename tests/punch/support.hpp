// Shared helpers of the punch tests: the Riemann-Hilbert oracle for the isolated wedge below the
// boundary (rhabel::riemann::solve_abel_rh: Riemann problem + Abel inversion; it shares no code with
// abel::solve_step's enrichment or the spectral relation), and the tolerance of a C_f comparison.
#pragma once

#include "rhabel/punch.hpp"
#include "rhabel/riemann.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace punch_test {

/// The wedge density of a solved contact, recomputed by the Riemann-Hilbert route on the
/// solver's own interval [r.a, r.b] (apex at `apex`), order 16.
struct wedge_oracle {
  double S1, S2, pressure_scale;
  rhabel::riemann::abel_rh_solution<double> sol;

  wedge_oracle(const rhabel::punch::material& m, double speed, double S1_, double S2_, double apex, double a, double b)
      : S1(S1_), S2(S2_),
        pressure_scale(boost::math::constants::pi<double>() / 2 * m.effective_modulus(speed)),
        sol(make(m, S1_, S2_, apex, a, b)), apex_(apex) {}

  /// C_f = (S1 int_a^apex g - S2 int_apex^b g) / int g.
  double friction() const {
    const double total = sol.total().value, ahead = sol.integral(apex_).value;
    return (S1 * ahead - S2 * (total - ahead)) / total;
  }
  /// int p over the contact.
  double load() const { return pressure_scale * sol.total().value; }
  /// p(t), t in (a, b), t != apex.
  double pressure(double t) const { return pressure_scale * sol.density(t).value; }

 private:
  static rhabel::riemann::abel_rh_solution<double> make(const rhabel::punch::material& m, double S1, double S2,
                                                        double apex, double a, double b) {
    const double gf = boost::math::tgamma(1 - m.alpha);
    rhabel::riemann::piecewise_function<double> F{[S1, gf](double) { return S1 / gf; }, {{apex, -(S1 + S2) / gf}}};
    rhabel::riemann::abel_rh_options<double> o;
    o.order = 16;
    return rhabel::riemann::solve_abel_rh(m.alpha, m.beta(), a, b, F, rhabel::riemann::edge::bounded,
                                          rhabel::riemann::edge::bounded, o);
  }
  double apex_;
};

/// Tolerance of a C_f comparison: `relative` times the size of C_f, floored at min(S1, S2) (C_f
/// vanishes for the elastic frictionless wedge), and never below 16 eps (S1 + S2): C_f is a
/// difference of the two faces' shares, each known to a few eps of the total times its slope.
inline double friction_tolerance(double relative, double cf, double S1, double S2) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  return std::max(relative * std::max(std::abs(cf), std::min(S1, S2)), 16 * eps * (S1 + S2));
}

}  // namespace punch_test
