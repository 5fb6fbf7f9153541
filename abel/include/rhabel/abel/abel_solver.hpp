// rhabel/abel/abel_solver.hpp
//
// Solves the generalized Abel equation  A g = F  on [lo, hi] (abel_operator.hpp) in a chosen
// index class (leading, trailing edge behaviour), for
//   * F a callable (smooth on [lo, hi]):           solve(op, leading, trailing, F, options)
//   * F piecewise smooth with interior breakpoints: solve_piecewise(op, leading, trailing, F, breaks, options)
//   * F given by its coefficients in the image basis P_m^(gam+nu, del+nu):  solve_image_series(...)
//   * F a polynomial in s (monomial coefficients):  solve_polynomial(...)
//
// Method. Write F~(y) = (L/2)^(-alpha) F(s(y)). Its coefficients d_m in the image basis are
// divided by the eigenvalues of the spectral relation: c_n = d_{n-nu} / lambda_n.
//  * smooth F: interpolation at m Chebyshev points, exact re-expansion Chebyshev -> P^(p,q)
//    (uniform through p = -1, so the class nu = -1 works on both sides of alpha + beta/2 = 1/2),
//    m doubled from 17 until the last eighth of the Chebyshev coefficients is below
//    tolerance x max|F~| (or max_degree is reached: status not_converged). Spectral accuracy.
//  * piecewise F: d_m = <F~, omega P_m>/h_m with omega = (1-y)^p (1+y)^q by Gauss-Jacobi on each
//    piece (exact for piecewise polynomials; for step data these ARE the Rodrigues coefficients
//    int omega P_m = [(1-y)^(p+1)(1+y)^(q+1) P_{m-1}^(p+1,q+1)]/(-2m), which the tests check).
//    Needs p > -1: for nu = -1 this is 2 alpha + beta < 1 (the case where an interior apex
//    occurs physically); otherwise std::domain_error. The density of step data converges only
//    algebraically in the degree (g has an interior singularity |t - t0|^(-alpha), log at
//    alpha = 0); int g is nevertheless exact (c_0 only) but int_lo^t0 g converges like
//    degree^-(1 - alpha) (kink data: degree^-(2 - alpha)). For a jump at ONE point use
//    solve_step (step_enrichment.hpp): the local solution is built in and int_lo^t0 g reaches
//    ~1e-13 at 65 points for an apex away from the edges (all alpha in [0, 1), alpha = 0 with the
//    log singularity included; an apex within ~1e-2 L of an edge is reported not_converged).
//
// Evidence returned (abel_solution):
//  * nu = -1: solvability_defect = d_0, the image-P_0 coefficient of F~ (a weighted mean of F~;
//    zero iff F satisfies the orthogonality condition of docs/theory.md section 4). The solution solves
//    A g = F - (L/2)^alpha d_0 exactly (to rounding + truncation).
//  * nu = +1: homogeneous = w (c_0 chosen so that its integral is 1); the returned density has
//    c_0 = 0 unless options.load is set (then int g = load).
//  * residual: max_j |A g(s_j) - F(s_j) (+ defect)| / max_j |F(s_j)| at residual_points interior
//    Chebyshev points, A g computed by DIRECT QUADRATURE of the two one-sided integrals
//    (apply_by_quadrature), never through the spectral relation. The residual grid never shares
//    a node with the interpolation grid (detail::residual_grid_size: residual_points or one more).
//    An estimate, not a bound.
//  * coefficient_tail: size of the discarded Chebyshev tail relative to max|F~| (smooth F),
//    an estimate of the relative error of the image expansion; degree; status: converged only
//    with a finite density (and a finite residual when computed); for piecewise data only with
//    the residual within piecewise_residual_acceptance.
// Limit: F is sampled at lo + h (1 + x) rounded to a double, so an interval far from the origin
// (|lo| >> L) sees its data at abscissae off by ~eps |lo|, a relative error ~eps |lo|/L of the
// data's variation: smooth data on [1e3, 1e3 + 1e-6] end not_converged with residual 1.4e-8, on
// [1e6, 1e6 + 1e-6] with 2.7e-5 (throwaway driver). Shift the origin to the interval first.
#pragma once

