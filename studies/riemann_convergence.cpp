// study_riemann_convergence: accuracy against order of the Riemann-Hilbert solver
// (rhabel/riemann/abel_solver.hpp), and the step-data reference it provides to the spectral
// solvers (rhabel::abel::solve_piecewise, rhabel::abel::solve_step).
//
//  1. Wedge with an interior apex (docs/theory.md section 5: nu = -1, alpha + beta/2 < 1/2, step data
//     F = S1/Gamma(1-alpha) - (S1+S2)/Gamma(1-alpha) [s > 0], S2 from the orthogonality
//     condition): int_a^0 g by the RH route at orders n = 8..64, against its own value at
//     n = 96; then the spectral solver's int_a^0 g at degrees 16..1024 against that reference,
//     and solve_step (singular enrichment, adaptive) once.
//  2. Parabolic punch (closed form): |int_a^y g - closed form| / int g against the order n.
//  3. Parabolic punch density g(y) at y = a + 1e-6 L, a + 0.37 L, b - 1e-6 L against the closed
//     form, relative to max(|g(y)|, int g / L), against the order n (method column: the point).
//
// CSV on standard output: study,alpha,beta,method,order,value,error,error_estimate,seconds
// (error: against the closed form (parabola) or the n = 96 RH value (wedge)).
// Summary on standard error. Runs in ~10 s. Asserts nothing.
#include "rhabel/abel.hpp"
#include "rhabel/riemann.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>

#include <chrono>
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <vector>

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void row(const char* study, double alpha, double beta, const char* method, std::size_t order, double value,
         double error, double estimate, double seconds) {
  std::printf("%s,%.3f,%.3f,%s,%zu,%.17g,%.3e,%.3e,%.4f\n", study, alpha, beta, method, order, value, error, estimate,
              seconds);
}

// Parabolic punch f' = -x/R on [a, b] (docs/theory.md section 5, nu = -1): g = K (t-a)^gam (b-t)^del.
struct parabola {
  double alpha, beta, R = 1.3, L = 2.0;
  double pi = boost::math::constants::pi<double>();
  double b() const { return L * (1 - 2 * alpha - beta) / (2 * (1 - alpha)); }
  double a() const { return b() - L; }
  double gam() const { return (1 - 2 * alpha - beta) / 2; }
  double del() const { return (1 + beta) / 2; }
  double K() const { return std::cos(beta * pi / 2) / (pi * R * std::tgamma(2 - alpha)); }
  double total() const { return K() * std::pow(L, gam() + del() + 1) * boost::math::beta(gam() + 1, del() + 1); }
  double c() const { return 1 / (R * std::tgamma(1 - alpha)); }  // F(s) = -c s
};

}  // namespace

