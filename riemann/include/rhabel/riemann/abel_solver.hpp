// rhabel/riemann/abel_solver.hpp
//
// The Riemann-Hilbert route to the generalized Abel equation (paper eq. 8; docs/theory.md section 1):
//
//     F(s) = int_s^b g(t) (t - s)^(alpha-1) dt - kappa int_a^s g(t) (s - t)^(alpha-1) dt ,  a < s < b,
//     kappa = cos((alpha + beta/2) pi) / cos(beta pi/2),
//
// for 0 <= alpha < 1 (alpha = 0 is the Carleman limit PV int g/(t-s) dt + pi tan(beta pi/2) g(s)),
// 0 <= beta < 1, and F = smooth + steps (piecewise_function: the wedge is one step). This
// solver is INDEPENDENT of rhabel::abel by its METHOD (no spectral relation, no Jacobi expansion
// of F): it solves a Riemann problem with Cauchy integrals and inverts an elementary Abel
// operator; the tests compare the two. Its Gauss-Jacobi rules are those of
// rhabel::quadrature::gauss_jacobi (tested on their own against committed high-precision
// tables): the independence of the two routes rests on the different method, not on a
// private quadrature rule.
//
// Derivation (re-derived and checked numerically, not read off the OCR of the paper; the
// paper's own Phi carries a different factor [(z-a)(b-z)]^(-alpha/2), hence its G = -e^{i pi
// (alpha+beta)} and its z0 construction). Let
//     Phi(z) = (b - z)^(-alpha) int_a^b g(t) (t - z)^(alpha-1) dt = int_a^b g(t) ((t-z)/(b-z))^alpha / (t-z) dt,
// principal powers: analytic in C \ [a, b], Phi(z) ~ -(int g)/z. On the cut, with
// A(x) = int_a^x g (x-t)^(alpha-1) dt and B(x) = int_x^b g (t-x)^(alpha-1) dt,
//     Phi_+-(x) = (b-x)^(-alpha) [B(x) - exp(-+ i pi alpha) A(x)] ,
// so  A = (b-x)^alpha (Phi_+ - Phi_-)/(2 i sin(pi alpha))  and  F = B - kappa A  becomes
//     Phi_+ = G Phi_- + g1 ,   G = -exp(i pi beta) = exp(2 pi i theta), theta = (1 + beta)/2,
//     g1(x) = 2 cos(beta pi/2) exp(i pi beta/2) (b - x)^(-alpha) F(x)
// (using e^{i pi alpha} - kappa = i sin(pi alpha) e^{-i pi beta/2}/cos(beta pi/2)). sin(pi alpha)
// cancels: the problem is uniform as alpha -> 0 and is the Carleman problem at alpha = 0.
// With the canonical function X = (z-a)^m (z-b)^n of riemann_problem.hpp (index 0) and
// Abel's inversion int_a^y g = (sin(pi alpha)/pi) int_a^y A(x) (y-x)^(-alpha) dx:
//     A~(x) := (sin(pi alpha)/pi) A(x) = (b-x)^alpha (Phi_+ - Phi_-)(x) / (2 pi i)
//            = (c/pi) [ s F(x) - (c/pi) (x-a)^m (b-x)^(n+alpha) PV int_a^b w*(t) F(t)/(t-x) dt ],
//     w*(t) = (t-a)^(-m) (b-t)^(-alpha-n),  c = cos(beta pi/2), s = sin(beta pi/2),
//     int_a^y g = int_a^y A~(x) (y-x)^(-alpha) dx                                   (derivative-free)
//     g(y)      = A~(y) (y-a)^(-alpha) + alpha int_a^y (A~(y) - A~(x)) (y-x)^(-alpha-1) dx
//     int_a^b g = (1/(2 pi i)) int rho = -(c/pi) (-1)^j int_a^b w* F ,  j = 1 if n = (beta-1)/2, else 0.
// (For beta = 0 and the class bounded at both ends this is docs/theory.md section 6.)
//
// Index classes (g ~ (t-a)^gam, (b-t)^del; nu = -(gam + del + alpha) = the index):
//   leading (a)  trailing (b)  nu   m = gam + alpha   n = del        how
//   bounded      unbounded      0   (1-beta)/2        (beta-1)/2     Riemann problem of index 0
//   unbounded    bounded        0   -(1+beta)/2       (1+beta)/2     index 0; needs alpha+beta/2 < 1/2
//   bounded      bounded       -1   (1-beta)/2        (1+beta)/2     = the first row when F satisfies
//                                                                     the orthogonality condition
//   unbounded    unbounded     +1   -(1+beta)/2       (beta-1)/2     first row + C g_h, needs
//                                                                     alpha+beta/2 < 1/2
// * nu = -1. The bounded solution exists iff the first-row solution is bounded at b, i.e. iff
//   the (finite-part) orthogonality integral of the paper (20) / docs/theory.md section 4 vanishes. We
//   return the first-row solution and the defect, normalised to be analytic in the parameters
//   (the finite part has a pole at alpha + beta/2 = 1/2):
//       defect = (1/Gamma(1/2 - alpha - beta/2)) FP int_a^b (s-a)^((beta-1)/2) (b-s)^(-(1+beta)/2-alpha) F(s) ds
//              = rgamma(P+1) int (s-a)^Q (b-s)^(P+1) (F(s)-F(b))/(b-s) ds + F(b) L^(P+Q+1) Gamma(Q+1)/Gamma(P+Q+2),
//   P = -(1+beta)/2 - alpha, Q = (beta-1)/2, L = b - a (at alpha+beta/2 = 1/2 it is F(b) L^Q:
//   there the equation is one-sided and the bounded solution needs F(b) = 0).
// * nu = +1. The homogeneous solution is g_h = (t-a)^(-(1+2alpha+beta)/2) (b-t)^((beta-1)/2)
//   (docs/theory.md section 4; C X(z) in the Riemann problem); int g_h = L^(-alpha) B((1-2alpha-beta)/2, (1+beta)/2).
//   options.load fixes C by int g = load; without it C = 0.
//
// Numerics. The PV is jacobi_cauchy_integral (product integration, cauchy_integral.hpp); the
// Abel integrals over [a, y] use composite Gauss-Jacobi rules (rhabel::quadrature::gauss_jacobi
// on [-1, 1], mapped to each panel through the distances 1 -+ x) that carry (x-a)^m on the panel
// touching a and (y-x)^(-alpha) on the panel touching y, geometrically graded (ratio 1/4)
// towards y when b or a step of F is near y, and towards every step of F inside (a, y) (where
// A~ has a logarithmic singularity, lambda log|x - c| with lambda = cos^2(beta pi/2) size/pi^2;
// when y is itself a step, e.g. int_a^0 g for the wedge, that log is integrated exactly).
// Nodes are evaluated at their rounded positions, but every factor that varies on the scale of
// a short panel ((y-x)^(-alpha), (x-a)^m) is formed from the EXACT node offsets (near an end the
// rounding of a node is relatively ~ulp(y)/(distance), 1e-10 at 1e-6 L).
// The density uses the derivative form with a Chebyshev window around y (index0_abel::density):
// A~ is interpolated at n Chebyshev-Lobatto points of [y - H, y + H], H = 1/3 of the distance
// from y to a, b and the steps, and the near part of alpha int (A~(y) - A~(x))(y-x)^(-alpha-1)
// is integrated from the interpolant's divided difference, a polynomial evaluated by a stable
// recurrence; the far part on panels graded (ratio 2) towards y - H. The rounding of A~ is then
// amplified by ~ (n/H)^alpha instead of (n^2/d)^alpha (d = distance of the nearest Gauss node,
// ~ H/n^2, as before this session).
// The far part's breaks y - 2^j H that fall within 2^(j-1) H of a step or of a are left out
// (the step or a is a break itself, with its grading or weight): before this, a panel could end
// 1e-3 of its length before the log singularity of A~ at the wedge apex, ungraded, and g(y) lost
// up to 1e-6 relative at isolated points (the two orders disagreed there; regression test in
// tests/riemann/test_batch_density.cpp).
// Every query is answered at two orders (n and 3n/2, inner and outer) and returns the finer
// value with |difference| as error_estimate: an ESTIMATE, not a bound.
// Many points (abel_rh_solution::densities): the same algorithm and orders, with A~ taken from a
// piecewise Chebyshev interpolant per order built once per call (detail::reduced_interpolant:
// 24 first-kind points per panel in double, 69 at 50 digits; A~/(x-a)^m on the panel at a,
// A~ - sum lambda log|x - c| elsewhere; panels halving each segment between a, the steps and b,
// graded towards b and towards a step until each panel is no longer than its distance to the
// nearest other singular point) instead of one principal value per quadrature node (~1 us
// each, ~120 per g(y) and order). At 50 digits densities() and density() agree to ~2e-28
// (order 12, one case; not in the tests). Both interpolations (the window, Chebyshev-Lobatto,
// and the panels, first kind) are fitted by one routine, detail::chebyshev_fit: the DCT of the
// samples at their rounded abscissae, refined twice by the DCT of the residual.
//
// Usage for step data (the wedge; one call per scene, the punch layer's oracle):
//     piecewise_function<double> F{[&](double) { return S1 / tgamma(1 - alpha); },
//                                  {step<double>{apex, -(S1 + S2) / tgamma(1 - alpha)}}};
//     const auto sol = solve_abel_rh(alpha, beta, a, b, F, edge::bounded, edge::bounded);
//     sol.integral(apex).value;   // int_a^apex g  (error_estimate: two orders)
//     sol.total().value;          // int_a^b g     (moment formula)
//     sol.orthogonality_defect(); // nu = -1: ~0 iff S2/(S1+S2) satisfies the contact condition
//     sol.densities(ys);          // g at many points (pressure samples), one interpolant of A~
// Any number of steps (breakpoints of F) at any positions in (a, b), also within 1e-6 L of an end.
//
// Accuracy (measured in double on this machine, Release, unless said; commands:
// build-rh3/tests/riemann_test_abel_solver, build-rh3/tests/riemann_test_density_table and
// build-rh3/bin/study_riemann_convergence):
//  * int g and int_a^y g: a few eps relative to int g for smooth F in every class, alpha in
//    [0, 0.9], beta in [0, 0.9]: parabola closed form <= 11 eps (also at b - y = 1e-7 L: the
//    weakness near b of the previous session came from rounded nodes and is gone); 50-digit
//    table <= 133 eps (3e-14); rhabel::abel agreement <= 1e-13; at 50 digits <= 1e-45.
//    As alpha -> 1, A~ = O(1 - alpha) is formed from O(1) boundary values: a factor
//    1/(1 - alpha) is lost (alpha = 0.999: ~1e-13 instead of 1e-16).
//  * step data (wedge with an apex at e L from a, e in {1e-6, 1e-3, 0.4, 0.5, 0.999, 1 - 1e-6}):
//    int g against the incomplete-beta closed form <= 64 eps max|F| int w*; int_a^apex g: the two
//    orders agree to <= 32 eps, against rhabel::abel::solve_step (apex at 0.4 L, 0.5 L) <= 2e-14,
//    independent residual of eq. 8 <= 1e-12 (limited by the residual's own quadrature).
//  * g(y), relative to max(|g(y)|, int g / L), smooth F, every class, alpha in [0, 0.9], beta in
//    [0, 0.9] (build-rh3/tests/riemann_test_density_table: 54 cases x 7 points against the
//    45-digit table of tests/data/riemann_density_reference.hpp). The rounding of A~ is amplified
//    by ~ (n/H)^alpha, H = d/3, d = min(y - a, b - y): measured error <= 133 eps (L/d)^alpha.
//    At d >= 0.14 L: <= 50 eps for alpha <= 0.6, <= 550 eps (1.2e-13) at alpha = 0.8, 0.9.
//    At 0.005 L from a: <= 480 eps (alpha <= 0.6), 2.2e3 eps (0.8), 9.3e3 eps (2e-12, 0.9).
//    At 5e-7 L from a: <= 1.1e3 eps (alpha <= 0.6), 9e3 eps (0.8), 3e4 eps (7e-12, 0.9).
//    At 5e-7 L from b, classes unbounded at b: up to 2e4 eps (alpha <= 0.6), 2.7e6 eps (0.9).
//    KNOWN LIMIT at b for the classes bounded at b (g -> 0 while A~ = O(1); the first-row
//    representation of nu = -1 also leaves its (b-t)^((beta-1)/2) component at rounding level):
//    <= 12 eps (L/d)^(alpha + (1-beta)/2); at 5e-7 L from b 3.7e3 eps for alpha = beta = 0,
//    1e5 eps (alpha = 0.6), 1.8e6 eps (4e-10, alpha = 0.8), 3.5e7 eps (8e-9, alpha = 0.9).
//    The spectral solver rhabel::abel is the more accurate side there; the RH route is the more
//    accurate side inside for alpha = beta = 0.9 (spectral 1e-12, RH 1e-14).
//    Prefer int_a^y g when a quantity can be written with it (loads, moments, C_f by parts).
//  * densities() against density(): <= 2.2e-13 relative to max(|g|, int g / L) (wedge step data,
//    apex 0.5 .. 1e-3 L from an edge, points 1e-6 from the apex and the ends) and within
//    test_density_table's tolerances against the 45-digit table (tests/riemann/
//    test_batch_density.cpp). Wedge (alpha 0.2, S1 = S2, apex 0.25 L from b) after the far-panel
//    fix: g(y) against abel::solve_step 1.2e-12 .. 5.5e-12 relative (solve_step's own level), the
//    two orders within 1e-15 .. 1e-13, where 1e-9 .. 1e-6 before.
//  * hard alphas: 1e-3 and 0 (the Carleman limit) lose nothing; 0.5 -+ 1e-9 (kappa through 0)
//    loses nothing (the single-power integral K(q, .) is uniform through q = 0); 0.999 loses
//    1/(1 - alpha) in int g and ~1/(1 - alpha)^2 in g.
// Cost (double, Release, 2 busy cores; study_riemann_convergence "seconds"): construction
// 2-15 ms; int_a^y g 0.2 ms (smooth F) to 1-20 ms (steps, graded panels); g(y) (n window
// samples + graded far panels, two orders) 0.1-10 ms; 50 digits ~100x more. densities():
// 13-115 us per point (CPU, load ~5; wedge step data, 1000 points, apex 0.5 .. 0.01 L from an
// edge, the most where the points lie beyond the apex, whose log singularity the far part
// grades to rounding level) against 70-1400 us per point for density(); the interpolants cost
// ~0.3-0.5 ms per order (20-30 panels x 24 principal values).
//
// Bad input (alpha outside [0,1), beta outside [0,1), a >= b, a class that does not exist for
// these parameters, y outside [a, b], a density point on a step) throws std::domain_error
// naming the function, the parameter, its value and the valid range.
#pragma once

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/riemann/riemann_problem.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/special_functions/next.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace rhabel::riemann {

/// Behaviour of g at an end of the contact interval.
enum class edge { bounded, unbounded };

enum class abel_status {
  converged,                    ///< every estimate below options.tolerance (relative)
  orthogonality_not_satisfied,  ///< nu = -1 and |defect| > tolerance x its scale: no bounded solution
  not_converged,                ///< the two orders disagree by more than options.tolerance
};

/// A value and an estimate of its error (|value at order n - value at order 3n/2|).
template <class Real>
struct estimated {
  Real value;
  Real error_estimate;
};

template <class Real>
struct abel_rh_options {
  std::size_t order = 0;                ///< Gauss nodes per panel, PV and Abel integrals (0 = default)
  std::optional<Real> load;             ///< nu = +1: int g = load fixes the free constant
  Real tolerance = 1000 * std::numeric_limits<Real>::epsilon();  ///< for the status only
};

namespace detail {

// Chebyshev interpolation at rounded abscissae, shared by index0_abel::density_with (the window
// around y, Chebyshev-Lobatto points) and reduced_interpolant (the panels of A~, first-kind
// points). The N samples f_j are taken at the representable points x_j nearest to the nominal
// nodes, i.e. at abscissae s'_j = s_j + O(ulp(x)/panel): next to an end or a step A~ varies on
// the scale of the panel, and s'_j - s_j ~ 1e-10 at 1e-6 L. So the coefficients of
// P(s) = sum_k c_k T_k(s) are fitted at the ACTUAL s'_j: the discrete cosine transform of the
// samples, refined twice by the transform of the residual f_j - P(s'_j) (a fixed-point iteration
// that contracts like N^2 max|s'_j - s_j|; three transforms in all). The transforms:
//   lobatto     s_j = cos(pi j/(N-1)):      c_k = (2/(N-1)) sum''_j f_j T_k(s_j), halved for k = 0, N-1
//                                           (DCT-I; sum'' halves the terms j = 0, N-1);
//   first_kind  s_j = cos(pi (j+1/2)/N):    c_k = (2/N) sum_j f_j T_k(s_j), halved for k = 0 (DCT-II).
// T_k(s_j) comes from a table built once (the Lobatto entries from the 2(N-1) values
// cos(pi m/(N-1)), m = k j mod 2(N-1), the first-kind entries cos(pi (j+1/2) k/N) directly).
template <class Real>
class chebyshev_fit {
 public:
  enum class grid { lobatto, first_kind };

  chebyshev_fit() = default;
  chebyshev_fit(std::size_t N, grid kind) : N_(N), kind_(kind), table_(N * N) {
    using std::cos;
    const Real pi = boost::math::constants::pi<Real>();
    if (kind == grid::lobatto) {
      const std::size_t M = N - 1;  // cos(pi m/M), m < 2M, with the argument reduced to [0, pi/2]
      std::vector<Real> cosine(2 * M);
      for (std::size_t m = 0; m < 2 * M; ++m) {
        const std::size_t r = m > M ? 2 * M - m : m;  // cos is even and 2 pi periodic
        cosine[m] = 2 * r > M ? -cos(pi * Real(M - r) / Real(M)) : cos(pi * Real(r) / Real(M));
      }
      for (std::size_t k = 0; k < N; ++k)
        for (std::size_t j = 0; j < N; ++j) table_[k * N + j] = cosine[(k * j) % (2 * M)];
    } else {
      for (std::size_t k = 0; k < N; ++k)
        for (std::size_t j = 0; j < N; ++j) table_[k * N + j] = cos(pi * (Real(j) + Real(1) / 2) * Real(k) / Real(N));
    }
  }

  std::size_t size() const { return N_; }
  /// T_k(s_j) at the nominal node s_j.
  const Real& chebyshev_t(std::size_t k, std::size_t j) const { return table_[k * N_ + j]; }

  /// c_0 .. c_{N-1} of the interpolant of values[j] at abscissae[j] (see above).
  std::vector<Real> coefficients(const std::vector<Real>& values, const std::vector<Real>& abscissae) const {
    const bool lobatto = kind_ == grid::lobatto;
    const Real divisor = Real(lobatto ? N_ - 1 : N_);
    std::vector<Real> c(N_, Real(0)), residual = values;
    for (int sweep = 0; sweep < 3; ++sweep) {
      for (std::size_t k = 0; k < N_; ++k) {
        const Real* row = &table_[k * N_];
        Real sum = 0;
        for (std::size_t j = 0; j < N_; ++j) {
          const Real term = residual[j] * row[j];
          sum += (lobatto && (j == 0 || j + 1 == N_)) ? term / 2 : term;
        }
        const bool single = k == 0 || (lobatto && k + 1 == N_);
        c[k] += (single ? sum : 2 * sum) / divisor;
      }
      for (std::size_t j = 0; j < N_; ++j) residual[j] = values[j] - clenshaw(c, abscissae[j]);
    }
    return c;
  }

  /// sum_k c_k T_k(s) (Clenshaw).
  static Real clenshaw(const std::vector<Real>& c, const Real& s) {
    Real b1 = 0, b2 = 0;
    for (std::size_t k = c.size(); k-- > 1;) {
      const Real b0 = 2 * s * b1 - b2 + c[k];
      b2 = b1;
      b1 = b0;
    }
    return s * b1 - b2 + c[0];
  }

 private:
  std::size_t N_ = 0;
  grid kind_ = grid::lobatto;
  std::vector<Real> table_;  // T_k(s_j) at [k N + j]
};

// One index-0 solution of the Abel equation at one order: Riemann problem + Abel inversion.
template <class Real>
class index0_abel {
 public:
  index0_abel(Real alpha, Real beta, Real a, Real b, const piecewise_function<Real>& F, bounded_end bounded,
              std::size_t order)
      : alpha_(alpha), a_(a), b_(b), F_(F), n_(order), rh_(make_solution(alpha, beta, a, b, F, bounded, order)) {
    using std::cos;
    using std::sin;
    const Real pi = boost::math::constants::pi<Real>();
    c_ = cos(beta * pi / 2);
    s_ = sin(beta * pi / 2);
    m_ = rh_.canonical().exponent_lo;
    legendre_ = quadrature::gauss_jacobi<Real>(n_, Real(0), Real(0));
    at_a_ = quadrature::gauss_jacobi<Real>(n_, Real(0), m_);
    at_y_ = quadrature::gauss_jacobi<Real>(n_, -alpha_, Real(0));
    both_ = quadrature::gauss_jacobi<Real>(n_, -alpha_, m_);
    sigma_ = Real(1) / 4;
    // density()'s Chebyshev-Lobatto window of N = n|1 points: its table T_k(s_j), built once
    // (density() needs 3 N^2 of them per point).
    window_ = chebyshev_fit<Real>(n_ | 1, chebyshev_fit<Real>::grid::lobatto);
  }

  // The node with distances (from_lo, to_hi) to the ends of the panel [u, v], rounded to a
  // representable point strictly inside (a tiny panel next to a, y or a step can otherwise round
  // its nodes onto the end, where A~ is singular or undefined).
  // A panel narrower than two ulps has no interior point: the node then stays inside (a, b) and
  // off the steps (A~(x)/(x-a)^m is smooth, so a neighbouring point serves).
  Real node(const std::pair<Real, Real>& panel, const Real& from_lo, const Real& to_hi) const {
    Real x = from_lo <= to_hi ? panel.first + from_lo : panel.second - to_hi;
    if (!(x > panel.first)) x = boost::math::float_next(panel.first);
    if (!(x < panel.second)) x = boost::math::float_prior(panel.second);
    if (!(x > a_)) x = boost::math::float_next(a_);
    if (!(x < b_)) x = boost::math::float_prior(b_);
    for (const auto& s : F_.steps)
      if (x == s.position) x = panel.second <= s.position ? boost::math::float_prior(x) : boost::math::float_next(x);
    return x;
  }

  // A~ at the node of `panel` with distances (from_lo, to_hi) to its ends, divided by (x-a)^m
  // on the panel touching a (whose rule carries that weight). The node is evaluated at its
  // rounded position x (node()), which differs from the exact node by up to ulp(x)/2: relatively
  // ~1e-10 of x - a at 1e-6 from a, where A~ ~ (x-a)^m varies on the scale x - a. Since
  // A~(x)/(x-a)^m is smooth on the scale of L, it is taken at x and multiplied by the EXACT
  // (x-a)^m (from the exact distances); all factors in y - x are likewise formed from the exact
  // distances by the callers. (Near b, A~ = smooth + (b-x)^k smooth has no such one-term
  // correction: the residual sensitivity ulp(x)/(b - x) is a documented limit.)
  Real sample(const std::pair<Real, Real>& panel, const Real& from_lo, const Real& to_hi, bool at_a) const {
    using std::pow;
    const Real x = node(panel, from_lo, to_hi);
    Real value = reduced(x);
    if (at_a) return value / pow(x - a_, m_);
    const Real exact = (panel.first - a_) + from_lo;
    return exact == x - a_ ? value : value * pow(exact / (x - a_), m_);
  }

  // A~(x) = (b-x)^alpha (Phi_+ - Phi_-)/(2 pi i) in its real form (file header)
  //     A~ = (c/pi) [s F(x) - (c/pi) (x-a)^m (b-x)^(n+alpha) PV int w* F/(t-x) dt]
  // (one principal value; the complex form Im(Phi_+ - Phi_-) cancels terms of size |rho X| ~
  // (x-a)^(-m) |A~| next to a: 1e-12 relative at 1e-7 L from a; the two forms were checked to
  // agree to 1e-14 in every row).
  Real reduced(const Real& x) const {
    using std::pow;
    const Real pi = boost::math::constants::pi<Real>();
    const Real n = rh_.canonical().exponent_hi;
    return c_ / pi * (s_ * F_(x) - c_ / pi * pow(x - a_, m_) * pow(b_ - x, n + alpha_) * rh_.cauchy().principal_value(x));
  }

  Real total() const {
    // (1/(2 pi i)) int rho
    return rh_.orthogonality_defect().real();
  }

  // int_a^y g
  Real integral(const Real& y) const {
    using std::pow;
    using std::log;
    if (y == a_) return Real(0);
    // y on a step at c: A~(x) = lambda log(c - x) + (continuous) near c, lambda = cos^2(beta pi/2) size/pi^2
    // (the step's PV contributes -size w*(c) log|x - c| and (x-a)^m (b-x)^(n+alpha) w*(c) = 1 at c;
    // the slope of A~ against log(c - x) was checked numerically: before this session lambda
    // carried one factor cos(beta pi/2), harmless because the panels are graded towards the step);
    // the log is integrated exactly against (y-x)^(-alpha) on the panel touching y.
    Real lambda = 0;
    for (const auto& s : F_.steps)
      if (s.position == y) lambda += log_coefficient(s.size);
    Real sum = 0;
    for (const auto& panel : panels(y)) {
      const bool at_a = panel.first == a_, at_y = panel.second == y;
      const auto& standard = at_a ? (at_y ? both_ : at_a_) : (at_y ? at_y_ : legendre_);
      const Real half = (panel.second - panel.first) / 2;
      const Real scale = pow(half, (at_a ? m_ : Real(0)) + (at_y ? -alpha_ : Real(0)) + 1);
      for (std::size_t i = 0; i < standard.size(); ++i) {
        const Real from_lo = standard.x_minus_lo[i] * half, to_hi = standard.hi_minus_x[i] * half;
        const Real distance_to_y = at_y ? to_hi : (y - panel.second) + to_hi;  // exact node
        Real f = sample(panel, from_lo, to_hi, at_a);
        if (at_y && lambda != 0) f -= lambda * log(distance_to_y);
        if (!at_y) f *= pow(distance_to_y, -alpha_);
        sum += standard.weight[i] * scale * f;
      }
      if (at_y && lambda != 0) {
        // int_0^h log(u) u^(-alpha) du = h^(1-alpha) [log h/(1-alpha) - 1/(1-alpha)^2]
        const Real h = panel.second - panel.first, e = 1 - alpha_;
        sum += lambda * pow(h, e) * (log(h) / e - 1 / (e * e));
      }
    }
    return sum;
  }

  // g(y), a < y < b, off the steps: Abel's inversion in derivative form (file header),
  //     g(y) = A~(y) (y-a)^(-alpha) + alpha int_a^y (A~(y) - A~(x)) (y-x)^(-alpha-1) dx ,
  // evaluated WITHOUT divided differences of computed A~ at short distances (those amplify the
  // rounding of A~ by (distance)^(-alpha): 1e-12..1e-7 relative for alpha >= 0.6 with Gauss
  // nodes clustered at y). On the window [y - H, y + H], H = 1/3 of the distance from y to a,
  // b and the steps of F (A~ is analytic there: Bernstein ratio 3 + sqrt 8), A~ is replaced by
  // its Chebyshev interpolant P(y + H s) = sum'' c_k T_k(s) at n Chebyshev-Lobatto points, and
  //     (A~(y) - A~(x)) / (y - x) = (1/H) sum c_k D_k(s),  D_k(s) = (T_k(s) - T_k(0))/s,
  // D_0 = 0, D_1 = 1, D_{k+1} = 2 T_k - D_{k-1} (from T_{k+1} = 2 s T_k - T_{k-1}, T_{k+1}(0) =
  // -T_{k-1}(0)): a polynomial evaluated by a stable recurrence, never a cancelling difference.
  // The nearest sample of A~ is then H/n from y (not H/n^2), and the rounding of A~ is amplified
  // by ~ (n/H)^alpha instead of (n^2/H)^alpha. With u = (y - x)/H,
  //     g(y) = A~(y) H^(-alpha) + alpha H^(-alpha) int_0^1 sum c_k D_k(-u) u^(-alpha) du
  //            - alpha int_a^(y-H) A~(x) (y-x)^(-alpha-1) dx
  // (the A~(y) terms of the far part integrate in closed form and combine with A~(y)(y-a)^(-alpha)).
  // The far integral uses panels graded geometrically (ratio 2) towards y - H, so each panel
  // sees the singularity at y at a distance >= its length, and towards every step of F.
  Real density(const Real& y) const { return density_with(y, *this); }

  // density() with A~ taken from `source` (source.reduced(x), source.sample(panel, from_lo,
  // to_hi, at_a) as this class defines them): *this, or the piecewise Chebyshev interpolant
  // of A~ used by abel_rh_solution::densities (reduced_interpolant below).
  template <class Source>
  Real density_with(const Real& y, const Source& source) const {
    using std::abs;
    using std::pow;
    using std::sin;
    const Real ay = source.reduced(y);
    if (alpha_ == 0) return ay;
    const Real pi = boost::math::constants::pi<Real>();
    Real distance = std::min<Real>(y - a_, b_ - y);
    for (const auto& s : F_.steps) distance = std::min<Real>(distance, abs(s.position - y));
    // H = y - (y - distance/3) as rounded: the far part ends at the representable point y - H and
    // the near part starts there. (Next to an end the integrand of the far part is ~H^(-alpha-1)
    // at y - H, so a split point off by ulp(y)/2 would cost ~ulp(y) H^(-alpha-1) |A~|: 1e-10
    // relative at 1e-6 from a, alpha = 0.6.) H itself is exact when y - H and y are within a
    // factor 2 (Sterbenz), i.e. whenever H is small; otherwise its rounding is relative eps.
    const Real H = y - (y - distance / 3);
    // Chebyshev-Lobatto samples s_j = cos(j pi/(N-1)) = sin(pi (N-1-2j) / (2(N-1))) (exactly
    // symmetric, s = 0 exact). The sample y + H s_j is rounded to a representable x_j; next to a
    // or b, A~ varies on the scale of H itself while x_j moves by up to ulp(y)/2 (relatively
    // ~1e-10 of H at 1e-6 from an end), so the interpolant is built at the ACTUAL abscissae
    // s'_j = (x_j - y)/H (chebyshev_fit).
    const std::size_t N = window_.size();  // n|1, odd: y itself is a sample
    std::vector<Real> values(N), abscissae(N);
    for (std::size_t j = 0; j < N; ++j) {
      const Real s = sin(pi * (Real(N - 1) - 2 * Real(j)) / (2 * Real(N - 1)));
      if (s == 0) {
        values[j] = ay;
        abscissae[j] = 0;
        continue;
      }
      Real x = y + H * s;
      if (!(x > a_)) x = boost::math::float_next(a_);
      if (!(x < b_)) x = boost::math::float_prior(b_);
      values[j] = source.reduced(x);
      abscissae[j] = (x - y) / H;
    }
    const std::vector<Real> coefficients = window_.coefficients(values, abscissae);
    // near part: alpha H^(-alpha) int_0^1 sum c_k D_k(-u) u^(-alpha) du (at_y_ is exact: degree N-2 <= 2n-1)
    Real near = 0;
    for (std::size_t i = 0; i < at_y_.size(); ++i) {
      const Real u = at_y_.hi_minus_x[i] / 2, s = -u;  // weight (1 - v)^(-alpha), u = (1 - v)/2
      Real t_prev = 1, t = s, d_prev = 0, d = 1, sum = coefficients[1];  // T_0, T_1, D_0, D_1
      for (std::size_t k = 1; k + 1 < N; ++k) {
        const Real d_next = 2 * t - d_prev, t_next = 2 * s * t - t_prev;
        sum += coefficients[k + 1] * d_next;
        d_prev = d;
        d = d_next;
        t_prev = t;
        t = t_next;
      }
      near += at_y_.weight[i] * sum;
    }
    near *= pow(Real(2), alpha_ - 1);  // int_0^1 f(u) u^(-alpha) du = 2^(alpha-1) sum w_i f(u_i)
    Real result = (ay + alpha_ * near) * pow(H, -alpha_);
    // far part: - alpha int_a^(y-H) A~(x) (y-x)^(-alpha-1) dx
    for (const auto& panel : far_panels(y, H)) {
      const bool at_a = panel.first == a_;
      const auto& standard = at_a ? at_a_ : legendre_;
      const Real half = (panel.second - panel.first) / 2;
      const Real scale = pow(half, (at_a ? m_ : Real(0)) + 1);
      for (std::size_t i = 0; i < standard.size(); ++i) {
        const Real from_lo = standard.x_minus_lo[i] * half, to_hi = standard.hi_minus_x[i] * half;
        const Real f = source.sample(panel, from_lo, to_hi, at_a) * pow((y - panel.second) + to_hi, -alpha_ - 1);
        result -= standard.weight[i] * scale * alpha_ * f;
      }
    }
    return result;
  }

  const riemann_solution<Real>& riemann() const { return rh_; }
  /// The interval [a, b], the exponent m of A~ ~ (x-a)^m at a, the data F.
  const Real& lo() const { return a_; }
  const Real& hi() const { return b_; }
  const Real& exponent_lo() const { return m_; }
  const piecewise_function<Real>& data() const { return F_; }
  /// lambda = cos^2(beta pi/2) size/pi^2: A~(x) = lambda log|x - c| + (functions analytic on
  /// either side of c) next to a step of F at c of this size (see integral()).
  Real log_coefficient(const Real& size) const {
    const Real pi = boost::math::constants::pi<Real>();
    return c_ * c_ * size / (pi * pi);
  }

 private:
  static riemann_solution<Real> make_solution(Real alpha, Real beta, Real a, Real b, const piecewise_function<Real>& F,
                                              bounded_end bounded, std::size_t order) {
    using std::cos;
    using std::sin;
    const Real pi = boost::math::constants::pi<Real>();
    riemann_problem<Real> problem;
    problem.lo = a;
    problem.hi = b;
    problem.theta = (1 + beta) / 2;
    const Real c = cos(beta * pi / 2);
    problem.data_factor = 2 * c * std::complex<Real>(cos(beta * pi / 2), sin(beta * pi / 2));
    problem.data_exponent_lo = 0;
    problem.data_exponent_hi = -alpha;
    problem.data = F;
    return solve_riemann_problem(problem, 0, bounded, std::complex<Real>(0), order);
  }

  // Panels of [a, y]: breaks at the steps of F inside (a, y) (log singularities of A~), graded
  // towards a step and towards y when b or a step is near y.
  std::vector<std::pair<Real, Real>> panels(const Real& y) const {
    std::vector<Real> breaks{a_};
    for (const auto& s : F_.steps)
      if (s.position > a_ && s.position < y) breaks.push_back(s.position);
    std::sort(breaks.begin(), breaks.end());
    breaks.push_back(y);
    std::vector<std::pair<Real, Real>> result;
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) grade(result, breaks[k], breaks[k + 1], y);
    return result;
  }

  // Appends [u, v] to `result`, cut geometrically (ratio sigma_ = 1/4) towards an end that is a
  // step of F, and towards v = y when b or a step lies within (v - u)/2 beyond y; a and the other
  // breaks need no grading.
  void grade(std::vector<std::pair<Real, Real>>& result, const Real& u, const Real& v, const Real& y) const {
    using std::abs;
    auto is_step = [&](const Real& e) {
      for (const auto& s : F_.steps)
        if (e == s.position) return true;
      return false;
    };
    const Real eps = std::numeric_limits<Real>::epsilon();
    const Real length = v - u;
    Real beyond = b_ - y;  // distance from y to the nearest singularity beyond it
    for (const auto& s : F_.steps)
      if (s.position >= y) beyond = std::min<Real>(beyond, s.position - y);
    const Real du = is_step(u) ? Real(0) : length;
    const Real dv = is_step(v) ? Real(0) : (v == y ? beyond : length);
    const bool grade_u = du < length / 2, grade_v = dv < length / 2;
    if (!grade_u && !grade_v) {
      result.emplace_back(u, v);
      return;
    }
    const Real middle = grade_u && grade_v ? u + length / 2 : (grade_u ? v : u);
    if (grade_u) {
      // u < ... < middle, geometric towards u
      std::vector<Real> points;
      Real h = (middle - u) * sigma_;
      const Real stop = std::max<Real>({du, (middle - u) * eps, 8 * eps * abs(u)});
      while (h > stop) {
        points.push_back(u + h);
        h *= sigma_;
      }
      Real left = u;
      for (auto it = points.rbegin(); it != points.rend(); ++it) {
        result.emplace_back(left, *it);
        left = *it;
      }
      result.emplace_back(left, middle);
    }
    if (grade_v) {
      std::vector<Real> points;
      Real h = (v - middle) * sigma_;
      const Real stop = std::max<Real>({dv, (v - middle) * eps, 8 * eps * abs(v)});
      while (h > stop) {
        points.push_back(v - h);
        h *= sigma_;
      }
      Real left = middle;
      for (const Real& p : points) {
        result.emplace_back(left, p);
        left = p;
      }
      result.emplace_back(left, v);
    } else if (middle < v) {
      result.emplace_back(middle, v);
    }
  }

  // Panels of [a, y - H] for the far part of density(): breaks at y - 2^j H (j >= 0), at the
  // steps of F (which all lie below y - 3H), graded towards each step as in panels().
  std::vector<std::pair<Real, Real>> far_panels(const Real& y, const Real& H) const {
    using std::abs;
    std::vector<Real> breaks{a_};
    for (const auto& s : F_.steps)
      if (s.position > a_ && s.position < y) breaks.push_back(s.position);
    // A break y - d within d/2 of a step or of a is left out (the step is a break and its panels
    // are graded towards it; the panel at a carries (x-a)^m): otherwise a panel ends a tiny
    // distance before the log singularity of A~ at the step, or starts a tiny distance after a,
    // ungraded (g(y) lost up to 1e-6 relative where some y - 2^j H fell next to the wedge apex
    // or to a, and the two orders disagreed).
    for (Real d = H; y - d > a_ + d / 2; d *= 2) {
      bool next_to_step = false;
      for (const auto& s : F_.steps) next_to_step = next_to_step || abs(s.position - (y - d)) < d / 2;
      if (!next_to_step) breaks.push_back(y - d);
    }
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    std::vector<std::pair<Real, Real>> result;
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) grade(result, breaks[k], breaks[k + 1], y);
    return result;
  }

  Real alpha_, a_, b_;
  piecewise_function<Real> F_;
  std::size_t n_;
  riemann_solution<Real> rh_;
  Real c_, s_, m_, sigma_;
  chebyshev_fit<Real> window_;  // density()'s Chebyshev-Lobatto interpolation, N = n|1 points
  quadrature::quadrature_rule<Real> legendre_, at_a_, at_y_, both_;
};

