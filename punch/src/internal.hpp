// punch/src/internal.hpp: what the punch layer's source files share (not installed).
//
//   material.cpp       the material (beta, kappa, E_U, regime) and the solve context;
//   shapes.cpp         the shapes and their forcing F = f'/Gamma(1 - alpha), its projection on
//                      the image basis (steps in closed form);
//   single_contact.cpp one contact alone: the density builders (Jacobi series, the wedge's apex
//                      enrichment, the near-edge split form), edge conditions and root finding;
//   coupled_*.cpp      several contacts at once (paper system 41), by stage around the shared
//                      state of coupled_problem.hpp: coupled_fixed.cpp the linear solve on the
//                      union of the contact intervals for given edges, coupled_newton.cpp Newton-
//                      Broyden on all edge conditions, coupled_solve.cpp the starts
//                      (continuations in the load, the heights, the loads' ratio and the offset
//                      from seeds, and the coarse solve of all indentors at once of
//                      coarse_bodies.cpp) and the result;
//   fields.cpp         edge intensities, peak, Riemann-Hilbert samples, the displacement kernel;
//   surface.hpp        the surface displacement (displacement grid, penetration check);
//   report.cpp         the report of a solved contact: residual of (8), status, sampled fields;
//   contact.cpp        the public entry points (solve, solve_single, trial_interval), validation;
//   contact_set.cpp    a sampled profile on one rigid body (solve_profile): the search for its
//                      contact set, started from coarse_contact.hpp's boundary-element solve, on
//                      the spline and bumps of profile_curve.hpp;
//   panel_grid.cpp     the boundary-element discretisation of a profile (finite: Toeplitz;
//                      periodic: the regularised circulant) and its active set, shared by
//                      coarse_contact.cpp and profile_bem.cpp (and its finite kernel by
//                      coarse_bodies.cpp: several independent indentors on one grid);
//   periodic_profile.cpp a periodic profile by the spectral search (solve_profile with a
//                      period): one period as a finite window (contact_set.cpp's search_window,
//                      profile_search.hpp) with the other periods' displacement of
//                      periodic_images.cpp, by fixed-point passes;
//   profile_bem.cpp    a sampled profile by the boundary-element method (solve_profile_bem):
//                      grids refined until the extrapolated loads and C_f meet the acceptance.
// A new shape: its forcing in shapes.cpp (own_slope, own_forcing), its isolated contact in
// single_contact.cpp (solve_isolated), its role in the coupled system in coupled_problem.hpp
// (role_of), its profile in surface.hpp. A new edge condition: coupled_newton.cpp (evaluate).
#pragma once

#include "rhabel/punch/contact.hpp"
#include "rhabel/punch/detail/contact_density.hpp"
#include "rhabel/riemann/abel_solver.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rhabel::punch::detail {

constexpr double pi = boost::math::constants::pi<double>();
constexpr double boundary_width = 1e-12;  // |alpha + beta/2 - 1/2| below this is "boundary"
constexpr double alpha_zero = 1e-300;     // material.alpha below this is solved as alpha = 0
// Wedge below the boundary, apex at distance min(eps, 1 - eps) L from an edge. The isolated wedge
// with the apex in an outer quarter (min(eps, 1 - eps) < 1/4) is solved in the split form of
// build_wedge_near_edge (the long side's constant in closed form plus the short side's step with
// the apex mapped to the centre): 66 points from 1/4 down to 1 - eps = 1e-14, C_f and pressure
// within 2e-14 of the Riemann-Hilbert route and of the elastic closed form (study_wedge_near_edge),
// 0.35-0.58 ms without the residual. A coupled wedge keeps abel::solve_step's balanced map
// (converges at 65 points down to ~1e-2, 195 down to 1e-3, 585 down to 1e-4) and, within
// enrich_limit, the plain Jacobi series for everything (pressure unresolved next to the apex; C_f
// by Richardson extrapolation of the series). With options.wedge_apex_split off, the isolated
// wedge takes C_f and the pressure samples from the Riemann-Hilbert route (wedge_by_rh,
// rh_pressure: 3.5-3.6 ms) and the plain series the residual and the displacement.
constexpr double enrich_limit = 1e-4;

