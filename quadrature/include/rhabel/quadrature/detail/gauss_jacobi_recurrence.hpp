// rhabel/quadrature/detail/gauss_jacobi_recurrence.hpp
//
// Private part of gauss_jacobi.hpp: Newton's method on the three-term recurrence, written in
// the distance u = 1 - x to the end x = +1, and the normalising constant of the weights.
//
// Why u and not x. Near x = +1 a node stored as x keeps only a few digits of 1 - x (at
// n = 65536, p = -0.9 the last node has 1 - x = 4.9e-11, so x carries 5 significant digits of
// it). Forming the recurrence coefficient A_k x + B_k as (A_k + B_k) - A_k u does not help:
// the sum rounds to eps relative to 1, an absolute perturbation of x of size eps, which is a
// relative perturbation eps/u of u (observed: Newton steps of 1e-10 relative noise at the
// node above, in long double). The recurrence is therefore run in difference form
// (the device of Reinsch's modification of Goertzel's algorithm near x = 1): with
//   e_k = P_k(1 - u) / P_k(1),  d_k = e_k - e_{k-1},   P_k(1) = (p+1)_k / k!,
// the recurrence P_{k+1} = (A_k x + B_k) P_k - C_k P_{k-1} (DLMF 18.9.1-2) becomes
//   d_{k+1} = gamma_k d_k - beta_k u e_k,   e_{k+1} = e_k + d_{k+1},
//   beta_k  = A_k (k+1)/(k+p+1)              = (s+1)(s+2) / (2 (k+p+q+1)(k+p+1)),
//   gamma_k = C_k k (k+1)/((k+p)(k+p+1))      = k (k+q)(s+2) / ((k+p+q+1)(k+p+1) s),   s = 2k + p + q,
//   e_0 = 1, d_1 = -(p+q+2) u / (2 (p+1)),
// (the identity (A_k + B_k) P_k(1) = P_{k+1}(1) + C_k P_{k-1}(1) removes the term that does not
// carry u). u enters only through the product beta_k u e_k, with relative accuracy, so the
// polynomial is evaluated at the exact point 1 - u however small u is, and the small
// differences d_k are formed from small quantities. Nodes near x = -1 are found as the nodes
// near +1 of P_n^(q,p), since P_n^(p,q)(-x) = (-1)^n P_n^(q,p)(x). Dividing by P_k(1) also
// removes the growth k^p (no overflow for p = 30, n = 10^6).
// The constant is a finite product for n <= 128 and a product of gamma ratios with arguments
// n + O(1) beyond (gamma_delta_ratio below, a few ulps for any n): exp of a difference of four
// lgamma values of size n log n would lose log10(n log n) digits (7 at n = 10^6).
//
// In the code gamma_k d_k is formed as d_k - (1 - gamma_k) d_k with 1 - gamma_k in closed form,
//   1 - gamma_k = (2 (2p+1) k (k+p+q+1) + c0) / ((k+p+q+1)(k+p+1) s),
//   c0 = p^3 + 2p^2 q + 2p^2 + p q^2 + 3pq + p + q^2 + q = (p + q + 1)(p + 1)(p + q),
// and the sums d_k + increment are compensated (Kahan). Every coefficient is formed from
// p + 1 and q + 1 (exact for double p, q in [-1, -1/2]), c0 in the factored form, s as
// 2 (k - 1) + (p + 1) + (q + 1): the expanded c0 has O(1) terms and the value O(p + 1) when
// p, q -> -1 and lost 1e-11 relative in long double at p = q = -1 + 1e-9 (1.6e5 eps in the
// weights of issue #2).
//
// Accuracy. Without the compensation the rounding errors of the d_k add up coherently (the
// increments are small and vary smoothly with k), O(n) units of the working precision: 4.5e-15
// relative node error at n = 10^6 in long double. With it the error in e_n near a zero stays
// at a few units of the working precision relative to the local amplitude (measured 4e-20
// relative node error at that node), which moves a node by that relative amount in u.
// gauss_jacobi runs this code in long double (64-bit significand, unit roundoff 5.4e-20) when
// Real is double, and in Real otherwise.
//
// Double sweep (jacobi_recurrence_in_u_compensated; the boundary nodes of the asymptotic
// path). The same recurrence in double with the e and e' sums compensated as well (they cost
// ~3 units of the working precision uncompensated), the coefficients formed from p + 1 and
// q + 1 (in the expanded form, (p + q) + 2 and c0 cancel to 1000 eps at p = q = -0.999), and the
// results rounded once from the compensated sums. Rounding errors of the coefficients are
// relative eps per step and do not accumulate into the phase (measured: the nodes agree with
// the long double sweep to <= 1 ulp, the weights to <= 4.5 eps, n = 101 ... 10^6,
// p, q down to -0.999). Two nodes per SIMD vector; ~9x cheaper than the long double sweep
// (measured at n = 10^6: 24 against 231 ms CPU time for the two ends of p = 0.25, q = 0).
//
// Cost. One sweep costs O(n) per node; all nodes of a batch share the coefficients, so a
// sweep over a batch of K nodes costs O(n K).
#pragma once

