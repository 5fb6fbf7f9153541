// rhabel/abel/step_enrichment.hpp
//
// Solver for A g = F when F jumps at one interior point t0 (the wedge apex), with the local
// singularity of g built in (singular enrichment), so that int_a^t0 g converges spectrally; and
// (solve_kinks, section "Kinks" below) when F's first or second derivative jumps at points t_k
// (the knots of a cubic spline's slope), with each kink's singularity built in the same way.
//
// Local analysis (derived for this module; checked by the tests through the independent
// quadrature of the operator). Near an interior point, A maps the pair t_+^mu, (-t)_+^mu
// (t = x - x0) to |s|^(mu+alpha) on both sides, with coefficients containing Gamma(-mu-alpha):
// for mu = k - alpha, k = 0, 1, ..., every combination produces log|s| |s|^k terms EXCEPT
//     v_right / v_left = (-1)^k kappa,
// i.e. the functions (x - x0)^k E(x) with
//     E(x) = kappa (x - x0)_+^(-alpha) + (x0 - x)_+^(-alpha)
// have log-free images: an exact jump-type term of order k at x0 plus functions analytic across
// x0. For k = 0 the jump (left limit minus right limit) of A[E] is, from the Mellin constants
//     K_left - K_right = psi(1-alpha) - psi(alpha) = pi cot(pi alpha),
//     J_E = (pi / sin(pi alpha)) (1 - 2 kappa cos(pi alpha) + kappa^2)        (> 0 for alpha in (0,1)).
// So step data is matched by g = C phi + w sum_n c_n P_n^(del,gam), where
//     phi(x) = w(x) q(x) E(x),  q analytic on [-1, 1] with w q = w(x0) + O((x-x0)^(K+1)),
// so that phi creates no jump-type terms of order 1..K, and w keeps the edge behaviour of the
// class (the image of phi is smooth at the ends). q is the Taylor polynomial (degree K) of
// w(x0)/w(x) at x0 (see "Taylor degree" below; with the Moebius map of an apex near an edge, of
// the mapped local solution). C = jump(F~)/(w(x0) J_E);
// the remainder F~ - C A[phi] has only jump-type terms of order >= K+1 at x0 and is solved by the
// spectral method of abel_solver.hpp (Chebyshev interpolation, adaptive). A[phi] at the
// interpolation points is computed by composite Gauss-Jacobi quadrature, split at x0, at the
// evaluation point and graded toward every singular point (each factor's exponent is the
// Gauss-Jacobi weight of the pieces it ends).
// Small alpha (< 0.01 = normalized_enrichment_threshold(), down to alpha = 0 included).
// J_E = O(alpha) and the local solution becomes a log, so E is replaced by
//     (E - 1)/alpha = -log|x - x0| exprel(..) - ((1-kappa)/alpha) [x > x0] |x-x0|^-alpha
// (the removed w q/alpha is a smooth density), with jump
//     J_E/alpha = (pi alpha/sin(pi alpha)) [((1-kappa)/alpha)^2 + 4 kappa (sin(pi alpha/2)/alpha)^2]
// (pi^2/cos^2(beta pi/2) at alpha = 0); the kernel singularity at the evaluation point is
// subtracted on a neighbourhood (closed form f(y) eps^alpha (1-kappa)/alpha), and the log-type
// factor at x0 is the weight of a Gauss rule of its own on the panel next to x0
// (detail::gauss_log_power_rule for (t^-alpha - 1)/alpha; see detail::enrichment_piece). Above
// the threshold the plain E loses ~ eps/alpha^2 to cancellation (measured 1.3e-13 at alpha = 0.01).
// F may also have higher-order jumps at t0 (kinks); then only the step is removed and the
// convergence is algebraic, of order (2 - alpha) faster than without enrichment.
//
// Sampling grid. The remainder F~ - C A[phi] is continuous at x0 but its two terms are not: F is
// evaluated on one side and A[phi](x0) is a principal value, not the mean of its one-sided limits.
// So x0 must never be a sampling point; the odd first-kind grids (65, 195, ...) always contain
// the centre x = 0. solve_step uses m or m + 1 points (detail::grid_size_avoiding: the two grids
// interlace, so x0 is about half a spacing from every node of one of them); `degree` reports the
// size used (even sizes occur). Before this, a symmetric wedge gave 0.396 instead of 0.5 for the
// trailing share of the load (tests: "apex on a Chebyshev node").
// Adaptive levels (nested): 65 points (initial_step_sampling_size), then 3x as many: the
// first-kind grid of size 3m contains the grid of size m (node j is node 3j + 1), so each level
// reuses the remainder values already computed and evaluates A[phi] at 2m new points only;
// 65 -> 195 -> 585, and a last level of exactly max_degree points (not nested) when 3m would
// exceed it. (Before: 17 -> 33 -> 65 -> 129 ..., every level from scratch: 115 evaluations of
// A[phi] to reach 65 points, 244 to reach 129; now 65 and 195.) A level at which grid_size_avoiding
// picks m + 1 is not nested and is computed in full. The loop stops when the tail (the last m/8
// Chebyshev coefficients, relative to max|F~|) is below options.tolerance, below 4 rounding_floor,
// or below 1024 eps and no longer decaying (against the previous level or against the second
// half of the coefficients of this one: a rounding plateau).
//
// Taylor degree and rounding floor. q has radius of convergence 1 - |x0| and max|q| on [-1, 1]
// grows like ((1 + |x0|)/(1 - |x0|))^K. The smooth part of g cancels C phi far from the apex, so
// the Chebyshev tail of the remainder stalls at max|q| eps (measured 1-5 x); on the plain path
// (alpha >= 0.01) the two one-sided integrals of A[E] also cancel next to x0, ~ eps/(4 alpha)^2
// (measured tails at 65 points 0.7-1.2 x that for alpha in [0.01, 0.05]). rounding_floor is the
// larger of the two. taylor_degree = 0 (default) picks the largest K <= 12 (max_taylor_degree)
// with max|q| <= 1e4 (max_taylor_amplification), at least 1; the adaptive loop stops as converged
// once the tail is below 4 rounding_floor (before, asymmetric cases ran to max_degree and reported
// not_converged; alpha in [0.01, 0.05] went to 195 points without improving int g).
//
// Apex near an edge: Moebius map (|x0| > 1/2 = moebius_threshold, i.e. eps = (t0 - a)/L outside
// [1/4, 3/4]; automatic K only). Next to an edge q's radius 1 - |x0| shrinks and the solution
// varies on the scale d = 1 - |x0| around the apex: a global polynomial needs ~ 1/sqrt(d) points.
// The operator is covariant under the Moebius maps of [-1, 1] onto itself, x = M(sigma) =
// (sigma + s)/(1 + s sigma), |s| < 1 (derived for this module from M(sigma) - M(tau) = (1 - s^2)
// (sigma - tau)/((1 + s sigma)(1 + s tau)) and M' = (1 - s^2)/(1 + s sigma)^2; checked by the tests
// against tanh-sinh quadrature of the operator):
//     A[g](M(sigma)) = (1 - s^2)^alpha (1 + s sigma)^(1 - alpha) A[g~](sigma),
//     g~(sigma) = g(M(sigma)) (1 + s sigma)^(-1 - alpha),
// and M fixes -1 and 1, so g~ has the edge exponents of g. solve_step solves A g~ = F~ := (1 -
// s^2)^-alpha (1 + s sigma)^(alpha - 1) F(M(sigma)) with the apex at sigma0 = M^-1(x0). The map
// multiplies the ratios r = (1 - x)/(1 + x): r(M(sigma)) = r_s r(sigma), r_s = (1 - s)/(1 + s).
// Its price is F~'s factor, analytic on [-1, 1] with a branch point at -1/s, ~ 2 r_s beyond the
// end far from the apex, which limits the Chebyshev convergence there. So r(x0) is split as
// r^(1/4) (the apex's ratio after the map: eps 0.99 -> 0.76, 0.999 -> 0.85) times r^(3/4) (the
// map's; moebius_apex_exponent: 1/4 and 1/5 measured best, 1/3 up to 1.5x and 1/2 up to 3x more
// points). The local solution in sigma is (the map's image of E) ~ E~(sigma)/(1 + s sigma), so q
// matches w(sigma0)(1 + s sigma0)/(w(sigma)(1 + s sigma)) to order K (mapped_weight_taylor), and C
// comes from the jump of F at t0 (one-sided values taken in x: the map compresses distances next
// to the apex) times F~/F there. nu = -1: the physical problem is A g = F - defect with a
// CONSTANT defect, which is not constant in sigma, so the defect <F, w'>/<1, w'> (w' the image
// weight (1 - x)^(gam-1) (1 + x)^(del-1)) is removed from F before the map, by Gauss-Jacobi in x
// (solvability_defect keeps its meaning; what remains of the image-P_0 coefficient joins the tail).
// The density carries s (enriched_density::mobius); its evaluations, integrals (composite rule
// graded also toward the branch point), intensities and apply map back. A point costs as much as
// without the map.
//
// Accuracy and cost (command: build-lead/bin/study_abel_convergence out.csv, CSV rows
// step_adaptive_*, step_apex_eps_*, step_apex_rh_*; default options as the punch layer calls it;
// median wall time, residual off; one run, 2026-11-21 21:34 UTC, after the node powers joined one
// power_product, panel_integrator::for_each_node_deferred).
// Step at t0 = 0.1 on [-1, 1], beta = 0.2, relative error of int g against the exact Rodrigues
// value (int_a^t0 g against the degree-257 solution: same level):
//     alpha = 0, 1e-3 (normalized path):      65 points, <= 1.3e-15,   0.38-0.43 ms (was 0.67-1.08:
//                                               Gauss-Laguerre end rule and grading toward x0;
//                                               1.8-2.0x the plain path, was 2.7-3.3x)
//     alpha = 0.01:                             65 points, <= 1.7e-13,   0.21 ms (was 195 for nu = -1)
//     alpha = 0.049, 0.05:                      65 points, <= 9.1e-15,   0.21 ms (was 195)
//     alpha = 0.25, 0.5, 0.9:                   65 points, <= 9.8e-15,   0.21 ms
// Apex position eps = (t0 - a)/L, wedge data of the class nu = -1 satisfying the orthogonality
// condition (alpha = 0.3, beta = 0.2; rows step_apex_rh_*), max relative error of int g and
// int_a^t0 g against the independent Riemann-Hilbert route riemann::solve_abel_rh (its error
// estimates <= 1e-15 here):
//     eps      map        65 pts     195 pts    585 pts    adaptive (default options)
//     0.5      none       1.2e-15    1.2e-15    1.2e-15     66 pts, 1.2e-15, 0.21 ms
//     0.8      s = 0.48   4.4e-16    4.1e-16    2.2e-16     65 pts, 4.4e-16, 0.21 ms (was 195 pts, 7.5e-13, 0.91 ms)
//     0.9      s = 0.68   4.0e-15    7.0e-15    5.0e-15     65 pts, 4.0e-15, 0.21 ms (was 585 pts, 15 ms)
//     0.97     s = 0.86   4.4e-13    3.3e-13    1.4e-13     65 pts, 4.4e-13, 0.23 ms (was 1024 pts, 44 ms)
//     0.99     s = 0.94   1.0e-12    7.5e-13    6.3e-13    195 pts, 7.5e-13, 0.66 ms (was not_converged, 49 ms)
//     0.999    s = 0.99   1.1e-6     5.0e-13    2.6e-13    195 pts, 3.8e-13, 0.64 ms (was 2.7e-9, 95 ms)
//     0.03     s = -0.86  1.2e-14    1.5e-14    1.7e-14     65 pts, 1.2e-14, 0.23 ms (was 1024 pts, 88 ms)
//     0.001    s = -0.99  1.4e-5     4.2e-13    1.9e-13    195 pts, 4.5e-13, 0.66-1.1 ms (was 4.6e-11, 130 ms)
// (The fixed 195-point solve at eps = 0.001 took 0.66 ms in the same run; the adaptive row's 1.1 ms
// is the host's noise or the 65-point level before it.)
// (~1e-12 is the level at which the Taylor factor's floor (max|q| ~ 1e4) and the reference's own
// int_a^y meet: a variant with max|q| <= 1e2 converged to the same value at 195 points.) The punch
// layer's hardest former case (alpha = 0.2, k = 0.5, S1 = S2: eps = 0.84) now takes 65 points:
// 6.7e-16 (alpha = 0.2, 0.22 ms), 1.4e-16 (1e-3, 0.71-0.77 ms), 1.8e-15 (0, 0.39 ms); before 195.
// The same study with F = +-1 in both classes (rows step_apex_eps_*, error of int g against the
// exact Rodrigues value): eps in [0.1, 0.9] converged at 65-66 points, <= 1.8e-12; eps = 0.01,
// 0.99, 1e-3, 0.999 at 195 points, <= 5.1e-13 (was 1024 points, not_converged at 1e-3 and 0.999).
// LIMIT (apex within ~1e-4 L of an edge): the branch point of the map's factor lies ~ 2 r^(3/4)
// beyond the far end (~1e-4 at 1 - eps = 1e-6) and the Chebyshev interpolation needs ~ r^(-3/8)
// points: 1 - eps = 1e-4 converges at 585 points, 1e-6 not within max_degree (measured: error of
// int g 6e-8 .. 3e-6 at 1025 points, status not_converged). The solver reports what it did not
// reach: status not_converged and a residual sampled at the Chebyshev points of both axes and next
// to the apex (x0 -+ d/2 and d/4, 3d/4 of the way to the near edge, in sigma), measured >=
// error(int g)/42. Data vanishing on the long side of t0 do not have this limit (next section):
// the punch layer's isolated wedge is reduced to them.
//
// Data vanishing on the long side (apex_placement::centred; derived for this module, used by
// punch's isolated wedge). The limit above comes from F~'s factor (1 + s sigma)^(alpha - 1) on the
// LONG side, next to the far end. If F = 0 there, F~ is 0 on the long side and the factor
// multiplies data on the short side only, ~1 from its branch point whatever s is; the solution
// there sees no singularity of the data's continuation (the inversion integrates the data over the
// short side only), so the map may put the apex at the centre: s = x0, sigma0 = 0, Taylor degree
// 12. Piecewise constant data (the wedge) reduce to this case by subtracting the long side's
// constant, whose solution is a closed form in the class nu = 0 singular at the near edge (docs/theory.md
// section 4, n = 0); nu = -1 is excluded (its defect, a constant, would not vanish on the long
// side). Measured (alpha = 0.3, beta = 0 and 0.2; rows of tests/abel/test_step_enrichment.cpp):
// 66 points, Chebyshev tail <= 2e-15, at 1 - eps = 1e-3 .. 1e-12, 0.22 ms per solve without the
// residual; closed form plus this part against the exact int g of the wedge: <= 2.3e-16. On the
// plain path (alpha >= 0.01) its rounding floor is eps/alpha^2: the tails at 65 points measured
// 5-20 times eps/(4 alpha)^2 (the data's scale is the short side's step alone).
// The map keeps 1 - |s| exactly (mobius_rest): s = 1 - 2e-10 rounded moves the apex's image by
// ~1e-6 of its distance to the edge, and int_a^t0 g (|sigma|^-alpha at the apex) was off by
// ~1e-13/d (1e-7 at d = 1e-6; now within 2e-14 of a long double solve).
//
// Kinks (solve_kinks, kink_enrichment; derived for this module, checked by the tests). For
// F^(k) jumping by J at t0 (k = 1, 2; F and its lower derivatives continuous), the data carry the
// jump-type term (J/k!) (s - t0)_+^k. The image of (x - x0)^k E on the line, from the one-sided
// Beta integrals of t_+^mu and (-t)_+^mu at mu = k - alpha (the poles of Gamma(-mu-alpha) cancel
// at the ratio above), is an analytic part plus
//     -(R_k/k!) J_E (x - x0)_+^k,   R_k = Gamma(k + 1 - alpha)/Gamma(1 - alpha)
//                                        = (1 - alpha) ... (k - alpha)
// (k = 0 gives the step's -J_E: the jump above is left minus right), using
// psi(k + 1 - alpha) - psi(alpha - k) = pi cot(pi alpha) and the reflection formula. So
//     phi_k = w q (x - x0)^k E,   C = -(J h^k/R_k) h^-alpha / (w(x0) J_E)
// (h = L/2; the reference problem's data are h^-alpha F): F - A[C phi_k] has jump-type terms of
// order >= k + K + 1 only at t0, and its Chebyshev interpolation converges spectrally. No jump is
// measured from the data: the caller gives J (a spline's knots know theirs). Several kinks are
// several terms, each with its own q; solve_kinks solves the remainder F - sum A[C phi_k] by
// abel_solver.hpp's solve. For k >= 1 the image is continuous at x0 (C^(k-1)), so a sampling
// point may lie on a kink; one that does to rounding (x0 = 0 is a node of every odd first-kind
// grid) takes the image extrapolated from x0 + 1e-8 and x0 + 2e-8 (error O(1e-16 A'')), as the
// split quadrature cannot take y = x0 as one point. Normalized mode (alpha < 0.01) as for the
// step, with (x - x0)^k (E - 1)/alpha (w q (x - x0)^k is analytic: its image has no jump-type
// term). No Moebius map: the Taylor degree is the automatic one without it (4-6 at |x0| = 0.8).
// Rounding floor: C phi grows like q away from the kink, ~ max|q| (up to 1e4) times its value
// there, and the series cancels it: int g measured within 1.5e-12 (alpha = 0.3) .. 2e-11 (alpha =
// 0) of the exact projection for a kink at x0 = -0.8, within 3e-15 for |x0| <= 0.2.
// Accuracy and cost (alpha = 0.3, beta = 0.3, [-2, 1], one kink at x0 = 0.067, residual off; the
// tests' data; throwaway driver, best of 20, 2026-12-06): adaptive 17 -> 33 -> 65 points,
// Chebyshev tail <= 1e-16, 0.47 ms (alpha = 0: 0.86 ms), for F' or F'' jumping; the plain solver
// on the same data stops at 1024 coefficients with tail 4.6e-7 (F') or 9e-10 (F''), 1.5-1.7 ms.
// A knot at x0 = 0.8 takes 129-257 points (the lower Taylor degree). On a rough profile's
// contacts: docs/accuracy.md (study_spline_kinks).
//
// Residual: direct quadrature of the one-sided integrals at interior Chebyshev points (never at
// a sampling node nor at x0) plus the four points next to the apex; for the phi part this is the
// same quadrature that built the data, so the residual checks the smooth part; the phi part is
// checked by the tests against the jump formula and the exact int g. An estimate.
#pragma once