/// Edge classes of the index nu used by punch: -1 (bounded, bounded), 0 (bounded, unbounded),
/// +1 (unbounded, unbounded).
inline abel::edge leading_edge(int nu) { return nu == 1 ? abel::edge::unbounded : abel::edge::bounded; }
inline abel::edge trailing_edge(int nu) { return nu == -1 ? abel::edge::bounded : abel::edge::unbounded; }

enum class kind { parabola, wedge, flat, general };

/// One indentor inside a scene: its shape, its own F and the solved density.
struct indentor_state {
  kind k = kind::parabola;
  const indentor* source = nullptr;
  std::size_t scene_index = 0;  // position in scene::indentors
  double apex = 0;
  double target_load = 0;  // in units of int g (the load divided by (pi/2) E_U)
  double height = 0;       // scene::body: the apex's height on the body [m]
  // The edges (in the states' frame) a coupled solve starts from instead of the isolated contact
  // (general profiles only): the first round of a sampled profile's contact search, seeded by its
  // coarse boundary-element solve (contact_set.cpp).
  std::optional<std::pair<double, double>> seed;
  // A cap on the degree of this contact's own series below solve_options::max_degree (0: none):
  // a sampled profile's contact that met the acceptance at a lower degree, searched again at a
  // higher one for others (contact_set.cpp, raise_degree).
  std::size_t degree_cap = 0;
  // With seed on a rigid body: target_load is the seed's own load (a coarse solve's or a solved
  // round's, not a guess), which coupled_solve.cpp's loads-imposed start may impose.
  bool seed_load = false;
  // With seed on a rigid body: the coupled iteration drops this contact for starving only from
  // a point near the solution (coupled_newton.cpp, trusted_residual); set by a sampled profile's
  // search that spares light contacts (contact_set.cpp, search_start::spare).
  bool spare_light = false;
  contact_density g;
  // A coupled solve in the boundary-layer basis: g as solved, series and poles, before
  // absorb_layer made g one Jacobi series (whose distance from this is in g.tail). The report's
  // residual of (8) is evaluated on this (report.cpp).
  std::optional<contact_density> solved;
  std::string status = "ok";
  status_code code = status_code::ok;
  std::optional<double> epsilon;
  std::optional<double> friction;  // C_f when it does not come from g (wedge, apex next to an edge)
  double friction_error = 0;       // its error estimate
  // Isolated wedge with the apex within enrich_limit L of an edge: its Riemann-Hilbert solution on
  // the unit interval, the source of the pressure samples (see wedge_by_rh).
  std::shared_ptr<const riemann::abel_rh_solution<double>> rh_unit;
  double rh_one_minus_eps = 0;  // its interval is [-eps, rh_one_minus_eps]
};

/// Thrown by context::check_time from inside a solve's inner loops when solve_options::time_limit
/// has run out. The loops that own a state to report (the Newton iteration of a coupled solve, the
/// contact search of a sampled profile) catch it and report that state as not_converged; it never
/// leaves the library. Not a std::domain_error, so the handlers of a contact's own failures (which
/// try other forms or shorter steps) let it through.
struct time_limit_reached : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct context {
  double alpha = 0, beta = 0, kappa = 0, offset = 0;
  double gamma_factor = 1;  // Gamma(1 - alpha)
  double pressure_scale = 1;  // (pi/2) E_U
  solve_options options;
  /// When options.time_limit > 0: the moment it runs out (make_context is called at the start of
  /// a solve); time_point::max() otherwise.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  // The operator's parameters for rhabel::abel; on the boundary (kappa = 0 above) kappa is exactly 0.
  abel::abel_parameters<double> par{0.0, 0.0};
  /// Set for a sampled profile's search at a higher degree from the contacts of the search before
  /// (contact_set.cpp, raise_degree): its rounds polish a settled set, to ladder_accuracy
  /// (coupled_solve.cpp) instead of seeded_accuracy.
  bool ladder = false;

