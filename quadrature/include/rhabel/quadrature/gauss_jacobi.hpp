// rhabel/quadrature/gauss_jacobi.hpp
//
// Gauss-Jacobi quadrature: nodes x_i and weights w_i such that
//   sum_i w_i f(x_i) = int_{-1}^{1} (1 - x)^p (1 + x)^q f(x) dx   for every polynomial f of degree <= 2n - 1,
// for any n >= 1 and exponents p, q in (-1, 30] (p belongs to x = +1, q to x = -1), and the same
// rule mapped to [lo, hi] for the weight (hi - t)^p (t - lo)^q. Beside each node the rule
// carries its distances 1 - x_i and 1 + x_i (hi - t_i, t_i - lo), computed without
// cancellation: near the ends the node itself keeps only a few digits of them (at n = 65536,
// p = -0.9 the last node has 1 - x = 4.9e-11), and endpoint factors such as (1 - x)^p need them.
//
// Theory. The nodes are the zeros of P_n^(p,q); the weights are
//   w_i = K_n / ((1 - x_i^2) P_n'(x_i)^2),  K_n = 2^(p+q+1) Gamma(n+p+1) Gamma(n+q+1) / (Gamma(n+p+q+1) n!)
// (Szego, "Orthogonal Polynomials", (15.3.5)). All work is done in the angle
// t = arccos x, or directly in the distance u = 1 - x to the nearer end, never in x: a node
// nearest +1 is a zero of P_n^(p,q)(1 - u), a node nearest -1 a zero of P_n^(q,p)(1 - u)
// (P_n^(p,q)(-x) = (-1)^n P_n^(q,p)(x)); the rule is assembled from the two halves.
//
// Algorithms and regimes (gauss_jacobi_method::automatic chooses; the others force a path):
//  * closed forms, any n: p = q = -1/2 (t_k = (2k-1) pi/(2n), w_k = pi/n) and p = q = 1/2
//    (t_k = k pi/(n+1), w_k = pi/(n+1) sin^2 t_k), formed in the angle from the nearer end.
//  * recurrence (n <= gauss_jacobi_recurrence_max_n = 40, and every Real other than float
//    and double): Golub-Welsch eigenvalues (implicit QL on the Jacobi matrix in double,
//    detail::tridiagonal_eigenvalues) as starting values, then Newton's method in u = distance
//    to the nearer end on the three-term recurrence in difference form
//    (detail/gauss_jacobi_recurrence.hpp; it evaluates P_n at the exact point 1 - u, with every
//    coefficient formed from p + 1 and q + 1), run in long double when Real is double or float
//    and in Real otherwise; weights from K_n / ((1 - x^2) P_n'^2). O(n^2) per sweep; one sweep
//    per end from these starting values.
//  * asymptotic (n > 40, Real = double or float): after Hale & Townsend (2013). The nodes with
//    t <= pi/2 are found for (p, q), the others as the same problem for (q, p) (for p = q the
//    half is mirrored), written in place into the rule. Interior nodes: Newton in t on Hahn's
//    interior expansion of P_n (detail/gauss_jacobi_asymptotic.hpp) from the Gatteschi-Pittaluga
//    guesses, finished by a Halley step and a Taylor step for the derivative that use the
//    differential equation; weights from the derivative and a gamma-ratio constant. O(1) per
//    node: from n ~ 1000 on, the guess is within the finishing threshold and one evaluation of
//    4 (n = 10^6) to 6 (n = 10^4) terms per node suffices. The guess's phase is formed as
//    (k - 1/2) pi plus a small angle (no sin/cos of a large argument, no tan), and the nodes
//    are processed in batches of 32 whose arithmetic the compiler vectorises: the guesses
//    (sin and cos of K/2 <= 0.8 by Taylor series, exact products by Dekker's split instead of
//    fma, which is a libm call in this build), the expansion, the finishing step and the
//    weight factor s^(2p+1) c^(2q+1) (detail/gauss_jacobi_power.hpp: two pow per batch and a
//    series for the ratios to the batch's middle node, within 2 eps like two pow per node).
//    Points whose guess is not yet within the finishing threshold take up to three Newton
//    steps in the batch, for every exponent (about 2000 nodes at p = 30, n = 10^4; 11 at
//    (-0.9, 0.3), 170 at (5, 5)); only the points that move are evaluated again, and each step
//    puts the phase and s, c at the same double t (interior_guesser::move). That consistency
//    matters: with s, c by the addition theorem (about an ulp less accurate than sin and cos of
//    t/2) the steps raise the worst weight at p = q = 5 from 11.6 to 15.6 eps, with s, c of the
//    rounded t and the phase of the unrounded K + correction to 14.1 eps (up to (2p + 1) eps/2
//    in the weight); with the point consistent they lower it to 8.9 eps (accuracy figures
//    below; the regression test for p or q = 5 pins it). A node is interior when the
//    expansion, summed to at most 30 terms, has a phase-independent term bound below eps/16
//    and a sum of term bounds <= max(2, (2p + 1)/4) for the exponent p at that end
//    (detail::hahn_admissible_total, continuous in p: the weights carry the (2p + 1)-fold
//    amplification of the node's rounding anyway, and the bound 2 made p = 30 start the
//    interior at rho t ~ 650 with ~190 boundary nodes, 0.4 s of O(n) sweeps at n = 10^6).
//    Measured at n = 10^4 and 10^6 (the same figures) this puts the first interior node at
//    rho t ~ 20 for |p| <= 2, 21 for p = 4, 22 for p = 5, 32 for p = 10 and ~166 for p = 30
//    (rho = n + (p+q+1)/2), i.e. 5-6, 4, 4, 5 and 38 boundary nodes at that end (none for
//    p = 1/2, one for p = 3.5, 4.5, 5.5, where alpha_l of the expansion vanishes from
//    l = p + 1/2 on).
//    Boundary nodes: Newton in u on the difference-form recurrence from Bessel-zero guesses
//    (Olver; DLMF 18.16.8; boost::math::cyl_bessel_j_zero in double), all boundary nodes of one
//    end sharing each O(n) sweep; for n >= ~10^3 the guesses are already within the finishing
//    threshold and one sweep per end suffices. The sweep runs in double with all four running
//    sums compensated, two nodes per SIMD vector, and coefficients formed from p + 1 and q + 1
//    (no cancellation at p = -0.999); the Newton step is also required to be small relative to
//    u (first node at p = -0.999). Against a long double sweep it moves these nodes by
//    <= 1 ulp and their weights by <= 4.5 eps (measured, n = 101 ... 10^6, p, q down to -0.999),
//    at a ninth of the cost. Hale & Townsend use the Baratella-Gatteschi Bessel expansion there;
//    the recurrence is used instead because it has no truncation error to control at any n,
//    at the price of O(n) per boundary node (28% of the time at n = 10^4 and at 10^6 for
//    (-0.9, 0.3), 6 boundary nodes per end; perf).
//    Safety net: if the Newton iterations fail or the distances of the nodes are not strictly
//    monotone, the routine falls back to the recurrence path for n <= gauss_jacobi_fallback_max_n
//    = 20000 and throws std::runtime_error above (observed only for p = q = -1 + 1e-9 at odd n,
//    where the split of the symmetric rule followed a rounded guess; fixed, and pinned by a
//    regression test).
//
// Accuracy contract, Real = double (relative error; an estimate from the tables, not a bound):
//  * 1 <= n <= 10^6, p, q in (-1, 5]: <= 1e-14 (45 eps) in every weight and in min(1 - x, 1 + x)
//    of every node, and in max(1 - x, 1 + x). Measured against the committed 60-digit table
//    tests/data/gauss_jacobi_reference.csv (tools/reference/gauss_jacobi_reference.cpp:
//    n = 1, 2, 3, 100, 101, 10^4 for all 64 pairs p, q in {-0.999, -0.9, -0.5, 0, 0.25, 0.5, 5, 30},
//    n = 10^6 for five pairs, 1024 and 65536 for the regression values; node indices on both
//    sides of the boundary/interior switch; and both exponents near -1: p, q in
//    {-1 + 1e-9, -1 + 1e-5, -0.999}, n = 1, 2, 3, 16, 40, 41, 80, 101, 10^4), measured by
//    tests/quadrature/test_gauss_jacobi.cpp (its -s output): worst 3.2 eps for the nodes and
//    8.9 eps for the weights (n = 10^6: 2.0 and 5.7 eps; both exponents near -1, n >= 41: 2.6
//    and 7.8 eps). The weights
//    of the asymptotic path carry s^(2p+1) c^(2q+1), s = sin(t/2), c = cos(t/2), so a one-ulp
//    rounding of the node is amplified by up to 2p + 1; the recurrence path (n <= 40, or
//    forced) is within 0.5 eps, also for p = q = -1 + 1e-9 (its constants are formed from p + 1
//    and q + 1: the expanded (p+q+1)(p+1)(p+q) cancels there, 1.6e5 eps in the weights and 4e4
//    eps in the nodes). For n = 10 ... 100 (across the 40 / 41 switch)
//    the asymptotic path is within 5.0 eps (min(1 - x, 1 + x)) and 14 eps (weights) of the
//    recurrence path (every n, p and q in {-0.999, -0.9, -0.5, 0, 0.25, 0.5, 5}).
//  * p or q in (5, 30]: nodes within 4 eps (measured 2.5), weights within 128 eps (measured
//    62 eps at n = 100 and at n = 10^4, 49 eps at n = 10^6).
//  * Real = cpp_bin_float_50 (recurrence path): measured 49 eps_50 (n <= 100, q = 30).
//  * p or q > 30: refused (std::domain_error naming the parameter and the range (-1, 30];
//    gauss_jacobi_max_exponent), for every Real and n. Beyond 30 nothing above is measured and
//    the paths, unguarded, fail silently: p = q = 1000, n = 2 gives weights 0 (the sum is 0.056);
//    p = 10^6, n = 1 NaN; q = 1000 with p = -1 + 1e-12 inf; for p = 10^300 Newton's method does
//    not converge; p = 300, q = -0.9 takes 75 s at n = 10^4. Subnormal exponents (1e-320) are in range
//    and give the rule of exponent 0 to the contract.
//  Never judge a rule by sum(w) alone: it hides 1e-9 errors in individual weights.
//
// Constants. K_n and the interior weight factor are products of gamma ratios
// Gamma(z)/Gamma(z + delta) with z = n + O(1), computed in long double (detail::gamma_delta_ratio:
// z^-delta exp(-S) with the Bernoulli-polynomial series S of DLMF 5.11.8 for large z, Boost's
// tgamma_delta_ratio otherwise; Boost's alone errs by 6e-15 at z = 10^6, delta = 15.5). exp of a
// difference of lgamma values of size n log n would lose 7 digits at n = 10^6. For n <= 128
// K_n / P_n(1)^2 is a finite product and three gamma functions whose arguments stay away from
// the poles (Gamma(p+q+2) is kept as Gamma(p+q+3)/(p+q+2)), all from p + 1 and q + 1.
//
// Cost (bench/gauss_jacobi.cpp, Release, median CPU time of 5 repetitions,
//   build/bin/bench_gauss_jacobi --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// on the shared 2-core machine at load 4-5, where wall time was up to twice that):
//   (p, q) = (0.25, -0.5): n = 8 4 us, 100 39 us, 4000 0.28 ms (GSL's
//   gsl_integration_fixed_jacobi 286 ms, 1000 times slower, its weights off by up to 4e-10
//   there), 10^4 0.64 ms, 10^6 82 ms; Legendre 10^4 0.38 ms, 10^6 56 ms; (-0.5, 0): 10^4
//   0.58 ms, 10^6 79 ms; (0.25, 0): 0.74 ms, 79 ms. Generic exponents (2p + 1 or 2q + 1 not in
//   {0, 1/2, 1, 3/2, 2}), n = 10^4 and 10^6: (-0.9, 0.3) 0.87 ms, 86 ms; (0.3, 0.7) 0.87 ms,
//   86 ms; (-0.5, 2.2) 0.74 ms, 90 ms; (4.5, -0.7) 0.97 ms, 96 ms (0.91 ms, 89 ms in a second
//   run); large exponents: (5, 5) 0.62 ms, 61 ms; (30, 0) 2.3 ms, 152 ms. GSL at n = 8: 2 us.
// The targets (n = 10^4 in 1 ms, 10^6 in 100 ms, >= 100x GSL at 4000) are met on this
// loaded machine for all these pairs except (30, 0), the generic ones with 3-15% margin. Where
// the time goes ((-0.9, 0.3), perf): at n = 10^4 the interior arithmetic (guesses, expansion,
// finishing step, weight factor) 60%, the boundary sweeps 28%, the Bessel-zero guesses 5%; at
// 10^6 the same split plus ~8% for the first touch of the 32 MB of the rule (page faults).
// The interior takes two pow per batch of 32 nodes, no sincos or fma call per guess (Taylor
// series and Dekker products in the vectorised loop), no division per node beyond the batch's
// and one vectorised accumulation loop (evaluate_batch). (30, 0) is above the targets: its 38
// boundary nodes per sweep cost half of the time at 10^6 (perf), and its interior needs 10 to
// 27 terms per node at 10^4. Small n (recurrence path):
// the eigenvalues, one long double sweep per end and the constants take 4 us at n = 8, twice
// GSL's 2 us.
//
// References.
//  N. Hale, A. Townsend, Fast and accurate computation of Gauss-Legendre and Gauss-Jacobi
//    quadrature nodes and weights, SIAM J. Sci. Comput. 35(2) (2013) A652-A674.
//  E. Hahn, Asymptotik bei Jacobi-Polynomen und Jacobi-Funktionen, Math. Z. 171 (1980) 201-226.
//  L. Gatteschi, G. Pittaluga, An asymptotic expansion for the zeros of Jacobi polynomials (1985).
//  G. H. Golub, J. H. Welsch, Calculation of Gauss quadrature rules, Math. Comp. 23 (1969).
//  FastGaussQuadrature.jl (gaussjacobi.jl) and Chebfun (jacpts.m) for the overall structure.
#pragma once

