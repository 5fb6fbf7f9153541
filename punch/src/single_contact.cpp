// punch/src/single_contact.cpp: one contact alone: the density builders (spectral, the
// wedge's apex enrichment and near-edge split form), the edge conditions and their root finding
// (orthogonality root, load), per shape. See internal.hpp for the layout of punch/src.
#include "internal.hpp"

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"
#include "rhabel/riemann/abel_solver.hpp"

#include <Eigen/Dense>
#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace rhabel::punch::detail {

// Bounded ("smooth edge") and unbounded ("corner") edge exponents of docs/theory.md section 3.
double gam_smooth(double alpha, double beta) { return (1 - 2 * alpha - beta) / 2; }
double del_smooth(double beta) { return (1 + beta) / 2; }


// C_f = (S1 int_a^apex g - S2 int_apex^b g) / int g, each part integrated directly (not as the
// total minus the other), so that C_f keeps its relative accuracy at extreme slope ratios, where
// one part is tiny and multiplied by the large slope.
// The smaller part is integrated directly, the larger one is the total minus it (no cancellation:
// it is at least about half the total).
double wedge_friction(const contact_density& g, const wedge& w, double apex) {
  const double total = g.integral();
  double ahead, behind;
  if (apex - g.a() <= g.b() - apex) {
    ahead = g.integral_to(apex);
    behind = total - ahead;
  } else {
    behind = g.integral_from(apex);
    ahead = total - behind;
  }
  return (w.slope_leading * ahead - w.slope_trailing * behind) / total;
}

// Sets c_0 of the series so that int g = load: int g = (L/2) c_0 h_0 + int (apex part), and c_0
// enters nothing else. For the isolated wedge the exact load is known in closed form while the
// projection's c_0 (through the image coefficient d_1) cancels at extreme slope ratios.
void set_load(contact_density& g, double load) {
  if (g.jacobi.coefficients.empty()) return;
  const double h0 = quadrature::jacobi_norm_squared<double>(0, g.jacobi.del, g.jacobi.gam);
  g.jacobi.coefficients[0] = (load - g.apex_integral) / (g.length() / 2 * h0);
}

// The isolated wedge below the boundary by the Riemann-Hilbert route (riemann::solve_abel_rh,
// order 16: Riemann problem + Abel inversion, graded toward the apex), on the unit interval
// [-eps, 1 - eps] with the apex at 0 (C_f does not depend on the scale; g_L(t) = L^-alpha
// g_1((t - apex)/L)). Used when the apex is next to an edge, where abel::solve_step's Taylor
// factor limits it: int_a^apex g is integrated directly, so C_f keeps its accuracy for eps -> 0;
// for eps -> 1, int_apex^b g = total - int_a^apex g loses ~1e-16 of the total, i.e. ~1e-16
// (S1 + S2) absolute in C_f (and riemann's int_a^y loses accuracy for y within 1e-9 of b:
// riemann/abel_solver.hpp). The solution is kept for the pressure samples (abel_rh_solution::
// densities). friction_error: estimate of the error of C_f.
struct wedge_rh {
  double friction = 0, friction_error = 0;
  std::shared_ptr<const riemann::abel_rh_solution<double>> unit;  // on [-eps, 1 - eps], apex at 0
};

wedge_rh wedge_by_rh(const context& cx, double S1, double S2, double eps, double one_minus_eps) {
  const double gf = cx.gamma_factor;
  riemann::piecewise_function<double> F{[S1, gf](double) { return S1 / gf; }, {{0.0, -(S1 + S2) / gf}}};
  riemann::abel_rh_options<double> o;
  o.order = 16;
  wedge_rh out;
  out.unit = std::make_shared<const riemann::abel_rh_solution<double>>(riemann::solve_abel_rh(
      cx.alpha, cx.beta, -eps, one_minus_eps, F, riemann::edge::bounded, riemann::edge::bounded, o));
  const auto total = out.unit->total(), ahead = out.unit->integral(0.0);
  const double behind = total.value - ahead.value;
  out.friction = (S1 * ahead.value - S2 * behind) / total.value;
  out.friction_error = (S1 + S2) * (ahead.error_estimate + total.error_estimate) / std::abs(total.value) +
                       (S1 + S2) * 4 * std::numeric_limits<double>::epsilon();
  return out;
}