  void set_parameters() {
    par = abel::abel_parameters<double>(alpha, beta);
    if (kappa == 0 && par.kappa() != 0) par = abel::abel_parameters<double>::from_kappa(alpha, 0.0);
  }
  /// Set once options.interrupt has returned true (shared by the copies of the context).
  std::shared_ptr<std::atomic<bool>> interrupted = std::make_shared<std::atomic<bool>>(false);
  /// Whether options.time_limit has run out or the solve was interrupted.
  bool out_of_time() const { return *interrupted || seconds_left() <= 0; }
  /// Seconds until the deadline (negative past it; infinity without a time limit).
  double seconds_left() const {
    if (deadline == std::chrono::steady_clock::time_point::max()) return std::numeric_limits<double>::infinity();
    return std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
  }
  /// Polls options.interrupt (unless it has fired already); whether the solve is interrupted.
  bool poll_interrupt() const {
    if (!*interrupted && options.interrupt && options.interrupt()) *interrupted = true;
    return *interrupted;
  }
  /// Throws punch::interrupted when options.interrupt has stopped the solve (before a report; with
  /// poll, options.interrupt is polled first: between long steps that check nothing inside).
  void throw_if_interrupted(const char* function, bool poll = false) const {
    if (poll ? poll_interrupt() : static_cast<bool>(*interrupted))
      throw punch::interrupted(std::string(function) + ": " + time_limit_message());
  }
  /// The failure text of a solve stopped by options.time_limit (or by options.interrupt).
  std::string time_limit_message() const;
  /// Throws time_limit_reached when options.time_limit has run out or options.interrupt returns
  /// true (polled here). Called at every evaluation of
  /// a coupled solve and every step of the coarse contact search, so that a solve ends within one
  /// evaluation of the limit (solve_options::time_limit).
  void check_time() const;
  /// Edge exponents of the class of index nu (see leading_edge, trailing_edge).
  edge_exponents exponents(int nu) const { return par.exponents(leading_edge(nu), trailing_edge(nu)); }
};

context make_context(const material& m, double speed, const solve_options& options);

/// Image coefficients of F in the image basis of the class e on [a, b] (contact.cpp).
struct image_expansion {
  std::vector<double> d;
  double tail = 0;
};
image_expansion image_coefficients(double a, double b, const edge_exponents& e, const forcing& F, std::size_t M);
contact_density density_from_image(double a, double b, const abel::abel_parameters<double>& par, const edge_exponents& e,
                                   const image_expansion& img);

/// f'(s) of the indentor at absolute s.
double own_slope(const indentor_state& st, double s);
/// max |f'| on [a, b] at 9 equally spaced points (0 for a flat face): the scale of a contact's data.
double max_slope(const indentor_state& st, double a, double b);
/// F = f'/Gamma(1 - alpha) of the own profile (smooth part + steps).
forcing own_forcing(const indentor_state& st, const context& cx);
/// Options and tail rule of the wedge's abel::solve_step calls.
abel::solve_options<double> step_options(const context& cx);
double step_tail(const abel::enriched_solution<double>& sol, const context& cx);
/// Wedge density on [a, b] with the apex enrichment (abel::solve_step); `defect` (if given)
/// receives solve_step's solvability defect (nu = -1: A g = F - (L/2)^alpha defect).
contact_density build_wedge_step(double a, double b, double apex, int nu, const context& cx, const forcing& F,
                                 double* defect = nullptr);
/// Wedge below the boundary on [-eps, 1 - eps] (apex at 0, L = 1) in the split form: the long
/// side's constant in closed form plus the short side's step (abel::apex_placement::centred), both
/// in the class nu = 0 singular at the near edge (near > 0: trailing, < 0: leading, 0: the nearer
/// of the two); g.physical = the bounded class. Their singular parts cancel iff eps solves the
/// orthogonality condition (the isolated wedge); otherwise g is the nu = 0 solution of the data.
contact_density build_wedge_near_edge(double eps, double one_minus_eps, const context& cx, double f_leading,
                                      double f_trailing, int near = 0);
