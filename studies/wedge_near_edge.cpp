// study_wedge_near_edge: the isolated wedge below the boundary with its apex near an edge (issue
// #4: eps, L, C_f and 1000 pressure samples; the apex within 0.1 L of an edge is common: eps =
// 0.907 for alpha = 0.3, S1 = S2; 0.972 for alpha = 0.2, S2/S1 = 3).
//
// What the solver does there (punch/src/contact.cpp, solve_wedge): eps in closed form (incomplete
// beta inversion), L from the exact load; with the apex nearer an edge than L/4 (every case below)
// the density is the split form of build_wedge_near_edge: the long side's constant in closed form
// plus the short side's step by abel::solve_step with the apex mapped to the centre
// (apex_placement::centred, abel/step_enrichment.hpp); C_f, the pressure samples, the residual and
// the displacement all come from it (column `path`: step). The Riemann-Hilbert path (`rh`, named
// in the status) is taken only with solve_options::wedge_apex_split off.
//
// Cases (nu = 0.3, E1 = 1, U = 1, unit load): eps in {0.84, 0.907, 0.953, 0.972} (alpha = 0.2, 0.3,
// 0.1, 0.2 with k in {0, 0.5} and S2/S1 = 1 or 3), eps in {0.99, 0.995, 0.998, 0.999, 0.9995,
// 0.9999, 0.99999} and 0.01 at alpha = 0.2, k = 0 (the slope ratio that gives this eps), and the
// elastic frictionless wedge (alpha = k = 0: closed form) at eps 0.972, 0.999, 0.9999 and 0.99999.
//
// References, each computed once per case, and how independent they are:
//   * eps, L: study_support.hpp's wedge_moment_reference at 50 digits: eps by the 50-digit
//     inversion of the same incomplete-beta condition (checks the solver's rounding only), L from
//     the load-moment formula with incomplete beta functions (a different formula from the
//     solver's eps^del (1-eps)^gam form). err_eps = max of the relative errors of eps and 1 - eps
//     (1 - eps = (b - apex)/L: the small one of the two).
//   * the Riemann-Hilbert route at order 24 (riemann::solve_abel_rh: a Riemann problem and Abel's
//     inversion; no spectral relation, no Jacobi expansion of F, no enrichment) on the solver's
//     interval [a, b], apex at 0:
//       err_Cf_rh24  C_f = (S1 int_a^apex g - S2 int_apex^b g) / int g (as tests/punch/support.hpp's
//                    wedge_oracle), relative to max(|C_f|, min(S1, S2)) (C_f = 0 for alpha = k = 0);
//       err_p_rh24   its pointwise g(y) at every 10th of the 1000 samples, max |p - p_ref| over the
//                    largest reference sample; samples where its two orders disagree by more than
//                    1e-12 relative are left out (n_p_ref says how many of the 100 were kept).
//     On the solver's step path this is independent by method. On
//     its Riemann-Hilbert path (wedge_apex_split off) it is the same method at a different order, on the
//     solver's interval instead of the unit one, pointwise instead of interpolated: it then checks
//     the order, the scaling and the interpolant, not the method; the next reference and the
//     closed form below are the independent checks of that path.
//   * rh path only: abel::solve_step (Moebius map, up to 1025 points, tolerance 1e-14, residual
//     off) on the solver's interval, the method of the step path and independent of the
//     Riemann-Hilbert route: err_Cf_step and err_p_step as above (same samples, same norms); its
//     own error at an apex 1e-4 ... 1e-5 L from an edge (where it may not converge within 1025
//     points, abel/step_enrichment.hpp) is part of what they show (status_step: converged or not,
//     and its coefficient tail).
//   * alpha = k = 0 only, independent and exact:
//       err_p_exact  the closed form g = ((S1 + S2)/pi^2) [2 log(A + B) - log(L |apex - t|)],
//                    A = sqrt((apex - a)(b - t)), B = sqrt((b - apex)(t - a))
//                    (tests/punch/test_wedge.cpp), at all 100 samples, relative to its largest;
//       err_Cf_exact |C_f| / min(S1, S2): C_f = 0 exactly (no hysteresis).
// Time: minimum per call over a 0.3 s budget (studies/support/study_support.hpp), solve_single
// with grid_points = 1000, displacement off, tolerance 1e-10; with and without the residual;
// cpu_seconds is the CPU time per call of the run with the residual.
//
// CSV on stdout: alpha,k,S2_over_S1,eps,path (step: solve_step's enriched density; rh: the
//                Riemann-Hilbert route),err_eps,err_L,err_Cf_rh24,err_p_rh24,n_p_ref,err_p_exact,
//                err_Cf_exact,err_Cf_step,err_p_step,status_step,error_estimate,pressure_estimate
//                (the solver's, from its status: rh path only),degree,seconds,seconds_no_residual,
//                cpu_seconds,status (commas replaced by semicolons)
//   error_estimate and degree are indentor_result's fields as reported: on the rh path they
//   describe the plain series of degree 127 (residual and displacement only; error_estimate ~1);
//   degree on the mapped step path is that of the series in the mapped variable.
// Usage: study_wedge_near_edge [> wedge_near_edge.csv]
#define BOOST_MATH_DISABLE_FLOAT128  // see studies/support/study_support.hpp
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
#include <utility>
#include <vector>