#include "rhabel/abel/abel_solver.hpp"

#include <boost/math/constants/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

namespace rhabel::abel {

template <class Real>
struct enriched_density;
template <class Real>
class enriched_evaluator;

/// g = C phi + w sum c_n P_n on [lo, hi] (see header); evaluations exact up to quadrature rounding.
/// With a Moebius map (mobius != 0: the apex near an edge) smooth, x0 and q describe
/// g~(sigma) = g(M(sigma)) (1 + s sigma)^(-1-alpha) in the variable sigma of x = M(sigma); every
/// evaluation below maps back (the header's "Apex near an edge").
template <class Real>
struct enriched_density {
  jacobi_density<Real> smooth;   ///< w sum_n c_n P_n^(del,gam) (in sigma when mapped)
  Real enrichment = 0;           ///< C
  Real x0 = 0;                   ///< breakpoint in the reference variable (sigma when mapped)
  Real kappa = 0, alpha = 0;
  /// k of phi = w q (x - x0)^k E (header, "Kinks"): 0 for a step, 1 or 2 for a jump of F' or F''.
  /// k > 0 only without a Moebius map (mobius == 0).
  unsigned order = 0;
  /// Taylor coefficients of the factor q in powers of (x - x0): w(x0)/w(x), times (1 + s x0)/(1 + s x)
  /// when mapped. Evaluate q with q_at.
  std::vector<Real> q;
  /// alpha < 0.01: E is replaced by (E - 1)/alpha (uniform to alpha = 0, where it is
  /// -log|x - x0| - pi tan(beta pi/2) [x > x0]); the "-1/alpha" part is w q, a smooth density.
  bool normalized = false;
  Real one_minus_kappa_over_alpha = 0;
  /// s of the Moebius map x = M(sigma) = (sigma + s)/(1 + s sigma), |s| < 1; 0: no map. Set it
  /// with set_mobius: every formula takes 1 - s and 1 + s from mobius_rest.
  Real mobius = 0;
  /// 1 - |s|, exact: the apex 1e-10 from an edge has s = 1 - 2e-10, whose rounding would move the
  /// apex's image M(0) by ~1e-6 of its distance to the edge (next to the apex the one-sided
  /// integrals carry |sigma - x0|^-alpha: int_a^t0 g was off by ~1e-13/d relative).
  Real mobius_rest = 1;

  /// The map with s = sign * (1 - rest), from the exact complement rest in (0, 1].
  void set_mobius(const Real& rest, bool negative) {
    mobius_rest = rest;
    mobius = negative ? rest - 1 : 1 - rest;
  }
  Real one_minus_s() const { return mobius >= 0 ? mobius_rest : 2 - mobius_rest; }
  Real one_plus_s() const { return mobius >= 0 ? 2 - mobius_rest : mobius_rest; }

  Real half_length() const { return smooth.half_length(); }

  /// The enrichment factor at distance `dist` = |x - x0| on the right (x > x0) or left side.
  Real E_full(const Real& dist, bool right) const {
    using std::log;
    using std::pow;
    if (!normalized) return right ? kappa * pow(dist, -alpha) : pow(dist, -alpha);
    // (|u|^-alpha - 1)/alpha = -L exprel(-alpha L), L = log|u|; right: + (kappa - 1)/alpha |u|^-alpha.
    // dist^-alpha = 1 + alpha core (no second transcendental call).
    const Real L = log(dist);
    const Real core = -L * detail::exprel(-alpha * L);
    return right ? core - one_minus_kappa_over_alpha * (1 + alpha * core) : core;
  }
  /// (x - x0)^order E at distance `dist` = |x - x0| on the right or left side: E_full for a step.
  Real E_order(const Real& dist, bool right) const {
    if (order == 0) return E_full(dist, right);
    if (dist == 0) return Real(0);  // the limit: |x - x0|^(order - alpha), or times a log
    return E_full(dist, right) * order_power(dist, right);
  }
  /// The sign of (x - x0)^order on the right or left side of x0.
  Real order_sign(bool right) const { return right || order % 2 == 0 ? Real(1) : Real(-1); }
  /// (x - x0)^order at distance dist on the right or left side.
  Real order_power(const Real& dist, bool right) const {
    Real p = 1;
    for (unsigned k = 0; k < order; ++k) p *= dist;
    return order_sign(right) * p;
  }
  /// Gauss-Jacobi exponent used at x0 for pieces that end there (the rest is E_over_weight):
  /// order - alpha, or order in normalized mode (its log-type factor is E_over_weight's).
  Real x0_exponent() const { return normalized ? Real(order) : Real(order) - alpha; }
  Real E_over_weight(const Real& dist, bool right) const {
    if (!normalized) return right ? kappa : order_sign(false);
    return order_sign(right) * E_full(dist, right);
  }

  /// phi(x) with distances 1 + x, 1 - x (reference variable; sigma when mapped).
  Real phi(const Real& one_plus_x, const Real& one_minus_x) const {
    using std::pow;
    const Real u = one_plus_x <= one_minus_x ? one_plus_x - (1 + x0) : (1 - x0) - one_minus_x;
    const Real E = u > 0 ? E_order(u, true) : E_order(-u, false);
    return detail::power_product<Real>().times(one_minus_x, smooth.del).times(one_plus_x, smooth.gam).value() *
           q_at(one_plus_x, one_minus_x) * E;
  }

  /// The map at a point given by its distances to the ends. sigma_of: from (1 + x, 1 - x) to
  /// {1 + sigma, 1 - sigma, 1 + s sigma}; x_of: from (1 + sigma, 1 - sigma) to {1 + x, 1 - x,
  /// 1 + s sigma}. Both exact to a few ulps up to the ends: 1 + x = (1 + s)(1 + sigma)/(1 + s sigma),
  /// 1 - x = (1 - s)(1 - sigma)/(1 + s sigma), 1 + s sigma = (1 - s^2)/(1 - s x), and the
  /// denominators are sums of two non-negative terms ((1 - |s|) + |s| times a distance).
  std::array<Real, 3> sigma_of(const Real& one_plus_x, const Real& one_minus_x) const {
    using std::abs;
    const Real s = mobius, rest = mobius_rest;
    const Real one_minus_sx = s >= 0 ? rest + s * one_minus_x : rest - s * one_plus_x;
    return {one_minus_s() * one_plus_x / one_minus_sx, one_plus_s() * one_minus_x / one_minus_sx,
            one_minus_s() * one_plus_s() / one_minus_sx};
  }
  std::array<Real, 3> x_of(const Real& one_plus_sigma, const Real& one_minus_sigma) const {
    using std::abs;
    const Real s = mobius, rest = mobius_rest;
    const Real one_plus_s_sigma = s >= 0 ? rest + s * one_plus_sigma : rest - s * one_minus_sigma;
    return {one_plus_s() * one_plus_sigma / one_plus_s_sigma, one_minus_s() * one_minus_sigma / one_plus_s_sigma, one_plus_s_sigma};
  }
  /// Distance beyond the end -1 (first) and +1 (second) of the sigma axis of the pole -1/s of the
  /// map's factors (1 + s sigma)^c; infinite without a map or on the other side.
  std::array<Real, 2> pole_distances() const {
    using std::abs;
    const Real inf = std::numeric_limits<Real>::infinity();
    if (mobius == 0) return {inf, inf};
    const Real d = mobius_rest / abs(mobius);
    return mobius > 0 ? std::array<Real, 2>{d, inf} : std::array<Real, 2>{inf, d};
  }

  /// Distance on the sigma axis beyond -1 (below) or +1 (above) of the point at distance d beyond
  /// x = -1 or +1; infinite if the map sends it past the pole (it then lies beyond the other end,
  /// farther than the pole). Without a map: d.
  Real beyond_in_sigma(const Real& d, bool below) const {
    using std::abs;
    const Real s = mobius, rest = mobius_rest;
    // 1 - s x at x = -1 - d or 1 + d, as (1 - |s|) plus or minus |s| times a distance.
    const Real one_minus_sx = below ? (s >= 0 ? rest + s * (2 + d) : rest + s * d) : (s >= 0 ? rest - s * d : rest - s * (2 + d));
    if (!(one_minus_sx > 0)) return std::numeric_limits<Real>::infinity();
    return (below ? one_minus_s() : one_plus_s()) * d / one_minus_sx;
  }

  /// g at the point with reference distances 1 + x, 1 - x to the ends (x != x0). For many points
  /// use evaluator() (the series' recurrence coefficients computed once).
  Real value_at_distance(const Real& one_plus_x, const Real& one_minus_x) const;
  /// g at the point with reference distances 1 + x, 1 - x to the ends and offset dx = x - x_apex
  /// from the apex (x_apex = apex_reference()), whichever are exact: next to the apex |dx|^-alpha
  /// needs dx itself, not a difference of rounded abscissae. Mapped: sigma - sigma0 =
  /// (1 - s^2) dx/((1 - s x)(1 - s x_apex)).
  Real value_with_offset(const Real& one_plus_x, const Real& one_minus_x, const Real& dx) const;
  /// The two above for many points (see enriched_evaluator).
  enriched_evaluator<Real> evaluator() const { return enriched_evaluator<Real>(*this); }
  /// g(t), lo < t < hi, t != t0.
  Real operator()(const Real& t) const {
    if (!(t > smooth.lo) || !(t < smooth.hi)) return Real(0);
    const Real h = half_length();
    return value_at_distance((t - smooth.lo) / h, (smooth.hi - t) / h);
  }
  /// (1 - s^2)^alpha (1 + s sigma)^(1 - alpha), the covariance factor of the map (header):
  /// A[g](M(sigma)) = this times A[g~](sigma); 1 without a map.
  Real covariance_factor(const Real& one_plus_s_sigma) const {
    using std::pow;
    return pow(one_minus_s() * one_plus_s(), alpha) * pow(one_plus_s_sigma, 1 - alpha);
  }
  /// The apex on the x axis: x_of(1 + x0, 1 - x0) = {1 + x_apex, 1 - x_apex, 1 + s sigma0} (the
  /// last is 1 without a map).
  std::array<Real, 3> apex_in_x() const { return x_of(1 + x0, 1 - x0); }
  /// Reference abscissa of the apex (x0 mapped back when mobius != 0).
  Real apex_reference() const {
    if (mobius == 0) return x0;
    const auto d = apex_in_x();
    return d[0] <= d[1] ? d[0] - 1 : 1 - d[1];
  }

  /// int_lo^hi f(t) g(t) dt for f smooth between the breakpoints (t0 is always a cut).
  /// Composite Gauss-Jacobi: for the series part per piece with the edge exponents as weights (as
  /// jacobi_density::integrate), for phi with the exponents -alpha at t0, gam, del at the ends,
  /// graded toward every singular point and, when mapped, toward the pole of the map's factor.
  /// `beyond_lo`, `beyond_hi`: distances (in units of the half-length) of further singular points
  /// of f below lo and above hi (grading; infinite: none).
  template <class Fn>
  Real integrate(Fn&& f, std::vector<Real> breakpoints = {}, const Real& beyond_lo = std::numeric_limits<Real>::infinity(),
                 const Real& beyond_hi = std::numeric_limits<Real>::infinity()) const {
    return integrate_between(f, smooth.lo, smooth.hi, std::move(breakpoints), beyond_lo, beyond_hi);
  }
  /// int_from^to f g for lo <= from < to <= hi: the pieces of integrate's composite rule between
  /// from and to (cut there, never masked: nodes next to the apex, where |t - t0|^-alpha carries
  /// weight down to rounding distances, keep their side).
  template <class Fn>
  Real integrate_between(Fn&& f, const Real& from, const Real& to, std::vector<Real> breakpoints = {},
                         const Real& beyond_lo = std::numeric_limits<Real>::infinity(),
                         const Real& beyond_hi = std::numeric_limits<Real>::infinity()) const;