#include "rhabel/quadrature/detail/gauss_jacobi_asymptotic.hpp"
#include "rhabel/quadrature/detail/gauss_jacobi_power.hpp"
#include "rhabel/quadrature/detail/gauss_jacobi_recurrence.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <boost/math/constants/constants.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace rhabel::quadrature {

/// A quadrature rule on [lo, hi]: sum_i weight[i] f(x[i]) ~ int_lo^hi w(t) f(t) dt.
/// Beside each node it carries its distances to both ends, computed without cancellation,
/// so that callers can evaluate endpoint weight factors (hi - t)^p (t - lo)^q to full
/// relative accuracy even where x[i] itself holds only a few digits of hi - x[i].
template <class Real>
struct quadrature_rule {
  std::vector<Real> x;           ///< nodes, increasing (strictly while the distances below are resolved by x)
  std::vector<Real> hi_minus_x;  ///< hi - x[i]  (1 - x[i] on [-1, 1]), strictly decreasing
  std::vector<Real> x_minus_lo;  ///< x[i] - lo  (1 + x[i] on [-1, 1]), strictly increasing
  std::vector<Real> weight;      ///< positive weights

  std::size_t size() const { return x.size(); }

  /// sum_i weight[i] f(x[i]).
  template <class F>
  Real integrate(F&& f) const {
    Real sum = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sum += weight[i] * f(x[i]);
    return sum;
  }
};

/// Which algorithm gauss_jacobi uses (see the header comment for the regimes).
enum class gauss_jacobi_method {
  automatic,   ///< closed forms where exact, recurrence for n <= 40 or Real not float/double, else asymptotic
  recurrence,  ///< Golub-Welsch start + Newton on the recurrence, O(n^2); any Real
  asymptotic,  ///< interior expansion + boundary recurrence, O(n); Real = float or double only
};

