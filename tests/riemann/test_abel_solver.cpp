// Tests of rhabel/riemann/abel_solver.hpp: the generalized Abel equation (paper eq. 8) by the
// Riemann-Hilbert route. Oracles:
//  * the closed forms of notes section 5 (parabolic punch nu = -1 on both sides of
//    alpha + beta/2 = 1/2, wedge nu = 0, flat punch nu = +1) and the wedge orthogonality
//    condition I_eps((1+beta)/2, (1-2alpha-beta)/2) = S2/(S1+S2) (Boost's ibeta);
//  * an independent residual of eq. (8) in integrated form, computed from G(y) = int_a^y g
//    with Boost's tanh-sinh quadrature (shares no code with the solver):
//        int_s0^s1 F = [J_B(s0) - J_B(s1)] - kappa [J_A(s1) - J_A(s0)],
//        J_A(s) = int_a^s G(t) (s-t)^(alpha-1) dt,  J_B(s) = int_s^b (G(b) - G(t)) (t-s)^(alpha-1) dt
//    (integrate eq. (8) over [s0, s1] and integrate by parts once: no derivative of G needed);
//  * the spectral solver rhabel::abel (a different method: Jacobi expansion + spectral relation).
#include <doctest/doctest.h>

#include "rhabel/abel.hpp"
#include "rhabel/riemann/abel_solver.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using namespace rhabel::riemann;
using mp50 = boost::multiprecision::cpp_bin_float_50;

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
const double pi = boost::math::constants::pi<double>();

double kappa_of(double alpha, double beta) { return std::cos((alpha + beta / 2) * pi) / std::cos(beta * pi / 2); }

// Parabolic punch f' = -x/R, closed form of notes section 5 (any alpha, beta; class nu = -1).
struct parabola {
  double alpha, beta, R = 1.3, L = 2.0;
  double b() const { return L * (1 - 2 * alpha - beta) / (2 * (1 - alpha)); }
  double a() const { return b() - L; }
  double gam() const { return (1 - 2 * alpha - beta) / 2; }
  double del() const { return (1 + beta) / 2; }
  double K() const { return std::cos(beta * pi / 2) / (pi * R * std::tgamma(2 - alpha)); }
  double g(double t) const { return K() * std::pow(t - a(), gam()) * std::pow(b() - t, del()); }
  double G(double y) const {
    const double x = std::min(1.0, (y - a()) / L);  // (b - a)/L may round above 1
    return K() * std::pow(L, gam() + del() + 1) * boost::math::beta(gam() + 1, del() + 1, x);
  }
  piecewise_function<double> F() const {
    const double c = 1 / (R * std::tgamma(1 - alpha));
    return {[c](double x) { return -c * x; }, {}};
  }
};

// Independent residual of eq. (8) in integrated form over [s0, s1] (see file header), relative
// to int_s0^s1 |F|. G is any callable y -> int_a^y g; `breaks` are the steps of F.
template <class GFun>
double integrated_residual(double alpha, double beta, double a, double b, const piecewise_function<double>& F,
                           GFun&& G, double s0, double s1) {
  boost::math::quadrature::tanh_sinh<double> ts;
  const double tol = 1e-14;
  const double kappa = kappa_of(alpha, beta);
  const double total = G(b);
  std::vector<double> breaks;
  for (const auto& s : F.steps) breaks.push_back(s.position);
  auto integrate_split = [&](auto&& f, double lo, double hi, auto&& to_u) {
    // integrate f(u) over [lo, hi] splitting where a step of F maps into (lo, hi)
    std::vector<double> cuts{lo};
    for (double c : breaks) {
      const double u = to_u(c);
      if (u > lo && u < hi) cuts.push_back(u);
    }
    std::sort(cuts.begin(), cuts.end());
    cuts.push_back(hi);
    double sum = 0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) sum += ts.integrate(f, cuts[k], cuts[k + 1], tol);
    return sum;
  };
  auto JA = [&](double s) {  // int_0^{s-a} G(s-u) u^(alpha-1) du
    return integrate_split([&](double u) { return G(s - u) * std::pow(u, alpha - 1); }, 0.0, s - a,
                           [&](double c) { return s - c; });
  };
  auto JB = [&](double s) {  // int_0^{b-s} (total - G(s+u)) u^(alpha-1) du
    return integrate_split([&](double u) { return (total - G(s + u)) * std::pow(u, alpha - 1); }, 0.0, b - s,
                           [&](double c) { return c - s; });
  };
  const double lhs = integrate_split([&](double s) { return F(s); }, s0, s1, [](double c) { return c; });
  const double scale = integrate_split([&](double s) { return std::abs(F(s)); }, s0, s1, [](double c) { return c; });
  const double rhs = (JB(s0) - JB(s1)) - kappa * (JA(s1) - JA(s0));
  return std::abs(lhs - rhs) / scale;
}

