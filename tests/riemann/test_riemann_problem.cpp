// Tests of rhabel/riemann/riemann_problem.hpp: Phi_+ = G Phi_- + g1 on a segment.
// Oracle: when the exponents of rho = g1/X_+ add up to -1 the Cauchy integral has the closed
// form pi f(z)/sin(pi p), f = ((z-1)/(z+1))^p/(z+1) (Liouville), so Phi is known in closed form;
// the closed form itself is checked against the boundary relation (the theory), and the solver
// against the closed form. For general data: boundary relation, far field, index classes.
#include <doctest/doctest.h>

#include "rhabel/riemann/riemann_problem.hpp"
#include "riemann/support.hpp"

#include <boost/math/constants/constants.hpp>

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

using namespace rhabel::riemann;
using cplx = std::complex<double>;

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
const double pi = boost::math::constants::pi<double>();
const cplx I(0, 1);

// Closed-form Phi for [lo, hi] = [-1, 1], index 0 bounded at hi, theta = 0.2, g1 = c1 (1+x)^-0.3 (1-x)^-0.7:
// n = theta, m = -theta, rho = c1 e^{-i pi n} (1-t)^p (1+t)^q with p = -0.7 - n = -0.9, q = -0.3 - m = -0.1.
struct closed_form {
  double theta = 0.2;
  cplx c1 = cplx(0.7, -1.3);
  double p = -0.9, q = -0.1;
  cplx k() const { return c1 * std::exp(-I * pi * theta) / (2 * pi * I); }
  cplx X(cplx z) const { return std::pow(z + 1.0, -theta) * std::pow(z - 1.0, theta); }
  cplx cauchy(cplx z) const { return pi * std::pow((z - 1.0) / (z + 1.0), p) / (z + 1.0) / std::sin(pi * p); }
  cplx phi(cplx z) const { return X(z) * k() * cauchy(z); }
  double w(double x) const { return std::pow(1 - x, p) * std::pow(1 + x, q); }
  cplx X_plus(double x) const { return std::pow(1 + x, -theta) * std::pow(1 - x, theta) * std::exp(I * pi * theta); }
  cplx X_minus(double x) const { return std::pow(1 + x, -theta) * std::pow(1 - x, theta) * std::exp(-I * pi * theta); }
  cplx phi_plus(double x) const { return X_plus(x) * k() * (pi / std::tan(pi * p) * w(x) + I * pi * w(x)); }
  cplx phi_minus(double x) const { return X_minus(x) * k() * (pi / std::tan(pi * p) * w(x) - I * pi * w(x)); }
  cplx g1(double x) const { return c1 * std::pow(1 + x, -0.3) * std::pow(1 - x, -0.7); }
  cplx G() const { return std::exp(2 * pi * I * theta); }
};

riemann_problem<double> closed_form_problem() {
  riemann_problem<double> problem;
  problem.lo = -1;
  problem.hi = 1;
  problem.theta = 0.2;
  problem.data_factor = cplx(0.7, -1.3);
  problem.data_exponent_lo = -0.3;
  problem.data_exponent_hi = -0.7;
  problem.data = piecewise_function<double>{[](double) { return 1.0; }, {}};
  return problem;
}

double scale_of(cplx v) { return std::max(1.0, std::abs(v)); }
}  // namespace

TEST_CASE("closed form: the boundary relation holds (checks the theory, not the code)") {
  const closed_form cf;
  for (double x : {-0.9, -0.3, 0.0, 0.45, 0.8}) {
    const cplx residual = cf.phi_plus(x) - cf.G() * cf.phi_minus(x) - cf.g1(x);
    CHECK(std::abs(residual) <= 32 * eps * scale_of(cf.g1(x)));
    // and the closed-form boundary values are the limits of the closed-form Phi
    CHECK(std::abs(cf.phi(cplx(x, 1e-9)) - cf.phi_plus(x)) <= 1e-7 * scale_of(cf.phi_plus(x)));
    CHECK(std::abs(cf.phi(cplx(x, -1e-9)) - cf.phi_minus(x)) <= 1e-7 * scale_of(cf.phi_minus(x)));
  }
}

TEST_CASE("solve_riemann_problem reproduces the closed form (index 0, bounded at hi)") {
  constexpr double tolerance = 64 * eps;  // the Cauchy integral's accuracy (test_cauchy_integral)
  const closed_form cf;
  const auto solution = solve_riemann_problem(closed_form_problem(), 0, bounded_end::hi);
  CHECK(solution.canonical().exponent_hi == doctest::Approx(0.2));
  CHECK(solution.canonical().exponent_lo == doctest::Approx(-0.2));
  for (cplx z : {cplx(0.2, 0.3), cplx(-0.9, -0.05), cplx(1.5, 0.0), cplx(-3.0, 0.0), cplx(0.5, 1e-5), cplx(20, -7)})
    CHECK(std::abs(solution(z) - cf.phi(z)) <= tolerance * scale_of(cf.phi(z)));
  for (double x : {-0.95, -0.3, 0.0, 0.45, 0.8, 0.999}) {
    const auto [plus, minus] = solution.boundary_values(x);
    const double condition = 1 + cf.w(x);
    CHECK(std::abs(plus - cf.phi_plus(x)) <= tolerance * condition * scale_of(cf.phi_plus(x)));
    CHECK(std::abs(minus - cf.phi_minus(x)) <= tolerance * condition * scale_of(cf.phi_minus(x)));
    CHECK(std::abs(solution.plus(x) - plus) <= 4 * eps * scale_of(plus));
  }
}

