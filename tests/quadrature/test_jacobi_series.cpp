// Tests of rhabel::quadrature::jacobi_series (jacobi_polynomial.hpp): the precomputed-coefficient
// evaluator of sum_k c_k P_k^(p,q)(x).
// Oracles: the end values P_k^(p,q)(1) = (p+1)_k/k!, P_k^(p,q)(-1) = (-1)^k (q+1)_k/k! (DLMF
// 18.6.1) accumulated by an independent product loop here; Legendre (p = q = 0) sums against the
// same sum at 50 digits; and agreement with jacobi_clenshaw (the per-call evaluator it replaces:
// the same operations in the same order in both branches, so the sums are bit-identical).
#include <doctest/doctest.h>

#include <rhabel/quadrature.hpp>

#include <cmath>
#include <limits>

#include "quadrature/support.hpp"

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rq = rhabel::quadrature;
using bf50 = boost::multiprecision::cpp_bin_float_50;
using rhabel_test::eps;

namespace {

// Deterministic coefficients of mixed sign, decaying like 1/(k+1) (no cancellation-free sums).
std::vector<double> test_coefficients(std::size_t K) {
  std::vector<double> c(K);
  for (std::size_t k = 0; k < K; ++k) c[k] = std::cos(0.7 * static_cast<double>(k) + 0.3) / static_cast<double>(k + 1);
  return c;
}

// sum_k |c_k| |P_k(x)| bound from the end values max(|P_k(1)|, |P_k(-1)|) (|P_k| attains its
// max on [-1, 1] at an end when max(p, q) >= -1/2, Szego 7.32.1): the scale of rounding.
double magnitude(const std::vector<double>& c, double p, double q) {
  double pk = 1, qk = 1, m = 0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (k > 0) {
      pk *= (static_cast<double>(k) + p) / static_cast<double>(k);
      qk *= (static_cast<double>(k) + q) / static_cast<double>(k);
    }
    m += std::abs(c[k]) * std::max({std::abs(pk), std::abs(qk), 1.0});
  }
  return m;
}

}  // namespace

TEST_CASE("jacobi_series at x = +-1 equals the closed-form end values (p+1)_k/k!, (-1)^k (q+1)_k/k!") {
  // The end values are products of K exact-ish factors: O(K eps) relative each, summed.
  constexpr double end_value_tolerance = 8 * 64 * eps;  // 64-term sums of O(64 eps) products, 8x margin
  for (const auto& [p, q] : std::vector<std::pair<double, double>>{{0.0, 0.0}, {-0.5, 0.5}, {0.45, -0.95}, {-0.999, -0.999}, {1.5, 2.5}}) {
    const auto c = test_coefficients(64);
    const rq::jacobi_series<double> s(c, p, q);
    double at_plus = 0, at_minus = 0, pk = 1, qk = 1;
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (k > 0) {
        pk *= (static_cast<double>(k) + p) / static_cast<double>(k);
        qk *= (static_cast<double>(k) + q) / static_cast<double>(k);
      }
      at_plus += c[k] * pk;
      at_minus += (k % 2 == 0 ? 1 : -1) * c[k] * qk;
    }
    const double scale = magnitude(c, p, q);
    CHECK(std::abs(s(1.0) - at_plus) <= end_value_tolerance * scale);
    CHECK(std::abs(s(-1.0) - at_minus) <= end_value_tolerance * scale);
    CHECK(std::abs(s(0.0, 2.0) - at_plus) <= end_value_tolerance * scale);   // complements form
    CHECK(std::abs(s(2.0, 0.0) - at_minus) <= end_value_tolerance * scale);
  }
}

TEST_CASE("jacobi_series agrees with jacobi_clenshaw: bit-identical in both branches, K up to 2000") {
  // Both evaluate Clenshaw's recurrence for |x| < 1/2 and the difference form with the
  // coefficients of detail::difference_form_coefficients near the ends, in the same order.
  for (std::size_t K : {std::size_t(1), std::size_t(2), std::size_t(7), std::size_t(129), std::size_t(2000)}) {
    for (const auto& [p, q] : std::vector<std::pair<double, double>>{{0.0, 0.0}, {-0.45, 0.2}, {-0.999, 0.5}, {0.3, -0.999}}) {
      const auto c = test_coefficients(K);
      const rq::jacobi_series<double> s(c, p, q);
      for (int i = 0; i <= 400; ++i) {
        const double x = -1 + i / 200.0;
        CHECK(s(x) == rq::jacobi_clenshaw(c, p, q, x));
      }
      for (double d : {std::ldexp(1.0, -40), std::ldexp(1.0, -30), 0.25}) {  // 1 - d exact: the same u both ways
        CHECK(s(d, 2 - d) == rq::jacobi_clenshaw(c, p, q, 1 - d));
        CHECK(s(2 - d, d) == rq::jacobi_clenshaw(c, p, q, d - 1));
      }
    }
  }
}

