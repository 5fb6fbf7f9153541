// tools/reference/gauss_jacobi_reference.cpp
//
// Generator of tests/data/gauss_jacobi_reference.csv: nodes (as 1 - x and 1 + x) and weights
// of Gauss-Jacobi rules for the weight (1 - x)^p (1 + x)^q, printed with 60 significant digits
// (at least 40 of them correct, see below), for the
// cases listed in main() (selected node indices for large n).
//
// Independence from the code under test. rhabel's double rule is used ONLY as the starting
// value of Newton's method. Everything else is computed here in 64-digit binary floating
// point (boost::multiprecision::cpp_bin_float<64>) by a different algorithm from rhabel's:
//  * the recurrence of the ORTHONORMAL polynomials (the Jacobi matrix of Golub & Welsch),
//    b_{k+1} p_{k+1}(x) = (x - a_k) p_k(x) - b_k p_{k-1}(x),  p_0 = mu_0^(-1/2),
//    run in x (not in 1 - x): at 64 digits a node with 1 - x = 1e-13 still has 51 digits of
//    1 - x, and the recurrence's O(sqrt(n)) eps error is far below the printed 60 digits;
//  * Newton's method p_n / p_n' until the step is below 1e-50 times the distance of the node to
//    its nearer end plus 1e-56 (x itself is resolved to ~1e-64; at n = 10^6 the recurrence's
//    rounding is ~1e-58), so every printed 1 - x and 1 + x has at least 40 correct digits
//    (more than 50 for n <= 10^4);
//  * weights from the Christoffel function w = 1 / sum_{k<n} p_k(x)^2 (Szego (3.4.8)), not
//    from the derivative formula that rhabel uses;
//  * mu_0 = 2^(p+q+1) Gamma(p+1) Gamma(q+1) / Gamma(p+q+2) through Boost.Math at 64 digits.
// The exponents are the exact double values of the literals (-0.9 means the double nearest
// -0.9), converted exactly, so the table describes the rule the double code is asked for.
//
// Build and run (single thread; the n = 10^6 cases take a few minutes each):
//   cmake --preset release -DRHABEL_BUILD_TOOLS=ON && cmake --build build --target gauss_jacobi_reference
//   (builds build/bin/gauss_jacobi_reference; the tools are off in the default build)
//   build/bin/gauss_jacobi_reference small > /tmp/small.csv    # n <= 65536
//   build/bin/gauss_jacobi_reference large > /tmp/large.csv    # n = 10^6
//   build/bin/gauss_jacobi_reference corner > /tmp/corner.csv  # both exponents near -1
//   cat /tmp/small.csv /tmp/large.csv /tmp/corner.csv > tests/data/gauss_jacobi_reference.csv
// (the CSV header line is printed by the "small" group only). The "corner" group (issue #2:
// p and q both within 1e-5 of -1, where p + q + 2 ~ 0 made the former expanded recurrence
// coefficients cancel) takes about a minute.
#include <rhabel/quadrature/gauss_jacobi.hpp>

#include <boost/math/special_functions/gamma.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <set>
#include <string>
#include <vector>