struct gauss_jacobi_options {
  gauss_jacobi_method method = gauss_jacobi_method::automatic;
};

/// n up to this uses the recurrence path under gauss_jacobi_method::automatic. Above it the
/// asymptotic path is cheaper (forced paths, (p, q) = (0.25, 0) and (-0.5, 0), loaded machine:
/// n = 24 22 against 23-46 us, n = 32 38 against 24-42 us, n = 40 57 against 26-46 us, n = 48
/// 80 against 28-50 us); the switch stays at 40, where the costs are close, because the
/// recurrence path is the more accurate (0.5 eps against up to 4 eps in the nodes and 16.5 eps
/// in the weights).
inline constexpr std::size_t gauss_jacobi_recurrence_max_n = 40;
/// Largest exponent p or q that gauss_jacobi accepts: the accuracy contract (header comment) is
/// measured up to 30. Beyond it the paths were not designed or tested and failed silently
/// (issue 14: at p = q = 1000, n = 2 the weights underflowed to 0 instead of summing to
/// 2^(p+q+1) B(p+1, q+1) = 0.056; p = 10^6 gave NaN, q = 1000 with p near -1 gave inf, p = 10^300
/// stopped Newton's method, p = 300 at n = 10^4 took 75 s), so they are refused with
/// std::domain_error naming the parameter and the range (-1, 30].
inline constexpr double gauss_jacobi_max_exponent = 30;
/// Largest n for which a failure of the asymptotic path falls back to the O(n^2) recurrence
/// path (above it, std::runtime_error; never observed).
inline constexpr std::size_t gauss_jacobi_fallback_max_n = 20000;

namespace detail {

template <class Real>
inline constexpr bool gauss_jacobi_is_hardware_float = std::is_same_v<Real, double> || std::is_same_v<Real, float>;

// Working precision of the recurrence: long double for float and double, Real otherwise.
template <class Real>
using gauss_jacobi_working_t = std::conditional_t<gauss_jacobi_is_hardware_float<Real>, long double, Real>;

// Sanity of an assembled rule: 1 - x strictly decreasing and 1 + x strictly increasing,
// both positive, weights positive.
template <class Real>
bool gauss_jacobi_strictly_increasing(const quadrature_rule<Real>& rule) {
  // Only the distances are tested: for n beyond ~10^7 the nodes next to an end round to the
  // same double x (1 - x below eps), while their distances stay distinct.
  for (std::size_t i = 0; i + 1 < rule.size(); ++i) {
    if (!(rule.hi_minus_x[i] > rule.hi_minus_x[i + 1]) || !(rule.x_minus_lo[i] < rule.x_minus_lo[i + 1])) {
      return false;
    }
  }
  for (std::size_t i = 0; i < rule.size(); ++i) {
    if (!(rule.weight[i] > 0) || !(rule.hi_minus_x[i] > 0) || !(rule.x_minus_lo[i] > 0)) return false;
  }
  return true;
}

// Chebyshev closed forms, p = q = -1/2 (first kind) or p = q = 1/2 (second kind), in the
// angle: node k from the end +1 has t_k, and 1 - x = 2 sin^2(t_k/2); the half at -1 is the
// mirror image, so both halves are formed from small angles only.
template <class Real>
quadrature_rule<Real> gauss_chebyshev(std::size_t n, bool second_kind) {
  using std::sin;
  const Real pi = boost::math::constants::pi<Real>();
  quadrature_rule<Real> rule;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = n - i;  // node i (0-based, increasing x) is node k (1-based) from +1
    const Real t = second_kind ? Real(k) * pi / Real(n + 1) : Real(2 * k - 1) * pi / Real(2 * n);
    const Real t_mirror = second_kind ? Real(n + 1 - k) * pi / Real(n + 1) : Real(2 * (n - k) + 1) * pi / Real(2 * n);
    const Real sin_half = sin(t / 2), sin_half_mirror = sin(t_mirror / 2);  // cos(t/2) = sin(t_mirror/2)
    const Real near = 2 * sin_half * sin_half, far = 2 * sin_half_mirror * sin_half_mirror;
    rule.hi_minus_x.push_back(near);
    rule.x_minus_lo.push_back(far);
    rule.x.push_back(near <= far ? 1 - near : far - 1);  // from the nearer end
    const Real sin_t = 2 * sin_half * sin_half_mirror;  // sin t without cancellation near t = pi
    rule.weight.push_back(second_kind ? pi / Real(n + 1) * sin_t * sin_t : pi / Real(n));
  }
  return rule;
}

// Eigenvalues of the symmetric tridiagonal matrix with diagonal d (size n) and off-diagonal e
// (size n - 1), in increasing order, by the implicit QL algorithm with Wilkinson's shift
// (Bowdler, Martin, Reinsch & Wilkinson, tql1 in the Handbook for Automatic Computation II,
// 1971; Golub & Van Loan 8.3). Absolute error O(eps max|T|), like any backward-stable method;
// the rules only take starting values for Newton's method from it. Returns false if an
// eigenvalue needs more than 60 sweeps (never observed; the caller then uses Eigen).
// For n = 8 it costs a tenth of Eigen's SelfAdjointEigenSolver, which dominated small rules.
inline bool tridiagonal_eigenvalues(std::vector<double>& d, std::vector<double> e) {
  const std::size_t n = d.size();
  e.push_back(0.0);  // e[i] couples d[i] and d[i + 1]; e[n - 1] = 0
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (std::size_t l = 0; l < n; ++l) {
    for (int sweep = 0;; ++sweep) {
      // Find the first negligible off-diagonal element at or after l.
      std::size_t m = l;
      for (; m + 1 < n; ++m) {
        if (std::abs(e[m]) <= eps * (std::abs(d[m]) + std::abs(d[m + 1]))) break;
      }
      if (m == l) break;  // d[l] is an eigenvalue
      if (sweep == 60) return false;
      // Wilkinson's shift from the leading 2 x 2 block, then one implicit QL sweep from m up to l.
      double g = (d[l + 1] - d[l]) / (2 * e[l]);
      double r = std::sqrt(g * g + 1);
      g = d[m] - d[l] + e[l] / (g + (g >= 0 ? r : -r));
      double s = 1, c = 1, shift = 0;
      bool deflated = false;
      for (std::size_t i = m; i-- > l;) {
        const double f = s * e[i], b = c * e[i];
        r = std::sqrt(f * f + g * g);  // entries are O(1): no overflow, hypot not needed
        e[i + 1] = r;
        if (r == 0) {  // underflow: the matrix splits here
          d[i + 1] -= shift;
          e[m] = 0;
          deflated = true;
          break;
        }
        s = f / r;
        c = g / r;
        g = d[i + 1] - shift;
        r = (d[i] - g) * s + 2 * c * b;
        shift = s * r;
        d[i + 1] = g + shift;
        g = c * r - b;
      }
      if (deflated) continue;
      d[l] -= shift;
      e[l] = g;
      e[m] = 0;
    }
  }
  std::sort(d.begin(), d.end());
  return true;
}

