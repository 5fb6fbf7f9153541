// punch/src/report.cpp: the report of a solved contact and its evidence: the residual of (8) by an
// independent quadrature at check points, the status (judge: residual, error estimate, sign of
// the pressure, load, penetration), the sampled fields. See internal.hpp for the layout.
#include "internal.hpp"
#include "surface.hpp"

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

// The boundary-layer part's action at s outside [lo, hi] (s off the edges): abel's panel rule
// (another node count than the solve's) graded toward the poles and toward the end facing s, where
// the kernel's branch point lies, with the kernel's argument from the distances to the ends.
double layer_outside(const abel::layer_density<double>& layer, double s, const abel::abel_parameters<double>& par) {
  const double inf = std::numeric_limits<double>::infinity(), h = layer.half_length();
  const bool before = s < layer.lo;  // s before the interval: t - s > 0
  const double d = before ? layer.lo - s : s - layer.hi;
  const abel::panel_integrator<double> rule(layer.del, layer.gam, 20);
  return h * rule.integrate(2.0, std::min(layer.nearest_lo(), before ? d / h : inf),
                            std::min(layer.nearest_hi(), before ? inf : d / h), [&](double u, double v) {
                              const double t_minus_s = before ? d + h * u : -(d + h * v);
                              return layer.factor_at_distance(u, v) * abel::cross_kernel(par, t_minus_s);
                            });
}

// A g (s) for s outside (or on the edge of) the support of g: the operator of (8)
// (abel_operator::apply: graded Gauss-Jacobi quadrature outside the interval), plus the apex part
// and the boundary-layer part (a density as solved, indentor_state::solved; s off the edges).
double apply_outside(const contact_density& g, double s, const abel::abel_parameters<double>& par) {
  const double alpha = par.alpha();
  if (g.line_load) {
    const double r = g.a() - s;
    if (r > 0) return g.line_weight * std::pow(r, alpha - 1);
    return -par.kappa() * g.line_weight * std::pow(-r, alpha - 1);
  }
  const abel::abel_operator<double> op(par, g.a(), g.b());
  const auto& j = g.jacobi;
  double result = 0;
  if (j.coefficients.empty() || (s >= g.a() && s <= g.b())) {
    result = op.apply(j, s);
  } else {
    // The same quadrature as op.apply outside the support (apply_by_quadrature with the series'
    // length as degree hint), the series summed with its recurrence coefficients computed once:
    // the sum at every node is what costs, O(degree) each. Two parabolas 1e-3 / 4e-4 L apart
    // (series of degree ~500 / ~800): the report's residual 97 / 258 ms with jacobi_density's
    // Clenshaw sum, 52 / 133 ms so (the same residuals).
    const rhabel::quadrature::jacobi_series<double> series(j.coefficients, j.del, j.gam);
    result = op.apply_by_quadrature([&](double x) { return series(x); }, j.gam, j.del, s, j.coefficients.size());
  }
  if (g.has_apex) result += abel::apply(op, g.apex, s);
  for (const auto& term : g.kinks) result += abel::apply(op, term, s);
  if (!g.layer.empty()) result += layer_outside(g.layer, s, par);
  return result;
}

