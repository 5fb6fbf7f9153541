// rhabel/abel/step_enrichment.hpp
//
// Solver for A g = F when F jumps at one interior point t0 (the wedge apex), with the local
// singularity of g built in (singular enrichment), so that int_a^t0 g converges spectrally.
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
// class (the image of phi is smooth at the ends). Two choices of q (see "Taylor degree" below):
// the Taylor polynomial (degree K) of w(x0)/w(x) at x0, or, for an apex near an edge, the
// edge-damped factor. C = jump(F~)/(w(x0) J_E);
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
// singularity at x0 is integrated by a Gauss-Laguerre end rule after u = delta e^-t (exact for
// the log; see detail::enrichment_piece). Above the threshold the plain E loses ~ eps/alpha^2 to
// cancellation (measured 1.3e-13 at alpha = 0.01).
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
// the Chebyshev tail of the remainder stalls at rounding_floor = max|q| eps (measured 1-5 x).
// taylor_degree = 0 (default) picks the largest K <= 12 with max|q| <= 1e4
// (max_taylor_amplification), at least 1; the adaptive loop stops as converged once the tail is
// below 4 rounding_floor (before, asymmetric cases ran to max_degree and reported not_converged).
// Edge-damped factor (apex near an edge: automatic K < 5 = min_taylor_degree, i.e. eps = (t0 -
// a)/L beyond ~0.87 or below ~0.13). The Taylor factor then leaves jump-type terms of order K + 1
// <= 5 with coefficients ~ (1 - |x0|)^-(K+1), and the error decayed only like n^-(2K+2-2alpha).
// Instead, with K = 5 (edge_damped_degree; K + 1 even) and u = x - x0, d+- = 1 -+ x0,
//     q = (d+/D+)^del (d-/D-)^gam,   D+- = (1 -+ x) + sigma d+- (u/d+-)^(K+1),   sigma = 1,
// so w q = w(x0) ((1-x)/D+)^del ((1+x)/D-)^gam. D+- > 0 on [-1, 1] (both terms >= 0 and not both
// 0), so q is analytic there; (1 -+ x)/D+- = 1 + O(u^(K+1)) at x0 (no jump-type terms of order
// 1..K); (1 -+ x)/D+- lies in [0, 1], so for del, gam >= 0 (the wedge class nu = -1) max|q| <= 1
// (no amplification at all), and near each end D+- ~ sigma d+- keeps w's edge behaviour. The
// price: the zeros of D+ lie at u ~ d+ e^(+-i 21 deg) (0.85 d+ from x0, 0.3 d+ off the axis, for
// K = 5), so the images are analytic only in a region of size ~ d+ around the apex and the
// error decays geometrically at a rate ~ sqrt(d+) (points ~ 1/sqrt(1 - |x0|)) instead of
// algebraically; and the quadratures of phi need K/2 + 28 nodes per panel instead of K/2 + 16
// (with 16 the images stalled at ~1e-9). K = 5 against K = 3, 7 (eps = 0.97, 257 points): 4e-11
// against 2.5e-9, 5e-9; sigma = 0.1 gave 7.7e-11, sigma = 10 1e-8. If a negative edge exponent makes max|q|
// exceed max_taylor_amplification (the class unbounded at the near edge, (1/D)^del growing where
// D is large), the Taylor factor is kept. With the edge-damped factor rounding_floor is
// max(max|q|, 64) eps: the tails of its images plateau at 1e-14 .. 1e-13 (measured).
//
// Accuracy and cost (command: build-step4/bin/study_abel_convergence out.csv, CSV rows
// step_adaptive_*, step_apex_eps_*, step_apex_rh_eps_*; default options as the punch layer calls
// it; median wall time, residual off, measured with the machine's 2 cores shared by ~5 jobs
// (load 5), so times are +-30%).
// Step at t0 = 0.1 on [-1, 1], beta = 0.2, relative error of int g against the exact Rodrigues
// value (int_a^t0 g against the degree-257 solution: same level):
//     alpha = 0, 1e-3 (normalized path):      65 points, <= 1.1e-15,   0.83-0.97 ms
//     alpha = 1e-8 (not in the study; thread CPU time of the same solve): 65 points, 0.85 ms
//     alpha = 0.01:                             65 / 195 points (nu = 0 / -1), <= 1.2e-13,  0.28 / 0.92 ms
//     alpha = 0.049, 0.05:                      65 / 195 points, <= 1.2e-14,  0.28 / 0.91 ms
//     alpha = 0.25, 0.5, 0.9:                   65 points, <= 9.5e-15,   0.28 ms
// so the target (1e-12 in under 1 ms) is met for every alpha. Before this session (same
// machine, thread CPU time): 0.51 ms at 65 points (17 + 33 + 65 evaluated), 2.0-2.4 ms at alpha <=
// 1e-3. The gains: nested levels starting at 65 (1.7x), and on the normalized path K/2 + 10
// nodes per panel instead of K/2 + 16 and no pow in E_full (|u|^-alpha = 1 + alpha core) and a
// series for exprel at tiny arguments (2.3-2.8x).
// Apex position eps = (t0 - a)/L, wedge data of the class nu = -1 satisfying the orthogonality
// condition (alpha = 0.3, beta = 0.2; rows step_apex_rh_*), max relative error of int g and
// int_a^t0 g against the independent Riemann-Hilbert route riemann::solve_abel_rh (its error
// estimates <= 1e-15 here); n = points, factor = Taylor (K) or edge-damped (K = 5):
//     eps      factor      65 pts     195 pts    585 pts    adaptive (default options)
//     0.5      Taylor 12   1.2e-15    1.2e-15    1.2e-15     66 pts, 1.2e-15, 0.28 ms
//     0.8      Taylor 7    2.5e-11    7.5e-13    8.4e-13    195 pts, 7.5e-13, 0.91 ms
//     0.9      edge 5      2.5e-7     8.6e-12    6.4e-15    585 pts, 6.4e-15, 15 ms
//     0.97     edge 5      1.6e-4     5.1e-9     2.6e-13   1024 pts, 1.1e-14, 44 ms
//     0.99     edge 5      1.4e-3     5.8e-6     9.5e-12   1024 pts, 1.6e-13, 49 ms (not_converged)
//     0.999    edge 5      8.3e-2     3.1e-3     1.1e-5    1024 pts, 2.7e-9,  95 ms (not_converged)
//     0.03     edge 5      1.6e-6     1.1e-10    3.5e-14   1024 pts, 2.5e-14, 88 ms
//     0.001    edge 5      5.1e-3     8.1e-5     2.6e-8    1024 pts, 4.6e-11, 130 ms (not_converged)
// Before (Taylor factor only, doubling levels to 513 points; probe of this session against the
// same RH reference): eps = 0.9: 6.8e-12 at 513 points; 0.97: 1.6e-9 (not_converged); 0.99:
// 3.3e-8; 0.999: 2.5e-5. The punch layer's hardest wedge (alpha = 0.2, k = 0.5, S1 = S2: eps =
// 0.84, Taylor K = 6) converges at 195 points to 1.8e-12 (alpha = 0.2), 1.8e-13 (alpha = 1e-3),
// 1.1e-13 (alpha = 0), in 1.6 / 9 / 9 ms wall (thread CPU: 0.86 / 2.6 / 2.3 ms; before: 257
// points, 4.2 / 12.1 / 11.4 ms CPU). The edge-damped points cost ~2.3x the Taylor ones (K/2 + 28
// nodes per panel and exp/log of D+-).
// The same study with F = +-1 in both classes (rows step_apex_eps_*, error of int g only):
// eps in [0.3, 0.7] converged at 65-66 points, <= 1.5e-12; eps = 0.1, 0.9 converged at 195-585
// points, <= 1.7e-12; eps = 0.01, 0.99 <= 1.6e-13 at 1024 points except nu = 0 at 0.99 (Taylor
// kept: del < 0) 1.4e-12; eps = 1e-3, 0.999: 1e-13 .. 2.7e-9, residual 2e-9 .. 4e-6,
// not_converged; eps = 1e-6, 1 - 1e-6: not_converged, error up to 0.27, residual 0.02 .. 0.7.
// LIMIT (apex within ~1e-2 L of an edge): the solution then varies on the scale d = min(eps,
// 1 - eps) L next to the apex (locally the step solution of a half-line problem, which is not
// built in); any global polynomial representation needs ~ 1/sqrt(d/L) points to resolve it (the
// Chebyshev spacing there is ~ sqrt(d L)/n). The edge-damped factor makes the convergence
// geometric at that rate (1e-12 needs 585 points at 1 - eps = 0.03, ~1000 at 0.01, more than
// the default max_degree 1024 at 1e-3) instead of algebraic. The solver reports what it did not reach: status not_converged and a residual
// sampled next to the apex (x0 -+ d/2 and d/4, 3d/4 of the way to the near edge), measured
// >= error(int g)/10 in every case above. For eps within 1e-3 of an edge use the Riemann-Hilbert
// route (as the punch layer does).
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
#include <optional>
#include <utility>
#include <vector>