// Recurrence path: Golub-Welsch starting values, Newton in u in the working precision W,
// written directly into the rule.
template <class Real>
quadrature_rule<Real> gauss_jacobi_by_recurrence(std::size_t n, const Real& p, const Real& q) {
  using W = gauss_jacobi_working_t<Real>;
  const double pd = static_cast<double>(p), qd = static_cast<double>(q);
  std::vector<W> right_start, left_start;  // distances to the nearer end, increasing
  if (n == 1) {
    // 1 - x = 2 (p + 1)/(p + q + 2), 1 + x = 2 (q + 1)/(p + q + 2): from the nearer end
    // (Newton polishes the rounding).
    if (qd >= pd) {
      right_start.push_back(W(2 * (pd + 1) / (pd + qd + 2)));
    } else {
      left_start.push_back(W(2 * (qd + 1) / (pd + qd + 2)));
    }
  } else {
    // Symmetric Jacobi matrix of the orthonormal polynomials (Golub & Welsch 1969), formed from
    // p + 1 and q + 1 (its entries for p, q near -1 are only starting values, but should not
    // cancel to nothing).
    const double p1 = pd + 1, q1 = qd + 1, pq2 = p1 + q1;
    std::vector<double> diagonal(n), off_diagonal(n - 1);
    diagonal[0] = (q1 - p1) / pq2;
    for (std::size_t k = 1; k < n; ++k) {
      const double s = 2.0 * static_cast<double>(k - 1) + pq2;  // 2k + p + q
      diagonal[k] = (q1 - p1) * (pq2 - 2) / (s * (s + 2));
    }
    for (std::size_t k = 1; k < n; ++k) {
      const double m = static_cast<double>(k), s = 2 * (m - 1) + pq2;  // 2k + p + q
      const double b2 = k == 1 ? 4 * p1 * q1 / (pq2 * pq2 * (pq2 + 1))
                               : 4 * m * (m - 1 + p1) * (m - 1 + q1) * (m - 2 + pq2) / (s * s * (s + 1) * (s - 1));
      off_diagonal[k - 1] = std::sqrt(b2);
    }
    std::vector<double> start = diagonal;  // eigenvalues, increasing
    if (!tridiagonal_eigenvalues(start, off_diagonal)) {
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
      const Eigen::Map<const Eigen::VectorXd> eigen_diagonal(diagonal.data(), static_cast<Eigen::Index>(n));
      const Eigen::Map<const Eigen::VectorXd> eigen_off(off_diagonal.data(), static_cast<Eigen::Index>(n - 1));
      eigen.computeFromTridiagonal(eigen_diagonal, eigen_off, Eigen::EigenvaluesOnly);
      for (std::size_t i = 0; i < n; ++i) start[i] = eigen.eigenvalues()[static_cast<Eigen::Index>(i)];
    }
    // Split at x = 0 into distances from the nearer end; the right half in order of
    // increasing u = 1 - x (decreasing x).
    constexpr double tiny = 1e-300;  // a start at (or rounded onto) an end is moved inside
    for (std::size_t i = n; i-- > 0;) {
      if (start[i] >= 0) right_start.push_back(W(std::max(1 - start[i], tiny)));
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (start[i] < 0) left_start.push_back(W(std::max(1 + start[i], tiny)));
    }
  }
  const W pw = W(p), qw = W(q);
  const auto constants = gauss_jacobi_weight_constants<W>(n, pw, qw);
  const auto right = recurrence_newton<W>(n, pw, qw, std::move(right_start), constants.right);
  const auto left = recurrence_newton<W>(n, qw, pw, std::move(left_start), constants.left);
  if (!right.converged || !left.converged) {
    throw std::runtime_error("rhabel::quadrature::gauss_jacobi: Newton's method on the recurrence did not converge (n = " +
                             std::to_string(n) + "); please report the case");
  }
  quadrature_rule<Real> rule;
  rule.x.resize(n);
  rule.hi_minus_x.resize(n);
  rule.x_minus_lo.resize(n);
  rule.weight.resize(n);
  const std::size_t left_count = left.u.size();
  for (std::size_t j = 0; j < left_count; ++j) {  // node j from -1 is element j
    rule.x_minus_lo[j] = Real(left.u[j]);
    rule.hi_minus_x[j] = Real(2 - left.u[j]);
    rule.x[j] = Real(left.u[j]) - 1;
    rule.weight[j] = Real(left.weight[j]);
  }
  for (std::size_t j = 0; j < right.u.size(); ++j) {  // node j from +1 is element n - 1 - j
    const std::size_t i = n - 1 - j;
    rule.hi_minus_x[i] = Real(right.u[j]);
    rule.x_minus_lo[i] = Real(2 - right.u[j]);
    rule.x[i] = 1 - Real(right.u[j]);
    rule.weight[i] = Real(right.weight[j]);
  }
  return rule;
}

// Where one half of the asymptotic rule goes in the final arrays: node k (1-based, counted
// from this end) is element first + stride (k - 1); near and far are that end's distance
// arrays (hi_minus_x and x_minus_lo for the end +1), and x = end (1 - near), end = +-1.
struct gauss_jacobi_half_target {
  double* x;
  double* near;
  double* far;
  double* weight;
  std::ptrdiff_t first, stride;
  double end;
  void set(std::size_t k, double u, double v, double w) const {
    const auto i = static_cast<std::size_t>(first + stride * static_cast<std::ptrdiff_t>(k - 1));
    near[i] = u;
    far[i] = v;
    weight[i] = w;
    x[i] = end * (1 - u);
  }
};

// Guess k of the interior region as a point ready for the expansion: t = K + correction
// (interior_guess), K = (k + a/2 - 1/4) pi / rho, with s = sin(t/2), c = cos(t/2), 1/(s c)
// and the phase. The phase of the expansion at t is
//   phi_0 = rho t - (a + 1/2) pi/2 = (k - 1/2) pi + epsilon,
//   epsilon = [rho K - (k + a/2 - 1/4) pi] + rho correction,
// the bracket (the rounding of the double K) formed exactly by Dekker's two-product
// (detail::two_product_error, no FMA call, so the loop vectorises) and a two-term pi, so that
// cos phi_0 = (-1)^k sin epsilon and sin phi_0 = (-1)^(k+1) cos epsilon. This replaces the tan of
// the guess and the sin and cos of a phase of size n (whose rounding alone is eps rho t) by one
// sin and cos of K/2 and two small angles, and the phase of the double point t is known to a few
// eps absolute. The guess is split in steps so that `complete` is free of branches and calls
// (the batches of gauss_jacobi_asymptotic_half vectorise it).
struct interior_guesser {
  static constexpr double pi_hi = 3.141592653589793116, pi_lo = 1.2246467991473532e-16;  // pi = pi_hi + pi_lo
  // complete() is exact to 3e-22 relative up to this angle (first omitted Taylor terms).
  static constexpr double largest_polynomial_angle = 0.01;
  // guess_angles uses the Taylor series of sin and cos of K/2 up to this angle (the half of
  // the rule needs K/2 <= pi/4 + O(1/n)).
  static constexpr double largest_series_half_angle = 0.8;
  double rho, angle_scale, inverse_4rho2, ca, cb, a_quarter;
  interior_guesser(double a, double b, double rho_)
      : rho(rho_), angle_scale(pi_hi / rho_), inverse_4rho2(1 / (4 * rho_ * rho_)), ca(0.25 - a * a),
        cb(0.25 - b * b), a_quarter(a / 2 - 0.25) {}

