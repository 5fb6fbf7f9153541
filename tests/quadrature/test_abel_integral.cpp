// Tests of rhabel/quadrature/abel_integral.hpp.
// Oracles: the committed 40-digit table tests/data/abel_reference.hpp (Boost tanh-sinh in
// cpp_bin_float_50, left integrals computed directly, tools/reference/cauchy_abel_reference.cpp),
// Beta-function closed forms, Euler's hypergeometric integral for x < -1 (boost pFq), and
// the spectral relation of docs/theory.md section 4 for all three index classes.
#include <doctest/doctest.h>

#include <rhabel/quadrature.hpp>

#include "data/abel_reference.hpp"
#include "quadrature/support.hpp"

#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/special_functions/hypergeometric_pFq.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace rq = rhabel::quadrature;
using bf50 = boost::multiprecision::cpp_bin_float_50;
using rhabel_test::eps;
using rhabel_test::h_poly;
using rhabel_test::pi;
using rhabel_test::table_series_coefficients;

TEST_CASE("abel integrals: 40-digit table, mu in {0.01, 0.5, 0.999}, x at and beyond the ends") {
  // The integrand is positive up to the sign changes of h; relative to the L1-like scale
  // |value| + int w |h| (t - x)^(mu-1): rounding of O(100) panel sums and of the end factors
  // with exponents up to 30 -> 128 eps.
  rhabel_test::error_sweep sweep(128 * eps);
  for (const auto& c : rhabel_test_data::abel_cases) {
    const double reference = std::strtod(c.value, nullptr);
    rq::integral_result<double> r{};
    if (c.h == 0) {
      auto h = [](double t) { return h_poly(t); };
      r = c.right ? rq::abel_integral_right(h, c.p, c.q, c.mu, c.x) : rq::abel_integral_left(h, c.p, c.q, c.mu, c.x);
    } else {
      r = c.right ? rq::abel_integral_right_series(table_series_coefficients, c.p, c.q, c.mu, c.x)
                  : rq::abel_integral_left_series(table_series_coefficients, c.p, c.q, c.mu, c.x);
    }
    // Scale: the same integral with |h| replaced by its bound (3 for h_poly, 1e4 covers the
    // series P_3 + P_6/2 for exponents <= 30 on most of the interval) is not available
    // independently; use |reference| + int w (the magnitude of the weight's integral).
    const double scale = std::abs(reference) + rq::jacobi_norm_squared(0, c.p, c.q);
    INFO("h = " << c.h << ' ' << std::string(c.right ? "right" : "left") << " p = " << c.p << " q = " << c.q
                << " mu = " << c.mu << " x = " << c.x << " value = " << r.value << " reference = " << reference);
    sweep.check(std::abs(r.value - reference) / scale);
  }
  sweep.report("abel integrals");
  CHECK(sweep.checked() == 228);
}

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("abel integrals at 50 digits reproduce the table to 1e-38") {
  int checked = 0;
  for (const auto& c : rhabel_test_data::abel_cases) {
    if (c.h != 0 || c.mu != 0.5 || (c.x != 0.7 && c.x != -0.7 && c.x != -1.5 && c.x != 1.5)) continue;
    const bf50 reference(c.value);
    auto h = [](const bf50& t) { return h_poly(t); };
    const auto r = c.right ? rq::abel_integral_right(h, bf50(c.p), bf50(c.q), bf50(c.mu), bf50(c.x))
                           : rq::abel_integral_left(h, bf50(c.p), bf50(c.q), bf50(c.mu), bf50(c.x));
    const bf50 scale = abs(reference) + rq::jacobi_norm_squared(0, bf50(c.p), bf50(c.q));
    INFO(std::string(c.right ? "right" : "left") << " p = " << c.p << " q = " << c.q << " x = " << c.x);
    CHECK(abs(r.value - reference) <= bf50(1e-38) * scale);
    ++checked;
  }
  CHECK(checked >= 16);
}
#endif  // RHABEL_TEST_MULTIPRECISION

TEST_CASE("closed forms: int_x^1 (t-x)^(mu-1) (1-t)^p dt = (1-x)^(mu+p) B(mu, p+1), and mirrored") {
  auto one = [](double) { return 1.0; };
  for (double p : {-0.999, -0.5, 0.0, 0.5, 5.0, 30.0})
    for (double mu : {0.01, 0.3, 0.999})
      for (double x : {-1 + 1e-12, -0.5, 0.2, 1 - 1e-12}) {
        const double closed = std::pow(1 - x, mu + p) * boost::math::beta(mu, p + 1);
        const double right = rq::abel_integral_right(one, p, 0.0, mu, x).value;
        const double left = rq::abel_integral_left(one, 0.0, p, mu, -x).value;  // mirror image
        INFO("p = " << p << " mu = " << mu << " x = " << x);
        // 128 eps: pow and beta are a few ulps, the panel sums add O(10) eps, and the
        // Gauss-Jacobi weights for exponents up to 30 carry ~1e-14 (gauss_jacobi's contract).
        CHECK(std::abs(right - closed) <= 128 * eps * closed);
        CHECK(std::abs(left - closed) <= 128 * eps * closed);
      }
}