namespace rhabel::abel {

/// g = C phi + w sum c_n P_n on [lo, hi] (see header); evaluations exact up to quadrature rounding.
template <class Real>
struct enriched_density {
  jacobi_density<Real> smooth;   ///< w sum_n c_n P_n^(del,gam)
  Real enrichment = 0;           ///< C
  Real x0 = 0;                   ///< breakpoint in the reference variable
  Real kappa = 0, alpha = 0;
  /// Taylor coefficients of w(x0)/w(x) in powers of (x - x0); edge-damped mode (edge_power > 0):
  /// {1, 0, ..., 0} of size K + 1 (q is then 1 times edge_factor). Evaluate q with q_at.
  std::vector<Real> q;
  /// alpha < 0.01: E is replaced by (E - 1)/alpha (uniform to alpha = 0, where it is
  /// -log|x - x0| - pi tan(beta pi/2) [x > x0]); the "-1/alpha" part is w q, a smooth density.
  bool normalized = false;
  Real one_minus_kappa_over_alpha = 0;

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
  /// Gauss-Jacobi exponent used at x0 for pieces that end there (the rest is E_over_weight).
  Real x0_exponent() const { return normalized ? Real(0) : -alpha; }
  Real E_over_weight(const Real& dist, bool right) const {
    if (!normalized) return right ? kappa : Real(1);
    return E_full(dist, right);
  }
  /// Gap left around x0 by the quadratures: 0 since the normalized mode integrates its
  /// log-type singularity at x0 exactly (Gauss-Laguerre end rule, detail::enrichment_piece);
  /// formerly 1e-18. Kept for source compatibility.
  static Real x0_gap() { return Real(0); }