  /// int_lo^hi g: c_0 h_0 (L/2) plus int C phi; mapped: integrate(1).
  Real integral() const {
    if (mobius != 0) return integrate([](const Real&) { return Real(1); });
    return smooth.integral() + enrichment * half_length() * phi_integral_to(Real(1));
  }
  /// int_{-1}^{X} phi dx (reference variable), X in [-1, 1]. Mapped: the integral in sigma, without
  /// the map's jacobian (integral() and integral_to() then use integrate).
  Real phi_integral_to(const Real& X) const;

  /// Leading-edge intensity lim g (t-a)^(-gam): smooth part plus C 2^del q(-1) E(-1), times (2/L)^gam;
  /// mapped: that of g~ times ((1 - s)/(1 + s))^gam (1 - s)^(1 + alpha).
  Real intensity_leading() const {
    using std::pow;
    const Real mapped = smooth.intensity_leading() + enrichment * pow(2 / (smooth.hi - smooth.lo), smooth.gam) *
                                                         pow(Real(2), smooth.del) * q_at(Real(-1)) * E_order(1 + x0, false);
    const Real s = mobius;
    return s == 0 ? mapped : mapped * pow(one_minus_s() / one_plus_s(), smooth.gam) * pow(one_minus_s(), 1 + alpha);
  }
  /// Trailing-edge intensity lim g (b-t)^(-del): smooth part plus C 2^gam q(1) E(+1), times (2/L)^del;
  /// mapped: that of g~ times ((1 + s)/(1 - s))^del (1 + s)^(1 + alpha).
  Real intensity_trailing() const {
    using std::pow;
    const Real mapped = smooth.intensity_trailing() + enrichment * pow(2 / (smooth.hi - smooth.lo), smooth.del) *
                                                          pow(Real(2), smooth.gam) * q_at(Real(1)) * E_order(1 - x0, true);
    const Real s = mobius;
    return s == 0 ? mapped : mapped * pow(one_plus_s() / one_minus_s(), smooth.del) * pow(one_plus_s(), 1 + alpha);
  }

  /// q(x) (the Taylor polynomial) at x.
  Real q_at(const Real& x) const { return q_at(1 + x, 1 - x); }
  /// q at the point with distances 1 + x, 1 - x to the ends.
  Real q_at(const Real& one_plus_x, const Real& one_minus_x) const {
    const Real u = one_plus_x <= one_minus_x ? one_plus_x - (1 + x0) : (1 - x0) - one_minus_x;
    Real qq = 0;
    for (std::size_t k = q.size(); k-- > 0;) qq = qq * u + q[k];
    return qq;
  }
  /// Gauss nodes per panel of the quadratures of phi (split_integrator callers use 4 fewer):
  /// K/2 + 16; K/2 + 10 in normalized mode (alpha < 0.01: measured <= 1e-15 in int g, 20% faster).
  std::size_t quadrature_nodes() const { return q.size() / 2 + (normalized ? 10 : 16); }

  /// int_t^hi g (integrate_between: relative accuracy kept for t near hi).
  Real integral_from(const Real& t) const {
    if (!(t < smooth.hi)) return Real(0);
    return integrate_between([](const Real&) { return Real(1); }, std::max(t, smooth.lo), smooth.hi);
  }
  /// int_lo^t g: the Rodrigues form of the series plus int C phi; mapped: the pieces below t of
  /// integrate's composite rule. Both integrate from lo (relative accuracy kept for t near lo).
  Real integral_to(const Real& t) const {
    if (!(t > smooth.lo)) return Real(0);
    if (!(t < smooth.hi)) return integral();
    if (mobius != 0) return integrate_between([](const Real&) { return Real(1); }, smooth.lo, t);
    const Real h = half_length();
    return smooth.integral_to(t) + enrichment * h * phi_integral_to(-1 + (t - smooth.lo) / h);
  }
};

/// g of an enriched density at many points: the series' recurrence coefficients computed once
/// (quadrature::jacobi_series: the same sums as jacobi_clenshaw to a few ulps) and the weight
/// w = (1 - x)^del (1 + x)^gam computed once for the series and phi. Holds a reference to the
/// density (which must outlive it).
template <class Real>
class enriched_evaluator {
 public:
  explicit enriched_evaluator(const enriched_density<Real>& d)
      : d_(d), series_(d.smooth.series_evaluator()),
        one_plus_s_sigma0_(d.apex_in_x()[2]) {}
  /// g at the point with reference distances 1 + x, 1 - x (x != x_apex).
  Real operator()(const Real& one_plus_x, const Real& one_minus_x) const {
    return value(d_, series_, one_plus_s_sigma0_, one_plus_x, one_minus_x, nullptr);
  }
  /// The same with the exact offset dx = x - x_apex (see enriched_density::value_with_offset).
  Real with_offset(const Real& one_plus_x, const Real& one_minus_x, const Real& dx) const {
    return value(d_, series_, one_plus_s_sigma0_, one_plus_x, one_minus_x, &dx);
  }
  /// operator() at the n points (one_plus_x[i], one_minus_x[i]) into out[i], bit for bit, with the
  /// series summed by jacobi_series::evaluate (several points' recurrences interleaved: ~3x fewer
  /// ns per point for the series at degree ~80, which dominates a point's cost there).
  void values(const Real* one_plus_x, const Real* one_minus_x, Real* out, std::size_t n) const {
    std::vector<point> points;
    points.reserve(n);
    std::vector<Real> xs(n), sums(n);
    for (std::size_t i = 0; i < n; ++i) {
      points.push_back(locate(d_, one_plus_s_sigma0_, one_plus_x[i], one_minus_x[i], nullptr));
      xs[i] = points.back().x;
    }
    series_.evaluate(xs.data(), sums.data(), n);
    for (std::size_t i = 0; i < n; ++i) out[i] = finish(d_, points[i], sums[i]);
  }

  /// The evaluation for any series evaluator S(x) (single points: jacobi_clenshaw, no set-up).
  template <class Series>
  static Real value(const enriched_density<Real>& d, const Series& series, const Real& one_plus_s_sigma0,
                    const Real& one_plus_x, const Real& one_minus_x, const Real* dx) {
    const point pt = locate(d, one_plus_s_sigma0, one_plus_x, one_minus_x, dx);
    return finish(d, pt, series(pt.x));
  }

 private:
  // A point in the series' variable (sigma when mapped): its distances to the ends, its offset u
  // from the apex, x itself, and the map's factor (1 + s sigma)^(1 + alpha) of the weight.
  struct point {
    Real one_plus, one_minus, u, x;
    detail::power_product<Real> weight;
  };

  static point locate(const enriched_density<Real>& d, const Real& one_plus_s_sigma0, const Real& one_plus_x,
                      const Real& one_minus_x, const Real* dx) {
    const Real s = d.mobius;
    point pt{one_plus_x, one_minus_x, dx != nullptr ? *dx : Real(0), Real(0), {}};
    // w (1 + s sigma)^(1 + alpha) as one power_product (the map's factor only when mapped).
    if (s != 0) {
      const auto m = d.sigma_of(one_plus_x, one_minus_x);
      pt.one_plus = m[0], pt.one_minus = m[1];
      pt.weight.times(m[2], 1 + d.alpha);
      // 1 - s x = (1 - s^2)/(1 + s sigma), the same at the apex.
      if (dx != nullptr) pt.u = *dx * m[2] * one_plus_s_sigma0 / (d.one_minus_s() * d.one_plus_s());
    }
    if (dx == nullptr) pt.u = pt.one_plus <= pt.one_minus ? pt.one_plus - (1 + d.x0) : (1 - d.x0) - pt.one_minus;
    pt.x = pt.one_plus <= pt.one_minus ? pt.one_plus - 1 : 1 - pt.one_minus;
    return pt;
  }

  static Real finish(const enriched_density<Real>& d, point pt, const Real& series_value) {
    using std::isinf;
    Real inner = series_value;
    if (d.enrichment != 0)
      inner += d.enrichment * d.q_at(pt.one_plus, pt.one_minus) * (pt.u > 0 ? d.E_order(pt.u, true) : d.E_order(-pt.u, false));
    const Real w = pt.weight.times(pt.one_minus, d.smooth.del).times(pt.one_plus, d.smooth.gam).value();
    // Exactly at an end with a negative exponent: the limit (never 0 * inf = NaN).
    if (isinf(w) && inner == 0) return Real(0);
    return w * inner;
  }

  const enriched_density<Real>& d_;
  rhabel::quadrature::jacobi_series<Real> series_;
  Real one_plus_s_sigma0_;
};

template <class Real>
Real enriched_density<Real>::value_at_distance(const Real& one_plus_x, const Real& one_minus_x) const {
  return enriched_evaluator<Real>::value(*this, [this](const Real& x) { return smooth.series(x); }, apex_in_x()[2],
                                         one_plus_x, one_minus_x, nullptr);
}
template <class Real>
Real enriched_density<Real>::value_with_offset(const Real& one_plus_x, const Real& one_minus_x, const Real& dx) const {
  return enriched_evaluator<Real>::value(*this, [this](const Real& x) { return smooth.series(x); }, apex_in_x()[2],
                                         one_plus_x, one_minus_x, &dx);
}

template <class Real>
struct enriched_solution {
  enriched_density<Real> density;
  edge_exponents<Real> exponents{};
  Real solvability_defect = 0;  ///< nu = -1: image-P_0 coefficient of the remainder data
  Real residual = std::numeric_limits<Real>::quiet_NaN();
  Real coefficient_tail = 0;
  std::size_t degree = 0;
  solve_status status = solve_status::converged;
  /// K, the order of the local expansion built into phi (Taylor factor; mapped or not: see
  /// density.mobius).
  std::size_t taylor_degree = 0;
  /// Estimated relative rounding floor of the Chebyshev tail, max|q| eps over [-1, 1]: the adaptive
  /// loop stops (converged) once the tail is below 4x this even if options.tolerance is smaller.
  /// An estimate, not a bound.
  Real rounding_floor = 0;
};

/// solve_step uses the normalized enrichment (E - 1)/alpha below this alpha. Above it the plain
/// enrichment E loses ~ eps/alpha^2 to cancellation (C = O(1/alpha), A[E] = O(1/alpha)): measured
/// agreement of the two paths 1.3e-13 at alpha = 0.01, 5e-15 at 0.03 (int g, int_a^t0 g), at
/// ~1-2 ms instead of 3-8 ms.
template <class Real>
Real normalized_enrichment_threshold() {
  return Real(1) / 100;
}

/// Automatic choice of the Taylor degree K in solve_step: largest K <= 12 whose Taylor factor q
/// stays below this on [-1, 1].
template <class Real>
Real max_taylor_amplification() {
  return Real(10000);
}

/// First sampling grid of solve_step's adaptive loop (first-kind Chebyshev points; the next
/// levels have 3x as many and contain it).
inline std::size_t initial_step_sampling_size() { return 65; }

/// Largest automatic Taylor degree (solve_step).
inline std::size_t max_taylor_degree() { return 12; }

/// solve_step moves an apex with |x0| above this (eps = (t0 - a)/L outside [1/4, 3/4]) toward the
/// centre by a Moebius map (header, "Apex near an edge").
template <class Real>
Real moebius_threshold() {
  return Real(1) / 2;
}

/// The Moebius map of an apex near an edge splits r = (1 - x0)/(1 + x0) as r^(1/4) (the apex's
/// ratio after the map) times r^(3/4) (the map's: its pole lies ~ r^(3/4) beyond the far end). Measured
/// (alpha = 0.3, beta = 0.2, exponents 0.2 .. 0.5 at eps = 0.8 .. 0.9999): 1/4 and 1/5 need the fewest points, 1/3
/// up to 1.5 times more, 1/2 (a symmetric split) up to 3 times more (the header's table).
template <class Real>
Real moebius_apex_exponent() {
  return Real(1) / 4;
}

/// Where solve_step's Moebius map puts the apex (header, "Apex near an edge" and "Data vanishing on
/// the long side").
enum class apex_placement {
  /// Any F. With |x0| > moebius_threshold the apex's ratio r becomes r^(1/4); otherwise no map.
  balanced,
  /// F = 0 on the long side of t0 (the side of the farther edge; checked at every sampling point,
  /// std::domain_error naming f otherwise) and nu = 0 or +1 (nu = -1 removes a constant defect, which
  /// does not vanish there). The map puts the apex at sigma = 0 (s = x0; none when x0 = 0).
  centred
};

/// Composite quadrature of int_{-1}^{1} over pieces split at sorted points (the apex x0 of an
/// enriched density and the points next to it), each piece with its end exponents as Gauss-Jacobi
/// weight and graded geometrically toward the neighbouring cuts (panel_integrator, numerics.hpp,
/// `nodes` nodes per panel; the rules are cached per exponent pair, so one integrator serves many
/// integrals). For integrands analytic on each piece up to singularities at the cuts it converges
/// like panel_integrator's panels, (3 + sqrt 8)^(-2 nodes): the step enrichment takes
/// enriched_density::quadrature_nodes() - 4 nodes, which reaches double rounding (the measured
/// errors of int g in this header's accuracy table include it). Real: as abel_operator.
template <class Real>
class split_integrator {
 public:
  explicit split_integrator(std::size_t nodes) : nodes_(nodes) {}
  std::size_t nodes() const { return nodes_; }

  /// int_{-1}^{1} over the pieces [cuts[k], cuts[k+1]] (cuts[0] = -1, cuts.back() = 1), piece k
  /// with the Gauss-Jacobi weight (x - cuts[k])^left_exponent[k] (cuts[k+1] - x)^right_exponent[k]
  /// on its end panels and graded toward the neighbouring cuts. f(k, u, v, q_here, p_here) gets the
  /// node's distances u, v from the piece's ends and must return the integrand WITHOUT the piece's
  /// end factors, times u^q_here v^p_here: the end powers of panels inside the piece, which
  /// panel_integrator::for_each_node_deferred leaves to the integrand so that it can form all its
  /// powers in one power_product (q_here = 0, p_here = 0 on the end panels, where they are weights).
  template <class F>
  Real integrate_deferred(const std::vector<Real>& cuts, const std::vector<Real>& left_exponent,
                          const std::vector<Real>& right_exponent, F&& f) const {
    const Real inf = std::numeric_limits<Real>::infinity();
    Real sum = 0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const Real len = cuts[k + 1] - cuts[k];
      if (!(len > 0)) continue;
      const auto& rule = integrator(right_exponent[k], left_exponent[k]);
      const Real d_left = k == 0 ? inf : cuts[k] - cuts[k - 1];
      const Real d_right = k + 2 == cuts.size() ? inf : cuts[k + 2] - cuts[k + 1];
      Real piece = 0;
      rule.for_each_node_deferred(len, d_left, d_right, [&](const Real& u, const Real& v, const Real& weight,
                                                            const Real& q_here, const Real& p_here) {
        piece += weight * f(k, u, v, q_here, p_here);
      });
      sum += piece;
    }
    return sum;
  }

 private:
  const panel_integrator<Real>& integrator(const Real& p, const Real& q) const {
    const auto key = std::make_pair(static_cast<double>(p), static_cast<double>(q));
    auto it = cache_.find(key);
    if (it == cache_.end()) it = cache_.emplace(key, std::make_shared<panel_integrator<Real>>(p, q, nodes_)).first;
    return *it->second;
  }
  std::size_t nodes_;
  mutable std::map<std::pair<double, double>, std::shared_ptr<panel_integrator<Real>>> cache_;
};

