// rhabel/abel/abel_operator.hpp
//
// The generalized Abel operator of the paper (eq. 8) on an interval [lo, hi] = [a, b]:
//
//     (A g)(s) = int_s^b g(t) (t - s)^(alpha-1) dt  -  kappa int_a^s g(t) (s - t)^(alpha-1) dt,
//     kappa    = cos((alpha + beta/2) pi) / cos(beta pi / 2),
//
// alpha in [0, 1) the material exponent, beta in (-1, 1) the friction parameter (the paper uses
// [0, 1); negative beta is the same theory with the friction reversed). At alpha = 0 the operator
// is the Carleman operator  PV int_a^b g(t)/(t - s) dt + pi tan(beta pi/2) g(s), reached
// uniformly: (1 - kappa)/alpha = 2 sin((alpha+beta) pi/2) sin(alpha pi/2) / (alpha cos(beta pi/2)).
//
// Edge behaviour and index classes (docs/theory.md section 3). The density is
//     g(t) = (1 - x)^del (1 + x)^gam S(x),   x = (2 t - a - b)/(b - a) in [-1, 1],
// with gam at the leading edge a (x = -1) and del at the trailing edge b (x = +1):
//     gam = (1 - 2 alpha - beta)/2  (edge::bounded)   or  -(1 + 2 alpha + beta)/2  (edge::unbounded),
//     del = (1 + beta)/2            (edge::bounded)   or  (beta - 1)/2             (edge::unbounded),
// nu = -(gam + del + alpha) in {-1, 0, +1}. "bounded" names the less singular representative: for
// 2 alpha + beta > 1 the bounded leading exponent is negative. The unbounded leading class needs
// gam > -1, i.e. 2 alpha + beta < 1; asking for it otherwise throws std::domain_error.
//
// Spectral relation (docs/theory.md section 4, re-verified by the tests through an independent quadrature):
//     A[w P_n^(del,gam)](y) = (L/2)^alpha lambda_n P_{n-nu}^(gam+nu, del+nu)(y),   P_{-1} := 0,
//     lambda_n = -2^(-nu) pi (1 - alpha)_n / (n! sin(pi del)),
// w = (1-x)^del (1+x)^gam in the reference variable (so g is written WITHOUT the factor
// (L/2)^(gam+del); this keeps intervals from 1e-9 to 1e6 free of overflow). Note the image family
// has its exponents SWAPPED: (p, q) = (gam + nu, del + nu) with p at x = +1.
//
// What is computed and how accurately:
//  * eigenvalue(n, e), eigenvalues(N, e): lambda_n above, the ratio (1 - alpha)_n / n! as the
//    running product of (k - alpha)/k (one value in O(n); all N in O(N), bit-identical to the
//    single values); relative error <= (3n + 8) eps (measured <= 0.09 (3n + 8) eps against the
//    Gamma-function form at 50 digits, n <= 2000, alpha in {0, 1e-8, 0.3, 0.999}).
//  * apply(density, s), s inside (a, b): exact through the spectral relation; relative error
//    O(n eps) of the image series.
//  * apply_by_quadrature(...): the SAME quantity by direct quadrature of the two one-sided
//    integrals (the independent route used for residuals), composite Gauss-Jacobi graded
//    geometrically toward the density's edge singularities. For alpha >= 0.05 the kernel
//    (t-s)^(alpha-1) is the Gauss-Jacobi weight. For alpha < 0.05 (uniform down to alpha = 0):
//    the smooth part of g at s is subtracted from both integrals and the diverging parts are
//    summed in closed form,  g(s) [ (b-s)^alpha B(del+1, alpha) - kappa (s-a)^alpha B(gam+1, alpha) ],
//    rewritten with expm1 and psi-integrals so that nothing cancels (see detail::numerics).
//    Accuracy: ~ 1e-14 relative to max(|A g(s)|, |g(s)| (L/2)^alpha) for smooth S of degree
//    < ~ 2 x nodes (near an unbounded edge the terms are ~ |g(s)| and cancel); an ESTIMATE.
//  * apply at s outside [a, b] (surface slope, paper 27-28): one integral with kernel
//    (t - s)^(alpha-1) (s < a) or -kappa (s - t)^(alpha-1) (s > b), by geometric panels graded
//    toward the near end: uniform as s -> a-, b+ (the value diverges there like the density's
//    edge exponent dictates).
//
// Conditioning (measured, see tests/abel): for alpha -> 1 the eigenvalues lambda_n, n >= 1, are
// ~ (1 - alpha)/n, so solutions lose ~ log10(1/(1 - alpha)) digits (alpha = 0.999: residual 5e-10
// relative in the worst class). For a class whose exponent is within delta of -1 (alpha + beta/2
// -> 1/2 with an unbounded leading edge) the double exponents are consistent with kappa only to
// ~eps, and A w depends on gam with sensitivity ~ kappa/(gam + 1)^2: the independent quadrature
// and the spectral route then differ by ~ eps kappa/delta^2 (1e-7 at delta = 1e-9).
//
// References: the source paper (eq. 8, 27, 28, 41; docs/theory.md); Szego ch. 4; DLMF 18.9 (Rodrigues
// derivative form 18.9.16 used for partial integrals); Samko, Kilbas, Marichev, "Fractional
// integrals and derivatives" section 30 (the operator with kernel (c1 + c2 sign)|t-s|^(alpha-1)).
#pragma once