// Builds the density on [a, b] for the forcing: a smooth forcing (adaptive) by abel::solve; a forcing
// with steps (wedge, corners) or at fixed degree max_degree by the projection above (step coefficients
// in closed form, adaptive in the smooth part's tail), then abel::solve_image_series.
contact_density build(double a, double b, const context& cx, const edge_exponents& e, const forcing& F,
                       bool adaptive) {
  const std::size_t max_degree = std::max<std::size_t>(cx.options.max_degree, 8);
  if (adaptive && F.steps.empty()) {
    // Smooth forcing: abel::solve (adaptive Chebyshev interpolation, exact re-expansion in the image basis).
    const abel::abel_operator<double> op(cx.par, a, b);
    abel::solve_options<double> o;
    o.residual_points = 0;
    o.tolerance = cx.options.tolerance;
    o.max_degree = max_degree + 1;
    const auto smooth = F.smooth;
    auto sol = abel::solve(op, leading_edge(e.nu), trailing_edge(e.nu),
                           [&](double s) { return smooth ? smooth(s) : 0.0; }, o);
    contact_density g;
    g.jacobi = std::move(sol.density);
    g.nu = e.nu;
    g.tail = sol.coefficient_tail;
    return g;
  }
  std::size_t M = adaptive ? 8 : max_degree;
  for (;;) {
    const auto img = image_coefficients(a, b, e, F, M);
    if (!adaptive || img.tail <= cx.options.tolerance || M >= max_degree)
      return density_from_image(a, b, cx.par, e, img);
    M = std::min(2 * M, max_degree);
  }
}

// Only the orthogonality coefficient d_0 (nu = -1): one projection, no full expansion.
double orthogonality_coefficient(double a, double b, const edge_exponents& e, const forcing& F, std::size_t M) {
  return image_coefficients(a, b, e, F, e.gam - 1 > -1 ? 0 : M).d[0];
}

// ---------------------------------------------------------------------------------------------
// Root finding helpers.

template <class Fn>
double bracket_and_solve(Fn f, double x0, double step, double tol_abs, const char* what) {
  // f decreasing in x: expand a bracket around x0 and polish with TOMS 748.
  double lo = x0 - step, hi = x0 + step;
  double flo = f(lo), fhi = f(hi);
  for (int k = 0; k < 60 && !(flo >= 0 && fhi <= 0); ++k) {
    if (flo < 0) {
      lo -= step;
      flo = f(lo);
    }
    if (fhi > 0) {
      hi += step;
      fhi = f(hi);
    }
    step *= 2;
  }
  if (!(flo >= 0 && fhi <= 0)) throw std::domain_error(std::string("rhabel::punch::solve: no bracket for ") + what);
  if (flo == 0) return lo;
  if (fhi == 0) return hi;
  std::uintmax_t iterations = 200;
  const auto r = boost::math::tools::toms748_solve(
      f, lo, hi, flo, fhi, [tol_abs](double u, double v) { return std::abs(u - v) <= tol_abs; }, iterations);
  return (r.first + r.second) / 2;
}

// Solve load(L) = target where load is increasing, with load ~ L^exponent as a first guess.
template <class Fn>
double solve_length(Fn load_of, double L0, double target, double exponent, double tol) {
  double L = L0, v = load_of(L);
  double logL_prev = 0, logv_prev = 0;
  bool have_prev = false;
  for (int it = 0; it < 60; ++it) {
    double slope = exponent;
    if (have_prev && std::abs(std::log(L) - logL_prev) > 0) slope = (std::log(v) - logv_prev) / (std::log(L) - logL_prev);
    if (!(slope > 0) || !std::isfinite(slope)) slope = exponent;
    const double step = (std::log(target) - std::log(v)) / slope;
    logL_prev = std::log(L);
    logv_prev = std::log(v);
    have_prev = true;
    L = std::exp(std::log(L) + std::clamp(step, -3.0, 3.0));
    v = load_of(L);
    if (std::abs(step) < tol) break;
  }
  return L;
}

// ---------------------------------------------------------------------------------------------
// Per-shape contact solvers. Each fills st.g for the current forcing (others held fixed).