abel_status status_of(const abel_rh_solution<double>& s) { return s.status(); }
}  // namespace

TEST_CASE("parabolic punch (nu = -1): closed form on both sides of alpha + beta/2 = 1/2") {
  // total and int_a^y g: a few eps (product integration + Gauss-Jacobi panels, two orders);
  // g(y): the Abel-inversion derivative form amplifies rounding of A~ near y by ~ d^(-alpha)
  // (d: distance of the nearest Gauss node to y), hence the alpha-dependent tolerance.
  constexpr double integral_tolerance = 32 * eps;
  for (double alpha : {0.0, 0.2, 0.45, 0.6, 0.8})
    for (double beta : {0.0, 0.3, 0.7}) {
      CAPTURE(alpha);
      CAPTURE(beta);
      const parabola P{alpha, beta};
      const auto sol = solve_abel_rh(alpha, beta, P.a(), P.b(), P.F(), edge::bounded, edge::bounded);
      CHECK(sol.index() == -1);
      const double loss = 1 / (1 - alpha);  // see "hard alphas" below
      CHECK(std::abs(sol.orthogonality_defect().value) <= 64 * eps * loss);
      CHECK(status_of(sol) == abel_status::converged);
      const double total = P.G(P.b());
      CHECK(std::abs(sol.total().value - total) <= integral_tolerance * total);
      for (double f : {1e-6, 0.1, 0.5, 0.93, 0.999}) {
        const double y = P.a() + f * P.L;
        CHECK(std::abs(sol.integral(y).value - P.G(y)) <= integral_tolerance * total);
      }
      // within 1e-7 of the trailing edge A~ mixes (b-x)^(n+alpha) terms whose rounding grows
      // like (b - y)^(n+alpha-1) eps: ~3 digits at alpha = 0.8 (documented weakness).
      CHECK(std::abs(sol.integral(P.a() + (1 - 1e-7) * P.L).value - P.G(P.a() + (1 - 1e-7) * P.L)) <=
            2e3 * eps * loss * total);
      const double density_tolerance = 2e3 * eps * loss * loss;
      for (double f : {0.05, 0.5, 0.9}) {
        const double y = P.a() + f * P.L;
        CHECK(std::abs(sol.density(y).value - P.g(y)) <= density_tolerance * std::max(std::abs(P.g(y)), total / P.L));
      }
    }
}

TEST_CASE("hard alphas: 1e-3, 0.5 -+ 1e-9 (kappa -> 0 through zero), 0.999") {
  for (double alpha : {1e-3, 0.5 - 1e-9, 0.5, 0.5 + 1e-9, 0.999}) {
    CAPTURE(alpha);
    const double beta = 0.0;
    const parabola P{alpha, beta};
    const auto sol = solve_abel_rh(alpha, beta, P.a(), P.b(), P.F(), edge::bounded, edge::bounded);
    const double total = P.G(P.b());
    // alpha -> 1: A~ = (sin(pi alpha)/pi) A is formed from O(1) boundary values that cancel to
    // O(1 - alpha): 1/(1 - alpha) is lost in int_a^y g and ~1/(1-alpha)^2 in g.
    const double loss = 1 / (1 - alpha);
    CHECK(std::abs(sol.total().value - total) <= 32 * eps * total);
    CHECK(std::abs(sol.orthogonality_defect().value) <= 64 * eps * loss);
    for (double f : {0.01, 0.4, 0.99}) {
      const double y = P.a() + f * P.L;
      CHECK(std::abs(sol.integral(y).value - P.G(y)) <= 64 * eps * loss * total);
      CHECK(std::abs(sol.density(y).value - P.g(y)) <= 2e3 * eps * loss * loss * loss * std::abs(P.g(y)));
    }
  }
}