  /// phi(x) with distances 1 + x, 1 - x (reference variable).
  Real phi(const Real& one_plus_x, const Real& one_minus_x) const {
    using std::pow;
    const Real u = one_plus_x <= one_minus_x ? one_plus_x - (1 + x0) : (1 - x0) - one_minus_x;
    const Real E = u > 0 ? E_full(u, true) : E_full(-u, false);
    return pow(one_minus_x, smooth.del) * pow(one_plus_x, smooth.gam) * q_at(one_plus_x, one_minus_x) * E;
  }

  /// g(t), lo < t < hi, t != t0.
  Real operator()(const Real& t) const {
    const Real h = half_length();
    return smooth(t) + enrichment * phi((t - smooth.lo) / h, (smooth.hi - t) / h);
  }

  /// int_{-1}^{X} phi dx (reference variable), X in [-1, 1].
  Real phi_integral_to(const Real& X) const;

  /// int_lo^hi f(t) g(t) dt for f smooth between the breakpoints (t0 is always a cut).
  /// Moments: f(t) = t^k. Composite Gauss-Jacobi with the exponents -alpha at t0, gam, del at
  /// the ends as weights, graded toward every singular point.
  template <class Fn>
  Real integrate(Fn&& f, std::vector<Real> breakpoints = {}) const;

  Real integral() const { return smooth.integral() + enrichment * half_length() * phi_integral_to(Real(1)); }

  /// q(x) (the Taylor polynomial) at x.
  Real q_at(const Real& x) const { return q_at(1 + x, 1 - x); }
  /// q at the point with distances 1 + x, 1 - x to the ends (accurate next to an end).
  Real q_at(const Real& one_plus_x, const Real& one_minus_x) const {
    const Real u = one_plus_x <= one_minus_x ? one_plus_x - (1 + x0) : (1 - x0) - one_minus_x;
    Real qq = 0;
    for (std::size_t k = q.size(); k-- > 0;) qq = qq * u + q[k];
    if (edge_power == 0) return qq;
    return qq * edge_factor(one_plus_x, one_minus_x, u);
  }
  /// Edge-damped mode (edge_power = K + 1 > 0, even): q = ((1-x0)/D+)^del ((1+x0)/D-)^gam,
  /// D+- = (1 -+ x) + sigma (1 -+ x0) (u/(1 -+ x0))^(K+1) (see header).
  Real edge_factor(const Real& one_plus_x, const Real& one_minus_x, const Real& u) const {
    using std::exp;
    using std::log;
    const Real dp = 1 - x0, dm = 1 + x0;
    Real tp = u / dp, tm = u / dm, pp = 1, pm = 1;
    for (std::size_t k = 0; k < edge_power; ++k) pp *= tp, pm *= tm;
    // D+-/d+- = (1 -+ x)/d+- + sigma t^(K+1): a sum of two non-negative terms (no cancellation).
    // One exp and two logs instead of two pow calls (pow of a base near 1 was 70% of the cost).
    return exp(-smooth.del * log(one_minus_x / dp + edge_sigma * pp) - smooth.gam * log(one_plus_x / dm + edge_sigma * pm));
  }
  std::size_t edge_power = 0;   ///< 0: q is the Taylor polynomial; K + 1 (even): edge-damped q
  Real edge_sigma = 1;
  /// Gauss nodes per panel of the quadratures of phi (split_integrator callers use 4 fewer):
  /// K/2 + 16 for the Taylor factor; K/2 + 10 in normalized mode (alpha < 0.01: measured
  /// <= 1e-15 in int g, 20% faster); K/2 + 28 for the edge-damped factor, whose complex zeros of
  /// D+- lie ~0.3 (1 - |x0|) from the real axis (with K/2 + 16 the images stalled at 1e-9).
  std::size_t quadrature_nodes() const { return q.size() / 2 + (edge_power != 0 ? 28 : (normalized ? 10 : 16)); }
  /// Leading-edge intensity lim g (t-a)^(-gam): smooth part plus C 2^del q(-1) E(-1), times (2/L)^gam.
  Real intensity_leading() const {
    using std::pow;
    return smooth.intensity_leading() +
           enrichment * pow(2 / (smooth.hi - smooth.lo), smooth.gam) * pow(Real(2), smooth.del) * q_at(Real(-1)) *
               E_full(1 + x0, false);
  }
  /// Trailing-edge intensity lim g (b-t)^(-del): smooth part plus C 2^gam q(1) E(+1), times (2/L)^del.
  Real intensity_trailing() const {
    using std::pow;
    return smooth.intensity_trailing() +
           enrichment * pow(2 / (smooth.hi - smooth.lo), smooth.del) * pow(Real(2), smooth.gam) * q_at(Real(1)) *
               E_full(1 - x0, true);
  }