  // K, its rounding residual rho K - (k + a/2 - 1/4) pi, sin(K/2), cos(K/2) and (-1)^k for
  // the nodes k = k0, ..., k0 + count - 1 (count <= hahn_expansion::batch_size), in loops
  // without calls that the compiler vectorises: the exact products by Dekker's two-product
  // (the same values as fma, which is a libm call in this build), sin and cos of K/2 <=
  // largest_series_half_angle by their Taylor series (glibc's sincos otherwise). Single nodes
  // go through the same code (count = 1), so batch and single node agree bit for bit.
  void guess_angles(std::size_t k0, std::size_t count, double* K, double* residual, double* sin_K, double* cos_K,
                    double* sign) const {
    double half[hahn_expansion::batch_size];
    // Members in locals: the stores through the output pointers could otherwise alias them,
    // and the loop would not vectorise. k0 + i as double(k0) + int i (int to double converts
    // in SIMD registers, 64-bit integers do not with SSE2); exact below 2^53.
    const double rho = this->rho, angle_scale = this->angle_scale, a_quarter = this->a_quarter;
    const double first = static_cast<double>(k0), first_sign = (k0 & 1) ? -1.0 : 1.0;
    const int size = static_cast<int>(count);
    for (int i = 0; i < size; ++i) {
      // j = k + a/2 - 1/4 = j_hi + j_lo (TwoSum), j pi = P + P_lo.
      const double kk = first + static_cast<double>(i);
      const double j_hi = kk + a_quarter;
      const double j_virtual = j_hi - kk;
      const double j_lo = (kk - (j_hi - j_virtual)) + (a_quarter - j_virtual);
      const double P = j_hi * pi_hi;
      const double P_lo = two_product_error(j_hi, pi_hi, P) + j_hi * pi_lo + j_lo * pi_hi;
      K[i] = j_hi * angle_scale;
      // rho K - P is exact (Sterbenz: rho K is within an ulp or two of P), so with the exact
      // error of the product this is fma(rho, K, -P) - P_lo.
      const double rho_K = rho * K[i];
      residual[i] = ((rho_K - P) + two_product_error(rho, K[i], rho_K)) - P_lo;
      half[i] = K[i] / 2;
      const double x = half[i], z = x * x;
      // sin x = x + x z S(z), cos x = 1 - z/2 + z^2 C(z): Taylor to x^19 and x^20; for
      // x <= 0.8 the truncation is below 2^-70 relative.
      const double S =
          -1.0 / 6 +
          z * (1.0 / 120 +
               z * (-1.0 / 5040 +
                    z * (1.0 / 362880 +
                         z * (-1.0 / 39916800 +
                              z * (1.0 / 6227020800 +
                                   z * (-1.0 / 1307674368000 +
                                        z * (1.0 / 355687428096000 + z * (-1.0 / 121645100408832000))))))));
      const double C =
          1.0 / 24 +
          z * (-1.0 / 720 +
               z * (1.0 / 40320 +
                    z * (-1.0 / 3628800 +
                         z * (1.0 / 479001600 +
                              z * (-1.0 / 87178291200 +
                                   z * (1.0 / 20922789888000 +
                                        z * (-1.0 / 6402373705728000 + z * (1.0 / 2432902008176640000))))))));
      sin_K[i] = x + x * z * S;
      cos_K[i] = 1 - (z / 2 - z * z * C);
      sign[i] = (i & 1) ? -first_sign : first_sign;
    }
    for (std::size_t i = 0; i < count; ++i) {
      if (!(half[i] <= largest_series_half_angle)) {
        sin_K[i] = std::sin(half[i]);
        cos_K[i] = std::cos(half[i]);
      }
    }
  }

  void guess_angle(std::size_t k, double& K, double& residual, double& sin_K, double& cos_K, double& sign) const {
    guess_angles(k, 1, &K, &residual, &sin_K, &cos_K, &sign);
  }

  // The correction and the point, with Taylor polynomials for the sin and cos of the two small
  // angles correction/2 and epsilon; valid when largest_angle <= largest_polynomial_angle
  // (else call exact_point).
  void complete(double sin_K, double cos_K, double residual, double sign, double& correction, double& s, double& c,
                double& cos_phi, double& sin_phi, double& largest_angle) const {
    correction = (ca * cos_K * cos_K - cb * sin_K * sin_K) * inverse_4rho2 / (sin_K * cos_K);
    point(sin_K, cos_K, residual, sign, correction, s, c, cos_phi, sin_phi, largest_angle);
  }

  // sin x and cos x for |x| <= largest_polynomial_angle by their Taylor polynomials to x^7
  // and x^8 (truncation below 3e-22 relative). Products with the rounded reciprocals, not
  // divisions (twelve divisions per node were 5% of the rule at n = 10^4; the terms they
  // scale are below 1e-4 relative, so the reciprocals' rounding is below 1e-20).
  static void small_angle_sin_cos(double x, double& sin_x, double& cos_x) {
    constexpr double r6 = 1.0 / 6, r20 = 1.0 / 20, r42 = 1.0 / 42, r12 = 1.0 / 12, r30 = 1.0 / 30, r56 = 1.0 / 56;
    const double x2 = x * x;
    sin_x = x * (1 - x2 * r6 * (1 - x2 * r20 * (1 - x2 * r42)));
    cos_x = 1 - x2 / 2 * (1 - x2 * r12 * (1 - x2 * r30 * (1 - x2 * r56)));
  }

  // The point t = K + correction for a given correction (complete's second half), s and c by
  // the addition theorem from sin(K/2), cos(K/2) and the half correction.
  void point(double sin_K, double cos_K, double residual, double sign, double correction, double& s, double& c,
             double& cos_phi, double& sin_phi, double& largest_angle) const {
    const double delta = correction / 2, epsilon = residual + rho * correction;
    double sin_delta, cos_delta, sin_e, cos_e;
    small_angle_sin_cos(delta, sin_delta, cos_delta);
    small_angle_sin_cos(epsilon, sin_e, cos_e);
    s = sin_K * cos_delta + cos_K * sin_delta;  // sin((K + correction)/2)
    c = cos_K * cos_delta - sin_K * sin_delta;
    cos_phi = sign * sin_e;
    sin_phi = -sign * cos_e;
    largest_angle = std::max(std::abs(delta), std::abs(epsilon));
  }

  // The point with the library's sin and cos (angles beyond the polynomials occur near the
  // boundary for |a| > 1/2, where the correction grows like a^2).
  void exact_point(double sin_K, double cos_K, double residual, double sign, double correction, double& s, double& c,
                   double& cos_phi, double& sin_phi) const {
    const double delta = correction / 2;
    const double sin_delta = std::sin(delta), cos_delta = std::cos(delta);
    s = sin_K * cos_delta + cos_K * sin_delta;
    c = cos_K * cos_delta - sin_K * sin_delta;
    phase(residual, sign, correction, cos_phi, sin_phi);
  }

  // The phase phi_0 at t = K + correction as (cos phi_0, sin phi_0) from epsilon = residual +
  // rho correction (polynomials up to largest_polynomial_angle, the library beyond).
  void phase(double residual, double sign, double correction, double& cos_phi, double& sin_phi) const {
    const double epsilon = residual + rho * correction;
    double sin_e, cos_e;
    if (std::abs(epsilon) <= largest_polynomial_angle) {
      small_angle_sin_cos(epsilon, sin_e, cos_e);
    } else {
      sin_e = std::sin(epsilon);
      cos_e = std::cos(epsilon);
    }
    cos_phi = sign * sin_e;
    sin_phi = -sign * cos_e;
  }

  // A Newton step of the guess k: the new point is the double t = K + (correction + step), and
  // the correction becomes t - K, exact whenever t/K is in [1/2, 2] (Sterbenz's lemma; in the
  // interior t is within a few per cent of K: the guess's correction is ~ a^2/(2 (rho K)^2) of
  // K, 1.6% at a = 30 on the first interior node), so that the phase formed from the
  // correction is that of the same double t whose sin(t/2) and cos(t/2) are taken. Why it matters: the weight is Q s^(2a+1) c^(2b+1) / G'^2 with s, c at
  // the point where G' is taken, and G' follows the phase; a phase for the unrounded K +
  // correction with s, c of the rounded t (the former form) puts a relative error of up to
  // (2a + 1) eps/2 into the weight (p = q = 5: 14.1 eps instead of 8.9 eps in the 60-digit
  // table; with s, c by the addition theorem instead, 15.6 eps). The library's sin and cos of
  // t/2 are used rather than the addition theorem: after steps the correction may leave the
  // polynomials' range, and they are within half an ulp.
  void move(double K, double residual, double sign, double step, double& correction, double& s, double& c,
            double& cos_phi, double& sin_phi) const {
    const double t = K + (correction + step);
    correction = t - K;
    s = std::sin(t / 2);
    c = std::cos(t / 2);
    phase(residual, sign, correction, cos_phi, sin_phi);
  }
};

