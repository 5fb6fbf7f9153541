// The punch layer: contact intervals, pressures and friction of indentors on a power-law
// viscoelastic half-space. Mathematics: ../include/rhabel/punch/contact.hpp and
// ../../../docs/theory.md. Everything here is double precision.
#include "rhabel/punch/contact.hpp"
#include "rhabel/punch/detail/contact_density.hpp"
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

namespace rhabel::punch {

namespace detail {

// ---------------------------------------------------------------------------------------------
// Material helpers.

double material_beta(const material& m) {
  return 2 / pi * std::atan(m.coulomb * (1 - 2 * m.poisson) / (2 * (1 - m.poisson)));
}

// alpha + beta/2 - 1/2: the regime parameter.
double regime_offset(const material& m) { return m.alpha + material_beta(m) / 2 - 0.5; }

// kappa = cos((alpha + beta/2) pi)/cos(beta pi/2) = -sin(pi (alpha + beta/2 - 1/2))/cos(beta pi/2):
// the second form keeps full relative accuracy next to the boundary kappa = 0.
double material_kappa(const material& m) {
  const double off = regime_offset(m);
  if (std::abs(off) <= boundary_width) return 0;
  return -std::sin(pi * off) / std::cos(material_beta(m) * pi / 2);
}

// Bounded ("smooth edge") and unbounded ("corner") edge exponents of docs/theory.md section 3.
double gam_smooth(double alpha, double beta) { return (1 - 2 * alpha - beta) / 2; }
double del_smooth(double beta) { return (1 + beta) / 2; }

[[noreturn]] void bad_field(const std::string& field, double value, const char* requirement) {
  std::ostringstream os;
  os.precision(17);
  os << "rhabel::punch::solve: " << field << " = " << value << " must be " << requirement;
  throw std::invalid_argument(os.str());
}

// ---------------------------------------------------------------------------------------------
// Jacobi polynomials for exponents that may be <= -1 (the image family of the nu = -1 class above
// the boundary has p = gam - 1 < -1): abel::detail::plain_jacobi_values, the plain three-term
// recurrence, valid as long as no denominator vanishes, which docs/theory.md section 4's families
// guarantee for alpha not an integer >= 1.
using abel::detail::plain_jacobi_values;

// Position s of [a, b] -> (x, 1 + x, 1 - x) with both distances computed directly.
struct mapped {
  double x, one_plus, one_minus;
};
mapped map_to_reference(double s, double a, double b) {
  const double L = b - a;
  const double one_plus = 2 * (s - a) / L, one_minus = 2 * (b - s) / L;
  return {one_plus <= one_minus ? one_plus - 1 : 1 - one_minus, one_plus, one_minus};
}

// ---------------------------------------------------------------------------------------------
// Image coefficients: F(s) = sum_m d_m P_m^(p, q)(y) on [a, b], p = gam + nu (at y = +1),
// q = del + nu (at y = -1). Returns d_0 .. d_M. Not abel::solve_piecewise (which overlaps it), for
// four reasons: (1) the steps' coefficients here are in closed form (Rodrigues), where
// solve_piecewise integrates each piece by Gauss-Jacobi (M/2 + 24 nodes per piece); (2) d_0 alone
// (M = 0) is what the orthogonality root of coupled wedges and of general profiles with corners
// evaluates ~30 times per solve, while solve_piecewise always builds the full solution; (3) the
// adaptive degree is judged on the smooth part's tail alone (image_expansion::tail); (4) the
// Chebyshev fallback for a non-integrable image weight (nu = -1 above the boundary), which
// solve_piecewise rejects. The smooth part: M + 8 Gauss-Jacobi nodes.

image_expansion image_coefficients(double a, double b, const edge_exponents& e, const forcing& F,
                                   std::size_t M) {
  const double p = e.gam + e.nu, q = e.del + e.nu;
  image_expansion out;
  if (p > -1 && q > -1) {
    // Orthogonal projection with the (integrable) image weight (1 - y)^p (1 + y)^q: the smooth part
    // by M + 8 Gauss-Jacobi nodes (abel's process-wide rule cache; the shared_ptr keeps the rule
    // alive while in use), kept apart because the adaptive degree is judged on it alone (the step
    // coefficients below are exact).
    std::vector<double> smooth(M + 1, 0.0);
    if (F.smooth) {
      const auto rule_ptr = abel::detail::cached_gauss_jacobi_rule<double>(M + 8, p, q);
      const auto& rule = *rule_ptr;
      for (std::size_t i = 0; i < rule.size(); ++i) {
        const double s = rule.x_minus_lo[i] <= rule.hi_minus_x[i] ? a + (b - a) * rule.x_minus_lo[i] / 2
                                                                  : b - (b - a) * rule.hi_minus_x[i] / 2;
        const double f = F.smooth(s) * rule.weight[i];
        const auto P = plain_jacobi_values(M, p, q, rule.x[i]);
        for (std::size_t m = 0; m <= M; ++m) smooth[m] += f * P[m];
      }
    }
    out.d = smooth;
    // Steps H(s - s_k): int_{y_k}^1 w' P_m, by Rodrigues' formula (DLMF 18.9.16) for m >= 1 and by
    // the incomplete beta function for m = 0.
    for (const auto& [position, jump] : F.steps) {
      if (position >= b) continue;
      if (position <= a) {
        out.d[0] += jump * std::exp(quadrature::log_jacobi_norm_squared<double>(0, p, q));
        continue;
      }
      const mapped y = map_to_reference(position, a, b);
      out.d[0] += jump * std::pow(2.0, p + q + 1) * boost::math::beta(p + 1, q + 1, y.one_minus / 2);
      if (M >= 1) {
        const auto P = plain_jacobi_values(M - 1, p + 1, q + 1, y.x);
        const double W = std::pow(y.one_minus, p + 1) * std::pow(y.one_plus, q + 1);
        for (std::size_t m = 1; m <= M; ++m) out.d[m] += jump * W * P[m - 1] / (2.0 * static_cast<double>(m));
      }
    }
    double largest = 0, tail = 0;
    for (std::size_t m = 0; m <= M; ++m) {
      const double norm = quadrature::jacobi_norm_squared<double>(m, p, q);
      out.d[m] /= norm;
      largest = std::max(largest, std::abs(out.d[m]));
      if (4 * m >= 3 * M && m > 0) tail = std::max(tail, std::abs(smooth[m] / norm));
    }
    out.tail = largest > 0 ? tail / largest : 0;
    return out;
  }
  // Non-integrable image weight (nu = -1 above the boundary): interpolate F at Chebyshev points
  // in the image basis. The expansion of a polynomial is still unique (the family has exact
  // degrees), and d_0 = 0 is the analytic continuation of the orthogonality condition.
  const std::size_t n = M + 1;
  Eigen::MatrixXd V(n, n);
  Eigen::VectorXd rhs(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double theta = pi * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    const double y = std::cos(theta);
    const double s = a + (b - a) * (1 + y) / 2;
    double f = F.smooth ? F.smooth(s) : 0.0;
    for (const auto& [position, jump] : F.steps)
      if (s > position) f += jump;
    rhs[static_cast<Eigen::Index>(i)] = f;
    const auto P = plain_jacobi_values(M, p, q, y);
    for (std::size_t m = 0; m < n; ++m) V(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(m)) = P[m];
  }
  const Eigen::VectorXd d = V.partialPivLu().solve(rhs);
  out.d.assign(n, 0.0);
  double largest = 0, tail = 0;
  for (std::size_t m = 0; m < n; ++m) {
    out.d[m] = d[static_cast<Eigen::Index>(m)];
    largest = std::max(largest, std::abs(out.d[m]));
    if (4 * m >= 3 * M && m > 0) tail = std::max(tail, std::abs(out.d[m]));
  }
  out.tail = largest > 0 ? tail / largest : 0;
  return out;
}


// Density from the image coefficients of F (abel::solve_image_series: c_n = d_(n - nu) / lambda_n on
// F~ = (L/2)^(-alpha) F). For nu = +1 the homogeneous coefficient c_0 is left at 0 (the caller adds the load).
contact_density density_from_image(double a, double b, const abel::abel_parameters<double>& par, const edge_exponents& e,
                                   const image_expansion& img) {
  const abel::abel_operator<double> op(par, a, b);
  const double scale = std::pow((b - a) / 2, -par.alpha());
  std::vector<double> d = img.d;
  for (double& v : d) v *= scale;
  auto sol = abel::solve_image_series(op, leading_edge(e.nu), trailing_edge(e.nu), d);
  contact_density g;
  g.jacobi = std::move(sol.density);
  g.nu = e.nu;
  g.tail = img.tail;
  return g;
}

// A g (s) for s outside (or on the edge of) the support of g: the operator of (8)
// (abel_operator::apply: graded Gauss-Jacobi quadrature outside the interval), plus the apex part.
double apply_outside(const contact_density& g, double s, const abel::abel_parameters<double>& par) {
  const double alpha = par.alpha();
  if (g.line_load) {
    const double r = g.a() - s;
    if (r > 0) return g.line_weight * std::pow(r, alpha - 1);
    return -par.kappa() * g.line_weight * std::pow(-r, alpha - 1);
  }
  const abel::abel_operator<double> op(par, g.a(), g.b());
  double result = op.apply(g.jacobi, s);
  if (g.has_apex) result += abel::apply(op, g.apex, s);
  return result;
}

// (8) evaluated at points s inside the support by an independent quadrature of the two one-sided
// integrals (abel_operator::quadrature_evaluator, built once per density; it does not use the
// spectral relation, so it checks it), plus the apex enrichment by abel::apply (its direct graded
// quadrature of A[phi]: the same quadrature abel::solve_step used to build the data, so for that
// part the residual checks the smooth remainder only; s must not be the apex).
class inside_action {
 public:
  inside_action(const contact_density& g, const abel::abel_parameters<double>& par)
      : g_(g), op_(par, g.a(), g.b()), evaluate_(op_, g.jacobi.gam, g.jacobi.del, g.jacobi.coefficients.size() + 32),
        evaluate_mapped_(op_, g.jacobi.gam, g.jacobi.del, g.apex.smooth.coefficients.size() + 32),
        split_(g.apex.quadrature_nodes() - 4), series_(g.jacobi.coefficients, g.jacobi.del, g.jacobi.gam),
        mapped_series_(g.apex.smooth.series_evaluator()) {}
  inside_action(const inside_action&) = delete;
  inside_action& operator=(const inside_action&) = delete;
  double operator()(double s) const {
    // g.jacobi.series(x) with the recurrence coefficients computed once (same sum to a few ulps).
    double result = series_sum(evaluate_, series_, s);
    if (!g_.has_apex) return result;
    // A[C phi] as abel::apply computes it inside the interval, with the split rules built once
    // for all check points (abel::apply builds them per call).
    const double h = op_.half_length(), alpha = op_.parameters().alpha();
    const auto& apex = g_.apex;
    if (apex.mobius == 0) {
      const double y = map_to_reference(s, g_.a(), g_.b()).x;
      return result + std::pow(h, alpha) * apex.enrichment * abel::detail::enrichment_image_any(apex, op_.parameters(), split_, y);
    }
    // Mapped: the covariance A[g](M(sigma)) = (1 - s^2)^alpha (1 + s sigma)^(1 - alpha) A[g~](sigma)
    // (abel/step_enrichment.hpp), with the series part of g~ by the same independent quadrature.
    const auto d = apex.sigma_of((s - g_.a()) / h, (g_.b() - s) / h);
    const double y = d[0] <= d[1] ? d[0] - 1 : 1 - d[1];
    const double t = d[0] <= d[1] ? g_.a() + h * d[0] : g_.b() - h * d[1];
    const double mapped = series_sum(evaluate_mapped_, mapped_series_, t) +
                          std::pow(h, alpha) * apex.enrichment * abel::detail::enrichment_image_any(apex, op_.parameters(), split_, y);
    return result + apex.covariance_factor(d[2]) * mapped;
  }