#include "rhabel/abel/detail/numerics.hpp"
#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <Eigen/Dense>
#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <type_traits>
#include <vector>

namespace rhabel::abel {

/// Edge behaviour of the density at one end of an interval (see the header comment).
enum class edge { bounded, unbounded };

/// Endpoint exponents of one index class: g ~ (t - a)^gam at a, (b - t)^del at b; nu = -(gam+del+alpha).
template <class Real>
struct edge_exponents {
  Real gam;  ///< exponent at the leading edge a (x = -1)
  Real del;  ///< exponent at the trailing edge b (x = +1)
  int nu;    ///< index: -1 (bounded both), 0, +1 (unbounded both)
};

/// Material parameters (alpha, beta) and the derived kappa, with the alpha-uniform combinations.
template <class Real>
class abel_parameters {
 public:
  /// alpha in [0, 1), beta in (-1, 1); throws std::domain_error otherwise.
  abel_parameters(Real alpha, Real beta) : alpha_(alpha), beta_(beta) {
    using std::cos;
    using std::isfinite;
    using std::sin;
    if (!isfinite(alpha) || !(alpha >= 0) || !(alpha < 1))
      detail::throw_bad_parameter("rhabel::abel::abel_parameters", "alpha", alpha, "[0, 1)");
    if (!isfinite(beta) || !(beta > -1) || !(beta < 1))
      detail::throw_bad_parameter("rhabel::abel::abel_parameters", "beta", beta, "(-1, 1)");
    const Real pi = boost::math::constants::pi<Real>();
    const Real cb = cos(beta * pi / 2);
    // cos((alpha + beta/2) pi) = sin(pi (1/2 - alpha - beta/2)); the argument is formed as
    // (1/2 - alpha) - beta/2: the first difference is exact for alpha >= 1/4 (Sterbenz), so the
    // argument carries one rounding and kappa keeps full relative accuracy near kappa = 0.
    half_minus_ = (Real(1) / 2 - alpha) - beta / 2;
    kappa_ = sin(pi * half_minus_) / cb;
    const Real sin_half_over_alpha = alpha == 0 ? pi / 2 : sin(alpha * pi / 2) / alpha;
    one_minus_kappa_over_alpha_ = 2 * sin((alpha + beta) * pi / 2) * sin_half_over_alpha / cb;
  }

  /// From (alpha, kappa), alpha in (0, 1): beta = (2/pi) atan((cos(alpha pi) - kappa)/sin(alpha pi)).
  static abel_parameters from_kappa(Real alpha, Real kappa) {
    using std::atan;
    using std::cos;
    using std::isfinite;
    using std::sin;
    if (!isfinite(alpha) || !(alpha > 0) || !(alpha < 1))
      detail::throw_bad_parameter("rhabel::abel::abel_parameters::from_kappa", "alpha", alpha,
                                  "(0, 1) (at alpha = 0 kappa is 1 and beta is not determined)");
    if (!isfinite(kappa)) detail::throw_bad_parameter("rhabel::abel::abel_parameters::from_kappa", "kappa", kappa, "finite");
    const Real pi = boost::math::constants::pi<Real>();
    return abel_parameters(alpha, 2 * atan((cos(alpha * pi) - kappa) / sin(alpha * pi)) / pi);
  }

  const Real& alpha() const { return alpha_; }
  const Real& beta() const { return beta_; }
  const Real& kappa() const { return kappa_; }
  /// (1 - kappa)/alpha without cancellation; pi tan(beta pi/2) at alpha = 0.
  const Real& one_minus_kappa_over_alpha() const { return one_minus_kappa_over_alpha_; }

