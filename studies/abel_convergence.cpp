// Convergence study of the abel solvers: error against an independent reference, independent
// residual and time, as a function of the degree, for smooth, step and kink data and the hard
// alphas of the issue. Writes CSV to stdout (or to the file named by argv[1]):
//   case,alpha,beta,nu,n,error,residual,seconds
//
// References (none goes through the spectral solver being measured):
//  * smooth: manufactured solution. g* = w (1 + x/3) exp(x/2) (not a polynomial), F = A g*
//    evaluated by the direct one-sided quadrature (apply_by_quadrature); error = max relative
//    error of g at 7 interior points and of int g (Gauss-Jacobi on g*).
//  * step (F = 1 for s < t0, 0 after; the wedge apex): int g exact from the Rodrigues image
//    coefficient (c_0 only); int_a^t0 g from the exact-coefficient series summed in O(N) to
//    N = 2^20 with a Richardson step in the known rate N^-(1-alpha) (reference accurate to
//    ~1e-10, shown by its own convergence in the log).
//  * step_enriched (solve_step, singular enrichment at the apex): int_a^t0 g against the
//    degree-257 enriched solution (spectral self-reference; the extrapolated plain series and the
//    exact int g are printed to stderr as independent cross-checks); int g against Rodrigues.
//  * step_adaptive_total / _partial: adaptive solve_step (default options, the punch layer's call)
//    for alpha in {0, 1e-3, 0.01, 0.049, 0.05, 0.25, 0.5, 0.9}: int g against Rodrigues, int_a^t0 g
//    against the degree-257 enriched solution; n = points the adaptive loop used.
//  * step_apex_eps_<eps>: adaptive solve_step with the apex at eps = (t0 - a)/L, 1e-6 .. 1 - 1e-6
//    (alpha = 0.3, beta = 0.2): int g against Rodrigues, residual (with points next to the apex).
//  * step_apex_rh_eps_<eps>: wedge data satisfying the orthogonality condition (nu = -1), apex at
//    eps in {0.5, 0.8, 0.9, 0.97, 0.99, 0.999, 0.03, 0.001} (alpha = 0.3, beta = 0.2) and the punch layer's alpha = 0.2, 1e-3, 0,
//    k = 0.5 wedge (eps = 0.84): int g and int_a^apex g against riemann::solve_abel_rh (the
//    independent Riemann-Hilbert route), at 65, 195, 585 points and adaptive ("_adaptive").
//  * kink (F = |s - t0|): int_a^t0 g against the degree-2048 solution (algebraic reference);
//    with the kink built in (solve_kinks; rows kink_enriched*), the larger of the error of int g
//    against the exact projection (solve_piecewise at degree 4: int g depends on c_0 alone) and
//    the change of int_a^t0 g against the 257-point enriched solution (self-convergence).
// Timing: median of repeated solves (residual switched off), steady_clock.
#include "rhabel/abel.hpp"
#include "rhabel/riemann.hpp"

#include <boost/math/constants/constants.hpp>

#include <boost/math/special_functions/beta.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace rhabel::abel;