#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

namespace rhabel::quadrature::detail {

// Gamma(z) / Gamma(z + delta) for z > 0, z + delta > 0.
// For large z, Boost's tgamma_delta_ratio loses accuracy as |delta| grows (measured 6e-15
// relative at z = 10^6, delta = 15.5, in double and in long double). There
//   Gamma(z) / Gamma(z + delta) = z^-delta exp(-S),
//   S = sum_{k>=2} (-1)^k (B_k(delta) - B_k) / (k (k - 1) z^(k-1))    (DLMF 5.11.8),
// with pow (correctly rounded to an ulp) for z^-delta and a small S; used when
// z >= 64 (|delta| + 1)^2, where the terms fall by |delta|/z < 1/64 each and 14 terms are
// far below eps of long double. Hardware types are computed in long double, others by Boost.
template <class Real>
Real gamma_delta_ratio(const Real& z, const Real& delta) {
  if constexpr (std::is_floating_point_v<Real>) {
    using L = long double;
    const L Z = z, D = delta;
    const L ad = D < 0 ? -D : D;
    if (Z < 64 * (ad + 1) * (ad + 1)) return static_cast<Real>(boost::math::tgamma_delta_ratio(Z, D));
    // Bernoulli numbers B_0 .. B_14.
    static constexpr L bernoulli[15] = {1.0L,         -0.5L, 1.0L / 6, 0, -1.0L / 30, 0, 1.0L / 42, 0, -1.0L / 30, 0,
                                        5.0L / 66, 0, -691.0L / 2730, 0, 7.0L / 6};
    L S = 0, z_power = Z;  // z^(k-1)
    for (int k = 2; k <= 14; ++k) {
      // B_k(delta) - B_k = sum_{j<k} C(k, j) B_j delta^(k-j).
      L polynomial = 0, binomial = 1, delta_power = 1;  // C(k, j), delta^(k-j) built from j = k-1 down
      for (int j = k - 1; j >= 0; --j) {
        binomial = binomial * (j + 1) / (k - j);  // C(k, j) = C(k, j+1) (j+1)/(k-j)
        delta_power *= D;
        polynomial += binomial * bernoulli[j] * delta_power;
      }
      const L term = polynomial / (k * (k - 1) * z_power);
      S += (k % 2 == 0) ? term : -term;
      z_power *= Z;
    }
    return static_cast<Real>(std::pow(Z, -D) * std::exp(-S));
  } else {
    return boost::math::tgamma_delta_ratio(z, delta);
  }
}

// K_n = 2^(p+q+1) Gamma(n+p+1) Gamma(n+q+1) / (Gamma(n+p+q+1) n!) is the numerator of the
// weight formula w_i = K_n / ((1 - x_i^2) P_n'(x_i)^2) (Szego (15.3.5); DLMF 18.2).
// This is K_n / P_n^(p,q)(1)^2 with P_n(1) = Gamma(n+p+1) / (Gamma(p+1) n!) (DLMF 18.6.1), i.e.
// 2^(p+q+1) Gamma(p+1)^2 [n! / Gamma(n+p+1)] [Gamma(n+q+1) / Gamma(n+p+q+1)]; the factor of the
// weights in the normalised variable e_n = P_n / P_n(1) of the difference-form recurrence.
// For n <= gauss_jacobi_product_max_n the two brackets are finite products (n roundings of the
// working type, 2e-17 relative in long double at n = 128) and three gamma functions of
// arguments that never approach a pole, everything formed from p + 1 and q + 1:
//   Gamma(p+1)^2 n! / Gamma(n+p+1) = Gamma(p+1) / prod_{k=1}^n (k - 1 + (p+1)) / k,
//   Gamma(n+q+1) / Gamma(n+p+q+1) = (p+q+2) Gamma(q+2) / Gamma(p+q+3)                     (n = 1),
//                                 = Gamma(q+3) / Gamma(p+q+3) prod_{k=3}^n (k-1+(q+1)) / (k-2+(p+q+2))  (n >= 2)
// (Gamma(p+q+2) itself is near its pole when p, q -> -1; the first form keeps p + q + 2 as a
// factor). Beyond, gamma ratios with arguments n + O(1) (gamma_delta_ratio above, a few ulps for
// any n): exp of a difference of four lgamma values of size n log n would lose log10(n log n)
// digits (7 at n = 10^6).
inline constexpr std::size_t gauss_jacobi_product_max_n = 128;

// Gamma and 2^x in the working type: glibc's tgammal and exp2l for long double (within 10 ulps
// of long double, 5e-19; three times and ten times faster than Boost's tgamma and powl, which
// dominated the cost of small rules), Boost.Math and pow for other types.
template <class Real>
Real working_tgamma(const Real& x) {
  if constexpr (std::is_floating_point_v<Real>) {
    return std::tgamma(x);
  } else {
    return boost::math::tgamma(x);
  }
}
template <class Real>
Real working_exp2(const Real& x) {
  using std::pow;
  if constexpr (std::is_floating_point_v<Real>) {
    return std::exp2(x);
  } else {
    return pow(Real(2), x);
  }
}

// K_n / P_n(1)^2 for the end +1 (first) and, with p and q exchanged, for the end -1 (second).
template <class Real>
struct weight_constants {
  Real right, left;
};

template <class Real>
weight_constants<Real> gauss_jacobi_weight_constants(std::size_t n, const Real& p, const Real& q) {
  const Real p1 = p + 1, q1 = q + 1, pq2 = p1 + q1;
  const Real gamma_p1 = working_tgamma(p1), gamma_q1 = working_tgamma(q1);
  const Real power = working_exp2(pq2 - 1);
  if (n > gauss_jacobi_product_max_n) {
    const Real m = Real(n);
    return {power * gamma_delta_ratio(m + 1, p) * gamma_delta_ratio(m + q1, p) * gamma_p1 * gamma_p1,
            power * gamma_delta_ratio(m + 1, q) * gamma_delta_ratio(m + p1, q) * gamma_q1 * gamma_q1};
  }
  // P_n(1) for both ends, and Gamma(n+q+1)/Gamma(n+p+q+1), Gamma(n+p+1)/Gamma(n+p+q+1).
  Real end_p = 1, end_q = 1, ratio_q = 1, ratio_p = 1;
  for (std::size_t k = 1; k <= n; ++k) {
    end_p *= (Real(k - 1) + p1) / Real(k);
    end_q *= (Real(k - 1) + q1) / Real(k);
  }
  for (std::size_t k = 3; k <= n; ++k) {
    const Real denominator = Real(k - 2) + pq2;
    ratio_q *= (Real(k - 1) + q1) / denominator;
    ratio_p *= (Real(k - 1) + p1) / denominator;
  }
  const Real gamma_pq3 = working_tgamma(pq2 + 1);  // Gamma(p + q + 3), argument > 1
  const Real gamma_q2 = q1 * gamma_q1, gamma_p2 = p1 * gamma_p1;
  const Real second_q = n == 1 ? pq2 * gamma_q2 / gamma_pq3 : (q1 + 1) * gamma_q2 / gamma_pq3 * ratio_q;
  const Real second_p = n == 1 ? pq2 * gamma_p2 / gamma_pq3 : (p1 + 1) * gamma_p2 / gamma_pq3 * ratio_p;
  return {power * gamma_p1 / end_p * second_q, power * gamma_q1 / end_q * second_p};
}

// The first of the two (the end +1).
template <class Real>
Real gauss_jacobi_weight_constant_over_end_value(std::size_t n, const Real& p, const Real& q) {
  return gauss_jacobi_weight_constants(n, p, q).right;
}

// e_n(u_j) = P_n^(p,q)(1 - u_j) / P_n(1) and its derivative de_n/du for a batch of points,
// one difference-form sweep (see the header comment) shared by the batch. W is the working type.
template <class W>
void jacobi_recurrence_in_u(std::size_t n, const W& p, const W& q, const std::vector<W>& u, std::vector<W>& value,
                            std::vector<W>& slope) {
  const std::size_t K = u.size();
  // The state of one point, kept together (one cache line or two per point).
  struct state {
    W u, e, d, e_slope, d_slope;
    W d_carry, d_slope_carry;  // Kahan compensations
  };
  // Every coefficient is formed from p + 1 and q + 1 (exact for p, q in [-1, -1/2] in any
  // binary type), as in the double sweep below: the expanded c0 of the header comment has O(1)
  // terms and a value O(p + 1) when p -> -1 and q -> -1 (the root of issue #2's 1.6e5 eps
  // weight error at p = q = -1 + 1e-9 in long double), and (2k + p) + q rounds at k = 1.
  const W p1 = p + 1, q1 = q + 1, pq2 = p1 + q1;
  const W first = -pq2 / (2 * p1);  // d_1 / u
  std::vector<state> points(K);
  for (std::size_t j = 0; j < K; ++j) {
    const W d = first * u[j];
    points[j] = {u[j], 1 + d, d, first, first, W(0), W(0)};
  }
  // sum += increment with Kahan's compensation carry.
  auto accumulate = [](W& sum, W& carry, const W& increment) {
    const W y = increment - carry;
    const W next = sum + y;
    carry = (next - sum) - y;
    sum = next;
  };
  // 1 - gamma_k = (2 (2p+1) k (k+p+q+1) + c0) / ((k+p+q+1)(k+p+1) s), c0 = the value at k = 0,
  // c0 = (p + q + 1)(p + 1)(p + q) in factored form (no cancellation).
  const W c0 = (pq2 - 1) * p1 * (pq2 - 2);
  const W two_p_plus_1 = 2 * p1 - 1;
  state* const begin = points.data();
  state* const end = begin + K;
  for (std::size_t k = 1; k < n; ++k) {
    const W kk = W(k), km1 = W(k - 1);
    const W s = 2 * km1 + pq2;     // 2k + p + q
    const W kpq1 = km1 + pq2;      // k + p + q + 1
    const W inverse = 1 / (kpq1 * (kk + p1) * s);  // the one division of the step
    const W beta = (s + 1) * (s + 2) * s * inverse / 2;
    const W one_minus_gamma = (2 * two_p_plus_1 * kk * kpq1 + c0) * inverse;
    for (state* x = begin; x != end; ++x) {
      // d_{k+1} = d_k - (1 - gamma_k) d_k - beta_k u e_k and its u-derivative, then e += d.
      // The d sums are compensated: their increments are small and vary smoothly with k, so
      // plain rounding errors (or those of gamma_k d_k formed directly) add up coherently,
      // O(n) units of eps_W (observed: 4.5e-15 relative node error at n = 10^6, p = -0.9 in
      // long double); compensated, 4e-20. Compensating e and e' as well changes that to
      // 1.5e-19 only, so they are summed plainly.
      const W d_slope_increment = -one_minus_gamma * x->d_slope - beta * (x->e + x->u * x->e_slope);
      const W d_increment = -one_minus_gamma * x->d - beta * x->u * x->e;
      accumulate(x->d_slope, x->d_slope_carry, d_slope_increment);
      accumulate(x->d, x->d_carry, d_increment);
      x->e += x->d;
      x->e_slope += x->d_slope;
    }
  }
  value.resize(K);
  slope.resize(K);
  for (std::size_t j = 0; j < K; ++j) {
    value[j] = points[j].e;
    slope[j] = points[j].e_slope;
  }
}

// The same sweep in double with all four sums (d, d', e, e') compensated, for the boundary
// nodes of the asymptotic path (see "Double sweep" in the header comment). The states are
// kept in separate arrays (structure of arrays), padded to a multiple of 4 points by repeating
// the last one, so that the loop over the batch vectorises; the compensated sums are exact
// IEEE operations (no -ffast-math: the compiler must not reassociate them).
inline void jacobi_recurrence_in_u_compensated(std::size_t n, double p, double q, const std::vector<double>& u,
                                               std::vector<double>& value, std::vector<double>& slope) {
  // Two points per vector (GCC/Clang vector extension: element-wise IEEE operations, never
  // reassociated, so the compensations survive); all pairs advance together in k.
  typedef double pair_t __attribute__((vector_size(16)));
  struct state {
    pair_t u, e, d, e_slope, d_slope, carry_e, carry_d, carry_e_slope, carry_d_slope;
  };
  const std::size_t K = u.size();
  const std::size_t pairs = (K + 1) / 2;
  // Every coefficient is formed from p + 1 and q + 1 (exact for p, q in [-1, -1/2]), never as
  // (p + q) + 2 or (k + p + q) + 1: for p = q = -0.999 those sums cancel to 0.002 and would
  // lose 1000 eps in double (long double absorbs that in jacobi_recurrence_in_u).
  const double p1 = p + 1, q1 = q + 1, pq2 = p1 + q1;
  const double first = -pq2 / (2 * p1);  // d_1 / u
  std::vector<state> points(pairs);
  for (std::size_t j = 0; j < pairs; ++j) {
    const double u0 = u[2 * j], u1 = u[std::min(2 * j + 1, K - 1)];  // an odd batch repeats its last point
    const pair_t uu = {u0, u1};
    const pair_t d = first * uu;
    const pair_t zero = {0.0, 0.0}, f = {first, first};
    points[j] = {uu, 1 + d, d, f, f, zero, zero, zero, zero};
  }
  // c0 = (p + q + 1)(p + 1)(p + q), the expanded form of jacobi_recurrence_in_u factored.
  const double c0 = (pq2 - 1) * p1 * (pq2 - 2);
  state* const begin = points.data();
  state* const end = begin + pairs;
  for (std::size_t k = 1; k < n; ++k) {
    const double km1 = static_cast<double>(k - 1), kk = static_cast<double>(k);
    const double s = 2 * km1 + pq2;                 // 2k + p + q
    const double kpq1 = km1 + pq2;                  // k + p + q + 1
    const double inverse = 1 / (kpq1 * (kk + p1) * s);
    const double beta = (s + 1) * (s + 2) * s * inverse / 2;
    const double one_minus_gamma = (2 * (2 * p + 1) * kk * kpq1 + c0) * inverse;
    for (state* x = begin; x != end; ++x) {
      const pair_t d_slope_increment = -one_minus_gamma * x->d_slope - beta * (x->e + x->u * x->e_slope);
      const pair_t d_increment = -one_minus_gamma * x->d - beta * (x->u * x->e);
      pair_t y = d_slope_increment - x->carry_d_slope;
      pair_t next = x->d_slope + y;
      x->carry_d_slope = (next - x->d_slope) - y;
      x->d_slope = next;
      y = d_increment - x->carry_d;
      next = x->d + y;
      x->carry_d = (next - x->d) - y;
      x->d = next;
      y = x->d - x->carry_e;
      next = x->e + y;
      x->carry_e = (next - x->e) - y;
      x->e = next;
      y = x->d_slope - x->carry_e_slope;
      next = x->e_slope + y;
      x->carry_e_slope = (next - x->e_slope) - y;
      x->e_slope = next;
    }
  }
  value.resize(K);
  slope.resize(K);
  for (std::size_t j = 0; j < K; ++j) {
    // The compensated sums, rounded once: sum - carry.
    value[j] = points[j / 2].e[j % 2] - points[j / 2].carry_e[j % 2];
    slope[j] = points[j / 2].e_slope[j % 2] - points[j / 2].carry_e_slope[j % 2];
  }
}

// Result of the batched Newton iteration: refined distances u_j and the weights
// w_j = K_n / (u_j (2 - u_j) P_n'(1 - u_j)^2) = K_n / (P_n(1)^2 u_j (2 - u_j) e_n'(u_j)^2)
// (both in the working type).
template <class W>
struct recurrence_newton_result {
  std::vector<W> u;
  std::vector<W> weight;
  bool converged = true;
};

// Newton's method in u for the zeros of P_n^(p,q)(1 - u) started from u0 (each u0_j in (0, 2)).
// weight_constant is K_n / P_n(1)^2 (gauss_jacobi_weight_constant_over_end_value).
// A node is final once its Newton step, measured as a phase (the local zero spacing is
// pi sqrt(u (2 - u)) / rho), sigma = rho |du| / sqrt(u (2 - u)), is below sqrt(eps_W) / 16:
// the step is applied, leaving an error O(sigma^2) in phase, and the derivative at the new
// point comes from the one at the old point by a first-order Taylor step whose second
// derivative is given by the differential equation (DLMF 18.8.1) in u,
//   u (2 - u) y'' = (q - p - (p + q + 2)(1 - u)) y' - n (n + p + q + 1) y,   y = -y' du there,
// again with error O(sigma^2). So a batch started within sqrt(eps_W) needs a single sweep.
template <class W>
recurrence_newton_result<W> recurrence_newton(std::size_t n, const W& p, const W& q, std::vector<W> u,
                                              const W& weight_constant, int max_iterations = 60) {
  using std::abs;
  using std::sqrt;
  recurrence_newton_result<W> result;
  const std::size_t K = u.size();
  result.u.resize(K);
  result.weight.resize(K);
  const W tolerance = sqrt(std::numeric_limits<W>::epsilon()) / 16;
  const W rho = W(n) + (p + q + 1) / 2;
  const W lambda = W(n) * (W(n) + p + q + 1);
  std::vector<std::size_t> active(K);
  for (std::size_t j = 0; j < K; ++j) active[j] = j;
  std::vector<W> value, slope, points;
  for (int iteration = 0; iteration < max_iterations && !active.empty(); ++iteration) {
    points.resize(active.size());
    for (std::size_t t = 0; t < active.size(); ++t) points[t] = u[active[t]];
    if constexpr (std::is_same_v<W, double>) {
      jacobi_recurrence_in_u_compensated(n, p, q, points, value, slope);
    } else {
      jacobi_recurrence_in_u(n, p, q, points, value, slope);
    }
    std::vector<std::size_t> still_active;
    for (std::size_t t = 0; t < active.size(); ++t) {
      const std::size_t j = active[t];
      const W u0 = points[t];
      const W step = -value[t] / slope[t];
      const W span = u0 * (2 - u0);
      W next = u0 + step;
      // Safeguard: stay inside (0, 2); a step that leaves it is halved towards the end.
      if (!(next > 0)) next = u0 / 2;
      if (!(next < 2)) next = (u0 + 2) / 2;
      u[j] = next;
      // In double (the boundary nodes of the asymptotic path) the step must also be small
      // relative to u: for p near -1 the first zero has a phase rho t of only ~2 sqrt(p + 1)
      // (0.06 at p = -0.999), and a phase step of sqrt(eps)/16 would leave an O(sigma^2)
      // error of many eps relative to u (measured 70 eps at n = 101, p = -0.999 without this).
      const bool relative_ok = !std::is_same_v<W, double> || abs(step) < tolerance * u0;
      if (next == u0 + step && rho * abs(step) < tolerance * sqrt(span) && relative_ok) {
        const W correction = step * ((q - p - (p + q + 2) * (1 - u0)) + lambda * step) / span;
        const W slope_at_next = slope[t] * (1 + correction);
        result.weight[j] = weight_constant / (next * (2 - next) * slope_at_next * slope_at_next);
      } else {
        still_active.push_back(j);
      }
    }
    active.swap(still_active);
  }
  result.converged = active.empty();
  for (std::size_t j : active) {  // not converged: best effort, flagged by converged = false
    result.weight[j] = weight_constant / (u[j] * (2 - u[j]) * slope[0] * slope[0]);
  }
  result.u = std::move(u);
  return result;
}

}  // namespace rhabel::quadrature::detail