// (8) evaluated at points s inside the support by an independent quadrature of the two one-sided
// integrals (abel_operator::quadrature_evaluator, built once per density; it does not use the
// spectral relation, so it checks it), plus the apex enrichment by abel::apply (its direct graded
// quadrature of A[phi]: the same quadrature abel::solve_step used to build the data, so for that
// part the residual checks the smooth remainder only; s must not be the apex), plus the
// boundary-layer part of a density as solved (indentor_state::solved) by the same independent
// quadrature, its panels graded toward the poles, at another node count than the solve's.
class inside_action {
 public:
  inside_action(const contact_density& g, const abel::abel_parameters<double>& par)
      : g_(g), op_(par, g.a(), g.b()), evaluate_(op_, g.jacobi.gam, g.jacobi.del, g.jacobi.coefficients.size() + 32),
        evaluate_layer_(op_, g.jacobi.gam, g.jacobi.del, 40),
        evaluate_mapped_(op_, g.jacobi.gam, g.jacobi.del, g.apex.smooth.coefficients.size() + 32),
        split_(g.apex.quadrature_nodes() - 4), series_(g.jacobi.coefficients, g.jacobi.del, g.jacobi.gam),
        mapped_series_(g.apex.smooth.series_evaluator()) {}
  inside_action(const inside_action&) = delete;
  inside_action& operator=(const inside_action&) = delete;
  double operator()(double s) const {
    // g.jacobi.series(x) with the recurrence coefficients computed once (same sum to a few ulps).
    double result = series_sum(evaluate_, series_, s);
    if (!g_.layer.empty()) {
      const auto& layer = g_.layer;
      result += evaluate_layer_([&](double, double p, double m) { return layer.factor_at_distance(p, m); }, s,
                                layer.nearest_lo(), layer.nearest_hi());
    }
    // The knots' terms by abel::apply (their direct graded quadratures of A[C phi], which the tests
    // check against tanh-sinh: here, as for the apex, the residual checks the series' part).
    for (const auto& term : g_.kinks) result += abel::apply(op_, term, s);
    if (!g_.has_apex) return result;
    // A[C phi] as abel::apply computes it inside the interval, with the split rules built once
    // for all check points (abel::apply builds them per call).
    const double h = op_.half_length(), alpha = op_.parameters().alpha();
    const auto& apex = g_.apex;
    if (apex.mobius == 0) {
      const double y = map_to_reference(s, g_.a(), g_.b()).x;
      return result + std::pow(h, alpha) * apex.enrichment * abel::enrichment_image_any(apex, op_.parameters(), split_, y);
    }
    // Mapped: the covariance A[g](M(sigma)) = (1 - s^2)^alpha (1 + s sigma)^(1 - alpha) A[g~](sigma)
    // (abel/step_enrichment.hpp), with the series part of g~ by the same independent quadrature.
    const auto d = apex.sigma_of((s - g_.a()) / h, (g_.b() - s) / h);
    const double y = d[0] <= d[1] ? d[0] - 1 : 1 - d[1];
    const double t = d[0] <= d[1] ? g_.a() + h * d[0] : g_.b() - h * d[1];
    const double mapped = series_sum(evaluate_mapped_, mapped_series_, t) +
                          std::pow(h, alpha) * apex.enrichment * abel::enrichment_image_any(apex, op_.parameters(), split_, y);
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
  abel::abel_operator<double>::quadrature_evaluator evaluate_, evaluate_layer_, evaluate_mapped_;
  abel::split_integrator<double> split_;  // node count as in abel::apply
  rhabel::quadrature::jacobi_series<double> series_;  // g.jacobi's series, coefficients precomputed
  rhabel::quadrature::jacobi_series<double> mapped_series_;  // g.apex.smooth's (mapped only; else empty)
};

// Penetration check of every coupled contact i (an indentor that is not a flat punch, whose square
// corners bound it): outside the contact the surface must stay at or above the rigid profile,
// gap(x) = height(i, x) - profile(i, x) >= 0, at 2 x 7 points a - L 2^-m and b + L 2^-m
// (m = 0 .. 6; a general profile's inside its search window). Not closer to the edges: the moments' Gauss-Jacobi rule (~100 nodes) resolves the
// own contact's log kernel at a distance d from its end to ~(1 + sqrt(4 d/L))^-200, 1e-6 at
// d = L/1024 (measured: a spurious "penetration" of 1.5e-6 of the span there), 1e-20 at L/64. A
// wrong edge next to a point closer than that shows as tension (non-zero intensity) instead.
// Returns for each contact the worst gap relative to the profile's span over its points, and
// where (0 when none is negative).
//
// All contacts' points at once (surface::heights, one pass over the contacts with each contact's
// moments interpolated on graded panels): WHY not height(i, x) point by point: a quadrature of
// every near contact at each point, 13 s of a report of 974 contacts (1e5-sample periodic
// profile; 9 s of the 443-contact one's 2.9 min).
std::vector<std::pair<double, double>> worst_gaps(const surface& heights, const std::vector<indentor_state>& st) {
  std::vector<std::pair<double, double>> out(st.size(), {0.0, 0.0});
  struct probe {
    double x;
    std::size_t contact;
  };
  std::vector<probe> probes;
  for (std::size_t i = 0; i < st.size(); ++i) {
    const auto& g = st[i].g;
    if (g.line_load || st[i].k == kind::flat) continue;
    const double L = g.length();
    // A general profile is given on its search window only (a sampled profile's data: beyond
    // them the slope is a continuation, not the profile; contact_set.cpp checks every sample).
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    if (st[i].k == kind::general) {
      const auto& gp = std::get<general_profile>(st[i].source->shape);
      lo = st[i].apex + gp.search_lo;
      hi = st[i].apex + gp.search_hi;
    }
    for (int m = 0; m <= 6; ++m)
      for (const double x : {g.a() - L * std::ldexp(1.0, -m), g.b() + L * std::ldexp(1.0, -m)})
        if (x >= lo && x <= hi) probes.push_back({x, i});
  }
  // In ascending x: surface::moments then needs no sort per contact.
  std::stable_sort(probes.begin(), probes.end(), [](const probe& p, const probe& q) { return p.x < q.x; });
  std::vector<double> xs(probes.size());
  std::vector<std::size_t> reference(probes.size());
  for (std::size_t k = 0; k < probes.size(); ++k) xs[k] = probes[k].x, reference[k] = probes[k].contact;
  const std::vector<double> height = heights.heights(xs, reference);
  std::vector<double> span(st.size(), 0.0);
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const std::size_t i = probes[k].contact;
    const double f = heights.profile(i, xs[k]);
    span[i] = std::max(span[i], std::abs(f));
    const double gap = height[k] - f;
    if (gap < out[i].first) out[i] = {gap, xs[k]};
  }
  for (std::size_t i = 0; i < st.size(); ++i)
    if (span[i] > 0) out[i].first /= span[i];
  return out;
}

