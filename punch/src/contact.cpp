// punch/src/contact.cpp: the public entry points of the punch layer (solve, solve_single,
// trial_interval) and the validation of a scene. Mathematics: ../include/rhabel/punch/contact.hpp
// and docs/theory.md. Everything in punch/src is double precision; internal.hpp gives the layout.
#include "rhabel/punch/contact.hpp"
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

namespace rhabel::punch {

namespace detail {

[[noreturn]] void bad_field(const std::string& field, double value, const char* requirement,
                            const char* function = "rhabel::punch::solve") {
  std::ostringstream os;
  os.precision(17);
  os << function << ": " << field << " = " << value << " must be " << requirement;
  throw std::invalid_argument(os.str());
}

// ---------------------------------------------------------------------------------------------
// Limits of representable scenes (examples/README.md, the schema table). Each field may be
// valid alone while the scene is not representable in double precision: the solve works in the
// scene's units, so its contact lengths, strains and pressure scale must be numbers far from the
// double range (its squares and powers 1/(1 - alpha) are formed on the way). The checks use the
// scaling of the closed forms (docs/theory.md section 5) in logarithms, so that they never overflow:
// with E_U the effective modulus (material::effective_modulus), a contact length and a strain
//   parabola: L ~ (P R/E_U)^(1/(2 - alpha)), strain L/R;
//   wedge:    L from P/pressure_scale = K L^(1 - alpha), K in closed form (validate_scales),
//             strain S = (S1 + S2)/2;
//   flat:     L = width,                       strain P/(E_U width^(1 - alpha)).
// The parabola's constants (Beta functions of order 1, to the power 1/(2 - alpha) < 1) do not
// matter at these margins.
constexpr double max_decades_modulus = 250;  // E_U in [1e-250, 1e250]
constexpr double max_decades_length = 100;   // contact lengths in [1e-100, 1e100]
constexpr double max_decades_strain = 100;   // strains in [1e-100, 1e100]
// 1 - beta = (2/pi) atan(1/q), q = coulomb (1 - 2 nu)/(2 (1 - nu)): beyond q = 1e12, beta is
// within 7e-13 of 1, where the exponents of (8) (1 + beta)/2 and the kernel's factor
// tan(beta pi/2) leave no digits to the solve (measured at nu = 0.3: q = 3e5 ok; q = 3e7 .. 3e11
// not_converged, exit code 3; q = 3e299 gave beta = 1 exactly, an internal error).
constexpr double max_friction_ratio = 1e12;
// Below the boundary (alpha + beta/2 < 1/2), a wedge's leading slope at most 1e7 times its
// trailing one: beyond, the contact starts within ~1e-14 L of the apex, the apex split of the
// density and the residual's quadrature next to the apex fail (measured at alpha = 0, 0.1, 0.3:
// 1e7 ok, 1e8 refused with internal messages). Above it the contact ends at the apex (C_f = S1), and
// the other way (S2 >> S1) too: no limit there.
constexpr double max_slope_ratio = 1e7;

namespace {
[[noreturn]] void not_representable(const std::string& fields, double decades, const char* what, double limit,
                                    const char* function = "rhabel::punch::solve") {
  std::ostringstream os;
  os << std::fixed;
  os.precision(0);
  os << function << ": " << fields << " give " << what << " ~1e" << decades
     << ", beyond the representable range [1e-" << limit << ", 1e" << limit << "] (examples/README.md, limits)";
  throw std::invalid_argument(os.str());
}

// log10 E_U, formed in logarithms (never overflows).
double log10_modulus(const material& m, double speed) {
  const double alpha = m.alpha < alpha_zero ? 0.0 : m.alpha;
  return (std::log(m.E1) + std::lgamma(1 - alpha) + alpha * std::log(speed) - std::log1p(-m.poisson * m.poisson)) /
         std::log(10.0);
}
}  // namespace

// The scale limits above, for one indentor (after the fields' own ranges and E_U were checked by
// validate_material).
void validate_scales(const material& m, double speed, const indentor& ind, const std::string& p) {
  const double ln10 = std::log(10.0);
  const double alpha = m.alpha < alpha_zero ? 0.0 : m.alpha;
  const double log_modulus = log10_modulus(m, speed);
  const double log_load = std::log10(ind.load);
  double log_length = 0, log_strain = 0;
  std::string fields;
  if (const auto* q = std::get_if<parabolic>(&ind.shape)) {
    log_length = (log_load + std::log10(q->radius) - log_modulus) / (2 - alpha);
    log_strain = log_length - std::log10(q->radius);
    fields = p + "load, " + p + "radius and the material";
  } else if (const auto* w = std::get_if<wedge>(&ind.shape)) {
    // int g = K L^(1 - alpha) with the closed form of K (single_contact.cpp, solve_wedge): above
    // the boundary K = S1 cos(beta pi/2) B(gam + 1, del + 1)/(pi Gamma(1 - alpha)), exactly, since
    // its power 1/(1 - alpha) amplifies every factor as alpha -> 1 (Gamma(1 - alpha)^(1/(1 - alpha))
    // is 1e200 at alpha = 0.99); below it (alpha < 1/2, a power < 2) the same with S = (S1 + S2)/2.
    const double S = 0.5 * w->slope_leading + 0.5 * w->slope_trailing;
    log_strain = std::log10(S);
    const context cx = make_context(m, speed, solve_options{});
    const bool above = cx.offset >= -boundary_width;
    if (!above && w->slope_leading > max_slope_ratio * w->slope_trailing) {
      std::ostringstream os;
      os.precision(3);
      os << "rhabel::punch::solve: " << p << "slope_leading / " << p << "slope_trailing = "
         << w->slope_leading / w->slope_trailing << " must be <= " << max_slope_ratio
         << " below the boundary alpha + beta/2 = 1/2 (the contact would start within rounding of the apex; "
            "examples/README.md, limits)";
      throw std::invalid_argument(os.str());
    }
    const edge_exponents e = cx.exponents(above ? 0 : -1);
    const double log_beta = above ? (std::lgamma(e.gam + 1) + std::lgamma(e.del + 1) - std::lgamma(e.gam + e.del + 2)) / ln10 : 0.0;
    const double log_K = std::log10(above ? w->slope_leading : S) + std::log10(std::cos(cx.beta * pi / 2)) + log_beta -
                         std::log10(pi) - std::lgamma(1 - alpha) / ln10;
    const double log_target = log_load - std::log10(pi / 2) - log_modulus;  // P / pressure_scale
    log_length = (log_target - log_K) / (1 - alpha);
    fields = p + "load, " + p + "slope_leading, " + p + "slope_trailing and the material";
  } else if (const auto* f = std::get_if<flat>(&ind.shape)) {
    log_length = std::log10(f->width);
    log_strain = log_load - log_modulus - (1 - alpha) * log_length;
    fields = p + "load, " + p + "width and the material";
  } else {
    return;  // a general profile: its scales are the caller's
  }
  if (!(std::abs(log_length) <= max_decades_length)) not_representable(fields, log_length, "a contact length", max_decades_length);
  if (!(std::abs(log_strain) <= max_decades_strain)) not_representable(fields, log_strain, "a strain", max_decades_strain);
}

void validate_material(const material& m, double speed, const char* function) {
  if (!(m.alpha >= 0 && m.alpha < 1)) bad_field("material.alpha", m.alpha, "in [0, 1)", function);
  if (!(m.E1 > 0) || !std::isfinite(m.E1)) bad_field("material.E1", m.E1, "finite and > 0", function);
  if (!(m.poisson > -1 && m.poisson <= 0.5)) bad_field("material.poisson", m.poisson, "in (-1, 0.5]", function);
  if (!(m.coulomb >= 0) || !std::isfinite(m.coulomb)) bad_field("material.coulomb", m.coulomb, "finite and >= 0", function);
  if (m.coulomb * (1 - 2 * m.poisson) > max_friction_ratio * 2 * (1 - m.poisson)) {
    std::ostringstream os;
    os.precision(17);
    os << function << ": material.coulomb = " << m.coulomb << " must be <= 1e12 x 2 (1 - nu)/(1 - 2 nu) = "
       << max_friction_ratio * 2 * (1 - m.poisson) / (1 - 2 * m.poisson)
       << " (beyond, beta is within rounding of 1; examples/README.md, limits)";
    throw std::invalid_argument(os.str());
  }
  if (!(speed > 0) || !std::isfinite(speed)) bad_field("speed", speed, "finite and > 0", function);
  const double log_modulus = log10_modulus(m, speed);
  if (!(std::abs(log_modulus) <= max_decades_modulus))
    not_representable("material.E1, material.alpha and speed", log_modulus, "the effective modulus E_U",
                      max_decades_modulus, function);
}

void validate(const scene& s) {
  validate_material(s.material, s.speed, "rhabel::punch::solve");
  const auto& m = s.material;
  if (s.indentors.empty()) throw std::invalid_argument("rhabel::punch::solve: indentors is empty; give at least one");
  for (std::size_t i = 0; i < s.indentors.size(); ++i) {
    const auto& ind = s.indentors[i];
    const std::string p = "indentors[" + std::to_string(i) + "].";
    if (!s.body && (!(ind.load > 0) || !std::isfinite(ind.load))) bad_field(p + "load", ind.load, "finite and > 0");
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
      for (std::size_t k = 0; k < g->knots.size(); ++k) {
        const std::string knot = p + "knots[" + std::to_string(k) + "]";
        if (!std::isfinite(g->knots[k].first)) bad_field(knot + ".first", g->knots[k].first, "finite");
        if (!std::isfinite(g->knots[k].second)) bad_field(knot + ".second", g->knots[k].second, "finite");
      }
    }
    validate_scales(m, s.speed, ind, p);
  }
}

std::string indentor_name(std::size_t i, const indentor& ind) {
  static const char* names[] = {"parabolic", "wedge", "flat", "general_profile"};
  return "indentors[" + std::to_string(i) + "] (" + names[ind.shape.index()] + ")";
}

}  // namespace detail

