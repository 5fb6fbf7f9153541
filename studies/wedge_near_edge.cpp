// study_wedge_near_edge: the isolated wedge below the boundary with its apex near an edge (issue
// #4: eps, L, C_f and 1000 pressure samples; the apex within 0.1 L of an edge is common: eps =
// 0.907 for alpha = 0.3, S1 = S2; 0.972 for alpha = 0.2, S2/S1 = 3). There the solver takes C_f
// AND the pressure samples from the Riemann-Hilbert route (riemann::solve_abel_rh, order 16;
// samples from a piecewise Chebyshev interpolant of its density built with
// abel_rh_solution::densities), the load and L in closed form, the residual and the
// displacement from abel::solve_step's enriched density. Error and cost for eps in {0.84, 0.907,
// 0.953, 0.972, 0.99, 0.999} (alpha = 0.2, 0.3, 0.1 with nu = 0.3, k in {0, 0.5}), the apex 0.01 L
// from the leading edge, and the elastic frictionless wedge (closed form) at eps 0.972 and 0.999.
//
// References, and how independent they are:
//   * L: the load moment of the Riemann-Hilbert route with eps from a 50-digit ibeta_inv
//     (study_scene_timing's formula), at 50 digits: a different formula from the solver's.
//   * pressure, every 10th of the 1000 samples, relative to the largest reference sample:
//       err_p_rh24  riemann's pointwise g(y) at order 24 (the same method as the solver's source
//                   at a different order, without the interpolants: checks the batch
//                   evaluation and the interpolation, not the method);
//       err_p_step  abel::solve_step with up to 1025 Chebyshev points, tolerance 1e-14 (a
//                   different method, converging only algebraically this near an edge: its own
//                   error dominates below ~0.03 L, see step_enrichment.hpp);
//       err_p_exact alpha = k = 0 only: the closed form g = ((S1 + S2)/pi^2) [2 log(A + B) -
//                   log(L |apex - t|)], A = sqrt((apex - a)(b - t)), B = sqrt((b - apex)(t - a))
//                   (tests/punch/test_wedge.cpp): independent and exact.
//   * C_f: err_Cf_step against solve_step at 1025 points (as above); at alpha = k = 0, C_f = 0.
// Time: minimum per call over a 0.3 s budget (studies/support/study_support.hpp), solve_single
// with grid_points = 1000, displacement off, tolerance 1e-10; with and without the residual.
//
// CSV on stdout: alpha,k,S2_over_S1,eps,err_L,err_Cf_step,err_p_rh24,err_p_step,err_p_exact,
//                pressure_estimate (the solver's, from its status),seconds,seconds_no_residual,
//                cpu_seconds,status
// Usage: study_wedge_near_edge [> wedge_near_edge.csv]
#define BOOST_MATH_DISABLE_FLOAT128  // see study_scene_timing: no __float128 needed
#include "support/study_support.hpp"

#include "rhabel/abel.hpp"
#include "rhabel/punch.hpp"
#include "rhabel/riemann.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace rhabel::punch;
using rhabel_study::format_number;
using rhabel_study::min_time_per_call;
using big = boost::multiprecision::cpp_bin_float_50;

namespace {
constexpr double nu_poisson = 0.3;
constexpr double pi = boost::math::constants::pi<double>();

struct scene_case {
  double alpha, k;
  double eps;  // target: S2/S1 from I_eps(del, gam) = S2/(S1 + S2)
};

double slope_ratio(const material& m, double eps) {
  const double beta = m.beta(), gam = (1 - 2 * m.alpha - beta) / 2, del = (1 + beta) / 2;
  const double r = boost::math::ibeta(del, gam, eps);
  return r / (1 - r);
}

double moment_length(const material& m, double S1, double S2, double load) {
  const big alpha = m.alpha, beta = m.beta();
  const big bpi = boost::math::constants::pi<big>();
  const big gam = (1 - 2 * alpha - beta) / 2, del = (1 + beta) / 2;
  const big e = boost::math::ibeta_inv(del, gam, big(S2) / (big(S1) + big(S2)));
  const big P = (1 + beta) / 2, Q = (3 - beta) / 2 - alpha;
  const big B = boost::math::beta(P, Q), Be = boost::math::beta(P, Q, e);
  const big unit = cos(beta * bpi / 2) / (bpi * boost::math::tgamma(1 - alpha)) * (big(S1) * Be - big(S2) * (B - Be));
  const big E_U = big(m.E1) * boost::math::tgamma(1 - alpha) / (1 - big(m.poisson) * big(m.poisson));
  return static_cast<double>(pow(big(load) / (bpi / 2 * E_U * unit), 1 / (1 - alpha)));
}
}  // namespace