TEST_CASE("wedge, alpha + beta/2 >= 1/2 (nu = 0, contact ends at the apex b = 0)") {
  for (double alpha : {0.5, 0.65, 0.9})
    for (double beta : {0.0, 0.4}) {
      CAPTURE(alpha);
      CAPTURE(beta);
      const double L = 1.5, a = -L, b = 0, S1 = 0.7;
      const double gam = (1 - 2 * alpha - beta) / 2, del = (beta - 1) / 2;
      const double K = S1 * std::cos(beta * pi / 2) / (pi * std::tgamma(1 - alpha));
      const double c = S1 / std::tgamma(1 - alpha);
      const auto sol = solve_abel_rh(alpha, beta, a, b, piecewise_function<double>{[c](double) { return c; }, {}},
                                     edge::bounded, edge::unbounded);
      CHECK(sol.index() == 0);
      const double total = K * std::pow(L, gam + del + 1) * boost::math::beta(gam + 1, del + 1);
      CHECK(std::abs(sol.total().value - total) <= 32 * eps * total);
      for (double f : {0.2, 0.7, 0.999}) {
        const double y = a + f * L;
        const double Gy = K * std::pow(L, gam + del + 1) * boost::math::beta(gam + 1, del + 1, f);
        CHECK(std::abs(sol.integral(y).value - Gy) <= 32 * eps * total);
        const double gy = K * std::pow(y - a, gam) * std::pow(b - y, del);
        CHECK(std::abs(sol.density(y).value - gy) <= 1e5 * eps / ((1 - alpha) * (1 - alpha)) * std::abs(gy));
      }
    }
}

TEST_CASE("wedge with an interior apex (nu = -1, step data): orthogonality condition and int_a^0 g") {
  // alpha + beta/2 < 1/2: a < 0 < b, F = S1/Gamma(1-alpha) for s < 0, -S2/Gamma(1-alpha) for s > 0.
  // With eps = -a/L the condition is I_eps((1+beta)/2, (1-2alpha-beta)/2) = S2/(S1+S2) (notes 5).
  for (double alpha : {0.05, 0.3})
    for (double beta : {0.0, 0.3}) {
      CAPTURE(alpha);
      CAPTURE(beta);
      const double e = 0.4, L = 1.0, a = -e * L, b = a + L;
      const double I = boost::math::ibeta((1 + beta) / 2, (1 - 2 * alpha - beta) / 2, e);
      const double S1 = 1.0, S2 = S1 * I / (1 - I), G1 = std::tgamma(1 - alpha);
      const piecewise_function<double> F{[=](double) { return S1 / G1; }, {step<double>{0.0, -(S1 + S2) / G1}}};
      const auto sol = solve_abel_rh(alpha, beta, a, b, F, edge::bounded, edge::bounded);
      CHECK(std::abs(sol.orthogonality_defect().value) <= 64 * eps);
      CHECK(status_of(sol) == abel_status::converged);
      // a different S2 violates the condition and is reported
      const piecewise_function<double> F2{[=](double) { return S1 / G1; }, {step<double>{0.0, -(S1 + 2 * S2) / G1}}};
      const auto sol2 = solve_abel_rh(alpha, beta, a, b, F2, edge::bounded, edge::bounded);
      CHECK(std::abs(sol2.orthogonality_defect().value) > 1e-3);
      CHECK(status_of(sol2) == abel_status::orthogonality_not_satisfied);
      // int_a^0 g: the two orders agree to rounding (the log singularity of A~ at the apex is
      // integrated exactly), and the result solves eq. (8) (independent residual)
      const auto apex = sol.integral(0.0);
      CHECK(apex.error_estimate <= 16 * eps * apex.value);
      if (alpha == 0.3 && beta == 0.0) {  // one case: the residual costs ~2 s
        // order 16 is already converged for this data (studies/riemann_convergence.cpp)
        abel_rh_options<double> options;
        options.order = 16;
        const auto cheap = solve_abel_rh(alpha, beta, a, b, F, edge::bounded, edge::bounded, options);
        CHECK(std::abs(cheap.integral(0.0).value - apex.value) <= 16 * eps * apex.value);
        auto G = [&](double y) { return cheap.integral(y).value; };
        CHECK(integrated_residual(alpha, beta, a, b, F, G, -0.05, 0.1) <= 1e-12);  // spans the apex
      }
      // the spectral solver converges algebraically for step data: agreement to its accuracy
      rhabel::abel::abel_operator<double> op(alpha, beta, a, b);
      const auto spectral = rhabel::abel::solve_piecewise(op, rhabel::abel::edge::bounded, rhabel::abel::edge::bounded,
                                                          [&](double s) { return F(s); }, std::vector<double>{0.0});
      CHECK(std::abs(spectral.density.integral() - sol.total().value) <= 1e-12 * sol.total().value);
      // (its int_a^0 g converges like a power of the degree: ~1e-2 at its default degree 256)
      CHECK(std::abs(spectral.density.integral_to(0.0) - apex.value) <= 2e-2 * apex.value);
    }
}

