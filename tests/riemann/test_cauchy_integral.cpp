// Tests of rhabel/riemann/cauchy_integral.hpp and its special function K(q, rho)
// (detail/power_cauchy.hpp). The Gauss-Jacobi rules they use are rhabel::quadrature::gauss_jacobi,
// tested in tests/quadrature.
// Oracles: closed forms (elementary antiderivatives, Beta functions, the Cauchy integral of
// (1-t)^p (1+t)^(-1-p) from Liouville's theorem), never the code under test.
#include <doctest/doctest.h>

#include "rhabel/quadrature/cauchy_transform.hpp"
#include "rhabel/riemann/cauchy_integral.hpp"
#include "riemann/support.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

using rhabel::riemann::jacobi_cauchy_integral;
using rhabel::riemann::piecewise_function;
using rhabel::riemann::step;
using rhabel::riemann::detail::power_cauchy;
using cplx = std::complex<double>;
using mp50 = boost::multiprecision::cpp_bin_float_50;

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
const double pi = boost::math::constants::pi<double>();

double relative(double value, double reference) { return std::abs(value - reference) / std::max(1.0, std::abs(reference)); }
double relative(cplx value, cplx reference) { return std::abs(value - reference) / std::max(1.0, std::abs(reference)); }
}  // namespace

TEST_CASE("power_cauchy K(q, rho) matches elementary closed forms") {
  constexpr double tolerance = 8 * eps;  // series/quadrature to full precision, a few roundings
  // q = 0: K = log|1 - rho| - log|rho| (PV for 0 < rho < 1)
  const power_cauchy<double> k0(0.0);
  for (double rho : {-3.0, -0.7, -0.2, 0.1, 0.45, 0.55, 0.8, 0.999, 1.001, 1.6, 2.5, 40.0})
    CHECK(relative(k0.principal_value(rho), std::log(std::abs(1 - rho)) - std::log(std::abs(rho))) <= tolerance);
  // q = -1/2 (v = u^2): K = (1/sqrt rho) log|(1 - sqrt rho)/(1 + sqrt rho)| for rho > 0, and
  // (2/sqrt|rho|) atan(1/sqrt|rho|) for rho < 0.
  const power_cauchy<double> kh(-0.5);
  for (double rho : {0.05, 0.3, 0.5, 0.6, 0.95, 0.999999, 1.000001, 1.2, 1.9, 2.1, 30.0}) {
    const double s = std::sqrt(rho);
    // |1 - s| = |1 - rho|/(1 + s): no cancellation in the reference near rho = 1
    CHECK(relative(kh.principal_value(rho), (std::log(std::abs(1 - rho)) - 2 * std::log1p(s)) / s) <= tolerance);
  }
  for (double rho : {-0.1, -0.6, -1.5, -9.0}) {
    const double s = std::sqrt(-rho);
    CHECK(relative(kh.principal_value(rho), 2 * std::atan(1 / s) / s) <= tolerance);
  }
  // complex rho, q = -1/2: K = 2 int_0^1 du/(u^2 - z) = (1/s)[log(1-s) - log(1+s) - log(-s) + log(s)],
  // s = sqrt(z) principal (Im s != 0: the logs stay on their principal sheets along u in [0,1]).
  for (cplx z : {cplx(0.3, 0.2), cplx(0.8, -0.3), cplx(-1, 1), cplx(1.0, 1e-3), cplx(0.5, -1e-6), cplx(3, 4)}) {
    // reference in long double (the four logarithms cancel to ~1e-3 near z = 1); 1 - s = (1 - z)/(1 + s)
    using lcplx = std::complex<long double>;
    const lcplx zl(z.real(), z.imag()), s = std::sqrt(zl);
    const lcplx reference = (std::log((1.0L - zl) / (1.0L + s)) - std::log(1.0L + s) - std::log(-s) + std::log(s)) / s;
    CHECK(relative(kh(z), cplx(static_cast<double>(reference.real()), static_cast<double>(reference.imag()))) <= tolerance);
  }
  // q = 1/2: K = 2 int_0^1 u^2/(u^2 - rho) du = 2 + rho K(-1/2, rho)
  const power_cauchy<double> k12(0.5);
  for (double rho : {-2.0, 0.2, 0.7, 1.3, 5.0})
    CHECK(relative(k12.principal_value(rho), 2 + rho * kh.principal_value(rho)) <= tolerance);
}