namespace detail {

/// Number of first-kind Chebyshev points, m or m + 1, such that no node lies within `margin` of
/// the breakpoint x0. Why: the remainder F~ - C A[phi] is continuous at x0, but its two terms are
/// not; at a node y == x0 (always the case for x0 = 0 and odd m) F is evaluated on one side only
/// and A[phi](x0) is a principal-value integral, not the average of the one-sided limits, so the
/// interpolated remainder is wrong by O(jump) there (regression "apex on a Chebyshev node").
/// The nodes of the m + 1 grid interlace with those of the m grid, so if x0 is within `margin` of
/// a node of one grid it is about half a node spacing away from every node of the other. Both
/// grids are exact interpolation grids; only the size changes (odd or even).
template <class Real>
std::size_t grid_size_avoiding(std::size_t m, const Real& x0, const Real& margin) {
  using std::abs;
  auto nearest = [&](std::size_t size) {
    const chebyshev_grid<Real> grid(size);
    Real best = std::numeric_limits<Real>::infinity();
    for (const Real& x : grid.x) best = std::min(best, Real(abs(x - x0)));
    return best;
  };
  return nearest(m) >= margin ? m : m + 1;
}

/// Taylor coefficients (degree K) of w(x0)/w(x), w = (1-x)^del (1+x)^gam, in powers of u = x - x0:
/// (1 - u/(1-x0))^(-del) (1 + u/(1+x0))^(-gam).
template <class Real>
std::vector<Real> inverse_weight_taylor(const Real& gam, const Real& del, const Real& x0, std::size_t K) {
  std::vector<Real> a(K + 1), b(K + 1), c(K + 1, Real(0));
  a[0] = b[0] = 1;
  for (std::size_t k = 1; k <= K; ++k) {
    const Real kk = Real(k);
    a[k] = a[k - 1] * (del + kk - 1) / kk / (1 - x0);     // (del)_k/k! (1-x0)^-k
    b[k] = b[k - 1] * -(gam + kk - 1) / kk / (1 + x0);    // (-1)^k (gam)_k/k! (1+x0)^-k
  }
  for (std::size_t i = 0; i <= K; ++i)
    for (std::size_t j = 0; i + j <= K; ++j) c[i + j] += a[i] * b[j];
  return c;
}

/// Taylor coefficients (degree K) of the factor q of a mapped enrichment: w(x0)/w(x) times
/// (1 + s x0)/(1 + s x) = 1/(1 + c u), c = s/(1 + s x0) (the local solution of the mapped problem,
/// header "Apex near an edge"); s = 0: inverse_weight_taylor.
template <class Real>
std::vector<Real> mapped_weight_taylor(const Real& gam, const Real& del, const Real& x0, std::size_t K, const Real& s) {
  const std::vector<Real> w = inverse_weight_taylor(gam, del, x0, K);
  if (s == 0) return w;
  std::vector<Real> out(K + 1, Real(0));
  const Real c = -s / (1 + s * x0);
  Real ck = 1;
  for (std::size_t k = 0; k <= K; ++k, ck *= c)
    for (std::size_t i = 0; i + k <= K; ++i) out[i + k] += w[i] * ck;
  return out;
}

/// max |q(x)| over [-1, 1] (q from inverse_weight_taylor, in powers of x - x0), on the ends and
/// 64 first-kind Chebyshev points: the factor by which C phi exceeds its value at the apex far
/// from it. The smooth part of g cancels it there, so rounding errors of relative size eps in
/// A[phi] and in phi become errors of size ~ max|q| eps in g (the measured floor of the
/// Chebyshev tail is 1-5 x max|q| eps).
/// Only the first `degree` + 1 coefficients of q are used (all when degree >= q.size()): the
/// Taylor polynomial of degree K is a prefix of that of any higher degree.
template <class Real>
Real taylor_amplification(const std::vector<Real>& q, const Real& x0, std::size_t degree = std::size_t(-1)) {
  using std::abs;
  static const chebyshev_grid<Real> grid(64);  // the same points for every call
  const std::size_t terms = std::min(q.size(), degree == std::size_t(-1) ? q.size() : degree + 1);
  auto at = [&](const Real& x) {
    Real v = 0;
    for (std::size_t k = terms; k-- > 0;) v = v * (x - x0) + q[k];
    return abs(v);
  };
  Real biggest = std::max(at(Real(-1)), at(Real(1)));
  for (const Real& x : grid.x) biggest = std::max(biggest, at(x));
  return biggest;
}

/// A~[phi](y) (reference interval, without (L/2)^alpha) by split composite quadrature.
template <class Real>
Real enrichment_image(const enriched_density<Real>& d, const abel_parameters<Real>& par, const split_integrator<Real>& si,
                      const Real& y) {
  const Real alpha = par.alpha(), kappa = par.kappa();
  const Real x0 = d.x0;
  std::vector<Real> cuts{Real(-1)}, left_exp, right_exp;
  // Kinds of interior points: 0 = x0 (exponent order - alpha), 1 = y (exponent alpha - 1).
  std::vector<int> kind;
  if (y < x0) {
    cuts.push_back(y), kind.push_back(1);
    cuts.push_back(x0), kind.push_back(0);
  } else {
    cuts.push_back(x0), kind.push_back(0);
    cuts.push_back(y), kind.push_back(1);
  }
  cuts.push_back(Real(1));
  const Real at_x0 = Real(d.order) - alpha;
  auto exponent_of = [&](int k) { return k == 0 ? at_x0 : alpha - 1; };
  left_exp = {d.smooth.gam, exponent_of(kind[0]), exponent_of(kind[1])};
  right_exp = {exponent_of(kind[0]), exponent_of(kind[1]), d.smooth.del};
  return si.integrate_deferred(cuts, left_exp, right_exp, [&](std::size_t k, const Real& u, const Real& v,
                                                               const Real& q_here, const Real& p_here) {
    // Node at distance u from cuts[k], v from cuts[k+1]; u^q_here v^p_here: the piece's end
    // exponents on panels inside the piece (their Gauss-Jacobi weight only on the end panels).
    // Distances to every singular point, accurate near the piece ends.
    auto distance_to = [&](std::size_t point) -> Real {  // point index into cuts
      if (point == k) return u;
      if (point == k + 1) return v;
      if (point < k) return (cuts[k] - cuts[point]) + u;
      return (cuts[point] - cuts[k + 1]) + v;
    };
    // Coefficients times the powers of the distances to the singular points this node's piece
    // does not end at (those are the Gauss-Jacobi weight), as one power_product.
    Real coefficient = 1;
    power_product<Real> powers;
    powers.times(u, q_here).times(v, p_here);
    const Real one_plus_x = distance_to(0), one_minus_x = distance_to(3);
    if (k != 0) powers.times(one_plus_x, d.smooth.gam);
    if (k != 2) powers.times(one_minus_x, d.smooth.del);
    for (std::size_t point = 1; point <= 2; ++point) {
      const bool is_end = point == k || point == k + 1;
      const bool right_of_point = k >= point;  // node lies right of this point
      if (kind[point - 1] == 0) {
        coefficient *= right_of_point ? kappa : d.order_sign(false);
        if (!is_end) powers.times(distance_to(point), at_x0);
      } else {
        coefficient *= right_of_point ? Real(1) : -kappa;  // kernel: (x-y)^(alpha-1) for x > y
        if (!is_end) powers.times(distance_to(point), alpha - 1);
      }
    }
    return coefficient * powers.value() * d.q_at(one_plus_x, one_minus_x);
  });
}

}  // namespace detail

namespace detail {

/// int_a^b w(x) q(x) E(x) k(x) dx over a piece [a, b] lying on one side of x0, for the
/// enrichment of `d`. a_end / b_end say whether a, b are the ends -1, +1 or x0 (then the end
/// exponent is the Gauss-Jacobi weight); d_left, d_right are the distances of the nearest other
/// singular points beyond a and b (grading). k(x, dist_from_a, dist_from_b) is an extra factor,
/// smooth on the piece.
/// Normalized mode (alpha < 0.01) with x0 as an end: the factor (|u|^-alpha - 1)/alpha is
/// log-type at x0 and not a Gauss-Jacobi weight. The panel [0, D] next to x0 (D = half the distance
/// to every other singular point) carries it as the weight of gauss_log_power_rule (with u = D t,
/// E(D t) = kappa_side D^-alpha W(t) + E(D): that rule for the first term, Gauss-Legendre for the
/// constant; both exact for polynomials of degree < 2n, and the rest of the integrand is analytic
/// 3 panel half-widths from the panel's centre, as on panel_integrator's panels); the rest is
/// graded toward x0 from distance D. Before: 32-point Gauss-Laguerre after u = delta e^-t on
/// [0, distance/16] plus ~4 graded panels (and before that, geometric grading down to 1e-18, ~60
/// panels per piece); the log-power rule halved the nodes of the two pieces at x0, and a 65-point
/// solve went from 0.67-1.08 to 0.40-0.52 ms (header).
enum class piece_end { interval_end, x0, interior };

/// An extra factor of the form coefficient (offset + distance)^exponent, distance = the node's
/// distance from the piece end a (from_a) or b: the kernel of the small-alpha image. The piece
/// quadratures fold its power into the node's power_product (one exp per node fewer than a
/// separate power; the normalized image's inner loop is a handful of log/exp per node).
template <class Real>
struct distance_power {
  Real coefficient, offset, exponent;
  bool from_a;
};

/// A K that records the rule instead of a factor: a factor 1 at every node, it keeps the node's
/// distances to the reference ends (from those to the original piece's ends a, b) and, through
/// take(), the node's term of the sum (weight times integrand). enrichment_nodes' collector.
template <class Real>
struct node_recorder {
  Real a, b;  // the original piece, reference axis
  std::vector<Real>* one_plus_x;
  std::vector<Real>* one_minus_x;
  std::vector<Real>* term;
  Real operator()(const Real&, const Real& u, const Real& v) {
    one_plus_x->push_back((a + 1) + u);
    one_minus_x->push_back((1 - b) + v);
    return Real(1);
  }
  void take(const Real& contribution) { term->push_back(contribution); }
};
template <class K>
struct records_nodes : std::false_type {};
template <class Real>
struct records_nodes<node_recorder<Real>> : std::true_type {};

/// The factor k at a node (x, distance u from a, v from b): a distance_power joins `powers` and
/// returns its coefficient; any other callable is called.
template <class Real, class K>
Real extra_factor(K& k, power_product<Real>& powers, const Real& x, const Real& u, const Real& v) {
  if constexpr (std::is_same_v<std::remove_cv_t<K>, distance_power<Real>>) {
    powers.times(k.offset + (k.from_a ? u : v), k.exponent);
    return k.coefficient;
  } else {
    return k(x, u, v);
  }
}

/// Composite Gauss-Jacobi part of enrichment_piece (no log-type end). k is called with the
/// distances from the ends of the ORIGINAL piece: (u + offset_a, v + offset_b).
template <class Real, class K>
Real enrichment_piece_panels(const enriched_density<Real>& d, const Real& a, const Real& b, piece_end a_end,
                             piece_end b_end, const Real& d_left, const Real& d_right, const Real& offset_a,
                             const Real& offset_b, K& k) {
  using std::pow;
  if (!(b > a)) return Real(0);
  const bool right_side = a >= d.x0;
  const Real qa = a_end == piece_end::interval_end ? d.smooth.gam : (a_end == piece_end::x0 ? d.x0_exponent() : Real(0));
  const Real pb = b_end == piece_end::interval_end ? d.smooth.del : (b_end == piece_end::x0 ? d.x0_exponent() : Real(0));
  const panel_integrator<Real> rule(pb, qa, d.quadrature_nodes());
  Real sum = 0;
  rule.for_each_node_deferred(b - a, d_left, d_right, [&](const Real& u, const Real& v, const Real& weight,
                                                          const Real& q_here, const Real& p_here) {
    const Real one_plus_x = (a + 1) + u, one_minus_x = (1 - b) + v;
    const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
    // The piece's end powers on panels inside it (for_each_node_deferred), the edge powers this
    // piece does not carry as weight, and E: E_over_weight at x0 (the rest of E is the weight),
    // else kappa or 1 times dist^-alpha in the same power_product (normalized mode: E_full's log
    // form).
    power_product<Real> powers;
    powers.times(u, q_here).times(v, p_here);
    if (a_end != piece_end::interval_end) powers.times(one_plus_x, d.smooth.gam);
    if (b_end != piece_end::interval_end) powers.times(one_minus_x, d.smooth.del);
    const Real dist = right_side ? (a - d.x0) + u : (d.x0 - b) + v;
    const bool at_x0 = right_side ? a_end == piece_end::x0 : b_end == piece_end::x0;
    Real E;
    if (at_x0) {
      E = d.E_over_weight(dist, right_side);
    } else if (!d.normalized) {
      E = right_side ? d.kappa : d.order_sign(false);
      powers.times(dist, Real(d.order) - d.alpha);
    } else {
      E = d.E_order(dist, right_side);
    }
    const Real extra = extra_factor(k, powers, x, u + offset_a, v + offset_b);
    const Real term = weight * (powers.value() * E * d.q_at(one_plus_x, one_minus_x) * extra);
    sum += term;
    if constexpr (records_nodes<std::remove_cv_t<K>>::value) k.take(term);
  });
  return sum;
}

template <class Real, class K>
Real enrichment_piece(const enriched_density<Real>& d, const Real& a, const Real& b, piece_end a_end, piece_end b_end,
                      const Real& d_left, const Real& d_right, K&& k) {
  using std::min;
  using std::pow;
  if (!(b > a)) return Real(0);
  const bool x0_at_a = a_end == piece_end::x0, x0_at_b = b_end == piece_end::x0;
  if (!d.normalized || !(x0_at_a || x0_at_b))
    return enrichment_piece_panels(d, a, b, a_end, b_end, d_left, d_right, Real(0), Real(0), k);
  const Real len = b - a;
  // First panel [0, D] in the distance u from x0, D = half the distance to every other singular
  // point (the far end of the piece, whatever lies beyond it, and the nearest singular point
  // across x0), so the smooth factor G = w q k is analytic on a disc 3 panel half-widths from the
  // panel's centre, as on panel_integrator's panels. With u = D t,
  //     E(D t) = kappa_side (D^-alpha W(t) + core(D)) - c_side = kappa_side D^-alpha W(t) + E(D),
  // W(t) = (t^-alpha - 1)/alpha, core(u) = (u^-alpha - 1)/alpha (left of x0: kappa_side = 1,
  // c_side = 0; right: kappa, (1 - kappa)/alpha; E_full's two forms), so
  //     int_0^D E G du = D [kappa_side D^-alpha sum_W G(D t_i) + E(D) sum_Legendre G(D s_j)]:
  // the log-type factor is the weight of gauss_log_power_rule; both sums have positive weights and
  // D^-alpha, E(D) are exact closed forms (no cancellation between the two terms beyond that of E
  // itself). The rest is graded toward x0 from distance D.
  const Real D = min(len, x0_at_a ? d_left : d_right) / 2;
  const std::size_t nodes = d.quadrature_nodes();
  const auto& log_rule = gauss_log_power_rule<Real>(nodes, d.alpha);
  const auto& legendre = cached_gauss_jacobi_rule<Real>(nodes, Real(0), Real(0));
  const bool right_side = x0_at_a;
  auto G = [&](const Real& dist) {  // w q k at distance dist from x0 inside the piece
    const Real u = x0_at_a ? dist : len - dist, v = x0_at_a ? len - dist : dist;
    const Real one_plus_x = (a + 1) + u, one_minus_x = (1 - b) + v;
    const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
    power_product<Real> powers;
    powers.times(one_plus_x, d.smooth.gam).times(one_minus_x, d.smooth.del);
    const Real extra = extra_factor(k, powers, x, u, v);
    // (x - x0)^order: smooth on the panel, part of G (E's log-type factor is the rule's weight).
    return powers.value() * d.q_at(one_plus_x, one_minus_x) * extra * d.order_power(dist, right_side);
  };
  Real log_sum = 0, plain_sum = 0;
  // A node_recorder takes each node's term with the factors `near` applies to the sums below.
  constexpr bool recording = records_nodes<std::remove_cv_t<std::remove_reference_t<K>>>::value;
  const Real log_factor = recording ? D * (right_side ? d.kappa : Real(1)) * pow(D, -d.alpha) : Real(0);
  const Real plain_factor = recording ? D * d.E_full(D, right_side) : Real(0);
  for (std::size_t i = 0; i < log_rule.x.size(); ++i) {
    const Real term = log_rule.weight[i] * G(D * log_rule.x[i]);
    log_sum += term;
    if constexpr (recording) k.take(log_factor * term);
  }
  for (std::size_t j = 0; j < legendre->size(); ++j) {
    const Real term = legendre->weight[j] * G(D * legendre->x_minus_lo[j] / 2);
    plain_sum += term;
    if constexpr (recording) k.take(plain_factor * term / 2);
  }
  plain_sum /= 2;  // Gauss-Legendre on [-1, 1] moved to [0, 1]
  const Real near = D * ((right_side ? d.kappa : Real(1)) * pow(D, -d.alpha) * log_sum + d.E_full(D, right_side) * plain_sum);
  if (x0_at_a)
    return near + enrichment_piece_panels(d, a + D, b, piece_end::interior, b_end, D, d_right, D, Real(0), k);
  return near + enrichment_piece_panels(d, a, b - D, a_end, piece_end::interior, d_left, D, Real(0), D, k);
}

}  // namespace detail