  /// Endpoint exponents of the class (leading, trailing). Throws std::domain_error when the
  /// leading unbounded class is not integrable (2 alpha + beta >= 1).
  edge_exponents<Real> exponents(edge leading, edge trailing) const {
    // (1 - 2 alpha - beta)/2 and -(1 + 2 alpha + beta)/2 = that - 1, from the accurately formed
    // 1/2 - alpha - beta/2 (consistent with kappa to the last bit).
    const Real gam = leading == edge::bounded ? half_minus_ : half_minus_ - 1;
    const Real del = trailing == edge::bounded ? (1 + beta_) / 2 : (beta_ - 1) / 2;
    if (!(gam > -1))
      detail::throw_bad_parameter("rhabel::abel::abel_parameters::exponents", "leading edge exponent gam", gam,
                                  "(-1, inf): edge::unbounded at the leading edge needs 2 alpha + beta < 1");
    const int nu = leading == edge::bounded ? (trailing == edge::bounded ? -1 : 0)
                                            : (trailing == edge::bounded ? 0 : 1);
    return {gam, del, nu};
  }

 private:
  Real alpha_, beta_, kappa_, one_minus_kappa_over_alpha_, half_minus_;
};

/// A density on [lo, hi]: g(t) = (1 - x)^del (1 + x)^gam sum_n c_n P_n^(del,gam)(x),
/// x = (2t - lo - hi)/(hi - lo). All evaluations below are exact up to rounding for the
/// represented series (they do not add truncation error).
template <class Real>
struct jacobi_density {
  Real lo = -1, hi = 1;
  Real gam = 0, del = 0;
  std::vector<Real> coefficients;

  Real half_length() const { return (hi - lo) / 2; }

  /// g(t) for lo <= t <= hi (0 outside; at an end with a negative exponent the value is inf).
  Real operator()(const Real& t) const {
    if (!(t >= lo) || !(t <= hi)) return Real(0);
    return value_at_distance(t - lo, hi - t);
  }

  /// g at the point with distances u = t - lo, v = hi - t (accurate near either end).
  Real value_at_distance(const Real& u, const Real& v) const {
    using std::pow;
    const Real h = half_length();
    const Real one_plus_x = u / h, one_minus_x = v / h;
    const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
    const Real S = series(x);
    // Exactly at an end: the limit (0, the finite value, or a signed infinity; never 0 * inf = NaN).
    if ((u == 0 && gam < 0) || (v == 0 && del < 0)) {
      if (S == 0) return Real(0);
      return S > 0 ? std::numeric_limits<Real>::infinity() : -std::numeric_limits<Real>::infinity();
    }
    return pow(one_minus_x, del) * pow(one_plus_x, gam) * S;
  }

  /// S(x) = sum_n c_n P_n^(del,gam)(x) (the smooth factor, reference variable).
  Real series(const Real& x) const {
    if (coefficients.empty()) return Real(0);
    return rhabel::quadrature::jacobi_clenshaw(coefficients, del, gam, x);
  }
  /// series(x) for many x: the recurrence coefficients computed once (quadrature::jacobi_series,
  /// the same sum as series() bit for bit; zero for an empty series).
  rhabel::quadrature::jacobi_series<Real> series_evaluator() const {
    return coefficients.empty() ? rhabel::quadrature::jacobi_series<Real>()
                                : rhabel::quadrature::jacobi_series<Real>(coefficients, del, gam);
  }

  /// int_lo^hi g(t) dt = (L/2) c_0 h_0^(del,gam)  (orthogonality).
  Real integral() const {
    if (coefficients.empty()) return Real(0);
    return half_length() * coefficients[0] * rhabel::quadrature::jacobi_norm_squared(0, del, gam);
  }