using namespace detail;

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
  const forcing F = own_forcing(st[0], cx);
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

namespace detail {

/// scene::body: the total load, the heights, and the shapes a body carries.
void validate_body(const scene& s) {
  if (!s.body) return;
  if (!(s.body->load > 0) || !std::isfinite(s.body->load)) bad_field("body.load", s.body->load, "finite and > 0");
  for (std::size_t i = 0; i < s.indentors.size(); ++i) {
    const auto& ind = s.indentors[i];
    const std::string p = "indentors[" + std::to_string(i) + "].";
    if (!std::isfinite(ind.height)) bad_field(p + "height", ind.height, "finite");
    if (std::holds_alternative<flat>(ind.shape))
      throw std::invalid_argument("rhabel::punch::solve: " + p +
                                  "shape: a flat punch on a rigid body (scene body) is not supported; give each "
                                  "indentor its own load instead");
  }
}

/// scene::body: the body's approach, and the evidence that the loads add up to the total and the
/// levels approach_i + height_i agree (diagnostics code and status otherwise).
void report_body(const scene& s, const std::vector<indentor_state>& st, const context& cx, scene_result& out) {
  double total = 0, spread = 0, scale = 0;
  const auto& first = out.indentors[st[0].scene_index];
  const double level0 = first.approach + st[0].height;
  for (const auto& state : st) {
    const auto& r = out.indentors[state.scene_index];
    total += r.load;
    spread = std::max(spread, std::abs(r.approach + state.height - level0));
    scale = std::max(scale, max_slope(state, state.g.a(), state.g.b()) * state.g.length());
  }
  out.body_approach = level0;
  const double load_defect = std::abs(total / s.body->load - 1), level_defect = spread / scale;
  const double tol = cx.options.acceptance;
  if (out.diagnostics.code != status_code::ok || (load_defect <= tol && level_defect <= tol)) return;
  std::ostringstream os;
  os.precision(3);
  if (load_defect > tol) {
    out.diagnostics.code = status_code::load_mismatch;
    os << "the indentors' loads add up to " << total << " for a body load of " << s.body->load;
  } else {
    out.diagnostics.code = status_code::not_converged;
    os << "the indentors' levels (approach + height) differ by " << level_defect << " of max |f'| L";
  }
  out.diagnostics.status = os.str();
}


scene_states prepare_states(const scene& s, const context& cx) {
  // Indentors sorted by apex (st order; the contacts' order along x is the coupled solve's concern).
  std::vector<std::size_t> order(s.indentors.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t i, std::size_t j) { return s.indentors[i].apex < s.indentors[j].apex; });
  scene_states out;
  out.st.resize(s.indentors.size());
  out.origin = s.indentors[order[0]].apex;
  for (std::size_t i = 0; i < out.st.size(); ++i) {
    auto& state = out.st[i];
    const auto& ind = s.indentors[order[i]];
    state.source = &ind;
    state.scene_index = order[i];
    state.k = static_cast<kind>(ind.shape.index());
    // Coordinates relative to the first apex (shifted back in the report): a contact far from
    // the origin keeps its digits (a wedge of L = 5e-13 at apex 1e6 was an internal error).
    state.apex = ind.apex - out.origin;
    // On a rigid body the loads are unknowns: an equal share is the start.
    state.target_load = (s.body ? s.body->load / static_cast<double>(out.st.size()) : ind.load) / cx.pressure_scale;
    state.height = ind.height;
  }
  return out;
}