/// A g (s) for s outside the support of g (abel_operator::apply plus the apex part).
double apply_outside(const contact_density& g, double s, const abel::abel_parameters<double>& par);
/// The isolated contact of one indentor (no other present): fills st.g, st.epsilon, st.status.
void solve_isolated(indentor_state& st, const context& cx);
/// "indentors[i] (shape)".
std::string indentor_name(std::size_t i, const indentor& ind);

// ---- material.cpp
double material_beta(const material& m);
double material_kappa(const material& m);
double regime_offset(const material& m);  ///< alpha + beta/2 - 1/2

// ---- shapes.cpp
/// Position s of [a, b] -> (x, 1 + x, 1 - x) with both distances computed directly.
struct mapped {
  double x, one_plus, one_minus;
};
mapped map_to_reference(double s, double a, double b);
/// C_f = int f' g / int g for a density without apex part (split at a general profile's corners).
double mean_slope(const indentor_state& st, const contact_density& g);

// ---- single_contact.cpp
/// C_f of a wedge: (S1 int_a^apex g - S2 int_apex^b g) / int g, the smaller share integrated directly.
double wedge_friction(const contact_density& g, const wedge& w, double apex);
/// The density on [a, b] of the class e for the forcing F (adaptive when `adaptive`).
contact_density build(double a, double b, const context& cx, const edge_exponents& e, const forcing& F, bool adaptive);

/// An isolated wedge whose pressure comes from its Riemann-Hilbert solution g_1 on the unit
/// interval [-eps, one_minus_eps] (apex at 0): p(t) = scale g_1((t - apex)/L).
struct rh_wedge {
  std::shared_ptr<const riemann::abel_rh_solution<double>> unit;
  double eps = 0, one_minus_eps = 0, apex = 0, scale = 0;
};

}  // namespace rhabel::punch::detail

namespace rhabel::punch {
/// What a pressure_field evaluates: the contact's density and the scale that makes it a pressure.
struct pressure_field::source {
  detail::contact_density g;          ///< in the solve's coordinates
  double scale = 0;                   ///< p = scale g
  std::optional<detail::rh_wedge> rh;  ///< the Riemann-Hilbert route, when the report samples by it
};
}  // namespace rhabel::punch