TEST_CASE("power_cauchy is continuous through q = 0 (the kappa = 0 case of the solver)") {
  // K(q, rho) - K(0, rho) = q int_0^1 log(v)/(v - rho) dv + O(q^2): for q = 1e-9 the difference
  // is ~1e-9 times an O(1) number, so the formula has no 1/q cancellation.
  for (double rho : {0.3, 0.7, -0.4, 1.5, 3.0}) {
    const double k0 = power_cauchy<double>(0.0).principal_value(rho);
    const double kp = power_cauchy<double>(1e-9).principal_value(rho);
    const double km = power_cauchy<double>(-1e-9).principal_value(rho);
    CHECK(std::abs(kp - k0) < 1e-8);
    CHECK(std::abs(km - k0) < 1e-8);
    // symmetric difference is O(q^2): the first-order terms cancel to rounding
    CHECK(std::abs((kp - k0) + (km - k0)) <= 64 * eps * std::max(1.0, std::abs(k0)));
  }
}

TEST_CASE("jacobi_cauchy_integral: p + q = -1, h polynomial, against the closed form") {
  // For -1 < p < 0, f(z) = ((z-1)/(z+1))^p / (z+1) (principal power of the ratio: cut [-1, 1])
  // jumps by 2 i sin(pi p) (1-x)^p (1+x)^(-1-p) and decays like 1/z, so
  //   C[w](z) = int w/(t - z) dt = pi f(z) / sin(pi p),   PV = pi cot(pi p) w(x),
  // and for h(t) = 1 + 2t:  C[w h](z) = (1 + 2z) C[w](z) + 2 int w = (1+2z) C[w](z) - 2 pi/sin(pi p).
  constexpr double tolerance = 64 * eps;  // condition ~ int |w|/|t - x|: O(10) for these x
  for (double p : {-0.9, -0.5, -0.23}) {
    const double q = -1 - p;
    piecewise_function<double> h{[](double t) { return 1 + 2 * t; }, {}};
    jacobi_cauchy_integral<double> C(-1.0, 1.0, p, q, h);
    for (double x : {-0.97, -0.5, 0.0, 0.31, 0.5, 0.999}) {
      const double w = std::pow(1 - x, p) * std::pow(1 + x, q);
      const double reference = (1 + 2 * x) * pi / std::tan(pi * p) * w - 2 * pi / std::sin(pi * p);
      // the PV's condition number is ~ int |w h|/|t - x| ~ 1 + w(x)|h(x)| (1 + |log(1 -+ x)|)
      const double condition = 1 + std::abs(reference) + w * std::abs(1 + 2 * x) * (1 + std::abs(std::log(1 - x * x)));
      CHECK(std::abs(C.principal_value(x) - reference) <= tolerance * condition);
      CHECK(std::abs(C.plemelj_plus(x).imag() - pi * w * (1 + 2 * x)) <= tolerance * (1 + pi * w));
    }
    for (cplx z : {cplx(0.3, 0.5), cplx(0.3, 1e-4), cplx(-1.2, 0.0), cplx(2.0, -0.1), cplx(0.999, -0.01), cplx(50, 50)}) {
      const cplx f = std::pow((z - 1.0) / (z + 1.0), p) / (z + 1.0);
      const cplx reference = (1.0 + 2.0 * z) * pi * f / std::sin(pi * p) - 2 * pi / std::sin(pi * p);
      CHECK(relative(C.transform(z), reference) <= tolerance);
    }
    // int w = B(p+1, -p) = -pi/sin(pi p), int w t = 2 B(p+1, 1-p) - int w = (2 pi p + pi)/sin(pi p)
    CHECK(relative(C.moment(), pi * (1 + 4 * p) / std::sin(pi * p)) <= tolerance);
  }
}

TEST_CASE("jacobi_cauchy_integral 1e-7 and 1e-10 from an end: PV to full precision (regression)") {
  // p = q = -1/2, h = 1 + 2t: PV = pi cot(-pi/2) w h + 2 pi = 2 pi exactly (closed form above),
  // while w(x) ~ 2e3..7e4 there. Regression: the piece touching the OTHER end must not take the
  // singularity subtraction (evaluating its phi, which carries that end's factor (x - lo)^q or
  // (hi - x)^p, at x loses ~eps w(x)), and K(-1/2, rho) must not cancel two rho^(-1/2) terms.
  constexpr double tolerance = 64 * eps;  // sums of ~n O(1) terms (measured 24 eps at 1 - 1e-10)
  piecewise_function<double> h{[](double t) { return 1 + 2 * t; }, {}};
  jacobi_cauchy_integral<double> C(-1.0, 1.0, -0.5, -0.5, h);
  for (double x : {-1 + 1e-7, -1 + 1e-10, 1 - 1e-7, 1 - 1e-10}) {
    CAPTURE(x);
    CHECK(std::abs(C.principal_value(x) - 2 * pi) <= tolerance * 2 * pi);
  }
}