template <class Real>
Real enriched_density<Real>::phi_integral_to(const Real& X) const {
  using detail::piece_end;
  if (!(X > -1)) return Real(0);
  const Real inf = std::numeric_limits<Real>::infinity();
  auto one = [](const Real&, const Real&, const Real&) { return Real(1); };
  Real total = 0;
  const piece_end at_x0 = piece_end::x0;
  if (X < x0) {
    return detail::enrichment_piece(*this, Real(-1), X, piece_end::interval_end, piece_end::interior, inf,
                                    std::min(x0 - X, 1 - X), one);
  }
  if (X == x0) {
    return detail::enrichment_piece(*this, Real(-1), x0, piece_end::interval_end, at_x0, inf, 1 - x0, one);
  }
  total = detail::enrichment_piece(*this, Real(-1), x0, piece_end::interval_end, at_x0, inf, 1 - x0, one);
  total += detail::enrichment_piece(*this, x0, X, at_x0, X == 1 ? piece_end::interval_end : piece_end::interior,
                                    x0 + 1, X == 1 ? inf : 1 - X, one);
  return total;
}

template <class Real>
template <class Fn>
Real enriched_density<Real>::integrate_between(Fn&& f, const Real& from, const Real& to, std::vector<Real> breakpoints,
                                               const Real& beyond_lo, const Real& beyond_hi) const {
  using detail::piece_end;
  using std::min;
  using std::pow;
  const Real h = half_length(), lo = smooth.lo, hi = smooth.hi;
  // Cuts in the variable of phi (sigma when mapped): the ends, x0 (two-sided), the breakpoints and
  // the range ends; pieces outside [from, to] are skipped.
  // Formed as solve_step forms x0, and a cut within 4 ulps of x0 is x0: the sliver between them
  // would carry int_0^ulp |u|^-alpha du ~ 1e-11 (alpha = 0.3) of spurious weight.
  auto reference_of = [&](const Real& t) {
    using std::abs;
    Real x = -1 + (t - lo) / h;
    if (mobius != 0) {
      const auto d = sigma_of((t - lo) / h, (hi - t) / h);
      x = d[0] <= d[1] ? d[0] - 1 : 1 - d[1];
    }
    return abs(x - x0) <= 4 * std::numeric_limits<Real>::epsilon() * (1 + abs(x0)) ? x0 : x;
  };
  const Real range_lo = from > lo ? reference_of(from) : Real(-1), range_hi = to < hi ? reference_of(to) : Real(1);
  if (!(range_hi > range_lo)) return Real(0);
  std::vector<Real> cuts{Real(-1), Real(1), range_lo, range_hi};
  for (const Real& b : breakpoints)
    if (b > lo && b < hi) cuts.push_back(reference_of(b));
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  cuts.erase(std::remove(cuts.begin(), cuts.end(), x0), cuts.end());
  auto inside = [&](const Real& a, const Real& b) { return a >= range_lo && b <= range_hi; };
  // Singular points beyond the ends (sigma axis): those of f and the pole of the map's factors.
  const auto pole = pole_distances();
  const Real below = min(pole[0], beyond_in_sigma(beyond_lo, true)), above = min(pole[1], beyond_in_sigma(beyond_hi, false));
  // The integrand's factor at a node of a piece [a, b], from its distances u, v to a and b:
  // f(t) without a map; (1 - s^2) (1 + s sigma)^(alpha - 1) f(t(M(sigma))) with one (dx = (1 - s^2)
  // (1 + s sigma)^-2 dsigma and g = g~ (1 + s sigma)^(1 + alpha)).
  auto factor_on = [&](const Real& a, const Real& b) {
    return [&, a, b](const Real&, const Real& u, const Real& v) {
      Real one_plus = (a + 1) + u, one_minus = (1 - b) + v, jacobian = 1;
      if (mobius != 0) {
        const auto d = x_of(one_plus, one_minus);
        one_plus = d[0], one_minus = d[1];
        jacobian = one_minus_s() * one_plus_s() * pow(d[2], alpha - 1);
      }
      return jacobian * f(one_plus <= one_minus ? lo + h * one_plus : hi - h * one_minus);
    };
  };
  // Series part, per piece between all cuts (x0 included): edge weights on the end pieces,
  // geometric grading toward an edge a piece does not touch and toward the points beyond the ends.
  // Two passes: every node's abscissa and the rest of its integrand (rule weight, the edge powers
  // the piece does not carry, f and the map's factor) first, then the series at all nodes in one
  // jacobi_series::evaluate call (four recurrences interleaved: the series is most of a node's cost
  // at the degrees of a mapped density, ~100-230), then each piece's sum in the order and with the
  // operations of panel_integrator::integrate (the same value as one pass, bit for bit).
  Real series_sum = 0;
  if (!smooth.coefficients.empty()) {
    std::vector<Real> all = cuts;
    all.push_back(x0);
    std::sort(all.begin(), all.end());
    const auto series = smooth.series_evaluator();
    const std::size_t nodes = smooth.coefficients.size() / 2 + 24;
    struct node {
      Real rule_weight, weight, factor;
    };
    std::vector<Real> abscissae;
    std::vector<node> rest;
    std::vector<std::size_t> piece_starts;
    for (std::size_t k = 0; k + 1 < all.size(); ++k) {
      const bool first = k == 0, last = k + 2 == all.size();
      const panel_integrator<Real> rule(last ? smooth.del : Real(0), first ? smooth.gam : Real(0), nodes);
      const Real a = all[k], b = all[k + 1], start = a + 1, end = 1 - b;
      if (!inside(a, b)) continue;
      auto factor = factor_on(a, b);
      piece_starts.push_back(abscissae.size());
      rule.for_each_node(b - a, first ? below : start, last ? above : end,
                         [&](const Real& u, const Real& v, const Real& rule_weight) {
                           const Real one_plus_x = start + u, one_minus_x = end + v;
                           const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
                           Real weight = 1;
                           if (!first) weight *= pow(one_plus_x, smooth.gam);
                           if (!last) weight *= pow(one_minus_x, smooth.del);
                           abscissae.push_back(x);
                           rest.push_back({rule_weight, weight, factor(x, u, v)});
                         });
    }
    std::vector<Real> sums(abscissae.size());
    series.evaluate(abscissae.data(), sums.data(), abscissae.size());
    piece_starts.push_back(abscissae.size());
    for (std::size_t piece = 0; piece + 1 < piece_starts.size(); ++piece) {
      Real piece_sum = 0;
      for (std::size_t i = piece_starts[piece]; i < piece_starts[piece + 1]; ++i)
        piece_sum += rest[i].rule_weight * (rest[i].weight * sums[i] * rest[i].factor);
      series_sum += piece_sum;
    }
  }
  std::vector<Real> left_cuts, right_cuts;
  for (const Real& c : cuts) {
    if (c < x0) left_cuts.push_back(c);
    if (c > x0) right_cuts.push_back(c);
  }
  const piece_end at_x0 = piece_end::x0;
  Real sum = 0;
  left_cuts.push_back(x0);
  for (std::size_t k = 0; k + 1 < left_cuts.size(); ++k) {
    const Real a = left_cuts[k], b = left_cuts[k + 1];
    const bool last = k + 2 == left_cuts.size();
    if (!inside(a, b)) continue;
    sum += detail::enrichment_piece(*this, a, b, k == 0 ? piece_end::interval_end : piece_end::interior,
                                    last ? at_x0 : piece_end::interior, k == 0 ? below : a + 1,
                                    last ? 1 - x0 : std::min(x0 - b, 1 - b), factor_on(a, b));
  }
  right_cuts.insert(right_cuts.begin(), x0);
  for (std::size_t k = 0; k + 1 < right_cuts.size(); ++k) {
    const Real a = right_cuts[k], b = right_cuts[k + 1];
    const bool last = k + 2 == right_cuts.size();
    if (!inside(a, b)) continue;
    sum += detail::enrichment_piece(*this, a, b, k == 0 ? at_x0 : piece_end::interior,
                                    last ? piece_end::interval_end : piece_end::interior,
                                    k == 0 ? x0 + 1 : std::min(a - x0, a + 1), last ? above : 1 - b, factor_on(a, b));
  }
  return h * (series_sum + enrichment * sum);
}

namespace detail {

/// A~[phi](y) for the normalized enrichment (alpha < 0.01, uniform to alpha = 0). The kernel
/// singularity is treated by subtraction on [y - eps, y + eps], eps = half the distance from y
/// to the nearest of x0, -1, +1:
///   int_y^{y+eps} (x-y)^(alpha-1) (f(x) - f(y)) dx - kappa int_{y-eps}^y (y-x)^(alpha-1) (f(x) - f(y)) dx
///   + f(y) eps^alpha (1 - kappa)/alpha,
/// the rest by enrichment pieces with the smooth kernel factor, graded toward y, x0 and the ends.
template <class Real>
Real enrichment_image_uniform(const enriched_density<Real>& d, const abel_parameters<Real>& par, const Real& y) {
  using std::abs;
  using std::min;
  using std::pow;
  const Real alpha = par.alpha(), kappa = par.kappa();
  const Real x0 = d.x0;
  const Real inf = std::numeric_limits<Real>::infinity();
  const Real eps = min(abs(y - x0), min(1 + y, 1 - y)) / 2;
  // f at distances (1+x, 1-x): w q E.
  auto f_at = [&](const Real& one_plus_x, const Real& one_minus_x) { return d.phi(one_plus_x, one_minus_x); };
  const Real f_y = f_at(1 + y, 1 - y);
  const panel_integrator<Real> near(Real(0), alpha, d.quadrature_nodes());
  const Real R = near.integrate(eps, inf, eps, [&](const Real& u, const Real&) {
    return (f_at((1 + y) + u, (1 - y) - u) - f_y) / u;
  });
  const Real L = near.integrate(eps, inf, eps, [&](const Real& v, const Real&) {
    return (f_at((1 + y) - v, (1 - y) + v) - f_y) / v;
  });
  Real total = R - kappa * L + f_y * pow(eps, alpha) * par.one_minus_kappa_over_alpha();
  // Far pieces, kernel (x-y)^(alpha-1) right of y, -kappa (y-x)^(alpha-1) left of y.
  const Real ya = y - eps, yb = y + eps;
  // -kappa ((y - b) + v)^(alpha-1) on a piece ending at b <= ya; ((a - y) + u)^(alpha-1) on one
  // starting at a >= yb.
  auto kernel_left_of_y = [&](const Real& b) { return distance_power<Real>{-kappa, y - b, alpha - 1, false}; };
  auto kernel_right_of_y = [&](const Real& a) { return distance_power<Real>{Real(1), a - y, alpha - 1, true}; };
  if (y < x0) {
    total += enrichment_piece(d, Real(-1), ya, piece_end::interval_end, piece_end::interior, inf, eps, kernel_left_of_y(ya));
    total += enrichment_piece(d, yb, x0, piece_end::interior, piece_end::x0, eps, 1 - x0, kernel_right_of_y(yb));
    total += enrichment_piece(d, x0, Real(1), piece_end::x0, piece_end::interval_end, x0 - y, inf, kernel_right_of_y(x0));
  } else {
    total += enrichment_piece(d, Real(-1), x0, piece_end::interval_end, piece_end::x0, inf, y - x0, kernel_left_of_y(x0));
    total += enrichment_piece(d, x0, ya, piece_end::x0, piece_end::interior, x0 + 1, eps, kernel_left_of_y(ya));
    total += enrichment_piece(d, yb, Real(1), piece_end::interior, piece_end::interval_end, eps, inf, kernel_right_of_y(yb));
  }
  return total;
}

}  // namespace detail

/// A~[phi](y): the image under the Abel operator of the enrichment phi = w q E of the density d
/// at the reference point y in (-1, 1), y != x0, on the reference interval [-1, 1] (the physical
/// image is (L/2)^alpha times it, L the interval's length). By composite quadrature with si
/// (split at x0 and next to y) for alpha >= normalized_enrichment_threshold, and by the
/// normalized form (E - 1)/alpha, uniform down to alpha = 0, below it (d.normalized). Accuracy:
/// that of the quadrature, near double rounding with si of d.quadrature_nodes() - 4 nodes,
/// except for the cancellation of the two one-sided integrals next to x0, ~eps/(4 alpha)^2
/// relative on the plain path (solve_step's rounding_floor). Any abel_parameters (alpha in
/// [0, 1), kappa).
template <class Real>
Real enrichment_image_any(const enriched_density<Real>& d, const abel_parameters<Real>& par,
                          const split_integrator<Real>& si, const Real& y) {
  return d.normalized ? detail::enrichment_image_uniform(d, par, y) : detail::enrichment_image(d, par, si, y);
}