// Piecewise Chebyshev interpolant of A~ of one index0_abel: the source of A~ for many density
// evaluations (abel_rh_solution::densities), where A~ at the ~100 nodes of every g(y) would
// otherwise cost one principal value each (~1 us in double: ~0.1 ms per g(y) and order).
// Structure of A~ (file header and index0_abel::integral):
//   * next to a: A~ = (x-a)^m times a function analytic at a (g ~ (t-a)^gam, m = gam + alpha);
//   * next to a step c of F: A~ = lambda log|x - c| + functions analytic on either side of c
//     (the PV's log term; (x-a)^m (b-x)^(n+alpha) w*(x) = 1, so lambda is a constant,
//     index0_abel::log_coefficient), plus the piecewise constant (c s/pi) F;
//   * next to b: analytic + (b-x)^(n+alpha) analytic (no one-term form).
// So the interpolated function is A~(x)/(x-a)^m on the first panel [a, (a + s_1)/2] (s_1 = the
// first step of F or b) and R(x) = A~(x) - sum_k lambda_k log|x - c_k| on every other panel; the
// panels break at the steps, halve each segment between breaks, and are graded geometrically
// (ratio 1/2) towards b until they are shorter than `finest`; every panel is interpolated at
// `points` Chebyshev points of the first kind (never at a, b or a step). Each panel then sees its
// nearest singularity at a distance >= its own length (Bernstein ratio >= 3 + sqrt 8: 24 points
// resolve A~ to rounding). Within at most `finest` of b, A~ is computed exactly (index0_abel::reduced).
// tail(): the largest |c_(points-1)| / max_k |c_k| over the panels, an indication (not a bound)
// of the interpolation error relative to the panel's scale.
template <class Real>
class reduced_interpolant {
 public:
  reduced_interpolant(const index0_abel<Real>& exact, const Real& finest, std::size_t points)
      : exact_(exact), a_(exact.lo()), b_(exact.hi()), m_(exact.exponent_lo()) {
    using std::abs;
    std::vector<Real> breaks{a_};
    for (const auto& s : exact.data().steps) {
      if (s.position > a_ && s.position < b_) {
        breaks.push_back(s.position);
        logs_.emplace_back(s.position, exact.log_coefficient(s.size));
      }
    }
    std::sort(breaks.begin(), breaks.end());
    breaks.push_back(b_);
    // Each segment [u, v] between breaks is halved; each half is graded towards its end until the
    // panel touching the end is no longer than `limit` of that end: a step c needs panels no longer
    // than its distance to the nearest other break (R is analytic at c, but its continuation is
    // singular there), b needs `finest` (the rest is computed exactly), a none (A~/(x-a)^m).
    auto limit = [&](std::size_t k) {
      if (k == 0) return b_ - a_;
      if (k + 1 == breaks.size()) return finest;
      return std::min<Real>(breaks[k] - breaks[k - 1], breaks[k + 1] - breaks[k]);
    };
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
      const Real u = breaks[k], v = breaks[k + 1], mid = u + (v - u) / 2;
      // left half, graded towards u (pieces pushed from the middle outwards, then reversed)
      std::vector<piece> left;
      Real e = mid;
      while (e - u > limit(k) && (e - u) > 8 * std::numeric_limits<Real>::epsilon() * abs(u)) {
        const Real split = u + (e - u) / 2;
        left.push_back(piece{split, e, false, {}});
        e = split;
      }
      left.push_back(piece{u, e, k == 0, {}});
      pieces_.insert(pieces_.end(), left.rbegin(), left.rend());
      // right half, graded towards v; at b the innermost finest/2 .. is left to exact evaluation
      const bool at_b = k + 2 == breaks.size();
      Real f = mid;
      while (v - f > limit(k + 1) && (v - f) > 8 * std::numeric_limits<Real>::epsilon() * abs(v)) {
        const Real split = v - (v - f) / 2;
        pieces_.push_back(piece{f, split, false, {}});
        f = split;
      }
      if (!at_b) pieces_.push_back(piece{f, v, false, {}});
    }
    covered_ = pieces_.back().hi;
    // First-kind nodes s_j = cos(pi (j + 1/2)/P) = T_1(s_j), DCT-II coefficients (chebyshev_fit).
    const std::size_t P = points;
    const chebyshev_fit<Real> fit(P, chebyshev_fit<Real>::grid::first_kind);
    // The nodes are rounded to representable x_j; next to b (or a step) A~ varies on the scale of
    // the panel, and a node moved by ulp(x)/2 on a panel of length 1e-7 shifts the data by ~1e-9
    // relatively. So, as in density(), the interpolant is fitted at the ACTUAL abscissae s'_j.
    std::vector<Real> values(P), abscissae(P);
    tail_ = 0;
    for (auto& p : pieces_) {
      const Real half = (p.hi - p.lo) / 2;
      for (std::size_t j = 0; j < P; ++j) {
        // node in [-1, 1], placed by index0_abel::node (strictly inside the panel, off the steps:
        // a panel a few ulps long next to a step must not put a node on it)
        const Real t = fit.chebyshev_t(1, j);
        const Real x = exact.node({p.lo, p.hi}, half * (1 + t), half * (1 - t));
        const Real value = exact.reduced(x);
        values[j] = p.weighted ? value / pow_m(x - a_) : value - logs(x);
        abscissae[j] = ((x - p.lo) - (p.hi - x)) / (p.hi - p.lo);
      }
      p.c = fit.coefficients(values, abscissae);
      Real largest = 0;
      for (const Real& c : p.c) largest = std::max<Real>(largest, abs(c));
      if (largest > 0) tail_ = std::max<Real>(tail_, abs(p.c[P - 1]) / largest);
    }
  }

  /// A~(x), a < x < b.
  Real reduced(const Real& x) const {
    const piece* p = find(x);
    if (p == nullptr) return exact_.reduced(x);
    const Real v = clenshaw(p->c, abscissa(*p, x));
    return p->weighted ? v * pow_m(x - a_) : v + logs(x);
  }

  /// index0_abel::sample from the interpolant: A~ (divided by (x-a)^m when at_a) at the node of
  /// `panel` with distances (from_lo, to_hi) to its ends, (x-a)^m from the exact offset.
  Real sample(const std::pair<Real, Real>& panel, const Real& from_lo, const Real& to_hi, bool at_a) const {
    const Real x = exact_.node(panel, from_lo, to_hi);
    const piece* p = find(x);
    if (p == nullptr) return exact_.sample(panel, from_lo, to_hi, at_a);
    const Real exact_offset = (panel.first - a_) + from_lo;
    const Real v = clenshaw(p->c, abscissa(*p, x));
    if (p->weighted) return at_a ? v : v * pow_m(exact_offset);
    const Real full = v + logs(x);
    return at_a ? full / pow_m(exact_offset) : full;
  }

  Real tail() const { return tail_; }
  std::size_t panels() const { return pieces_.size(); }

 private:
  struct piece {
    Real lo, hi;
    bool weighted;         // A~/(x-a)^m (the panel at a) instead of A~ - sum lambda log|x - c|
    std::vector<Real> c;   // Chebyshev coefficients on [lo, hi]
  };

  Real pow_m(const Real& d) const {
    using std::pow;
    return pow(d, m_);
  }
  Real logs(const Real& x) const {
    using std::abs;
    using std::log;
    Real sum = 0;
    for (const auto& [c, lambda] : logs_) sum += lambda * log(abs(x - c));
    return sum;
  }
  const piece* find(const Real& x) const {
    if (!(x > a_) || !(x < covered_)) return nullptr;
    const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), x,
                                     [](const Real& v, const piece& p) { return v < p.hi; });
    return it == pieces_.end() ? nullptr : &*it;
  }
  static Real abscissa(const piece& p, const Real& x) { return ((x - p.lo) - (p.hi - x)) / (p.hi - p.lo); }
  static Real clenshaw(const std::vector<Real>& c, const Real& s) { return chebyshev_fit<Real>::clenshaw(c, s); }

  const index0_abel<Real>& exact_;
  Real a_, b_, m_, covered_ = 0, tail_ = 0;
  std::vector<piece> pieces_;
  std::vector<std::pair<Real, Real>> logs_;  // (step position, lambda)
};

}  // namespace detail