// The finishing step of an interior node (Newton step, then Halley and Taylor, see below): from
// s = sin(t/2), c = cos(t/2), 1/(s c), G and G' at t, the distances u = 1 - cos(t + h),
// v = 1 + cos(t + h), the Newton step and y'(t + h) / prefactor(t) (weight_slope).
struct interior_finisher {
  double a_half, b_half, a_minus_b, a_plus_b_1, lambda;
  interior_finisher(std::size_t n, double a, double b)
      : a_half(a + 0.5), b_half(b + 0.5), a_minus_b(a - b), a_plus_b_1(a + b + 1),
        lambda(static_cast<double>(n) * (static_cast<double>(n) + a + b + 1)) {}
  void operator()(double s, double c, double inverse_sc, double value, double slope, double& step, double& h,
                  double& u, double& v, double& weight_slope) const {
    const double inverse_sin_t = inverse_sc / 2;
    // y' / prefactor = G' + L G, L = d/dt log prefactor = ((b + 1/2) s^2 - (a + 1/2) c^2) / sin t.
    const double y_slope = slope + (b_half * s * s - a_half * c * c) * inverse_sin_t * value;
    step = -value / y_slope;
    const double cos_t = (c - s) * (c + s);
    const double C = (a_minus_b + a_plus_b_1 * cos_t) * inverse_sin_t;
    const double C_prime = -(a_plus_b_1 + a_minus_b * cos_t) * inverse_sin_t * inverse_sin_t;
    const double ratio2 = -C + lambda * step;                            // y'' / y'
    const double ratio3 = C * C - C_prime - lambda - C * lambda * step;  // y''' / y'
    // Halley's step step / (1 + r), r = step ratio2 / 2, without the division: once
    // rho |step| < 1e-6, |r| < 1e-5 (ratio2 = O(rho^2 step) + O(C)), and the omitted r^3 is
    // below 1e-15 relative to the step (1e-21 in phase).
    const double r = step * ratio2 / 2;
    h = step * (1 - r * (1 - r));
    weight_slope = y_slope * (1 + ratio2 * h + ratio3 * h * h / 2);  // second-order Taylor step of y'
    // sin, cos of (t + h)/2 by the addition theorem; |h/2| < 1e-8, so two terms of each series are exact.
    const double half_h = h / 2, sin_dh = half_h - half_h * half_h * half_h * (1.0 / 6), cos_dh = 1 - half_h * half_h / 2;
    const double s1 = s * cos_dh + c * sin_dh, c1 = c * cos_dh - s * sin_dh;
    u = 2 * s1 * s1;
    v = 2 * c1 * c1;
  }
};

// One half of the asymptotic path (double): the nodes 1..count nearest the end with exponent a,
// written into a gauss_jacobi_half_target. The boundary nodes (initial guess outside the interior
// region of the Hahn expansion) and the interior nodes that the expansion cannot finish are
// refined together by recurrence_newton.
class gauss_jacobi_asymptotic_half_rule {
 public:
  gauss_jacobi_asymptotic_half_rule(std::size_t n, double a, double b, std::size_t count, double weight_factor,
                                    const gauss_jacobi_half_target& target)
      : n_(n), a_(a), b_(b), count_(count), weight_factor_(weight_factor), target_(target), hahn_(n, a, b),
        rho_(hahn_.rho()), guesser_(a, b, rho_), finisher_(n, a, b), power_(2 * a + 1, 2 * b + 1) {}

  // Computes all count nodes; false if Newton's method failed somewhere (the caller then falls back).
  bool run() {
    const std::size_t boundary = boundary_nodes();
    for (std::size_t k = 1; k <= boundary; ++k) by_recurrence(k, boundary_guess(k, a_, b_, rho_));
    for (std::size_t k0 = boundary + 1; k0 <= count_; k0 += B) batch(k0, std::min(B, count_ - k0 + 1));
    return refine_by_recurrence();
  }

 private:
  static constexpr std::size_t B = hahn_expansion::batch_size;
  // Interior: Newton in t on y = P_n(cos t) = prefactor(t) G(t). Once the phase step
  // sigma = rho |dt| is below 1e-6 the node is finished with one Halley step and the weight
  // from a second-order Taylor step of y', both using the differential equation
  //   y'' = -C(t) y' - lambda y,  C = (a - b + (a + b + 1) cos t) / sin t,  lambda = n (n + a + b + 1)
  // (DLMF 18.8.1 in t); the neglected terms are O(sigma^3) relative, below 1e-17.
  // w = weight_factor s^(2a+1) c^(2b+1) / (y'(t + h)/prefactor(t))^2 (s, c at the point t).
  static constexpr double finish_threshold = 1e-6;
  // Newton sweeps over a batch before its remaining unfinished points go node by node, for
  // every exponent (at a = 30, n = 10^4, about 2000 nodes need them, which took 3/4 of the time
  // node by node; at (-0.9, 0.3) 11 nodes, at (5, 5) 170). With the point after a step made
  // consistent (interior_guesser::move) they also lower the table's worst weight at p = q = 5
  // (8.9 eps, against 11.6 without the sweeps).
  static constexpr int batch_newton_sweeps = 3;

  // The state of the points of one batch (arrays of hahn_expansion::batch_size).
  struct batch_points {
    double K[B], residual[B], sin_K[B], cos_K[B], sign[B], correction[B], largest_angle[B];
    double s0[B], c0[B], cos_phi[B], sin_phi[B], last_bound[B], total[B];
    double step[B], h[B], u[B], v[B], weight_slope[B], factor[B];
  };

  // The number of boundary nodes: those before the first one whose initial guess lies in the
  // interior region.
  std::size_t boundary_nodes() const {
    std::size_t boundary = 0;
    double value = 0, slope = 0, s = 0, c = 0;
    while (boundary < count_ && !hahn_.evaluate(interior_guess(boundary + 1, a_, b_, rho_), value, slope, s, c)) ++boundary;
    return boundary;
  }

  // Hands node k over to recurrence_newton, starting from the angle t (u = 1 - cos t).
  void by_recurrence(std::size_t k, double t) {
    by_recurrence_.push_back(k);
    const double sin_half = std::sin(t / 2);
    recurrence_start_.push_back(2 * sin_half * sin_half);
  }

  // One interior node on its own (the batches below hand over every node they cannot finish):
  // the batch's computation for a single point, with up to 20 Newton steps.
  void single_node(std::size_t k) {
    double K, residual, sin_K, cos_K, sign, correction, cos_phi, sin_phi, largest_angle;
    double value = 0, slope = 0, s = 0, c = 0;
    guesser_.guess_angle(k, K, residual, sin_K, cos_K, sign);
    guesser_.complete(sin_K, cos_K, residual, sign, correction, s, c, cos_phi, sin_phi, largest_angle);
    if (!(largest_angle <= interior_guesser::largest_polynomial_angle)) {
      guesser_.exact_point(sin_K, cos_K, residual, sign, correction, s, c, cos_phi, sin_phi);
    }
    double step = 0, h = 0, u = 0, v = 0, weight_slope = 0;
    bool ok = hahn_.evaluate_at(s, c, 1 / (s * c), cos_phi, sin_phi, value, slope);
    // Newton in t until the step is small (rare: small n or large exponents), then finish.
    for (int iteration = 0; ok; ++iteration) {
      finisher_(s, c, 1 / (s * c), value, slope, step, h, u, v, weight_slope);
      if (std::abs(step) * rho_ < finish_threshold) break;
      ok = iteration < 20 && std::abs(step) < K + correction;  // t stays in (0, 2t)
      if (ok) {
        guesser_.move(K, residual, sign, step, correction, s, c, cos_phi, sin_phi);
        ok = hahn_.evaluate_at(s, c, 1 / (s * c), cos_phi, sin_phi, value, slope);
      }
    }
    if (ok && K + correction + h > 0) {
      target_.set(k, u, v, weight_factor_ * power_(s, c) / (weight_slope * weight_slope));
    } else {
      by_recurrence(k, interior_guess(k, a_, b_, rho_));
    }
  }