/// A g at any s (inside: spectral part + direct quadrature of A[phi]; outside [lo, hi]: the
/// surface-slope formula, paper 27-28, by graded quadrature). s != t0, lo, hi. Mapped densities:
/// inside by the covariance A[g](M(sigma)) = (1 - s^2)^alpha (1 + s sigma)^(1 - alpha) A[g~](sigma)
/// (header), outside by integrate with the kernel (graded toward s).
template <class Real>
Real apply(const abel_operator<Real>& op, const enriched_density<Real>& g, const Real& s) {
  using detail::piece_end;
  using std::pow;
  const Real h = op.half_length(), alpha = op.parameters().alpha(), kappa = op.parameters().kappa();
  const bool below = s <= op.lo(), inside = s > op.lo() && s < op.hi();
  if (g.mobius != 0) {
    if (inside) {
      const auto d = g.sigma_of((s - op.lo()) / h, (op.hi() - s) / h);
      const Real y = d[0] <= d[1] ? d[0] - 1 : 1 - d[1];
      const split_integrator<Real> si(g.quadrature_nodes() - 4);
      const Real t = d[0] <= d[1] ? op.lo() + h * d[0] : op.hi() - h * d[1];
      const Real mapped = op.apply(g.smooth, t) + pow(h, alpha) * g.enrichment * enrichment_image_any(g, op.parameters(), si, y);
      return g.covariance_factor(d[2]) * mapped;
    }
    // t - s from the distances to the facing end (no cancellation).
    const Real gap = below ? op.lo() - s : s - op.hi();
    const Real inf = std::numeric_limits<Real>::infinity();
    return g.integrate(
        [&](const Real& t) { return below ? pow((t - op.lo()) + gap, alpha - 1) : -kappa * pow((op.hi() - t) + gap, alpha - 1); },
        {}, below ? gap / h : inf, below ? inf : gap / h);
  }
  Real value = op.apply(g.smooth, s);
  const split_integrator<Real> si(g.quadrature_nodes() - 4);
  if (inside) {
    const Real y = -1 + (s - op.lo()) / h;
    return value + pow(h, alpha) * g.enrichment * enrichment_image_any(g, op.parameters(), si, y);
  }
  const Real d = below ? (op.lo() - s) / h : (s - op.hi()) / h;  // distance of y from the interval
  const Real inf = std::numeric_limits<Real>::infinity();
  const piece_end at_x0 = piece_end::x0;
  auto kernel = [&](const Real& x, const Real&, const Real&) {
    return below ? pow((x + 1) + d, alpha - 1) : -kappa * pow((1 - x) + d, alpha - 1);
  };
  Real sum = detail::enrichment_piece(g, Real(-1), g.x0, piece_end::interval_end, at_x0, below ? d : inf, 1 - g.x0, kernel);
  sum += detail::enrichment_piece(g, g.x0, Real(1), at_x0, piece_end::interval_end, g.x0 + 1, below ? inf : d, kernel);
  return value + pow(h, alpha) * g.enrichment * sum;
}

namespace detail {

// Taylor degree of q for the apex `apex` (mapped by `mobius`): the largest K <= max_taylor_degree
// with max|q| <= max_taylor_amplification, at least 1.
// q has radius of convergence 1 - |x0| and grows like ((1 + |x0|)/(1 - |x0|))^K on the far
// side, which sets a rounding floor ~ max|q| eps (taylor_amplification). Automatic K: the largest
// K <= max_taylor_degree() with max|q| <= max_taylor_amplification (1e4: floor ~ 1e-12), at least 1.
// q is built once at the largest degree: each Taylor coefficient is summed in the same order
// whatever K is, so q of degree K is its first K + 1 coefficients, to the last bit.
template <class Real>
std::size_t automatic_taylor_degree(const edge_exponents<Real>& e, const Real& apex, const Real& mobius) {
  const auto q_max = mapped_weight_taylor(e.gam, e.del, apex, max_taylor_degree(), mobius);
  for (std::size_t K = max_taylor_degree(); K > 1; --K)
    if (taylor_amplification(q_max, apex, K) <= max_taylor_amplification<Real>()) return K;
  return std::size_t(1);
}

// Sets g's Moebius map and apex g.x0 (reference variable) for an apex at reference distances
// (1 + x0, 1 - x0) from the ends, and returns the Taylor degree of q (taylor_degree if nonzero).
template <class Real>
std::size_t place_step_apex(enriched_density<Real>& g, const edge_exponents<Real>& e, const Real& x0,
                            const Real& one_plus_x0, const Real& one_minus_x0, bool centred, std::size_t taylor_degree) {
  using std::abs;
  if (centred) {
    // M(0) = s: the map with s = x0 puts the apex at the centre (header, "Data vanishing on the long side").
    g.set_mobius(std::min(one_plus_x0, one_minus_x0), one_plus_x0 < one_minus_x0);
    g.x0 = 0;
    if (taylor_degree == 0) taylor_degree = automatic_taylor_degree(e, g.x0, g.mobius);
  } else if (taylor_degree == 0) {
    if (!(abs(x0) > moebius_threshold<Real>())) taylor_degree = automatic_taylor_degree(e, x0, Real(0));
    if (abs(x0) > moebius_threshold<Real>()) {
      // Apex near an edge: the Moebius map that splits r = (1 - x0)/(1 + x0) (see header).
      using std::pow;
      const Real r = one_minus_x0 / one_plus_x0, r_map = pow(r, 1 - moebius_apex_exponent<Real>());
      // s = (1 - r_map)/(1 + r_map): 1 - |s| = 2 min(r_map, 1)/(1 + r_map).
      g.set_mobius(2 * std::min(r_map, Real(1)) / (1 + r_map), r_map > 1);
      const auto apex = g.sigma_of(one_plus_x0, one_minus_x0);
      g.x0 = apex[0] <= apex[1] ? apex[0] - 1 : 1 - apex[1];
      taylor_degree = automatic_taylor_degree(e, g.x0, g.mobius);
    }
  }
  return taylor_degree;
}

// Rounding floor of the remainder's Chebyshev tail for the density g (q and the apex set).
// max|q| eps (the smooth part cancels C phi far from the apex) and, on the plain path
// (alpha >= 0.01), the cancellation of the two one-sided integrals of A[E] near x0,
// ~ eps/(4 alpha)^2 (normalized_enrichment_threshold: ~eps/alpha^2).
template <class Real>
Real step_rounding_floor(const enriched_density<Real>& g, const Real& alpha, bool centred) {
  using std::max;
  Real floor = taylor_amplification(g.q, g.x0) * std::numeric_limits<Real>::epsilon();
  // With the apex centred (apex_placement::centred) the tails at 65 points measured 5-20 times
  // eps/(4 alpha)^2 (alpha 0.01 .. 0.05, 1 - eps = 1e-2 and 1e-4; the data vanish on the long
  // side, so max|F~| is the short side's step alone): the floor is eps/alpha^2 there. (With
  // eps/(4 alpha)^2 alpha = 0.01 went to 585 points, 9 ms, without gaining accuracy.)
  if (!(alpha < normalized_enrichment_threshold<Real>()))
    floor = max(floor, std::numeric_limits<Real>::epsilon() / ((centred ? 1 : 16) * alpha * alpha));
  return floor;
}

// The physical solvability defect of nu = -1 data F (f_at: F at reference distances
// (1 + x, 1 - x)), the image-P_0 coefficient <F, w'>/<1, w'>.
// nu = -1 solves A g = F - defect with a CONSTANT defect (F projected on the range: the image-P_0
// coefficient <F, w'>/<1, w'>, w' = (1 - x)^(gam-1) (1 + x)^(del-1), the weight of the image
// family P^(gam+nu, del+nu) (docs/theory.md section 4: the orthogonality condition); A[phi] has none). Mapped, a
// constant is not constant in sigma, so the physical defect is removed from F before the map:
// by Gauss-Jacobi on [-1, x0] and [x0, 1] (F smooth on each), graded toward the far end.
template <class Real, class FAt>
Real step_physical_defect(const edge_exponents<Real>& e, const Real& one_plus_x0, const Real& one_minus_x0,
                          const FAt& f_at) {
  using std::pow;
  const Real inf = std::numeric_limits<Real>::infinity();
  const panel_integrator<Real> left_piece(Real(0), e.del - 1, 32), right_piece(e.gam - 1, Real(0), 32);
  const Real moment = left_piece.integrate(one_plus_x0, inf, one_minus_x0, [&](const Real& u, const Real& v) {
    return pow(one_minus_x0 + v, e.gam - 1) * f_at(u, one_minus_x0 + v);
  }) + right_piece.integrate(one_minus_x0, one_plus_x0, inf, [&](const Real& u, const Real& v) {
    return pow(one_plus_x0 + u, e.del - 1) * f_at(one_plus_x0 + u, v);
  });
  return moment / (pow(Real(2), e.gam + e.del - 1) * boost::math::beta(e.gam, e.del));
}

// R_k = Gamma(k + 1 - alpha)/Gamma(1 - alpha) = (1 - alpha)(2 - alpha)...(k - alpha): the image of
// (x - x0)^k E has the jump-type term -(R_k/k!) J_E (x - x0)_+^k (header, "Kinks").
template <class Real>
Real kink_factor(const Real& alpha, unsigned k) {
  Real r = 1;
  for (unsigned j = 1; j <= k; ++j) r *= Real(j) - alpha;
  return r;
}

// J_E, the jump of A[E] at the apex (of A[(E - 1)/alpha] times alpha when g.normalized).
template <class Real>
Real enrichment_jump(const enriched_density<Real>& g, const Real& alpha, const Real& kappa) {
  using std::cos;
  using std::sin;
  const Real pi = boost::math::constants::pi<Real>();
  if (!g.normalized) return pi / sin(pi * alpha) * (1 - 2 * kappa * cos(pi * alpha) + kappa * kappa);
  // Jump of A[(E - 1)/alpha] = J_E / alpha, with 1 - 2 kappa cos + kappa^2 =
  // alpha^2 [((1-kappa)/alpha)^2 + 4 kappa (sin(pi alpha/2)/alpha)^2]: uniform, pi^2/cos^2(beta pi/2) at 0.
  const Real m = g.one_minus_kappa_over_alpha;
  const Real sh = alpha == 0 ? pi / 2 : sin(pi * alpha / 2) / alpha;
  const Real ratio = alpha == 0 ? Real(1) : pi * alpha / sin(pi * alpha);
  return ratio * (m * m + 4 * kappa * sh * sh);
}

// The least distance (reference variable, mapped when g is) of a sampling point from the apex.
// Sampling points stay at least `margin` away from x0 (reference variable): far enough that the
// side on which F is evaluated (s < t0 or s > t0 in the physical variable, rounded) is the
// side on which A[phi] is evaluated, however large |t0| is compared with the length.
// A point next to the apex gets its abscissa from its distance to the nearer end, with an absolute
// rounding ~ eps (|that end| + |t0|); sqrt(eps) times that (reference units) leaves a wide berth.
// (Before: sqrt(eps) (1 + max(|lo|, |hi|)/h), which the map below turned into more than a node
// spacing for an apex 1e-9 from the end at 0 of [-1, 1e-9]: the residual's search for a grid
// avoiding x0 never ended.)
// Mapped: distances at the apex shrink by M'(sigma0) = (1 - s^2)/(1 + s sigma0)^2 on the x axis.
template <class Real>
Real step_sampling_margin(const abel_operator<Real>& op, const enriched_density<Real>& g, const Real& t0,
                          const Real& one_plus_x0, const Real& one_minus_x0) {
  using std::abs;
  using std::max;
  using std::sqrt;
  const Real nearer_end = one_plus_x0 <= one_minus_x0 ? abs(op.lo()) : abs(op.hi());
  Real margin = sqrt(std::numeric_limits<Real>::epsilon()) * (nearer_end + abs(t0)) / op.half_length();
  if (g.mobius != 0) {
    const Real one_plus_s_sigma0 = g.apex_in_x()[2];
    margin *= max(Real(1), one_plus_s_sigma0 * one_plus_s_sigma0 / (g.one_minus_s() * g.one_plus_s()));
  }
  return margin;
}

// The remainder F - C A[E] sampled on the last grid: its Chebyshev coefficients a, their relative
// tail, the grid size, max |scaled data| on the grid, and whether the tail converged.
template <class Real>
struct step_remainder {
  std::vector<Real> a;
  Real tail = 0;
  std::size_t used = 0;
  Real biggest_data = 0;
  bool converged = true;
};

// Chebyshev coefficients of the scaled remainder scale_F F - C A[E] on nested first-kind grids
// avoiding the apex by `margin` (data_at: F at reference distances (1 + sigma, 1 - sigma)),
// refined 3m at a time until the tail meets options.tolerance, its rounding floor or a plateau.
template <class Real, class DataAt>
step_remainder<Real> sample_step_remainder(const abel_operator<Real>& op, const enriched_density<Real>& g,
                                           const split_integrator<Real>& si, const DataAt& data_at, const Real& scale_F,
                                           const Real& margin, const Real& rounding_floor,
                                           const solve_options<Real>& options) {
  using std::abs;
  using std::max;
  step_remainder<Real> out;
  std::vector<Real>& a = out.a;
  Real& tail = out.tail;
  std::size_t m = options.degree != 0 ? options.degree : std::min(initial_step_sampling_size(), std::max<std::size_t>(options.max_degree, 2));
  Real previous_tail = std::numeric_limits<Real>::infinity();
  std::size_t used = m;
  // Nested grids: the first-kind grid of size 3m contains the grid of size m (node j is node
  // 3j + 1), so a level reuses the remainder values of the previous one and computes 2m new ones.
  std::vector<Real> values, abs_data;
  for (;;) {
    const std::size_t previous_used = values.size();
    used = grid_size_avoiding(m, g.x0, margin);
    const bool nested = previous_used != 0 && used == 3 * previous_used;
    const chebyshev_grid<Real> grid(used);
    std::vector<Real> next_values(used), next_abs(used);
    for (std::size_t j = 0; j < used; ++j) {
      if (nested && j % 3 == 1) {
        next_values[j] = values[j / 3];
        next_abs[j] = abs_data[j / 3];
        continue;
      }
      const Real v = data_at(grid.one_plus_x[j], grid.one_minus_x[j]);
      next_abs[j] = abs(scale_F * v);
      next_values[j] = scale_F * v - g.enrichment * enrichment_image_any(g, op.parameters(), si, grid.x[j]);
    }
    values = std::move(next_values);
    abs_data = std::move(next_abs);
    Real biggest = 0;
    for (const Real& v : abs_data) biggest = max(biggest, v);
    a = chebyshev_coefficients(values);
    const std::size_t tail_start = used - std::max<std::size_t>(2, used / 8);
    tail = 0;
    for (std::size_t k = tail_start; k < used; ++k) tail = max(tail, abs(a[k]));
    if (biggest > 0) tail /= biggest;
    if (options.degree != 0 || tail <= options.tolerance) break;
    // At the rounding floor of the enrichment (4 max|q| eps; measured 1-5 max|q| eps) more points
    // cannot help: converged to that floor (reported in rounding_floor). (Also requiring the
    // tail to stagnate was measured with the former doubling levels: it took 65 -> 513 points at
    // eps = 0.1 without improving int g.)
    if (tail <= 4 * rounding_floor) break;
    // Plateau: a tail below 1024 eps that no longer decays, against the previous level or within
    // this one (the coefficients of the second half before the tail), is rounding noise.
    Real middle = 0;
    for (std::size_t k = used / 2; k < tail_start; ++k) middle = max(middle, abs(a[k]));
    if (biggest > 0) middle /= biggest;
    if (tail <= 1024 * std::numeric_limits<Real>::epsilon() && std::min(previous_tail, middle) <= 10 * tail) break;
    previous_tail = tail;
    // Next level: 3m (nested) up to options.max_degree points; a last level of exactly
    // max_degree points (not nested) when 3m would exceed it.
    if (used >= options.max_degree) {
      out.converged = false;
      break;
    }
    m = std::min<std::size_t>(3 * used, options.max_degree);
  }
  out.used = used;
  for (const Real& v : abs_data) out.biggest_data = max(out.biggest_data, v);
  return out;
}

// The points (1 + y, 1 - y) of solve_step's residual: a Chebyshev grid of about
// residual_points points avoiding the sampling grid (`used` points) and the apex, the same grid
// in x when g is mapped, and four points that see an apex close to an edge.
template <class Real>
std::vector<std::pair<Real, Real>> step_residual_points(const enriched_density<Real>& g, const Real& margin,
                                                        std::size_t residual_points, std::size_t used) {
  using std::abs;
  // Residual points: no node of the sampling grid (residual_grid_size) and none within margin of x0.
  std::size_t r = residual_grid_size(residual_points, used);
  while (grid_size_avoiding(r, g.x0, margin) != r || same_power_of_two(r, used)) ++r;
  const chebyshev_grid<Real> grid(r);
  // Points as (1 + y, 1 - y): the interior Chebyshev points, plus four points that see an apex
  // close to an edge (where the Chebyshev points are sparse relative to the apex's distance d
  // to the nearer edge): y = x0 -+ d/2 and the points d/4, 3 d/4 of the way from x0 to that edge.
  std::vector<std::pair<Real, Real>> points;
  for (std::size_t j = 0; j < grid.x.size(); ++j) points.emplace_back(grid.one_plus_x[j], grid.one_minus_x[j]);
  if (g.mobius != 0) {
    // Mapped: the sigma grid crowds toward the apex and leaves the far side of the physical
    // interval (squeezed next to the pole-side end) with few points; add the same grid in x.
    for (std::size_t j = 0; j < grid.x.size(); ++j) {
      const auto d = g.sigma_of(grid.one_plus_x[j], grid.one_minus_x[j]);
      const Real y = d[0] <= d[1] ? d[0] - 1 : 1 - d[1];
      if (abs(y - g.x0) > margin) points.emplace_back(d[0], d[1]);
    }
  }
  const Real to_lo = 1 + g.x0, to_hi = 1 - g.x0, d = std::min(to_lo, to_hi);
  for (const Real& shift : {-d / 2, d / 2}) points.emplace_back(to_lo + shift, to_hi - shift);
  for (const Real& fraction : {Real(1) / 4, Real(3) / 4}) {
    if (to_lo <= to_hi) points.emplace_back(to_lo * (1 - fraction), to_hi + to_lo * fraction);
    else points.emplace_back(to_lo + to_hi * fraction, to_hi * (1 - fraction));
  }
  return points;
}

// solve_step's independent residual max |A g - (F - defect)| / max |F| at step_residual_points,
// by direct quadrature of the one-sided integrals of both parts of g (sol.density).
template <class Real, class DataAt>
Real step_residual(const abel_operator<Real>& op, const enriched_solution<Real>& sol, const split_integrator<Real>& si,
                   const DataAt& data_at, const Real& margin, std::size_t residual_points, std::size_t used) {
  using std::abs;
  using std::max;
  using std::pow;
  const enriched_density<Real>& g = sol.density;
  const edge_exponents<Real>& e = sol.exponents;
  const Real h = op.half_length(), alpha = op.parameters().alpha();
  const typename abel_operator<Real>::quadrature_evaluator direct(op, e.gam, e.del, g.smooth.coefficients.size());
  const auto points = step_residual_points(g, margin, residual_points, used);
  // (Mapped: the defect is already out of the data.)
  const Real defect = e.nu == -1 && g.mobius == 0 ? pow(h, alpha) * sol.solvability_defect : Real(0);
  // g.smooth.series with the recurrence coefficients computed once (quadrature::jacobi_series).
  const auto series = g.smooth.series_evaluator();
  Real worst = 0, scale = 0;
  for (const auto& [one_plus_y, one_minus_y] : points) {
    // s: the point of the solved problem (sigma, in the units of [lo, hi], when mapped).
    const Real s = one_plus_y <= one_minus_y ? op.lo() + h * one_plus_y : op.hi() - h * one_minus_y;
    const Real y = one_plus_y <= one_minus_y ? one_plus_y - 1 : 1 - one_minus_y;
    const Real Ag = direct([&](const Real& x) { return series(x); }, s) +
                    pow(h, alpha) * g.enrichment * enrichment_image_any(g, op.parameters(), si, y);
    const Real Fs = data_at(one_plus_y, one_minus_y);
    // Mapped: the residual of the physical equation A g = F - defect is that of the mapped one
    // times F/F~ here.
    const Real back = g.covariance_factor(g.x_of(one_plus_y, one_minus_y)[2]);  // 1 without a map
    worst = max(worst, abs(Ag - (Fs - defect)) * back);
    scale = max(scale, abs(Fs) * back);
  }
  return scale > 0 ? worst / scale : worst;
}

}  // namespace detail