// Options of the wedge's abel::solve_step calls: no residual (punch computes its own), the
// scene's tolerance, and up to 2 max_degree + 1 Chebyshev points, at least the third nested level
// (585: an apex 1e-4 L from an edge converges there under the balanced map, abel/step_enrichment.hpp):
// the remainder after the enrichment is smooth, so the cost is the quadrature of A[phi] at the
// points, not the degree.
abel::solve_options<double> step_options(const context& cx) {
  abel::solve_options<double> o;
  o.residual_points = 0;
  o.tolerance = cx.options.tolerance;
  o.max_degree = std::max<std::size_t>(2 * std::max<std::size_t>(cx.options.max_degree, 8) + 1, 585);
  return o;
}

// The density's error estimate from a solve_step solution: its Chebyshev tail, at least the
// tolerance when it did not converge.
double step_tail(const abel::enriched_solution<double>& sol, const context& cx) {
  if (sol.status != abel::solve_status::converged) return std::max(sol.coefficient_tail, cx.options.tolerance);
  return sol.coefficient_tail;
}

// Wedge density on [a, b] for a forcing with ONE step, at the apex (jump -(S1+S2)/Gamma(1-alpha)):
// abel::solve_step builds the apex singularity in (g = C phi + w sum c_n P_n, C from the jump in
// closed form), the rest of F (the faces' constants) is solved
// spectrally with adaptive Chebyshev interpolation. The series is moved to g.jacobi, C phi stays
// in g.apex (with an empty series of its own).
contact_density build_wedge_step(double a, double b, double apex, int nu, const context& cx, const forcing& F,
                                 double* defect) {
  const abel::abel_operator<double> op(cx.par, a, b);
  const auto o = step_options(cx);
  const auto smooth = F.smooth;
  const auto steps = F.steps;
  auto f = [&](double s) {
    double v = smooth ? smooth(s) : 0.0;
    for (const auto& [position, jump] : steps)
      if (s > position) v += jump;
    return v;
  };
  auto sol = abel::solve_step(op, leading_edge(nu), trailing_edge(nu), f, apex, o);
  if (defect) *defect = sol.solvability_defect;
  contact_density g;
  g.nu = nu;
  if (sol.density.mobius == 0) {
    g.jacobi = std::move(sol.density.smooth);
    g.apex = std::move(sol.density);
    g.apex.smooth.coefficients.clear();
    g.apex.smooth.lo = g.jacobi.lo;
    g.apex.smooth.hi = g.jacobi.hi;
    g.apex.smooth.gam = g.jacobi.gam;
    g.apex.smooth.del = g.jacobi.del;
  } else {
    // Apex near an edge: solve_step's Moebius map; its series lives in the mapped variable, so the
    // whole density stays in `apex` and `jacobi` keeps only a c_0 for set_load.
    g.apex = std::move(sol.density);
    g.jacobi = {g.apex.smooth.lo, g.apex.smooth.hi, g.apex.smooth.gam, g.apex.smooth.del, {0.0}};
  }
  g.has_apex = true;
  g.update_apex_integral();
  g.tail = step_tail(sol, cx);
  return g;
}

