// rhabel/quadrature/detail/gauss_jacobi_asymptotic.hpp
//
// Private part of gauss_jacobi.hpp: the interior (Hahn) asymptotic expansion of P_n^(a,b)(cos t)
// used for Newton's method in t, its constants, and initial guesses. Double precision only
// (the caller, gauss_jacobi.hpp, documents the regimes and the measured accuracy).
//
// Expansion (Hahn 1980; Hale & Townsend 2013, eq. (3.1)): with rho = n + (a + b + 1)/2,
// s = sin(t/2), c = cos(t/2),
//   P_n^(a,b)(cos t) = 2^(2 rho) B(n+a+1, n+b+1) / (pi s^(a+1/2) c^(b+1/2)) * G(t) + R_M,
//   G(t) = sum_{m<M} 2^-m / (2 rho + 1)_m sum_{l=0}^m alpha_l beta_{m-l} cos(phi_m - l pi/2) / (s^l c^(m-l)),
//   phi_m = (2 rho + m) t / 2 - (a + 1/2) pi / 2,
//   alpha_l = (1/2 + a)_l (1/2 - a)_l / l!,   beta_j = (1/2 + b)_j (1/2 - b)_j / j!.
// (Checked against mpmath's jacobi at 30 digits, n = 50, (a, b) = (0.3, -0.4) and (5, 2), t = 1.)
// The series is asymptotic in 1/(n s) and 1/(n c); it is exact after one term when
// a, b are +-1/2. Each term is bounded, independently of the phase, by
//   bound_m = 2^-m / (2 rho + 1)_m sum_l |alpha_l beta_{m-l}| s^-l c^-(m-l),
// and the evaluation stops at the first m with bound_m < eps / 16. If no m < 30 reaches that,
// or if the sum of the bounds exceeds 2 (the terms first grow like (p^2/(2 rho t))^m / m! for
// large p, and cancellation would cost accuracy; (2p + 1)/4 for p > 3.5, see
// hahn_admissible_total), the point is outside the interior region and the caller uses the
// recurrence. Measured at n = 10^6: the interior starts at rho t = 20 for |p| <= 2, 22 for
// p = 5, 32 for p = 10 and ~165 for p = 30 (~650 with the bound 2). evaluate_batch sums the same series for up to
// 32 points at once with the number of terms its first point needs (the bounds decrease with t
// in the interior), so a later point may get a few more terms than it needs, each below eps/16
// of the amplitude; the caller checks every point's last bound and bound sum.
//
// The zeros of P_n are those of G. Newton's method is run on G in t: the phase phi_0 = rho t
// is formed with relative error eps, so t is found to relative accuracy O(eps) for every
// node, and 1 - x = 2 sin^2(t/2) inherits it (no cancellation). At a zero,
//   w = K_n / (dP/dt)^2 = Q s^(2a+1) c^(2b+1) / G'(t)^2,
//   Q = K_n pi^2 / (2^(2 rho) B)^2 = pi 2^(a+b+1) Gamma(rho+1/2)^2 Gamma(rho+1)^2
//       / (Gamma(n+a+b+1) n! Gamma(n+a+1) Gamma(n+b+1)),
// where 2^(2 rho) B(n+a+1, n+b+1) = sqrt(pi) Gamma(n+a+1) Gamma(n+b+1) / (Gamma(rho+1/2) Gamma(rho+1))
// by Legendre's duplication formula. Q is the product of four gamma ratios with arguments
// n + O(1) (gamma_delta_ratio: a few ulps), so nothing overflows and nothing cancels.
#pragma once

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/bessel.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include "rhabel/quadrature/detail/gauss_jacobi_recurrence.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