  /// int_lo^t g, t in [lo, hi]: c_0 times an incomplete beta function plus, for n >= 1, the
  /// Rodrigues form int_{-1}^X w P_n = -(1/(2n)) (1-X)^(del+1) (1+X)^(gam+1) P_{n-1}^(del+1,gam+1)(X).
  Real integral_to(const Real& t) const {
    using std::pow;
    if (coefficients.empty() || !(t > lo)) return Real(0);
    if (!(t < hi)) return integral();
    const Real h = half_length();
    const Real one_plus_x = (t - lo) / h, one_minus_x = (hi - t) / h;
    const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
    // n = 0: int_{-1}^X (1-x)^del (1+x)^gam dx = 2^(del+gam+1) B(gam+1, del+1) I_{(1+X)/2}(gam+1, del+1).
    const Real scale = pow(Real(2), del + gam + 1) * boost::math::beta(gam + 1, del + 1);
    // I_z(a, b) = 1 - I_{1-z}(b, a): take the form whose argument is the small distance.
    const Real part = one_plus_x <= one_minus_x ? boost::math::ibeta(gam + 1, del + 1, one_plus_x / 2)
                                                : 1 - boost::math::ibeta(del + 1, gam + 1, one_minus_x / 2);
    Real total = coefficients[0] * scale * part;
    if (coefficients.size() > 1) {
      std::vector<Real> shifted(coefficients.size() - 1);
      for (std::size_t n = 1; n < coefficients.size(); ++n) shifted[n - 1] = -coefficients[n] / (2 * Real(n));
      total += pow(one_minus_x, del + 1) * pow(one_plus_x, gam + 1) * rhabel::quadrature::jacobi_clenshaw(shifted, Real(del + 1), Real(gam + 1), x);
    }
    return h * total;
  }

  /// int_lo^hi t^k g(t) dt by Gauss-Jacobi (exact for the series: (deg + k)/2 + 1 nodes).
  Real moment(std::size_t k) const {
    using std::pow;
    if (coefficients.empty()) return Real(0);
    const std::size_t nodes = (coefficients.size() + k) / 2 + 2;
    const auto rule = quadrature::gauss_jacobi<Real>(nodes, del, gam);
    const Real h = half_length();
    Real sum = 0;
    for (std::size_t i = 0; i < rule.size(); ++i) {
      const Real t = rule.x_minus_lo[i] <= rule.hi_minus_x[i] ? lo + h * rule.x_minus_lo[i] : hi - h * rule.hi_minus_x[i];
      sum += rule.weight[i] * pow(t, Real(k)) * series(rule.x[i]);
    }
    return h * sum;
  }

  /// int_lo^hi f(t) g(t) dt for f smooth on each piece between the given breakpoints (sorted or
  /// not; those outside (lo, hi) are ignored). Composite Gauss-Jacobi per piece (edge weight on
  /// the end pieces, geometric grading toward an edge that a piece does not touch); `nodes` per
  /// panel (default: enough for the series plus 24). Accuracy: that of the piecewise-polynomial
  /// approximation of f; exact up to rounding for piecewise polynomials of modest degree.
  template <class F>
  Real integrate(F&& f, std::vector<Real> breakpoints = {}, std::size_t nodes = 0) const {
    using std::pow;
    if (coefficients.empty()) return Real(0);
    if (nodes == 0) nodes = coefficients.size() / 2 + 24;
    const Real h = half_length();
    const Real inf = std::numeric_limits<Real>::infinity();
    std::vector<Real> cuts{Real(-1)};
    std::sort(breakpoints.begin(), breakpoints.end());
    for (const Real& b : breakpoints)
      if (b > lo && b < hi) cuts.push_back(-1 + (b - lo) / h);
    cuts.push_back(Real(1));
    // The series with its recurrence coefficients computed once (series() recomputes them at
    // every node: O(n) each, the cost of a long series).
    const auto S = series_evaluator();
    Real sum = 0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const bool first = k == 0, last = k + 2 == cuts.size();
      // Pieces that do not touch an end see that end's weight singularity at a distance:
      // graded panels toward it (a breakpoint 1e-12 from an end costs ~ 40 panels, stays exact).
      const panel_integrator<Real> rule(last ? del : Real(0), first ? gam : Real(0), nodes);
      const Real start = cuts[k] + 1, end = 1 - cuts[k + 1];  // distances of the piece ends from -1, +1
      sum += rule.integrate(cuts[k + 1] - cuts[k], first ? inf : start, last ? inf : end,
                            [&](const Real& u, const Real& v) {
                              const Real one_plus_x = start + u, one_minus_x = end + v;
                              const Real x = one_plus_x <= one_minus_x ? one_plus_x - 1 : 1 - one_minus_x;
                              Real weight = 1;
                              if (!first) weight *= pow(one_plus_x, gam);
                              if (!last) weight *= pow(one_minus_x, del);
                              const Real t = one_plus_x <= one_minus_x ? lo + h * one_plus_x : hi - h * one_minus_x;
                              return weight * f(t) * S(x);
                            });
    }
    return h * sum;
  }

  /// Leading-edge intensity K_a = lim_{t->a+} g(t) (t - a)^(-gam) = (2/L)^gam 2^del S(-1).
  Real intensity_leading() const {
    using std::pow;
    return pow(2 / (hi - lo), gam) * pow(Real(2), del) * series(Real(-1));
  }
  /// Trailing-edge intensity K_b = lim_{t->b-} g(t) (b - t)^(-del) = (2/L)^del 2^gam S(+1).
  Real intensity_trailing() const {
    using std::pow;
    return pow(2 / (hi - lo), del) * pow(Real(2), gam) * series(Real(1));
  }
};

