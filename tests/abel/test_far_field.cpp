// Tests of rhabel/abel/far_field.hpp (the interpolative far field of many intervals):
// against the direct sum by a fine Gauss-Jacobi rule of each density (shares no code with the
// tree, the moments or the interpolation), on rows of equal intervals and on irregular layouts
// (widths over three decades, gaps from 1e-3 to 10 widths, a layout far from the origin); and
// the bookkeeping (a pair of leaves left out or counted twice would show as an O(1) error in the
// comparison, which sums every leaf that is not near).
#include <doctest/doctest.h>

#include "rhabel/abel.hpp"
#include "support.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <stdexcept>
#include <vector>

using namespace rhabel::abel;
using namespace abel_test;
using ff = far_field<double>;

namespace {

struct layout {
  std::vector<ff::box> boxes;
  std::vector<jacobi_density<double>> g;
};

/// Densities w P-series with decaying random coefficients on the given boxes (bounded/unbounded
/// classes alternate), exponents of the class nu = 0 and nu = -1.
layout densities(const abel_parameters<double>& par, const std::vector<ff::box>& boxes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  layout out{boxes, {}};
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const auto e = par.exponents(edge::bounded, i % 2 ? edge::unbounded : edge::bounded);
    jacobi_density<double> g;
    g.lo = boxes[i].lo, g.hi = boxes[i].hi, g.gam = e.gam, g.del = e.del;
    for (int n = 0; n < 12; ++n) g.coefficients.push_back(u(rng) * std::pow(0.5, n));
    out.g.push_back(g);
  }
  return out;
}

/// The direct far sum at the point of leaf j at distance s_off from its lo: every i not near j
/// by a 100-point Gauss-Jacobi rule of g_i's weight (the kernel is smooth on I_i there:
/// admissible pairs are a width apart), t - s from distances (no cancellation far from the
/// origin); and the scale sum int |K g| for the relative error.
std::pair<double, double> direct(const abel_parameters<double>& par, const layout& L, const ff& F, std::size_t j,
                                 double s_off) {
  static std::map<std::pair<double, double>, rhabel::quadrature::quadrature_rule<double>> rules;
  double sum = 0, scale = 0;
  const auto& near = F.near_leaves(j);
  for (std::size_t i = 0; i < L.g.size(); ++i) {
    if (i == j || std::binary_search(near.begin(), near.end(), i)) continue;
    const auto& g = L.g[i];
    auto it = rules.find({g.del, g.gam});
    if (it == rules.end()) it = rules.emplace(std::make_pair(g.del, g.gam), rhabel::quadrature::gauss_jacobi<double>(100, g.del, g.gam)).first;
    const auto& rule = it->second;
    const double h = g.half_length();
    for (std::size_t q = 0; q < rule.size(); ++q) {
      const double t_minus_s = i > j ? h * rule.x_minus_lo[q] + (g.lo - L.g[j].lo) - s_off
                                     : -(h * rule.hi_minus_x[q] + (L.g[j].lo - g.hi) + s_off);
      const double v = h * rule.weight[q] * g.series(rule.x[q]) * cross_kernel(par, t_minus_s);
      sum += v, scale += std::abs(v);
    }
  }
  return {sum, scale};
}

/// Every leaf's moments of its density.
std::vector<ff::vector> leaf_moments(const ff& F, const layout& L) {
  std::vector<ff::vector> W;
  for (std::size_t i = 0; i < L.g.size(); ++i) W.push_back(F.density_moments(i, L.g[i]));
  return W;
}

/// Max over leaves and 7 points each of |far - direct| / scale, for the far field F of L's densities.
double far_error(const abel_parameters<double>& par, const layout& L, const ff& F) {
  const auto local = F.far_values(leaf_moments(F, L));
  double worst = 0;
  for (std::size_t j = 0; j < L.g.size(); ++j)
    for (double x : {-1.0, -0.9, -0.31, 0.0, 0.44, 0.97, 1.0}) {
      const auto [sum, scale] = direct(par, L, F, j, L.g[j].half_length() * (1 + x));
      if (scale > 0) worst = std::max(worst, std::abs(F.interpolate(local[j], x) - sum) / scale);
    }
  return worst;
}