// Isolated wedge below the boundary with the apex in an outer quarter of [a, b] (min(eps, 1 - eps)
// < 1/4), F constant on each side of the apex. Write F = F_long + (F - F_long), F_long its value
// on the long side (the side of the far edge), and solve both in the class nu = 0 singular at the
// NEAR edge (docs/theory.md sections 3-4; both exist below the boundary):
//   * g_long: A g_long = F_long, the closed form c_0 w (abel::solve_image_series, one coefficient);
//   * g_short: A g_short = F - F_long, data VANISHING on the long side, by abel::solve_step with
//     apex_placement::centred: the Moebius map puts the apex at the centre, and its factor
//     (1 + s sigma)^(alpha - 1), whose branch point lies ~ 2 (1 - eps)/eps beyond the far end,
//     multiplies data only on the short side, ~1 away from it. The balanced map (any F) must leave
//     the apex off centre to keep that point away from data on the long side, and needed 195 points
//     at 1e-3 L from an edge, 585 at 1e-4 L and did not converge within 1025 closer still.
// g = g_long + g_short is the nu = -1 solution: eps solves the orthogonality condition, which is
// the vanishing of the singular part at the near edge, so the two singular parts cancel (to the
// error of g_short; g is bounded there and its density is formed as the difference). Measured at
// the abel level (alpha = 0.3, 1 - eps = 1e-3 .. 1e-13): 66 points, tail <= 2e-15, values and
// int_a^t0 within 1e-12 of a long double solve.
// F is given by its two values (f' / Gamma(1 - alpha) of the faces): formed as S1 plus the step
// -(S1 + S2), the trailing value -S2 of a slope ratio 1e-6 lost 1e-10 to cancellation (measured:
// the load 2.9e-11 off at S2/S1 = 1e-6).
contact_density build_wedge_near_edge(double eps, double one_minus_eps, const context& cx, double f_leading, double f_trailing,
                                      int near) {
  const double a = -eps, b = one_minus_eps;  // apex at 0, L = 1
  const bool near_trailing = near == 0 ? one_minus_eps <= eps : near > 0;
  const edge_exponents physical = cx.exponents(-1);
  const abel::edge leading = near_trailing ? abel::edge::bounded : abel::edge::unbounded;
  const abel::edge trailing = near_trailing ? abel::edge::unbounded : abel::edge::bounded;
  const abel::abel_operator<double> op(cx.par, a, b);
  const double f_long = near_trailing ? f_leading : f_trailing, f_short = near_trailing ? f_trailing : f_leading;
  auto long_part = abel::solve_image_series(op, leading, trailing, std::vector<double>{std::pow(op.half_length(), -cx.alpha) * f_long});
  const auto o = step_options(cx);
  // Exactly 0 on the long side (solve_step checks it): the step's value there is f_long itself.
  const double short_value = f_short - f_long;  // -(S1 + S2) or S1 + S2 (over Gamma(1 - alpha)): no cancellation
  auto short_data = [&](double s) { return (near_trailing ? s > 0 : s < 0) ? short_value : 0.0; };
  auto sol = abel::solve_step(op, leading, trailing, short_data, 0.0, o, 0, abel::apex_placement::centred);
  contact_density g;
  g.nu = 0;
  g.physical = physical;
  g.jacobi = std::move(long_part.density);
  g.apex = std::move(sol.density);
  g.has_apex = true;
  g.update_apex_integral();
  g.tail = step_tail(sol, cx);
  return g;
}

void solve_smooth_edges(indentor_state& st, const context& cx, const forcing& F, double L_guess, double b_guess,
                        double load_exponent) {
  const edge_exponents e = cx.exponents(-1);
  const double tol = cx.options.tolerance;
  std::size_t M = 8;
  {
    // Degree needed by the forcing, measured once on the guessed interval.
    const auto g0 = build(b_guess - L_guess, b_guess, cx, e, F, true);
    M = std::max<std::size_t>(g0.jacobi.coefficients.size(), 8);
  }
  double a_last = b_guess - L_guess;
  auto place = [&](double L) {
    auto d0 = [&](double a) { return orthogonality_coefficient(a, a + L, e, F, M); };
    a_last = bracket_and_solve(d0, a_last + (L - L_guess) * 0, L / 8, tol * L, "the leading edge (orthogonality)");
    return a_last;
  };
  auto load_of = [&](double L) {
    const double a = place(L);
    st.g = build(a, a + L, cx, e, F, true);
    return st.g.integral();
  };
  solve_length(load_of, L_guess, st.target_load, load_exponent, tol);
}

void solve_parabola(indentor_state& st, const context& cx, const forcing& F) {
  const double R = std::get<parabolic>(st.source->shape).radius;
  const double alpha = cx.alpha, beta = cx.beta;
  // First guess from the closed form of docs/theory.md section 5 (exact for a single indentor).
  // load = int g = cos(beta pi/2) L^(2-alpha) B(gam+1, del+1)/(pi R Gamma(2-alpha)).
  const double gam = gam_smooth(alpha, beta), del = del_smooth(beta);
  const double K = std::cos(beta * pi / 2) * boost::math::beta(gam + 1, del + 1) / (pi * R * boost::math::tgamma(2 - alpha));
  const double L = std::pow(st.target_load / K, 1 / (2 - alpha));
  const double b = st.apex + L * (1 - 2 * alpha - beta) / (2 * (1 - alpha));
  solve_smooth_edges(st, cx, F, L, b, 2 - alpha);
}