/// The operator A on one interval [lo, hi] for given material parameters.
template <class Real>
class abel_operator {
 public:
  abel_operator(const abel_parameters<Real>& parameters, Real lo, Real hi) : par_(parameters), lo_(lo), hi_(hi) {
    using std::isfinite;
    if (!isfinite(lo)) detail::throw_bad_parameter("rhabel::abel::abel_operator", "lo", lo, "finite");
    if (!isfinite(hi) || !(hi > lo)) detail::throw_bad_parameter("rhabel::abel::abel_operator", "hi", hi, "finite and > lo");
  }
  abel_operator(Real alpha, Real beta, Real lo, Real hi) : abel_operator(abel_parameters<Real>(alpha, beta), lo, hi) {}

  const abel_parameters<Real>& parameters() const { return par_; }
  const Real& lo() const { return lo_; }
  const Real& hi() const { return hi_; }
  Real half_length() const { return (hi_ - lo_) / 2; }
  edge_exponents<Real> exponents(edge leading, edge trailing) const { return par_.exponents(leading, trailing); }

  /// lambda_n of the spectral relation (reference interval, without the (L/2)^alpha factor),
  ///     lambda_n = -2^(-nu) pi (1 - alpha)_n / (n! sin(pi del)),
  /// the ratio (1 - alpha)_n / n! = prod_{k=1}^n (k - alpha)/k formed in O(n) operations (relative
  /// error <= ~3 n eps: three roundings per factor). For all of lambda_0 .. lambda_{N-1} use
  /// eigenvalues(N, e): O(N) in all instead of O(N^2), and bit-identical to this.
  Real eigenvalue(std::size_t n, const edge_exponents<Real>& e) const {
    Real rising = 1;  // (1 - alpha)_n / n!
    for (std::size_t k = 1; k <= n; ++k) rising = next_rising(rising, k);
    return eigenvalue_factor(e) * rising / eigenvalue_denominator(e);
  }

  /// lambda_0, ..., lambda_{count-1} (see eigenvalue()) by the ratio recurrence
  /// lambda_n / lambda_{n-1} = (n - alpha)/n: O(count) operations. Each lambda_n carries the
  /// same roundings in the same order as eigenvalue(n, e) (the running product is the same
  /// sequence of partial products), so the two agree bit for bit; against the Gamma-function
  /// form -2^(-nu) pi Gamma(n+1-alpha) / (Gamma(1-alpha) n! sin(pi del)) the relative error is
  /// <= ~3 n eps (tests/abel/test_operator.cpp, n < 2001, alpha in {0, 1e-8, 0.3, 0.999}).
  std::vector<Real> eigenvalues(std::size_t count, const edge_exponents<Real>& e) const {
    std::vector<Real> out;
    out.reserve(count);
    const Real factor = eigenvalue_factor(e), denominator = eigenvalue_denominator(e);
    Real rising = 1;
    for (std::size_t n = 0; n < count; ++n) {
      if (n > 0) rising = next_rising(rising, n);
      out.push_back(factor * rising / denominator);
    }
    return out;
  }

  /// A g at s for a series density of this interval. Inside (lo, hi): spectral relation.
  /// Outside [lo, hi]: graded quadrature (see header). At s = lo or hi: the one-sided limit of
  /// the spectral image (finite; the image polynomial is evaluated at x = -1 or +1).
  Real apply(const jacobi_density<Real>& g, const Real& s) const {
    using std::pow;
    if (g.coefficients.empty()) return Real(0);
    const Real h = half_length();
    if (s >= lo_ && s <= hi_) {
      const Real x = (s - lo_) <= (hi_ - s) ? -1 + (s - lo_) / h : 1 - (hi_ - s) / h;
      const Real nu_real = -(g.gam + g.del + par_.alpha());
      const int nu = static_cast<int>(std::lround(static_cast<double>(nu_real)));
      const edge_exponents<Real> e{g.gam, g.del, nu};
      std::vector<Real> image;
      const std::vector<Real> lambda = eigenvalues(g.coefficients.size(), e);
      for (std::size_t n = 0; n < g.coefficients.size(); ++n) {
        const long m = static_cast<long>(n) - nu;
        if (m < 0) continue;
        if (image.size() <= static_cast<std::size_t>(m)) image.resize(static_cast<std::size_t>(m) + 1, Real(0));
        image[static_cast<std::size_t>(m)] += lambda[n] * g.coefficients[n];
      }
      // Image family (gam + nu, del + nu): for nu = -1 an exponent may be <= -1, which only
      // detail::jacobi_sum_any handles (it defers to quadrature::jacobi_clenshaw otherwise).
      return pow(h, par_.alpha()) * detail::jacobi_sum_any(image, g.gam + Real(nu), g.del + Real(nu), x);
    }
    return apply_outside([&](const Real& x) { return g.series(x); }, g.gam, g.del, g.coefficients.size(), s);
  }