#include "rhabel/abel/abel_operator.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

namespace rhabel::abel {

enum class solve_status {
  converged,      ///< tolerance met (smooth data) / coefficients exact (series, polynomial); piecewise:
                  ///< residual within piecewise_residual_acceptance; always a finite density
  not_converged,  ///< max_degree reached before the Chebyshev tail fell below the tolerance; piecewise:
                  ///< residual above piecewise_residual_acceptance; or a non-finite density or residual
};

/// The residual (relative to max|F|) up to which solve_piecewise reports converged. Piecewise data
/// converge only algebraically in the degree: at the default 256 coefficients step data reach a
/// residual of 6.5e-3 and kink data 2e-5 (alpha = 0.3, measured); 4 coefficients for |s| leave
/// 0.2, 2 leave 0.8, which must not be reported as a solution.
inline constexpr double piecewise_residual_acceptance = 1e-2;

template <class Real>
struct solve_options {
  std::size_t degree = 0;           ///< number of image coefficients; 0 = adaptive (smooth F)
  std::size_t max_degree = 1024;    ///< adaptive cap (smooth F)
  Real tolerance = 16 * std::numeric_limits<Real>::epsilon();  ///< relative Chebyshev tail
  std::size_t residual_points = 8;  ///< 0 = do not compute the independent residual
  std::optional<Real> load;         ///< nu = +1: prescribe int g (else c_0 = 0)
  std::size_t piecewise_degree = 256;  ///< image coefficients for piecewise F (degree = 0)
};

template <class Real>
struct abel_solution {
  jacobi_density<Real> density;      ///< g: the solution (see nu = +1 / -1 notes above)
  edge_exponents<Real> exponents{};  ///< (gam, del, nu) of the class
  Real solvability_defect = 0;       ///< nu = -1: image-P_0 coefficient of (L/2)^(-alpha) F
  jacobi_density<Real> homogeneous;  ///< nu = +1: unit-integral homogeneous solution; else empty
  Real residual = std::numeric_limits<Real>::quiet_NaN();  ///< independent relative residual (NaN if not computed)
  Real coefficient_tail = 0;         ///< relative size of the discarded image coefficients (estimate)
  std::size_t degree = 0;            ///< number of image coefficients used
  solve_status status = solve_status::converged;