TEST_CASE("flat punch (nu = +1): F = 0 gives C g_h with int g = load") {
  for (double alpha : {0.1, 0.3})
    for (double beta : {0.0, 0.3}) {
      abel_rh_options<double> options;
      options.load = 2.0;
      const auto sol = solve_abel_rh(alpha, beta, -1.0, 1.0, piecewise_function<double>{[](double) { return 0.0; }, {}},
                                     edge::unbounded, edge::unbounded, options);
      CHECK(sol.index() == 1);
      CHECK(sol.total().value == doctest::Approx(2.0).epsilon(8 * eps));
      // g = C (t-a)^(-(1+2alpha+beta)/2) (b-t)^((beta-1)/2), C = load / (L^-alpha B(..))
      const double C = 2.0 / (std::pow(2.0, -alpha) * boost::math::beta((1 - 2 * alpha - beta) / 2, (1 + beta) / 2));
      for (double y : {-0.9, 0.0, 0.7})
        CHECK(sol.density(y).value ==
              doctest::Approx(C * std::pow(y + 1, -(1 + 2 * alpha + beta) / 2) * std::pow(1 - y, (beta - 1) / 2))
                  .epsilon(16 * eps));
    }
}

TEST_CASE("smooth data, every index class: agreement with rhabel::abel and the independent residual") {
  // F(s) = exp(s/2) - s^2 + 0.3 + lambda; for nu = -1 lambda is chosen with the SPECTRAL solver's
  // defect (linear in F) so that F satisfies the orthogonality condition, then both solvers are
  // compared (and the RH defect must vanish too: a cross-check of the two defects).
  const double a = -0.8, b = 1.3;
  auto F0 = [](double s) { return std::exp(0.5 * s) - s * s + 0.3; };
  for (double alpha : {0.2, 0.45, 0.7})
    for (double beta : {0.0, 0.35})
      for (int cls = 0; cls < 4; ++cls) {
        const edge lead = (cls & 1) ? edge::unbounded : edge::bounded;
        const edge trail = (cls & 2) ? edge::unbounded : edge::bounded;
        if (lead == edge::unbounded && alpha + beta / 2 >= 0.5) continue;
        CAPTURE(alpha);
        CAPTURE(beta);
        CAPTURE(cls);
        const auto a_lead = lead == edge::bounded ? rhabel::abel::edge::bounded : rhabel::abel::edge::unbounded;
        const auto a_trail = trail == edge::bounded ? rhabel::abel::edge::bounded : rhabel::abel::edge::unbounded;
        rhabel::abel::abel_operator<double> op(alpha, beta, a, b);
        double lambda = 0;
        if (cls == 0) {
          const double d0 = rhabel::abel::solve(op, a_lead, a_trail, F0).solvability_defect;
          const double d1 = rhabel::abel::solve(op, a_lead, a_trail, [](double) { return 1.0; }).solvability_defect;
          lambda = -d0 / d1;
        }
        auto Ff = [&](double s) { return F0(s) + lambda; };
        abel_rh_options<double> options;
        rhabel::abel::solve_options<double> spectral_options;
        if (cls == 3) options.load = spectral_options.load = 1.7;
        const piecewise_function<double> F{Ff, {}};
        const auto rh = solve_abel_rh(alpha, beta, a, b, F, lead, trail, options);
        const auto spectral = rhabel::abel::solve(op, a_lead, a_trail, Ff, spectral_options);
        const auto g = cls == 3 ? spectral.with_load(1.7) : spectral.density;
        const double total = std::abs(g.integral());
        if (cls == 0) CHECK(std::abs(rh.orthogonality_defect().value) <= 1e-13);
        CHECK(std::abs(rh.total().value - g.integral()) <= 1e-14 * total);
        for (double y : {-0.79, -0.5, 0.1, 0.9, 1.25, 1.299})
          CHECK(std::abs(rh.integral(y).value - g.integral_to(y)) <= 1e-13 * total);
        for (double y : {-0.5, 0.1, 0.9}) {
          // density: see the parabola test for the alpha-dependent loss of the derivative form
          const double tolerance = alpha < 0.5 ? 2e-13 : 2e-11;
          CHECK(std::abs(rh.density(y).value - g(y)) <= tolerance * std::max(std::abs(g(y)), total / (b - a)));
        }
        if (alpha == 0.45) {
          auto G = [&](double y) { return rh.integral(y).value; };
          CHECK(integrated_residual(alpha, beta, a, b, F, G, -0.7, -0.2) <= 1e-12);
          CHECK(integrated_residual(alpha, beta, a, b, F, G, 0.4, 1.2) <= 1e-12);
        }
      }
}