  /// A g at s (any s, inside or outside) for g(t) = (1-x)^del (1+x)^gam S(x) with S a callable of
  /// the reference variable x, by direct quadrature of the one-sided integrals (independent of
  /// the spectral relation). `degree_hint` ~ the polynomial degree S needs (sets the node count).
  /// Inside, S must be smooth (analytic near [-1, 1] for spectral accuracy). For many points
  /// with the same (gam, del) use quadrature_evaluator (it caches the rules).
  template <class S>
  Real apply_by_quadrature(S&& smooth, const Real& gam, const Real& del, const Real& s,
                           std::size_t degree_hint = 32) const;

  /// Caches the rules and constants of apply_by_quadrature for one class (gam, del).
  class quadrature_evaluator {
   public:
    quadrature_evaluator(const abel_operator& op, const Real& gam, const Real& del, std::size_t degree_hint = 32)
        : op_(op), gam_(gam), del_(del), degree_hint_(degree_hint),
          nodes_(std::max<std::size_t>(16, degree_hint / 2 + 12)),
          subtract_(op.parameters().alpha() < subtraction_threshold()),
          right_(del, subtract_ ? op.parameters().alpha() : op.parameters().alpha() - 1, nodes_),
          left_(subtract_ ? op.parameters().alpha() : op.parameters().alpha() - 1, gam, nodes_) {
      using std::exp;
      const Real alpha = op.parameters().alpha();
      E_del_ = detail::lgamma_difference_over_alpha(del, alpha);
      E_gam_ = detail::lgamma_difference_over_alpha(gam, alpha);
      r_gam_ = boost::math::tgamma(1 + alpha) * exp(-alpha * E_gam_);
    }

    /// A g(s) for g = w S. S is called as S(x), or as S(x, 1 + x, 1 - x) when it takes three
    /// arguments (the distances to the ends without the rounding of x: a factor with a pole at
    /// distance d beyond an end needs them to ~eps relative instead of eps/d). beyond_lo,
    /// beyond_hi (reference units, default none): distances beyond x = -1 and x = +1 of
    /// singularities of S (the poles of detail/layered_union.hpp); the panels are graded toward
    /// them as toward s. Used inside [lo, hi] only.
    template <class S>
    Real operator()(S&& smooth_in, const Real& s, const Real& beyond_lo = std::numeric_limits<Real>::infinity(),
                    const Real& beyond_hi = std::numeric_limits<Real>::infinity()) const {
      const auto smooth3 = [&](const Real& x, const Real& one_plus_x, const Real& one_minus_x) -> Real {
        if constexpr (std::is_invocable_v<S&, const Real&, const Real&, const Real&>)
          return smooth_in(x, one_plus_x, one_minus_x);
        else
          return smooth_in(x);
      };
      const abel_operator& op = op_;
      if (!(s > op.lo_) || !(s < op.hi_)) {
        if (s == op.lo_ || s == op.hi_)
          detail::throw_bad_parameter("rhabel::abel::abel_operator::apply_by_quadrature", "s", s,
                                      "s != lo, hi (the one-sided integrals are singular at the ends)");
        return op.apply_outside([&](const Real& x) { return smooth3(x, 1 + x, 1 - x); }, gam_, del_, degree_hint_, s);
      }
      return inside<Real>(smooth3, s, beyond_lo, beyond_hi);
    }