TEST_CASE("x < -1: Euler's integral 2^(p+q+1) (-1-x)^(mu-1) B(q+1,p+1) 2F1(1-mu, q+1; p+q+2; 2/(1+x))") {
  auto one = [](double) { return 1.0; };
  for (double p : {-0.999, 0.5, 5.0})
    for (double q : {-0.999, -0.5, 0.5})
      for (double mu : {0.01, 0.5, 0.999})
        for (double x : {-3.5, -8.0}) {  // |2/(1+x)| < 1 so that the pFq series converges
          const double F = boost::math::hypergeometric_pFq({1 - mu, q + 1}, {p + q + 2}, 2 / (1 + x));
          const double closed = std::pow(2.0, p + q + 1) * std::pow(-1 - x, mu - 1) * boost::math::beta(q + 1, p + 1) * F;
          const double value = rq::abel_integral_right(one, p, q, mu, x).value;
          INFO("p = " << p << " q = " << q << " mu = " << mu << " x = " << x);
          CHECK(std::abs(value - closed) <= 64 * eps * closed);  // pFq and beta: tens of ulps
        }
}

TEST_CASE("spectral relation (docs/theory.md section 4) for the three index classes") {
  // int_x^1 (t-x)^(a-1) w P_n^(del,gam) - kappa int_-1^x (x-t)^(a-1) w P_n^(del,gam)
  //   = -2^(-nu) pi (1-a)_n / (n! sin(pi del)) P_(n-nu)^(gam+nu, del+nu)(x),  w = (1-t)^del (1+t)^gam.
  const double alpha = 0.3, beta = 0.2;
  const double kappa = std::cos((alpha + beta / 2) * pi) / std::cos(beta * pi / 2);
  struct index_class {
    int nu;
    double gam, del;
  };
  const std::vector<index_class> classes{{-1, (1 - 2 * alpha - beta) / 2, (1 + beta) / 2},
                                         {0, (1 - 2 * alpha - beta) / 2, (beta - 1) / 2},
                                         {1, -(1 + 2 * alpha + beta) / 2, (beta - 1) / 2}};
  for (const auto& k : classes) {
    REQUIRE(std::abs(k.gam + k.del + alpha + k.nu) < 1e-15);
    for (std::size_t n = 0; n <= 6; ++n) {
      std::vector<double> c(n + 1, 0.0);
      c[n] = 1;
      for (double x : {-1 + 1e-9, -0.6, 0.05, 0.7, 1 - 1e-9}) {
        const double right = rq::abel_integral_right_series(c, k.del, k.gam, alpha, x).value;
        const double left = rq::abel_integral_left_series(c, k.del, k.gam, alpha, x).value;
        const double pochhammer_over_factorial =
            std::exp(std::lgamma(n + 1 - alpha) - std::lgamma(1 - alpha) - std::lgamma(n + 1.0));
        const long m = static_cast<long>(n) - k.nu;
        const double image =
            m < 0 ? 0.0 : rq::jacobi_p(static_cast<std::size_t>(m), k.gam + k.nu, k.del + k.nu, x);
        const double expected = -std::pow(2.0, -k.nu) * pi * pochhammer_over_factorial / std::sin(pi * k.del) * image;
        const double scale = std::abs(right) + std::abs(kappa * left) + std::abs(expected);
        INFO("nu = " << k.nu << " n = " << n << " x = " << x);
        CHECK(std::abs(right - kappa * left - expected) <= 64 * eps * scale);  // two O(10 eps) integrals
      }
    }
  }
}

TEST_CASE("bad input: mu, exponents, x on the wrong side, divergent end, NaN") {
  auto one = [](double) { return 1.0; };
  CHECK_THROWS_AS(rq::abel_integral_right(one, 0.0, 0.0, 0.0, 0.0), std::domain_error);
  CHECK_THROWS_AS(rq::abel_integral_right(one, 0.0, 0.0, 1.5, 0.0), std::domain_error);
  CHECK_THROWS_AS(rq::abel_integral_right(one, -1.0, 0.0, 0.5, 0.0), std::domain_error);
  CHECK_THROWS_AS(rq::abel_integral_right(one, 0.0, 0.0, 0.5, 1.5), std::domain_error);
  CHECK_THROWS_AS(rq::abel_integral_left(one, 0.0, 0.0, 0.5, -1.5), std::domain_error);
  CHECK_THROWS_AS(rq::abel_integral_left(one, 0.0, 0.0, 0.5, std::nan("")), std::domain_error);
  CHECK_THROWS_AS(rq::abel_integral_right(one, 0.0, -0.8, 0.1, -1.0), std::domain_error);  // q + mu <= 0
  CHECK(rq::abel_integral_right(one, 0.0, -0.8, 0.9, -1.0).value > 0);                     // q + mu > 0
  rhabel_test::check_domain_error_mentions([&] { rq::abel_integral_left(one, 0.5, 0.5, 2.0, 0.0); },
                                           {"abel_integral_left", "mu = 2", "(0, 1]"});
}