TEST_CASE("general data, every index class: boundary relation, far field, orthogonality") {
  constexpr double tolerance = 256 * eps;
  riemann_problem<double> problem;
  problem.lo = -0.4;
  problem.hi = 1.1;
  problem.theta = 0.65;
  problem.data_factor = cplx(1.0, 0.5);
  problem.data_exponent_lo = 0.0;
  problem.data_exponent_hi = -0.25;
  problem.data = piecewise_function<double>{[](double t) { return std::cos(2 * t) + t; }, {step<double>{0.3, -0.8}}};
  const cplx G = std::exp(2 * pi * I * problem.theta);
  struct class_case {
    int index;
    bounded_end end;
  };
  for (const class_case cc : {class_case{-1, bounded_end::hi}, class_case{0, bounded_end::hi},
                              class_case{0, bounded_end::lo}, class_case{1, bounded_end::hi}}) {
    CAPTURE(cc.index);
    const cplx constant = cc.index == 1 ? cplx(0.3, -0.2) : cplx(0);
    const auto solution = solve_riemann_problem(problem, cc.index, cc.end, constant);
    const auto& X = solution.canonical();
    CHECK(X.exponent_lo + X.exponent_hi == doctest::Approx(-cc.index));
    for (double x : {-0.35, 0.0, 0.29, 0.31, 0.7, 1.05}) {
      const auto [plus, minus] = solution.boundary_values(x);
      const cplx g1 = problem.data_factor * std::pow(problem.hi - x, problem.data_exponent_hi) * problem.data(x);
      CHECK(std::abs(plus - G * minus - g1) <= tolerance * (std::abs(plus) + std::abs(minus) + std::abs(g1)));
      // X_+ / X_- = G  (branch convention of the canonical function)
      CHECK(std::abs(X.plus(x) / X.minus(x) - G) <= 8 * eps);
      // the limit of Phi from above is Phi_+  (Phi continuous up to the cut away from the step)
      if (std::abs(x - 0.3) > 0.05)
        CHECK(std::abs(solution(cplx(x, 1e-7)) - plus) <= 1e-5 * scale_of(plus));
    }
    // far field: Phi(z) ~ X(z) [-(1/(2 pi i)) int rho / z + C] with X ~ z^(-index)
    const cplx z(3e6, 1e6);
    const cplx defect = solution.orthogonality_defect();  // (1/(2 pi i)) int rho
    const cplx leading = cc.index == 1 ? constant / z : (cc.index == 0 ? -defect / z : -defect);
    CHECK(std::abs(solution(z) - leading) <= 1e-5 * std::abs(leading));
  }
}

TEST_CASE("index -1: the solution vanishes at infinity exactly when the orthogonality condition holds") {
  // data h = 1 + lambda t on [-1, 1] with r_lo = r_hi = 0, theta = 0.3: rho ~ (1-t)^(-0.3) (1+t)^(-0.7)
  // (p + q = -1): int rho = 0 for lambda = -int w / int w t = -(-pi/sin(pi p)) / (pi (1 + 2p)/sin(pi p)).
  const double p = -0.3;
  const double lambda = 1.0 / (1 + 2 * p);
  riemann_problem<double> problem{-1.0, 1.0, 0.3, cplx(1, 0), 0.0, 0.0,
                                  piecewise_function<double>{[lambda](double t) { return 1 + lambda * t; }, {}}};
  const auto solution = solve_riemann_problem(problem, -1);
  CHECK(std::abs(solution.orthogonality_defect()) <= 64 * eps);
  const cplx far = solution(cplx(1e5, 2e5));
  CHECK(std::abs(far) <= 1e-4);  // O(1/z)
  problem.data.smooth = [](double t) { return 1 + t; };
  CHECK(std::abs(solve_riemann_problem(problem, -1).orthogonality_defect()) > 0.1);
}

TEST_CASE("riemann problem: bad input names the parameter") {
  auto message = [](auto&& f) { return rhabel::riemann::test::domain_error_message(f); };
  auto problem = closed_form_problem();
  CHECK(message([&] { solve_riemann_problem(problem, 2); }).find("index") != std::string::npos);
  problem.theta = 1.0;
  CHECK(message([&] { solve_riemann_problem(problem, 0); }).find("theta") != std::string::npos);
  problem = closed_form_problem();
  problem.data_exponent_hi = -1.5;
  CHECK(message([&] { solve_riemann_problem(problem, 0); }).find("integrable") != std::string::npos);
  CHECK(message([&] { make_canonical_function(1.0, 0.0, 0.5, 0); }).find("hi") != std::string::npos);
}