namespace rhabel::quadrature::detail {

// Largest number of terms of the interior expansion that is ever summed.
inline constexpr int hahn_max_terms = 30;
// Largest admissible sum of the term bounds: the terms may first grow (by (p^2/(2 rho t))^m/m!)
// before they decay, and the rounding error of G is about eps times this sum (G has amplitude 1).
// The sum admitted for every exponent (hahn_admissible_total).
inline constexpr double hahn_max_total = 2;
// The admissible sum at the end with exponent a: max(2, (2a + 1)/4), continuous in a (the
// larger value from a = 3.5 on). For large a the interior weights already carry s^(2a+1),
// which turns the rounding of the node into a relative error of up to (2a + 1) ulp (measured
// 62 eps at a = 30), so a rounding error of G' up to a quarter of that is not visible in the
// weights; and it moves the first interior node at a = 30 from rho t ~ 650 (with the bound 2)
// to ~ 165 (38 instead of 191 boundary nodes, each an O(n) recurrence sweep: n = 10^6 in 0.15 s
// instead of 0.4 s). Measured at a = 30, n = 4000, against the long double recurrence: the
// nodes that the larger bound makes interior have weight errors <= 50 eps, below the 55-62 eps
// of the interior nodes beyond them.
inline double hahn_admissible_total(double a) { return std::max(hahn_max_total, (2 * a + 1) / 4); }

// The weight factor Q of the header comment (symmetric in a, b).
inline double hahn_weight_factor(std::size_t n, double p, double q) {
  // In long double: rho is not a double for most p, q, and each ratio is then exact to a few
  // ulps of long double before the product is rounded.
  using L = long double;
  const L P = p, Q = q, m = static_cast<L>(n);
  const L rho = m + (P + Q + 1) / 2;
  const L r1 = gamma_delta_ratio(rho + 0.5L, (P - Q) / 2);     // Gamma(rho+1/2)/Gamma(n+p+1)
  const L r2 = gamma_delta_ratio(rho + 0.5L, (Q - P) / 2);     // Gamma(rho+1/2)/Gamma(n+q+1)
  const L r3 = gamma_delta_ratio(rho + 1, (P + Q - 1) / 2);    // Gamma(rho+1)/Gamma(n+p+q+1)
  const L r4 = gamma_delta_ratio(rho + 1, -(P + Q + 1) / 2);   // Gamma(rho+1)/Gamma(n+1)
  return static_cast<double>(boost::math::constants::pi<L>() * std::pow(2.0L, P + Q + 1) * r1 * r2 * r3 * r4);
}

// The interior expansion for the end t = 0 with exponent a there and b at t = pi.
class hahn_expansion {
 public:
  // Terms are summed until the first whose phase-independent bound is below this.
  static constexpr double tolerance = std::numeric_limits<double>::epsilon() / 16;
  // Largest batch of evaluate_batch.
  static constexpr std::size_t batch_size = 32;

  hahn_expansion(std::size_t n, double a, double b) : a_(a), max_total_(hahn_admissible_total(a)) {
    rho_ = static_cast<double>(n) + (a + b + 1) / 2;
    alpha_.resize(hahn_max_terms);
    beta_.resize(hahn_max_terms);
    inverse_.resize(hahn_max_terms);
    alpha_[0] = beta_[0] = inverse_[0] = 1;
    for (int l = 1; l < hahn_max_terms; ++l) {
      const double j = l - 1;
      alpha_[l] = alpha_[l - 1] * (0.5 + a + j) * (0.5 - a + j) / l;
      beta_[l] = beta_[l - 1] * (0.5 + b + j) * (0.5 - b + j) / l;
      inverse_[l] = inverse_[l - 1] / (2 * (2 * rho_ + 1 + j));
    }
  }

  double rho() const { return rho_; }
  // The largest admissible sum of the term bounds at this end (hahn_admissible_total).
  double max_total() const { return max_total_; }

  // G(t) and G'(t) (value, slope), with s = sin(t/2) and c = cos(t/2). Returns false when
  // the series does not reach the tolerance within hahn_max_terms terms at t, or the sum of
  // the bounds exceeds max_total() (t is then outside the interior region).
  bool evaluate(double t, double& value, double& slope, double& s, double& c) const {
    s = std::sin(t / 2);
    c = std::cos(t / 2);
    const double phase = rho_ * t - (a_ + 0.5) * boost::math::constants::half_pi<double>();
    return evaluate_at(s, c, 1 / (s * c), std::cos(phase), std::sin(phase), value, slope);
  }

  // The same from s = sin(t/2), c = cos(t/2), inverse_sc = 1/(s c) and the phase
  // phi_0 = rho t - (a + 1/2) pi/2 as (cos phi_0, sin phi_0), which the caller may know more
  // cheaply and more accurately than from t (gauss_jacobi.hpp forms phi_0 - (k - 1/2) pi, a
  // small angle, for the k-th guess).
  bool evaluate_at(double s, double c, double inverse_sc, double cos_phi, double sin_phi, double& value,
                   double& slope) const {
    const double inverse_s = c * inverse_sc, inverse_c = s * inverse_sc;  // 1/s = c/(sc), 1/c = s/(sc)
    const double half_cot = c * inverse_s / 2, half_tan = s * inverse_c / 2;
    double g[hahn_max_terms], h[hahn_max_terms];  // alpha_l s^-l, beta_j c^-j, filled as needed
    double power_s = 1, power_c = 1;
    value = 0;
    slope = 0;
    double total = 0;  // sum of the bounds: the rounding error of G is about eps * total
    for (int m = 0; m < hahn_max_terms; ++m) {
      g[m] = alpha_[m] * power_s;
      h[m] = beta_[m] * power_c;
      power_s *= inverse_s;
      power_c *= inverse_c;
      // cos(phi_m - l pi/2) = cos phi_m, sin phi_m, -cos phi_m, -sin phi_m for l = 0, 1, 2, 3
      // (mod 4): U collects the even l, V the odd l, each with the sign (-1)^(l/2).
      double U = 0, V = 0, dU = 0, dV = 0, bound = 0;
      for (int l = 0; l <= m; ++l) {
        const double product = g[l] * h[m - l];
        const double d = (m - l) * half_tan - l * half_cot;  // d/dt log(s^-l c^-(m-l))
        const double signed_product = (l & 2) ? -product : product;
        bound += std::abs(product);
        (l & 1 ? V : U) += signed_product;
        (l & 1 ? dV : dU) += signed_product * d;
      }
      const double w = inverse_[m];
      value += w * (cos_phi * U + sin_phi * V);
      slope += w * ((2 * rho_ + m) / 2 * (cos_phi * V - sin_phi * U) + cos_phi * dU + sin_phi * dV);
      total += w * bound;
      if (w * bound < tolerance) return total <= max_total_;
      // phi_{m+1} = phi_m + t/2: rotate by the angle t/2.
      const double next_cos = cos_phi * c - sin_phi * s;
      sin_phi = sin_phi * c + cos_phi * s;
      cos_phi = next_cos;
    }
    return false;
  }