/// Solution of the generalized Abel equation by the Riemann-Hilbert route (file header).
template <class Real>
class abel_rh_solution {
 public:
  abel_rh_solution(Real alpha, Real beta, Real a, Real b, piecewise_function<Real> F, edge leading, edge trailing,
                   const abel_rh_options<Real>& options)
      : alpha_(alpha), beta_(beta), a_(a), b_(b), leading_(leading), trailing_(trailing), options_(options) {
    using std::isfinite;
    const char* fn = "solve_abel_rh";
    if (!(alpha >= 0) || !(alpha < 1)) quadrature::detail::throw_bad_parameter(fn, "alpha", alpha, "[0, 1)");
    if (!(beta >= 0) || !(beta < 1)) quadrature::detail::throw_bad_parameter(fn, "beta", beta, "[0, 1)");
    if (!isfinite(a)) quadrature::detail::throw_bad_parameter(fn, "a", a, "finite, a < b");
    if (!isfinite(b) || !(b > a)) quadrature::detail::throw_bad_parameter(fn, "b", b, "finite, b > a");
    if (!F.smooth && F.steps.empty()) quadrature::detail::throw_bad_parameter(fn, "F", 0, "a callable or steps");
    const bool needs_unbounded_lead = leading == edge::unbounded;
    if (needs_unbounded_lead && !(alpha + beta / 2 < Real(1) / 2))
      quadrature::detail::throw_bad_parameter(
          fn, "alpha + beta/2", alpha + beta / 2,
          "[0, 1/2) for a solution unbounded at the leading edge a (its exponent -(1+2 alpha+beta)/2 must exceed -1)");
    const std::size_t n = options.order == 0 ? default_cauchy_order<Real>() : options.order;
    if (n < 4) quadrature::detail::throw_bad_parameter(fn, "options.order", n, "[4, inf) (0 = default)");
    const bounded_end bounded =
        (leading == edge::unbounded && trailing == edge::bounded) ? bounded_end::hi : bounded_end::lo;
    coarse_ = std::make_shared<detail::index0_abel<Real>>(alpha, beta, a, b, F, bounded, n);
    fine_ = std::make_shared<detail::index0_abel<Real>>(alpha, beta, a, b, F, bounded, n + n / 2);
    nu_ = leading == edge::bounded ? (trailing == edge::bounded ? -1 : 0) : (trailing == edge::bounded ? 0 : 1);

    using std::pow;
    if (nu_ == 1) {
      homogeneous_total_ = pow(b - a, -alpha) * boost::math::beta((1 - 2 * alpha - beta_) / 2, (1 + beta_) / 2);
      if (options.load) {
        const estimated<Real> t0 = base_total();
        constant_ = (*options.load - t0.value) / homogeneous_total_;
      }
    }
    if (nu_ == -1) defect_ = compute_defect(F);

    // status
    const Real tol = options.tolerance;
    const estimated<Real> t = total();
    status_ = abel_status::converged;
    // Written as !(within): a NaN estimate or value (NaN data) is not converged, never the reverse.
    using std::isfinite;
    if (!(t.error_estimate <= tol * std::max<Real>(abs_value(t.value), std::numeric_limits<Real>::min())) ||
        !isfinite(t.value))
      status_ = abel_status::not_converged;
    if (nu_ == -1 && !(abs_value(defect_.value) <= tol * defect_scale_)) {
      status_ = isfinite(defect_.value) ? abel_status::orthogonality_not_satisfied : abel_status::not_converged;
    }
  }