TEST_CASE("jacobi_cauchy_integral: step data on [lo, hi] against elementary antiderivatives") {
  // p = -1/2 at hi, q = 0: PV int_c^hi (hi-t)^(-1/2)/(t - x) dt with u = sqrt(hi - t):
  //   = (1/r) log| (r + U)/(r - U) |,  r = sqrt(hi - x), U = sqrt(hi - c).
  constexpr double tolerance = 64 * eps;
  const double lo = -0.5, hi = 1.5;
  for (double c : {-0.49, 0.0, 0.7, 1.49}) {
    piecewise_function<double> h{nullptr, {step<double>{c, 2.5}}};
    jacobi_cauchy_integral<double> C(lo, hi, -0.5, 0.0, h);
    const double U = std::sqrt(hi - c);
    for (double x : {-0.4999, -0.3, c - 1e-9, c - 1e-3, c + 1e-7, 0.9, 1.4999}) {
      if (!(x > lo && x < hi)) continue;
      const double r = std::sqrt(hi - x);
      // r - U = (c - x)/(r + U): no cancellation near the step
      const double reference = 2.5 * std::log((r + U) * (r + U) / std::abs(c - x)) / r;
      const double condition = 1 + std::abs(reference) + 2.5 / r;  // w(x) |h| near hi (see above)
      CHECK(std::abs(C.principal_value(x) - reference) <= tolerance * condition);
    }
    CHECK(relative(C.moment(), 2.5 * 2 * U) <= tolerance);
  }
}

TEST_CASE("jacobi_cauchy_integral agrees with the graded quadrature of rhabel::quadrature") {
  // Two independent methods (product integration with subtraction here; composite graded
  // Gauss rules without subtraction in quadrature/cauchy_transform.hpp, which normalises by 1/pi).
  constexpr double tolerance = 256 * eps;  // both a few eps times the condition number
  auto h = [](double t) { return std::cos(2 * t) + t; };
  for (double p : {-0.7, 0.0, 1e-9, 0.4, 1.5})
    for (double q : {-0.5, 0.25, 0.9}) {
      jacobi_cauchy_integral<double> C(-1.0, 1.0, p, q, piecewise_function<double>{h, {}});
      for (double x : {-0.999, -0.6, 0.0, 0.3, 0.77, 0.999}) {
        const auto other = rhabel::quadrature::cauchy_principal_value(h, p, q, x);
        const double condition = 1 + std::abs(C.density(x)) * (1 + std::abs(std::log(1 - x * x)));
        CHECK(std::abs(C.principal_value(x) - pi * other.value) <= tolerance * condition);
      }
    }
}

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("jacobi_cauchy_integral at 50 digits: p + q = -1 closed form") {
  const mp50 tolerance = 1e-45;  // 50-digit arithmetic, a few digits for the condition number
  const mp50 p = mp50(-3) / 7, q = -1 - p;
  const mp50 pi50 = boost::math::constants::pi<mp50>();
  piecewise_function<mp50> h{[](mp50 t) { return 1 + 2 * t; }, {}};
  jacobi_cauchy_integral<mp50> C(mp50(-1), mp50(1), p, q, h);
  for (const mp50& x : {mp50(-0.9), mp50(0), mp50(0.4), mp50(0.99)}) {
    const mp50 w = pow(1 - x, p) * pow(1 + x, q);
    const mp50 reference = (1 + 2 * x) * pi50 / tan(pi50 * p) * w - 2 * pi50 / sin(pi50 * p);
    CHECK(abs(C.principal_value(x) - reference) <= tolerance * (1 + abs(reference)));
  }
}
#endif  // RHABEL_TEST_MULTIPRECISION

TEST_CASE("jacobi_cauchy_integral rejects bad input, naming the parameter") {
  piecewise_function<double> h{[](double t) { return t; }, {}};
  auto message = [](auto&& f) { return rhabel::riemann::test::domain_error_message(f); };
  CHECK(message([&] { jacobi_cauchy_integral<double>(1.0, 0.0, 0.0, 0.0, h); }).find("hi") != std::string::npos);
  CHECK(message([&] { jacobi_cauchy_integral<double>(0.0, 1.0, -1.0, 0.0, h); }).find("p = -1") != std::string::npos);
  CHECK(message([&] { jacobi_cauchy_integral<double>(0.0, 1.0, 0.0, std::nan(""), h); }).find("q") != std::string::npos);
  piecewise_function<double> bad_step{nullptr, {step<double>{2.0, 1.0}}};
  CHECK(message([&] { jacobi_cauchy_integral<double>(0.0, 1.0, 0.0, 0.0, bad_step); }).find("step position") !=
        std::string::npos);
  jacobi_cauchy_integral<double> C(0.0, 1.0, 0.2, -0.3, h);
  CHECK(message([&] { C.principal_value(1.0); }).find("x = 1") != std::string::npos);
  CHECK(message([&] { C.transform(cplx(0.5, 0.0)); }).find("z") != std::string::npos);
  CHECK_THROWS_AS(power_cauchy<double>(1.0), std::domain_error);
}