  // The number of terms evaluate_at sums at (s, c): the first m + 1 with a term bound below
  // the tolerance, or hahn_max_terms + 1 if there is none.
  int terms_needed(double s, double c) const {
    const double inverse_s = 1 / s, inverse_c = 1 / c;
    double g[hahn_max_terms], h[hahn_max_terms], power_s = 1, power_c = 1;
    for (int m = 0; m < hahn_max_terms; ++m) {
      g[m] = std::abs(alpha_[m]) * power_s;
      h[m] = std::abs(beta_[m]) * power_c;
      power_s *= inverse_s;
      power_c *= inverse_c;
      double bound = 0;
      for (int l = 0; l <= m; ++l) bound += g[l] * h[m - l];
      if (inverse_[m] * bound < tolerance) return m + 1;
    }
    return hahn_max_terms + 1;
  }

  // evaluate_at for a batch of `count` points (count <= batch_size) with exactly `terms` terms
  // each (terms <= hahn_max_terms), in loops over the batch without branches that the compiler
  // vectorises. Inputs s, c, 1/(s c) and the phase (cos phi_0, sin phi_0); outputs G, G', the
  // bound of the last term and the sum of the bounds, from which the caller decides, point by
  // point, what evaluate_at would have decided (terms beyond the first one below the tolerance
  // change G by less than that).
  void evaluate_batch(std::size_t count, int terms, const double* s, const double* c, const double* inverse_sc,
                      const double* cos_phi, const double* sin_phi, double* value, double* slope, double* last_bound,
                      double* total) const {
    double power_s[hahn_max_terms][batch_size], power_c[hahn_max_terms][batch_size];  // s^-l, c^-j
    double half_cot[batch_size], half_tan[batch_size];
    double U[batch_size], V[batch_size], dU[batch_size], dV[batch_size], bound[batch_size];
    // Local copies of the in/out arrays: with six pointer arguments the compiler did not
    // vectorise the accumulation loop below (too many runtime alias checks; it was the hottest
    // line of the rule at n = 10^4).
    double cos_phase[batch_size], sin_phase[batch_size], G[batch_size], G_slope[batch_size], sum[batch_size];
    double last[batch_size];
    for (std::size_t i = 0; i < count; ++i) {
      half_cot[i] = c[i] * c[i] * inverse_sc[i] / 2;
      half_tan[i] = s[i] * s[i] * inverse_sc[i] / 2;
      power_s[0][i] = power_c[0][i] = 1;
      G[i] = G_slope[i] = sum[i] = last[i] = 0;
      cos_phase[i] = cos_phi[i];
      sin_phase[i] = sin_phi[i];
    }
    for (int m = 1; m < terms; ++m) {
      for (std::size_t i = 0; i < count; ++i) {
        power_s[m][i] = power_s[m - 1][i] * (c[i] * inverse_sc[i]);
        power_c[m][i] = power_c[m - 1][i] * (s[i] * inverse_sc[i]);
      }
    }
    // Adds the term (m, l), coefficient alpha_l beta_j (j = m - l) with the sign of
    // cos(phi_m - l pi/2), times s^-l c^-j to its sum (U for even l, V for odd l), the term
    // times d/dt log(s^-l c^-j) = j tan(t/2)/2 - l cot(t/2)/2 to the slope's sum, and |term| to
    // the bound. The terms l = 0 (the first of U) and l = 1 (the first of V) set their sums
    // instead (zeroing the five arrays per term cost 1/6 of this routine in memset calls at
    // n = 10^4), and l = 0 sets the bound: the flags are compile-time constants, so the one loop
    // body is instantiated three times without a branch or select inside.
    auto accumulate_term = [&](int m, int l, auto sets_partial, auto sets_bound) {
      const double coefficient = ((l & 2) ? -1.0 : 1.0) * alpha_[l] * beta_[m - l];
      const double magnitude = std::abs(coefficient);
      const double j = m - l, ll = l;
      double* partial = (l & 1) ? V : U;
      double* partial_slope = (l & 1) ? dV : dU;
      const double* ps = power_s[l];
      const double* pc = power_c[m - l];
      for (std::size_t i = 0; i < count; ++i) {
        const double power = ps[i] * pc[i];
        const double product = coefficient * power;
        const double product_slope = product * (j * half_tan[i] - ll * half_cot[i]);
        if constexpr (decltype(sets_partial)::value) {
          partial[i] = product;
          partial_slope[i] = product_slope;
        } else {
          partial[i] += product;
          partial_slope[i] += product_slope;
        }
        if constexpr (decltype(sets_bound)::value) {
          bound[i] = magnitude * power;
        } else {
          bound[i] += magnitude * power;
        }
      }
    };
    for (int m = 0; m < terms; ++m) {
      // The order of the additions is that of evaluate_at.
      accumulate_term(m, 0, std::true_type{}, std::true_type{});
      if (m >= 1) accumulate_term(m, 1, std::true_type{}, std::false_type{});
      for (int l = 2; l <= m; ++l) accumulate_term(m, l, std::false_type{}, std::false_type{});
      if (m == 0) {
        for (std::size_t i = 0; i < count; ++i) V[i] = dV[i] = 0;
      }
      const double w = inverse_[m], frequency = (2 * rho_ + m) / 2;
      for (std::size_t i = 0; i < count; ++i) {
        G[i] += w * (cos_phase[i] * U[i] + sin_phase[i] * V[i]);
        G_slope[i] += w * (frequency * (cos_phase[i] * V[i] - sin_phase[i] * U[i]) + cos_phase[i] * dU[i] +
                           sin_phase[i] * dV[i]);
        sum[i] += w * bound[i];
        last[i] = w * bound[i];
        const double next_cos = cos_phase[i] * c[i] - sin_phase[i] * s[i];
        sin_phase[i] = sin_phase[i] * c[i] + cos_phase[i] * s[i];
        cos_phase[i] = next_cos;
      }
    }
    for (std::size_t i = 0; i < count; ++i) {
      value[i] = G[i];
      slope[i] = G_slope[i];
      total[i] = sum[i];
      last_bound[i] = last[i];
    }
  }