TEST_CASE("parabolic punch at 50 digits") {
  const mp50 alpha = mp50(3) / 10, beta = mp50(1) / 5, R = 1, L = 2;
  const mp50 pi50 = boost::math::constants::pi<mp50>();
  const mp50 b = L * (1 - 2 * alpha - beta) / (2 * (1 - alpha)), a = b - L;
  const mp50 gam = (1 - 2 * alpha - beta) / 2, del = (1 + beta) / 2;
  const mp50 K = cos(beta * pi50 / 2) / (pi50 * R * boost::math::tgamma(2 - alpha));
  const mp50 c = 1 / (R * boost::math::tgamma(1 - alpha));
  const auto sol = solve_abel_rh(alpha, beta, a, b, piecewise_function<mp50>{[c](mp50 x) { return -c * x; }, {}},
                                 edge::bounded, edge::bounded);
  const mp50 total = K * pow(L, gam + del + 1) * boost::math::beta(gam + 1, del + 1);
  const mp50 tolerance = 1e-45;  // 50-digit arithmetic, a few digits for the quadrature
  CHECK(abs(sol.total().value - total) <= tolerance * total);
  const mp50 y = a + L * 3 / 10;
  const mp50 Gy = K * pow(L, gam + del + 1) * boost::math::beta(gam + 1, del + 1, mp50(3) / 10);
  CHECK(abs(sol.integral(y).value - Gy) <= tolerance * total);
  CHECK(abs(sol.orthogonality_defect().value) <= tolerance);
}

TEST_CASE("solve_abel_rh rejects bad input, naming parameter, value and range") {
  const piecewise_function<double> F{[](double s) { return s; }, {}};
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::domain_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(message([&] { solve_abel_rh(1.0, 0.0, -1.0, 1.0, F, edge::bounded, edge::bounded); }).find("alpha = 1") !=
        std::string::npos);
  CHECK(message([&] { solve_abel_rh(0.3, -0.1, -1.0, 1.0, F, edge::bounded, edge::bounded); }).find("beta") !=
        std::string::npos);
  CHECK(message([&] { solve_abel_rh(0.3, 0.0, 1.0, -1.0, F, edge::bounded, edge::bounded); }).find("b = -1") !=
        std::string::npos);
  // the class unbounded at the leading edge does not exist for alpha + beta/2 >= 1/2
  CHECK(message([&] { solve_abel_rh(0.6, 0.0, -1.0, 1.0, F, edge::unbounded, edge::bounded); }).find("alpha + beta/2") !=
        std::string::npos);
  const auto sol = solve_abel_rh(0.3, 0.0, -1.0, 1.0, F, edge::bounded, edge::unbounded);
  CHECK(message([&] { sol.integral(1.5); }).find("y = 1.5") != std::string::npos);
  CHECK(message([&] { sol.density(-1.0); }).find("y = -1") != std::string::npos);
}