void solve_general(indentor_state& st, const context& cx, const forcing& F) {
  const auto& gp = std::get<general_profile>(st.source->shape);
  // Guess: parabola of the same curvature at the apex.
  const double h = 1e-6 * (gp.search_hi - gp.search_lo);
  const double curvature = -(gp.slope(h) - gp.slope(-h)) / (2 * h);
  double L = (gp.search_hi - gp.search_lo) / 4;
  if (curvature > 0 && std::isfinite(curvature)) {
    const double gam = gam_smooth(cx.alpha, cx.beta), del = del_smooth(cx.beta);
    const double K = std::cos(cx.beta * pi / 2) * boost::math::beta(gam + 1, del + 1) * curvature /
                     (pi * boost::math::tgamma(2 - cx.alpha));
    L = std::min(L, std::pow(st.target_load / K, 1 / (2 - cx.alpha)));
  }
  solve_smooth_edges(st, cx, F, L, st.apex + L / 2, 2 - cx.alpha);
  if (st.g.jacobi.lo < st.apex + gp.search_lo || st.g.jacobi.hi > st.apex + gp.search_hi) {
    std::ostringstream os;
    os << "contact [" << st.g.jacobi.lo << ", " << st.g.jacobi.hi << "] leaves the search window of the general profile";
    st.status = os.str();
  }
}

// F in the variable s - origin (the isolated wedge is solved with its apex at 0).
forcing shifted(const forcing& F, double origin) {
  forcing out;
  if (F.smooth) out.smooth = [smooth = F.smooth, origin](double s) { return smooth(s + origin); };
  for (const auto& [position, jump] : F.steps) out.steps.push_back({position - origin, jump});
  return out;
}

/// A wedge whose contact ends at its apex (docs/theory.md section 5): nu = 0, b = apex, one
/// unknown L.
void solve_wedge_at_apex(indentor_state& st, const context& cx, const forcing& F) {
  const auto& w = std::get<wedge>(st.source->shape);
  const double alpha = cx.alpha, beta = cx.beta;
  const edge_exponents e = cx.exponents(0);
  auto load_of = [&](double L) {
    st.g = build(st.apex - L, st.apex, cx, e, F, true);
    return st.g.integral();
  };
  // Closed-form guess: int g = S1 cos(beta pi/2) L^(1-alpha) B(gam+1, del+1) / (pi Gamma(1-alpha)).
  const double K = w.slope_leading * std::cos(beta * pi / 2) * boost::math::beta(e.gam + 1, e.del + 1) /
                   (pi * cx.gamma_factor);
  const double L0 = std::pow(st.target_load / K, 1 / (1 - alpha));
  solve_length(load_of, L0, st.target_load, 1 - alpha, cx.options.tolerance);
  st.epsilon = 1.0;
}

/// A wedge below the boundary (nu = -1, smooth at both edges, the contact wrapping its apex) in
/// closed form: the exponents, the slopes, eps = (apex - a)/L and 1 - eps, and int g of the
/// isolated wedge on the unit interval (its load scales like L^(1 - alpha)).
struct wedge_below {
  edge_exponents e;
  double S1 = 0, S2 = 0, eps = 0, one_minus_eps = 0, unit_load = 0;