int main() {
  std::printf("alpha,k,S2_over_S1,eps,err_L,err_Cf_step,err_p_rh24,err_p_step,err_p_exact,pressure_estimate,seconds,"
              "seconds_no_residual,cpu_seconds,status\n");
  const std::vector<scene_case> cases{{0.2, 0.5, -1},  {0.3, 0.0, -1},  {0.1, 0.5, -3},   {0.2, 0.0, -3},
                                      {0.2, 0.0, 0.99}, {0.2, 0.0, 0.999}, {0.2, 0.0, 0.01}, {0.0, 0.0, 0.972},
                                      {0.0, 0.0, 0.999}};
  for (const auto& c : cases) {
    const material m{c.alpha, 1.0, nu_poisson, c.k};
    // negative eps: -(S2/S1) given directly (the brief's cases)
    const double ratio = c.eps < 0 ? -c.eps : slope_ratio(m, c.eps);
    const double S1 = 0.1, S2 = S1 * ratio, load = 1.0, apex = 0.0;
    const indentor ind{wedge{S1, S2}, load, apex};
    solve_options o;
    o.grid_points = 1000;
    o.displacement = false;
    o.tolerance = 1e-10;
    const auto r = solve_single(m, 1.0, ind, o);
    const double eps = *r.epsilon, L = r.contact_length;
    const double ps = pi / 2 * m.effective_modulus(1.0), gf = boost::math::tgamma(1 - c.alpha);
    // References on the solver's interval.
    rhabel::riemann::piecewise_function<double> F{[S1, gf](double) { return S1 / gf; }, {{apex, -(S1 + S2) / gf}}};
    rhabel::riemann::abel_rh_options<double> ro;
    ro.order = 24;
    const auto rh = rhabel::riemann::solve_abel_rh(c.alpha, m.beta(), r.a, r.b, F, rhabel::riemann::edge::bounded,
                                                   rhabel::riemann::edge::bounded, ro);
    const rhabel::abel::abel_operator<double> op(c.alpha, m.beta(), r.a, r.b);
    rhabel::abel::solve_options<double> so;
    so.tolerance = 1e-14;
    so.max_degree = 1025;
    so.residual_points = 0;
    const auto step = rhabel::abel::solve_step(op, rhabel::abel::edge::bounded, rhabel::abel::edge::bounded,
                                               [&](double s) { return F(s); }, apex, so);
    const double total = step.density.integral(), ahead = step.density.integral_to(apex);
    const double cf_step = (S1 * ahead - S2 * (total - ahead)) / total;
    double peak = 0, e_rh = 0, e_step = 0, e_exact = 0;
    for (std::size_t k = 5; k < 1000; k += 10) peak = std::max(peak, ps * rh.density(r.grid_x[k]).value);
    for (std::size_t k = 5; k < 1000; k += 10) {
      const double t = r.grid_x[k];
      e_rh = std::max(e_rh, std::abs(r.pressure[k] - ps * rh.density(t).value) / peak);
      e_step = std::max(e_step, std::abs(r.pressure[k] - ps * step.density(t)) / peak);
      if (c.alpha == 0 && c.k == 0) {
        const double A = std::sqrt((apex - r.a) * (r.b - t)), B = std::sqrt((r.b - apex) * (t - r.a));
        const double p = ps * (S1 + S2) / (pi * pi) * (2 * std::log(A + B) - std::log(L * std::abs(apex - t)));
        e_exact = std::max(e_exact, std::abs(r.pressure[k] - p) / peak);
      }
    }
    const auto t_full = min_time_per_call([&] { return solve_single(m, 1.0, ind, o).load; }, 0.3);
    solve_options fast = o;
    fast.residual = false;
    const auto t_fast = min_time_per_call([&] { return solve_single(m, 1.0, ind, fast).load; }, 0.3);
    std::string estimate = "";
    if (const auto at = r.status.find("error estimate "); at != std::string::npos)
      estimate = r.status.substr(at + 15, r.status.find(' ', at + 15) - at - 15);
    std::string status = r.status;
    std::replace(status.begin(), status.end(), ',', ';');
    std::printf("%g,%g,%.6g,%.6g,%.2e,%.2e,%.2e,%.2e,%s,%s,%.3e,%.3e,%.3e,%s\n", c.alpha, c.k, ratio, eps,
                std::abs(L / moment_length(m, S1, S2, load) - 1),
                std::abs(r.hysteretic_friction - cf_step) / std::max(std::abs(cf_step), std::min(S1, S2)), e_rh, e_step,
                c.alpha == 0 && c.k == 0 ? format_number(e_exact, 3).c_str() : "", estimate.c_str(), t_full.seconds,
                t_fast.seconds, t_full.cpu_seconds, status.c_str());
    std::fflush(stdout);
  }
  return 0;
}