namespace {

using mp = boost::multiprecision::number<boost::multiprecision::cpp_bin_float<64>>;

struct reference_case {
  std::size_t n;
  double p, q;
  std::vector<std::size_t> indices;  // 0-based, increasing x
};

std::string format(const mp& value) { return value.str(60, std::ios_base::scientific); }

// Indices j and n-1-j for every j in from_end (clipped), plus the given interior fractions.
std::vector<std::size_t> select(std::size_t n, const std::vector<std::size_t>& from_end,
                                const std::vector<double>& fractions) {
  std::set<std::size_t> chosen;
  for (std::size_t j : from_end) {
    if (j < n) {
      chosen.insert(j);
      chosen.insert(n - 1 - j);
    }
  }
  for (double f : fractions) chosen.insert(std::min(n - 1, static_cast<std::size_t>(f * static_cast<double>(n))));
  return {chosen.begin(), chosen.end()};
}

void run_case(const reference_case& c) {
  const std::size_t n = c.n;
  const mp p = mp(c.p), q = mp(c.q);
  // Jacobi matrix of the orthonormal Jacobi polynomials.
  std::vector<mp> a(n), b(n + 1), inverse_b(n + 1);
  b[0] = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const mp kk = mp(k), s = 2 * kk + p + q;
    a[k] = k == 0 ? (q - p) / (p + q + 2) : (q * q - p * p) / (s * (s + 2));
    const mp k1 = kk + 1, s1 = 2 * k1 + p + q;  // b_{k+1}
    b[k + 1] = k == 0 ? sqrt(4 * (1 + p) * (1 + q) / ((2 + p + q) * (2 + p + q) * (3 + p + q)))
                      : sqrt(4 * k1 * (k1 + p) * (k1 + q) * (k1 + p + q) / (s1 * s1 * (s1 + 1) * (s1 - 1)));
    inverse_b[k + 1] = 1 / b[k + 1];
  }
  const mp mu0 = pow(mp(2), p + q + 1) * boost::math::tgamma(p + 1) * boost::math::tgamma(q + 1) /
                 boost::math::tgamma(p + q + 2);
  const mp p0 = 1 / sqrt(mu0);

