// rhabel/abel/union_memory.hpp: a priori memory estimates of abel::solve_union (multi_interval.hpp)
// and the largest collocation degree that fits a memory budget, for K intervals at M collocation
// points each (T = K M unknowns), Real numbers of sizeof(Real) bytes.
//
//  * union_memory_bytes<Real>(K, M), union_degree_limit<Real>(K, bytes): the dense route (the
//    assembled T x T system and its LU).
//  * union_far_memory_bytes(far, M), union_far_degree_limit(far, bytes): the matrix-free route
//    (far_field.hpp) on the intervals of `far`.
// Accuracy: estimates of the peak of the allocations that grow with M (the measured peaks are in
// multi_interval.hpp's "Memory" paragraph); the fixed costs (the data, the quadrature caches) are
// not counted. The limits are exact for the estimates (bisection on integers; the estimates
// increase with M).
#pragma once

#include "rhabel/abel/far_field.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace rhabel::abel {

/// Estimated peak memory (bytes, as a double: no overflow for any size_t arguments) of one
/// dense solve of abel::solve_union for K intervals at M collocation points each, T = K M unknowns: the
/// larger of the assembly phase, T^2 + 6 M^2 numbers (the matrix plus one cross block's kernel
/// values M x Q, basis values Q x M and their M x M product; Q ~ 2M nodes at gaps down to 1e-4,
/// 2.5M at 1e-12), and the factorisation phase, T^2 numbers (LU in place) or 2 T^2 for non-IEEE
/// types (the inverse, see `condition`). Measured peaks: multi_interval.hpp's "Memory" paragraph.
template <class Real>
double union_memory_bytes(std::size_t K, std::size_t M) {
  const double T = double(K) * double(M), m = double(M);
  const double assembly = T * T + (K > 1 ? 6 * m * m : 0);
  const double factorisation = (std::is_floating_point_v<Real> ? 1 : 2) * T * T;
  return double(sizeof(Real)) * std::max(assembly, factorisation);
}

/// The largest M with union_memory_bytes<Real>(K, M) <= bytes (K >= 1; bisection, the estimate
/// is increasing in M and >= sizeof(Real) (K M)^2).
template <class Real>
std::size_t union_degree_limit(std::size_t K, std::size_t bytes) {
  using std::sqrt;
  std::size_t lo = 0;  // union_memory_bytes(K, lo) <= bytes
  std::size_t hi = static_cast<std::size_t>(sqrt(double(bytes) / (double(sizeof(Real)) * double(K) * double(K)))) + 1;
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    (union_memory_bytes<Real>(K, mid) <= double(bytes) ? lo : hi) = mid;
  }
  return lo;
}

/// Estimated peak memory (bytes) of the matrix-free route (far field, far_field.hpp) for K
/// intervals at M points each with `near` near pairs in all: the own and near blocks and the
/// diagonal blocks' LUs ((2 K + near) M^2), the Krylov basis and work vectors (64 K M), the
/// moment matrices (K p M) and the pairs' kernel matrices (pairs p^2).
template <class Real>
double union_far_memory_bytes(const far_field<Real>& far, std::size_t M) {
  const double K = double(far.leaves()), m = double(M), p = double(far.order());
  double near = 0;
  for (std::size_t j = 0; j < far.leaves(); ++j) near += double(far.near_leaves(j).size());
  return double(sizeof(Real)) * ((2 * K + near) * m * m + 64 * K * m + K * p * m + double(far.pairs()) * p * p);
}

/// The largest M (>= 1) with union_far_memory_bytes(far, M) <= bytes (0 if none: the estimate is
/// increasing in M).
template <class Real>
std::size_t union_far_degree_limit(const far_field<Real>& far, std::size_t bytes) {
  if (union_far_memory_bytes(far, 1) > double(bytes)) return 0;
  std::size_t lo = 1, hi = 2;
  while (union_far_memory_bytes(far, hi) <= double(bytes)) lo = hi, hi *= 2;
  while (hi - lo > 1) {
    const std::size_t mid = lo + (hi - lo) / 2;
    (union_far_memory_bytes(far, mid) <= double(bytes) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace rhabel::abel