  /// nu in {-1, 0, +1}.
  int index() const { return nu_; }
  /// The class asked for: behaviour at the leading edge a and at the trailing edge b.
  edge leading() const { return leading_; }
  edge trailing() const { return trailing_; }
  abel_status status() const { return status_; }

  /// int_a^y g, a <= y <= b.
  estimated<Real> integral(const Real& y) const {
    using std::pow;
    if (!(y >= a_) || !(y <= b_)) quadrature::detail::throw_bad_parameter("rhabel::riemann::abel_rh_solution::integral", "y", y, "[a, b]");
    if (y == b_) return total();
    estimated<Real> r = pair(coarse_->integral(y), fine_->integral(y));
    if (nu_ == 1 && constant_ != 0) {
      const Real L = b_ - a_;
      r.value += constant_ * pow(L, -alpha_) *
                 boost::math::beta((1 - 2 * alpha_ - beta_) / 2, (1 + beta_) / 2, (y - a_) / L);
    }
    return r;
  }

  /// g(y), a < y < b (not on a step of F).
  estimated<Real> density(const Real& y) const {
    using std::pow;
    if (!(y > a_) || !(y < b_)) quadrature::detail::throw_bad_parameter("rhabel::riemann::abel_rh_solution::density", "y", y, "(a, b)");
    estimated<Real> r = pair(coarse_->density(y), fine_->density(y));
    if (nu_ == 1 && constant_ != 0) r.value += constant_ * homogeneous(y);
    return r;
  }

