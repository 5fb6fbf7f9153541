// Tests of rhabel/quadrature/cauchy_transform.hpp.
// Oracles: the committed 40-digit table tests/data/cauchy_reference.hpp (Boost tanh-sinh with
// pole subtraction in cpp_bin_float_50, tools/reference/cauchy_abel_reference.cpp), the
// hypergeometric closed form of the weight's principal value (derived in the header of
// this test, evaluated with boost::math::hypergeometric_pFq), Chebyshev closed forms, and the
// Plemelj limits against the transform at distance 1e-13 from the cut.
#include <doctest/doctest.h>

#include <rhabel/quadrature.hpp>

#include "data/cauchy_reference.hpp"
#include "quadrature/support.hpp"

#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/hypergeometric_pFq.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <cstdlib>
#include <complex>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rq = rhabel::quadrature;
using bf50 = boost::multiprecision::cpp_bin_float_50;
using cd = std::complex<double>;
using rhabel_test::eps;
using rhabel_test::h_poly;
using rhabel_test::pi;
using rhabel_test::table_series_coefficients;

namespace {

// Scale of the problem for relative errors: |value| + |w(x) h(x)| (the PV behaves like
// w h log near the ends) + int w |h| (bounded by h_0 max|h|, max|h| <= 3 for the table's h).
double problem_scale(double value, double p, double q, double x, double hx) {
  return std::abs(value) + std::pow(1 - x, p) * std::pow(1 + x, q) * std::abs(hx) +
         3 * rq::jacobi_norm_squared(0, p, q);
}

}  // namespace

TEST_CASE("cauchy_principal_value: 40-digit table, p, q in {-0.999..30}, x 2^-40 from the ends") {
  // 128 eps: the composite rule sums O(100) panels; each value and weight is rounded, and the
  // end factors (1 -+ t)^e with |e| <= 30 amplify the relative rounding of 1 -+ t by |e|.
  rhabel_test::error_sweep sweep(128 * eps);
  for (const auto& c : rhabel_test_data::cauchy_pv_cases) {
    const double reference = std::strtod(c.value, nullptr);
    double value = 0, hx = 1;
    if (c.h == 0) {
      value = rq::cauchy_principal_value([](double t) { return h_poly(t); }, c.p, c.q, c.x).value;
      hx = h_poly(c.x);
    } else if (c.h == 1) {
      value = rq::cauchy_principal_value_series(table_series_coefficients, c.p, c.q, c.x).value;
      hx = rq::jacobi_clenshaw(table_series_coefficients, c.p, c.q, c.x);
    } else {
      value = rq::cauchy_principal_value([](double) { return 1.0; }, c.p, c.q, c.x).value;
    }
    INFO("h = " << c.h << " p = " << c.p << " q = " << c.q << " x = " << c.x << " value = " << value
                << " reference = " << reference);
    sweep.check(std::abs(value - reference) / problem_scale(reference, c.p, c.q, c.x, hx));
  }
  sweep.report("cauchy_principal_value");
  CHECK(sweep.checked() == 252);
}

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("cauchy_principal_value at 50 digits reproduces the table to 1e-38") {
  // The table holds >= 40 correct digits; the 50-digit computation is far more accurate.
  int checked = 0;
  for (const auto& c : rhabel_test_data::cauchy_pv_cases) {
    if (c.h != 0 || (c.x != 0.3 && c.x != -1 + std::ldexp(1.0, -40))) continue;
    const bf50 reference(c.value);
    const auto r = rq::cauchy_principal_value([](const bf50& t) { return h_poly(t); }, bf50(c.p), bf50(c.q), bf50(c.x));
    const bf50 scale = abs(reference) + 3 * rq::jacobi_norm_squared(0, bf50(c.p), bf50(c.q)) +
                       pow(1 - bf50(c.x), bf50(c.p)) * pow(1 + bf50(c.x), bf50(c.q)) * 3;
    INFO("p = " << c.p << " q = " << c.q << " x = " << c.x);
    CHECK(abs(r.value - reference) <= bf50(1e-38) * scale);
    CHECK(r.error_estimate <= bf50(1e-38) * scale);
    ++checked;
  }
  CHECK(checked == 24);
}
#endif  // RHABEL_TEST_MULTIPRECISION