  // Evaluates `size` points given by s, c and the phase, and finishes them; false if the first
  // point needs more than hahn_max_terms terms (the caller's order: increasing t).
  bool evaluate(std::size_t size, const double* s_, const double* c_, const double* cos_phi_, const double* sin_phi_,
                double* last_bound_, double* total_, double* step_, double* h_, double* u_, double* v_,
                double* weight_slope_) const {
    double inverse_sc[B], values[B], slopes[B];
    for (std::size_t i = 0; i < size; ++i) inverse_sc[i] = 1 / (s_[i] * c_[i]);
    const int terms = hahn_.terms_needed(s_[0], c_[0]);
    if (terms > hahn_max_terms) return false;
    hahn_.evaluate_batch(size, terms, s_, c_, inverse_sc, cos_phi_, sin_phi_, values, slopes, last_bound_, total_);
    for (std::size_t i = 0; i < size; ++i) {
      finisher_(s_[i], c_[i], inverse_sc[i], values[i], slopes[i], step_[i], h_[i], u_[i], v_[i], weight_slope_[i]);
    }
    return true;
  }

  // The interior nodes k0, ..., k0 + size - 1 as a batch: the computation of single_node
  // in loops over the batch without branches or calls (vectorised by the compiler; the rule at
  // n = 10^6 takes about 0.8 of the time of the node-by-node loop), with the number of terms
  // that the batch's first node needs (the bound decreases with t in the interior, except near
  // t = pi/2 for large b). A node goes to single_node whenever single_node would have taken another branch:
  // a last term not below eps/16, a bound sum above hahn.max_total(), or a Newton step above the
  // finishing threshold after the batch's sweeps.
  void batch(std::size_t k0, std::size_t size) {
    batch_points p{};  // value-initialised: else GCC 12 at -O3 warns -Wmaybe-uninitialized
    guesser_.guess_angles(k0, size, p.K, p.residual, p.sin_K, p.cos_K, p.sign);
    for (std::size_t i = 0; i < size; ++i) {
      guesser_.complete(p.sin_K[i], p.cos_K[i], p.residual[i], p.sign[i], p.correction[i], p.s0[i], p.c0[i],
                        p.cos_phi[i], p.sin_phi[i], p.largest_angle[i]);
    }
    for (std::size_t i = 0; i < size; ++i) {
      if (!(p.largest_angle[i] <= interior_guesser::largest_polynomial_angle)) {
        guesser_.exact_point(p.sin_K[i], p.cos_K[i], p.residual[i], p.sign[i], p.correction[i], p.s0[i], p.c0[i],
                             p.cos_phi[i], p.sin_phi[i]);
      }
    }
    if (!evaluate(size, p.s0, p.c0, p.cos_phi, p.sin_phi, p.last_bound, p.total, p.step, p.h, p.u, p.v,
                  p.weight_slope)) {
      for (std::size_t i = 0; i < size; ++i) single_node(k0 + i);
      return;
    }
    newton_sweeps(size, p);
    power_(size, p.s0, p.c0, p.factor);
    for (std::size_t i = 0; i < size; ++i) {
      const bool ok = p.last_bound[i] < hahn_expansion::tolerance && p.total[i] <= hahn_.max_total() &&
                      std::abs(p.step[i]) * rho_ < finish_threshold && p.K[i] + p.correction[i] + p.h[i] > 0;
      if (ok) {
        target_.set(k0 + i, p.u[i], p.v[i], weight_factor_ * p.factor[i] / (p.weight_slope[i] * p.weight_slope[i]));
      } else {
        single_node(k0 + i);
      }
    }
  }

  // Up to batch_newton_sweeps Newton steps for the batch's points not yet within the finishing
  // threshold.
  // Newton sweeps for the points whose guess is not yet within the finishing threshold (all
  // of them near the end at large exponents, a few elsewhere): only those points move
  // (interior_guesser::move: the step goes into the correction, so the phase stays a small
  // angle known to a few eps) and only they are evaluated again, as a batch of their own in
  // the order of the batch (the points that did not move keep their results).
  void newton_sweeps(std::size_t size, batch_points& p) const {
    for (int sweep = 0; sweep < batch_newton_sweeps; ++sweep) {
      std::size_t moving[B], moving_count = 0;
      for (std::size_t i = 0; i < size; ++i) {
        if (std::abs(p.step[i]) * rho_ >= finish_threshold && p.last_bound[i] < hahn_expansion::tolerance &&
            p.total[i] <= hahn_.max_total() && std::abs(p.step[i]) < p.K[i] + p.correction[i]) {
          moving[moving_count++] = i;
        }
      }
      if (moving_count == 0) break;
      double ms[B], mc[B], mcos[B], msin[B], mlast[B], mtotal[B], mstep[B], mh[B], mu[B], mv[B], mslope[B];
      for (std::size_t j = 0; j < moving_count; ++j) {
        const std::size_t i = moving[j];
        guesser_.move(p.K[i], p.residual[i], p.sign[i], p.step[i], p.correction[i], p.s0[i], p.c0[i], p.cos_phi[i],
                      p.sin_phi[i]);
        ms[j] = p.s0[i];
        mc[j] = p.c0[i];
        mcos[j] = p.cos_phi[i];
        msin[j] = p.sin_phi[i];
      }
      // A first moving point outside the interior region: the moving points go to single_node
      // (an infinite step marks them unfinished).
      if (!evaluate(moving_count, ms, mc, mcos, msin, mlast, mtotal, mstep, mh, mu, mv, mslope)) {
        for (std::size_t j = 0; j < moving_count; ++j) p.step[moving[j]] = std::numeric_limits<double>::infinity();
        break;
      }
      for (std::size_t j = 0; j < moving_count; ++j) {
        const std::size_t i = moving[j];
        p.last_bound[i] = mlast[j];
        p.total[i] = mtotal[j];
        p.step[i] = mstep[j];
        p.h[i] = mh[j];
        p.u[i] = mu[j];
        p.v[i] = mv[j];
        p.weight_slope[i] = mslope[j];
      }
    }
  }

  // The nodes handed over to recurrence_newton, refined and written; false if it did not converge.
  bool refine_by_recurrence() {
    if (by_recurrence_.empty()) return true;
    const long double la = a_, lb = b_;
    const auto refined = recurrence_newton<double>(
        n_, a_, b_, recurrence_start_,
        static_cast<double>(gauss_jacobi_weight_constant_over_end_value<long double>(n_, la, lb)));
    if (!refined.converged) return false;
    for (std::size_t j = 0; j < by_recurrence_.size(); ++j) {
      target_.set(by_recurrence_[j], refined.u[j], 2 - refined.u[j], refined.weight[j]);
    }
    return true;
  }

  std::size_t n_;
  double a_, b_;
  std::size_t count_;
  double weight_factor_;
  const gauss_jacobi_half_target& target_;
  const hahn_expansion hahn_;
  const double rho_;
  const interior_guesser guesser_;
  const interior_finisher finisher_;
  // s^(2a+1) c^(2b+1): per batch with two pows per batch (detail/gauss_jacobi_power.hpp,
  // within 2 eps like pow * pow), or per node with two pows.
  const endpoint_power power_;
  std::vector<std::size_t> by_recurrence_;  // node numbers k
  std::vector<double> recurrence_start_;
};

// One half of the asymptotic path (double): nodes 1..count nearest the end with exponent a,
// written in place into target. Returns false if Newton's method failed somewhere (the caller
// then falls back).
inline bool gauss_jacobi_asymptotic_half(std::size_t n, double a, double b, std::size_t count, double weight_factor,
                                         const gauss_jacobi_half_target& target) {
  return gauss_jacobi_asymptotic_half_rule(n, a, b, count, weight_factor, target).run();
}

