// Tests of rhabel/quadrature/jacobi_polynomial.hpp (and jacobi_coefficients).
// Oracles: the committed table tests/data/jacobi_polynomial_reference.hpp (100-digit
// recurrence in tools/reference/jacobi_polynomial_reference.cpp), explicit closed forms for
// small n, exact identities (orthogonality, Christoffel-Darboux, the differential identity
// DLMF 18.9.17, connection and lowering identities), incomplete beta special cases.
#include <doctest/doctest.h>

#include <rhabel/quadrature.hpp>

#include "data/jacobi_polynomial_reference.hpp"
#include "quadrature/support.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rq = rhabel::quadrature;
using bf50 = boost::multiprecision::cpp_bin_float_50;
using rhabel_test::eps;

namespace {

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

TEST_CASE("jacobi_p: 100-digit table, n up to 10^6, x 2^-40 and 2^-30 from the ends") {
  // Error measured relative to the local scale max(|P_{n-1}|, |P_n|, |P_{n+1}|) at x (this
  // avoids dividing by a value that happens to be near a zero). Forward recurrence in the
  // interior and Reinsch's difference form for |x| >= 1/2: O(n eps) -> 4 (n + 10) eps. In the
  // transition zone 1 < n^2 (1 -+ x) < n, with the exponent at that end near -1, the measured
  // error is up to 640 n eps (n = 10^6, p = -0.999, 1 - x = 2^-30: the values there are
  // 1e-6 of the polynomial's size elsewhere); the tolerance there is 1024 (n + 10) eps.
  int checked = 0;
  double worst = 0;
  for (const auto& c : rhabel_test_data::jacobi_value_cases) {
    const double reference = std::strtod(c.value, nullptr);
    const auto n = static_cast<std::size_t>(c.n);
    const double value = rq::jacobi_p(n, c.p, c.q, c.x);
    const double scale = std::max({std::abs(reference), std::abs(rq::jacobi_p(n - 1, c.p, c.q, c.x)),
                                   std::abs(rq::jacobi_p(n + 1, c.p, c.q, c.x))});
    const double distance = 1 - std::abs(c.x);
    const double end_exponent = c.x > 0 ? c.p : c.q;
    const double N = static_cast<double>(n);
    const bool transition = N * N * distance > 1 && N * distance < 1 && end_exponent < -0.9;
    const double tolerance = (transition ? 1024 : 4) * (N + 10) * eps * scale;
    const double error = std::abs(value - reference) / ((N + 10) * eps * scale);
    if (!transition) worst = std::max(worst, error);
    INFO("n = " << n << " p = " << c.p << " q = " << c.q << " x = " << c.x);
    CHECK(std::abs(value - reference) <= tolerance);
    ++checked;
  }
  MESSAGE("jacobi_p worst error outside the transition zone: " << worst << " (n + 10) eps * scale");
  CHECK(checked == 7 * 7 * 7);
}

TEST_CASE("jacobi_p: explicit P_1, P_2 and the end value P_n(1) = (p+1)_n / n!") {
  for (double p : {-0.999, -0.5, 0.0, 0.5, 5.0, 30.0})
    for (double q : {-0.999, 0.5, 30.0})
      for (double x : {-0.9, 0.2, 0.7}) {
        const double p1 = (p + q + 2) / 2 * x + (p - q) / 2;
        // DLMF 18.5.8 with n = 2.
        const double a = (x - 1) / 2, b = (x + 1) / 2;
        const double p2 = (p + 2) * (p + 1) / 2 * b * b + (p + 2) * (q + 2) * a * b + (q + 2) * (q + 1) / 2 * a * a;
        CHECK(std::abs(rq::jacobi_p(1, p, q, x) - p1) <= 8 * eps * (std::abs(p1) + 30));
        CHECK(std::abs(rq::jacobi_p(2, p, q, x) - p2) <= 16 * eps * (std::abs(p2) + 1000));
      }
  // P_n(1) = (p+1)_n / n! = prod_{k=1}^{n} (k + p)/k: exact value at the end, n = 50.
  for (double p : {-0.999, -0.5, 0.5, 5.0}) {
    double reference = 1;
    for (int k = 1; k <= 50; ++k) reference *= (k + p) / k;
    CHECK(std::abs(rq::jacobi_p(50, p, 0.3, 1.0) - reference) <= 128 * eps * reference);  // 50 roundings each side
  }
}

TEST_CASE("jacobi_p_all agrees with jacobi_p, and Clenshaw with the direct sum") {
  const double p = 0.5, q = -0.999, x = 0.37;
  const auto all = rq::jacobi_p_all(30, p, q, x);
  for (std::size_t k = 0; k <= 30; ++k) CHECK(all[k] == rq::jacobi_p(k, p, q, x));
  std::vector<double> c(31);
  double direct = 0, magnitude = 0;
  for (std::size_t k = 0; k <= 30; ++k) {
    c[k] = 1.0 / (1.0 + static_cast<double>(k * k)) * (k % 3 == 0 ? -1 : 1);
    direct += c[k] * all[k];
    magnitude += std::abs(c[k] * all[k]);
  }
  CHECK(std::abs(rq::jacobi_clenshaw(c, p, q, x) - direct) <= 64 * eps * magnitude);  // two O(K eps) sums
}

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("orthogonality and norms by Gauss-Jacobi quadrature, 50 digits") {
  const bf50 tolerance = 1e-40;  // the rule is exact for degree 2n-1; 50-digit arithmetic
  for (auto [p, q] : std::vector<std::pair<double, double>>{{-0.5, 0.5}, {0.0, 0.0}, {5.0, 0.5}, {-0.999, 30.0}}) {
    const bf50 P = p, Q = q;
    const auto rule = rq::gauss_jacobi<bf50>(12, P, Q);
    for (std::size_t m = 0; m < 12; ++m)
      for (std::size_t k = 0; k <= m; ++k) {
        bf50 sum = 0;
        for (std::size_t i = 0; i < rule.size(); ++i)
          sum += rule.weight[i] * rq::jacobi_p(m, P, Q, rule.x[i]) * rq::jacobi_p(k, P, Q, rule.x[i]);
        const bf50 h = rq::jacobi_norm_squared(m, P, Q);
        INFO("p = " << p << " q = " << q << " m = " << m << " k = " << k);
        if (k == m)
          CHECK(abs(sum - h) <= tolerance * h);
        else
          CHECK(abs(sum) <= tolerance * sqrt(h * rq::jacobi_norm_squared(k, P, Q)));
      }
  }
}
#endif  // RHABEL_TEST_MULTIPRECISION

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("Christoffel-Darboux identity, 50 digits") {
  // sum_{k<=n} P_k(x) P_k(y) / h_k = (P_{n+1}(x) P_n(y) - P_n(x) P_{n+1}(y)) / (A_n h_n (x - y)),
  // A_n = k_{n+1}/k_n = (2n+p+q+1)(2n+p+q+2) / (2 (n+1)(n+p+q+1)).
  const bf50 p = bf50(7) / 10, q = bf50(-999) / 1000, x = bf50(3) / 10, y = bf50(-4) / 7;
  const std::size_t n = 25;
  bf50 sum = 0;
  for (std::size_t k = 0; k <= n; ++k)
    sum += rq::jacobi_p(k, p, q, x) * rq::jacobi_p(k, p, q, y) / rq::jacobi_norm_squared(k, p, q);
  const bf50 N = n;
  const bf50 A = (2 * N + p + q + 1) * (2 * N + p + q + 2) / (2 * (N + 1) * (N + p + q + 1));
  const bf50 right = (rq::jacobi_p(n + 1, p, q, x) * rq::jacobi_p(n, p, q, y) -
                      rq::jacobi_p(n, p, q, x) * rq::jacobi_p(n + 1, p, q, y)) /
                     (A * rq::jacobi_norm_squared(n, p, q) * (x - y));
  CHECK(abs(sum - right) <= bf50(1e-44) * abs(sum));
}
#endif  // RHABEL_TEST_MULTIPRECISION

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("derivative: (2n+p+q)(1-x^2) P_n' = n[(p-q) - (2n+p+q)x] P_n + 2(n+p)(n+q) P_{n-1}") {
  // DLMF 18.9.17 rearranged; independent of the formula P_n' = (n+p+q+1)/2 P_{n-1}^(p+1,q+1) used by the code.
  const bf50 p = bf50(-1) / 2, q = bf50(5);
  for (std::size_t n : {1u, 2u, 7u, 40u})
    for (int i = -3; i <= 3; ++i) {
      const bf50 x = bf50(i) / 4 + bf50(1) / 100;
      const bf50 N = n, s = 2 * N + p + q;
      const bf50 left = s * (1 - x * x) * rq::jacobi_p_derivative(n, p, q, x);
      const bf50 right = N * ((p - q) - s * x) * rq::jacobi_p(n, p, q, x) +
                         2 * (N + p) * (N + q) * rq::jacobi_p(n - 1, p, q, x);
      CHECK(abs(left - right) <= bf50(1e-42) * (abs(left) + abs(right) + 1));
    }
}
#endif  // RHABEL_TEST_MULTIPRECISION

TEST_CASE("connection and lowering identities, and the series versions") {
  const double p = 0.25, q = -0.999;
  for (double x : {-0.999, -0.3, 0.6, 0.9999})
    for (std::size_t n = 0; n < 12; ++n) {
      const double P = rq::jacobi_p(n, p, q, x);
      const double scale = 1 + std::abs(P) + std::abs(rq::jacobi_p(n + 1, p, q, x));
      const double tol = 64 * eps * scale * static_cast<double>(n + 2);  // recurrences of length n
      auto [a, b] = rq::jacobi_connection_raise_p(n, p, q);
      CHECK(std::abs(a * rq::jacobi_p(n, p + 1, q, x) + (n ? b * rq::jacobi_p(n - 1, p + 1, q, x) : 0.0) - P) <=
            tol * 4);
      auto [c, d] = rq::jacobi_connection_raise_q(n, p, q);
      CHECK(std::abs(c * rq::jacobi_p(n, p, q + 1, x) + (n ? d * rq::jacobi_p(n - 1, p, q + 1, x) : 0.0) - P) <=
            tol * 4);
      auto [e, f] = rq::jacobi_lowering_one_minus_x(n, p, q);
      CHECK(std::abs((1 - x) * rq::jacobi_p(n, p + 1, q, x) - e * P - f * rq::jacobi_p(n + 1, p, q, x)) <= tol * 4);
      auto [g, h] = rq::jacobi_lowering_one_plus_x(n, p, q);
      CHECK(std::abs((1 + x) * rq::jacobi_p(n, p, q + 1, x) - g * P - h * rq::jacobi_p(n + 1, p, q, x)) <= tol * 4);
    }
  // Series: the same function in two families, evaluated by Clenshaw.
  const std::vector<double> c{0.3, -1.0, 0.5, 0.25, -0.125, 2.0};
  const auto raised_p = rq::jacobi_series_raise_p(c, p, q);
  const auto raised_q = rq::jacobi_series_raise_q(c, p, q);
  // (1 - x) times a series in the family (p + 1/2, q) = ((p - 1/2) + 1, q), expanded in (p - 1/2, q).
  const auto lowered_m = rq::jacobi_series_times_one_minus_x(c, p - 0.5, q);
  for (double x : {-0.8, 0.1, 0.95}) {
    const double f = rq::jacobi_clenshaw(c, p, q, x);
    CHECK(std::abs(rq::jacobi_clenshaw(raised_p, p + 1, q, x) - f) <= 256 * eps * (1 + std::abs(f)));
    CHECK(std::abs(rq::jacobi_clenshaw(raised_q, p, q + 1, x) - f) <= 256 * eps * (1 + std::abs(f)));
    const double g = rq::jacobi_clenshaw(c, p + 0.5, q, x);
    CHECK(std::abs(rq::jacobi_clenshaw(lowered_m, p - 0.5, q, x) - (1 - x) * g) <= 256 * eps * (1 + std::abs(g)));
  }
  // (1 + x) times a series in the family (p, q' + 1), q' = q - 0.0005 = -0.9995, expanded in (p, q').
  const auto lowered_p = rq::jacobi_series_times_one_plus_x(c, p, q - 0.0005);
  for (double x : {-0.8, 0.1, 0.95}) {
    const double g = rq::jacobi_clenshaw(c, p, q - 0.0005 + 1, x);
    CHECK(std::abs(rq::jacobi_clenshaw(lowered_p, p, q - 0.0005, x) - (1 + x) * g) <= 256 * eps * (1 + std::abs(g)));
  }
}

TEST_CASE("jacobi_coefficients: exact for polynomials, spectral for exp") {
  const double p = -0.5, q = 5;
  // f = P_3 - 2 P_0 + 0.5 P_7 in the family: coefficients recovered exactly.
  auto f = [&](double x) {
    return rq::jacobi_p(3, p, q, x) - 2 + 0.5 * rq::jacobi_p(7, p, q, x);
  };
  const auto c = rq::jacobi_coefficients(f, p, q, 10);
  for (std::size_t k = 0; k < 10; ++k) {
    const double expected = k == 3 ? 1.0 : k == 0 ? -2.0 : k == 7 ? 0.5 : 0.0;
    CHECK(std::abs(c[k] - expected) <= 64 * eps);  // sums of 10 O(1) terms
  }
  // exp: the Clenshaw sum of 20 coefficients reproduces exp to rounding on [-1, 1]. (With a
  // large exponent, e.g. q = 5, the coefficients' absolute noise ~ eps ||f||_w / sqrt(h_k) is
  // amplified by |P_k(-1)| ~ k^5 where the weight vanishes, so the uniform check uses q = 0.5.)
  const auto e = rq::jacobi_coefficients([](double x) { return std::exp(x); }, p, 0.5, 20);
  for (double x : {-0.99, -0.2, 0.5, 1.0})
    CHECK(std::abs(rq::jacobi_clenshaw(e, p, 0.5, x) - std::exp(x)) <= 64 * eps * 3);  // 20-term sums, |f| <= e
  CHECK(max_abs(e) < 10);
}

TEST_CASE("jacobi_coefficients: long expansions near singular ends; the three-argument form") {
  // f = P_0 + P_397 (jacobi_p: the endpoint series next to the ends, another evaluation than the
  // projection's recurrences) at n = 400, exponents of a singular and a bounded end: recovered to
  // 2e3 eps (400-term sums whose terms grow toward the ends; measured 1.0e3 eps, and 4.9e3 eps
  // with P_k evaluated at each node from the rounded x instead of the rule's distances).
  const double p = -0.65, q = 0.35;
  const std::size_t n = 400, m = 397;
  const auto c = rq::jacobi_coefficients([&](double x) { return 1 + rq::jacobi_p(m, p, q, x); }, p, q, n);
  for (std::size_t k = 0; k < n; ++k) {
    CAPTURE(k);
    const double expected = k == 0 || k == m ? 1.0 : 0.0;
    CHECK(std::abs(c[k] - expected) <= 2e3 * eps);
  }
  // f(x, 1 + x, 1 - x) gets the rule's distances to the ends: they sum to 2 and match x to
  // rounding, and a polynomial written in them has the coefficients of the one-argument form.
  double worst_sum = 0, worst_x = 0;
  const auto three = rq::jacobi_coefficients(
      [&](double x, double u, double v) {
        worst_sum = std::max(worst_sum, std::abs(u + v - 2));
        worst_x = std::max(worst_x, std::abs((u <= v ? u - 1 : 1 - v) - x));
        return u * u * v;
      },
      p, q, 12);
  const auto one = rq::jacobi_coefficients([](double x) { return (1 + x) * (1 + x) * (1 - x); }, p, q, 12);
  CHECK(worst_sum <= 4 * eps);
  CHECK(worst_x <= 2 * eps);
  for (std::size_t k = 0; k < 12; ++k) CHECK(std::abs(three[k] - one[k]) <= 64 * eps);
}

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("jacobi_integral_below: Rodrigues formula vs quadrature on [-1, x0], incomplete beta") {
  // Oracle: Gauss-Jacobi on [-1, x0] with weight (t + 1)^q and (1 - t)^p evaluated at the nodes,
  // exact up to the smooth factor (1-t)^p (high order rule, 50 digits).
  for (auto [p, q] : std::vector<std::pair<double, double>>{{0.5, -0.999}, {-0.5, 0.5}, {5.0, 0.0}, {0.0, 30.0}})
    for (double x0d : {-0.999, -0.2, 0.4}) {
      const bf50 P = p, Q = q, x0 = x0d;
      const auto rule = rq::gauss_jacobi<bf50>(60, bf50(0), Q, bf50(-1), x0);
      for (std::size_t m : {0u, 1u, 2u, 5u, 9u}) {
        bf50 oracle = 0;
        for (std::size_t i = 0; i < rule.size(); ++i)
          oracle += rule.weight[i] * pow(1 - rule.x[i], P) * rq::jacobi_p(m, P, Q, rule.x[i]);
        const bf50 value = rq::jacobi_integral_below(m, P, Q, x0);
        INFO("p = " << p << " q = " << q << " x0 = " << x0d << " m = " << m);
        // (1-t)^p on [-1, 0.4] is analytic within rho ~ 1.6/... ; 60 nodes give > 25 digits.
        CHECK(abs(value - oracle) <= bf50(1e-22) * (abs(oracle) + rq::jacobi_integral_below(0, P, Q, x0)));
      }
    }
  // Special cases: p = q = 0 gives 1 + x0; the full interval gives h_0 for m = 0 and 0 for m >= 1.
  CHECK(std::abs(rq::jacobi_integral_below(0, 0.0, 0.0, 0.3) - 1.3) <= 4 * eps);
  CHECK(std::abs(rq::jacobi_integral_below(0, 5.0, -0.999, 1.0) - rq::jacobi_norm_squared(0, 5.0, -0.999)) <=
        32 * eps * rq::jacobi_norm_squared(0, 5.0, -0.999));
  CHECK(rq::jacobi_integral_below(4, 5.0, -0.999, 1.0) == 0.0);
  // Near x0 = 1 the complement overload keeps the tail: int_{x0}^1 (1-x)^p dx for q = 0 is
  // (1-x0)^(p+1)/(p+1); with 1 - x0 = 1e-300 the total minus the tail is exact to rounding.
  const double tail = 1e-300;
  const double below = rq::jacobi_integral_below(0, 0.5, 0.0, tail, 2.0 - tail);
  CHECK(std::abs(below - 2 * std::sqrt(8.0) / 3) <= 4 * eps * below);
}
#endif  // RHABEL_TEST_MULTIPRECISION

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("jacobi_step_coefficients and jacobi_ramp_coefficients reproduce the functions") {
  // The step series converges in L2_w; check the moments instead: the coefficients are exact moments.
  const double p = 0.5, q = -0.5, x0 = 0.3;
  const auto step = rq::jacobi_step_coefficients(6, p, q, x0);
  const auto ramp = rq::jacobi_ramp_coefficients(6, p, q, x0);
  // Oracle: composite Gauss-Jacobi on [-1, x0] (weight (1+t)^q) of P_m (1-t)^p and (x0 - t) P_m (1-t)^p.
  const auto rule = rq::gauss_jacobi<bf50>(60, bf50(0), bf50(q), bf50(-1), bf50(x0));
  for (std::size_t m = 0; m < 6; ++m) {
    bf50 s = 0, r = 0;
    for (std::size_t i = 0; i < rule.size(); ++i) {
      const bf50 term = rule.weight[i] * pow(1 - rule.x[i], bf50(p)) * rq::jacobi_p(m, bf50(p), bf50(q), rule.x[i]);
      s += term;
      r += term * (bf50(x0) - rule.x[i]);
    }
    const double h = rq::jacobi_norm_squared(m, p, q);
    CHECK(std::abs(step[m] - static_cast<double>(s) / h) <= 64 * eps * (1 + std::abs(step[m])));
    CHECK(std::abs(ramp[m] - static_cast<double>(r) / h) <= 64 * eps * (1 + std::abs(ramp[m])));
  }
}
#endif  // RHABEL_TEST_MULTIPRECISION

TEST_CASE("bad input names function, parameter and value") {
  CHECK_THROWS_AS(rq::jacobi_p(3, -1.0, 0.0, 0.2), std::domain_error);
  CHECK_THROWS_AS(rq::jacobi_p(3, 0.0, std::nan(""), 0.2), std::domain_error);
  CHECK_THROWS_AS(rq::jacobi_integral_below(3, 0.0, 0.0, 1.5), std::domain_error);
  CHECK_THROWS_AS(rq::jacobi_coefficients([](double) { return 1.0; }, 0.0, 0.0, 0), std::domain_error);
  // Regression: the message named the internal jacobi_integral_below instead of the public function.
  rhabel_test::check_domain_error_mentions([] { rq::jacobi_step_coefficients(3, 0.5, -1.5, 0.0); },
                                           {"jacobi_step_coefficients", "q = -1.5", "(-1, inf)"});
  // Regression: the ramp's message named jacobi_step_coefficients (a copied validation block).
  rhabel_test::check_domain_error_mentions([] { rq::jacobi_ramp_coefficients(3, 0.5, 0.0, 2.5, -0.5); },
                                           {"jacobi_ramp_coefficients", "one_minus_x0 = 2.5", "[0, 2]"});
}

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
namespace {

// Independent 50-digit oracle for the switch tests: the plain recurrence in the undivided
// form of DLMF 18.9.2 (not the library's normalised or difference forms).
bf50 recurrence_oracle(std::size_t n, const bf50& p, const bf50& q, const bf50& x) {
  bf50 previous = 1, current = (p + q + 2) / 2 * x + (p - q) / 2;
  if (n == 0) return previous;
  for (std::size_t k = 2; k <= n; ++k) {
    const bf50 K = k, s = 2 * K + p + q;
    const bf50 next = ((s - 1) * (s * (s - 2) * x + p * p - q * q) * current - 2 * (K + p - 1) * (K + q - 1) * s * previous) /
                      (2 * K * (K + p + q) * (s - 2));
    previous = current;
    current = next;
  }
  return current;
}

}  // namespace
#endif  // RHABEL_TEST_MULTIPRECISION

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("jacobi_p and jacobi_clenshaw on both sides of their algorithm switches") {
  // Switches: |x| = 1/2 (plain recurrence / difference form; Clenshaw / forward sum) and
  // n^2 (1 -+ x)/2 = 1 (difference form / endpoint series). Tolerance 8 (n + 10) eps relative
  // to the local scale, as in the table test.
  for (auto [p, q] : std::vector<std::pair<double, double>>{{-0.999, 0.5}, {0.5, -0.999}, {5.0, 30.0}}) {
    const std::size_t n = 1000;
    const double boundary_u = 2.0 / (1000.0 * 1000.0);  // n^2 u / 2 = 1 at 1 - x = 2e-6
    for (double x : {0.5, std::nextafter(0.5, 0.0), -0.5, std::nextafter(-0.5, 0.0), 1 - boundary_u,
                     1 - boundary_u * (1 + 1e-9), 1 - boundary_u * (1 - 1e-9), -1 + boundary_u,
                     -1 + boundary_u * (1 + 1e-9)}) {
      const double reference = static_cast<double>(recurrence_oracle(n, bf50(p), bf50(q), bf50(x)));
      const double scale = std::max({std::abs(reference), std::abs(static_cast<double>(recurrence_oracle(n - 1, bf50(p), bf50(q), bf50(x)))),
                                     std::abs(static_cast<double>(recurrence_oracle(n + 1, bf50(p), bf50(q), bf50(x))))});
      INFO("p = " << p << " q = " << q << " x = " << x);
      CHECK(std::abs(rq::jacobi_p(n, p, q, x) - reference) <= 8 * (n + 10) * eps * scale);
    }
    // Clenshaw switch: a 12-term series on both sides of |x| = 1/2 against the oracle sum.
    std::vector<double> c(12);
    for (std::size_t k = 0; k < c.size(); ++k) c[k] = 1.0 / static_cast<double>(k + 1);
    for (double x : {0.5, std::nextafter(0.5, 0.0), -0.5, std::nextafter(-0.5, 0.0)}) {
      bf50 sum = 0, magnitude = 0;
      for (std::size_t k = 0; k < c.size(); ++k) {
        const bf50 term = bf50(c[k]) * recurrence_oracle(k, bf50(p), bf50(q), bf50(x));
        sum += term;
        magnitude += abs(term);
      }
      CHECK(std::abs(rq::jacobi_clenshaw(c, p, q, x) - static_cast<double>(sum)) <= 64 * eps * static_cast<double>(magnitude));
    }
  }
}
#endif  // RHABEL_TEST_MULTIPRECISION

TEST_CASE("jacobi_weight: regression, complements above 2 and NaN are rejected (the message said [0, 2])") {
  using rhabel::quadrature::jacobi_weight;
  using rhabel_test::check_domain_error_mentions;
  check_domain_error_mentions([] { jacobi_weight(0.5, 0.5, 2.5, 0.1); }, {"jacobi_weight", "one_minus_x", "2.5", "[0, 2]"});
  check_domain_error_mentions([] { jacobi_weight(0.5, 0.5, 0.1, 2.0000000000000004); },
                              {"jacobi_weight", "one_plus_x", "[0, 2]"});
  check_domain_error_mentions([] { jacobi_weight(0.5, 0.5, std::nan(""), 1.0); }, {"jacobi_weight", "one_minus_x", "nan"});
  check_domain_error_mentions([] { jacobi_weight(0.5, 0.5, 1.0, -1e-300); }, {"jacobi_weight", "one_plus_x"});
  // The ends of the range are accepted: (1 - x)^p (1 + x)^q at x = -1 and at 1e-300 from +1.
  CHECK(jacobi_weight(0.5, 2.0, 2.0, 0.0) == 0);
  CHECK(jacobi_weight(-0.5, 0.0, 1e-300, 2.0) == doctest::Approx(1e150).epsilon(4 * eps));
}