/// Solves A g = F on [lo, hi] for F smooth except for a jump at t0 in (lo, hi) (see header).
/// taylor_degree = 0 (default): automatic factor q (Taylor polynomial of the largest K <= 12 with
/// max|q| <= 1e4) and, for an apex with |x0| > 1/2, the Moebius map (density.mobius); taylor_degree
/// = K > 0 forces the Taylor polynomial of degree K without a map. options.degree != 0 fixes the
/// number of sampling points (m or m + 1, see grid_size_avoiding); otherwise adaptive, 65 -> 195 ->
/// 585 -> ... up to options.max_degree points. Returns the density with the evidence: status,
/// coefficient_tail (estimate of the relative error of the image expansion), rounding_floor,
/// residual (an estimate, see header), solvability_defect (nu = -1), degree and taylor_degree.
template <class Real, class F>
enriched_solution<Real> solve_step(const abel_operator<Real>& op, edge leading, edge trailing, F&& f, const Real& t0,
                                   const solve_options<Real>& options = {}, std::size_t taylor_degree = 0,
                                   apex_placement placement = apex_placement::balanced) {
  using std::abs;
  using std::max;
  using std::pow;
  const Real alpha = op.parameters().alpha(), kappa = op.parameters().kappa();
  if (!(t0 > op.lo() && t0 < op.hi()))
    detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_step", "t0", t0, "(lo, hi)");
  const auto e = op.exponents(leading, trailing);
  const bool centred = placement == apex_placement::centred;
  if (centred && e.nu == -1)
    detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_step", "nu (apex_placement::centred)", Real(e.nu), "{0, +1}");
  const Real h = op.half_length();
  const Real scale_F = pow(h, -alpha);
  const Real x0 = -1 + (t0 - op.lo()) / h;

  enriched_solution<Real> sol;
  sol.exponents = e;
  enriched_density<Real>& g = sol.density;
  g.smooth.lo = op.lo();
  g.smooth.hi = op.hi();
  g.smooth.gam = e.gam;
  g.smooth.del = e.del;
  g.x0 = x0;
  g.kappa = kappa;
  g.alpha = alpha;
  const Real one_plus_x0 = (t0 - op.lo()) / h, one_minus_x0 = (op.hi() - t0) / h;
  taylor_degree = detail::place_step_apex(g, e, x0, one_plus_x0, one_minus_x0, centred, taylor_degree);
  g.q = detail::mapped_weight_taylor(e.gam, e.del, g.x0, taylor_degree, g.mobius);
  sol.taylor_degree = taylor_degree;
  sol.rounding_floor = detail::step_rounding_floor(g, alpha, centred);
  // The data of the solved problem at the point with reference distances (1 + sigma, 1 - sigma):
  // F, or with the map F~(sigma) = (1 - s^2)^-alpha (1 + s sigma)^(alpha - 1) F(M(sigma)) (header).
  const Real s_map = g.mobius;
  auto map_factor = [&](const Real& one_plus_s_sigma) { return 1 / g.covariance_factor(one_plus_s_sigma); };  // F~ / F
  // F at the point with reference distances 1 + x, 1 - x (x axis), checked finite.
  const bool long_side_below = one_minus_x0 <= one_plus_x0;  // the apex is nearer to hi
  auto f_at = [&](const Real& one_plus, const Real& one_minus) {
    const Real t = one_plus <= one_minus ? op.lo() + h * one_plus : op.hi() - h * one_minus;
    const Real v = f(t);
    detail::check_finite_value("rhabel::abel::solve_step", v, t);
    if (centred && v != 0 && (long_side_below ? one_plus < one_plus_x0 : one_minus < one_minus_x0))
      detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_step", "f on the long side of t0 (apex_placement::centred)", v, "{0}");
    return v;
  };
  const Real physical_defect =
      s_map != 0 && e.nu == -1 ? detail::step_physical_defect(e, one_plus_x0, one_minus_x0, f_at) : Real(0);
  auto data_at = [&](const Real& one_plus_sigma, const Real& one_minus_sigma) {
    if (s_map == 0) return f_at(one_plus_sigma, one_minus_sigma);
    const auto d = g.x_of(one_plus_sigma, one_minus_sigma);
    return map_factor(d[2]) * (f_at(d[0], d[1]) - physical_defect);
  };
  // Jump of F at t0 from one-sided values (F is evaluated on each side only, in the physical
  // variable: the map compresses distances next to the apex), times the map's factor there.
  const Real delta = 64 * std::numeric_limits<Real>::epsilon() * max(abs(t0), op.hi() - op.lo());
  const Real left_value = f(t0 - delta), right_value = f(t0 + delta);
  detail::check_finite_value("rhabel::abel::solve_step", left_value, t0 - delta);
  detail::check_finite_value("rhabel::abel::solve_step", right_value, t0 + delta);
  const Real jump = (left_value - right_value) * map_factor(g.apex_in_x()[2]);  // factor 1 without a map
  const Real w0 = pow(1 - g.x0, e.del) * pow(1 + g.x0, e.gam);
  g.normalized = alpha < normalized_enrichment_threshold<Real>();
  g.one_minus_kappa_over_alpha = op.parameters().one_minus_kappa_over_alpha();
  g.enrichment = scale_F * jump / (w0 * detail::enrichment_jump(g, alpha, kappa));

  const split_integrator<Real> si(g.quadrature_nodes() - 4);
  const Real p = e.gam + Real(e.nu), qI = e.del + Real(e.nu);
  const Real margin = detail::step_sampling_margin(op, g, t0, one_plus_x0, one_minus_x0);
  auto remainder = detail::sample_step_remainder(op, g, si, data_at, scale_F, margin, sol.rounding_floor, options);
  if (!remainder.converged) sol.status = solve_status::not_converged;
  std::vector<Real>& a = remainder.a;
  Real tail = remainder.tail;
  const std::size_t used = remainder.used;
  Real biggest_a = 0;
  for (const Real& v : a) biggest_a = max(biggest_a, abs(v));
  std::size_t keep = a.size();
  while (keep > 1 && abs(a[keep - 1]) <= 8 * std::numeric_limits<Real>::epsilon() * biggest_a) --keep;
  a.resize(keep);
  const auto d = detail::chebyshev_to_jacobi(a, p, qI);
  solve_options<Real> inner = options;
  inner.load.reset();
  const abel_solution<Real> smooth = detail::solution_from_image(op, e, d, inner);
  g.smooth = smooth.density;
  sol.solvability_defect = smooth.solvability_defect;
  if (s_map != 0 && e.nu == -1) {
    // The physical defect (below) was removed from the data: what is left of the image-P_0
    // coefficient is the data's lack of resolution (and quadrature error): part of the tail.
    sol.solvability_defect = scale_F * physical_defect;
    if (remainder.biggest_data > 0) tail = max(tail, abs(smooth.solvability_defect) / remainder.biggest_data);
  }
  sol.coefficient_tail = tail;
  sol.degree = used;
  // Independent residual: direct quadrature of the one-sided integrals of both parts.
  if (options.residual_points > 0) sol.residual = detail::step_residual(op, sol, si, data_at, margin, options.residual_points, used);
  return sol;
}

/// The composite rule of an enrichment as weighted nodes (enrichment_nodes): node j at reference
/// distances one_plus_x[j], one_minus_x[j] from the ends, value[j] = its rule weight times C phi
/// there times the half-length, so that int_lo^hi f(t) C phi(t) dt ~= sum_j value[j] f(t_j).
template <class Real>
struct enrichment_rule {
  std::vector<Real> one_plus_x, one_minus_x, value;
  std::size_t size() const { return value.size(); }
  /// The reference abscissa x_j in [-1, 1] from the nearer end.
  Real x(std::size_t j) const { return one_plus_x[j] <= one_minus_x[j] ? one_plus_x[j] - 1 : 1 - one_minus_x[j]; }
  /// t_j from the nearer end (exact next to either end).
  Real t(std::size_t j, const Real& lo, const Real& hi) const {
    const Real h = (hi - lo) / 2;
    return one_plus_x[j] <= one_minus_x[j] ? lo + h * one_plus_x[j] : hi - h * one_minus_x[j];
  }
};

/// The nodes of enriched_density::integrate's composite rule for the enrichment C phi of d alone
/// (d without a Moebius map and with an empty series: a kink's term, kink_enrichment), for
/// integrands f whose nearest singular points lie beyond_lo half-lengths below lo and beyond_hi
/// above hi (the panels are graded toward them; infinite: none). The same pieces, nodes and terms
/// as integrate: sum_j value[j] f(t_j) equals d.integrate(f, {}, beyond_lo, beyond_hi) up to the
/// order of summation, so its accuracy is integrate's (near double rounding for f analytic on
/// [lo, hi]). WHY: a density that acts at many points (a contact's action on its neighbours)
/// evaluates phi once per node instead of once per node and point.
template <class Real>
enrichment_rule<Real> enrichment_nodes(const enriched_density<Real>& d, const Real& beyond_lo, const Real& beyond_hi) {
  if (d.mobius != 0 || !d.smooth.coefficients.empty())
    throw std::invalid_argument("rhabel::abel::enrichment_nodes: the enrichment alone (no map, empty series)");
  using detail::piece_end;
  enrichment_rule<Real> out;
  const Real x0 = d.x0;
  detail::node_recorder<Real> left{Real(-1), x0, &out.one_plus_x, &out.one_minus_x, &out.value};
  detail::node_recorder<Real> right{x0, Real(1), &out.one_plus_x, &out.one_minus_x, &out.value};
  detail::enrichment_piece(d, Real(-1), x0, piece_end::interval_end, piece_end::x0, beyond_lo, 1 - x0, left);
  detail::enrichment_piece(d, x0, Real(1), piece_end::x0, piece_end::interval_end, x0 + 1, beyond_hi, right);
  const Real scale = d.enrichment * d.half_length();
  for (Real& v : out.value) v *= scale;
  return out;
}

/// One kink of the data (solve_kinks): F's derivative of order `order` (1 or 2) jumps by
/// `jump` = F^(order)(position+) - F^(order)(position-), F and its lower derivatives continuous
/// there (order 1: a kink; order 2: a knot of a cubic spline's slope).
template <class Real>
struct kink {
  Real position = 0;
  unsigned order = 2;
  Real jump = 0;
};