  /// int_lo^t g.
  Real integral_to(const Real& t) const {
    const Real h = half_length();
    if (!(t > smooth.lo)) return Real(0);
    const Real X = t >= smooth.hi ? Real(1) : -1 + (t - smooth.lo) / h;
    return smooth.integral_to(t) + enrichment * h * phi_integral_to(X);
  }
};

template <class Real>
struct enriched_solution {
  enriched_density<Real> density;
  edge_exponents<Real> exponents{};
  Real solvability_defect = 0;  ///< nu = -1: image-P_0 coefficient of the remainder data
  Real residual = std::numeric_limits<Real>::quiet_NaN();
  Real coefficient_tail = 0;
  std::size_t degree = 0;
  solve_status status = solve_status::converged;
  /// K, the order of the local expansion built into phi (Taylor or edge-damped factor: see
  /// density.edge_power).
  std::size_t taylor_degree = 0;
  /// Estimated relative rounding floor of the Chebyshev tail, max|q| eps over [-1, 1] (edge-damped
  /// factor: max(max|q|, 64) eps, its quadrature plateau): the adaptive loop stops (converged) once
  /// the tail is below 4x this even if options.tolerance is smaller. An estimate, not a bound.
  Real rounding_floor = 0;
};

/// solve_step uses the normalized enrichment (E - 1)/alpha below this alpha. Above it the plain
/// enrichment E loses ~ eps/alpha^2 to cancellation (C = O(1/alpha), A[E] = O(1/alpha)): measured
/// agreement of the two paths 1.3e-13 at alpha = 0.01, 5e-15 at 0.03 (int g, int_a^t0 g), at
/// ~1-2 ms instead of 3-8 ms. (Formerly 0.05.)
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

/// Below this automatic Taylor degree solve_step switches to the edge-damped factor.
template <class Real>
std::size_t min_taylor_degree() {
  return 5;
}
/// K of the edge-damped factor (odd: K + 1 even keeps D+- > 0 on [-1, 1]).
template <class Real>
std::size_t edge_damped_degree() {
  return 5;
}

namespace detail {

/// Composite quadrature of int_{-1}^{1} over pieces split at the sorted points, with the
/// end exponent of each piece taken as Gauss-Jacobi weight (see header).
template <class Real>
class split_integrator {
 public:
  explicit split_integrator(std::size_t nodes) : nodes_(nodes) {}
  std::size_t nodes() const { return nodes_; }