/// The same for the far field built on L's boxes at order p.
double far_error(const abel_parameters<double>& par, const layout& L, std::size_t p) {
  return far_error(par, L, ff(par, L.boxes, p));
}

std::vector<ff::box> row(std::size_t K, double pitch, double origin = 0) {
  std::vector<ff::box> b;
  for (std::size_t i = 0; i < K; ++i) b.push_back({origin + pitch * double(i), origin + pitch * double(i) + 1});
  return b;
}

std::vector<ff::box> irregular(std::size_t K, unsigned seed, double origin = 0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<ff::box> b;
  double x = origin;
  for (std::size_t i = 0; i < K; ++i) {
    const double w = std::pow(10.0, -3 * u(rng));          // widths 1e-3 .. 1
    const double gap = w * std::pow(10.0, 4 * u(rng) - 3);  // 1e-3 .. 10 widths
    b.push_back({x, x + w});
    x += w + gap;
  }
  return b;
}

}  // namespace

TEST_CASE("far field: near leaves of a row are its two neighbours, and rows have O(K) admissible pairs") {
  const abel_parameters<double> par(0.3, 0.2);
  for (std::size_t K : {1, 2, 3, 7, 64, 100}) {
    const ff F(par, row(K, 1.5), 12);
    std::size_t near = 0;
    for (std::size_t j = 0; j < K; ++j) {
      near += F.near_leaves(j).size();
      for (std::size_t i : F.near_leaves(j)) CHECK(i != j);
    }
    // Row at pitch 1.5 (gap 0.5 < eta = 1 width): exactly the two neighbours are near.
    CHECK(near == (K > 1 ? 2 * (K - 1) : 0));
    CHECK(F.pairs() <= 7 * K);
  }
}

TEST_CASE("far field: the interpolative sum matches the direct sum (rows, irregular, far from the origin)") {
  // Tolerance: the header's estimate eps/100 of the kernel at p = 26 relative to sum |K g|; 64 eps
  // covers the rounding of the O(log K) transfers and of the direct sum itself (~100 terms a leaf).
  const double tol = 64 * eps;
  for (double alpha : {0.0, 0.3, 0.5, 0.9}) {
    const abel_parameters<double> par(alpha, 0.3);
    CAPTURE(alpha);
    CHECK(far_error(par, densities(par, row(40, 1.5), 1), 26) < tol);
    CHECK(far_error(par, densities(par, row(33, 3.0, 1e6), 2), 26) < tol);
    CHECK(far_error(par, densities(par, irregular(50, 3), 0), 26) < tol);
    CHECK(far_error(par, densities(par, irregular(50, 4, -1e4), 4), 26) < tol);
  }
}

TEST_CASE("far field: order_for(tolerance) reaches the tolerance; the error falls with p") {
  const abel_parameters<double> par(0.25, 0.0);
  const auto L = densities(par, irregular(40, 5), 5);
  for (double tol : {1e-4, 1e-8, 1e-12}) {
    CAPTURE(tol);
    CHECK(far_error(par, L, ff::order_for(tol)) < tol);
  }
  CHECK(far_error(par, L, 8) > far_error(par, L, 16));  // not a test that cannot fail: p matters
}