  /// nu = +1 only: the solution with int g = load (adds a multiple of `homogeneous`).
  jacobi_density<Real> with_load(const Real& load) const {
    jacobi_density<Real> g = density;
    if (exponents.nu != 1 || homogeneous.coefficients.empty())
      detail::throw_bad_parameter("rhabel::abel::abel_solution::with_load", "nu", exponents.nu, "{+1} (a free constant exists only for nu = +1)");
    if (g.coefficients.empty()) g.coefficients.assign(1, Real(0));
    g.coefficients[0] += (load - density.integral()) * homogeneous.coefficients[0];
    return g;
  }
};

namespace detail {

template <class Real>
void check_finite_value(const char* function, const Real& value, const Real& s) {
  using std::isfinite;
  if (!isfinite(value)) {
    std::ostringstream where;
    where.precision(17);
    where << "finite (F(" << s << ") is not)";
    throw_bad_parameter(function, "F", value, where.str().c_str());
  }
}

/// Builds the solution from image coefficients d (basis P^(gam+nu, del+nu)) of F~.
template <class Real>
abel_solution<Real> solution_from_image(const abel_operator<Real>& op, const edge_exponents<Real>& e,
                                        const std::vector<Real>& d, const solve_options<Real>& options) {
  abel_solution<Real> sol;
  sol.exponents = e;
  sol.degree = d.size();
  sol.density.lo = op.lo();
  sol.density.hi = op.hi();
  sol.density.gam = e.gam;
  sol.density.del = e.del;
  std::vector<Real>& c = sol.density.coefficients;
  // c_n = d_{n - nu} / lambda_n: lambda_0 .. lambda_{d.size()} in O(d.size()) (abel_operator::eigenvalues).
  const std::vector<Real> lambda = op.eigenvalues(d.size() + 1, e);
  if (e.nu == -1) {
    sol.solvability_defect = d.empty() ? Real(0) : d[0];
    for (std::size_t m = 1; m < d.size(); ++m) c.push_back(d[m] / lambda[m - 1]);
  } else if (e.nu == 0) {
    for (std::size_t m = 0; m < d.size(); ++m) c.push_back(d[m] / lambda[m]);
  } else {
    c.push_back(Real(0));
    for (std::size_t m = 0; m < d.size(); ++m) c.push_back(d[m] / lambda[m + 1]);
    sol.homogeneous = sol.density;
    const Real h0 = rhabel::quadrature::jacobi_norm_squared(0, e.del, e.gam);
    sol.homogeneous.coefficients.assign(1, 1 / (op.half_length() * h0));
    if (options.load) c[0] = *options.load * sol.homogeneous.coefficients[0];
  }
  if (c.empty()) c.push_back(Real(0));
  return sol;
}

/// Size r' >= r of a first-kind Chebyshev grid that shares no node with the first-kind grid of
/// size m (m = 0: no constraint). Nodes cos(pi (2j+1)/(2r')) and cos(pi (2k+1)/(2m)) coincide
/// iff (2j+1) m = (2k+1) r' has a solution, i.e. iff m and r' contain the same power of 2; r and
/// r + 1 never do both. A residual sampled at the collocation points themselves is ~ rounding
/// whatever the error (measured: 1e-15 for a solution wrong by 1e-3), so it must avoid them.
inline bool same_power_of_two(std::size_t a, std::size_t b) {
  while (a % 2 == 0 && b % 2 == 0 && a > 0 && b > 0) {
    a /= 2;
    b /= 2;
  }
  return a % 2 == 1 && b % 2 == 1;
}
inline std::size_t residual_grid_size(std::size_t r, std::size_t m) {
  if (m == 0 || r == 0) return r;
  return same_power_of_two(r, m) ? r + 1 : r;
}

/// Independent residual: direct quadrature of A g at interior Chebyshev points (never at the
/// collocation points of a grid of size collocation_size, see residual_grid_size).
template <class Real, class F>
Real independent_residual(const abel_operator<Real>& op, const abel_solution<Real>& sol, F&& f,
                          std::size_t points, std::size_t collocation_size = 0) {
  using std::abs;
  using std::max;
  using std::pow;
  const chebyshev_grid<Real> grid(residual_grid_size(points, collocation_size));
  points = grid.x.size();
  const Real h = op.half_length();
  const Real defect = sol.exponents.nu == -1 ? pow(h, op.parameters().alpha()) * sol.solvability_defect : Real(0);
  const typename abel_operator<Real>::quadrature_evaluator evaluate(op, sol.density.gam, sol.density.del,
                                                                    sol.density.coefficients.size());
  // sol.density.series(x) with the recurrence coefficients computed once (the same sum to a few
  // ulps; quadrature::jacobi_series): it is evaluated at every node of every check point.
  const auto series = sol.density.series_evaluator();
  Real worst = 0, scale = 0;
  for (std::size_t j = 0; j < points; ++j) {
    const Real s = grid.one_plus_x[j] <= grid.one_minus_x[j] ? op.lo() + h * grid.one_plus_x[j]
                                                             : op.hi() - h * grid.one_minus_x[j];
    const Real Ag = evaluate([&](const Real& x) { return series(x); }, s);
    const Real Fs = f(s);
    worst = max(worst, abs(Ag - (Fs - defect)));
    scale = max(scale, abs(Fs));
  }
  return scale > 0 ? worst / scale : worst;
}

/// Whether every coefficient of the solution's density is finite.
template <class Real>
bool finite_density(const abel_solution<Real>& sol) {
  using std::isfinite;
  for (const Real& c : sol.density.coefficients) {
    if (!isfinite(c)) return false;
  }
  return true;
}

}  // namespace detail

/// Solve A g = F with the image coefficients d_m of F~ = (L/2)^(-alpha) F in the basis
/// P_m^(gam+nu, del+nu) given. Exact (no truncation); no residual is computed.
template <class Real>
abel_solution<Real> solve_image_series(const abel_operator<Real>& op, edge leading, edge trailing,
                                       const std::vector<Real>& image_coefficients,
                                       const solve_options<Real>& options = {}) {
  const auto e = op.exponents(leading, trailing);
  return detail::solution_from_image(op, e, image_coefficients, options);
}

/// Solve A g = F for F smooth on [lo, hi] (callable Real -> Real). See the header comment.
template <class Real, class F>
abel_solution<Real> solve(const abel_operator<Real>& op, edge leading, edge trailing, F&& f,
                          const solve_options<Real>& options = {}) {
  using std::abs;
  using std::max;
  using std::pow;
  const auto e = op.exponents(leading, trailing);
  const Real h = op.half_length();
  const Real scale_F = pow(h, -op.parameters().alpha());
  const Real p = e.gam + Real(e.nu), q = e.del + Real(e.nu);
  std::size_t m = options.degree != 0 ? options.degree : 17;
  std::vector<Real> a;
  Real tail = 0, previous_tail = std::numeric_limits<Real>::infinity();
  solve_status status = solve_status::converged;
  for (;;) {
    const chebyshev_grid<Real> grid(m);
    std::vector<Real> values(m);
    for (std::size_t j = 0; j < m; ++j) {
      const Real s = grid.one_plus_x[j] <= grid.one_minus_x[j] ? op.lo() + h * grid.one_plus_x[j]
                                                               : op.hi() - h * grid.one_minus_x[j];
      const Real v = f(s);
      detail::check_finite_value("rhabel::abel::solve", v, s);
      values[j] = scale_F * v;
    }
    a = chebyshev_coefficients(values);
    Real biggest = 0;
    for (const Real& v : values) biggest = max(biggest, abs(v));
    const std::size_t tail_start = m - std::max<std::size_t>(2, m / 8);
    tail = 0;
    for (std::size_t k = tail_start; k < m; ++k) tail = max(tail, abs(a[k]));
    if (biggest > 0) tail /= biggest;
    if (options.degree != 0) break;
    if (tail <= options.tolerance) break;
    // Rounding plateau: the tail stopped decreasing at the noise level of the interpolation.
    if (tail <= 1024 * std::numeric_limits<Real>::epsilon() && previous_tail <= 10 * tail) break;
    previous_tail = tail;
    if (2 * m - 1 > options.max_degree) {
      status = solve_status::not_converged;
      break;
    }
    m = 2 * m - 1;
  }
  // Chop the negligible tail (keeps the density degree honest).
  std::size_t keep = a.size();
  Real biggest_a = 0;
  for (const Real& v : a) biggest_a = max(biggest_a, abs(v));
  // Coefficients at the rounding level of the interpolation (8 eps max|a|) carry no information
  // and the exact re-expansion in P^(p,q) would only amplify them.
  while (keep > 1 && abs(a[keep - 1]) <= 8 * std::numeric_limits<Real>::epsilon() * biggest_a) --keep;
  a.resize(keep);
  const std::vector<Real> d = detail::chebyshev_to_jacobi(a, p, q);
  abel_solution<Real> sol = detail::solution_from_image(op, e, d, options);
  sol.coefficient_tail = tail;
  sol.degree = m;
  if (options.residual_points > 0) sol.residual = detail::independent_residual(op, sol, f, options.residual_points, m);
  using std::isfinite;
  const bool finite_residual = options.residual_points == 0 || isfinite(sol.residual);
  sol.status = finite_residual && detail::finite_density(sol) ? status : solve_status::not_converged;
  return sol;
}

/// Solve A g = P for a polynomial P(s) = sum_k coefficients[k] s^k (exact up to rounding).
template <class Real>
abel_solution<Real> solve_polynomial(const abel_operator<Real>& op, edge leading, edge trailing,
                                     const std::vector<Real>& coefficients, solve_options<Real> options = {}) {
  options.degree = std::max<std::size_t>(coefficients.size(), 1);
  auto poly = [&](const Real& s) {
    Real v = 0;
    for (std::size_t k = coefficients.size(); k-- > 0;) v = v * s + coefficients[k];
    return v;
  };
  return solve(op, leading, trailing, poly, options);
}

/// Solve A g = F for F smooth between the given interior breakpoints (jumps or kinks there).
/// Image coefficients by Gauss-Jacobi on each piece: exact for piecewise polynomial data.
template <class Real, class F>
abel_solution<Real> solve_piecewise(const abel_operator<Real>& op, edge leading, edge trailing, F&& f,
                                    std::vector<Real> breakpoints, const solve_options<Real>& options = {}) {
  using std::pow;
  const auto e = op.exponents(leading, trailing);
  const Real h = op.half_length();
  const Real p = e.gam + Real(e.nu), q = e.del + Real(e.nu);
  if (!(p > -1))
    detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_piecewise", "image exponent gam + nu", p,
                                "(-1, inf): piecewise data in the class nu = -1 needs 2 alpha + beta < 1");
  const std::size_t M = options.degree != 0 ? options.degree : options.piecewise_degree;
  if (M == 0) detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_piecewise", "piecewise_degree", M, "[1, inf)");
  const Real scale_F = pow(h, -op.parameters().alpha());
  std::sort(breakpoints.begin(), breakpoints.end());
  std::vector<Real> cuts{Real(-1)};
  std::vector<Real> cuts_s{op.lo()};
  for (const Real& b : breakpoints) {
    if (!(b > op.lo() && b < op.hi()))
      detail::throw_bad_parameter("rhabel::abel::rhabel::abel::solve_piecewise", "breakpoint", b, "(lo, hi)");
    cuts.push_back(-1 + (b - op.lo()) / h);
    cuts_s.push_back(b);
  }
  cuts.push_back(Real(1));
  cuts_s.push_back(op.hi());
  std::vector<Real> d(M, Real(0));
  const std::size_t nodes = M / 2 + 24;  // per panel: exact for degree M - 1 times a low-degree piece
  const Real inf = std::numeric_limits<Real>::infinity();
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const bool first = k == 0, last = k + 2 == cuts.size();
    const panel_integrator<Real> rule(last ? p : Real(0), first ? q : Real(0), nodes);
    const Real start = cuts[k] + 1, end = 1 - cuts[k + 1];
    rule.for_each_node(cuts[k + 1] - cuts[k], first ? inf : start, last ? inf : end,
                       [&](const Real& u, const Real& v, const Real& w) {
                         const Real one_plus_y = start + u, one_minus_y = end + v;
                         Real weight = w;
                         if (!first) weight *= pow(one_plus_y, q);
                         if (!last) weight *= pow(one_minus_y, p);
                         // Physical abscissa from the nearer end of the PIECE (data evaluated on its own side).
                         const Real s = u <= v ? cuts_s[k] + h * u : cuts_s[k + 1] - h * v;
                         const Real y = one_plus_y <= one_minus_y ? one_plus_y - 1 : 1 - one_minus_y;
                         const Real value = f(s);
                         detail::check_finite_value("rhabel::abel::solve_piecewise", value, s);
                         const auto P = rhabel::quadrature::jacobi_p_all(M - 1, p, q, y);  // p, q > -1 here
                         const Real wf = weight * scale_F * value;
                         for (std::size_t m = 0; m < M; ++m) d[m] += wf * P[m];
                       });
  }
  for (std::size_t m = 0; m < M; ++m) d[m] /= rhabel::quadrature::jacobi_norm_squared(m, p, q);
  abel_solution<Real> sol = detail::solution_from_image(op, e, d, options);
  sol.degree = M;
  using std::abs;
  sol.coefficient_tail = abs(d.back());
  if (options.residual_points > 0) sol.residual = detail::independent_residual(op, sol, f, options.residual_points);
  // Converged only on evidence: a finite density and, when measured, a residual within the
  // acceptance (without the residual: the coefficients are exact for piecewise polynomials).
  const bool within = options.residual_points == 0 || sol.residual <= Real(piecewise_residual_acceptance);
  sol.status = within && detail::finite_density(sol) ? solve_status::converged : solve_status::not_converged;
  return sol;
}

}  // namespace rhabel::abel