using namespace rhabel::punch;
using rhabel_study::format_number;
using rhabel_study::min_time_per_call;
using rhabel_study::relative_error;
using rhabel_study::wedge_friction;
using rhabel_study::wedge_friction_error;
using big = boost::multiprecision::cpp_bin_float_50;

namespace {
constexpr double nu_poisson = 0.3;
constexpr double pi = boost::math::constants::pi<double>();

struct scene_case {
  double alpha, k;
  double eps;  // target eps: S2/S1 from I_eps(del, gam) = S2/(S1 + S2); negative: -(S2/S1) given
};

double slope_ratio(const material& m, double eps) {
  const double beta = m.beta(), gam = (1 - 2 * m.alpha - beta) / 2, del = (1 + beta) / 2;
  const double r = boost::math::ibeta(del, gam, eps);
  return r / (1 - r);
}
}  // namespace

int main() {
  std::printf("alpha,k,S2_over_S1,eps,path,err_eps,err_L,err_Cf_rh24,err_p_rh24,n_p_ref,err_p_exact,err_Cf_exact,"
              "err_Cf_step,err_p_step,status_step,error_estimate,pressure_estimate,degree,seconds,"
              "seconds_no_residual,cpu_seconds,status\n");
  const std::vector<scene_case> cases{{0.2, 0.5, -1},     {0.3, 0.0, -1},     {0.1, 0.5, -3},    {0.2, 0.0, -3},
                                      {0.2, 0.0, 0.99},   {0.2, 0.0, 0.995},  {0.2, 0.0, 0.998}, {0.2, 0.0, 0.999},
                                      {0.2, 0.0, 0.9995}, {0.2, 0.0, 0.9999}, {0.2, 0.0, 0.99999}, {0.2, 0.0, 0.01},
                                      {0.0, 0.0, 0.972},  {0.0, 0.0, 0.999},  {0.0, 0.0, 0.9999},  {0.0, 0.0, 0.99999}};
  for (const auto& c : cases) {
    const material m{c.alpha, 1.0, nu_poisson, c.k};
    const double ratio = c.eps < 0 ? -c.eps : slope_ratio(m, c.eps);
    const double S1 = 0.1, S2 = S1 * ratio, load = 1.0, apex = 0.0;
    const indentor ind{wedge{S1, S2}, load, apex};
    solve_options o;
    o.grid_points = 1000;
    o.displacement = false;
    o.tolerance = 1e-10;
    const auto r = solve_single(m, 1.0, ind, o);
    const double L = r.contact_length;
    const double ps = pi / 2 * m.effective_modulus(1.0), gf = boost::math::tgamma(1 - c.alpha);
    // eps and L at 50 digits (E_U = E1 Gamma(1 - alpha) / (1 - nu^2) at U = 1).
    const big E_U = big(m.E1) * boost::math::tgamma(1 - big(c.alpha)) / (1 - big(nu_poisson) * big(nu_poisson));
    const auto moments =
        rhabel_study::wedge_moment_reference<big>(big(c.alpha), big(m.beta()), big(S1), big(S2), big(load), E_U);
    const double err_eps = std::max(relative_error(r.epsilon.value_or(1.0), static_cast<double>(moments.eps)),
                                    relative_error((r.b - apex) / L, static_cast<double>(moments.one_minus_eps)));
    // The Riemann-Hilbert route at order 24 on the solver's interval, and its samples (once).
    rhabel::riemann::piecewise_function<double> F{[S1, gf](double) { return S1 / gf; }, {{apex, -(S1 + S2) / gf}}};
    rhabel::riemann::abel_rh_options<double> ro;
    ro.order = 24;
    const auto rh = rhabel::riemann::solve_abel_rh(c.alpha, m.beta(), r.a, r.b, F, rhabel::riemann::edge::bounded,
                                                   rhabel::riemann::edge::bounded, ro);
    const double cf_rh = wedge_friction(S1, S2, rh.total().value, rh.integral(apex).value);
    std::vector<std::size_t> index;
    std::vector<double> p_ref;
    for (std::size_t k = 5; k < r.grid_x.size(); k += 10) {
      const double t = r.grid_x[k];
      if (t == apex) continue;  // p is infinite at the apex
      const auto d = rh.density(t);
      if (!(std::abs(d.error_estimate) < 1e-12 * std::abs(d.value))) continue;  // its two orders disagree
      index.push_back(k);
      p_ref.push_back(ps * d.value);
    }
    double peak = 0, e_rh = 0, e_exact = 0;
    for (double p : p_ref) peak = std::max(peak, std::abs(p));
    for (std::size_t j = 0; j < index.size(); ++j)
      e_rh = std::max(e_rh, std::abs(r.pressure[index[j]] - p_ref[j]) / peak);
    const bool rh_path = r.status.find("Riemann-Hilbert") != std::string::npos;
    std::string cf_step_cell, p_step_cell, status_step;
    if (rh_path) {
      const rhabel::abel::abel_operator<double> op(c.alpha, m.beta(), r.a, r.b);
      rhabel::abel::solve_options<double> so;
      so.tolerance = 1e-14;
      so.max_degree = 1025;
      so.residual_points = 0;
      const auto step = rhabel::abel::solve_step(op, rhabel::abel::edge::bounded, rhabel::abel::edge::bounded,
                                                 [&](double s) { return F(s); }, apex, so);
      const double cf_step = wedge_friction(S1, S2, step.density.integral(), step.density.integral_to(apex));
      double e_step = 0;
      for (std::size_t j = 0; j < index.size(); ++j)
        e_step = std::max(e_step, std::abs(r.pressure[index[j]] - ps * step.density(r.grid_x[index[j]])) / peak);
      cf_step_cell = format_number(wedge_friction_error(r.hysteretic_friction, cf_step, S1, S2), 3);
      p_step_cell = format_number(e_step, 3);
      status_step = (step.status == rhabel::abel::solve_status::converged ? "converged" : "not converged") +
                    std::string(" tail ") + format_number(step.coefficient_tail, 2);
    }
    const bool elastic = c.alpha == 0 && c.k == 0;
    if (elastic) {
      std::vector<std::pair<std::size_t, double>> exact;  // (sample, closed-form pressure)
      double exact_peak = 0;
      for (std::size_t k = 5; k < r.grid_x.size(); k += 10) {
        const double t = r.grid_x[k];
        if (t == apex) continue;
        const double A = std::sqrt((apex - r.a) * (r.b - t)), B = std::sqrt((r.b - apex) * (t - r.a));
        exact.emplace_back(k, ps * (S1 + S2) / (pi * pi) * (2 * std::log(A + B) - std::log(L * std::abs(apex - t))));
        exact_peak = std::max(exact_peak, std::abs(exact.back().second));
      }
      for (const auto& [k, p] : exact) e_exact = std::max(e_exact, std::abs(r.pressure[k] - p) / exact_peak);
    }
    const auto t_full = min_time_per_call([&] { return solve_single(m, 1.0, ind, o).load; }, 0.3);
    solve_options fast = o;
    fast.residual = false;
    const auto t_fast = min_time_per_call([&] { return solve_single(m, 1.0, ind, fast).load; }, 0.3);
    std::string estimate;
    if (const auto at = r.status.find("error estimate "); at != std::string::npos)
      estimate = r.status.substr(at + 15, r.status.find(' ', at + 15) - at - 15);
    std::string status = r.status;
    std::replace(status.begin(), status.end(), ',', ';');
    std::printf("%g,%g,%.6g,%.6g,%s,%.2e,%.2e,%.2e,%.2e,%zu,%s,%s,%s,%s,%s,%.2e,%s,%zu,%.3e,%.3e,%.3e,%s\n",
                c.alpha, c.k, ratio,
                static_cast<double>(moments.eps), rh_path ? "rh" : "step", err_eps,
                relative_error(L, static_cast<double>(moments.L)),
                wedge_friction_error(r.hysteretic_friction, cf_rh, S1, S2), e_rh,
                p_ref.size(), elastic ? format_number(e_exact, 3).c_str() : "",
                elastic ? format_number(std::abs(r.hysteretic_friction) / std::min(S1, S2), 3).c_str() : "",
                cf_step_cell.c_str(), p_step_cell.c_str(), status_step.c_str(),
                r.error_estimate, estimate.c_str(), r.degree,
                t_full.seconds, t_fast.seconds, t_full.cpu_seconds, status.c_str());
    std::fflush(stdout);
  }
  return 0;
}