  wedge_below(const wedge& w, const context& cx) : e(cx.exponents(-1)), S1(w.slope_leading), S2(w.slope_trailing) {
    // eps from I_eps(del, gam) = S2/(S1 + S2) (docs/theory.md section 5); 1 - eps from the
    // complementary equation so that both are accurate at extreme slope ratios.
    eps = boost::math::ibeta_inv(e.del, e.gam, S2 / (S1 + S2));
    one_minus_eps = boost::math::ibeta_inv(e.gam, e.del, S1 / (S1 + S2));
    // The moment formula of the Riemann-Hilbert route (riemann/abel_solver.hpp: int g = (c/pi) int
    // (t-a)^((beta-1)/2) (b-t)^((1-beta)/2-alpha) F) gives (c/(pi Gamma(1-alpha))) [(S1 + S2)
    // B_eps(del, gam + 1) - S2 B(del, gam + 1)] (c = cos(beta pi/2)), which cancels badly at extreme
    // slope ratios; with B_x(a, b + 1) = (b B_x(a, b) + x^a (1-x)^b)/(a + b) and the eps condition
    // (S1 + S2) B_eps(del, gam) = S2 B(del, gam) it is (c/(pi Gamma(1-alpha))) (S1 + S2) eps^del
    // (1-eps)^gam / (1 - alpha): no cancellation (alpha = 0, S1 = S2 = m: load = E* m L/2, Johnson's
    // P = E* m a).
    unit_load = std::cos(cx.beta * pi / 2) / (pi * cx.gamma_factor) * (S1 + S2) * std::pow(eps, e.del) *
                std::pow(one_minus_eps, e.gam) / (1 - cx.alpha);
  }
  /// st.g, solved on the unit interval with the apex at 0 (its load `divisor` times unit_load),
  /// scaled to the length L at st.target_load and placed.
  void place(indentor_state& st, double alpha, double divisor = 1) const {
    const double L = std::pow(st.target_load / unit_load, 1 / (1 - alpha));
    st.g.scale(std::pow(L, -alpha) / divisor);
    st.g.set_interval(st.apex - eps * L, st.apex + one_minus_eps * L);
    st.epsilon = eps;
  }
};

/// The apex within 1e-14 L of the trailing edge: to double precision the contact ends at the apex,
/// as on the boundary (eps -> 1 exponentially fast as alpha + beta/2 -> 1/2 or S2/S1 -> inf).
void solve_wedge_nearly_at_apex(indentor_state& st, const context& cx, const forcing& F, const wedge_below& wb) {
  context above = cx;
  above.offset = 0;
  solve_wedge_at_apex(st, above, F);
  st.status = "eps within 1e-14 of 1: solved as a contact ending at the apex";
  if (wb.one_minus_eps > 1e-30) {
    // The apex singularity still carries weight (its amplitude grows with S1 + S2): C_f from the
    // Riemann-Hilbert route on the true interval. Closer still, C_f = S1 to double precision.
    const auto rh = wedge_by_rh(cx, wb.S1, wb.S2, wb.eps, wb.one_minus_eps);
    st.friction = rh.friction;
    st.friction_error = rh.friction_error;
    st.status += "; C_f by the Riemann-Hilbert route";
  }
}

/// Apex in an outer quarter (wedge_apex_split): the long side's constant in closed form plus the
/// short side's step with the apex mapped to the centre (build_wedge_near_edge), on the unit
/// interval, then scaled. The load is matched by scaling the whole density (c_0 of the closed form
/// alone would break the cancellation of the singular parts at the near edge).
void solve_wedge_apex_near_edge(indentor_state& st, const context& cx, const wedge_below& wb) {
  st.g = build_wedge_near_edge(wb.eps, wb.one_minus_eps, cx, wb.S1 / cx.gamma_factor, -wb.S2 / cx.gamma_factor);
  const double load_ratio = st.g.integral() / wb.unit_load;
  st.g.tail = std::max(st.g.tail, std::abs(load_ratio - 1));
  wb.place(st, cx.alpha, load_ratio);
}

/// wedge_apex_split off: the plain Jacobi series serves the residual and the displacement (its
/// tail flags the unresolved apex), C_f and the pressure samples come from the Riemann-Hilbert
/// route on the true interval.
void solve_wedge_plain(indentor_state& st, const context& cx, const forcing& F, const wedge_below& wb) {
  st.g = build(st.apex - wb.eps, st.apex + wb.one_minus_eps, cx, wb.e, F, false);
  set_load(st.g, wb.unit_load);
  // The step makes the density's coefficients decay only like n^(alpha - 1/2): report the size of
  // their tail (the last quarter relative to the largest), which flags the unresolved apex.
  double largest = 0, tail = 0;
  const std::size_t N = st.g.jacobi.coefficients.size();
  for (std::size_t n = 0; n < N; ++n) {
    largest = std::max(largest, std::abs(st.g.jacobi.coefficients[n]));
    if (4 * n >= 3 * N) tail = std::max(tail, std::abs(st.g.jacobi.coefficients[n]));
  }
  st.g.tail = largest > 0 ? tail / largest : 0;
  st.status = "wedge_apex_split disabled: plain Jacobi series for the "
              "residual and the displacement; C_f and the pressure grid by the Riemann-Hilbert route";
  const auto rh = wedge_by_rh(cx, wb.S1, wb.S2, wb.eps, wb.one_minus_eps);
  st.friction = rh.friction;
  st.friction_error = rh.friction_error;
  st.rh_unit = rh.unit;
  st.rh_one_minus_eps = wb.one_minus_eps;
  wb.place(st, cx.alpha);
}

