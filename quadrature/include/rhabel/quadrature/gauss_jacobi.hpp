// rhabel/quadrature/gauss_jacobi.hpp
//
// Gauss-Jacobi quadrature: nodes x_i and weights w_i such that
//   sum_i w_i f(x_i) = int_{-1}^{1} (1 - x)^p (1 + x)^q f(x) dx   for every polynomial f of degree <= 2n - 1,
// for any n >= 1 and exponents p, q > -1 (p belongs to x = +1, q to x = -1), and the same
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
//    and double): Golub-Welsch eigenvalues (Eigen, double) as starting values, then Newton's
//    method in u = distance to the nearer end on the three-term recurrence in difference form
//    (detail/gauss_jacobi_recurrence.hpp; it evaluates P_n at the exact point 1 - u), run in
//    long double when Real is double or float and in Real otherwise; weights from
//    K_n / ((1 - x^2) P_n'^2). O(n^2) per sweep, a handful of sweeps.
//  * asymptotic (n > 40, Real = double or float): after Hale & Townsend (2013). The nodes with
//    t <= pi/2 are found for (p, q), the others as the same problem for (q, p) (for p = q the
//    half is mirrored). Interior nodes: Newton in t on Hahn's interior expansion of P_n
//    (detail/gauss_jacobi_asymptotic.hpp) from the Gatteschi-Pittaluga guesses, finished by a
//    Halley step and a Taylor step for the derivative that use the differential equation;
//    weights from the derivative and a gamma-ratio constant. O(1) per node. A node is interior
//    when the expansion, summed to at most 30 terms, has a phase-independent term bound below
//    eps/16 and a sum of term bounds <= 2 (no cancellation). Measured at n = 10^6 this puts the
//    first interior node at rho t ~ 20 for |p| <= 2, 22 for p = 5 and ~650 for p = 30
//    (rho = n + (p+q+1)/2), i.e. 6, 4 and ~190 boundary nodes at that end (none for p = 1/2).
//    Boundary nodes: Newton in u on the difference-form recurrence from Bessel-zero guesses
//    (Olver; DLMF 18.16.8; boost::math::cyl_bessel_j_zero), all boundary nodes of one end
//    sharing each O(n) sweep; for n >= ~10^4 the guesses are already within 1e-15 and one
//    sweep suffices. The sweep runs in double with all four running sums compensated, two
//    nodes per SIMD vector, and coefficients formed from p + 1 and q + 1 (no cancellation at
//    p = -0.999); the Newton step is also required to be small relative to u (first node at
//    p = -0.999). Against the former long double sweep it moves these nodes by <= 1 ulp and
//    their weights by <= 4.5 eps (measured, n = 101 ... 10^6, p, q down to -0.999), at a
//    ninth of the cost. Hale & Townsend use the Baratella-Gatteschi Bessel expansion there;
//    the recurrence is used instead because it has no truncation error to control at any n,
//    at the price of O(n) per boundary node (~17% of the time at n = 10^6 for p <= 5; the
//    rest is the interior expansion, one evaluation per node, and its sin/cos).
//    Safety net: if the Newton iterations fail or the distances of the assembled nodes are not
//    strictly monotone (never observed), the routine falls back to the recurrence path for
//    n <= gauss_jacobi_fallback_max_n = 20000 and throws std::runtime_error above.
//
// Accuracy contract, Real = double (relative error; an estimate from the tables, not a bound):
//  * 1 <= n <= 10^6, p, q in (-1, 5]: <= 1e-14 (45 eps) in every weight and in min(1 - x, 1 + x)
//    of every node, and in max(1 - x, 1 + x). Measured against the committed 60-digit table
//    tests/data/gauss_jacobi_reference.csv (tools/reference/gauss_jacobi_reference.cpp:
//    n = 1, 2, 3, 100, 101, 10^4 for all 64 pairs p, q in {-0.999, -0.9, -0.5, 0, 0.25, 0.5, 5, 30},
//    n = 10^6 for five pairs, 1024 and 65536 for the regression values; node indices on both
//    sides of the boundary/interior switch): worst 2.9 eps for the nodes and 12 eps for the
//    weights (n = 10^6: 2.3 and 5.5 eps). The weights of the asymptotic path carry
//    s^(2p+1) c^(2q+1), s = sin(t/2), c = cos(t/2), so a one-ulp rounding of the node is
//    amplified by up to 2p + 1; the recurrence path (n <= 40, or forced) is within 0.5 eps.
//    At the n = 40 / 41 switch and for n = 10 ... 100 the asymptotic path is within 3.5 eps
//    (nodes) and 18 eps (weights) of the recurrence path (p, q in [-0.999, 5]).
//  * p or q in (5, 30]: nodes within 4 eps (measured 3.2), weights within 128 eps (measured
//    62 eps at n = 100, 48 eps at n = 10^4 and at n = 10^6).
//  * Real = cpp_bin_float_50 (recurrence path): measured 46 eps_50 (n <= 100, q = 30).
//  Never judge a rule by sum(w) alone: it hides 1e-9 errors in individual weights.
//
// Constants. K_n and the interior weight factor are products of gamma ratios
// Gamma(z)/Gamma(z + delta) with z = n + O(1), computed in long double (detail::gamma_delta_ratio:
// z^-delta exp(-S) with the Bernoulli-polynomial series S of DLMF 5.11.8 for large z, Boost's
// tgamma_delta_ratio otherwise; Boost's alone errs by 6e-15 at z = 10^6, delta = 15.5). exp of a
// difference of lgamma values of size n log n would lose 7 digits at n = 10^6.
//
// Cost (bench/gauss_jacobi.cpp, Release, CPU time on a shared, loaded 2-core machine where wall
// time was twice that; measured back to back with the previous version, whose figures follow
// in brackets): p = 0.25, q = -0.5: n = 4000 0.53-0.61 ms [1.0 ms; GSL's
// gsl_integration_fixed_jacobi 261 ms, its weights off by up to 4e-10 there], n = 10^4 1.4 ms
// [2.6 ms], n = 10^6 130-140 ms [266-291 ms]; Legendre n = 10^4 0.7 ms [1.9 ms], n = 10^6
// 90 ms [205-223 ms]. (p, q) = (-0.5, 0): n = 100 0.037 ms [0.43-0.52 ms], 1000 0.15 ms
// [0.27 ms], 10^4 1.2 ms [2.3 ms], 10^6 135 ms [247 ms]; (0.25, 0): 0.080 ms [0.42 ms],
// 0.22 ms [0.47 ms], 1.5 ms [3.7 ms], 150 ms [381 ms]; n = 8: 7-8 us (unchanged, recurrence
// path). The targets (1 ms at 10^4, 100 ms at 10^6) are still missed by up to 1.5x
// for p != -1/2, 0: at n = 10^6 ~17% of the time is the boundary sweep and most of the rest
// the interior expansion (one evaluation, a tan and two sincos per node). Large exponents
// cost more: p = 30 at n = 10^6 has ~190 boundary nodes in the sweep.
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
#include "rhabel/quadrature/detail/gauss_jacobi_recurrence.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <boost/math/constants/constants.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
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

