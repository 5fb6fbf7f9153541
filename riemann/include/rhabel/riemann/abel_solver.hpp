// rhabel/riemann/abel_solver.hpp
//
// The Riemann-Hilbert route to the generalized Abel equation (paper eq. 8; notes section 1):
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
//            = (c/pi) [ s F(x) - (1/pi) (x-a)^m (b-x)^(n+alpha) PV int_a^b w*(t) F(t)/(t-x) dt ],
//     w*(t) = (t-a)^(-m) (b-t)^(-alpha-n),  c = cos(beta pi/2), s = sin(beta pi/2),
//     int_a^y g = int_a^y A~(x) (y-x)^(-alpha) dx                                   (derivative-free)
//     g(y)      = A~(y) (y-a)^(-alpha) + alpha int_a^y (A~(y) - A~(x)) (y-x)^(-alpha-1) dx
//     int_a^b g = (1/(2 pi i)) int rho = -(c/pi) (-1)^j int_a^b w* F ,  j = 1 if n = (beta-1)/2, else 0.
// (For beta = 0 and the class bounded at both ends this is notes section 6.)
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
//   the (finite-part) orthogonality integral of the paper (20) / notes section 4 vanishes. We
//   return the first-row solution and the defect, normalised to be analytic in the parameters
//   (the finite part has a pole at alpha + beta/2 = 1/2):
//       defect = (1/Gamma(1/2 - alpha - beta/2)) FP int_a^b (s-a)^((beta-1)/2) (b-s)^(-(1+beta)/2-alpha) F(s) ds
//              = rgamma(P+1) int (s-a)^Q (b-s)^(P+1) (F(s)-F(b))/(b-s) ds + F(b) L^(P+Q+1) Gamma(Q+1)/Gamma(P+Q+2),
//   P = -(1+beta)/2 - alpha, Q = (beta-1)/2, L = b - a (at alpha+beta/2 = 1/2 it is F(b) L^Q:
//   there the equation is one-sided and the bounded solution needs F(b) = 0).
// * nu = +1. The homogeneous solution is g_h = (t-a)^(-(1+2alpha+beta)/2) (b-t)^((beta-1)/2)
//   (notes section 4; C X(z) in the Riemann problem); int g_h = L^(-alpha) B((1-2alpha-beta)/2, (1+beta)/2).
//   options.load fixes C by int g = load; without it C = 0.
//
// Numerics. The PV is jacobi_cauchy_integral (product integration, cauchy_integral.hpp); the
// Abel integrals over [a, y] use composite Gauss-Jacobi rules (rhabel::quadrature::gauss_jacobi
// on [-1, 1], mapped to each panel through the distances 1 -+ x) that carry (x-a)^m on the panel
// touching a and (y-x)^(-alpha) on the panel touching y, geometrically graded (ratio 1/4)
// towards y when b or a step of F is near y, and towards every step of F inside (a, y) (where
// A~ has a logarithmic singularity, lambda log|x - c| with lambda = cos(beta pi/2) size/pi^2;
// when y is itself a step, e.g. int_a^0 g for the wedge, that log is integrated exactly).
// Every query is answered at two orders (n and 3n/2, inner and outer) and returns the finer
// value with |difference| as error_estimate: an ESTIMATE, not a bound.
//
// Accuracy (measured, build-rh Release, tests/riemann/test_abel_solver.cpp; double unless said):
//  * int g and int_a^y g: a few eps relative to int g for smooth F in every class, alpha in
//    [0, 0.9], beta in [0, 0.7]: parabola closed form <= 32 eps; rhabel::abel agreement
//    <= 1e-13 (observed ~1e-15); at 50 digits (cpp_bin_float_50) <= 1e-45. KNOWN WEAKNESS:
//    for y within ~1e-5 L of the trailing edge b the error grows (alpha = 0.8, beta = 0:
//    1e-14 at b - y = 1e-5 L, 5e-13 at 1e-7 L, 1e-12 at 1e-9 L; cause not yet identified, A~
//    itself is smooth there to rounding); int_a^b g itself is exact (moment formula).
//    As alpha -> 1, A~ = O(1 - alpha) is formed from O(1) boundary values: a factor
//    1/(1 - alpha) is lost (alpha = 0.999: ~1e-13 instead of 1e-16).
//  * step data: int_a^0 g for the wedge with an interior apex to ~1e-16 (two orders agree to
//    rounding; independent residual of eq. 8 <= 1e-12, limited by the residual's own quadrature).
//  * g(y): the derivative form above divides differences of A~ by y - x down to the nearest
//    Gauss node, amplifying the rounding of A~ by ~ (distance)^(-alpha): ~1e-14..1e-13 relative
//    for alpha <= 0.5, ~1e-12..1e-11 for alpha in [0.6, 0.9], ~1e-7 at alpha = 0.999. Prefer
//    int_a^y g when a quantity can be written with it (loads, moments, C_f by parts).
//  * hard alphas: 1e-3 and 0 (the Carleman limit) lose nothing; 0.5 -+ 1e-9 (kappa through 0)
//    loses nothing (the single-power integral K(q, .) is uniform through q = 0).
// Cost (double): construction ~10 ms; a query int_a^y g ~0.2 ms (smooth F) to ~6 ms (steps,
// graded panels); 50 digits ~100x more.
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
    m_ = rh_.canonical().exponent_lo;
    legendre_ = quadrature::gauss_jacobi<Real>(n_, Real(0), Real(0));
    at_a_ = quadrature::gauss_jacobi<Real>(n_, Real(0), m_);
    at_y_ = quadrature::gauss_jacobi<Real>(n_, -alpha_, Real(0));
    both_ = quadrature::gauss_jacobi<Real>(n_, -alpha_, m_);
    sigma_ = Real(1) / 4;
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

  // A~(x) = (b-x)^alpha (Phi_+ - Phi_-)/(2 pi i), real.
  Real reduced(const Real& x) const {
    using std::pow;
    const auto [plus, minus] = rh_.boundary_values(x);
    const Real pi = boost::math::constants::pi<Real>();
    return pow(b_ - x, alpha_) * (plus - minus).imag() / (2 * pi);
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
    // y on a step at c: A~(x) = lambda log(c - x) + (continuous) near c, lambda = cos(beta pi/2) size/pi^2
    // (the step's PV contributes -size w*(c) log|x - c| and (x-a)^m (b-x)^(n+alpha) w*(c) = 1 at c);
    // the log is integrated exactly against (y-x)^(-alpha) on the panel touching y.
    Real lambda = 0;
    for (const auto& s : F_.steps)
      if (s.position == y) lambda += c_ * s.size / (boost::math::constants::pi<Real>() * boost::math::constants::pi<Real>());
    Real sum = 0;
    for (const auto& panel : panels(y)) {
      const bool at_a = panel.first == a_, at_y = panel.second == y;
      const auto& standard = at_a ? (at_y ? both_ : at_a_) : (at_y ? at_y_ : legendre_);
      const Real half = (panel.second - panel.first) / 2;
      const Real scale = pow(half, (at_a ? m_ : Real(0)) + (at_y ? -alpha_ : Real(0)) + 1);
      for (std::size_t i = 0; i < standard.size(); ++i) {
        const Real from_lo = standard.x_minus_lo[i] * half, to_hi = standard.hi_minus_x[i] * half;
        const Real x = node(panel, from_lo, to_hi);
        const Real distance_to_y = at_y ? to_hi : y - x;
        Real f = reduced(x);
        if (at_y && lambda != 0) f -= lambda * log(distance_to_y);
        // divide by the distance of the node AS EVALUATED (x rounded): A~(x)/(x-a)^m is smooth,
        // but (x - a) and the exact from_lo differ by ~eps |a| / (x - a) relatively near a.
        if (at_a) f /= pow(x - a_, m_);
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

  // g(y), a < y < b
  Real density(const Real& y) const {
    using std::pow;
    const Real ay = reduced(y);
    Real sum = ay * pow(y - a_, -alpha_);
    if (alpha_ == 0) return sum;
    for (const auto& panel : panels(y, true)) {
      const bool at_a = panel.first == a_, at_y = panel.second == y;
      const Real half = (panel.second - panel.first) / 2;
      if (at_y) {
        // alpha int (A~(y) - A~(x))/(y - x) (y-x)^(-alpha) dx
        const Real scale = pow(half, 1 - alpha_);
        for (std::size_t i = 0; i < at_y_.size(); ++i) {
          const Real from_lo = at_y_.x_minus_lo[i] * half, to_hi = at_y_.hi_minus_x[i] * half;
          const Real x = node(panel, from_lo, to_hi);
          sum += at_y_.weight[i] * scale * alpha_ * (ay - reduced(x)) / (y - x);
        }
        continue;
      }
      // alpha A~(y) int (y-x)^(-alpha-1) - alpha int A~(x) (y-x)^(-alpha-1)
      sum += ay * (pow(y - panel.second, -alpha_) - pow(y - panel.first, -alpha_));
      const auto& standard = at_a ? at_a_ : legendre_;
      const Real scale = pow(half, (at_a ? m_ : Real(0)) + 1);
      for (std::size_t i = 0; i < standard.size(); ++i) {
        const Real from_lo = standard.x_minus_lo[i] * half, to_hi = standard.hi_minus_x[i] * half;
        const Real x = node(panel, from_lo, to_hi);
        Real f = reduced(x) * pow(y - x, -alpha_ - 1);
        if (at_a) f /= pow(x - a_, m_);  // rounded node, as in integral()
        sum -= standard.weight[i] * scale * alpha_ * f;
      }
    }
    return sum;
  }

  const riemann_solution<Real>& riemann() const { return rh_; }

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

  // Panels of [a, y]: breaks at the steps of F inside (a, y) (log singularities of A~) and at
  // the middle, graded towards a step and towards y when b or a step is near y.
  std::vector<std::pair<Real, Real>> panels(const Real& y, bool split_middle = false) const {
    using std::abs;
    std::vector<Real> breaks{a_};
    for (const auto& s : F_.steps)
      if (s.position > a_ && s.position < y) breaks.push_back(s.position);
    std::sort(breaks.begin(), breaks.end());
    if (breaks.size() == 1 && split_middle) breaks.push_back((a_ + y) / 2);
    breaks.push_back(y);
    // distance from y to the nearest singularity beyond it
    Real beyond = b_ - y;
    for (const auto& s : F_.steps)
      if (s.position >= y) beyond = std::min<Real>(beyond, s.position - y);
    auto is_step = [&](const Real& e) {
      for (const auto& s : F_.steps)
        if (e == s.position) return true;
      return false;
    };
    std::vector<std::pair<Real, Real>> result;
    const Real eps = std::numeric_limits<Real>::epsilon();
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
      const Real u = breaks[k], v = breaks[k + 1];
      const Real length = v - u;
      const Real du = is_step(u) ? Real(0) : length;  // a and the middle need no grading
      const Real dv = is_step(v) ? Real(0) : (v == y ? beyond : length);
      const bool grade_u = du < length / 2, grade_v = dv < length / 2;
      if (!grade_u && !grade_v) {
        result.emplace_back(u, v);
        continue;
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
    return result;
  }

  Real alpha_, a_, b_;
  piecewise_function<Real> F_;
  std::size_t n_;
  riemann_solution<Real> rh_;
  Real c_, m_, sigma_;
  quadrature::quadrature_rule<Real> legendre_, at_a_, at_y_, both_;
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
    if (t.error_estimate > tol * std::max<Real>(abs_value(t.value), std::numeric_limits<Real>::min()))
      status_ = abel_status::not_converged;
    if (nu_ == -1 && abs_value(defect_.value) > tol * defect_scale_) status_ = abel_status::orthogonality_not_satisfied;
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
    if (!(y >= a_) || !(y <= b_)) quadrature::detail::throw_bad_parameter("abel_rh_solution::integral", "y", y, "[a, b]");
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
    if (!(y > a_) || !(y < b_)) quadrature::detail::throw_bad_parameter("abel_rh_solution::density", "y", y, "(a, b)");
    estimated<Real> r = pair(coarse_->density(y), fine_->density(y));
    if (nu_ == 1 && constant_ != 0) r.value += constant_ * homogeneous(y);
    return r;
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
    Real max_f = 0;
    for (int k = 1; k < 16; ++k) max_f = std::max<Real>(max_f, abs_value(F(a_ + (b_ - a_) * k / 16)));
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
        // - size int_a^c (t-a)^Q (b-t)^P dt   (F - F(b) = -size on (a, c))
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