  /// g(y_i) for many points y_i in (a, b), off the steps of F: density() with A~ taken from a
  /// piecewise Chebyshev interpolant per order (detail::reduced_interpolant, built once per
  /// call, 24 points per panel in double, 69 at 50 digits, graded towards b down to a third of
  /// the smallest b - y_i),
  /// instead of one principal value per quadrature node. Same algorithm, same two orders, same
  /// error_estimate (|value at order n - value at 3n/2|: an ESTIMATE). Measured against
  /// density() (<= 2.2e-13 relative to max(|g|, int g / L)) and the 45-digit table (within
  /// test_density_table's tolerances): tests/riemann/test_batch_density.cpp. Cost ~0.3-0.5 ms
  /// per order to build plus 13-115 us per point (two orders) instead of 70-1400 us per point
  /// (double, Release; the file header). Throws std::domain_error for a y outside (a, b) or on
  /// a step of F.
  std::vector<estimated<Real>> densities(const std::vector<Real>& ys) const {
    Real finest = b_ - a_;
    for (const Real& y : ys) {
      if (!(y > a_) || !(y < b_)) quadrature::detail::throw_bad_parameter("rhabel::riemann::abel_rh_solution::densities", "y", y, "(a, b)");
      for (const auto& s : coarse_->data().steps)
        if (y == s.position)
          quadrature::detail::throw_bad_parameter("rhabel::riemann::abel_rh_solution::densities", "y", y, "(a, b) off the steps of F");
      finest = std::min<Real>(finest, (b_ - y) / 3);
    }
    std::vector<estimated<Real>> out;
    out.reserve(ys.size());
    if (ys.empty()) return out;
    // Each panel sees its nearest singularity at >= its length (Bernstein ratio 3 + sqrt 8 =
    // 5.83): digits10 / log10(5.83) + 4 points resolve A~ to the working precision (24 in double).
    const std::size_t points =
        std::max<std::size_t>(24, static_cast<std::size_t>(std::numeric_limits<Real>::digits10 / 0.765) + 4);
    const detail::reduced_interpolant<Real> coarse(*coarse_, finest, points), fine(*fine_, finest, points);
    for (const Real& y : ys) {
      estimated<Real> r = pair(coarse_->density_with(y, coarse), fine_->density_with(y, fine));
      if (nu_ == 1 && constant_ != 0) r.value += constant_ * homogeneous(y);
      out.push_back(r);
    }
    return out;
  }