  /// points: sorted interior break/singular points in (-1, 1) with the exponent of the
  /// singularity there on its left side and right side; ends with exponents (q at -1, p at +1).
  /// f(x, one_plus_x, one_minus_x, distances...) must return the integrand WITHOUT the end
  /// factors of the current piece; `piece_factor(x, piece_index, dist_left_end, dist_right_end)`
  /// is given the distances to both ends of the piece.
  template <class F>
  Real integrate(const std::vector<Real>& cuts, const std::vector<Real>& left_exponent,
                 const std::vector<Real>& right_exponent, F&& f) const {
    // cuts[0] = -1, cuts.back() = 1; piece k = [cuts[k], cuts[k+1]] with weight
    // (x - cuts[k])^left_exponent[k] (cuts[k+1] - x)^right_exponent[k].
    const Real inf = std::numeric_limits<Real>::infinity();
    Real sum = 0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const Real len = cuts[k + 1] - cuts[k];
      if (!(len > 0)) continue;
      const auto& rule = integrator(right_exponent[k], left_exponent[k]);
      const Real d_left = k == 0 ? inf : cuts[k] - cuts[k - 1];
      const Real d_right = k + 2 == cuts.size() ? inf : cuts[k + 2] - cuts[k + 1];
      sum += rule.integrate(len, d_left, d_right, [&](const Real& u, const Real& v) { return f(k, u, v); });
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

/// max |q(x)| over [-1, 1] (q from inverse_weight_taylor, in powers of x - x0), on the ends and
/// 64 first-kind Chebyshev points: the factor by which C phi exceeds its value at the apex far
/// from it. The smooth part of g cancels it there, so rounding errors of relative size eps in
/// A[phi] and in phi become errors of size ~ max|q| eps in g (the measured floor of the
/// Chebyshev tail is 1-5 x max|q| eps).
template <class Real>
Real taylor_amplification(const std::vector<Real>& q, const Real& x0) {
  using std::abs;
  auto at = [&](const Real& x) {
    Real v = 0;
    for (std::size_t k = q.size(); k-- > 0;) v = v * (x - x0) + q[k];
    return abs(v);
  };
  Real biggest = std::max(at(Real(-1)), at(Real(1)));
  const chebyshev_grid<Real> grid(64);
  for (const Real& x : grid.x) biggest = std::max(biggest, at(x));
  return biggest;
}

/// A~[phi](y) (reference interval, without (L/2)^alpha) by split composite quadrature.
template <class Real>
Real enrichment_image(const enriched_density<Real>& d, const abel_parameters<Real>& par, const split_integrator<Real>& si_in,
                      const Real& y) {
  // The edge-damped factor needs more nodes than a caller sized for a Taylor polynomial may give.
  std::optional<split_integrator<Real>> own;
  if (si_in.nodes() + 4 < d.quadrature_nodes()) own.emplace(d.quadrature_nodes() - 4);
  const split_integrator<Real>& si = own ? *own : si_in;
  using std::pow;
  const Real alpha = par.alpha(), kappa = par.kappa();
  const Real x0 = d.x0;
  std::vector<Real> cuts{Real(-1)}, left_exp, right_exp;
  // Kinds of interior points: 0 = x0 (exponent -alpha), 1 = y (exponent alpha - 1).
  std::vector<int> kind;
  if (y < x0) {
    cuts.push_back(y), kind.push_back(1);
    cuts.push_back(x0), kind.push_back(0);
  } else {
    cuts.push_back(x0), kind.push_back(0);
    cuts.push_back(y), kind.push_back(1);
  }
  cuts.push_back(Real(1));
  auto exponent_of = [&](int k) { return k == 0 ? -alpha : alpha - 1; };
  left_exp = {d.smooth.gam, exponent_of(kind[0]), exponent_of(kind[1])};
  right_exp = {exponent_of(kind[0]), exponent_of(kind[1]), d.smooth.del};
  return si.integrate(cuts, left_exp, right_exp, [&](std::size_t k, const Real& u, const Real& v) {
    // Node at distance u from cuts[k], v from cuts[k+1].
    // Distances to every singular point, accurate near the piece ends.
    auto distance_to = [&](std::size_t point) -> Real {  // point index into cuts
      if (point == k) return u;
      if (point == k + 1) return v;
      if (point < k) return (cuts[k] - cuts[point]) + u;
      return (cuts[point] - cuts[k + 1]) + v;
    };
    Real value = 1;
    const Real one_plus_x = distance_to(0), one_minus_x = distance_to(3);
    if (k != 0) value *= pow(one_plus_x, d.smooth.gam);
    if (k != 2) value *= pow(one_minus_x, d.smooth.del);
    for (std::size_t point = 1; point <= 2; ++point) {
      const bool is_end = point == k || point == k + 1;
      const bool right_of_point = k >= point;  // node lies right of this point
      if (kind[point - 1] == 0) {
        const Real coef = right_of_point ? kappa : Real(1);
        value *= is_end ? coef : coef * pow(distance_to(point), -alpha);
      } else {
        const Real coef = right_of_point ? Real(1) : -kappa;  // kernel: (x-y)^(alpha-1) for x > y
        value *= is_end ? coef : coef * pow(distance_to(point), alpha - 1);
      }
    }
    return value * d.q_at(one_plus_x, one_minus_x);
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
/// log-singular at x0 and not a Gauss-Jacobi weight. The sub-piece [0, delta] next to x0
/// (delta = 1/16 of the distance to every other singular point) is integrated after the
/// substitution u = delta e^-t by 32-point Gauss-Laguerre: e^-t times a polynomial in t (the
/// log) times a function analytic in e^-t with radius >= 16 (terms (e^-t/16)^k, each integrated
/// to <= 3e-16 relative by 32 nodes; tests: "Gauss-Laguerre end rule"); e^{alpha t} from
/// |u|^-alpha is entire. The rest is
/// graded toward x0 from distance delta (a few panels). This replaces the former geometric
/// grading down to a gap of 1e-18 (~60 panels per piece) and cuts the cost of the small-alpha
/// path by ~5 (26 -> 5 ms at alpha = 0, measured with the Gauss-Jacobi rule cache; now ~0.9 ms
/// for a whole 65-point solve, see the header).
enum class piece_end { interval_end, x0, interior };

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
  return rule.integrate(b - a, d_left, d_right, [&](const Real& u, const Real& v) {
    const Real one_plus_x = (a + 1) + u, one_minus_x = (1 - b) + v;
    const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
    Real value = 1;
    if (a_end != piece_end::interval_end) value *= pow(one_plus_x, d.smooth.gam);
    if (b_end != piece_end::interval_end) value *= pow(one_minus_x, d.smooth.del);
    const Real dist = right_side ? (a - d.x0) + u : (d.x0 - b) + v;
    const bool at_x0 = right_side ? a_end == piece_end::x0 : b_end == piece_end::x0;
    value *= at_x0 ? d.E_over_weight(dist, right_side) : d.E_full(dist, right_side);
    return value * d.q_at(one_plus_x, one_minus_x) * k(x, u + offset_a, v + offset_b);
  });
}

template <class Real, class K>
Real enrichment_piece(const enriched_density<Real>& d, const Real& a, const Real& b, piece_end a_end, piece_end b_end,
                      const Real& d_left, const Real& d_right, K&& k) {
  using std::exp;
  using std::min;
  using std::pow;
  if (!(b > a)) return Real(0);
  const bool x0_at_a = a_end == piece_end::x0, x0_at_b = b_end == piece_end::x0;
  if (!d.normalized || !(x0_at_a || x0_at_b))
    return enrichment_piece_panels(d, a, b, a_end, b_end, d_left, d_right, Real(0), Real(0), k);
  const Real len = b - a;
  // Other singular points: the far end of the piece (at distance len), whatever lies beyond it,
  // and the nearest singular point across x0.
  const Real delta = min(len, x0_at_a ? d_left : d_right) / 16;
  const auto& lag = gauss_laguerre_rule<Real>(32);
  // int_0^delta G(u) du = delta int_0^inf e^-t G(delta e^-t) dt (u = delta e^-t: the distance
  // from x0, exact however small).
  Real near = 0;
  for (std::size_t i = 0; i < lag.x.size(); ++i) {
    const Real dist = delta * exp(-lag.x[i]);
    const Real u = x0_at_a ? dist : len - dist, v = x0_at_a ? len - dist : dist;
    const Real one_plus_x = (a + 1) + u, one_minus_x = (1 - b) + v;
    const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
    const Real value = pow(one_plus_x, d.smooth.gam) * pow(one_minus_x, d.smooth.del) * d.E_full(dist, x0_at_a);
    near += lag.weight[i] * value * d.q_at(one_plus_x, one_minus_x) * k(x, u, v);
  }
  near *= delta;
  if (x0_at_a)
    return near + enrichment_piece_panels(d, a + delta, b, piece_end::interior, b_end, delta, d_right, delta, Real(0), k);
  return near + enrichment_piece_panels(d, a, b - delta, a_end, piece_end::interior, d_left, delta, Real(0), delta, k);
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
Real enriched_density<Real>::integrate(Fn&& f, std::vector<Real> breakpoints) const {
  using detail::piece_end;
  const Real h = half_length();
  Real total = smooth.integrate(f, breakpoints);
  const Real inf = std::numeric_limits<Real>::infinity();
  // Cuts: the ends, x0 (two-sided) and the breakpoints.
  std::vector<Real> cuts{Real(-1), Real(1)};
  for (const Real& b : breakpoints)
    if (b > smooth.lo && b < smooth.hi) {
      const Real xb = -1 + (b - smooth.lo) / h;
      if (xb != x0) cuts.push_back(xb);
    }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  std::vector<Real> left_cuts, right_cuts;
  for (const Real& c : cuts) {
    if (c < x0) left_cuts.push_back(c);
    if (c > x0) right_cuts.push_back(c);
  }
  const piece_end at_x0 = piece_end::x0;
  auto factor = [&](const Real& x, const Real&, const Real&) {
    const Real t = smooth.lo + h * (x + 1);
    return f(t);
  };
  Real sum = 0;
  left_cuts.push_back(x0);
  for (std::size_t k = 0; k + 1 < left_cuts.size(); ++k) {
    const Real a = left_cuts[k], b = left_cuts[k + 1];
    const bool last = k + 2 == left_cuts.size();
    sum += detail::enrichment_piece(*this, a, b, k == 0 ? piece_end::interval_end : piece_end::interior,
                                    last ? at_x0 : piece_end::interior, k == 0 ? inf : a + 1,
                                    last ? 1 - x0 : std::min(x0 - b, 1 - b), factor);
  }
  right_cuts.insert(right_cuts.begin(), x0);
  for (std::size_t k = 0; k + 1 < right_cuts.size(); ++k) {
    const Real a = right_cuts[k], b = right_cuts[k + 1];
    const bool last = k + 2 == right_cuts.size();
    sum += detail::enrichment_piece(*this, a, b, k == 0 ? at_x0 : piece_end::interior,
                                    last ? piece_end::interval_end : piece_end::interior,
                                    k == 0 ? x0 + 1 : std::min(a - x0, a + 1), last ? inf : 1 - b,
                                    factor);
  }
  return total + enrichment * h * sum;
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
  auto kernel_left_of_y = [&](const Real& b) {  // piece ending at b <= ya
    return [&, b](const Real&, const Real&, const Real& v) { return -kappa * pow((y - b) + v, alpha - 1); };
  };
  auto kernel_right_of_y = [&](const Real& a) {
    return [&, a](const Real&, const Real& u, const Real&) { return pow((a - y) + u, alpha - 1); };
  };
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

/// A~[phi](y) in either mode.
template <class Real>
Real enrichment_image_any(const enriched_density<Real>& d, const abel_parameters<Real>& par,
                          const split_integrator<Real>& si, const Real& y) {
  return d.normalized ? enrichment_image_uniform(d, par, y) : enrichment_image(d, par, si, y);
}

}  // namespace detail

/// A g at any s (inside: spectral part + direct quadrature of A[phi]; outside [lo, hi]: the
/// surface-slope formula, paper 27-28, by graded quadrature). s != t0, lo, hi.
template <class Real>
Real apply(const abel_operator<Real>& op, const enriched_density<Real>& g, const Real& s) {
  using detail::piece_end;
  using std::pow;
  const Real h = op.half_length(), alpha = op.parameters().alpha(), kappa = op.parameters().kappa();
  Real value = op.apply(g.smooth, s);
  const detail::split_integrator<Real> si(g.quadrature_nodes() - 4);
  if (s > op.lo() && s < op.hi()) {
    const Real y = -1 + (s - op.lo()) / h;
    return value + pow(h, alpha) * g.enrichment * detail::enrichment_image_any(g, op.parameters(), si, y);
  }
  const bool below = s <= op.lo();
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

/// Solves A g = F on [lo, hi] for F smooth except for a jump at t0 in (lo, hi) (see header).
/// taylor_degree = 0 (default): automatic factor q (Taylor polynomial of the largest K <= 12 with
/// max|q| <= 1e4, or the edge-damped factor of degree 5 when that K is below 5); taylor_degree =
/// K > 0 forces the Taylor polynomial of degree K. options.degree != 0 fixes the number of
/// sampling points (m or m + 1, see grid_size_avoiding); otherwise adaptive, 65 -> 195 -> 585 ->
/// ... up to options.max_degree points. Returns the density with the evidence: status,
/// coefficient_tail (estimate of the relative error of the image expansion), rounding_floor,
/// residual (an estimate, see header), solvability_defect (nu = -1), degree and taylor_degree.
template <class Real, class F>
enriched_solution<Real> solve_step(const abel_operator<Real>& op, edge leading, edge trailing, F&& f, const Real& t0,
                                   const solve_options<Real>& options = {}, std::size_t taylor_degree = 0) {
  using std::abs;
  using std::cos;
  using std::max;
  using std::pow;
  using std::sin;
  const Real alpha = op.parameters().alpha(), kappa = op.parameters().kappa();
  if (!(t0 > op.lo() && t0 < op.hi()))
    detail::throw_bad_parameter("rhabel::abel::solve_step", "t0", t0, "(lo, hi)");
  const auto e = op.exponents(leading, trailing);
  const Real h = op.half_length();
  const Real scale_F = pow(h, -alpha);
  const Real pi = boost::math::constants::pi<Real>();
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
  const bool auto_degree = taylor_degree == 0;
  if (taylor_degree == 0) {
    // q has radius of convergence 1 - |x0| and grows like ((1 + |x0|)/(1 - |x0|))^K on the far
    // side, which sets a rounding floor ~ max|q| eps (taylor_amplification). Largest K <= 12
    // with max|q| <= max_taylor_amplification (1e4: floor ~ 1e-12), at least K = 1.
    taylor_degree = 1;
    for (std::size_t K = 12; K > 1; --K)
      if (detail::taylor_amplification(detail::inverse_weight_taylor(e.gam, e.del, x0, K), x0) <=
          max_taylor_amplification<Real>()) {
        taylor_degree = K;
        break;
      }
  }
  g.q = detail::inverse_weight_taylor(e.gam, e.del, x0, taylor_degree);
  auto amplification = [&] {  // max |q| on [-1, 1]: the ends and 64 first-kind Chebyshev points
    Real amp = std::max(abs(g.q_at(Real(0), Real(2))), abs(g.q_at(Real(2), Real(0))));
    const detail::chebyshev_grid<Real> grid(64);
    for (std::size_t j = 0; j < 64; ++j) amp = std::max(amp, Real(abs(g.q_at(grid.one_plus_x[j], grid.one_minus_x[j]))));
    return amp;
  };
  if (auto_degree && taylor_degree < min_taylor_degree<Real>()) {
    // Apex near an edge: the edge-damped factor (see header) instead of a short Taylor
    // polynomial, unless it amplifies too (a negative edge exponent: (1/D)^del grows like
    // D^|del| where D is large, far from the apex); then the Taylor factor stays.
    const std::vector<Real> taylor = g.q;
    g.q.assign(edge_damped_degree<Real>() + 1, Real(0));
    g.q[0] = 1;
    g.edge_power = edge_damped_degree<Real>() + 1;
    if (amplification() <= max_taylor_amplification<Real>()) {
      taylor_degree = edge_damped_degree<Real>();
    } else {
      g.q = taylor;
      g.edge_power = 0;
    }
  }
  sol.taylor_degree = taylor_degree;
  // Edge-damped factor: max|q| ~ 1, but the quadrature of its images (complex zeros of D+- near
  // the real axis) leaves a plateau of the tail at 1e-14 .. 1e-13 (measured): floor >= 64 eps.
  sol.rounding_floor = (g.edge_power != 0 ? std::max(amplification(), Real(64)) : amplification()) *
                       std::numeric_limits<Real>::epsilon();
  // Jump of F at t0 from one-sided values (F is evaluated on each side only).
  const Real delta = 64 * std::numeric_limits<Real>::epsilon() * max(abs(t0), op.hi() - op.lo());
  const Real left_value = f(t0 - delta), right_value = f(t0 + delta);
  detail::check_finite_value("rhabel::abel::solve_step", left_value, t0 - delta);
  detail::check_finite_value("rhabel::abel::solve_step", right_value, t0 + delta);
  const Real w0 = pow(1 - x0, e.del) * pow(1 + x0, e.gam);
  g.normalized = alpha < normalized_enrichment_threshold<Real>();
  g.one_minus_kappa_over_alpha = op.parameters().one_minus_kappa_over_alpha();
  Real J_E;
  if (!g.normalized) {
    J_E = pi / sin(pi * alpha) * (1 - 2 * kappa * cos(pi * alpha) + kappa * kappa);
  } else {
    // Jump of A[(E - 1)/alpha] = J_E / alpha, with 1 - 2 kappa cos + kappa^2 =
    // alpha^2 [((1-kappa)/alpha)^2 + 4 kappa (sin(pi alpha/2)/alpha)^2]: uniform, pi^2/cos^2(beta pi/2) at 0.
    const Real m = g.one_minus_kappa_over_alpha;
    const Real sh = alpha == 0 ? pi / 2 : sin(pi * alpha / 2) / alpha;
    const Real ratio = alpha == 0 ? Real(1) : pi * alpha / sin(pi * alpha);
    J_E = ratio * (m * m + 4 * kappa * sh * sh);
  }
  g.enrichment = scale_F * (left_value - right_value) / (w0 * J_E);

  const detail::split_integrator<Real> si(g.quadrature_nodes() - 4);
  const Real p = e.gam + Real(e.nu), qI = e.del + Real(e.nu);
  std::size_t m = options.degree != 0 ? options.degree : std::min(initial_step_sampling_size(), std::max<std::size_t>(options.max_degree, 2));
  std::vector<Real> a;
  Real tail = 0, previous_tail = std::numeric_limits<Real>::infinity();
  // Sampling points stay at least `margin` away from x0 (reference variable): far enough that the
  // side on which F is evaluated (s < t0 or s > t0 in the physical variable, rounded) is the
  // side on which A[phi] is evaluated, however large |t0| is compared with the length.
  using std::sqrt;
  const Real margin = sqrt(std::numeric_limits<Real>::epsilon()) * (1 + max(abs(op.lo()), abs(op.hi())) / h);
  std::size_t used = m;
  // Nested grids: the first-kind grid of size 3m contains the grid of size m (node j is node
  // 3j + 1), so a level reuses the remainder values of the previous one and computes 2m new ones.
  std::vector<Real> values, abs_data;
  for (;;) {
    const std::size_t previous_used = values.size();
    used = detail::grid_size_avoiding(m, x0, margin);
    const bool nested = previous_used != 0 && used == 3 * previous_used;
    const detail::chebyshev_grid<Real> grid(used);
    std::vector<Real> next_values(used), next_abs(used);
    for (std::size_t j = 0; j < used; ++j) {
      if (nested && j % 3 == 1) {
        next_values[j] = values[j / 3];
        next_abs[j] = abs_data[j / 3];
        continue;
      }
      const Real s = grid.one_plus_x[j] <= grid.one_minus_x[j] ? op.lo() + h * grid.one_plus_x[j]
                                                               : op.hi() - h * grid.one_minus_x[j];
      const Real v = f(s);
      detail::check_finite_value("rhabel::abel::solve_step", v, s);
      next_abs[j] = abs(scale_F * v);
      next_values[j] = scale_F * v - g.enrichment * detail::enrichment_image_any(g, op.parameters(), si, grid.x[j]);
    }
    values = std::move(next_values);
    abs_data = std::move(next_abs);
    Real biggest = 0;
    for (const Real& v : abs_data) biggest = max(biggest, v);
    a = detail::chebyshev_coefficients(values);
    const std::size_t tail_start = used - std::max<std::size_t>(2, used / 8);
    tail = 0;
    for (std::size_t k = tail_start; k < used; ++k) tail = max(tail, abs(a[k]));
    if (biggest > 0) tail /= biggest;
    if (options.degree != 0 || tail <= options.tolerance) break;
    // At the rounding floor of the enrichment (4 max|q| eps; measured 1-5 max|q| eps) more points
    // cannot help: converged to that floor (reported in rounding_floor). (Also requiring the
    // tail to stagnate was measured with the former doubling levels: it took 65 -> 513 points at
    // eps = 0.1 without improving int g.)
    if (tail <= 4 * sol.rounding_floor) break;
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
      sol.status = solve_status::not_converged;
      break;
    }
    m = std::min<std::size_t>(3 * used, options.max_degree);
  }
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
  sol.coefficient_tail = tail;
  sol.degree = used;
  if (options.residual_points > 0) {
    // Independent residual: direct quadrature of the one-sided integrals of both parts.
    const typename abel_operator<Real>::quadrature_evaluator direct(op, e.gam, e.del, g.smooth.coefficients.size());
    // Residual points: no node of the sampling grid (residual_grid_size) and none within margin of x0.
    std::size_t r = detail::residual_grid_size(options.residual_points, used);
    while (detail::grid_size_avoiding(r, x0, margin) != r || detail::same_power_of_two(r, used)) ++r;
    const detail::chebyshev_grid<Real> grid(r);
    // Points as (1 + y, 1 - y): the interior Chebyshev points, plus four points that see an apex
    // close to an edge (where the Chebyshev points are sparse relative to the apex's distance d
    // to the nearer edge): y = x0 -+ d/2 and the points d/4, 3 d/4 of the way from x0 to that edge.
    std::vector<std::pair<Real, Real>> points;
    for (std::size_t j = 0; j < grid.x.size(); ++j) points.emplace_back(grid.one_plus_x[j], grid.one_minus_x[j]);
    {
      const Real to_lo = 1 + x0, to_hi = 1 - x0, d = std::min(to_lo, to_hi);
      for (const Real& shift : {-d / 2, d / 2}) points.emplace_back(to_lo + shift, to_hi - shift);
      for (const Real& fraction : {Real(1) / 4, Real(3) / 4}) {
        if (to_lo <= to_hi) points.emplace_back(to_lo * (1 - fraction), to_hi + to_lo * fraction);
        else points.emplace_back(to_lo + to_hi * fraction, to_hi * (1 - fraction));
      }
    }
    const Real defect = e.nu == -1 ? pow(h, alpha) * sol.solvability_defect : Real(0);
    // g.smooth.series with the recurrence coefficients computed once (quadrature::jacobi_series).
    const auto series = g.smooth.series_evaluator();
    Real worst = 0, scale = 0;
    for (const auto& [one_plus_y, one_minus_y] : points) {
      const Real s = one_plus_y <= one_minus_y ? op.lo() + h * one_plus_y : op.hi() - h * one_minus_y;
      const Real y = one_plus_y <= one_minus_y ? one_plus_y - 1 : 1 - one_minus_y;
      const Real Ag = direct([&](const Real& x) { return series(x); }, s) +
                      pow(h, alpha) * g.enrichment * detail::enrichment_image_any(g, op.parameters(), si, y);
      const Real Fs = f(s);
      worst = max(worst, abs(Ag - (Fs - defect)));
      scale = max(scale, abs(Fs));
    }
    sol.residual = scale > 0 ? worst / scale : worst;
  }
  return sol;
}

}  // namespace rhabel::abel