/// The enrichment C phi of one kink on [lo, hi] (header, "Kinks"): an enriched_density with an
/// empty series, phi = w q (x - x0)^order E in the class of (leading, trailing), q the Taylor
/// factor of degree taylor_degree (0: automatic, as solve_step's without a Moebius map), C such
/// that A[C phi] carries the kink's jump-type term exactly, so that F - A[C phi] has jump-type
/// terms of order >= order + K + 1 only there. A[C phi]: apply(op, term, s); values, integrals and
/// intensities: the enriched_density's. Throws std::domain_error for a position outside (lo, hi),
/// an order outside {1, 2} or a jump that is not finite.
template <class Real>
enriched_density<Real> kink_enrichment(const abel_operator<Real>& op, edge leading, edge trailing, const kink<Real>& k,
                                       std::size_t taylor_degree = 0) {
  using std::isfinite;
  using std::pow;
  constexpr const char* who = "rhabel::abel::kink_enrichment";
  if (!(k.position > op.lo() && k.position < op.hi())) detail::throw_bad_parameter(who, "position", k.position, "(lo, hi)");
  if (k.order < 1 || k.order > 2) detail::throw_bad_parameter(who, "order", Real(k.order), "{1, 2}");
  if (!isfinite(k.jump)) detail::throw_bad_parameter(who, "jump", k.jump, "finite values");
  const auto e = op.exponents(leading, trailing);
  const Real alpha = op.parameters().alpha(), h = op.half_length();
  enriched_density<Real> g;
  g.smooth = {op.lo(), op.hi(), e.gam, e.del, {}};
  g.x0 = -1 + (k.position - op.lo()) / h;
  g.kappa = op.parameters().kappa();
  g.alpha = alpha;
  g.order = k.order;
  if (taylor_degree == 0) taylor_degree = detail::automatic_taylor_degree(e, g.x0, Real(0));
  g.q = detail::inverse_weight_taylor(e.gam, e.del, g.x0, taylor_degree);
  g.normalized = alpha < normalized_enrichment_threshold<Real>();
  g.one_minus_kappa_over_alpha = op.parameters().one_minus_kappa_over_alpha();
  // The data's term (jump/k!) (s - t0)_+^k is (jump h^k/k!) (x - x0)_+^k in x, times h^-alpha in
  // the reference problem; A~[(x - x0)^k E] has -(R_k/k!) J_E (x - x0)_+^k (header, "Kinks").
  Real scaled = k.jump * pow(h, -alpha);
  for (unsigned j = 0; j < k.order; ++j) scaled *= h;
  const Real w0 = pow(1 - g.x0, e.del) * pow(1 + g.x0, e.gam);
  g.enrichment = -scaled / (detail::kink_factor(alpha, k.order) * w0 * detail::enrichment_jump(g, alpha, g.kappa));
  return g;
}

/// The solution of solve_kinks: g = the series of `smooth` plus the kinks' enrichments `terms`.
template <class Real>
struct kinked_solution {
  /// The series (density), the class, solvability_defect (nu = -1: of F - sum A[C phi]), degree,
  /// coefficient_tail and status of the remainder's spectral solve; residual: the independent
  /// residual of A g = F (both parts; see solve_kinks).
  abel_solution<Real> smooth;
  std::vector<enriched_density<Real>> terms;  ///< C phi of each kink (empty series each)
  /// Estimated relative rounding floor of g: C phi grows like q away from its kink and the series
  /// cancels it there, so the largest of the terms' max|q| eps (and eps/(16 alpha^2) on the plain
  /// path; solve_step's rounding_floor), 16 eps max|F - sum A[C phi]| / max|F| on the residual's
  /// grid and 256 eps sum |int C phi| / |int g|. An estimate of the relative error of g and of
  /// int g (measured errors in solve_kinks' comment).
  Real rounding_floor = 0;

  /// g(t) for lo < t < hi.
  Real operator()(const Real& t) const {
    Real v = smooth.density(t);
    for (const auto& term : terms) v += term(t);
    return v;
  }
  /// int_lo^hi g.
  Real integral() const {
    Real v = smooth.density.integral();
    for (const auto& term : terms) v += term.integral();
    return v;
  }
  /// int_lo^t g.
  Real integral_to(const Real& t) const {
    Real v = smooth.density.integral_to(t);
    for (const auto& term : terms) v += term.integral_to(t);
    return v;
  }
  /// Edge intensities lim g |t - edge|^(-exponent) (series and terms).
  Real intensity_leading() const {
    Real v = smooth.density.intensity_leading();
    for (const auto& term : terms) v += term.intensity_leading();
    return v;
  }
  Real intensity_trailing() const {
    Real v = smooth.density.intensity_trailing();
    for (const auto& term : terms) v += term.intensity_trailing();
    return v;
  }
};

/// Solves A g = F on [lo, hi] for F smooth except at the kinks (header, "Kinks"): each kink's
/// enrichment (kink_enrichment) is built in with its coefficient from the given jump, and the
/// remainder F - sum A[C phi] is solved by solve (adaptive Chebyshev interpolation, options as
/// there; it stops at its rounding plateau), on the interval moved to [0, L] (the terms' images
/// at exactly the interpolation points; WHY: the body). options.tolerance and the reported
/// coefficient_tail are relative to max|F| (solve's tolerance is scaled by max|F|/max|remainder|
/// on 9 points). residual_points > 0: the independent residual of
/// the remainder's solve, relative to max|F| (rescaled from solve's max|remainder|): that of
/// A g = F up to the quadrature of the terms' images (the same quadrature that formed the
/// remainder; the tests check the original equation by tanh-sinh). nu = +1 with options.load:
/// int g (series and terms) = load. Cost: a term's image is a composite Gauss-Jacobi quadrature
/// (~3 us) at each interpolation point. Kinks whose positions coincide are allowed (orders 1 and 2
/// at one knot); the positions must lie in (lo, hi). A kink whose non-polynomial term |J| d^k/k!
/// (d: its distance to the nearer edge) is below options.tolerance times F's scale (max |F| at
/// the centre and the quarter points), or below what building it in would cost next to an edge
/// (see the body), is left to the interpolation (`terms` has the others). Limits: a kink near an
/// edge costs digits to cancellation (rounding_floor; int g off by 5.9e-9 at 1e-3 of the
/// half-length from an edge), and the adaptive loop stops there converged, as solve_step's at its
/// floor; and, as for solve, F far from the origin (|lo| >> hi - lo) is sampled at points
/// rounded by ~eps |lo|, which the status reports (not_converged at [1e6, 1e6 + 1e-6]): shift
/// the origin first. (A contact 1.2e-4 long at 0.59 with a spline-like knot: residual 2e-12.)
namespace detail {
/// solve_kinks on an interval as given (the public one moves it to [0, L] first).
template <class Real, class F>
kinked_solution<Real> solve_kinks_as_given(const abel_operator<Real>& op, edge leading, edge trailing, F&& f,
                                           const std::vector<kink<Real>>& kinks, const solve_options<Real>& options) {
  using std::abs;
  using std::max;
  using std::pow;
  kinked_solution<Real> out;
  // A kink is left to the interpolation when its non-polynomial term, on its short side
  // ((s - t0)_+^k = (s - t0)^k - (-1)^k (t0 - s)_+^k), relative to F's scale,
  //     short = |J| d^k/k! / scale   (d: the distance to the nearer edge),
  // is at most the tolerance or what building it in would cost: C phi is the term's size on the
  // whole interval, long = |J| L^k/k! / scale, amplified by q (max|q| ~ (2/d_ref)^K), and the
  // series cancels it to ~256 eps of that (rounding_floor). The interpolation then errs by about
  // `short`. WHY: a kink 1e-6 of the half-length from an edge built in left int g off by 5.7e-8,
  // where its term is 5e-13.
  const Real mid = op.lo() + op.half_length();
  const Real data_scale = max(abs(f(mid)), max(abs(f(op.lo() + op.half_length() / 2)), abs(f(mid + op.half_length() / 2))));
  for (const auto& k : kinks) {
    auto term = kink_enrichment(op, leading, trailing, k);  // validates k
    const Real factorial = k.order == 2 ? 2 : 1, length = op.hi() - op.lo();
    const Real d = std::min(k.position - op.lo(), op.hi() - k.position);
    const Real short_side = abs(k.jump) * pow(d, Real(k.order)) / factorial;
    const Real cost = 256 * std::numeric_limits<Real>::epsilon() * abs(k.jump) * pow(length, Real(k.order)) / factorial *
                      detail::taylor_amplification(term.q, term.x0);
    if (!(short_side > max(options.tolerance * data_scale, cost))) continue;
    out.terms.push_back(std::move(term));
    out.rounding_floor = max(out.rounding_floor, detail::step_rounding_floor(out.terms.back(), op.parameters().alpha(), false));
  }
  std::vector<split_integrator<Real>> rules;
  std::vector<Real> term_integrals;  // int C phi of each term (a composite quadrature each)
  for (const auto& term : out.terms) {
    rules.emplace_back(term.quadrature_nodes() - 4);
    term_integrals.push_back(term.integral());
  }
  const Real h = op.half_length(), scale = pow(h, op.parameters().alpha());
  // F - sum A[C phi] at s (inside: the terms' images on the reference interval times h^alpha).
  // A kink on an interpolation point, to rounding (the centre x0 = 0 is a node of every odd
  // first-kind grid): the quadratures split at y and x0 do not take the two as one point. The
  // image is C^(order - 1) there, with a one-sided term c u_+^order, so it is extrapolated from the
  // right: 2 I(x0 + d) - I(x0 + 2 d) = I(x0) + O(d^2 I''), d = kink_offset.
  const Real kink_offset = Real(1) / 100000000;
  auto image = [&](std::size_t k, const Real& y) {
    const auto& term = out.terms[k];
    if (abs(y - term.x0) > 4 * std::numeric_limits<Real>::epsilon() * (1 + abs(term.x0)))
      return enrichment_image_any(term, op.parameters(), rules[k], y);
    return 2 * enrichment_image_any(term, op.parameters(), rules[k], term.x0 + kink_offset) -
           enrichment_image_any(term, op.parameters(), rules[k], term.x0 + 2 * kink_offset);
  };
  auto remainder = [&](const Real& s) {
    Real v = f(s);
    detail::check_finite_value("rhabel::abel::solve_kinks", v, s);
    const Real y = -1 + (s - op.lo()) / h;
    for (std::size_t k = 0; k < out.terms.size(); ++k) v -= scale * out.terms[k].enrichment * image(k, y);
    return v;
  };
  // nu = +1 with a load: the series carries what the terms do not.
  solve_options<Real> o = options;
  if (o.load)
    for (const Real& integral : term_integrals) *o.load -= integral;
  // solve's tail is relative to max|remainder|, which the terms' images can make much larger than
  // max|F| (below): its tolerance is scaled by their ratio on 9 first-kind points, so that the
  // tail reaches options.tolerance relative to F. WHY: unscaled, a knot at x0 = 0.62 with q ~ 1e3
  // stopped at 17 points with tail 8e-10 and residual 4e-7 relative to F.
  auto ratio_on = [&](std::size_t points) {
    const chebyshev_grid<Real> grid(points);
    Real data = 0, rest = 0;
    for (std::size_t j = 0; j < grid.x.size(); ++j) {
      const Real s = grid.one_plus_x[j] <= grid.one_minus_x[j] ? op.lo() + h * grid.one_plus_x[j]
                                                               : op.hi() - h * grid.one_minus_x[j];
      data = max(data, abs(f(s)));
      rest = max(rest, abs(remainder(s)));
    }
    return std::pair<Real, Real>{data, rest};
  };
  if (!out.terms.empty()) {
    const auto [data, rest] = ratio_on(9);
    // Not below 16 eps (solve's default): there the rounding plateau stops the loop anyway.
    if (data > 0 && rest > data) o.tolerance = max(options.tolerance * data / rest, 16 * std::numeric_limits<Real>::epsilon());
  }
  out.smooth = solve(op, leading, trailing, remainder, o);
  if (out.terms.empty()) return out;
  // The remainder's scale against the data's, on the residual's grid (without a residual, 9
  // first-kind points: a scale only): solve's residual is relative to max|remainder|, which the
  // terms' images can make much larger than max|F| (a kink next to an edge: q ~ 1e4 .. 1e6), and
  // their rounding, eps times that size, is what the series then cancels (rounding_floor).
  const auto [data, rest] = ratio_on(options.residual_points > 0
                                          ? detail::residual_grid_size(options.residual_points, out.smooth.degree)
                                          : std::size_t(9));
  if (data > 0) {
    out.smooth.residual *= rest / data;  // relative to max|F| (NaN stays NaN)
    out.smooth.coefficient_tail *= rest / data;
    // 16 eps: the images' composite quadratures round to ~10-30 eps of their size (measured: the
    // residual relative to max|F| over eps max|remainder|/max|F|, 12-32 on the tests' cases).
    out.rounding_floor = max(out.rounding_floor, 16 * std::numeric_limits<Real>::epsilon() * rest / data);
  } else {
    out.rounding_floor = std::numeric_limits<Real>::infinity();
  }
  // int g = int series + sum int C phi cancels as well: 256 eps of the terms' integrals (the
  // composite rules of int phi: measured 50-200 eps of their size next to an edge).
  Real terms = 0, total = out.smooth.density.integral();  // total: as kinked_solution::integral
  for (const Real& integral : term_integrals) {
    terms += abs(integral);
    total += integral;
  }
  total = abs(total);
  if (terms > 0)
    out.rounding_floor = total > 0 ? max(out.rounding_floor, 256 * std::numeric_limits<Real>::epsilon() * terms / total)
                                   : std::numeric_limits<Real>::infinity();
  return out;
}
}  // namespace detail

template <class Real, class F>
kinked_solution<Real> solve_kinks(const abel_operator<Real>& op, edge leading, edge trailing, F&& f,
                                  const std::vector<kink<Real>>& kinks, const solve_options<Real>& options = {}) {
  // Solved on the interval moved to [0, L] and moved back. WHY: the terms are large where their
  // factor q grows (next to the far edge) and the series cancels them, so their images must be
  // taken at exactly the interpolation points the series is fitted at; on [lo, hi] the point's
  // reference abscissa comes back from the physical one rounded by ~eps |lo| / h, which that
  // size amplifies (a contact 1.2e-4 long at 0.59: residual 5e-9, against 2e-12 at the origin).
  const abel_operator<Real> local(op.parameters(), Real(0), op.hi() - op.lo());
  std::vector<kink<Real>> moved = kinks;
  for (auto& k : moved) {
    if (!(k.position > op.lo() && k.position < op.hi()))
      throw std::domain_error("rhabel::abel::solve_kinks: a kink's position must lie inside the interval");
    k.position -= op.lo();
    // Rounding must not put a kink inside onto an end.
    const Real margin = std::numeric_limits<Real>::epsilon() * local.hi();
    if (!(k.position >= margin)) k.position = margin;
    if (!(k.position <= local.hi() - margin)) k.position = local.hi() - margin;
  }
  const Real lo = op.lo();
  auto at = [&](const Real& u) { return f(lo + u); };
  auto out = detail::solve_kinks_as_given(local, leading, trailing, at, moved, options);
  auto place = [&](jacobi_density<Real>& d) {
    d.lo = op.lo();
    d.hi = op.hi();
  };
  place(out.smooth.density);
  place(out.smooth.homogeneous);
  for (auto& term : out.terms) place(term.smooth);
  return out;
}

}  // namespace rhabel::abel