std::vector<double> pressure_probes(const contact_density& g) {
  std::vector<double> out(64);
  for (int k = 0; k < 64; ++k) out[k] = g.a() + g.length() * (1 - std::cos(pi * (k + 0.5) / 64)) / 2;
  return out;
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

// C_f = int f' g / int g with the indentor's own f' (0 for a line load, a flat face, and a
// density that carries no load); a wedge's plain series (apex next to an edge) by Richardson
// extrapolation, whose spread joins r.error_estimate.
void report_friction(const indentor_state& state, const context& cx, indentor_result& r) {
  const auto& g = state.g;
  if (g.line_load) {
    r.hysteretic_friction = 0;
  } else if (state.friction) {
    r.hysteretic_friction = *state.friction;
    r.error_estimate = std::max(r.error_estimate, state.friction_error);
  } else if (state.k == kind::wedge && (g.has_apex || cx.offset >= 0)) {
    r.hysteretic_friction = wedge_friction(g, std::get<wedge>(state.source->shape), state.apex);
  } else if (state.k == kind::wedge) {
    const auto& w = std::get<wedge>(state.source->shape);
    // Plain series (apex next to an edge): C_f = S1 - (S1 + S2) int_apex^b g / int g. The Jacobi
    // series of int_apex^b g converges only algebraically (the step of F at the apex): its truncation error behaves like
    // N^(alpha-1) (1 + O(1/N)), so the partial sums at N/4, N/2, N are Richardson-extrapolated
    // with the exponents alpha - 1 and alpha - 2; the spread of the extrapolants is the estimate.
    auto fraction_behind = [&](std::size_t terms) {
      contact_density t = g;
      t.jacobi.coefficients.resize(std::min(terms, g.jacobi.coefficients.size()));
      return t.integral_from(state.apex) / g.integral();
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
  } else if (state.k == kind::flat) {
    r.hysteretic_friction = 0;
  } else {
    r.hysteretic_friction = mean_slope(state, g);
  }
  // A density that carries no load (a coupled solve that failed before this contact was solved:
  // its status says so) has no mean slope: 0, never NaN.
  if (!std::isfinite(r.hysteretic_friction)) r.hysteretic_friction = 0;
}

// The edges (exponents, intensity factors) and the peak pressure: +inf at a singular edge or a
// wedge's apex below the boundary, else the density's maximum (peak_of).
void report_edges(const indentor_state& state, double ps, indentor_result& r) {
  const auto& g = state.g;
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
    } else if (state.k == kind::wedge) {
      // Below the boundary the wedge density has a weak singularity at the apex
      // (|s|^-alpha, logarithmic at alpha = 0: docs/theory.md section 5).
      r.peak_pressure = std::numeric_limits<double>::infinity();
      r.peak_pressure_at = state.apex;
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
}

// The relative residual of (8) at the check points by an independent quadrature (evidence: see
// check_points). abel's quadrature_evaluator and enrichment image are uniform down to alpha = 0
// (kernel singularity subtracted for small alpha), so the elastic limit is checked too.
double contact_residual(const std::vector<indentor_state>& st, std::size_t i, const context& cx, const surface& heights,
                        const std::vector<double>& points) {
  const auto& g = st[i].g;
  double worst = 0;
  // Relative to the data's scale: max |F| at the points, and for a flat face (F = 0) the size
  // of the density's own action, mean(g) (L/2)^alpha.
  double scale = g.integral() / g.length() * std::pow(g.length() / 2, cx.alpha);
  // In the boundary-layer basis: the densities as solved (series and poles; g is their
  // projection, within g.tail), every other contact summed directly (fewer than
  // iterative_from contacts: no far field).
  const auto as_solved = [&](std::size_t j) -> const contact_density& { return st[j].solved ? *st[j].solved : st[j].g; };
  const bool layered = std::any_of(st.begin(), st.end(), [](const indentor_state& s) { return s.solved.has_value(); });
  const auto others = [&](double s) {
    if (!layered) return heights.others_action(i, s);
    double sum = 0;
    for (std::size_t j = 0; j < st.size(); ++j)
      if (j != i) sum += apply_outside(as_solved(j), s, cx.par);
    return sum;
  };
  const inside_action apply_inside(as_solved(i), cx.par);
  for (const double sck : points) {
    const double lhs = apply_inside(sck) + others(sck);
    const double rhs = own_slope(st[i], sck) / cx.gamma_factor;
    worst = std::max(worst, std::abs(lhs - rhs));
    scale = std::max(scale, std::abs(rhs));
  }
  return scale > 0 ? worst / scale : worst;
}

// The fields: the pressure as a function always (its source is a copy of the density), the
// pressure and displacement samples on request.
void report_fields(const std::vector<indentor_state>& st, std::size_t i, const context& cx, const surface& heights,
                   double origin, indentor_result& r) {
  const solve_options& options = cx.options;
  const double ps = cx.pressure_scale;
  const auto& g = st[i].g;
  auto field = std::make_shared<pressure_field::source>();
  field->g = g;
  field->scale = ps;
  if (st[i].rh_unit) field->rh = rh_wedge{st[i].rh_unit, *st[i].epsilon, st[i].rh_one_minus_eps, st[i].apex,
                                          ps * std::pow(g.length(), -cx.alpha)};
  if (options.grid_points > 0) {
    r.grid_x = pressure_grid(g.a(), g.b(), options.grid_points, options.spacing);
    const double estimate = sample_pressure(*field, r.grid_x, r.pressure);
    if (field->rh) {
      std::ostringstream os;
      os.precision(2);
      os << "; pressure grid error estimate " << estimate << " of the peak";
      r.status += os.str();
    }
    if (g.line_load) r.status += "; pressure grid is empty of meaning for a line load (all zeros)";
  }
  r.pressure_at = pressure_field(std::move(field), origin);
  if (options.grid_points > 0 && options.displacement) {
    const double L = g.length() > 0 ? g.length() : 1.0;
    r.displacement_x = even_grid(g.jacobi.lo - L, g.jacobi.hi + L, options.grid_points);
    r.displacement = heights.heights(i, r.displacement_x);
  }
}

// The status of one contact from its evidence (contact.hpp, status_code): the residual, the error
// estimate, the sign of the pressure (at 64 interior points and the check points, relative to the
// mean pressure) and the load. Keeps the solver's note (st.status) in front of the findings. Its
// messages give abscissae in the scene's coordinates (the solve's plus origin).
void judge(indentor_result& r, const indentor_state& st, const std::vector<double>& points, double pressure_scale,
           double acceptance, std::pair<double, double> gap, double origin) {
  std::ostringstream why;
  why.precision(3);
  status_code code = status_code::ok;
  auto fail = [&](status_code c, const std::string& text) {
    if (code == status_code::ok) code = c;
    why << (why.tellp() > 0 ? "; " : "") << text;
  };
  const double target = st.target_load * pressure_scale;  // the requested load (on a rigid body: its solved share)
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
    for (const double t : pressure_probes(st.g)) probe(t);
    for (double t : points) probe(t);
    if (lowest < -acceptance * std::abs(mean)) {
      std::ostringstream os;
      os.precision(3);
      os << "negative pressure " << pressure_scale * lowest << " at x = " << where + origin << " (" << lowest / mean
         << " of the mean pressure)";
      fail(status_code::tension, os.str());
    }
  }
  if (gap.first < -acceptance) {
    std::ostringstream os;
    os.precision(3);
    os << "the surface penetrates the indentor at x = " << gap.second + origin << " (by " << -gap.first
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
// The result of contact i, everything in the coordinates of the solve (shifted back by the
// caller): edges and their intensities, load, friction, peak, the residual of (8) at the check
// points and the status (judge), and the sampled fields on request.
indentor_result report_contact(const std::vector<indentor_state>& st, std::size_t i, const context& cx,
                               const surface& heights, double coulomb, std::pair<double, double> gap, double origin) {
  const solve_options& options = cx.options;
  const double ps = cx.pressure_scale;
  const auto& g = st[i].g;
  indentor_result r;
  switch (st[i].k) {
    case kind::parabola: r.shape = shape_kind::parabolic; break;
    case kind::wedge: r.shape = shape_kind::wedge; break;
    case kind::flat: r.shape = shape_kind::flat; break;
    case kind::general: r.shape = shape_kind::general; break;
  }
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
  report_friction(st[i], cx, r);
  r.total_friction = r.hysteretic_friction + coulomb;
  report_edges(st[i], ps, r);
  const auto points = check_points(st, i);
  if (!options.residual) {
    r.residual = std::numeric_limits<double>::quiet_NaN();  // not asked for (documented)
  } else if (!g.line_load) {
    r.residual = contact_residual(st, i, cx, heights, points);
  }
  judge(r, st[i], points, cx.pressure_scale, options.acceptance, gap, origin);
  report_fields(st, i, cx, heights, origin, r);
  return r;
}


}  // namespace rhabel::punch::detail