/// n up to this uses the recurrence path under gauss_jacobi_method::automatic (above it the
/// asymptotic path is cheaper: measured 0.12 against 0.16 ms at n = 40, 0.15 against 0.86 ms
/// at n = 100, loaded machine; it was 100 until the boundary sweep moved to double).
inline constexpr std::size_t gauss_jacobi_recurrence_max_n = 40;
/// Largest n for which a failure of the asymptotic path falls back to the O(n^2) recurrence
/// path (above it, std::runtime_error; never observed).
inline constexpr std::size_t gauss_jacobi_fallback_max_n = 20000;

namespace detail {

template <class Real>
inline constexpr bool gauss_jacobi_is_hardware_float = std::is_same_v<Real, double> || std::is_same_v<Real, float>;

// Working precision of the recurrence: long double for float and double, Real otherwise.
template <class Real>
using gauss_jacobi_working_t = std::conditional_t<gauss_jacobi_is_hardware_float<Real>, long double, Real>;

// One half of a rule: nodes near one end, in order of increasing distance to that end.
template <class Real>
struct gauss_jacobi_half {
  std::vector<Real> near;   // distance to this end (1 - x for the end +1)
  std::vector<Real> far;    // distance to the other end (2 - near, formed without cancellation)
  std::vector<Real> weight;
};

// Assembles the rule on [-1, 1] from the half at +1 (right) and the half at -1 (left).
template <class Real>
quadrature_rule<Real> gauss_jacobi_assemble(const gauss_jacobi_half<Real>& right, const gauss_jacobi_half<Real>& left) {
  quadrature_rule<Real> rule;
  const std::size_t n = right.near.size() + left.near.size();
  rule.x.reserve(n);
  rule.hi_minus_x.reserve(n);
  rule.x_minus_lo.reserve(n);
  rule.weight.reserve(n);
  for (std::size_t j = 0; j < left.near.size(); ++j) {
    rule.x_minus_lo.push_back(left.near[j]);
    rule.hi_minus_x.push_back(left.far[j]);
    rule.x.push_back(left.near[j] - 1);
    rule.weight.push_back(left.weight[j]);
  }
  for (std::size_t j = right.near.size(); j-- > 0;) {
    rule.hi_minus_x.push_back(right.near[j]);
    rule.x_minus_lo.push_back(right.far[j]);
    rule.x.push_back(1 - right.near[j]);
    rule.weight.push_back(right.weight[j]);
  }
  return rule;
}

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

// Recurrence path: Golub-Welsch starting values, Newton in u in the working precision W.
template <class Real>
quadrature_rule<Real> gauss_jacobi_by_recurrence(std::size_t n, const Real& p, const Real& q) {
  using W = gauss_jacobi_working_t<Real>;
  const double pd = static_cast<double>(p), qd = static_cast<double>(q);
  // Symmetric Jacobi matrix of the orthonormal polynomials (Golub & Welsch 1969).
  Eigen::VectorXd diagonal(static_cast<Eigen::Index>(n));
  Eigen::VectorXd off_diagonal(static_cast<Eigen::Index>(n > 1 ? n - 1 : 0));
  for (std::size_t k = 0; k < n; ++k) {
    const double s = 2.0 * static_cast<double>(k) + pd + qd;
    diagonal[static_cast<Eigen::Index>(k)] = k == 0 ? (qd - pd) / (pd + qd + 2) : (qd - pd) * (qd + pd) / (s * (s + 2));
  }
  for (std::size_t k = 1; k < n; ++k) {
    const double m = static_cast<double>(k), s = 2 * m + pd + qd;
    const double b2 = k == 1 ? 4 * (1 + pd) * (1 + qd) / ((2 + pd + qd) * (2 + pd + qd) * (3 + pd + qd))
                             : 4 * m * (m + pd) * (m + qd) * (m + pd + qd) / (s * s * (s + 1) * (s - 1));
    off_diagonal[static_cast<Eigen::Index>(k - 1)] = std::sqrt(b2);
  }
  std::vector<W> right_start, left_start;
  if (n == 1) {
    // x = (q - p)/(p + q + 2); start from the nearer end (Newton polishes the rounding).
    if (qd >= pd) {
      right_start.push_back(W(2 * (pd + 1) / (pd + qd + 2)));
    } else {
      left_start.push_back(W(2 * (qd + 1) / (pd + qd + 2)));
    }
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
    eigen.computeFromTridiagonal(diagonal, off_diagonal, Eigen::EigenvaluesOnly);
    constexpr double tiny = 1e-300;  // a start at (or rounded onto) an end is moved inside
    for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(n); ++i) {
      const double x = eigen.eigenvalues()[i];
      if (x >= 0) {
        right_start.push_back(W(std::max(1 - x, tiny)));
      } else {
        left_start.push_back(W(std::max(1 + x, tiny)));
      }
    }
  }
  const W pw = W(p), qw = W(q);
  