  const auto start = rhabel::quadrature::gauss_jacobi<double>(n, c.p, c.q);
  const std::size_t K = c.indices.size();
  std::vector<mp> x(K), distance(K);
  std::vector<bool> right(K);
  for (std::size_t j = 0; j < K; ++j) {
    const std::size_t i = c.indices[j];
    right[j] = start.hi_minus_x[i] <= start.x_minus_lo[i];
    x[j] = right[j] ? 1 - mp(start.hi_minus_x[i]) : mp(start.x_minus_lo[i]) - 1;
  }
  std::vector<mp> weight(K);
  std::vector<bool> done(K, false);
  for (int iteration = 0; iteration < 30; ++iteration) {
    std::vector<std::size_t> active;
    for (std::size_t j = 0; j < K; ++j) {
      if (!done[j]) active.push_back(j);
    }
    if (active.empty()) break;
    const std::size_t A = active.size();
    std::vector<mp> P(A, p0), Pm(A, mp(0)), D(A, mp(0)), Dm(A, mp(0)), christoffel(A, mp(0));
    std::vector<std::size_t> sign_changes(A, 0);
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t t = 0; t < A; ++t) {
        christoffel[t] += P[t] * P[t];
        if (k > 0 && (P[t] < 0) != (Pm[t] < 0)) ++sign_changes[t];
        const mp shifted = x[active[t]] - a[k];
        const mp Pn = (shifted * P[t] - b[k] * Pm[t]) * inverse_b[k + 1];
        const mp Dn = (shifted * D[t] + P[t] - b[k] * Dm[t]) * inverse_b[k + 1];
        Pm[t] = P[t];
        P[t] = Pn;
        Dm[t] = D[t];
        D[t] = Dn;
      }
    }
    for (std::size_t t = 0; t < A; ++t) {
      const std::size_t j = active[t];
      const mp step = P[t] / D[t];
      const mp near = right[j] ? 1 - x[j] : 1 + x[j];
      weight[j] = 1 / christoffel[t];  // at the pre-step x: the step is below 1e-30 relative here
      x[j] -= step;
      if (abs(step) < near * mp(1e-50) + mp(1e-56)) {
        done[j] = true;
        // Sturm: the sign changes of p_0(x), ..., p_{n-1}(x) at a zero x of p_n count the
        // zeros of p_n above x, so the node found is the one with the requested index.
        if (sign_changes[t] != n - 1 - c.indices[j]) {
          std::fprintf(stderr, "WRONG INDEX n=%zu p=%.17g q=%.17g index=%zu (zeros above: %zu)\n", n, c.p, c.q,
                       c.indices[j], sign_changes[t]);
          std::exit(1);
        }
      }
    }
  }
  for (std::size_t j = 0; j < K; ++j) {
    if (!done[j]) {
      std::fprintf(stderr, "no convergence n=%zu p=%.17g q=%.17g index=%zu\n", n, c.p, c.q, c.indices[j]);
    }
    std::printf("%zu,%.17g,%.17g,%zu,%s,%s,%s\n", n, c.p, c.q, c.indices[j], format(1 - x[j]).c_str(),
                format(1 + x[j]).c_str(), format(weight[j]).c_str());
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const bool small = argc > 1 && std::strcmp(argv[1], "small") == 0;
  const bool large = argc > 1 && std::strcmp(argv[1], "large") == 0;
  const bool corner = argc > 1 && std::strcmp(argv[1], "corner") == 0;
  if (!small && !large && !corner) {
    std::fprintf(stderr, "usage: gauss_jacobi_reference small|large|corner\n");
    return 2;
  }
  const std::vector<double> exponents = {-0.999, -0.9, -0.5, 0.0, 0.25, 0.5, 5.0, 30.0};
  std::vector<reference_case> cases;
  if (small) {
    std::printf("n,p,q,index,one_minus_x,one_plus_x,weight\n");
    // n = 1, 2, 3 (all nodes); n = 100 (recurrence path) and 101 (asymptotic path) at the
    // ends and a few interior nodes; n = 10^4 across the boundary/interior switch.
    const std::vector<std::size_t> ends_small = {0, 1, 2, 3, 4, 5, 6, 7, 9, 12, 16, 20, 25, 30, 40};
    const std::vector<std::size_t> ends_large = {0,  1,  2,  3,  4,  5,  6,  7,  9,  11,  13,  15,
                                                 19, 24, 29, 39, 49, 59, 79, 99, 119, 149};
    for (double p : exponents) {
      for (double q : exponents) {
        for (std::size_t n : {1, 2, 3}) cases.push_back({n, p, q, select(n, {0, 1, 2}, {})});
        for (std::size_t n : {100, 101}) cases.push_back({n, p, q, select(n, ends_small, {0.5})});
        cases.push_back({10000, p, q, select(10000, ends_large, {0.25, 0.5, 0.75})});
      }
    }
    // Published regression values (weight at the node nearest +1).
    cases.push_back({1024, 0.25, 0.0, select(1024, {0, 1, 2}, {0.5})});
    cases.push_back({65536, -0.9, 0.0, select(65536, {0, 1, 2}, {0.5})});
  } else if (corner) {
    // Both exponents near -1 (p + q + 2 in [2e-9, 1e-3]): every pair from {-1 + 1e-9,
    // -1 + 1e-5 (= -0.99999 in double), -0.999} with at least one exponent within 1e-5 of -1,
    // on both sides of the recurrence | asymptotic switch (40 | 41) and at 10^4.
    const std::vector<double> near_minus_one = {-1 + 1e-9, -1 + 1e-5, -0.999};
    const std::vector<std::size_t> ends = {0, 1, 2, 3, 4, 5, 6, 7, 9, 12, 16, 20, 25, 30, 40, 59, 99, 149};
    for (double p : near_minus_one) {
      for (double q : near_minus_one) {
        if (p == -0.999 && q == -0.999) continue;  // in the "small" group
        for (std::size_t n : {1, 2, 3, 16, 40, 41, 80, 101, 10000}) {
          cases.push_back({n, p, q, select(n, ends, {0.25, 0.5})});
        }
      }
    }
  } else {
    // Across the boundary/interior switch (index ~6 from each end for p <= 5, ~190 for 30).
    const std::vector<std::size_t> ends = {0, 1, 2, 3, 5, 9, 19, 59, 189, 199};
    for (auto [p, q] : std::vector<std::pair<double, double>>{
             {-0.9, 0.0}, {0.25, 0.0}, {-0.999, -0.5}, {0.5, 5.0}, {30.0, -0.999}}) {
      cases.push_back({1000000, p, q, select(1000000, ends, {0.5})});
    }
  }
  for (const auto& c : cases) run_case(c);
  return 0;
}