TEST_CASE("far field: one tree for intervals inside its boxes (far_field(boxes, intervals)) matches the direct sum") {
  // The tree is built on boxes; the densities live on intervals that fill 60 ... 100 % of their box
  // at random offsets (one interval is its whole box). Tolerance as above: the re-expansion into the
  // box is exact (degree p - 1), so only the boxes' interpolation error and rounding remain.
  const double tol = 64 * eps;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (double alpha : {0.0, 0.3, 0.9}) {
    const abel_parameters<double> par(alpha, 0.3);
    CAPTURE(alpha);
    for (const auto& boxes : {row(40, 1.5), irregular(50, 8, -1e4)}) {
      std::vector<ff::box> inside;
      for (std::size_t i = 0; i < boxes.size(); ++i) {
        const double w = boxes[i].hi - boxes[i].lo, keep = i == 3 ? 1.0 : 0.6 + 0.4 * u(rng);
        const double lo = boxes[i].lo + (1 - keep) * w * u(rng);
        inside.push_back({lo, std::min(boxes[i].hi, lo + keep * w)});
      }
      const ff tree(par, boxes, 26);
      REQUIRE(tree.covers(inside));
      const auto L = densities(par, inside, 9);
      const ff F(tree, inside);
      CHECK(F.pairs() == tree.pairs());
      CHECK(far_error(par, L, F) < tol);
      // The interval's own moments without the re-expansion (the tree's leaves taken as the
      // intervals) are wrong by O(1): the comparison sees the difference.
      CHECK(far_error(par, L, tree) > 1e3 * tol);
    }
  }
  // An interval outside its box is refused.
  const abel_parameters<double> par(0.3, 0.3);
  const ff tree(par, row(4, 1.5), 12);
  auto outside = row(4, 1.5);
  outside[2].hi += 0.01;
  CHECK_FALSE(tree.covers(outside));
  CHECK_THROWS_AS(ff(tree, outside), std::invalid_argument);
  CHECK_FALSE(tree.covers(row(3, 1.5)));
}

namespace {

/// int_{I_i} k(t - x) g_i(t) dt by the 100-point rule of g_i's weight (x outside I_i), and the
/// same with |.| for the scale.
std::pair<double, double> leaf_direct(const std::function<double(double)>& k, const jacobi_density<double>& g, double x) {
  const auto rule = cached_gauss_jacobi_rule<double>(100, g.del, g.gam);
  const double h = g.half_length();
  double sum = 0, scale = 0;
  for (std::size_t q = 0; q < rule->size(); ++q) {
    const double t_minus_x = g.lo > x ? (g.lo - x) + h * rule->x_minus_lo[q] : -((x - g.hi) + h * rule->hi_minus_x[q]);
    const double v = h * rule->weight[q] * g.series(rule->x[q]) * k(t_minus_x);
    sum += v, scale += std::abs(v);
  }
  return {sum, scale};
}

}  // namespace

TEST_CASE("far field: at_point (the treecode) matches the direct sum inside leaves and in the gaps, for the cross and a log kernel") {
  // Tolerance as above: the interpolation in t alone at p = 26, eps/100 of the kernel's size.
  const double tol = 64 * eps;
  const abel_parameters<double> par(0.3, 0.4);
  const std::vector<std::function<double(double)>> kernels{
      [&](double d) { return cross_kernel(par, d); },
      [](double d) { return d > 0 ? -std::log(d) : 0.7 - 0.4 * std::log(-d); }};
  const auto L = densities(par, irregular(60, 7, 1e3), 7);
  for (const auto& k : kernels) {
    const ff F(k, L.boxes, 26);
    const auto boxes = F.upward(leaf_moments(F, L));
    double worst = 0;
    std::size_t points = 0;
    for (std::size_t j = 0; j + 1 < L.g.size(); ++j)
      for (double x : {L.g[j].lo + 0.3 * (L.g[j].hi - L.g[j].lo), L.g[j].hi + 0.5 * (L.g[j + 1].lo - L.g[j].hi)}) {
        double reference = 0, scale = 0;
        for (std::size_t i = 0; i < L.g.size(); ++i) {
          if (x >= L.g[i].lo && x <= L.g[i].hi) continue;  // the point's own leaf: excluded
          const auto [v, s] = leaf_direct(k, L.g[i], x);
          reference += v, scale += s;
        }
        const double tree = F.at_point(boxes, x, [&](std::size_t i) {
          return x >= L.g[i].lo && x <= L.g[i].hi ? 0.0 : leaf_direct(k, L.g[i], x).first;
        });
        worst = std::max(worst, std::abs(tree - reference) / scale);
        ++points;
      }
    CHECK(points == 118);
    CHECK(worst < tol);
  }
}