 private:
  // The quadrature of the series part at s, its series summed in batches from degree 48 on
  // (quadrature_evaluator::with_series: the same value bit for bit; the rule's work is done twice,
  // so short series keep the one-node-at-a-time path). Whole scene with the residual, interleaved
  // runs: degree 174 (eps 0.999) 4.9 -> 3.4 ms, 84 (eps 0.994) 2.3 -> 2.0, 51 (alpha 0.3) 0.94 -> 0.89.
  static double series_sum(const abel::abel_operator<double>::quadrature_evaluator& evaluate,
                           const rhabel::quadrature::jacobi_series<double>& series, double s) {
    if (series.size() >= 48) return evaluate.with_series(series, s);
    return evaluate([&](double x) { return series(x); }, s);
  }

  const contact_density& g_;
  abel::abel_operator<double> op_;
  abel::abel_operator<double>::quadrature_evaluator evaluate_, evaluate_mapped_;
  abel::detail::split_integrator<double> split_;  // node count as in abel::apply
  rhabel::quadrature::jacobi_series<double> series_;  // g.jacobi's series, coefficients precomputed
  rhabel::quadrature::jacobi_series<double> mapped_series_;  // g.apex.smooth's (mapped only; else empty)
};

// The action A g (s) of another indentor's density at points s of an interval [lo, hi] outside its
// contact, for the coupling of paper system 41: the nodes of abel's cross terms (abel::detail::
// make_cross_nodes, composite Gauss-Jacobi graded toward the end facing [lo, hi]; the same as in
// abel::solve_union) are built once and reused at every s; the kernel is abel::detail::cross_kernel.
class cross_action {
 public:
  cross_action(const contact_density& g, const abel::abel_parameters<double>& par, double lo, double hi)
      : g_(g), par_(par), right_of_(g.a() > hi) {
    if (g.line_load) return;
    const double gap = right_of_ ? g.a() - hi : lo - g.b();
    nodes_ = abel::detail::make_cross_nodes(g.jacobi, std::max(gap, 1e-3 * g.length()), right_of_,
                                            std::max<std::size_t>(g.jacobi.coefficients.size() / 2 + 16, 32));
    series_.resize(nodes_.x.size());
    for (std::size_t q = 0; q < nodes_.x.size(); ++q) series_[q] = nodes_.weight[q] * g.jacobi.series(nodes_.x[q]);
  }
  double operator()(double s) const {
    if (g_.line_load || (right_of_ ? !(s < g_.a()) : !(s > g_.b()))) return apply_outside(g_, s, par_);
    double sum = 0;
    for (std::size_t q = 0; q < series_.size(); ++q) {
      // t - s from the distances to the facing end (no cancellation).
      const double t_minus_s = right_of_ ? nodes_.t_minus_lo[q] + (g_.a() - s) : -(nodes_.hi_minus_t[q] + (s - g_.b()));
      sum += series_[q] * abel::detail::cross_kernel(par_, t_minus_s);
    }
    if (g_.has_apex) sum += abel::apply(abel::abel_operator<double>(par_, g_.a(), g_.b()), g_.apex, s);
    return sum;
  }

