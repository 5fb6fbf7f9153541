// rhabel/riemann/riemann_problem.hpp
//
// The scalar Riemann (Hilbert) boundary value problem on a segment with a constant,
// unimodular coefficient (Gakhov, "Boundary Value Problems", ch. II sec. 42-43;
// Muskhelishvili, "Singular Integral Equations", ch. 10):
//
//     find Phi analytic in C \ [lo, hi], Phi(z) = O(1/z) at infinity, with integrable
//     singularities at lo and hi, whose boundary values satisfy
//         Phi_+(x) = G Phi_-(x) + g1(x) ,     lo < x < hi ,
//     G = exp(2 pi i theta), 0 < theta < 1,
//     g1(x) = c1 (x - lo)^r_lo (hi - x)^r_hi h(x)      (c1 complex, h real, piecewise smooth).
//
// Phi_+ is the limit from Im z > 0, Phi_- from Im z < 0.
//
// Canonical function (branch conventions). X(z) = (z - lo)^m (z - hi)^n with PRINCIPAL powers
// (cuts of the two factors along (-inf, lo] and (-inf, hi]). Because m + n = -index is an
// integer, the jumps on (-inf, lo) cancel and X is analytic in C \ [lo, hi], X(z) ~ z^(-index)
// at infinity. On the cut (hi - x > 0):
//     X_+-(x) = (x - lo)^m (hi - x)^n exp(+- i pi n) ,   so   X_+ / X_- = exp(2 pi i n) = G
// for n = theta (mod 1). The index classes (Gakhov's kappa = index):
//     index -1 : n = theta,     m = 1 - theta   (X vanishes at both ends: Phi bounded at both)
//     index  0 : n = theta,     m = -theta      (bounded at hi, unbounded at lo), or
//                n = theta - 1, m = 1 - theta   (bounded at lo, unbounded at hi)
//     index +1 : n = theta - 1, m = -theta      (unbounded at both ends)
//
// General solution (Gakhov 43.5; the paper's eq. 14):
//     Phi(z) = X(z) [ (1/(2 pi i)) int_lo^hi rho(t)/(t - z) dt + C ] ,   rho = g1 / X_+ ,
// with C an arbitrary constant for index +1 (the homogeneous solution C X(z)) and C = 0
// otherwise. rho(t) = c1 exp(-i pi n) (t - lo)^(r_lo - m) (hi - t)^(r_hi - n) h(t) is a
// Jacobi-weighted density, required to be integrable: r_lo - m > -1 and r_hi - n > -1
// (otherwise std::domain_error; a non-integrable rho needs a finite-part integral, which the
// generalized Abel solver treats by itself, see abel_solver.hpp).
// For index -1, Phi = O(1/z) requires the orthogonality condition (Gakhov 43.6; paper 15)
//     int_lo^hi rho(t) dt = 0 ;
// orthogonality_defect() returns (1/(2 pi i)) int rho, and Phi then behaves like
// -defect * z^0 at infinity. The solution object is returned either way: the defect is evidence.
// The Plemelj limits (Sokhotski-Plemelj) are
//     Phi_+-(x) = X_+-(x) [ +- rho(x)/2 + (1/(2 pi i)) PV int rho/(t - x) dt + C ].
//
// Accuracy: that of jacobi_cauchy_integral (cauchy_integral.hpp): a few eps relative to the
// condition number int |rho| / |t - x| dt for h analytic near [lo, hi] at the default order;
// the boundary relation Phi_+ = G Phi_- + g1 then holds to that accuracy (it is exact in the
// construction: tests/riemann/test_riemann_problem.cpp checks it and the far-field behaviour).
#pragma once

#include "rhabel/riemann/cauchy_integral.hpp"

#include <boost/math/constants/constants.hpp>

#include <cmath>
#include <complex>
#include <cstddef>
#include <utility>

namespace rhabel::riemann {

/// Which end a solution of index 0 is bounded at.
enum class bounded_end { lo, hi };

/// X(z) = (z - lo)^m (z - hi)^n, principal powers, m + n = -index (see file header).
template <class Real>
struct canonical_function {
  using complex_type = std::complex<Real>;
  Real lo, hi;
  Real exponent_lo;  ///< m
  Real exponent_hi;  ///< n
  int index;