  // Newton in u for each half; the right half wants increasing u: eigenvalues are increasing
  // in x, so reverse.
  std::reverse(right_start.begin(), right_start.end());
  const auto right =
      recurrence_newton<W>(n, pw, qw, right_start, gauss_jacobi_weight_constant_over_end_value<W>(n, pw, qw));
  const auto left =
      recurrence_newton<W>(n, qw, pw, left_start, gauss_jacobi_weight_constant_over_end_value<W>(n, qw, pw));
  if (!right.converged || !left.converged) {
    throw std::runtime_error("gauss_jacobi: Newton's method on the recurrence did not converge (n = " +
                             std::to_string(n) + "); please report the case");
  }
  gauss_jacobi_half<Real> right_half, left_half;
  for (std::size_t j = 0; j < right.u.size(); ++j) {
    right_half.near.push_back(Real(right.u[j]));
    right_half.far.push_back(Real(2 - right.u[j]));
    right_half.weight.push_back(Real(right.weight[j]));
  }
  for (std::size_t j = 0; j < left.u.size(); ++j) {
    left_half.near.push_back(Real(left.u[j]));
    left_half.far.push_back(Real(2 - left.u[j]));
    left_half.weight.push_back(Real(left.weight[j]));
  }
  return gauss_jacobi_assemble(right_half, left_half);
}