    /// A (w S_k)(s), k = 1 ... K, for lo < s < hi in ONE pass over the nodes: values(x, 1 + x,
    /// 1 - x) returns the K factors there as an Eigen::Array<Real, Eigen::Dynamic, 1>. The same
    /// rule as operator() (bit for bit per factor when K = 1); the panels are graded toward
    /// beyond_lo, beyond_hi, which must be the nearest singularities of all the S_k.
    template <class S>
    Eigen::Array<Real, Eigen::Dynamic, 1> many(S&& values, const Real& s,
                                               const Real& beyond_lo = std::numeric_limits<Real>::infinity(),
                                               const Real& beyond_hi = std::numeric_limits<Real>::infinity()) const {
      if (!(s > op_.lo_) || !(s < op_.hi_))
        detail::throw_bad_parameter("rhabel::abel::abel_operator::quadrature_evaluator::many", "s", s, "(lo, hi)");
      using V = Eigen::Array<Real, Eigen::Dynamic, 1>;
      return inside<V>([&](const Real& x, const Real& p, const Real& m) -> V { return values(x, p, m); }, s, beyond_lo,
                       beyond_hi);
    }

    /// operator() for the smooth factor given as a series, with the same value bit for bit but the
    /// series summed at all of the point's nodes in one jacobi_series::evaluate call (four
    /// recurrences interleaved, ~3x fewer ns a node at degree ~80): a first pass records, in order,
    /// the abscissae at which operator() asks for the factor (its nodes do not depend on the
    /// factor's values), a second pass replays the sums. The rule's own work is done twice, so
    /// this pays off for long series only (punch's residual uses it from degree 48 on).
    Real with_series(const rhabel::quadrature::jacobi_series<Real>& series, const Real& s) const {
      std::vector<Real> abscissae;
      (*this)([&](const Real& x) {
        abscissae.push_back(x);
        return Real(0);
      }, s);
      std::vector<Real> sums(abscissae.size());
      series.evaluate(abscissae.data(), sums.data(), abscissae.size());
      std::size_t next = 0;
      return (*this)([&](const Real&) { return sums[next++]; }, s);
    }

   private:
    static Real zero_like(const Real&) { return Real(0); }
    static Eigen::Array<Real, Eigen::Dynamic, 1> zero_like(const Eigen::Array<Real, Eigen::Dynamic, 1>& v) {
      return Eigen::Array<Real, Eigen::Dynamic, 1>::Zero(v.size());
    }
    /// panel_integrator::integrate for a value type V (Real: the same sum, in the same order).
    template <class V, class F>
    static V integrate(const panel_integrator<Real>& rule, const Real& len, const Real& d_left,
                       const Real& d_right, const V& zero, F&& f) {
      V sum = zero;
      rule.for_each_node(len, d_left, d_right, [&](const Real& u, const Real& v, const Real& weight) { sum += weight * f(u, v); });
      return sum;
    }
    /// operator() and many() at lo < s < hi (V = Real or an Eigen array of factors).
    template <class V, class S3>
    V inside(const S3& smooth3, const Real& s, const Real& beyond_lo, const Real& beyond_hi) const {
      using std::log;
      using std::pow;
      const abel_operator& op = op_;
      const Real alpha = op.par_.alpha(), kappa = op.par_.kappa();
      const Real gam = gam_, del = del_;
      const Real h = op.half_length();
      const Real one_plus_y = (s - op.lo_) / h, one_minus_y = (op.hi_ - s) / h;
      const Real y = one_plus_y <= one_minus_y ? one_plus_y - 1 : 1 - one_minus_y;
      const V S_y = smooth3(y, one_plus_y, one_minus_y);
      const V zero = zero_like(S_y);
      if (!subtract_) {
        // alpha >= 0.05: Gauss-Jacobi with the kernel (x-y)^(alpha-1) as weight, no subtraction
        // (each one-sided integral is O(1/alpha) <= 20 x the result: at most ~1.3 digits lost).
        const V R = integrate(right_, one_minus_y, one_plus_y, beyond_hi, zero, [&](const Real& u, const Real& v) -> V {
          const Real x = u <= v ? y + u : 1 - v;  // u = x - y, v = 1 - x
          return pow(one_plus_y + u, gam) * smooth3(x, one_plus_y + u, v);
        });
        const V Lft = integrate(left_, one_plus_y, beyond_lo, one_minus_y, zero, [&](const Real& u, const Real& v) -> V {
          const Real x = u <= v ? u - 1 : y - v;  // u = x + 1, v = y - x
          return pow(one_minus_y + v, del) * smooth3(x, u, one_minus_y + v);
        });
        return V(pow(h, alpha) * (R - kappa * Lft));
      }
      // Right: int_y^1 (1-x)^del (x-y)^alpha [h(x) - h(y)]/(x - y) dx,  h = (1+x)^gam S.
      const V h_y = pow(one_plus_y, gam) * S_y;
      const V R = integrate(right_, one_minus_y, one_plus_y, beyond_hi, zero, [&](const Real& u, const Real& v) -> V {
        const Real x = u <= v ? y + u : 1 - v;  // u = x - y, v = 1 - x
        return (pow(one_plus_y + u, gam) * smooth3(x, one_plus_y + u, v) - h_y) / u;
      });
      // Left: int_{-1}^y (1+x)^gam (y-x)^alpha [k(x) - k(y)]/(y - x) dx,  k = (1-x)^del S.
      const V k_y = pow(one_minus_y, del) * S_y;
      const V Lft = integrate(left_, one_plus_y, beyond_lo, one_minus_y, zero, [&](const Real& u, const Real& v) -> V {
        const Real x = u <= v ? u - 1 : y - v;  // u = x + 1, v = y - x
        return (pow(one_minus_y + v, del) * smooth3(x, u, one_minus_y + v) - k_y) / v;
      });
      // Closed-form part g(y) C(y), C = [(1-y)^alpha r(del) - kappa (1+y)^alpha r(gam)]/alpha,
      // r(c) = Gamma(1+alpha) Gamma(c+1)/Gamma(c+1+alpha) = Gamma(1+alpha) exp(-alpha E(c)),
      // = (1+y)^alpha r(gam) [exprel(alpha z) z + (1 - kappa)/alpha], z = log((1-y)/(1+y)) - E(del) + E(gam).
      const Real z = log(one_minus_y / one_plus_y) - E_del_ + E_gam_;
      const Real C = pow(one_plus_y, alpha) * r_gam_ *
                     (detail::exprel(alpha * z) * z + op.par_.one_minus_kappa_over_alpha());
      const V g_y = pow(one_minus_y, del) * h_y;
      return V(pow(h, alpha) * (R - kappa * Lft + g_y * C));
    }