// The asymptotic rule, built in place; an empty rule tells the caller to fall back.
inline quadrature_rule<double> gauss_jacobi_asymptotic(std::size_t n, double p, double q) {
  // Split at t = pi/2: the right half holds the nodes whose initial guess has t <= pi/2.
  const double rho = static_cast<double>(n) + (p + q + 1) / 2;
  std::size_t right_count = 0;
  if (p == q) {
    // Symmetric: the middle node of an odd n has the guess t = pi/2 up to rounding (which fell
    // above pi/2 at p = q = -1 + 1e-9, n = 101, and the mirror then lacked a node).
    right_count = (n + 1) / 2;
  } else {
    // interior_guess is increasing in k on (0, pi); bisect for the last k with t_k <= pi/2.
    std::size_t lo = 0, hi = n + 1;  // t_lo <= pi/2 < t_hi (t_0 = 0, t_{n+1} = pi by convention)
    while (hi - lo > 1) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (interior_guess(mid, p, q, rho) <= boost::math::constants::half_pi<double>()) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    right_count = lo;
  }
  quadrature_rule<double> rule;
  rule.x.resize(n);
  rule.hi_minus_x.resize(n);
  rule.x_minus_lo.resize(n);
  rule.weight.resize(n);
  const auto last = static_cast<std::ptrdiff_t>(n) - 1;
  const gauss_jacobi_half_target right{rule.x.data(), rule.hi_minus_x.data(), rule.x_minus_lo.data(),
                                       rule.weight.data(), last, -1, 1.0};
  const gauss_jacobi_half_target left{rule.x.data(), rule.x_minus_lo.data(), rule.hi_minus_x.data(),
                                      rule.weight.data(), 0, 1, -1.0};
  const double weight_factor = hahn_weight_factor(n, p, q);
  if (!gauss_jacobi_asymptotic_half(n, p, q, right_count, weight_factor, right)) return {};
  if (p == q) {
    // The rule is symmetric (the middle node of an odd n belongs to the right half): the left
    // half is the mirror image of the right one.
    for (std::size_t i = 0; i < n - right_count; ++i) {
      const std::size_t j = n - 1 - i;
      rule.x[i] = -rule.x[j];
      rule.x_minus_lo[i] = rule.hi_minus_x[j];
      rule.hi_minus_x[i] = rule.x_minus_lo[j];
      rule.weight[i] = rule.weight[j];
    }
  } else if (!gauss_jacobi_asymptotic_half(n, q, p, n - right_count, weight_factor, left)) {
    return {};
  }
  return rule;
}

// The double rule as a rule in Real (float); for double the rule itself, moved (a copy
// cost 15% of the time at n = 10^6).
template <class Real>
quadrature_rule<Real> convert_rule(quadrature_rule<double>&& rule) {
  if constexpr (std::is_same_v<Real, double>) {
    return std::move(rule);
  } else {
    quadrature_rule<Real> result;
    for (std::size_t i = 0; i < rule.size(); ++i) {
      result.x.push_back(Real(rule.x[i]));
      result.hi_minus_x.push_back(Real(rule.hi_minus_x[i]));
      result.x_minus_lo.push_back(Real(rule.x_minus_lo[i]));
      result.weight.push_back(Real(rule.weight[i]));
    }
    return result;
  }
}

}  // namespace detail

/// n-point Gauss-Jacobi rule for the weight (1 - x)^p (1 + x)^q on [-1, 1]: exact for
/// polynomials of degree <= 2n - 1. n >= 1, p and q in (-1, 30] (gauss_jacobi_max_exponent: the
/// range of the accuracy contract; larger exponents are refused). Returns the nodes in
/// increasing order with 1 - x and 1 + x to full relative accuracy, and the weights.
/// Accuracy (Real = double, relative, measured): <= 1e-14 in weights and in min(1 - x, 1 + x)
/// for n <= 10^6, p, q in (-1, 5]; weights <= 128 eps for p or q up to 30 (header comment).
/// Cost O(n) for n > 40 (double, float), O(n^2) otherwise.
/// Throws std::domain_error naming n, p or q when out of range (p or q <= -1, > 30, or NaN:
/// "rhabel::quadrature::gauss_jacobi: p = 1000 is outside the valid range (-1, 30]"); std::invalid_argument if the
/// asymptotic method is forced for a Real other than float/double; std::runtime_error if
/// Newton's method fails (never observed).
template <class Real>
quadrature_rule<Real> gauss_jacobi(std::size_t n, Real p, Real q, gauss_jacobi_options options = {}) {
  // (-1, 30]: the accuracy contract's range (gauss_jacobi_max_exponent); NaN fails both tests.
  // Subnormal and zero exponents are inside it.
  if (!(p > -1) || !(p <= Real(gauss_jacobi_max_exponent))) {
    detail::throw_bad_parameter("rhabel::quadrature::gauss_jacobi", "p", p, "(-1, 30]");
  }
  if (!(q > -1) || !(q <= Real(gauss_jacobi_max_exponent))) {
    detail::throw_bad_parameter("rhabel::quadrature::gauss_jacobi", "q", q, "(-1, 30]");
  }
  if (n == 0) detail::throw_bad_parameter("rhabel::quadrature::gauss_jacobi", "n", 0, "[1, inf)");
  const bool hardware = detail::gauss_jacobi_is_hardware_float<Real>;
  switch (options.method) {
    case gauss_jacobi_method::automatic:
      if (p == q && (p == Real(-0.5) || p == Real(0.5))) return detail::gauss_chebyshev<Real>(n, p > 0);
      break;
    case gauss_jacobi_method::recurrence:
      return detail::gauss_jacobi_by_recurrence(n, p, q);
    case gauss_jacobi_method::asymptotic:
      if (!hardware) {
        throw std::invalid_argument(
            "rhabel::quadrature::gauss_jacobi: method = asymptotic is only available for Real = float or double; use recurrence");
      }
      break;
  }
  if (!hardware || (options.method == gauss_jacobi_method::automatic && n <= gauss_jacobi_recurrence_max_n)) {
    return detail::gauss_jacobi_by_recurrence(n, p, q);
  }
  if constexpr (detail::gauss_jacobi_is_hardware_float<Real>) {
    auto rule = detail::gauss_jacobi_asymptotic(n, static_cast<double>(p), static_cast<double>(q));
    if (rule.size() != n || !detail::gauss_jacobi_strictly_increasing(rule)) {
      // Safety net (see the header comment); the O(n^2) path only where it finishes in seconds.
      if (n <= gauss_jacobi_fallback_max_n) return detail::gauss_jacobi_by_recurrence(n, p, q);
      throw std::runtime_error("rhabel::quadrature::gauss_jacobi: the asymptotic path failed for n = " + std::to_string(n) +
                               "; please report the case");
    }
    return detail::convert_rule<Real>(std::move(rule));
  } else {
    return detail::gauss_jacobi_by_recurrence(n, p, q);
  }
}

/// n-point Gauss-Jacobi rule for the weight (hi - t)^p (t - lo)^q on [lo, hi] (lo < hi finite,
/// hi - lo finite). Nodes t_i = lo + (hi - lo)/2 (1 + x_i), taken from the nearer end;
/// hi - t_i and t_i - lo are the scaled distances of the rule on [-1, 1] (relative error
/// unchanged up to one rounding); weights scaled by ((hi - lo)/2)^(p+q+1), which may
/// overflow or underflow for extreme intervals and exponents.
template <class Real>
quadrature_rule<Real> gauss_jacobi(std::size_t n, Real p, Real q, Real lo, Real hi, gauss_jacobi_options options = {}) {
  using std::isfinite;
  using std::pow;
  if (!isfinite(lo)) detail::throw_bad_parameter("rhabel::quadrature::gauss_jacobi", "lo", lo, "finite, lo < hi");
  if (!isfinite(hi) || !(hi > lo)) detail::throw_bad_parameter("rhabel::quadrature::gauss_jacobi", "hi", hi, "finite, hi > lo");
  const Real half_length = hi / 2 - lo / 2;  // no overflow even when hi - lo exceeds the range
  quadrature_rule<Real> rule = gauss_jacobi(n, p, q, options);
  const Real scale = pow(half_length, p + q + 1);
  for (std::size_t i = 0; i < rule.size(); ++i) {
    rule.hi_minus_x[i] *= half_length;
    rule.x_minus_lo[i] *= half_length;
    // Take the node from the nearer end so that it inherits that distance's accuracy.
    rule.x[i] = rule.x_minus_lo[i] <= rule.hi_minus_x[i] ? lo + rule.x_minus_lo[i] : hi - rule.hi_minus_x[i];
    rule.weight[i] *= scale;
  }
  return rule;
}

}  // namespace rhabel::quadrature