  /// X(z), z off [lo, hi].
  complex_type operator()(const complex_type& z) const {
    return detail::pow_principal<Real>(z - lo, exponent_lo) * detail::pow_principal<Real>(z - hi, exponent_hi);
  }
  /// |X_+-(x)| = (x - lo)^m (hi - x)^n on the cut.
  Real modulus_on_cut(const Real& x) const {
    using std::pow;
    return pow(x - lo, exponent_lo) * pow(hi - x, exponent_hi);
  }
  /// X_+(x) = (x - lo)^m (hi - x)^n exp(i pi n).
  complex_type plus(const Real& x) const {
    using std::cos;
    using std::sin;
    const Real pi = boost::math::constants::pi<Real>();
    return modulus_on_cut(x) * complex_type(cos(pi * exponent_hi), sin(pi * exponent_hi));
  }
  /// X_-(x) = (x - lo)^m (hi - x)^n exp(-i pi n).
  complex_type minus(const Real& x) const {
    using std::cos;
    using std::sin;
    const Real pi = boost::math::constants::pi<Real>();
    return modulus_on_cut(x) * complex_type(cos(pi * exponent_hi), -sin(pi * exponent_hi));
  }
};

/// Canonical function of G = exp(2 pi i theta), 0 < theta < 1, for index in {-1, 0, +1};
/// for index 0 `bounded` chooses the end where the solutions are bounded.
template <class Real>
canonical_function<Real> make_canonical_function(Real lo, Real hi, Real theta, int index,
                                                 bounded_end bounded = bounded_end::hi) {
  using std::isfinite;
  const char* fn = "make_canonical_function";
  if (!isfinite(lo)) quadrature::detail::throw_bad_parameter(fn, "lo", lo, "finite, lo < hi");
  if (!isfinite(hi) || !(hi > lo)) quadrature::detail::throw_bad_parameter(fn, "hi", hi, "finite, hi > lo");
  if (!(theta > 0) || !(theta < 1)) quadrature::detail::throw_bad_parameter(fn, "theta", theta, "(0, 1)");
  Real n;
  switch (index) {
    case -1:
      n = theta;
      break;
    case 0:
      n = bounded == bounded_end::hi ? theta : theta - 1;
      break;
    case 1:
      n = theta - 1;
      break;
    default:
      quadrature::detail::throw_bad_parameter(fn, "index", index, "{-1, 0, 1}");
  }
  return {lo, hi, Real(-index) - n, n, index};
}

/// Data of the problem Phi_+ = exp(2 pi i theta) Phi_- + c1 (x-lo)^r_lo (hi-x)^r_hi h(x).
template <class Real>
struct riemann_problem {
  Real lo, hi;
  Real theta;                          ///< G = exp(2 pi i theta), 0 < theta < 1
  std::complex<Real> data_factor;      ///< c1
  Real data_exponent_lo = 0;           ///< r_lo
  Real data_exponent_hi = 0;           ///< r_hi
  piecewise_function<Real> data;       ///< h (real, piecewise smooth)
};

/// The solution Phi of a riemann_problem in a chosen index class (file header).
template <class Real>
class riemann_solution {
 public:
  using complex_type = std::complex<Real>;

  riemann_solution(const riemann_problem<Real>& problem, canonical_function<Real> x, complex_type constant,
                   std::size_t order)
      : x_(x),
        constant_(constant),
        cauchy_(problem.lo, problem.hi, problem.data_exponent_hi - x.exponent_hi,
                problem.data_exponent_lo - x.exponent_lo, problem.data, order) {
    using std::cos;
    using std::sin;
    const Real pi = boost::math::constants::pi<Real>();
    // rho = c1 exp(-i pi n) w h ;  (1/(2 pi i)) int rho/(t-z) = factor_ * C(z)
    const complex_type phase(cos(pi * x.exponent_hi), -sin(pi * x.exponent_hi));
    rho_factor_ = problem.data_factor * phase;
    factor_ = rho_factor_ / complex_type(0, 2 * pi);
  }

  const canonical_function<Real>& canonical() const { return x_; }
  int index() const { return x_.index; }
  /// The arbitrary constant C of index +1 (0 for the other classes).
  const complex_type& constant() const { return constant_; }

  /// Phi(z), z off [lo, hi].
  complex_type operator()(const complex_type& z) const { return x_(z) * (factor_ * cauchy_.transform(z) + constant_); }

  /// Phi_+(x), lo < x < hi.
  complex_type plus(const Real& x) const {
    return x_.plus(x) * (factor_ * cauchy_.plemelj_plus(x) + constant_);
  }
  /// Phi_-(x), lo < x < hi.
  complex_type minus(const Real& x) const {
    return x_.minus(x) * (factor_ * cauchy_.plemelj_minus(x) + constant_);
  }
  /// {Phi_+(x), Phi_-(x)} with one principal value.
  std::pair<complex_type, complex_type> boundary_values(const Real& x) const {
    const Real pi = boost::math::constants::pi<Real>();
    const Real pv = cauchy_.principal_value(x);
    const Real half_jump = pi * cauchy_.density(x);
    return {x_.plus(x) * (factor_ * complex_type(pv, half_jump) + constant_),
            x_.minus(x) * (factor_ * complex_type(pv, -half_jump) + constant_)};
  }

  /// rho(x) = g1(x) / X_+(x).
  complex_type density(const Real& x) const { return rho_factor_ * cauchy_.density(x); }

  /// (1/(2 pi i)) int rho dt: must vanish for index -1 (paper 15); reported for every index.
  complex_type orthogonality_defect() const { return factor_ * cauchy_.moment(); }

  /// The Cauchy integral of the weighted data (p = r_hi - n, q = r_lo - m).
  const jacobi_cauchy_integral<Real>& cauchy() const { return cauchy_; }

 private:
  canonical_function<Real> x_;
  complex_type constant_;
  jacobi_cauchy_integral<Real> cauchy_;
  complex_type rho_factor_, factor_;
};

/// Solves `problem` in the class of `index` (bounded end for index 0); `constant` is the
/// arbitrary constant C of index +1 (ignored otherwise); `order` Gauss nodes per piece (0 = default).
template <class Real>
riemann_solution<Real> solve_riemann_problem(const riemann_problem<Real>& problem, int index,
                                             bounded_end bounded = bounded_end::hi,
                                             std::complex<Real> constant = std::complex<Real>(0),
                                             std::size_t order = 0) {
  auto x = make_canonical_function(problem.lo, problem.hi, problem.theta, index, bounded);
  const Real p = problem.data_exponent_hi - x.exponent_hi;
  const Real q = problem.data_exponent_lo - x.exponent_lo;
  if (!(p > -1))
    quadrature::detail::throw_bad_parameter("rhabel::riemann::solve_riemann_problem", "data_exponent_hi - n", p,
                                            "(-1, inf) (g1 / X_+ must be integrable at hi)");
  if (!(q > -1))
    quadrature::detail::throw_bad_parameter("rhabel::riemann::solve_riemann_problem", "data_exponent_lo - m", q,
                                            "(-1, inf) (g1 / X_+ must be integrable at lo)");
  return riemann_solution<Real>(problem, x, index == 1 ? constant : std::complex<Real>(0), order);
}

}  // namespace rhabel::riemann