TEST_CASE("cauchy_principal_value of the weight: hypergeometric closed form") {
  // For p not an integer (derived from the Euler integral of 2F1 and the 1 - zeta connection
  // formula; checked with mpmath to 30 digits):
  //   PV int_{-1}^{1} w(t)/(t - x) dt = pi cot(pi p) w(x) - 2^(p+q) B(p, q+1) 2F1(1, -p-q; 1-p; (1-x)/2)
  // The series converges for |1 - x| < 2; we use x >= 0 so that (1-x)/2 <= 1/2 (pFq reports
  // total cancellation for larger arguments with -p-q << 0).
  for (double p : {-0.999, -0.5, 0.25, 0.5})  // 1 - p > 0: pFq's series has no sign changes in b
    for (double q : {-0.999, -0.3, 0.7, 1.6})  // p + q never an integer (pFq would terminate at 0)
      for (double x : {0.0, 0.4, 0.9, 1 - 1e-10}) {
        const double w = std::pow(1 - x, p) * std::pow(1 + x, q);
        INFO("p = " << p << " q = " << q << " x = " << x);
        const double F = boost::math::hypergeometric_pFq({1.0, -p - q}, {1.0 - p}, (1 - x) / 2);
        // B(p, q+1) through tgamma: boost::math::beta needs positive arguments, p may be negative.
        const double B = std::tgamma(p) * std::tgamma(q + 1) / std::tgamma(p + q + 1);
        const double closed = (pi / std::tan(pi * p) * w - std::pow(2.0, p + q) * B * F) / pi;
        const double value = rq::cauchy_principal_value([](double) { return 1.0; }, p, q, x).value;
        INFO("p = " << p << " q = " << q << " x = " << x << " closed = " << closed << " value = " << value);
        // The closed form cancels two terms of size |B(p, q+1)| 2^(p+q) (large for p -> 0, -1)
        // and pFq is accurate to a few hundred eps there: 1e3 eps of the larger term; the PV
        // itself is conditioned by w(x) (1 + |log((1-x)/(1+x))|) near the ends.
        const double scale = std::abs(closed) + std::pow(2.0, p + q) * std::abs(B) * std::abs(F) / pi +
                             w * (1 + std::abs(std::log((1 - x) / (1 + x)))) / pi;
        CHECK(std::abs(value - closed) <= 1e3 * eps * scale);
      }
}

TEST_CASE("Chebyshev closed forms: PV of (1-t^2)^(-1/2) is 0, of (1-t^2)^(1/2) is -pi x") {
  for (double x : {-1 + 1e-12, -0.7, 0.0, 0.33, 1 - 1e-12}) {
    const double first = rq::cauchy_principal_value([](double) { return 1.0; }, -0.5, -0.5, x).value;
    const double second = rq::cauchy_principal_value([](double) { return 1.0; }, 0.5, 0.5, x).value;
    // Scale of the first: w(x) |log((1-x)/(1+x))| / pi ~ 1e6 * 28 / pi at 1e-12 from an end.
    const double scale = 1 + std::pow(1 - x * x, -0.5) * std::abs(std::log((1 - x) / (1 + x)));
    CHECK(std::abs(first) <= 64 * eps * scale);
    CHECK(std::abs(second + x) <= 64 * eps);
  }
  // Phi(z) = (1/(2 pi i)) int (1-t^2)^(-1/2)/(t - z) dt = (1/(2 pi i)) (-pi) / (sqrt(z-1) sqrt(z+1)).
  for (cd z : {cd(0.2, 1e-8), cd(-0.99, -0.5), cd(3, 2), cd(-1 - 1e-9, 0), cd(1, 1e-12)}) {
    const cd closed = -pi / (std::sqrt(z - 1.0) * std::sqrt(z + 1.0)) / (cd(0, 2 * pi));
    const cd value = rq::cauchy_transform([](double) { return 1.0; }, -0.5, -0.5, z).value;
    INFO("z = " << z << " closed = " << closed << " value = " << value);
    CHECK(std::abs(value - closed) <= 64 * eps * (std::abs(closed) + 1));
  }
}

TEST_CASE("cauchy_plemelj: limits agree with the transform at z = x +- 1e-13 i, and jump = density") {
  // For a Hoelder density Phi(x + i d) - Phi_+(x) = O(d log d): 1e-13 gives ~1e-11.
  for (auto [p, q] : std::vector<std::pair<double, double>>{{-0.5, 0.5}, {0.0, 0.0}, {5.0, -0.999}})
    for (double x : {-0.6, 0.1, 0.8}) {
      auto h = [](double t) { return h_poly(t); };
      const auto limits = rq::cauchy_plemelj(h, p, q, x);
      const cd above = rq::cauchy_transform(h, p, q, cd(x, 1e-13)).value;
      const cd below = rq::cauchy_transform(h, p, q, cd(x, -1e-13)).value;
      const double scale = std::abs(limits.plus) + 1;
      INFO("p = " << p << " q = " << q << " x = " << x);
      CHECK(std::abs(limits.plus - above) <= 1e-10 * scale);
      CHECK(std::abs(limits.minus - below) <= 1e-10 * scale);
      const double density = std::pow(1 - x, p) * std::pow(1 + x, q) * h_poly(x);
      CHECK(std::abs(limits.plus - limits.minus - density) <= 8 * eps * scale);
    }
}