coupled_outcome solve_states(const scene& s, scene_states& ss, const context& cx) {
  auto& st = ss.st;
  if (st.size() > 1)
    return solve_coupled(st, cx, s.body ? std::optional<double>(s.body->load / cx.pressure_scale) : std::nullopt,
                         ss.jacobian);
  try {
    solve_isolated(st[0], cx);
  } catch (const std::domain_error& err) {
    throw std::domain_error("rhabel::punch::solve: " + indentor_name(st[0].scene_index, *st[0].source) +
                            " failed: " + err.what());
  }
  return {};
}

// The surface displacement of several contacts on one grid (scene_result::surface): grid_points
// a contact, uniform over the contacts' span widened by the longest contact on either side.
void report_surface(const std::vector<indentor_state>& st, const surface& heights, const context& cx, double origin,
                    scene_result& out) {
  double lo = st.front().g.a(), hi = st.front().g.b(), longest = 0;
  for (const auto& state : st) {
    lo = std::min(lo, state.g.a());
    hi = std::max(hi, state.g.b());
    longest = std::max(longest, state.g.length());
  }
  if (!(longest > 0)) longest = hi - lo > 0 ? hi - lo : 1.0;
  std::vector<double> xs = even_grid(lo - longest, hi + longest, cx.options.grid_points * st.size());
  out.surface = heights.absolute(xs);
  for (double& x : xs) x += origin;
  out.surface_x = std::move(xs);
}

