// The FFT product of the coarse contact search (punch/src/toeplitz_product.hpp, internal to the
// punch library) against the plain sum over the matrix entries, which shares nothing with it but
// the definition T(i, j) = t[j - i + n - 1].
#include <doctest/doctest.h>

#include "../punch/src/toeplitz_product.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

namespace {
using rhabel::punch::detail::toeplitz_product;

// The FFT's rounding grows like log2(M) eps times the row's sum of |T(i, j) v_j| (the header's
// bound); 64 eps covers M up to 2^13 with a margin of 4.
constexpr double fft_tol = 64 * std::numeric_limits<double>::epsilon();

std::vector<double> diagonals(std::size_t n, std::mt19937& rng) {
  // A kernel like the coarse search's: log-singular at 0, with a different decay on each side.
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> t(2 * n - 1);
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double d = std::abs(static_cast<double>(k) - static_cast<double>(n - 1)) + 0.5;
    t[k] = (k < n - 1 ? 0.7 : 1.0) * -std::log(d) + 0.01 * u(rng);
  }
  return t;
}

/// The largest relative difference between T.apply(v) (v random) and the plain sum over the
/// matrix entries t[j - i + n - 1], relative to each row's sum of |terms|.
double worst_whole_product(toeplitz_product& T, const std::vector<double>& t, std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd v(static_cast<Eigen::Index>(n));
  for (auto& x : v) x = u(rng);
  const Eigen::VectorXd y = T.apply(v);
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0, scale = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const double term = t[j - i + n - 1] * v[static_cast<Eigen::Index>(j)];
      sum += term;
      scale += std::abs(term);
    }
    worst = std::max(worst, std::abs(y[static_cast<Eigen::Index>(i)] - sum) / scale);
  }
  return worst;
}
}  // namespace

TEST_CASE("toeplitz_product: the FFT product equals the matrix's sum, whole and restricted") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const std::size_t n : {1, 2, 3, 17, 256, 1000}) {
    CAPTURE(n);
    const auto t = diagonals(n, rng);
    toeplitz_product T(t, n);
    CHECK(worst_whole_product(T, t, n, rng) < fft_tol);
    // Restricted: every third column, the rows from n/2 on.
    std::vector<std::size_t> rows, columns;
    for (std::size_t j = 0; j < n; j += 3) columns.push_back(j);
    for (std::size_t i = n / 2; i < n; ++i) rows.push_back(i);
    Eigen::VectorXd w(static_cast<Eigen::Index>(columns.size()));
    for (auto& x : w) x = u(rng);
    const Eigen::VectorXd z = T.apply(rows, columns, w);
    REQUIRE(z.size() == static_cast<Eigen::Index>(rows.size()));
    double worst = 0;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      double sum = 0, scale = 0;
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const double term = t[columns[c] - rows[r] + n - 1] * w[static_cast<Eigen::Index>(c)];
        sum += term;
        scale += std::abs(term);
      }
      worst = std::max(worst, std::abs(z[static_cast<Eigen::Index>(r)] - sum) / scale);
    }
    CHECK(worst < fft_tol);
  }
}

TEST_CASE("toeplitz_product: a circulant of a fast length by FFTs of its own length equals the matrix's sum") {
  // n = 4 2^a 3^b 5^c is taken at its own length; 4 * 7 and 6 (not multiples of 4 with only 2, 3,
  // 5) fall back to the padded transform: both must give the circulant's product.
  std::mt19937 rng(11);
  for (const std::size_t n : {4, 6, 28, 60, 400, 1000, 1536}) {
    CAPTURE(n);
    auto t = diagonals(n, rng);
    for (std::size_t k = 1; k < n; ++k) t[n - 1 + k] = t[k - 1];  // T(i, j) = c((i - j) mod n)
    toeplitz_product T(t, n, true);
    const bool own = n % 4 == 0 && n != 28;
    if (own) CHECK(T.transform_length() == n);
    if (!own) CHECK(T.transform_length() >= 2 * n);
    CHECK(worst_whole_product(T, t, n, rng) < fft_tol);
  }
}