namespace {

template <class Fn>
double median_seconds(Fn&& fn, int repeats) {
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    const auto t1 = std::chrono::steady_clock::now();
    times.push_back(std::chrono::duration<double>(t1 - t0).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

// int g for step data with one breakpoint t0: the plain solver's image coefficients by
// Gauss-Jacobi per piece, for piecewise constant F the exact Rodrigues values (c_0 only needed).
template <class F>
double rodrigues_total(const abel_operator<double>& op, edge trailing, F&& f, double t0) {
  solve_options<double> plain;
  plain.degree = 4;
  plain.residual_points = 0;
  return solve_piecewise(op, edge::bounded, trailing, f, {t0}, plain).density.integral();
}

// solve_step with default options (adaptive, residual computed) and the median time of the same
// solve without the residual.
template <class F>
std::pair<enriched_solution<double>, double> default_step(const abel_operator<double>& op, edge trailing, F&& f,
                                                          double t0, int repeats) {
  solve_options<double> options;
  auto sol = solve_step(op, edge::bounded, trailing, f, t0, options);
  options.residual_points = 0;
  const double seconds = median_seconds([&] { (void)solve_step(op, edge::bounded, trailing, f, t0, options); }, repeats);
  return {std::move(sol), seconds};
}

// int_{-1}^{y0} g for the left-step solution, exact coefficients summed to N (O(N)).
double step_partial_integral(const abel_operator<double>& op, const edge_exponents<double>& e, double y0, long N) {
  const double p = e.gam + e.nu, q = e.del + e.nu;
  const double h = op.half_length(), scale = std::pow(h, -op.parameters().alpha());
  // P_{m-1}^(p+1, q+1)(y0) and P_{n-1}^(del+1, gam+1)(y0) by the recurrence, h_m by its ratio.
  std::vector<double> Pimg = detail::jacobi_values_any(std::size_t(N + 1), p + 1, q + 1, y0);
  std::vector<double> Pden = detail::jacobi_values_any(std::size_t(N), e.del + 1, e.gam + 1, y0);
  const double fac_img = std::pow(1 - y0, p + 1) * std::pow(1 + y0, q + 1);
  const double fac_den = std::pow(1 - y0, e.del + 1) * std::pow(1 + y0, e.gam + 1);
  std::vector<double> d(std::size_t(N + 2));
  d[0] = boost::math::ibeta(q + 1, p + 1, (1 + y0) / 2);
  double hm = rhabel::quadrature::jacobi_norm_squared(1, p, q);
  for (long m = 1; m <= N + 1; ++m) {
    d[std::size_t(m)] = -fac_img * Pimg[std::size_t(m - 1)] / (2.0 * double(m) * hm);
    const double mm = double(m);
    hm *= (2 * mm + p + q + 1) / (2 * mm + p + q + 3) * (mm + p + 1) * (mm + q + 1) / ((mm + p + q + 1) * (mm + 1));
  }
  double sum = 0, lambda = op.eigenvalue(0, e);
  const double alpha = op.parameters().alpha();
  for (long n = 0; n < N; ++n) {
    const long m = n - e.nu;
    const double c = m >= 0 ? scale * d[std::size_t(m)] / lambda : 0.0;
    const double J = n == 0 ? std::pow(2.0, e.del + e.gam + 1) * boost::math::beta(e.gam + 1, e.del + 1) *
                                  boost::math::ibeta(e.gam + 1, e.del + 1, (1 + y0) / 2)
                            : -fac_den * Pden[std::size_t(n - 1)] / (2.0 * double(n));
    sum += c * J;
    lambda *= (double(n) + 1 - alpha) / (double(n) + 1);
  }
  return h * sum;
}

}  // namespace

int main(int argc, char** argv) {
  std::ofstream file;
  if (argc > 1) file.open(argv[1]);
  std::ostream& out = argc > 1 ? file : std::cout;
  out.precision(6);
  out << "case,alpha,beta,nu,n,error,residual,seconds\n";
  out << std::setprecision(6);
  std::cerr.precision(14);

  // ---- smooth data: manufactured solution, hard alphas ----
  for (double alpha : {0.0, 1e-8, 1e-3, 0.25, 0.5 - 1e-9, 0.5, 0.9, 0.999}) {
    const double beta = 0.3, lo = -1.0, hi = 2.0;
    abel_operator<double> op(alpha, beta, lo, hi);
    const edge leading = edge::bounded, trailing = edge::unbounded;
    const auto e = op.exponents(leading, trailing);
    auto S = [](double x) { return (1 + x / 3) * std::exp(x / 2); };
    const typename abel_operator<double>::quadrature_evaluator forward(op, e.gam, e.del, 40);
    auto F = [&](double s) { return forward(S, s); };
    jacobi_density<double> probe{lo, hi, e.gam, e.del, {1.0}};
    const double exact_integral = probe.integrate([&](double t) {
      const double x = -1 + (t - lo) / op.half_length();
      return S(x);
    });
    for (std::size_t n : {4, 8, 12, 16, 20, 24, 32, 48, 64}) {
      solve_options<double> options;
      options.degree = n;
      options.residual_points = 8;
      const auto sol = solve(op, leading, trailing, F, options);
      double error = std::abs(sol.density.integral() / exact_integral - 1);
      for (double x : {-0.9, -0.5, -0.1, 0.2, 0.5, 0.8, 0.95}) error = std::max(error, std::abs(sol.density.series(x) / S(x) - 1));
      // Time the solve alone on tabulated data (F through the quadrature would dominate).
      std::vector<double> table;
      const chebyshev_grid<double> grid(n);
      for (std::size_t j = 0; j < n; ++j) table.push_back(F(lo + op.half_length() * grid.one_plus_x[j]));
      options.residual_points = 0;
      std::size_t calls = 0;
      const double seconds = median_seconds(
          [&] {
            calls = 0;
            (void)solve(op, leading, trailing, [&](double) { return table[calls++ % n]; }, options);
          },
          51);
      out << "smooth," << std::setprecision(12) << alpha << std::setprecision(6) << "," << beta << "," << e.nu << "," << n << "," << error << "," << sol.residual
          << "," << seconds << "\n";
    }
  }

  // ---- step data (wedge apex): int g exact, int_a^t0 g algebraic ----
  for (double alpha : {0.0, 1e-3, 0.25, 0.4}) {
    const double beta = 0.2, lo = -1.0, hi = 1.0, t0 = 0.1;
    abel_operator<double> op(alpha, beta, lo, hi);
    for (edge trailing : {edge::unbounded, edge::bounded}) {
      if (trailing == edge::bounded && 2 * alpha + beta >= 1) continue;
      const auto e = op.exponents(edge::bounded, trailing);
      auto F = [&](double s) { return s < t0 ? 1.0 : 0.0; };
      const double y0 = -1 + (t0 - lo) / op.half_length();
      // Reference: S(N) at N = 2^19, 2^20 and one Richardson step with rate 2^-(1-alpha).
      const double s19 = step_partial_integral(op, e, y0, 1L << 19), s20 = step_partial_integral(op, e, y0, 1L << 20);
      const double r = std::pow(2.0, -(1 - alpha));
      const double reference = s20 + (s20 - s19) * r / (1 - r);
      std::cerr << "step alpha=" << alpha << " nu=" << e.nu << " reference int_a^t0 g = " << reference
                << " (Richardson correction " << (reference - s20) << ")\n";
      for (std::size_t n : {16, 32, 64, 128, 256, 512, 1024}) {
        solve_options<double> options;
        options.degree = n;
        options.residual_points = 0;
        const auto sol = solve_piecewise(op, edge::bounded, trailing, F, {t0}, options);
        const double err_partial = std::abs(sol.density.integral_to(t0) - reference) / std::abs(reference);
        const double seconds = median_seconds([&] { (void)solve_piecewise(op, edge::bounded, trailing, F, {t0}, options); }, 5);
        out << "step_partial," << alpha << "," << beta << "," << e.nu << "," << n << "," << err_partial << ",nan,"
            << seconds << "\n";
      }
      // O(N) exact-coefficient sum: error of S(N) against the reference, and its time.
      for (long N : {1L << 10, 1L << 14, 1L << 18}) {
        const double value = step_partial_integral(op, e, y0, N);
        const double seconds = median_seconds([&] { (void)step_partial_integral(op, e, y0, N); }, 3);
        out << "step_partial_exact_series," << alpha << "," << beta << "," << e.nu << "," << N << ","
            << std::abs(value - reference) / std::abs(reference) << ",nan," << seconds << "\n";
      }
    }
  }

  // ---- step data with singular enrichment (solve_step) ----
  for (double alpha : {0.0, 1e-3, 0.05, 0.25, 0.4, 0.9}) {
    const double beta = 0.2, lo = -1.0, hi = 1.0, t0 = 0.1;
    abel_operator<double> op(alpha, beta, lo, hi);
    for (edge trailing : {edge::unbounded, edge::bounded}) {
      const auto e = op.exponents(edge::bounded, trailing);
      auto F = [&](double s) { return s < t0 ? 1.0 : 0.0; };
      solve_options<double> ref_options;
      ref_options.degree = 257;
      ref_options.residual_points = 0;
      const auto fine = solve_step(op, edge::bounded, trailing, F, t0, ref_options);
      const double reference = fine.density.integral_to(t0);
      // Independent cross-checks: int g against the exact Rodrigues c_0 (plain solver), and
      // int_a^t0 g against the extrapolated exact-coefficient series (when 2 alpha + beta < 1).
      double exact_total = std::nan("");
      if (2 * alpha + beta < 1 || e.nu == 0) exact_total = rodrigues_total(op, trailing, F, t0);
      const double y0 = -1 + (t0 - lo) / op.half_length();
      double series_reference = std::nan("");
      if (2 * alpha + beta < 1 || e.nu == 0) {
        const double s19 = step_partial_integral(op, e, y0, 1L << 19), s20 = step_partial_integral(op, e, y0, 1L << 20);
        const double r = std::pow(2.0, -(1 - alpha));
        series_reference = s20 + (s20 - s19) * r / (1 - r);
      }
      std::cerr << "step_enriched alpha=" << alpha << " nu=" << e.nu << ": int_a^t0 g (n=257) = " << reference
                << ", extrapolated plain series = " << series_reference << ", int g error vs Rodrigues = "
                << std::abs(fine.density.integral() - exact_total) / std::abs(exact_total) << "\n";
      for (std::size_t n : {9, 17, 33, 65, 129}) {
        solve_options<double> options;
        options.degree = n;
        options.residual_points = 8;
        const auto sol = solve_step(op, edge::bounded, trailing, F, t0, options);
        options.residual_points = 0;
        const double seconds = median_seconds([&] { (void)solve_step(op, edge::bounded, trailing, F, t0, options); }, 7);
        out << "step_enriched_partial," << alpha << "," << beta << "," << e.nu << "," << n << ","
            << std::abs(sol.density.integral_to(t0) - reference) / std::abs(reference) << "," << sol.residual << ","
            << seconds << "\n";
        if (!std::isnan(exact_total))
          out << "step_enriched_total," << alpha << "," << beta << "," << e.nu << "," << n << ","
              << std::abs(sol.density.integral() - exact_total) / std::abs(exact_total) << "," << sol.residual << ","
              << seconds << "\n";
      }
    }
  }

  // ---- step data, adaptive solve_step as the punch layer calls it: cost and accuracy per alpha ----
  // Default options (adaptive degree, tolerance 16 eps), residual off for the timing. Errors:
  // int g against the exact Rodrigues value (plain solver, c_0 only), int_a^t0 g against the
  // degree-257 enriched solution ("step_adaptive_partial"; spectral self-reference).
  for (double alpha : {0.0, 1e-3, 0.01, 0.049, 0.05, 0.25, 0.5, 0.9}) {
    const double beta = 0.2, lo = -1.0, hi = 1.0, t0 = 0.1;
    abel_operator<double> op(alpha, beta, lo, hi);
    for (edge trailing : {edge::unbounded, edge::bounded}) {
      if (2 * alpha + beta >= 1 && trailing == edge::bounded) continue;  // nu = -1: no interior apex there
      const auto e = op.exponents(edge::bounded, trailing);
      auto F = [&](double s) { return s < t0 ? 1.0 : 0.0; };
      solve_options<double> ref_options;
      ref_options.degree = 257;
      ref_options.residual_points = 0;
      const double reference = solve_step(op, edge::bounded, trailing, F, t0, ref_options).density.integral_to(t0);
      const double exact_total = rodrigues_total(op, trailing, F, t0);
      const auto [sol, seconds] = default_step(op, trailing, F, t0, 9);
      out << "step_adaptive_total," << alpha << "," << beta << "," << e.nu << "," << sol.degree << ","
          << std::abs(sol.density.integral() - exact_total) / std::abs(exact_total) << "," << sol.residual << ","
          << seconds << "\n";
      out << "step_adaptive_partial," << alpha << "," << beta << "," << e.nu << "," << sol.degree << ","
          << std::abs(sol.density.integral_to(t0) - reference) / std::abs(reference) << "," << sol.residual << ","
          << seconds << "\n";
    }
  }

  // ---- apex position: eps = (t0 - a)/L from 1e-6 to 1 - 1e-6 (alpha = 0.3, beta = 0.2) ----
  // Adaptive solve_step with default options; error of int g against Rodrigues; the residual
  // includes the points next to the apex. Case name carries eps; n = points used; status to stderr.
  for (double eps_apex : {1e-6, 1e-3, 1e-2, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999, 1 - 1e-6}) {
    const double alpha = 0.3, beta = 0.2;
    abel_operator<double> op(alpha, beta, 0.0, 1.0);
    for (edge trailing : {edge::unbounded, edge::bounded}) {
      const auto e = op.exponents(edge::bounded, trailing);
      auto F = [&](double s) { return s < eps_apex ? 1.0 : -1.0; };
      const double exact_total = rodrigues_total(op, trailing, F, eps_apex);
      const auto [sol, seconds] = default_step(op, trailing, F, eps_apex, 3);
      std::cerr << "step_apex eps=" << eps_apex << " nu=" << e.nu << " K=" << sol.taylor_degree << " n=" << sol.degree
                << " status=" << (sol.status == solve_status::converged ? "converged" : "not_converged")
                << " tail=" << sol.coefficient_tail << " floor=" << sol.rounding_floor << "\n";
      out << "step_apex_eps_" << eps_apex << "," << alpha << "," << beta << "," << e.nu << "," << sol.degree << ","
          << std::abs(sol.density.integral() - exact_total) / std::abs(exact_total) << "," << sol.residual << ","
          << seconds << "\n";
    }
  }

  // ---- apex near an edge, wedge data (nu = -1, orthogonality satisfied), against the RH route ----
  // F = 1 before the apex, 1 - 1/(1 - I_eps((1+beta)/2, (1-2alpha-beta)/2)) after it (closed form:
  // the data satisfy the orthogonality condition exactly). Reference: riemann::solve_abel_rh
  // (independent route; int g and int_a^apex g good to ~1e-13 per its header). Rows
  // step_apex_rh_eps_<eps>: error = max of the relative errors of int g and int_a^apex g (relative
  // to int g), n = points (fixed 65, 195, 585; "adaptive" rows: default options), residual,
  // seconds (median, residual off). Status, Taylor degree (mapped or not) and tail to stderr.
  {
    const double beta_k = 2 / boost::math::constants::pi<double>() * std::atan(0.5 * 0.4 / 1.4);  // k = 0.5, nu = 0.3
    struct apex_case {
      double alpha, beta, eps;
    };
    std::vector<apex_case> cases;
    for (double e : {0.5, 0.8, 0.9, 0.97, 0.99, 0.999, 0.03, 0.001}) cases.push_back({0.3, 0.2, e});
    for (double a : {0.2, 1e-3, 0.0}) cases.push_back({a, beta_k, 0.84});
    for (const auto& c : cases) {
      const double lo = -c.eps, hi = 1 - c.eps;
      abel_operator<double> op(c.alpha, c.beta, lo, hi);
      const double J = 1 / (1 - boost::math::ibeta((1 + c.beta) / 2, (1 - 2 * c.alpha - c.beta) / 2, c.eps));
      auto F = [&](double s) { return s < 0.0 ? 1.0 : 1.0 - J; };
      rhabel::riemann::piecewise_function<double> PF{[](double) { return 1.0; }, {rhabel::riemann::step<double>{0.0, -J}}};
      const auto rh = rhabel::riemann::solve_abel_rh(c.alpha, c.beta, lo, hi, PF, rhabel::riemann::edge::bounded,
                                                     rhabel::riemann::edge::bounded);
      const double total = rh.total().value, partial = rh.integral(0.0).value;
      auto error_of = [&](const enriched_solution<double>& sol) {
        return std::max(std::abs(sol.density.integral() / total - 1),
                        std::abs(sol.density.integral_to(0.0) - partial) / std::abs(total));
      };
      std::ostringstream name;
      name << "step_apex_rh_eps_" << c.eps;
      for (std::size_t n : {65, 195, 585, 0}) {
        solve_options<double> options;
        options.degree = n;
        const auto sol = solve_step(op, edge::bounded, edge::bounded, F, 0.0, options);
        options.residual_points = 0;
        const double seconds = median_seconds([&] { (void)solve_step(op, edge::bounded, edge::bounded, F, 0.0, options); }, n == 0 ? 5 : 3);
        if (n == 0)
          std::cerr << name.str() << " alpha=" << c.alpha << " adaptive: K=" << sol.taylor_degree
                    << (sol.density.mobius != 0 ? " (mapped)" : " (Taylor)") << " n=" << sol.degree
                    << " status=" << (sol.status == solve_status::converged ? "converged" : "not_converged")
                    << " tail=" << sol.coefficient_tail << " floor=" << sol.rounding_floor
                    << " RH error estimates " << rh.total().error_estimate << ", " << rh.integral(0.0).error_estimate << "\n";
        out << name.str() << (n == 0 ? "_adaptive," : ",") << c.alpha << "," << c.beta << ",-1," << sol.degree << ","
            << error_of(sol) << "," << sol.residual << "," << seconds << "\n";
      }
    }
  }

  // ---- kink data ----
  for (double alpha : {0.0, 0.25}) {
    const double beta = 0.2, lo = -1.0, hi = 1.0, t0 = 0.1;
    abel_operator<double> op(alpha, beta, lo, hi);
    auto F = [&](double s) { return std::abs(s - t0); };
    solve_options<double> reference_options;
    reference_options.degree = 2048;
    reference_options.residual_points = 0;
    const double reference =
        solve_piecewise(op, edge::bounded, edge::unbounded, F, {t0}, reference_options).density.integral_to(t0);
    for (std::size_t n : {16, 32, 64, 128, 256, 512}) {
      solve_options<double> options;
      options.degree = n;
      options.residual_points = 0;
      const auto sol = solve_piecewise(op, edge::bounded, edge::unbounded, F, {t0}, options);
      const double seconds = median_seconds([&] { (void)solve_piecewise(op, edge::bounded, edge::unbounded, F, {t0}, options); }, 5);
      out << "kink_partial," << alpha << "," << beta << ",0," << n << ","
          << std::abs(sol.density.integral_to(t0) - reference) / std::abs(reference) << ",nan," << seconds << "\n";
    }
    // The same kink built in (solve_kinks: F' jumps by 2 at t0) at 17, 33, 65 points and adaptive.
    const std::vector<kink<double>> kinks{{t0, 1, 2.0}};
    solve_options<double> fine;
    fine.degree = 257;
    fine.residual_points = 0;
    const double enriched_reference = solve_kinks(op, edge::bounded, edge::unbounded, F, kinks, fine).integral_to(t0);
    solve_options<double> projection;
    projection.degree = 4;
    projection.residual_points = 0;
    const double exact_integral = solve_piecewise(op, edge::bounded, edge::unbounded, F, {t0}, projection).density.integral();
    for (std::size_t n : {17, 33, 65, 0}) {
      solve_options<double> options;
      options.degree = n;
      options.residual_points = 0;
      const auto sol = solve_kinks(op, edge::bounded, edge::unbounded, F, kinks, options);
      const double seconds = median_seconds([&] { (void)solve_kinks(op, edge::bounded, edge::unbounded, F, kinks, options); }, 5);
      const double error = std::max(std::abs(sol.integral() - exact_integral) / std::abs(exact_integral),
                                    std::abs(sol.integral_to(t0) - enriched_reference) / std::abs(enriched_reference));
      out << "kink_enriched" << (n == 0 ? "_adaptive," : ",") << alpha << "," << beta << ",0," << sol.smooth.degree << ","
          << error << ",nan," << seconds << "\n";
    }
  }
  return 0;
}