TEST_CASE("series variants agree with the callable of the same function") {
  const std::vector<double> c{0.5, -1.0, 0.25, 0.0, 2.0, -0.75};
  const double p = 0.5, q = -0.999;
  auto h = [&](double t) { return rq::jacobi_clenshaw(c, p, q, t); };
  for (double x : {-1 + 1e-12, 0.25}) {
    const double a = rq::cauchy_principal_value_series(c, p, q, x).value;
    const double b = rq::cauchy_principal_value(h, p, q, x).value;
    CHECK(std::abs(a - b) <= 64 * eps * (std::abs(a) + 1e3));
  }
  const cd z(0.3, 0.01);
  CHECK(std::abs(rq::cauchy_transform_series(c, p, q, z).value - rq::cauchy_transform(h, p, q, z).value) <= 1e-13);
  const auto s = rq::cauchy_plemelj_series(c, p, q, 0.3);
  const auto f = rq::cauchy_plemelj(h, p, q, 0.3);
  CHECK(std::abs(s.plus - f.plus) <= 1e-13);
}

TEST_CASE("bad input: exponents, points on or off the cut, NaN") {
  auto one = [](double) { return 1.0; };
  CHECK_THROWS_AS(rq::cauchy_principal_value(one, -1.0, 0.0, 0.0), std::domain_error);
  CHECK_THROWS_AS(rq::cauchy_principal_value(one, 0.0, 0.0, 1.0), std::domain_error);
  CHECK_THROWS_AS(rq::cauchy_principal_value(one, 0.0, 0.0, std::nan("")), std::domain_error);
  CHECK_THROWS_AS(rq::cauchy_transform(one, 0.0, 0.0, cd(0.5, 0.0)), std::domain_error);
  CHECK_THROWS_AS(rq::cauchy_transform(one, 0.0, 0.0, cd(std::nan(""), 1.0)), std::domain_error);
  CHECK_THROWS_AS(rq::cauchy_plemelj(one, 0.0, 0.0, -1.5), std::domain_error);
  rhabel_test::check_domain_error_mentions([&] { rq::cauchy_principal_value(one, 0.5, 0.5, 1.25); },
                                           {"cauchy_principal_value", "x = 1.25", "(-1, 1)"});
}

TEST_CASE("jacobi_q_all: recurrence (forward and Miller) vs graded quadrature of each P_k") {
  // Q_k(z) = -2 pi i Phi[P_k](z); the oracle integrates P_k directly (series with one
  // coefficient), no recurrence for Q. Both sides of the forward/Miller switch rho^(2 n) = 16.
  for (auto [p, q] : std::vector<std::pair<double, double>>{{-0.999, 0.5}, {0.0, 0.0}, {5.0, -0.5}})
    for (cd z : {cd(0.3, 1e-3), cd(0.3, 0.2), cd(1.5, 0.0), cd(-2.0, 1.0), cd(0.0, 5.0)}) {
      const std::size_t n_max = 24;
      const auto Q = rq::jacobi_q_all(n_max, p, q, z);
      for (std::size_t k : {0u, 1u, 2u, 7u, 24u}) {
        std::vector<double> c(k + 1, 0.0);
        c[k] = 1;
        const cd oracle = cd(0, -2 * pi) * rq::cauchy_transform_series(c, p, q, z).value;
        INFO("p = " << p << " q = " << q << " z = " << z << " k = " << k << " Q = " << Q[k] << " oracle = " << oracle);
        // Relative to |Q_0| (the size of the transform of the weight), 1e3 eps: Q_k decays like
        // rho^-k while the quadrature's absolute error is ~ eps int |w P_k| / |t - z|.
        CHECK(std::abs(Q[k] - oracle) <= 1e3 * eps * (std::abs(Q[0]) + std::abs(oracle)));
      }
    }
  // On the cut: principal values.
  const auto Qx = rq::jacobi_q_all_on_cut(10, 0.5, -0.5, 0.25);
  for (std::size_t k : {0u, 3u, 10u}) {
    std::vector<double> c(k + 1, 0.0);
    c[k] = 1;
    const double oracle = -pi * rq::cauchy_principal_value_series(c, 0.5, -0.5, 0.25).value;
    CHECK(std::abs(Qx[k] - oracle) <= 256 * eps * (std::abs(Qx[0]) + 1));
  }
}

TEST_CASE("error_estimate bounds the actual error when the panel order is too low") {
  // With 4 nodes per panel (and 8 for the returned value) the integrals are far from
  // converged; the estimate |I(4) - I(8)| must still exceed the true error of I(8) (table).
  int checked = 0;
  for (const auto& c : rhabel_test_data::cauchy_pv_cases) {
    if (c.h != 0) continue;
    const double reference = std::strtod(c.value, nullptr);
    const auto r = rq::cauchy_principal_value([](double t) { return h_poly(t); }, c.p, c.q, c.x, 4);
    const double error = std::abs(r.value - reference);
    const double rounding = 128 * eps * problem_scale(reference, c.p, c.q, c.x, h_poly(c.x));
    INFO("p = " << c.p << " q = " << c.q << " x = " << c.x << " error = " << error << " estimate = " << r.error_estimate);
    CHECK(error <= r.error_estimate + rounding);
    ++checked;
  }
  CHECK(checked == 84);
}