// x^e for x in (0, 1] and a fixed exponent e: the frequent exponents 0, 1/2, 1, 3/2, 2 by
// sqrt and products (within 1.5 ulp, like pow's 1 ulp), others by pow.
class weight_power {
 public:
  explicit weight_power(double e) : e_(e) {
    kind_ = e == 0 ? 0 : e == 0.5 ? 1 : e == 1 ? 2 : e == 1.5 ? 3 : e == 2 ? 4 : 5;
  }
  double operator()(double x) const {
    switch (kind_) {
      case 0: return 1;
      case 1: return std::sqrt(x);
      case 2: return x;
      case 3: return x * std::sqrt(x);
      case 4: return x * x;
      default: return std::pow(x, e_);
    }
  }

 private:
  double e_;
  int kind_;
};

// One half of the asymptotic path (double): nodes 1..count nearest the end with exponent a.
inline gauss_jacobi_half<double> gauss_jacobi_asymptotic_half(std::size_t n, double a, double b, std::size_t count,
                                                              double weight_factor) {
  const hahn_expansion hahn(n, a, b);
  const double rho = hahn.rho();
  gauss_jacobi_half<double> half;
  half.near.assign(count, 0.0);
  half.far.assign(count, 0.0);
  half.weight.assign(count, 0.0);
  // Boundary: the nodes before the first one whose initial guess lies in the interior region.
  std::size_t boundary = 0;
  double value = 0, slope = 0, s = 0, c = 0;
  while (boundary < count && !hahn.evaluate(interior_guess(boundary + 1, a, b, rho), value, slope, s, c)) ++boundary;
  std::vector<std::size_t> by_recurrence;  // 0-based indices k - 1
  std::vector<double> recurrence_start;
  for (std::size_t k = 1; k <= boundary; ++k) {
    by_recurrence.push_back(k - 1);
    const double t = boundary_guess(k, a, b, rho);
    const double sin_half = std::sin(t / 2);
    recurrence_start.push_back(2 * sin_half * sin_half);
  }
  // Interior: Newton in t on y = P_n(cos t) = prefactor(t) G(t). Once the phase step
  // sigma = rho |dt| is below 1e-6 the node is finished with one Halley step and the weight
  // from a second-order Taylor step of y', both using the differential equation
  //   y'' = -C(t) y' - lambda y,  C = (a - b + (a + b + 1) cos t) / sin t,  lambda = n (n + a + b + 1)
  // (DLMF 18.8.1 in t); the neglected terms are O(sigma^3) relative, below 1e-17.
  const double lambda = static_cast<double>(n) * (static_cast<double>(n) + a + b + 1);
  const weight_power power_s(2 * a + 1), power_c(2 * b + 1);
  for (std::size_t k = boundary + 1; k <= count; ++k) {
    double t = interior_guess(k, a, b, rho);
    bool ok = false;
    for (int iteration = 0; iteration < 20; ++iteration) {
      if (!hahn.evaluate(t, value, slope, s, c)) break;
      // y' / prefactor = G' + L G with L = d/dt log prefactor = -(a + 1/2) c/(2s) + (b + 1/2) s/(2c).
      const double L = -(a + 0.5) * c / (2 * s) + (b + 0.5) * s / (2 * c);
      const double y_slope = slope + L * value;
      const double step = -value / y_slope;
      if (!(std::abs(step) * rho < 1e-6)) {
        t += step;
        continue;
      }
      const double sin_t = 2 * s * c, cos_t = (c - s) * (c + s);
      const double C = (a - b + (a + b + 1) * cos_t) / sin_t;
      const double C_prime = -((a + b + 1) + (a - b) * cos_t) / (sin_t * sin_t);
      const double ratio2 = -C + lambda * step;                            // y'' / y'
      const double ratio3 = C * C - C_prime - lambda - C * lambda * step;  // y''' / y'
      const double h = step / (1 + step * ratio2 / 2);                     // Halley
      const double taylor = 1 + ratio2 * h + ratio3 * h * h / 2;
      const double weight_slope = y_slope * taylor;
      half.weight[k - 1] =
          weight_factor * power_s(s) * power_c(c) / (weight_slope * weight_slope);
      // sin, cos of (t + h)/2 by the addition theorem; |h/2| < 1e-8, so two terms of each series are exact.
      const double half_h = h / 2, sin_dh = half_h - half_h * half_h * half_h / 6, cos_dh = 1 - half_h * half_h / 2;
      const double s1 = s * cos_dh + c * sin_dh, c1 = c * cos_dh - s * sin_dh;
      half.near[k - 1] = 2 * s1 * s1;
      half.far[k - 1] = 2 * c1 * c1;
      ok = t + h > 0;
      break;
    }
    if (!ok) {
      by_recurrence.push_back(k - 1);
      const double sin_half = std::sin(interior_guess(k, a, b, rho) / 2);
      recurrence_start.push_back(2 * sin_half * sin_half);
    }
  }
  if (!by_recurrence.empty()) {
    const long double la = a, lb = b;
    const auto refined = recurrence_newton<double>(
        n, a, b, recurrence_start,
        static_cast<double>(gauss_jacobi_weight_constant_over_end_value<long double>(n, la, lb)));
    if (!refined.converged) return {};  // an empty half tells the caller to fall back
    for (std::size_t j = 0; j < by_recurrence.size(); ++j) {
      const std::size_t i = by_recurrence[j];
      half.near[i] = refined.u[j];
      half.far[i] = 2 - refined.u[j];
      half.weight[i] = refined.weight[j];
    }
  }
  return half;
}