 private:
  contact_density g_;
  abel::abel_parameters<double> par_;
  bool right_of_;
  abel::detail::cross_nodes<double> nodes_;
  std::vector<double> series_;
};

// ---------------------------------------------------------------------------------------------
// One indentor inside a scene: its shape, its own F and the solved density.

context make_context(const material& m, double speed, const solve_options& options) {
  context cx;
  // alpha below 1e-300 (down to the subnormal 5e-324, where the small-alpha forms divide by alpha)
  // is alpha = 0: the solution depends on alpha like alpha log(L), far below rounding there.
  cx.alpha = m.alpha < alpha_zero ? 0.0 : m.alpha;
  cx.beta = material_beta(m);
  cx.kappa = material_kappa(m);
  cx.offset = regime_offset(m);
  if (std::abs(cx.offset) <= boundary_width) cx.offset = 0;
  cx.gamma_factor = boost::math::tgamma(1 - cx.alpha);
  cx.pressure_scale = pi / 2 * m.effective_modulus(speed);
  cx.options = options;
  cx.set_parameters();
  return cx;
}

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

// Own slope f' of an indentor at absolute position s.
double own_slope(const indentor_state& st, double s) {
  const double x = s - st.apex;
  switch (st.k) {
    case kind::parabola: return -x / std::get<parabolic>(st.source->shape).radius;
    case kind::wedge: {
      const auto& w = std::get<wedge>(st.source->shape);
      return x < 0 ? w.slope_leading : -w.slope_trailing;
    }
    case kind::flat: return 0;
    case kind::general: return std::get<general_profile>(st.source->shape).slope(x);
  }
  return 0;
}

// C_f = int f' g / int g for a density without apex part (abel::jacobi_density::integrate, split at the corners).
double mean_slope(const indentor_state& st, const contact_density& g) {
  std::vector<double> corners;
  if (st.k == kind::general)
    for (double c : std::get<general_profile>(st.source->shape).corners) corners.push_back(st.apex + c);
  return g.jacobi.integrate([&](double t) { return own_slope(st, t); }, corners) / g.jacobi.integral();
}

// F = f'/Gamma(1 - alpha) as smooth part + steps, minus the action of the other indentors.
forcing own_forcing(const indentor_state& st, const context& cx, const std::vector<indentor_state>& all,
                    std::size_t self, bool couple) {
  forcing F;
  const double gf = cx.gamma_factor;
  std::function<double(double)> cross;
  std::vector<std::shared_ptr<const cross_action>> others;
  // The own interval (or, before it is solved, the apex) sets the grading of the others' nodes.
  const double own_lo = st.solved ? st.g.a() : st.apex, own_hi = st.solved ? st.g.b() : st.apex;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (couple && i != self && all[i].solved)
      others.push_back(std::make_shared<const cross_action>(all[i].g, cx.par, own_lo, own_hi));
  if (!others.empty()) {
    cross = [others](double s) {
      double sum = 0;
      for (const auto& o : others) sum += (*o)(s);
      return sum;
    };
  }
  switch (st.k) {
    case kind::parabola: {
      const double R = std::get<parabolic>(st.source->shape).radius, apex = st.apex;
      F.smooth = [=](double s) { return -(s - apex) / (R * gf) - (cross ? cross(s) : 0.0); };
      break;
    }
    case kind::wedge: {
      const auto& w = std::get<wedge>(st.source->shape);
      const double S1 = w.slope_leading;
      if (cross) F.smooth = [=](double s) { return S1 / gf - cross(s); };
      else F.smooth = [=](double) { return S1 / gf; };
      F.steps.push_back({st.apex, -(w.slope_leading + w.slope_trailing) / gf});
      break;
    }
    case kind::flat:
      if (cross) F.smooth = [=](double s) { return -cross(s); };
      break;
    case kind::general: {
      const auto& gp = std::get<general_profile>(st.source->shape);
      const auto slope = gp.slope;
      const double apex = st.apex;
      // Jumps of f' at the corners are taken out as steps so that the smooth part is continuous.
      std::vector<std::pair<double, double>> jumps;
      for (double c : gp.corners) {
        const double h = 1e-9 * std::max(1.0, std::abs(c));
        jumps.push_back({apex + c, (slope(c + h) - slope(c - h)) / gf});
      }
      F.steps = jumps;
      F.smooth = [=](double s) {
        double v = slope(s - apex) / gf;
        for (const auto& [pos, j] : jumps)
          if (s > pos) v -= j;
        return v - (cross ? cross(s) : 0.0);
      };
      break;
    }
  }
  return F;
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
// closed form), the rest of F (the faces' constants, the other indentors' smooth action) is solved
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

void solve_wedge(indentor_state& st, const context& cx, const forcing& F, bool isolated) {
  const auto& w = std::get<wedge>(st.source->shape);
  const double alpha = cx.alpha, beta = cx.beta;
  if (cx.offset >= -boundary_width) {
    // Contact ends at the apex (docs/theory.md section 5): nu = 0, b = apex, one unknown L.
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
    return;
  }
  // Below the boundary: nu = -1, smooth at both edges, contact wraps around the apex.
  const edge_exponents e = cx.exponents(-1);
  const double S1 = w.slope_leading, S2 = w.slope_trailing;
  // eps = (apex - a)/L from I_eps(del, gam) = S2/(S1 + S2) (docs/theory.md section 5); 1 - eps from the
  // complementary equation so that both are accurate at extreme slope ratios.
  const double eps = boost::math::ibeta_inv(e.del, e.gam, S2 / (S1 + S2));
  const double one_minus_eps = boost::math::ibeta_inv(e.gam, e.del, S1 / (S1 + S2));
  // int g of the isolated wedge on the unit interval, in closed form: the moment formula of the
  // Riemann-Hilbert route (riemann/abel_solver.hpp: int g = (c/pi) int (t-a)^((beta-1)/2)
  // (b-t)^((1-beta)/2-alpha) F) gives (c/(pi Gamma(1-alpha))) [(S1 + S2) B_eps(del, gam + 1) -
  // S2 B(del, gam + 1)] (c = cos(beta pi/2)), which cancels badly at extreme slope ratios; with
  // B_x(a, b + 1) = (b B_x(a, b) + x^a (1-x)^b)/(a + b) and the eps condition (S1 + S2) B_eps(del, gam)
  // = S2 B(del, gam) it is (c/(pi Gamma(1-alpha))) (S1 + S2) eps^del (1-eps)^gam / (1 - alpha): no
  // cancellation (alpha = 0, S1 = S2 = m: load = E* m L/2, Johnson's P = E* m a). int g scales like
  // L^(1 - alpha).
  const double unit_load = std::cos(cx.beta * pi / 2) / (pi * cx.gamma_factor) * (S1 + S2) *
                           std::pow(eps, e.del) * std::pow(one_minus_eps, e.gam) / (1 - alpha);
  if (isolated && one_minus_eps * 1e14 < 1) {
    // The apex is within 1e-14 L of the trailing edge: to double precision the contact ends at the
    // apex, as on the boundary (eps -> 1 exponentially fast as alpha + beta/2 -> 1/2 or S2/S1 -> inf).
    context above = cx;
    above.offset = 0;
    solve_wedge(st, above, F, isolated);
    st.status = "eps within 1e-14 of 1: solved as a contact ending at the apex";
    if (one_minus_eps > 1e-30) {
      // The apex singularity still carries weight (its amplitude grows with S1 + S2): C_f from the
      // Riemann-Hilbert route on the true interval. Closer still, C_f = S1 to double precision.
      const auto rh = wedge_by_rh(cx, S1, S2, eps, one_minus_eps);
      st.friction = rh.friction;
      st.friction_error = rh.friction_error;
      st.status += "; C_f by the Riemann-Hilbert route";
    }
    return;
  }
  // Isolated wedge with wedge_apex_split off (with it on, the split form below serves every apex
  // nearer an edge than L/4): C_f and the pressure samples from the Riemann-Hilbert route; the
  // density is the plain series, which then serves only the residual and the displacement (its
  // error_estimate says how rough it is: ~1 next to an edge). A coupled wedge within enrich_limit
  // keeps the plain series for everything (pressure unresolved next to the apex; C_f by Richardson
  // extrapolation of the series).
  const double edge_distance = std::min(eps, one_minus_eps);
  if (isolated && cx.options.wedge_apex_split && edge_distance < 0.25) {
    // Apex in an outer quarter: the long side's constant in closed form plus the short side's
    // step with the apex mapped to the centre (build_wedge_near_edge), on the unit interval, then
    // scaled as below. The load is matched by scaling the whole density (c_0 of the closed form
    // alone would break the cancellation of the singular parts at the near edge).
    const double L = std::pow(st.target_load / unit_load, 1 / (1 - alpha));
    st.g = build_wedge_near_edge(eps, one_minus_eps, cx, S1 / cx.gamma_factor, -S2 / cx.gamma_factor);
    const double load_ratio = st.g.integral() / unit_load;
    st.g.tail = std::max(st.g.tail, std::abs(load_ratio - 1));
    st.g.scale(std::pow(L, -alpha) / load_ratio);
    st.g.set_interval(st.apex - eps * L, st.apex + one_minus_eps * L);
    st.epsilon = eps;
    return;
  }
  const bool enrich = cx.options.wedge_apex_split && edge_distance > enrich_limit;
  if (isolated && !enrich) {
    auto load_of = [&](double L) {
      const double a = st.apex - eps * L, b = st.apex + one_minus_eps * L;
      st.g = build(a, b, cx, e, F, false);
      return st.g.integral();
    };
    load_of(1.0);
    set_load(st.g, unit_load);
    const double L = std::pow(st.target_load / unit_load, 1 / (1 - alpha));
    // The step makes the density's coefficients decay only like n^(alpha - 1/2): report the size of
    // their tail (the last quarter relative to the largest), which flags the unresolved apex.
    {
      double largest = 0, tail = 0;
      const std::size_t N = st.g.jacobi.coefficients.size();
      for (std::size_t n = 0; n < N; ++n) {
        largest = std::max(largest, std::abs(st.g.jacobi.coefficients[n]));
        if (4 * n >= 3 * N) tail = std::max(tail, std::abs(st.g.jacobi.coefficients[n]));
      }
      st.g.tail = largest > 0 ? tail / largest : 0;
      st.status = "wedge_apex_split disabled: plain Jacobi series for the "
                  "residual and the displacement; C_f and the pressure grid by the Riemann-Hilbert route";
    }
    const auto rh = wedge_by_rh(cx, S1, S2, eps, one_minus_eps);
    st.friction = rh.friction;
    st.friction_error = rh.friction_error;
    st.rh_unit = rh.unit;
    st.rh_one_minus_eps = one_minus_eps;
    st.g.scale(std::pow(L, -alpha));
    st.g.set_interval(st.apex - eps * L, st.apex + one_minus_eps * L);
    st.epsilon = eps;
    return;
  }
  if (isolated) {
    // Solved at L = 1 with the apex at 0 (no rounding of apex +- eps), then scaled: g_L(t) =
    // L^-alpha g_1((t - apex)/L), int g_L = L^(1 - alpha) int g_1.
    const forcing F0 = shifted(F, st.apex);
    const double exact_unit_load = unit_load;
    const double L = std::pow(st.target_load / unit_load, 1 / (1 - alpha));
    st.g = build_wedge_step(-eps, one_minus_eps, 0.0, -1, cx, F0);
    // The enriched density must carry the exact load: its defect joins the error estimate, then c_0
    // is set to the exact value.
    st.g.tail = std::max(st.g.tail, std::abs(st.g.integral() / exact_unit_load - 1));
    set_load(st.g, exact_unit_load);
    st.g.scale(std::pow(L, -alpha));
    st.g.set_interval(st.apex - eps * L, st.apex + one_minus_eps * L);
    st.epsilon = eps;
    return;
  }
  // Coupled: generic orthogonality root (the step part of d_0 is exact, the smooth part by quadrature).
  const double L_guess = st.g.length() > 0 ? st.g.length() : 1.0;
  solve_smooth_edges(st, cx, F, L_guess, st.apex + one_minus_eps * L_guess, 1 - alpha);
  const double e_now = (st.apex - st.g.jacobi.lo) / st.g.length();
  st.epsilon = e_now;
  if (cx.options.wedge_apex_split && std::min(e_now, 1 - e_now) > enrich_limit) {
    const double load = st.g.integral();  // exact: c_0 needs only d_1 (closed form for the step)
    st.g = build_wedge_step(st.g.jacobi.lo, st.g.jacobi.hi, st.apex, -1, cx, F);
    st.g.tail = std::max(st.g.tail, std::abs(st.g.integral() / load - 1));
  }
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

void solve_isolated(indentor_state& st, const context& cx, bool only_indentor) {
  const std::vector<indentor_state> none;
  const forcing F = own_forcing(st, cx, none, 0, false);
  switch (st.k) {
    case kind::parabola: solve_parabola(st, cx, F); break;
    case kind::wedge: solve_wedge(st, cx, F, only_indentor); break;
    case kind::flat: solve_flat(st, cx, F); break;
    case kind::general: solve_general(st, cx, F); break;
  }
  st.solved = true;
}

// ---------------------------------------------------------------------------------------------

void validate(const scene& s) {
  const auto& m = s.material;
  if (!(m.alpha >= 0 && m.alpha < 1)) bad_field("material.alpha", m.alpha, "in [0, 1)");
  if (!(m.E1 > 0) || !std::isfinite(m.E1)) bad_field("material.E1", m.E1, "finite and > 0");
  if (!(m.poisson > -1 && m.poisson <= 0.5)) bad_field("material.poisson", m.poisson, "in (-1, 0.5]");
  if (!(m.coulomb >= 0) || !std::isfinite(m.coulomb)) bad_field("material.coulomb", m.coulomb, "finite and >= 0");
  if (!(s.speed > 0) || !std::isfinite(s.speed)) bad_field("speed", s.speed, "finite and > 0");
  if (s.indentors.empty()) throw std::invalid_argument("rhabel::punch::solve: indentors is empty; give at least one");
  for (std::size_t i = 0; i < s.indentors.size(); ++i) {
    const auto& ind = s.indentors[i];
    const std::string p = "indentors[" + std::to_string(i) + "].";
    if (!(ind.load > 0) || !std::isfinite(ind.load)) bad_field(p + "load", ind.load, "finite and > 0");
    if (!std::isfinite(ind.apex)) bad_field(p + "apex", ind.apex, "finite");
    if (const auto* q = std::get_if<parabolic>(&ind.shape)) {
      if (!(q->radius > 0) || !std::isfinite(q->radius)) bad_field(p + "radius", q->radius, "finite and > 0");
    } else if (const auto* w = std::get_if<wedge>(&ind.shape)) {
      if (!(w->slope_leading > 0) || !std::isfinite(w->slope_leading))
        bad_field(p + "slope_leading", w->slope_leading, "finite and > 0");
      if (!(w->slope_trailing > 0) || !std::isfinite(w->slope_trailing))
        bad_field(p + "slope_trailing", w->slope_trailing, "finite and > 0");
    } else if (const auto* f = std::get_if<flat>(&ind.shape)) {
      if (!(f->width > 0) || !std::isfinite(f->width)) bad_field(p + "width", f->width, "finite and > 0");
    } else if (const auto* g = std::get_if<general_profile>(&ind.shape)) {
      if (!g->slope) throw std::invalid_argument("rhabel::punch::solve: " + p + "slope is empty; give f'(x)");
      if (!std::isfinite(g->search_lo) || !(g->search_lo < 0)) bad_field(p + "search_lo", g->search_lo, "finite and < 0");
      if (!std::isfinite(g->search_hi) || !(g->search_hi > 0)) bad_field(p + "search_hi", g->search_hi, "finite and > 0");
      for (std::size_t k = 0; k < g->corners.size(); ++k)
        if (!std::isfinite(g->corners[k]))
          bad_field(p + "corners[" + std::to_string(k) + "]", g->corners[k], "finite");
    }
  }
}

std::string indentor_name(std::size_t i, const indentor& ind) {
  static const char* names[] = {"parabolic", "wedge", "flat", "general_profile"};
  return "indentors[" + std::to_string(i) + "] (" + names[ind.shape.index()] + ")";
}

// K = lim g (distance to the edge)^-exponent at the leading or trailing edge, with g's exponents
// (contact_density::exponents). The series' and the apex part's intensities add up, except at the
// edge next to the apex of the split form (contact_density::physical): there both parts carry the
// singular exponent of the class nu = 0 and cancel, and K is that of the next term, from g at
// distances delta = 1e-3 d, d/2, d/4 (d = the apex's distance to that edge, the scale on which g
// varies there): g/delta^exponent = K + K1 delta + K2 delta^2 + ..., Richardson-extrapolated twice
// (truncation ~ (delta/d)^3 ~ 1e-9, the cancellation ~ eps d/delta ~ 1e-12: an estimate).
double edge_intensity(const contact_density& g, bool trailing) {
  const double parts = trailing ? g.jacobi.intensity_trailing() + (g.has_apex ? g.apex.intensity_trailing() : 0.0)
                                : g.jacobi.intensity_leading() + (g.has_apex ? g.apex.intensity_leading() : 0.0);
  if (!g.physical || g.jacobi.coefficients.empty()) return parts;
  const double h = g.jacobi.half_length(), x_apex = g.apex.apex_reference();
  const double d = trailing ? 1 - x_apex : 1 + x_apex;  // reference units
  if (trailing ? !(g.jacobi.del < 0) : !(g.jacobi.gam < 0)) return parts;  // the far edge
  const double exponent = trailing ? g.physical->del : g.physical->gam;
  auto ratio = [&](double delta) {
    const double near = delta, far = 2 - delta;
    const double value = trailing ? g.jacobi.value_at_distance(far * h, near * h) + g.apex.value_at_distance(far, near)
                                  : g.jacobi.value_at_distance(near * h, far * h) + g.apex.value_at_distance(near, far);
    return value / std::pow(near * h, exponent);
  };
  const double delta = 1e-3 * d;
  const double r1 = ratio(delta), r2 = ratio(delta / 2), r4 = ratio(delta / 4);
  const double e12 = 2 * r2 - r1, e24 = 2 * r4 - r2;
  return (4 * e24 - e12) / 3;
}

// Non-const: Boost 1.74 defines tanh_sinh::integrate(f, a, b) without the const of its declaration.
boost::math::quadrature::tanh_sinh<double>& tanh_sinh_rule() {
  thread_local boost::math::quadrature::tanh_sinh<double> rule;
  return rule;
}

// Pressure samples of an isolated wedge from its Riemann-Hilbert solution g_1 on the unit interval
// [lo, hi] = [-eps, 1 - eps], apex at 0 (wedge_by_rh): p(t) = scale g_1((t - apex)/L), scale =
// (pi/2) E_U L^-alpha. g_1 costs ~50-130 us per point of these near-edge wedges even from
// abel_rh_solution::densities (13-115 us per point on 1000-point grids with the apex 0.5 .. 0.01 L from an edge,
// riemann/abel_solver.hpp; A~
// interpolated once; most of it the far part next to the apex), so 1000 samples come from a
// piecewise Chebyshev interpolant of g_1 built from one densities call at its ~100-200 nodes.
// Structure of g_1 (the class nu = -1 with F constant next to either edge, docs/theory.md sections 3-5):
// (t - lo)^gam times an analytic function next to lo, (hi - t)^del times one next to hi, and
// |t|^-alpha A(t) + B(t) (log|t| A + B at alpha = 0) with A, B analytic on either side of the apex.
// Panels: [lo, lo/2] carrying (t - lo)^gam, [hi/2, hi] carrying (hi - t)^del, and [lo/2, 0],
// [0, hi/2] graded geometrically (ratio 1/2) towards the apex; each panel sees its nearest
// singularity at a distance >= its length (Bernstein ratio >= 3 + sqrt 8), so 16 first-kind
// points resolve g_1 to ~1e-13 of the panel's scale (measured: 2e-14 .. 7e-14 of the peak against
// the pointwise density, tests/punch/test_wedge.cpp, study_wedge_near_edge). Samples nearer to the
// apex than the innermost panel take g_1 directly, and so do the samples of a side of the apex that
// has fewer of them than interpolation nodes; the apex itself gets +inf (|t - apex|^-alpha, log at
// alpha = 0).
// Returns the largest error estimate of the g_1 values used (densities' two orders), relative to
// max g_1.
double rh_pressure(const riemann::abel_rh_solution<double>& unit, double lo, double hi, double gam, double del,
                   double apex, double L, double scale, indentor_result& r) {
  constexpr std::size_t points = 16;
  struct panel {
    double u, v;
    int weight;  // -1: (t - lo)^gam, +1: (hi - t)^del, 0: none
    std::vector<double> c;  // Chebyshev coefficients on [u, v]
  };
  // Unit abscissae of the samples. The graded panels stop at 2^-6 of the segment (or half the
  // nearest sample's distance from the apex): the few samples nearer to the apex are taken
  // directly, which is cheaper than the 16 nodes of each further panel (g_1 costs most next to
  // the apex, where densities() grades its far part deeply towards the log singularity of A~).
  std::vector<double> u(r.grid_x.size());
  double nearest_left = -lo, nearest_right = hi;
  for (std::size_t k = 0; k < u.size(); ++k) {
    u[k] = (r.grid_x[k] - apex) / L;
    if (u[k] < 0) nearest_left = std::min(nearest_left, -u[k]);
    if (u[k] > 0) nearest_right = std::min(nearest_right, u[k]);
  }
  std::vector<panel> left{{lo, lo / 2, -1, {}}};
  for (double e = lo / 2; -e / 2 >= std::max(nearest_left / 2, -lo * 0x1p-6); e /= 2) left.push_back({e, e / 2, 0, {}});
  std::vector<panel> right;
  for (double e = hi / 2; e / 2 >= std::max(nearest_right / 2, hi * 0x1p-6); e /= 2) right.push_back({e / 2, e, 0, {}});
  std::reverse(right.begin(), right.end());  // increasing abscissae, as in left
  right.push_back({hi / 2, hi, 1, {}});
  // A side with fewer samples than interpolation nodes (the short side of an apex next to an
  // edge; any side of a small grid) takes its samples directly: a sample costs as much as a node.
  const auto on_left = static_cast<std::size_t>(std::count_if(u.begin(), u.end(), [](double t) { return t < 0; }));
  const bool interpolate_left = on_left > left.size() * points;
  const bool interpolate_right = u.size() - on_left > right.size() * points;
  // Abscissae served by the interpolant: (lo, covered_left) and (covered_right, hi).
  const double covered_left = interpolate_left ? left.back().v : lo;
  const double covered_right = interpolate_right ? right.front().u : hi;
  std::vector<panel> panels;
  if (interpolate_left) panels = left;
  if (interpolate_right) panels.insert(panels.end(), right.begin(), right.end());
  // Nodes of every panel (abel's first-kind grid, offsets from the nearer end), then the samples
  // outside the panels, in one densities call.
  const abel::detail::chebyshev_grid<double> grid(points);
  std::vector<double> nodes;
  for (const auto& p : panels) {
    const double half = (p.v - p.u) / 2;
    for (std::size_t j = 0; j < points; ++j)
      nodes.push_back(grid.one_plus_x[j] <= grid.one_minus_x[j] ? p.u + half * grid.one_plus_x[j] : p.v - half * grid.one_minus_x[j]);
  }
  std::vector<std::size_t> direct;
  for (std::size_t k = 0; k < u.size(); ++k) {
    if (u[k] == 0) {
      r.pressure[k] = std::numeric_limits<double>::infinity();
    } else if (u[k] > lo && u[k] < hi && u[k] >= covered_left && u[k] <= covered_right) {
      direct.push_back(k);
      nodes.push_back(u[k]);
    }
  }
  const auto g = unit.densities(nodes);
  double largest = 0, estimate = 0;
  for (const auto& v : g) {
    largest = std::max(largest, std::abs(v.value));
    estimate = std::max(estimate, v.error_estimate);
  }
  auto weight = [&](const panel& p, double t) {
    return p.weight < 0 ? std::pow(t - lo, gam) : (p.weight > 0 ? std::pow(hi - t, del) : 1.0);
  };
  std::vector<double> values(points);
  for (std::size_t i = 0; i < panels.size(); ++i) {
    for (std::size_t j = 0; j < points; ++j) values[j] = g[i * points + j].value / weight(panels[i], nodes[i * points + j]);
    panels[i].c = abel::detail::chebyshev_coefficients(values);
  }
  for (std::size_t j = 0; j < direct.size(); ++j) r.pressure[direct[j]] = scale * g[panels.size() * points + j].value;
  for (std::size_t k = 0; k < u.size(); ++k) {
    const double t = u[k];
    if (!(t > lo && t < hi) || (t >= covered_left && t <= covered_right)) continue;
    const auto it = std::upper_bound(panels.begin(), panels.end(), t, [](double x, const panel& p) { return x < p.v; });
    if (it == panels.end()) continue;
    // sum_k c_k T_k(s) by Clenshaw's recurrence
    const double x = ((t - it->u) - (it->v - t)) / (it->v - it->u);
    double b1 = 0, b2 = 0;
    for (std::size_t n = it->c.size(); n-- > 1;) {
      const double b0 = 2 * x * b1 - b2 + it->c[n];
      b2 = b1;
      b1 = b0;
    }
    r.pressure[k] = scale * weight(*it, t) * (x * b1 - b2 + it->c[0]);
  }
  return largest > 0 ? estimate / largest : estimate;
}

// Peak pressure on [a, b] of a bounded density: sampling + Brent refinement.
std::pair<double, double> peak_of(const contact_density& g) {
  const int n = 128;
  double best = -1, where = g.jacobi.lo;
  for (int k = 0; k <= n; ++k) {
    const double t = g.jacobi.lo + g.length() * (k + 0.5) / (n + 1);
    const double v = g.value(t);
    if (v > best) {
      best = v;
      where = t;
    }
  }
  const double h = g.length() / (n + 1);
  const auto r = boost::math::tools::brent_find_minima([&](double t) { return -g.value(t); },
                                                       std::max(g.jacobi.lo, where - h), std::min(g.jacobi.hi, where + h), 40);
  if (-r.second > best) return {-r.second, r.first};
  return {best, where};
}

// Surface height h(x) - h(a_ref) from the slope field Gamma(1-alpha) A g (s), integrated in closed
// form in s first: int_{a_ref}^x K(t, s) ds = Psi(t, x) - Psi(t, a_ref), with
//   Psi(t, s) = -((t - s)^alpha - 1)/alpha                              (s < t)
//   Psi(t, s) = -kappa ((s - t)^alpha - 1)/alpha + (1 - kappa)/alpha      (s > t),
// continuous at s = t and finite as alpha -> 0 (the log kernel of the elastic half-plane).
double psi(double t, double s, double alpha, double one_minus_kappa_over_alpha, double kappa);
double psi_distance(double d, double alpha, double one_minus_kappa_over_alpha, double kappa);
double psi(double t, double s, double alpha, double one_minus_kappa_over_alpha, double kappa) {
  return psi_distance(s - t, alpha, one_minus_kappa_over_alpha, kappa);
}
// Psi as a function of d = s - t (exact when the caller knows the distance).
double psi_distance(double d, double alpha, double one_minus_kappa_over_alpha, double kappa) {
  const double t = 0, s = d;
  auto em = [alpha](double r) {  // (r^alpha - 1)/alpha, stable for small alpha
    const double l = std::log(r);
    return alpha == 0 ? l : std::expm1(alpha * l) / alpha;
  };
  if (s < t) return -em(t - s);
  if (s > t) return -kappa * em(s - t) + one_minus_kappa_over_alpha;
  return 0;
}


// Surface displacement w (downward positive: w = f(x) - f(a) + w(a) in contact, f the profile,
// so that outside a contact w >= f - f(a) + w(a) means the surface clears the indentor) from the
// slope field Gamma(1-alpha) A g (s) integrated in closed form in s (psi), relative to its value at
// the leading edge a_i of contact i:
//   x in contact i:        f_i(x) - f_i(a_i)                          (the indentor's profile),
//   x in another contact j: f_j(x) - f_j(a_j) + Gamma (E_j - E_i),
//   elsewhere:              Gamma (sum_o int g_o Psi(t, x) dt - E_i),
// E_k = sum_o int g_o Psi(t, a_k) dt (the datum at a_k: the own contact's integral, log-singular at
// t = a_k, by tanh-sinh in offsets from its singular ends; the others' by Gauss-Jacobi). Every
// moment by Gauss-Jacobi for the regular part (smooth in t when x is off the interval) and abel's
// composite rule for the apex part. E_k is computed once, on first use.
class surface {
 public:
  surface(const std::vector<indentor_state>& st, const context& cx)
      : st_(st), cx_(cx), omk_(cx.par.one_minus_kappa_over_alpha()), edge_(st.size()) {}

  /// f_k(x) - f_k(a_k): the rigid profile of indentor k relative to its leading edge.
  double profile(std::size_t k, double x) const {
    const auto& s = st_[k];
    const double a = s.g.jacobi.lo;
    switch (s.k) {
      case kind::parabola: {
        const double R = std::get<parabolic>(s.source->shape).radius;
        return -((x - s.apex) * (x - s.apex) - (a - s.apex) * (a - s.apex)) / (2 * R);
      }
      case kind::wedge: {
        const auto& w = std::get<wedge>(s.source->shape);
        auto f = [&](double y) { return y < s.apex ? w.slope_leading * (y - s.apex) : -w.slope_trailing * (y - s.apex); };
        return f(x) - f(a);
      }
      case kind::flat: return 0.0;
      case kind::general: {
        // int_a^x f' by Gauss-Legendre (f' smooth on the contact).
        const auto rule_ptr = abel::detail::cached_gauss_jacobi_rule<double>(32, 0.0, 0.0);
        const auto& rule = *rule_ptr;
        double sum = 0;
        for (std::size_t q = 0; q < rule.size(); ++q)
          sum += rule.weight[q] * own_slope(s, a + (x - a) * (1 + rule.x[q]) / 2);
        return sum * (x - a) / 2;
      }
    }
    return 0.0;
  }

  /// Surface displacement at x relative to its value at a_i (see the class comment).
  double height(std::size_t i, double x) const {
    for (std::size_t j = 0; j < st_.size(); ++j) {
      const auto& g = st_[j].g;
      if (g.line_load || !(x >= g.jacobi.lo && x <= g.jacobi.hi)) continue;
      if (j == i) return profile(i, x);
      return profile(j, x) + cx_.gamma_factor * (datum(j) - datum(i));
    }
    double h = 0;
    for (const auto& o : st_) h += moment(o.g, x);
    return cx_.gamma_factor * (h - datum(i));
  }

 private:
  double moment(const contact_density& d, double x) const {
    if (d.line_load) return d.line_weight * psi(d.jacobi.lo, x, cx_.alpha, omk_, cx_.kappa);
    const auto rule_ptr = abel::detail::cached_gauss_jacobi_rule<double>(
        std::max<std::size_t>(d.jacobi.coefficients.size() + 64, 96), d.jacobi.del, d.jacobi.gam);
    const auto& rule = *rule_ptr;
    double sum = 0;
    for (std::size_t q = 0; q < rule.size(); ++q) {
      const double t = rule.x_minus_lo[q] <= rule.hi_minus_x[q] ? d.jacobi.lo + d.length() * rule.x_minus_lo[q] / 2
                                                                : d.jacobi.hi - d.length() * rule.hi_minus_x[q] / 2;
      sum += rule.weight[q] * d.jacobi.series(rule.x[q]) * psi(t, x, cx_.alpha, omk_, cx_.kappa);
    }
    sum *= d.length() / 2;
    // Apex enrichment: abel's composite Gauss-Jacobi, cut and graded at the apex (psi is smooth
    // in t on the interval when x is outside it).
    if (d.has_apex) sum += d.apex.integrate([&](double t) { return psi(t, x, cx_.alpha, omk_, cx_.kappa); });
    return sum;
  }

  double datum(std::size_t k) const {
    if (edge_[k]) return *edge_[k];
    const auto& g = st_[k].g;
    double value = 0;
    for (std::size_t o = 0; o < st_.size(); ++o)
      if (o != k) value += moment(st_[o].g, g.jacobi.lo);
    if (!g.line_load) {  // psi(a, a) = 0 for a line load
      // In offsets from the nearer end, so that the end singularities (t-a)^gam log(t-a) and
      // (b-t)^del are evaluated from exact distances (tanh-sinh clusters its nodes there).
      const double Lg = g.length();
      // density from u = t - a, v = b - t and dx0 = x - x0 (reference axis), whichever are exact.
      auto density_at = [&](double u, double v, double dx0) {
        const double one_plus = 2 * u / Lg, one_minus = 2 * v / Lg;
        const double xr = one_plus <= one_minus ? one_plus - 1 : 1 - one_minus;
        double val = std::pow(one_minus, g.jacobi.del) * std::pow(one_plus, g.jacobi.gam) * g.jacobi.series(xr);
        if (g.has_apex) val += g.apex.value_with_offset(one_plus, one_minus, dx0);
        return val;
      };
      auto weight = [&](double u) { return psi_distance(-u, cx_.alpha, omk_, cx_.kappa); };
      if (!g.has_apex) {
        const double half = Lg / 2;
        value += tanh_sinh_rule().integrate([&](double u) { return density_at(u, Lg - u, 0) * weight(u); }, 0.0, half, 1e-12) +
                 tanh_sinh_rule().integrate([&](double v) { return density_at(Lg - v, v, 0) * weight(Lg - v); }, 0.0, half, 1e-12);
      } else {
        // Four pieces, each parametrised by the offset from its singular end (a, apex, apex, b).
        const double ua = st_[k].apex - g.jacobi.lo, vb = g.jacobi.hi - st_[k].apex, x0 = g.apex.apex_reference();
        auto piece = [&](auto&& f, double length) { return tanh_sinh_rule().integrate(f, 0.0, length, 1e-12); };
        value += piece([&](double u) { return density_at(u, Lg - u, 2 * u / Lg - 1 - x0) * weight(u); }, ua / 2);
        value += piece([&](double o) { return density_at(ua - o, vb + o, -2 * o / Lg) * weight(ua - o); }, ua / 2);
        value += piece([&](double o) { return density_at(ua + o, vb - o, 2 * o / Lg) * weight(ua + o); }, vb / 2);
        value += piece([&](double v) { return density_at(Lg - v, v, 1 - 2 * v / Lg - x0) * weight(Lg - v); }, vb / 2);
      }
    }
    edge_[k] = value;
    return value;
  }

  const std::vector<indentor_state>& st_;
  const context& cx_;
  double omk_;
  mutable std::vector<std::optional<double>> edge_;
};

// Penetration check of a coupled contact i (an indentor that is not a flat punch, whose square
// corners bound it): outside the contact the surface must stay at or above the rigid profile,
// gap(x) = height(i, x) - profile(i, x) >= 0, at 2 x 7 points a - L 2^-m and b + L 2^-m
// (m = 0 .. 6). Not closer to the edges: the moments' Gauss-Jacobi rule (~100 nodes) resolves the
// own contact's log kernel at a distance d from its end to ~(1 + sqrt(4 d/L))^-200, 1e-6 at
// d = L/1024 (measured: a spurious "penetration" of 1.5e-6 of the span there), 1e-20 at L/64. A
// wrong edge next to a point closer than that shows as tension (non-zero intensity) instead.
// Returns the worst gap relative to the profile's span over those points, and where (0 when none
// is negative).
std::pair<double, double> worst_gap(const surface& heights, const std::vector<indentor_state>& st, std::size_t i) {
  const auto& g = st[i].g;
  if (g.line_load || st[i].k == kind::flat) return {0.0, 0.0};
  const double L = g.length();
  double worst = 0, where = 0, span = 0;
  std::vector<std::pair<double, double>> gaps;
  for (int m = 0; m <= 6; ++m) {
    for (const double x : {g.a() - L * std::ldexp(1.0, -m), g.b() + L * std::ldexp(1.0, -m)}) {
      const double f = heights.profile(i, x);
      span = std::max(span, std::abs(f));
      gaps.push_back({x, heights.height(i, x) - f});
    }
  }
  for (const auto& [x, gap] : gaps)
    if (gap < worst) worst = gap, where = x;
  return {span > 0 ? worst / span : worst, where};
}

// Moves a result computed relative to `origin` (solve's first apex) back to absolute abscissae.
void shift(indentor_result& r, double origin) {
  if (origin == 0) return;
  r.a += origin;
  r.b += origin;
  r.peak_pressure_at += origin;
  for (auto& e : r.edges) e.position += origin;
  for (double& x : r.grid_x) x += origin;
  for (double& x : r.displacement_x) x += origin;
}

// Check points of contact i for the residual of (8) and the sign of the pressure: 7 interior
// points (1 - cos(pi k/8))/2 of [a, b], and points at 0.37 gap 3^k (k = 0, 1, ... while below L/4)
// from an end that faces another contact at distance gap: the boundary layer of width ~ gap of
// nearly touching contacts, which the interior points step over. Never within 1e-3 L of a
// wedge's apex (the residual's quadrature of the enrichment needs a point off it).
std::vector<double> check_points(const std::vector<indentor_state>& st, std::size_t i) {
  const auto& g = st[i].g;
  std::vector<double> out;
  if (g.line_load) return out;
  const double a = g.a(), b = g.b(), L = g.length();
  for (int k = 1; k <= 7; ++k) out.push_back(a + L * (1 - std::cos(pi * k / 8)) / 2);
  double gap_lo = std::numeric_limits<double>::infinity(), gap_hi = gap_lo;
  for (std::size_t j = 0; j < st.size(); ++j) {
    if (j == i) continue;
    if (st[j].g.b() <= a) gap_lo = std::min(gap_lo, a - st[j].g.b());
    if (st[j].g.a() >= b) gap_hi = std::min(gap_hi, st[j].g.a() - b);
  }
  for (double d = 0.37 * gap_lo; d < L / 4; d *= 3) out.push_back(a + d);
  for (double d = 0.37 * gap_hi; d < L / 4; d *= 3) out.push_back(b - d);
  if (st[i].k == kind::wedge)
    for (double& x : out)
      if (std::abs(x - st[i].apex) < 1e-3 * L) x = st[i].apex + (x < st[i].apex ? -2e-3 : 2e-3) * L;
  return out;
}

// The status of one contact from its evidence (contact.hpp, status_code): the residual, the error
// estimate, the sign of the pressure (at 64 interior points and the check points, relative to the
// mean pressure) and the load. Keeps the solver's note (st.status) in front of the findings.
void judge(indentor_result& r, const indentor_state& st, const std::vector<double>& points, double pressure_scale,
           double acceptance, std::pair<double, double> gap) {
  std::ostringstream why;
  why.precision(3);
  status_code code = status_code::ok;
  auto fail = [&](status_code c, const std::string& text) {
    if (code == status_code::ok) code = c;
    why << (why.tellp() > 0 ? "; " : "") << text;
  };
  const double target = st.source->load;
  if (r.residual > acceptance) {
    std::ostringstream os;
    os.precision(3);
    os << "residual of (8) " << r.residual << " > acceptance " << acceptance;
    fail(status_code::not_converged, os.str());
  }
  if (!(r.error_estimate <= acceptance)) {
    std::ostringstream os;
    os.precision(3);
    os << "error estimate " << r.error_estimate << " > acceptance " << acceptance;
    fail(status_code::not_converged, os.str());
  }
  if (!st.g.line_load && st.g.length() > 0) {
    const double mean = st.g.integral() / st.g.length();
    double lowest = std::numeric_limits<double>::infinity(), where = st.g.a();
    auto probe = [&](double t) {
      const double v = st.g.value(t);
      if (v < lowest) lowest = v, where = t;
    };
    for (int k = 0; k < 64; ++k) probe(st.g.a() + st.g.length() * (1 - std::cos(pi * (k + 0.5) / 64)) / 2);
    for (double t : points) probe(t);
    if (lowest < -acceptance * std::abs(mean)) {
      std::ostringstream os;
      os.precision(3);
      os << "negative pressure " << pressure_scale * lowest << " at x = " << where << " (" << lowest / mean
         << " of the mean pressure)";
      fail(status_code::tension, os.str());
    }
  }
  if (gap.first < -acceptance) {
    std::ostringstream os;
    os.precision(3);
    os << "the surface penetrates the indentor at x = " << gap.second << " (by " << -gap.first
       << " of the profile's span next to the contact): the contact set is not the physical one";
    fail(status_code::penetration, os.str());
  }
  if (!(std::abs(r.load - target) <= acceptance * target)) {
    std::ostringstream os;
    os.precision(10);
    os << "load " << r.load << " for " << target << " requested";
    fail(status_code::load_mismatch, os.str());
  }
  r.code = code;
  if (code == status_code::ok) return;
  r.status = (st.status == "ok" ? "" : st.status + "; ") + why.str();
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------
// Public API.

using namespace detail;

double material::beta() const { return material_beta(*this); }
double material::kappa() const { return material_kappa(*this); }
double material::effective_modulus(double speed) const {
  return E1 * boost::math::tgamma(1 - alpha) * std::pow(speed, alpha) / (1 - poisson * poisson);
}

const char* to_string(status_code code) {
  switch (code) {
    case status_code::ok: return "ok";
    case status_code::not_converged: return "not_converged";
    case status_code::tension: return "tension";
    case status_code::load_mismatch: return "load_mismatch";
    case status_code::contacts_merge: return "contacts_merge";
    case status_code::penetration: return "penetration";
  }
  return "unknown";
}

std::string regime(const material& m) {
  const double off = regime_offset(m);
  if (std::abs(off) <= boundary_width) return "boundary";
  return off < 0 ? "below" : "above";
}

trial_result trial_interval(const material& m, double speed, const indentor& ind, double a, double b,
                            const solve_options& options) {
  scene sc{m, speed, {ind}};
  validate(sc);
  if (!(a < b) || !std::isfinite(a) || !std::isfinite(b))
    throw std::invalid_argument("rhabel::punch::trial_interval: need finite a < b, got a = " + std::to_string(a) +
                                ", b = " + std::to_string(b));
  if (std::holds_alternative<flat>(ind.shape))
    throw std::invalid_argument("rhabel::punch::trial_interval: a flat punch has no trial family (its interval is fixed)");
  const context cx = make_context(m, speed, options);
  std::vector<indentor_state> st(1);
  st[0].source = &sc.indentors[0];
  st[0].k = static_cast<kind>(ind.shape.index());
  st[0].apex = ind.apex;
  const forcing F = own_forcing(st[0], cx, st, 0, false);
  const edge_exponents e = cx.exponents(0);
  contact_density g;
  if (st[0].k == kind::wedge && ind.apex > a && ind.apex < b && options.wedge_apex_split) {
    g = build_wedge_step(a, b, ind.apex, 0, cx, F);
  } else {
    g = build(a, b, cx, e, F, F.steps.empty());
  }
  trial_result out;
  const double total = g.integral();
  out.load = cx.pressure_scale * total;
  out.error_estimate = g.tail;
  if (st[0].k == kind::wedge) {
    out.hysteretic_friction = wedge_friction(g, std::get<wedge>(ind.shape), ind.apex);
  } else {
    out.hysteretic_friction = mean_slope(st[0], g);
  }
  return out;
}

indentor_result solve_single(const material& m, double speed, const indentor& ind, const solve_options& options) {
  scene s{m, speed, {ind}};
  return solve(s, options).indentors.front();
}

scene_result solve(const scene& s, const solve_options& options) {
  const auto start = std::chrono::steady_clock::now();
  validate(s);
  if (!(options.tolerance > 0) || !(options.tolerance < 1))
    throw std::invalid_argument("rhabel::punch::solve: options.tolerance must be in (0, 1)");
  const context cx = make_context(s.material, s.speed, options);

  // Indentors sorted by apex (st order; the contacts' order along x is the coupled solve's concern).
  std::vector<std::size_t> order(s.indentors.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t i, std::size_t j) { return s.indentors[i].apex < s.indentors[j].apex; });
  std::vector<indentor_state> st(s.indentors.size());
  const double origin = s.indentors[order[0]].apex;
  for (std::size_t i = 0; i < st.size(); ++i) {
    const auto& ind = s.indentors[order[i]];
    st[i].source = &ind;
    st[i].scene_index = order[i];
    st[i].k = static_cast<kind>(ind.shape.index());
    // Coordinates relative to the first apex (shifted back in the report): a contact far from
    // the origin keeps its digits (a wedge of L = 5e-13 at apex 1e6 was an internal error).
    st[i].apex = ind.apex - origin;
    st[i].target_load = ind.load / cx.pressure_scale;
  }
  const bool isolated = st.size() == 1;
  coupled_outcome coupled;
  if (isolated) {
    try {
      solve_isolated(st[0], cx, true);
    } catch (const std::domain_error& err) {
      throw std::domain_error("rhabel::punch::solve: " + indentor_name(order[0], *st[0].source) + " failed: " + err.what());
    }
  } else {
    coupled = solve_coupled(st, cx);
  }
  scene_result out;
  out.beta = cx.beta;
  out.kappa = cx.kappa;
  out.regime = regime(s.material);
  out.indentors.resize(st.size());
  const double ps = cx.pressure_scale;
  double worst_residual = 0;
  const surface heights(st, cx);
  for (std::size_t i = 0; i < st.size(); ++i) {
    const auto& g = st[i].g;
    indentor_result r;
    r.a = g.jacobi.lo;
    r.b = g.jacobi.hi;
    r.contact_length = g.length();
    r.epsilon = st[i].epsilon;
    r.load = ps * g.integral();
    // Mapped wedge density (abel's Moebius map): its series lives in apex.smooth, jacobi holds a c_0.
    const auto& series = g.has_apex && g.apex.mobius != 0 ? g.apex.smooth.coefficients : g.jacobi.coefficients;
    r.degree = series.empty() ? 0 : series.size() - 1;
    r.error_estimate = g.tail;
    r.status = st[i].status;
    // Hysteretic friction C_f = int f' g / int g with the indentor's own f'.
    if (g.line_load) {
      r.hysteretic_friction = 0;
    } else if (st[i].friction) {
      r.hysteretic_friction = *st[i].friction;
      r.error_estimate = std::max(r.error_estimate, st[i].friction_error);
    } else if (st[i].k == kind::wedge && (g.has_apex || cx.offset >= 0)) {
      r.hysteretic_friction = wedge_friction(g, std::get<wedge>(st[i].source->shape), st[i].apex);
    } else if (st[i].k == kind::wedge) {
      const auto& w = std::get<wedge>(st[i].source->shape);
      // Plain series (apex next to an edge): C_f = S1 - (S1 + S2) int_apex^b g / int g. The Jacobi series of int_apex^b g converges only
      // algebraically (the step of F at the apex): its truncation error behaves like
      // N^(alpha-1) (1 + O(1/N)), so the partial sums at N/4, N/2, N are Richardson-extrapolated
      // with the exponents alpha - 1 and alpha - 2; the spread of the extrapolants is the estimate.
      auto fraction_behind = [&](std::size_t terms) {
        contact_density t = g;
        t.jacobi.coefficients.resize(std::min(terms, g.jacobi.coefficients.size()));
        return t.integral_from(st[i].apex) / g.integral();
      };
      const std::size_t N = g.jacobi.coefficients.size();
      double behind = fraction_behind(N);
      if (N >= 32) {
        const double s1 = fraction_behind(N / 4), s2 = fraction_behind(N / 2), s3 = behind;
        const double r1 = std::pow(2.0, 1 - cx.alpha), r2 = std::pow(2.0, 2 - cx.alpha);
        const double e12 = s2 + (s2 - s1) / (r1 - 1), e23 = s3 + (s3 - s2) / (r1 - 1);
        behind = e23 + (e23 - e12) / (r2 - 1);
        r.error_estimate = std::max(r.error_estimate, std::abs(behind - e23));
      }
      r.hysteretic_friction = w.slope_leading - (w.slope_leading + w.slope_trailing) * behind;
    } else if (st[i].k == kind::flat) {
      r.hysteretic_friction = 0;
    } else {
      r.hysteretic_friction = mean_slope(st[i], g);
    }
    r.total_friction = r.hysteretic_friction + s.material.coulomb;
    // Edges.
    if (!g.line_load) {
      const edge_exponents e = g.exponents();
      edge_report lead{edge_side::leading, g.jacobi.lo, e.gam < 0, e.gam, ps * edge_intensity(g, false)};
      edge_report trail{edge_side::trailing, g.jacobi.hi, e.del < 0, e.del, ps * edge_intensity(g, true)};
      r.edges = {lead, trail};
      if (lead.singular) {
        r.peak_pressure = std::numeric_limits<double>::infinity();
        r.peak_pressure_at = g.jacobi.lo;
      } else if (trail.singular) {
        r.peak_pressure = std::numeric_limits<double>::infinity();
        r.peak_pressure_at = g.jacobi.hi;
      } else if (st[i].k == kind::wedge) {
        // Below the boundary the wedge density has a weak singularity at the apex
        // (|s|^-alpha, logarithmic at alpha = 0: docs/theory.md section 5).
        r.peak_pressure = std::numeric_limits<double>::infinity();
        r.peak_pressure_at = st[i].apex;
      } else {
        const auto [peak, where] = peak_of(g);
        r.peak_pressure = ps * peak;
        r.peak_pressure_at = where;
      }
    } else {
      r.edges = {edge_report{edge_side::leading, g.jacobi.lo, true, -1, ps * g.line_weight},
                 edge_report{edge_side::trailing, g.jacobi.hi, true, -1, ps * g.line_weight}};
      r.peak_pressure = std::numeric_limits<double>::infinity();
      r.peak_pressure_at = g.jacobi.lo;
    }
    // Residual of (8) at check points, by an independent quadrature (evidence: see check_points).
    // abel's quadrature_evaluator and enrichment image are uniform down to alpha = 0 (kernel
    // singularity subtracted for small alpha), so the elastic limit is checked too.
    const auto points = check_points(st, i);
    if (!options.residual) {
      r.residual = std::numeric_limits<double>::quiet_NaN();  // not asked for (documented)
      worst_residual = r.residual;
    } else if (!g.line_load) {
      double worst = 0;
      // Relative to the data's scale: max |F| at the points, and for a flat face (F = 0) the size
      // of the density's own action, mean(g) (L/2)^alpha.
      double scale = g.integral() / g.length() * std::pow(g.length() / 2, cx.alpha);
      const inside_action apply_inside(g, cx.par);
      for (const double sck : points) {
        double lhs = apply_inside(sck);
        for (std::size_t j = 0; j < st.size(); ++j)
          if (j != i) lhs += apply_outside(st[j].g, sck, cx.par);
        const double rhs = own_slope(st[i], sck) / cx.gamma_factor;
        worst = std::max(worst, std::abs(lhs - rhs));
        scale = std::max(scale, std::abs(rhs));
      }
      r.residual = scale > 0 ? worst / scale : worst;
      if (!std::isnan(worst_residual)) worst_residual = std::max(worst_residual, r.residual);
    }
    judge(r, st[i], points, cx.pressure_scale, options.acceptance,
          isolated ? std::pair<double, double>{0.0, 0.0} : worst_gap(heights, st, i));
    // Fields on request.
    if (options.grid_points > 0) {
      const std::size_t n = options.grid_points;
      r.grid_x.resize(n);
      r.pressure.resize(n);
      // g.value(t) at every sample through one abel::enriched_evaluator, in one values() call (the
      // series' recurrence coefficients once, the series of four samples summed together, the
      // weight w = (1-x)^del (1+x)^gam once per sample): without a map the
      // density whose series is g.jacobi and whose enrichment is g.apex's; mapped (apex near an
      // edge) g.apex itself, whose series lives in the mapped variable, plus g.jacobi's c_0.
      const bool mapped = g.has_apex && g.apex.mobius != 0;
      abel::enriched_density<double> whole = g.apex;
      if (!mapped) whole.smooth = g.jacobi;
      if (!g.has_apex) whole.enrichment = 0;
      const abel::enriched_evaluator<double> density(whole);
      const double h = g.jacobi.half_length();
      std::vector<std::size_t> inside;  // samples strictly inside the contact, evaluated in one batch
      std::vector<double> one_plus, one_minus;
      for (std::size_t k = 0; k < n; ++k) {
        const double t = g.jacobi.lo + g.length() * (static_cast<double>(k) + 0.5) / static_cast<double>(n);
        r.grid_x[k] = t;
        r.pressure[k] = 0.0;
        if (st[i].rh_unit) continue;  // filled by rh_pressure below
        if (g.line_load || !(t > g.a()) || !(t < g.b())) continue;
        inside.push_back(k);
        one_plus.push_back((t - g.jacobi.lo) / h);
        one_minus.push_back((g.jacobi.hi - t) / h);
      }
      std::vector<double> values(inside.size());
      density.values(one_plus.data(), one_minus.data(), values.data(), inside.size());
      for (std::size_t j = 0; j < inside.size(); ++j) {
        const double t = r.grid_x[inside[j]];
        double value = values[j];
        if (mapped) value += g.jacobi.value_at_distance(t - g.jacobi.lo, g.jacobi.hi - t);
        r.pressure[inside[j]] = ps * value;
      }
      if (st[i].rh_unit) {
        const double estimate = rh_pressure(*st[i].rh_unit, -*st[i].epsilon, st[i].rh_one_minus_eps, g.jacobi.gam,
                                            g.jacobi.del, st[i].apex, g.length(), ps * std::pow(g.length(), -cx.alpha), r);
        std::ostringstream os;
        os.precision(2);
        os << "; pressure grid error estimate " << estimate << " of the peak";
        r.status += os.str();
      }
      if (g.line_load) r.status += "; pressure grid is empty of meaning for a line load (all zeros)";
    }
    if (options.grid_points > 0 && options.displacement) {
      const std::size_t n = options.grid_points;
      const double L = g.length() > 0 ? g.length() : 1.0;
      r.displacement_x.resize(n);
      r.displacement.resize(n);
      const double lo = g.jacobi.lo - L, hi = g.jacobi.hi + L;
      for (std::size_t k = 0; k < n; ++k) {
        const double x = n == 1 ? (lo + hi) / 2 : lo + (hi - lo) * static_cast<double>(k) / static_cast<double>(n - 1);
        r.displacement_x[k] = x;
        r.displacement[k] = heights.height(i, x);
      }
    }
    shift(r, origin);
    out.indentors[order[i]] = std::move(r);
  }
  out.diagnostics.residual = worst_residual;
  out.diagnostics.code = coupled.code;
  out.diagnostics.status = coupled.code == status_code::ok ? "ok" : coupled.message;
  out.diagnostics.iterations = coupled.iterations;
  for (std::size_t i = 0; i < out.indentors.size(); ++i)
    if (out.indentors[i].code != status_code::ok && out.diagnostics.code == status_code::ok) {
      out.diagnostics.code = out.indentors[i].code;
      out.diagnostics.status = "see indentors[" + std::to_string(i) + "].status";
    }
  out.diagnostics.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rhabel::punch