int main() {
  using namespace rhabel;
  std::printf("study,alpha,beta,method,order,value,error,error_estimate,seconds\n");

  // 1. wedge with an interior apex
  for (double alpha : {0.05, 0.3, 0.45})
    for (double beta : {0.0, 0.3}) {
      if (!(alpha + beta / 2 < 0.5)) continue;
      const double e = 0.4, L = 1.0, a = -e * L, b = a + L;
      const double I = boost::math::ibeta((1 + beta) / 2, (1 - 2 * alpha - beta) / 2, e);
      const double S1 = 1.0, S2 = S1 * I / (1 - I), G1 = std::tgamma(1 - alpha);
      const riemann::piecewise_function<double> F{[=](double) { return S1 / G1; },
                                                  {riemann::step<double>{0.0, -(S1 + S2) / G1}}};
      riemann::abel_rh_options<double> reference_options;
      reference_options.order = 96;
      const double reference = riemann::solve_abel_rh(alpha, beta, a, b, F, riemann::edge::bounded,
                                                      riemann::edge::bounded, reference_options)
                                   .integral(0.0)
                                   .value;
      for (std::size_t n : {8u, 12u, 16u, 24u, 32u, 48u, 64u}) {
        const auto start = std::chrono::steady_clock::now();
        riemann::abel_rh_options<double> options;
        options.order = n;
        const auto sol =
            riemann::solve_abel_rh(alpha, beta, a, b, F, riemann::edge::bounded, riemann::edge::bounded, options);
        const auto apex = sol.integral(0.0);
        row("wedge_int_a_0", alpha, beta, "riemann", n, apex.value, std::abs(apex.value - reference) / reference,
            apex.error_estimate / reference, seconds_since(start));
      }
      abel::abel_operator<double> op(alpha, beta, a, b);
      for (std::size_t M : {16u, 64u, 256u, 1024u}) {
        const auto start = std::chrono::steady_clock::now();
        abel::solve_options<double> options;
        options.degree = M;
        const auto sol = abel::solve_piecewise(op, abel::edge::bounded, abel::edge::bounded,
                                               [&](double s) { return F(s); }, std::vector<double>{0.0}, options);
        const double value = sol.density.integral_to(0.0);
        row("wedge_int_a_0", alpha, beta, "spectral", M, value, std::abs(value - reference) / reference, 0.0,
            seconds_since(start));
      }
      {
        const auto start = std::chrono::steady_clock::now();
        const auto sol = abel::solve_step(op, abel::edge::bounded, abel::edge::bounded, [&](double s) { return F(s); }, 0.0);
        const double value = sol.density.integral_to(0.0);
        row("wedge_int_a_0", alpha, beta, "spectral_step", sol.degree, value, std::abs(value - reference) / reference,
            0.0, seconds_since(start));
      }
      std::fprintf(stderr, "wedge alpha=%.2f beta=%.2f: int_a^0 g = %.17g (RH, n = 96)\n", alpha, beta, reference);
    }

  // 2. parabolic punch, closed form
  for (double alpha : {0.2, 0.6})
    for (double beta : {0.0, 0.5}) {
      const parabola P{alpha, beta};
      const double a = P.a(), b = P.b(), L = P.L, total = P.total(), c = P.c();
      const double y = a + 0.37 * L;
      const double exact = P.K() * std::pow(L, P.gam() + P.del() + 1) * boost::math::beta(P.gam() + 1, P.del() + 1, 0.37);
      for (std::size_t n : {4u, 6u, 8u, 12u, 16u, 24u, 32u}) {
        const auto start = std::chrono::steady_clock::now();
        riemann::abel_rh_options<double> options;
        options.order = n;
        const auto sol = riemann::solve_abel_rh(alpha, beta, a, b,
                                                riemann::piecewise_function<double>{[c](double x) { return -c * x; }, {}},
                                                riemann::edge::bounded, riemann::edge::bounded, options);
        const auto v = sol.integral(y);
        row("parabola_int_a_y", alpha, beta, "riemann", n, v.value, std::abs(v.value - exact) / total,
            v.error_estimate / total, seconds_since(start));
      }
    }

  // 3. parabolic punch, density near the ends and inside
  for (double alpha : {0.2, 0.6, 0.9})
    for (double beta : {0.0, 0.5}) {
      const parabola P{alpha, beta};
      const double a = P.a(), b = P.b(), L = P.L, total = P.total(), c = P.c();
      const struct {
        const char* name;
        double y;
      } points[] = {{"a+1e-6L", a + 1e-6 * L}, {"a+0.37L", a + 0.37 * L}, {"b-1e-6L", b - 1e-6 * L}};
      for (std::size_t n : {8u, 12u, 16u, 24u, 32u, 48u}) {
        riemann::abel_rh_options<double> options;
        options.order = n;
        const auto sol = riemann::solve_abel_rh(alpha, beta, a, b,
                                                riemann::piecewise_function<double>{[c](double x) { return -c * x; }, {}},
                                                riemann::edge::bounded, riemann::edge::bounded, options);
        for (const auto& point : points) {
          const auto start = std::chrono::steady_clock::now();
          const auto v = sol.density(point.y);
          const double exact = P.K() * std::pow(point.y - a, P.gam()) * std::pow(b - point.y, P.del());
          const double scale = std::max(std::abs(exact), total / L);
          row("parabola_density", alpha, beta, point.name, n, v.value, std::abs(v.value - exact) / scale,
              v.error_estimate / scale, seconds_since(start));
        }
      }
    }
  return 0;
}