// The first count nodes of a half (its mirror image for p = q).
inline gauss_jacobi_half<double> mirror_half(const gauss_jacobi_half<double>& half, std::size_t count) {
  if (half.near.size() < count) return {};
  gauss_jacobi_half<double> result;
  result.near.assign(half.near.begin(), half.near.begin() + static_cast<std::ptrdiff_t>(count));
  result.far.assign(half.far.begin(), half.far.begin() + static_cast<std::ptrdiff_t>(count));
  result.weight.assign(half.weight.begin(), half.weight.begin() + static_cast<std::ptrdiff_t>(count));
  return result;
}

inline quadrature_rule<double> gauss_jacobi_asymptotic(std::size_t n, double p, double q) {
  // Split at t = pi/2: the right half holds the nodes whose initial guess has t <= pi/2.
  const double rho = static_cast<double>(n) + (p + q + 1) / 2;
  std::size_t right_count = 0;
  {
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
  const double weight_factor = hahn_weight_factor(n, p, q);
  const auto right = gauss_jacobi_asymptotic_half(n, p, q, right_count, weight_factor);
  // p = q: the rule is symmetric (the guesses split it at the middle, an odd n's middle node
  // going to the right half), so the left half is the mirror image of the right one.
  const auto left = p == q ? mirror_half(right, n - right_count) : gauss_jacobi_asymptotic_half(n, q, p, n - right_count, weight_factor);
  if (right.near.size() != right_count || left.near.size() != n - right_count) return {};  // falls back
  return gauss_jacobi_assemble(right, left);
}

template <class Real>
quadrature_rule<Real> convert_rule(const quadrature_rule<double>& rule) {
  if constexpr (std::is_same_v<Real, double>) {
    return rule;
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
/// polynomials of degree <= 2n - 1. n >= 1, p > -1, q > -1 (finite). Returns the nodes in
/// increasing order with 1 - x and 1 + x to full relative accuracy, and the weights.
/// Accuracy (Real = double, relative, measured): <= 1e-14 in weights and in min(1 - x, 1 + x)
/// for n <= 10^6, p, q in (-1, 5]; weights <= 128 eps for p or q up to 30 (header comment).
/// Cost O(n) for n > 40 (double, float), O(n^2) otherwise.
/// Throws std::domain_error naming n, p or q when out of range; std::invalid_argument if the
/// asymptotic method is forced for a Real other than float/double; std::runtime_error if
/// Newton's method fails (never observed).
template <class Real>
quadrature_rule<Real> gauss_jacobi(std::size_t n, Real p, Real q, gauss_jacobi_options options = {}) {
  detail::check_jacobi_exponents("gauss_jacobi", p, q);
  if (n == 0) detail::throw_bad_parameter("gauss_jacobi", "n", 0, "[1, inf)");
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
            "gauss_jacobi: method = asymptotic is only available for Real = float or double; use recurrence");
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
      throw std::runtime_error("gauss_jacobi: the asymptotic path failed for n = " + std::to_string(n) +
                               "; please report the case");
    }
    return detail::convert_rule<Real>(rule);
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
  if (!isfinite(lo)) detail::throw_bad_parameter("gauss_jacobi", "lo", lo, "finite, lo < hi");
  if (!isfinite(hi) || !(hi > lo)) detail::throw_bad_parameter("gauss_jacobi", "hi", hi, "finite, hi > lo");
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