 private:
  double a_, max_total_, rho_;
  std::vector<double> alpha_, beta_, inverse_;
};

// Interior initial guess for the k-th zero (k = 1 nearest t = 0) in t (Gatteschi & Pittaluga
// 1985; Hale & Townsend 2013 eq. (3.4)): K = (k + a/2 - 1/4) pi / rho,
//   t ~ K + ((1/4 - a^2) cot(K/2) - (1/4 - b^2) tan(K/2)) / (4 rho^2).
inline double interior_guess(std::size_t k, double a, double b, double rho) {
  const double K = (static_cast<double>(k) + a / 2 - 0.25) * boost::math::constants::pi<double>() / rho;
  const double tan_half = std::tan(K / 2);
  return K + ((0.25 - a * a) / tan_half - (0.25 - b * b) * tan_half) / (4 * rho * rho);
}

// Boundary initial guess for the k-th zero from the k-th zero j of J_a (Olver 1974;
// DLMF 18.16.8; Hale & Townsend 2013 eq. (3.8)): phi = j / rho,
//   t ~ phi + ((a^2 - 1/4)(1 - phi cot phi) / (2 phi) - (a^2 - b^2) tan(phi/2) / 4) / rho^2.
inline double boundary_guess(std::size_t k, double a, double b, double rho) {
  // In double without Boost's default promotion to long double (a starting value only; the
  // promoted evaluation cost a third of the time of a rule at n = 100).
  using double_policy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;
  // Boost's zero finder has no bracket for orders in (-1e-5, 0) ("No change of sign": a rule with
  // an exponent -1e-7 exited with an internal error); there the order-0 zero moved by its first-
  // order shift a pi/2 (McMahon) is the starting value (off by O(a^2 + a/k), far below a spacing).
  const double j = a < 0 && a > -1e-3 ? boost::math::cyl_bessel_j_zero(0.0, static_cast<int>(k), double_policy()) +
                                            a * boost::math::constants::pi<double>() / 2
                                      : boost::math::cyl_bessel_j_zero(a, static_cast<int>(k), double_policy());
  const double phi = j / rho;
  return phi + ((a * a - 0.25) * (1 - phi / std::tan(phi)) / (2 * phi) - (a * a - b * b) * std::tan(phi / 2) / 4) /
                   (rho * rho);
}

}  // namespace rhabel::quadrature::detail
