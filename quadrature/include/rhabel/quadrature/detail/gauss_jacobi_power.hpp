// rhabel/quadrature/detail/gauss_jacobi_power.hpp
//
// Private part of gauss_jacobi.hpp: the endpoint factor s^a c^b of the interior weights of the
// asymptotic path, w = Q s^(2p+1) c^(2q+1) / G'^2 (s = sin(t/2), c = cos(t/2)), for a batch of
// consecutive nodes, with two calls of pow per batch of 32 instead of two per node (glibc's pow
// costs ~9-14 ns here; two per node were a sixth of the rule at n = 10^4 for generic exponents).
//
// What it computes. endpoint_power{a, b}(count, s, c, out) sets out[i] = s[i]^a c[i]^b for
// finite a, b and any s[i], c[i] (in the rule a = 2p + 1, b = 2q + 1 in (-1, 61], s, c in
// (0, 1]); endpoint_power{a, b}(s, c) returns one such value directly (two pows, or sqrt and
// products), bit for bit the batch form's value for a batch of one (tested). Accuracy (relative, an estimate from tests, not a bound): within 2 eps, measured
// 1.4 eps (tests/quadrature/test_gauss_jacobi.cpp, "endpoint_power" cases: node-like batches
// and random ones against long double powl, s from subnormal to 1, exponents -1 + 1e-3 ... 61);
// two calls of pow and their product, the former form, measured 1.9 ulp of the result's binade
// on the same inputs. Exponents 0, 1/2, 1, 3/2, 2 of both factors keep sqrt and
// products (within 1.5 ulp). Where the series is not taken (below) the result is exactly
// pow(s, a) * pow(c, b), including its zeros, infinities, NaN and intermediate overflow.
//
// Method. Against an anchor (s0, c0) of the batch (its middle point),
//   s^a c^b = s0^a c0^b exp(y),  y = a log(s/s0) + b log(c/c0),  log(s/s0) = 2 atanh f,
//   f = (s - s0)/(s + s0)  (and g the same for c),
// with s0^a c0^b = pow(s0, a) pow(c0, b) once per batch, the product kept exactly as a pair
// (Dekker's two-product). s - s0 is exact (Sterbenz's lemma: s/s0 in [1/2, 2] when |f| <= 1/3),
// so f has relative error <= 1.5 eps, and y absolute error <= ~3 eps (|a f| + |b g|) + the
// series' roundings. A point takes the series only when |a f|, |b g| <= max_scaled_ratio = 1/16
// (so |y| <= 1/4 and y errs by <= 0.4 eps) and |f|, |g| <= max_ratio = 1/8; every other point,
// and every point of a batch whose anchor is not a comfortably normal double, takes pow. In the
// rule's batches of 32 nodes (anchor in the middle, so a point is at most 16 nodes from it and
// |a f| ~ 8 |a| / k at the node k from the end) this leaves pow to the first few batches (k <
// ~130 for |a| ~ 1) and to large exponents (a = 61: k < ~7800).
//   2 atanh f = 2 f (1 + z/3 + ... + z^8/17), z = f^2 <= 1/64: truncation below 2^-58 relative;
//   exp(y) = 1 + (y + y^2 E(y)), E the Taylor series to y^13/15!: truncation below 1e-21.
// Error: the anchor (two pows, within ~1 ulp together; the product exact), exp(y) (0.4 eps from
// y, 0.5 ulp rounding), the final sum (0.5 ulp). No fused multiply-add and no -ffast-math are
// needed: plain IEEE arithmetic in a loop without branches or calls that the compiler
// vectorises (two points per SSE2 instruction; 10 ns per point against 17.5 ns for two pow,
// measured on node-like batches).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace rhabel::quadrature::detail {