/// The apex inside (wedge_apex_split, farther than enrich_limit from both edges): the series
/// enriched by the apex's step (build_wedge_step), solved at L = 1 with the apex at 0 (no rounding
/// of apex +- eps), then scaled: g_L(t) = L^-alpha g_1((t - apex)/L), int g_L = L^(1 - alpha) int g_1.
void solve_wedge_enriched(indentor_state& st, const context& cx, const forcing& F, const wedge_below& wb) {
  st.g = build_wedge_step(-wb.eps, wb.one_minus_eps, 0.0, -1, cx, shifted(F, st.apex));
  // The enriched density must carry the exact load: its defect joins the error estimate, then c_0
  // is set to the exact value.
  st.g.tail = std::max(st.g.tail, std::abs(st.g.integral() / wb.unit_load - 1));
  set_load(st.g, wb.unit_load);
  wb.place(st, cx.alpha);
}

void solve_wedge(indentor_state& st, const context& cx, const forcing& F) {
  if (cx.offset >= -boundary_width) return solve_wedge_at_apex(st, cx, F);
  const wedge_below wb(std::get<wedge>(st.source->shape), cx);
  if (wb.one_minus_eps * 1e14 < 1) return solve_wedge_nearly_at_apex(st, cx, F, wb);
  // An isolated wedge with wedge_apex_split off: C_f and the pressure samples from the
  // Riemann-Hilbert route, the density the plain series (its error_estimate says how rough it is:
  // ~1 next to an edge). A coupled wedge within enrich_limit keeps the plain series for everything
  // (pressure unresolved next to the apex; C_f by Richardson extrapolation of the series).
  const double edge_distance = std::min(wb.eps, wb.one_minus_eps);
  if (cx.options.wedge_apex_split && edge_distance < 0.25) return solve_wedge_apex_near_edge(st, cx, wb);
  if (!(cx.options.wedge_apex_split && edge_distance > enrich_limit)) return solve_wedge_plain(st, cx, F, wb);
  solve_wedge_enriched(st, cx, F, wb);
}

void solve_flat(indentor_state& st, const context& cx, const forcing& F) {
  const double width = std::get<flat>(st.source->shape).width;
  const double a = st.apex - width / 2, b = st.apex + width / 2;
  if (cx.offset >= -boundary_width) {
    // Contact collapses to a moving line load at the leading corner (paper 24-25).
    st.g = contact_density{};
    st.g.jacobi.lo = st.g.jacobi.hi = a;
    st.g.line_load = true;
    st.g.line_weight = st.target_load;
    st.status = "line load at the leading corner; C_f is undefined for a line load (reported as 0)";
    return;
  }
  const edge_exponents e = cx.exponents(1);
  st.g = build(a, b, cx, e, F, true);
  // Homogeneous solution w itself (nu = +1): c_0 adds load without changing F.
  const double particular = st.g.integral();
  const double unit = (b - a) / 2 * std::pow(2.0, e.del + e.gam + 1) * boost::math::beta(e.del + 1, e.gam + 1);
  st.g.jacobi.coefficients[0] += (st.target_load - particular) / unit;
}

void solve_isolated(indentor_state& st, const context& cx) {
  const forcing F = own_forcing(st, cx);
  switch (st.k) {
    case kind::parabola: solve_parabola(st, cx, F); break;
    case kind::wedge: solve_wedge(st, cx, F); break;
    case kind::flat: solve_flat(st, cx, F); break;
    case kind::general: solve_general(st, cx, F); break;
  }
}

}  // namespace rhabel::punch::detail