scene_result report_scene(const scene& s, const scene_states& ss, const context& cx, const coupled_outcome& coupled) {
  const auto& st = ss.st;
  const bool isolated = st.size() == 1;
  scene_result out;
  out.beta = cx.beta;
  out.kappa = cx.kappa;
  out.regime = regime(s.material);
  out.indentors.resize(st.size());
  double worst_residual = 0;
  const surface heights(st, cx);
  const auto gaps = isolated ? std::vector<std::pair<double, double>>(1, {0.0, 0.0}) : worst_gaps(heights, st);
  for (std::size_t i = 0; i < st.size(); ++i) {
    indentor_result r = report_contact(st, i, cx, heights, s.material.coulomb, gaps[i], ss.origin);
    if (!isolated || s.body) r.approach = heights.approach(i);
    if (!cx.options.residual) worst_residual = r.residual;
    else if (!std::isnan(worst_residual)) worst_residual = std::max(worst_residual, r.residual);
    shift(r, ss.origin);
    out.indentors[st[i].scene_index] = std::move(r);
  }
  if (!isolated && cx.options.grid_points > 0 && cx.options.displacement) report_surface(st, heights, cx, ss.origin, out);
  out.diagnostics.residual = worst_residual;
  out.diagnostics.code = coupled.code;
  out.diagnostics.status = coupled.code == status_code::ok ? "ok" : coupled.message;
  out.diagnostics.iterations = coupled.iterations;
  if (out.diagnostics.code == status_code::ok)
    for (const auto& r : out.indentors)
      if (r.code != status_code::ok) {
        out.diagnostics.code = r.code;
        out.diagnostics.status = contacts_not_ok(out.indentors, "indentors");
        break;
      }
  if (s.body) report_body(s, st, cx, out);
  return out;
}

std::string contacts_not_ok(const std::vector<indentor_result>& results, const char* noun) {
  constexpr std::size_t listed = 8;
  std::vector<std::size_t> bad;
  for (std::size_t i = 0; i < results.size(); ++i)
    if (results[i].code != status_code::ok) bad.push_back(i);
  if (bad.empty()) return {};
  std::string out = std::string("see ") + noun + "[" + std::to_string(bad[0]) + "].status: " + results[bad[0]].status;
  if (bad.size() > 1) {
    out += "; " + std::to_string(bad.size()) + " of " + std::to_string(results.size()) + " " + noun + " are not ok: ";
    for (std::size_t k = 0; k < std::min(bad.size(), listed); ++k) out += (k ? ", " : "") + std::to_string(bad[k]);
    if (bad.size() > listed) out += ", ...";
  }
  return out;
}

void validate_options(const solve_options& options, const char* function) {
  if (!(options.tolerance > 0) || !(options.tolerance < 1))
    throw std::invalid_argument(std::string(function) + ": options.tolerance must be in (0, 1)");
  if (options.threads > 1024)
    throw std::invalid_argument(std::string(function) + ": options.threads = " + std::to_string(options.threads) +
                                " must be at most 1024 (0: every core)");
  if (!(options.time_limit >= 0) || !std::isfinite(options.time_limit))
    throw std::invalid_argument(std::string(function) + ": options.time_limit must be finite and >= 0 (0: no limit)");
  if (!(options.layered_below >= 0) || !std::isfinite(options.layered_below))
    throw std::invalid_argument(std::string(function) + ": options.layered_below must be finite and >= 0 (0: never)");
}

}  // namespace detail

scene_result solve(const scene& s, const solve_options& options) {
  const auto start = std::chrono::steady_clock::now();
  validate(s);
  validate_body(s);
  validate_options(options, "rhabel::punch::solve");
  const context cx = make_context(s.material, s.speed, options);
  scene_states states = prepare_states(s, cx);
  const coupled_outcome coupled = solve_states(s, states, cx);
  cx.throw_if_interrupted("rhabel::punch::solve");
  scene_result out = report_scene(s, states, cx, coupled);
  out.diagnostics.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rhabel::punch