  /// int_a^b g.
  estimated<Real> total() const {
    estimated<Real> r = base_total();
    if (nu_ == 1) r.value += constant_ * homogeneous_total_;
    return r;
  }

  /// nu = -1: the normalised orthogonality defect (file header); 0 with estimate 0 otherwise.
  const estimated<Real>& orthogonality_defect() const { return defect_; }

  /// nu = +1: g_h(y) = (y-a)^(-(1+2alpha+beta)/2) (b-y)^((beta-1)/2), and the constant C of g = g_0 + C g_h.
  Real homogeneous(const Real& y) const {
    using std::pow;
    return pow(y - a_, -(1 + 2 * alpha_ + beta_) / 2) * pow(b_ - y, (beta_ - 1) / 2);
  }
  const Real& homogeneous_constant() const { return constant_; }

  /// The underlying Riemann problem solution (finer order).
  const riemann_solution<Real>& riemann() const { return fine_->riemann(); }

 private:
  static Real abs_value(const Real& x) { return x < 0 ? -x : x; }

  static estimated<Real> pair(const Real& coarse, const Real& fine) { return {fine, abs_value(fine - coarse)}; }

  estimated<Real> base_total() const { return pair(coarse_->total(), fine_->total()); }

  estimated<Real> compute_defect(const piecewise_function<Real>& F) {
    using boost::math::tgamma;
    using std::pow;
    const Real P = -(1 + beta_) / 2 - alpha_, Q = (beta_ - 1) / 2, L = b_ - a_;
    const Real Fb = F(b_);
    const Real smooth_b = F.smooth ? F.smooth(b_) : Real(0);
    const Real rgamma_p1 = (P + 1 == 0) ? Real(0) : 1 / tgamma(P + 1);
    const Real end_term = Fb * pow(L, P + Q + 1) * tgamma(Q + 1) / tgamma(P + Q + 2);
    // scale of the defect for the status: max|F| times the size of its two terms
    defect_scale_ = abs_value(pow(L, P + Q + 1)) * (abs_value(rgamma_p1) + abs_value(tgamma(Q + 1) / tgamma(P + Q + 2)));
    // (sampled, and on both sides of every step: an apex 1e-6 L from a leaves F = S1 on a piece
    // no sample hits)
    Real max_f = abs_value(F(a_));
    for (int k = 1; k < 16; ++k) max_f = std::max<Real>(max_f, abs_value(F(a_ + (b_ - a_) * k / 16)));
    for (const auto& s : F.steps)
      max_f = std::max<Real>({max_f, abs_value(F(s.position)), abs_value(F(s.position) + s.size)});
    defect_scale_ *= std::max<Real>(max_f, abs_value(Fb));
    Real values[2];
    const std::size_t n = options_.order == 0 ? default_cauchy_order<Real>() : options_.order;
    const std::size_t orders[2] = {n, n + n / 2};
    for (int r = 0; r < 2; ++r) {
      Real sum = 0;
      if (F.smooth) {
        piecewise_function<Real> divided;
        const auto smooth = F.smooth;
        const Real bb = b_;
        divided.smooth = [smooth, bb, smooth_b](Real t) { return (smooth(t) - smooth_b) / (bb - t); };
        sum += jacobi_cauchy_integral<Real>(a_, b_, P + 1, Q, divided, orders[r]).moment();
      }
      for (const auto& s : F.steps) {
        // - size int_a^c (t-a)^Q (b-t)^P dt   (F - F(b) = -size on (a, c)). For P > -1 (alpha +
        // beta/2 < 1/2, where a wedge apex occurs) in closed form, L^(P+Q+1) B_x(Q+1, P+1),
        // x = (c-a)/L, through the complement B(Q+1, P+1) - B_(1-x)(P+1, Q+1) when c is nearer
        // to b (a Gauss rule on [a, c] would see (b-t)^P nearly singular: with c 1e-3 L from b
        // it gave the defect to only ~1e-3).
        if (P > -1) {
          const Real x = (s.position - a_) / L, xc = (b_ - s.position) / L;
          const Real incomplete = x <= xc ? boost::math::beta(Q + 1, P + 1, x)
                                          : boost::math::beta(Q + 1, P + 1) - boost::math::beta(P + 1, Q + 1, xc);
          sum -= s.size * pow(L, P + Q + 1) * incomplete;
          continue;
        }
        piecewise_function<Real> power;
        const Real bb = b_;
        power.smooth = [bb, P](Real t) {
          using std::pow;
          return pow(bb - t, P);
        };
        sum -= s.size * jacobi_cauchy_integral<Real>(a_, s.position, Real(0), Q, power, orders[r]).moment();
      }
      values[r] = rgamma_p1 * sum + end_term;
    }
    return pair(values[0], values[1]);
  }

  Real alpha_, beta_, a_, b_;
  edge leading_, trailing_;
  abel_rh_options<Real> options_;
  std::shared_ptr<detail::index0_abel<Real>> coarse_, fine_;
  int nu_ = 0;
  Real homogeneous_total_ = 0, constant_ = 0;
  estimated<Real> defect_{Real(0), Real(0)};
  Real defect_scale_ = 1;
  abel_status status_ = abel_status::converged;
};

/// Solves the generalized Abel equation (file header) for g in the class (leading, trailing).
template <class Real>
abel_rh_solution<Real> solve_abel_rh(Real alpha, Real beta, Real a, Real b, piecewise_function<Real> F, edge leading,
                                     edge trailing, const abel_rh_options<Real>& options = {}) {
  return abel_rh_solution<Real>(alpha, beta, a, b, std::move(F), leading, trailing, options);
}

}  // namespace rhabel::riemann