namespace rhabel::punch::detail {

// ---- fields.cpp
/// K = lim g / distance^exponent at an edge (Richardson estimate next to a split wedge's apex).
double edge_intensity(const contact_density& g, bool trailing);
/// Peak of a bounded density and where: sampling + Brent.
std::pair<double, double> peak_of(const contact_density& g);
/// n pressure abscissae strictly inside (a, b), increasing (sample_spacing).
std::vector<double> pressure_grid(double a, double b, std::size_t n, sample_spacing spacing);
/// n equally spaced abscissae from lo to hi, both included (n = 1: the midpoint); the
/// displacement grids.
std::vector<double> even_grid(double lo, double hi, std::size_t n);
/// p at the abscissae t (the solve's coordinates) into p: the density times its scale, 0 outside
/// (a, b). Returns the error estimate of the Riemann-Hilbert values relative to the peak (0 when
/// the density is a series).
double sample_pressure(const pressure_field::source& field, const std::vector<double>& t, std::vector<double>& p);
/// The surface displacement's kernel Psi(t, s) (closed-form integral in s of (8)'s kernel).
double psi(double t, double s, double alpha, double one_minus_kappa_over_alpha, double kappa);
double psi_distance(double d, double alpha, double one_minus_kappa_over_alpha, double kappa);
/// One tanh-sinh rule per thread.
boost::math::quadrature::tanh_sinh<double>& tanh_sinh_rule();

// ---- report.cpp
class surface;
/// Moves a result computed relative to `origin` (solve's first apex) back to absolute abscissae.
void shift(indentor_result& r, double origin);
/// The 64 interior points (Chebyshev points of the first kind on [a, b], in the order of x) at
/// which the sign of a contact's pressure is probed (the report's judge; the profile search's
/// repair of a contact with tension).
std::vector<double> pressure_probes(const contact_density& g);
/// The worst gap of each contact between the surface and its profile next to its edges,
/// relative to the profile's span, and where (report.cpp; {0, 0} for flat punches and line loads).
std::vector<std::pair<double, double>> worst_gaps(const surface& heights, const std::vector<indentor_state>& st);
/// The result of contact i with its evidence and status; `gap`: its entry of worst_gaps when
/// other indentors are present, else {0, 0}; `origin`: where the solve's x = 0 lies (its
/// pressure_at takes absolute abscissae).
indentor_result report_contact(const std::vector<indentor_state>& st, std::size_t i, const context& cx,
                               const surface& heights, double coulomb, std::pair<double, double> gap, double origin);

// ---- coupled_solve.cpp (with coupled_fixed.cpp, coupled_newton.cpp)
/// Outcome of the coupled solve (coupled_solve.cpp).
struct coupled_outcome {
  status_code code = status_code::ok;
  std::string message;      // empty when ok
  std::size_t iterations = 0;
  std::size_t jacobians = 0;     // finite-difference Jacobians the iterations took
  std::size_t union_degree = 0;  // the most collocation points of a contact in the last linear solve
  std::optional<std::size_t> lost;  // contact_lost: the st index of the indentor named
  std::optional<std::pair<std::size_t, std::size_t>> merged;  // contacts_merge: the two st indices
};

namespace coupled {
struct jacobian_memo;
}

/// Solves several indentors together (paper system 41): fills every st[i].g (and epsilon for
/// wedges). st in any order; the contacts' order along x is found, not assumed.
/// body_load (in units of int g): all indentors on one rigid body with this total load; their
/// target_load is then only the starting split, and is set to the solved load on return.
/// memo (a rigid body; null: none): the last Jacobian of the edge conditions, read when it was
/// taken at nearly these contacts and replaced by each new one (coupled_problem.hpp).
coupled_outcome solve_coupled(std::vector<indentor_state>& st, const context& cx,
                              std::optional<double> body_load = std::nullopt,
                              std::shared_ptr<coupled::jacobian_memo> memo = nullptr);

// ---- contact.cpp
/// A scene's indentors as the solver holds them: sorted by apex, abscissae relative to `origin`
/// (the first apex; the report shifts them back). st[i].source points into the scene, which
/// must outlive the states.
struct scene_states {
  std::vector<indentor_state> st;
  double origin = 0;
  // solve_coupled's memo (a sampled profile's rounds share one: contact_set.cpp); null: none.
  std::shared_ptr<coupled::jacobian_memo> jacobian;
};
/// The states of a validated scene (equal load shares on a rigid body: the start).
scene_states prepare_states(const scene& s, const context& cx);
/// One contact alone (solve_isolated) or several coupled (solve_coupled).
coupled_outcome solve_states(const scene& s, scene_states& ss, const context& cx);
/// The scene's result with every contact's evidence (report_contact, report_body).
scene_result report_scene(const scene& s, const scene_states& ss, const context& cx, const coupled_outcome& coupled);
/// The status of a result whose coupled solve converged but some contacts are not ok: the first
/// one's status and the count with their indices (at most 8), `noun` naming the list ("indentors",
/// "contacts"), e.g. "see contacts[44].status: residual of (8) 1.27e-06 > acceptance 1e-06; 8 of
/// 435 contacts are not ok: 44, 47, 190, 248, 304, 374, 399, 425". Empty when all are ok.
std::string contacts_not_ok(const std::vector<indentor_result>& results, const char* noun);
/// The material's fields and the speed (std::invalid_argument naming the field, from `function`).
void validate_material(const material& m, double speed, const char* function);
/// options.tolerance in (0, 1), else std::invalid_argument naming `function`.
void validate_options(const solve_options& options, const char* function);

}  // namespace rhabel::punch::detail