// a b - product exactly for product = fl(a b) (Dekker's two-product with Veltkamp's split, no
// FMA: std::fma is a libm call in this build and would stop vectorisation). |a|, |b| < 2^995.
inline double two_product_error(double a, double b, double product) {
  constexpr double splitter = 134217729.0;  // 2^27 + 1
  const double a_scaled = splitter * a, b_scaled = splitter * b;
  const double a_hi = a_scaled - (a_scaled - a), a_lo = a - a_hi;
  const double b_hi = b_scaled - (b_scaled - b), b_lo = b - b_hi;
  return ((a_hi * b_hi - product) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
}

// s^a c^b for a batch, see the header comment. The exponents are fixed at construction.
class endpoint_power {
 public:
  // Largest |a f| and |b g| taken by the series (f = (s - s0)/(s + s0)).
  static constexpr double max_scaled_ratio = 1.0 / 16;
  // Largest |f| taken by the series (its truncation at z^8: below 2^-57 relative to y).
  static constexpr double max_ratio = 0.125;
  // Points per anchor (the caller's batches are at most this long; longer ones are split).
  static constexpr std::size_t chunk = 32;

  endpoint_power(double a, double b) : a_(a), b_(b), kind_a_(kind_of(a)), kind_b_(kind_of(b)) {}

  // out[i] = s[i]^a c[i]^b for i < count.
  void operator()(std::size_t count, const double* s, const double* c, double* out) const {
    if (kind_a_ != generic && kind_b_ != generic) {
      for (std::size_t i = 0; i < count; ++i) out[i] = simple(s[i], kind_a_) * simple(c[i], kind_b_);
      return;
    }
    for (std::size_t first = 0; first < count; first += chunk) {
      const std::size_t size = count - first < chunk ? count - first : chunk;
      evaluate_chunk(size, s + first, c + first, out + first);
    }
  }

  // One value, directly: sqrt and products when both exponents are simple, else pow(s, a) *
  // pow(c, b). The same value as the batch form for a batch of one (whose anchor is the point
  // itself, so its series term is exactly 0 and anchor_hi + anchor_lo rounds to pow * pow, or
  // it takes pow outright), without the anchor's two-product and the series.
  double operator()(double s, double c) const {
    if (kind_a_ != generic && kind_b_ != generic) return simple(s, kind_a_) * simple(c, kind_b_);
    return by_pow(s, c);
  }

 private:
  enum kind : int { zero, half, one, three_halves, two, generic };
  static kind kind_of(double e) {
    return e == 0 ? zero : e == 0.5 ? half : e == 1 ? one : e == 1.5 ? three_halves : e == 2 ? two : generic;
  }
  // x^e for the exponents 0, 1/2, 1, 3/2, 2 by sqrt and products (within 1.5 ulp).
  static double simple(double x, kind k) {
    switch (k) {
      case zero: return 1;
      case half: return std::sqrt(x);
      case one: return x;
      case three_halves: return x * std::sqrt(x);
      case two: return x * x;
      default: return x;  // not reached
    }
  }

  double by_pow(double s, double c) const { return std::pow(s, a_) * std::pow(c, b_); }

  // 2 atanh(f) / (2 f) = 1 + z/3 + ... + z^8/17, z = f^2 <= 1/64 (truncation z^9/19 < 2^-58).
  static double atanh_factor(double z) {
    return 1 + z * (1.0 / 3 +
                    z * (1.0 / 5 +
                         z * (1.0 / 7 +
                              z * (1.0 / 9 +
                                   z * (1.0 / 11 + z * (1.0 / 13 + z * (1.0 / 15 + z * (1.0 / 17))))))));
  }

  // exp(y) - 1 for |y| <= 1/4: y + y^2 (1/2 + y/6 + ... + y^12/14!) (truncation y^15/15! < 1e-21).
  static double expm1_small(double y) {
    const double E =
        1.0 / 2 +
        y * (1.0 / 6 +
             y * (1.0 / 24 +
                  y * (1.0 / 120 +
                       y * (1.0 / 720 +
                            y * (1.0 / 5040 +
                                 y * (1.0 / 40320 +
                                      y * (1.0 / 362880 +
                                           y * (1.0 / 3628800 +
                                                y * (1.0 / 39916800 +
                                                     y * (1.0 / 479001600 +
                                                          y * (1.0 / 6227020800 + y * (1.0 / 87178291200))))))))))));
    return y + y * y * E;
  }

  void evaluate_chunk(std::size_t size, const double* s, const double* c, double* out) const {
    const std::size_t middle = size / 2;
    const double s0 = s[middle], c0 = c[middle];
    constexpr double smallest = std::numeric_limits<double>::min(), largest = std::numeric_limits<double>::max();
    // The anchor factor s0^a c0^b = anchor_hi + anchor_lo: the two pows (each within
    // 0.52 ulp) and their product exactly (Dekker's two-product; long double powl would
    // cost 1 us here).
    const double power_s = std::pow(s0, a_), power_c = std::pow(c0, b_);
    const double anchor_hi = power_s * power_c;
    double anchor_lo = two_product_error(power_s, power_c, anchor_hi);
    if (!std::isfinite(anchor_lo)) anchor_lo = 0;  // Dekker's split overflows beyond 2^996
    // The anchor must be a positive normal double, and its factor comfortably normal
    // (exp(y) is in [0.77, 1.3]).
    if (!(s0 >= smallest && s0 <= largest && c0 >= smallest && c0 <= largest && anchor_hi >= 4 * smallest &&
          anchor_hi <= largest / 4)) {
      for (std::size_t i = 0; i < size; ++i) out[i] = by_pow(s[i], c[i]);
      return;
    }
    double scaled[chunk], ratio[chunk];
    for (std::size_t i = 0; i < size; ++i) {
      const double f = (s[i] - s0) / (s[i] + s0), g = (c[i] - c0) / (c[i] + c0);
      const double af = a_ * f, bg = b_ * g;
      const double y = 2 * (af * atanh_factor(f * f) + bg * atanh_factor(g * g));
      const double e = expm1_small(y);
      out[i] = anchor_hi + (anchor_lo + anchor_hi * e);  // (anchor_hi + anchor_lo)(1 + e), anchor_lo e dropped
      scaled[i] = std::max(std::abs(af), std::abs(bg));
      ratio[i] = std::max(std::abs(f), std::abs(g));
    }
    for (std::size_t i = 0; i < size; ++i) {
      // NaN ratios (zero or non-finite inputs) fail the comparisons as well.
      if (!(scaled[i] <= max_scaled_ratio && ratio[i] <= max_ratio)) out[i] = by_pow(s[i], c[i]);
    }
  }

  double a_, b_;
  kind kind_a_, kind_b_;
};

}  // namespace rhabel::quadrature::detail