TEST_CASE("jacobi_series::evaluate equals operator() at every point, bit for bit, in every branch and lane count") {
  // evaluate sums four points at a time with the recurrences interleaved, after sorting the points
  // by branch; the per-point operations are those of operator(). Points: all three branches in
  // shuffled order, the branch switches x = +-1/2, the ends, |x| > 1 (Clenshaw, as operator()), and
  // counts 0 ... 9 so that every remainder of the 4-point blocks occurs in every branch.
  for (std::size_t K : {std::size_t(1), std::size_t(2), std::size_t(3), std::size_t(84), std::size_t(700)}) {
    for (const auto& [p, q] : std::vector<std::pair<double, double>>{{0.0, 0.0}, {-0.45, 0.2}, {-0.999, 0.5}}) {
      const rq::jacobi_series<double> s(test_coefficients(K), p, q);
      std::vector<double> xs{0.5, -0.5, 1.0, -1.0, 1.02, -1.01, 0.0, std::ldexp(1.0, -40) - 1, 1 - std::ldexp(1.0, -30)};
      for (int i = 0; i < 61; ++i) xs.push_back(std::sin(1.3 * i + 0.2));  // shuffled over [-1, 1]
      std::vector<std::size_t> counts{xs.size()};
      for (std::size_t count = 0; count < 10; ++count) counts.push_back(count);
      for (std::size_t count : counts) {
        std::vector<double> out(count, -7.0);
        s.evaluate(xs.data(), out.data(), count);
        for (std::size_t i = 0; i < count; ++i) CHECK(out[i] == s(xs[i]));
      }
    }
  }
  const std::vector<double> none;
  CHECK_NOTHROW(rq::jacobi_series<double>().evaluate(none.data(), nullptr, 0));
  const std::vector<double> bad{0.1, std::nan(""), 0.2};
  std::vector<double> out(3, 5.0);
  rhabel_test::check_domain_error_mentions([&] { rq::jacobi_series<double>(test_coefficients(3), 0.0, 0.0).evaluate(bad.data(), out.data(), 3); },
                                           {"jacobi_series::evaluate", "x = ", "finite"});
  CHECK(out[0] == 5.0);  // nothing written before the error
}

// Regression: beyond [-1, 1] a long series overflows (P_700(-3) ~ 1e535); the sum came back as
// NaN (inf - inf in Clenshaw's recurrence). Now std::overflow_error naming the function and x, from
// every entry point; moderate |x| > 1 still sums.
TEST_CASE("jacobi_series and jacobi_clenshaw: a sum beyond the range of double is an overflow_error, never NaN") {
  const auto c = test_coefficients(700);
  const rq::jacobi_series<double> s(c, 0.3, -0.2);
  auto check_overflow = [](auto&& call, const char* function) {
    bool thrown = false;
    try {
      call();
    } catch (const std::overflow_error& e) {
      thrown = true;
      const std::string what = e.what();
      CHECK(what.find(function) != std::string::npos);
      CHECK(what.find("x = -3") != std::string::npos);
    }
    CHECK(thrown);
  };
  check_overflow([&] { (void)s(-3.0); }, "jacobi_series");
  check_overflow([&] { (void)rq::jacobi_clenshaw(c, 0.3, -0.2, -3.0); }, "jacobi_clenshaw");
  const std::vector<double> xs{0.1, -3.0, 0.2};
  std::vector<double> out(xs.size());
  check_overflow([&] { s.evaluate(xs.data(), out.data(), xs.size()); }, "jacobi_series::evaluate");
  CHECK(std::isfinite(s(1.02)));  // P_700(1.02) ~ e^140: in range
}

#if RHABEL_TEST_MULTIPRECISION  // 50 digits: not in the sanitize build (tests/CMakeLists.txt)
TEST_CASE("jacobi_series of a Legendre sum matches the 50-digit sum to O(K eps)") {
  constexpr std::size_t K = 300;
  constexpr double legendre_tolerance = 4 * K * eps;  // |P_k| <= 1, sum of K terms each O(k eps)/k
  const auto c = test_coefficients(K);
  const rq::jacobi_series<double> s(c, 0.0, 0.0);
  const std::vector<bf50> cb(c.begin(), c.end());
  const rq::jacobi_series<bf50> sb(cb, bf50(0), bf50(0));
  double scale = 0;
  for (double v : c) scale += std::abs(v);
  for (double x : {-0.999, -0.7, -0.3, 0.0, 0.123, 0.5, 0.9, 0.99999}) {
    const double exact = static_cast<double>(sb(bf50(x)));
    CHECK(std::abs(s(x) - exact) <= legendre_tolerance * scale);
  }
}
#endif  // RHABEL_TEST_MULTIPRECISION

TEST_CASE("jacobi_series and jacobi_clenshaw reject bad exponents, complements and non-finite x") {
  CHECK_THROWS_AS(rq::jacobi_series<double>(std::vector<double>{1.0}, -1.0, 0.0), std::domain_error);
  const rq::jacobi_series<double> s(std::vector<double>{1.0, 2.0}, 0.0, 0.0);
  CHECK_THROWS_AS(s(-0.1, 2.0), std::domain_error);
  CHECK_THROWS_AS(s(1.0, 3.0), std::domain_error);
  // Regression: a NaN or infinite x returned NaN instead of an error.
  rhabel_test::check_domain_error_mentions([&] { (void)s(std::nan("")); }, {"jacobi_series", "x = ", "finite"});
  rhabel_test::check_domain_error_mentions(
      [] { (void)rq::jacobi_clenshaw(std::vector<double>{1.0, 2.0}, 0.0, 0.0, std::numeric_limits<double>::infinity()); },
      {"jacobi_clenshaw", "x = ", "finite"});
  CHECK(rq::jacobi_series<double>()(0.3) == 0.0);
}