   public:
    /// Below this alpha the one-sided integrals are combined analytically (subtraction of g(s)).
    static Real subtraction_threshold() { return Real(1) / 20; }

   private:
    const abel_operator& op_;
    Real gam_, del_;
    std::size_t degree_hint_, nodes_;
    bool subtract_;
    panel_integrator<Real> right_, left_;
    Real E_del_, E_gam_, r_gam_;
  };

 private:
  // The factors of lambda_n (eigenvalue(), eigenvalues()): -2^(-nu) pi, sin(pi del), and the
  // step (1 - alpha)_k/k! = (1 - alpha)_(k-1)/(k-1)! x (k - alpha)/k of the running product.
  static Real eigenvalue_factor(const edge_exponents<Real>& e) {
    using std::pow;
    return -pow(Real(2), Real(-e.nu)) * boost::math::constants::pi<Real>();
  }
  static Real eigenvalue_denominator(const edge_exponents<Real>& e) {
    using std::sin;
    return sin(boost::math::constants::pi<Real>() * e.del);
  }
  Real next_rising(const Real& rising, std::size_t k) const { return rising * ((Real(k) - par_.alpha()) / Real(k)); }

  static Real exp_(const Real& x) {
    using std::exp;
    return exp(x);
  }

  template <class S>
  Real apply_outside(S&& smooth, const Real& gam, const Real& del, std::size_t degree_hint, const Real& s) const {
    using std::pow;
    const Real alpha = par_.alpha(), kappa = par_.kappa();
    const Real h = half_length();
    const std::size_t nodes = std::max<std::size_t>(16, degree_hint / 2 + 12);
    const panel_integrator<Real> rule(del, gam, nodes);
    const Real inf = std::numeric_limits<Real>::infinity();
    if (s < lo_) {
      const Real d = (lo_ - s) / h;  // distance of y below -1
      const Real I = rule.integrate(Real(2), d, inf, [&](const Real& u, const Real& v) {
        const Real x = u <= v ? u - 1 : 1 - v;
        return pow(u + d, alpha - 1) * smooth(x);
      });
      return pow(h, alpha) * I;
    }
    const Real d = (s - hi_) / h;
    const Real I = rule.integrate(Real(2), inf, d, [&](const Real& u, const Real& v) {
      const Real x = u <= v ? u - 1 : 1 - v;
      return pow(v + d, alpha - 1) * smooth(x);
    });
    return -kappa * pow(h, alpha) * I;
  }

  abel_parameters<Real> par_;
  Real lo_, hi_;
};

template <class Real>
template <class S>
Real abel_operator<Real>::apply_by_quadrature(S&& smooth, const Real& gam, const Real& del, const Real& s,
                                              std::size_t degree_hint) const {
  return quadrature_evaluator(*this, gam, del, degree_hint)(smooth, s);
}

}  // namespace rhabel::abel
