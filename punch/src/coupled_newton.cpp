// punch/src/coupled_newton.cpp: the coupled solve's Newton-Broyden iteration on the edge
// conditions (newton; coupled_problem.hpp; the mathematics: "THE EDGES" and "A RIGID BODY" at the
// top of coupled_solve.cpp).
#include "coupled_problem.hpp"
#include "newton_krylov.hpp"
#include "parallel.hpp"
#include "surface.hpp"

#include "rhabel/abel/broyden_matrix.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace rhabel::punch::detail::coupled {

namespace {

struct unknowns {
  std::vector<std::size_t> state;  // which contact
  std::vector<bool> trailing;      // which edge
};

unknowns list_unknowns(const problem& pb) {
  unknowns u;
  for (std::size_t i = 0; i < pb.roles.size(); ++i) {
    if (pb.roles[i] == role::smooth_both) {
      u.state.push_back(i), u.trailing.push_back(false);
      u.state.push_back(i), u.trailing.push_back(true);
    } else if (pb.roles[i] == role::apex_ended) {
      u.state.push_back(i), u.trailing.push_back(false);
    }
  }
  return u;
}

struct evaluation {
  fixed_solution sol;
  Eigen::VectorXd r;
};

}  // namespace

/// scene::body: the level of every contact, approach_i + height_i (surface::approach: w - f_i on
/// the contact, w from the kernel Psi), which must be the same for all indentors.
std::vector<double> body_levels(const std::vector<indentor_state>& states, const std::vector<contact_density>& g,
                                const context& cx, double height_factor) {
  std::vector<indentor_state> tmp = states;
  for (std::size_t i = 0; i < tmp.size(); ++i) {
    tmp[i].g = g[i];
    tmp[i].g.absorb_layer(cx.options.tolerance);  // surface.hpp sees series and apex only
  }
  const surface w(tmp, cx);
  std::vector<double> level(tmp.size());
  for (std::size_t i = 0; i < tmp.size(); ++i) level[i] = w.approach(i) + height_factor * tmp[i].height;
  return level;
}

namespace {

/// The unit of a body's level row i > 0: Gamma times the larger max|f'| L of contacts i and i - 1
/// (the size of a contact's own displacement).
double level_row_scale(const problem& pb, std::size_t i, const std::vector<double>& a, const std::vector<double>& b) {
  const auto& st = *pb.st;
  const auto& cx = *pb.cx;
  const double scale = cx.gamma_factor * std::max(data_scale(st[i], cx, a[i], b[i]) * (b[i] - a[i]),
                                                  data_scale(st[i - 1], cx, a[i - 1], b[i - 1]) * (b[i - 1] - a[i - 1]));
  return std::max(scale, std::numeric_limits<double>::min());
}

/// scene::body: the second condition of every contact (the one a per-indentor load would fill):
/// contact 0 the total load, sum int g_j / body_load - 1; contact i > 0 its level against contact
/// i - 1's, in units of level_row_scale.
std::vector<double> body_conditions(const problem& pb, const fixed_solution& sol, const std::vector<double>& a,
                                    const std::vector<double>& b) {
  const auto& st = *pb.st;
  const std::vector<double> level = body_levels(st, sol.g, *pb.cx, pb.height_factor);
  std::vector<double> r(st.size());
  double total = 0;
  for (const auto& g : sol.g) total += g.integral();
  r[0] = total / (pb.load_factor * *pb.body_load) - 1;
  for (std::size_t i = 1; i < st.size(); ++i) r[i] = (level[i] - level[i - 1]) / level_row_scale(pb, i, a, b);
  return r;
}

/// Intensity factor of g at one edge (series and apex part) as K L^exponent relative to the mean
/// density load/L: the condition of an edge that must be smooth in a class singular there.
double relative_intensity(const contact_density& g, bool trailing, double load) {
  const double L = g.length();
  const double K = g.intensity(trailing);
  return K * std::pow(L, trailing ? g.jacobi.del : g.jacobi.gam) / (load / L);
}

/// The conditions, in the order of the unknowns. A smooth contact: h^alpha d_j / data scale (or,
/// in the split form, the relative intensity at the near edge) and load/P - 1; with the load
/// imposed, the relative intensities at both edges; on a rigid body, its second condition is
/// body_conditions'. A wedge ending at its apex: load/P - 1 (on a body: body_conditions').
evaluation evaluate(const problem& pb, const unknowns& u, const std::vector<double>& a, const std::vector<double>& b) {
  pb.cx->check_time();  // every evaluation: the Jacobian's columns, the line search, the sharpening
  evaluation ev{solve_fixed(pb, a, b), Eigen::VectorXd(static_cast<Eigen::Index>(u.state.size()))};
  const auto& st = *pb.st;
  const auto& cx = *pb.cx;
  const std::vector<double> body_rows = pb.body_load ? body_conditions(pb, ev.sol, a, b) : std::vector<double>{};
  for (std::size_t k = 0; k < u.state.size(); ++k) {
    const std::size_t i = u.state[k];
    const double load = ev.sol.g[i].integral() / (pb.load(i)) - 1;
    if (pb.body_load && (u.trailing[k] || pb.roles[i] == role::apex_ended)) {
      ev.r[static_cast<Eigen::Index>(k)] = body_rows[i];
    } else if (is_loaded(pb, i)) {  // load imposed: both intensities vanish
      ev.r[static_cast<Eigen::Index>(k)] = relative_intensity(ev.sol.g[i], u.trailing[k], pb.load(i));
    } else if (pb.roles[i] == role::smooth_both && !u.trailing[k] && pb.split[i] != 0) {  // split: the near edge's
      ev.r[static_cast<Eigen::Index>(k)] = relative_intensity(ev.sol.g[i], pb.split[i] > 0, pb.load(i));
    } else if (pb.roles[i] == role::smooth_both && !u.trailing[k]) {
      const double scale = std::max(data_scale(st[i], cx, a[i], b[i]), std::numeric_limits<double>::min());
      ev.r[static_cast<Eigen::Index>(k)] = std::pow((b[i] - a[i]) / 2, cx.alpha) * ev.sol.defect[i] / scale;
    } else {
      ev.r[static_cast<Eigen::Index>(k)] = load;
    }
  }
  if (pb.offset.size() == ev.r.size()) ev.r -= pb.offset;
  return ev;
}

/// What condition k of evaluate is, naming its indentor: for a message about the largest one.
std::string condition_name(const problem& pb, const unknowns& u, std::size_t k) {
  const std::size_t i = u.state[k];
  const std::string name = indentor_name((*pb.st)[i].scene_index, *(*pb.st)[i].source);
  if (pb.body_load && (u.trailing[k] || pb.roles[i] == role::apex_ended))
    return i == 0 ? "the body's total load" : "the level of " + name + " against its neighbour's";
  if (is_loaded(pb, i) || (pb.roles[i] == role::smooth_both && !u.trailing[k] && pb.split[i] != 0))
    return "the intensity at an edge of " + name;
  if (pb.roles[i] == role::smooth_both && !u.trailing[k]) return "the smoothness of the edges of " + name;
  return "the load of " + name;
}

edges moved(const problem& pb, const unknowns& u, const edges& x, const Eigen::VectorXd& dx) {
  edges y = x;
  for (std::size_t k = 0; k < u.state.size(); ++k) {
    const std::size_t i = u.state[k];
    (u.trailing[k] ? y.b[i] : y.a[i]) += dx[static_cast<Eigen::Index>(k)];
  }
  for (std::size_t i = 0; i < pb.roles.size(); ++i)
    if (pb.roles[i] == role::apex_ended) y.b[i] = (*pb.st)[i].apex;
  return y;
}

/// Smallest gap the coupled solve resolves, relative to the smaller of the two contacts. The
/// boundary-layer route (solve_options::layered_below) solves the coupling at any gap in
/// log(L/gap) unknowns, and the report's residual is evaluated on the densities as solved; what
/// grows is the reported density, one Jacobi series (contact_density::absorb_layer) of degree
/// ~ 15 sqrt(L/gap), projected and used by the fields in O(degree^2): ~1e4 at 1e-6 L, where its
/// measured projection error is ~3e-12 of the density. Two elastic parabolas (alpha 0, R 1,
/// load_g 0.3 each, throwaway driver): gaps 8.2e-6 / 3.0e-6 / 1.7e-6 L ok in 0.9 / 1.7 / 2.2 s;
/// apexes 0.23 apart, a gap closing below this limit, contacts_merge in 2.6 s. A Newton step that
/// would close a gap narrower than this ends the iteration (contacts_merge when the full step
/// closes it, else not_converged): contacts are not merged into one.
constexpr double resolved_gap = 1e-6;

/// Seeded contacts (problem::seeded, a sampled profile's): a gap narrower than this fraction of the
/// smaller contact that a step narrows ends the iteration as a merge (contacts_merge); the profile
/// search then solves the two as one contact, and splits it again where its pressure is negative
/// (contact_set.cpp, repair_tension). WHY: a pair's coupling degree grows like sqrt(L/gap); a
/// 1e5-sample periodic profile whose two contacts (of 233) closed in to 1e-5 .. 3e-6 L took it
/// from 243 to 465 points (then for every contact: 15 s an evaluation, 150 s a Jacobian; each
/// contact has its own degree since), while the iteration still could not resolve the gap
/// (traced in a scratch build). Not 1e-3: a pair of a 16000-sample periodic profile (seed 3, load 3e-3) closing to
/// 6e-4 L is two contacts, and merged there the search split it again for its negative pressure
/// (two more rounds: 27 s against 19 s).
constexpr double seeded_merge_gap = 1e-4;

/// The gap below which a narrowing pair ends the iteration (see above).
double merge_gap(const problem& pb) { return pb.seeded ? seeded_merge_gap : resolved_gap; }

/// Two neighbours whose gap the step (x + dx) would close while it is already below merge_gap.
struct closing_gap {
  std::size_t first, second;
  double gap_ratio;
  bool closes;  // the full step makes the gap negative
};

/// Largest t in (0, 1] such that x + t dx keeps every contact at least half as long and every gap
/// at least a fifth as wide as now (the contacts' order is kept); `closing` reports a gap below
/// merge_gap that the step narrows.
double step_limit(const problem& pb, const unknowns& u, const edges& x, const Eigen::VectorXd& dx,
                  std::optional<closing_gap>& closing) {
  const std::size_t n = pb.roles.size();
  std::vector<double> da(n, 0.0), db(n, 0.0);
  for (std::size_t k = 0; k < u.state.size(); ++k)
    (u.trailing[k] ? db : da)[u.state[k]] = dx[static_cast<Eigen::Index>(k)];
  double t = 1;
  for (std::size_t i = 0; i < n; ++i) {
    const double L = x.b[i] - x.a[i], dL = db[i] - da[i];
    if (dL < 0 && L > 0) t = std::min(t, 0.5 * L / -dL);
  }
  for (const auto& [i, j, gap, L] : neighbour_pairs(x.a, x.b)) {
    const double dgap = da[j] - db[i];
    if (dgap < 0 && gap > 0) t = std::min(t, 0.8 * gap / -dgap);
    if (dgap < 0 && gap < merge_gap(pb) * L) closing = closing_gap{i, j, gap / L, gap + dgap <= 0};
  }
  return t;
}

/// "the contacts of X and Y are r of a contact length apart and still closing" + what follows.
std::string closing_message(const problem& pb, const closing_gap& c, const std::string& what_follows) {
  const auto& st = *pb.st;
  std::ostringstream os;
  os.precision(3);
  os << "the contacts of " << indentor_name(st[c.first].scene_index, *st[c.first].source) << " and "
     << indentor_name(st[c.second].scene_index, *st[c.second].source) << " are " << c.gap_ratio
     << " of a contact length apart and still closing" << what_follows;
  return os.str();
}

/// scene::body: a contact shorter than this fraction of its isolated length (at an equal share of
/// the load) is taken as vanishing: its indentor would carry no load.
constexpr double vanishing_length = 1e-3;

/// Seeded contacts (problem::seeded) on a rigid body: a contact carrying less than this fraction
/// of the mean load that the full Newton step would shrink past zero length vanishes at once (not
/// only below vanishing_length). WHY: step_limit halves such a contact at every step while its
/// condition, relative to its own load, stays where it was, and the iteration stalls before it is
/// short enough (1e5-sample periodic profile, 233 contacts: a seed of one coarse panel, 1.9e-6
/// long, halved 7 times in 7 steps at the largest condition 240 while its load fell from 0.1 to
/// 3e-5 of the mean; then a new Jacobian grew it back). The profile search drops it and adds it
/// back, once, if the surface penetrates there later. Not for other bodies: a body of three
/// parabolas whose light one is pushed past zero by a first step far from the solution carries
/// load at the solution (test_coupled.cpp).
constexpr double vanishing_share = 1e-2;

/// starved_contact drops a contact with indentor_state::spare_light only in a step from a point
/// whose largest edge condition is at most this (problem::starve_untrusted: from any). WHY: far
/// from the solution the full step is no forecast of where a light contact goes. 1e5-sample
/// periodic profile, seed 3, load 6e-3 (428 patches in the boundary-element oracle): its first
/// round dropped a contact whose coarse load was 1.3 % of the mean, at the largest condition 108;
/// added back where the profile penetrated, the search lost and regained contacts until its time
/// limit. With every contact kept at such conditions, it ends ok with the oracle's 428 patches.
/// Not for every search (contact_set.cpp, spare): the ~980-patch profile (seed 1, load 1.4e-2)
/// converges by dropping a coarse seed at the largest condition 125 in its first round.
constexpr double trusted_residual = 0.1;

/// The load below which a contact of `sol` starves: vanishing_share of the mean |load|.
double vanishing_load(const fixed_solution& sol) {
  double total = 0;
  for (const auto& g : sol.g) total += std::abs(g.integral());
  return vanishing_share * (total / double(sol.g.size()));
}

/// The contact that vanishing_share names (the least loaded one if several), if any; `largest`
/// is the largest edge condition at the step's start. A starving contact kept for
/// indentor_state::spare_light (trusted_residual) sets `spared`.
std::optional<std::size_t> starved_contact(const problem& pb, const unknowns& u, const edges& x,
                                           const Eigen::VectorXd& dx, const fixed_solution& sol, double largest,
                                           bool& spared) {
  if (!pb.body_load || !pb.seeded) return std::nullopt;
  const std::size_t n = pb.roles.size();
  std::vector<double> dL(n, 0.0);
  for (std::size_t k = 0; k < u.state.size(); ++k)
    dL[u.state[k]] += (u.trailing[k] ? 1.0 : -1.0) * dx[static_cast<Eigen::Index>(k)];
  const double starving = vanishing_load(sol);
  std::optional<std::size_t> out;
  for (std::size_t i = 0; i < n; ++i) {
    const double load = sol.g[i].integral();
    if (pb.roles[i] != role::smooth_both || x.b[i] - x.a[i] + dL[i] > 0 || !(load < starving)) continue;
    if ((*pb.st)[i].spare_light && !pb.starve_untrusted && !(largest <= trusted_residual)) {
      spared = true;
      continue;
    }
    if (!out || load < sol.g[*out].integral()) out = i;
  }
  return out;
}

/// Seeded contacts on a rigid body whose iteration stalled: the contact its largest condition
/// belongs to (for a level, the lighter of that contact and its neighbour) when it carries less
/// than vanishing_share of the mean load; it vanishes. WHY: a starving contact that no full step
/// shrinks past zero (starved_contact) keeps its level condition where it is while the others
/// converge (1e5-sample periodic profile, 443 contacts: stalled at a level condition 0.0066 on
/// a flank's contact 2.3e-7 long carrying 1e-3 of the mean load, beside one carrying 4e-3; the
/// profile search then spent its time limit at degree 512 from that set). Named, it is dropped
/// and added back once if the surface penetrates there (contact_set.cpp).
std::optional<std::size_t> stalled_on_starved(const problem& pb, const unknowns& u, const evaluation& ev) {
  if (!pb.body_load || !pb.seeded || ev.r.size() == 0 || ev.sol.g.size() != pb.roles.size()) return std::nullopt;
  Eigen::Index worst = 0;
  ev.r.cwiseAbs().maxCoeff(&worst);
  const std::size_t k = static_cast<std::size_t>(worst), i = u.state[k];
  std::size_t named = i;
  const bool level = u.trailing[k] && i > 0;  // the level of i against i - 1 (condition_name)
  if (level && ev.sol.g[i - 1].integral() < ev.sol.g[i].integral()) named = i - 1;
  if (pb.roles[named] != role::smooth_both || !(ev.sol.g[named].integral() < vanishing_load(ev.sol))) return std::nullopt;
  return named;
}

/// A FLAT RUN: accepted steps that each lower the largest edge condition by less than
/// flat_gain (the line search shortened them to almost nothing). After flat_steps of them a new
/// Jacobian is taken; flat_steps more end the iteration. WHY: the conditions have reached the
/// floor of what the evaluation resolves, and the sufficient-decrease test (1 - 1e-4 t) accepts
/// steps of t ~ 1e-5 for ever (measured: a 12-sample profile whose two contacts closed in on
/// each other at 0.009 of a contact length; 30 steps at the same condition, 6e-4, at 0.36 s
/// each, then the iteration limit).
constexpr double flat_gain = 0.99;

constexpr std::size_t flat_steps = 4;

/// stall_floor: a contact whose series stopped at max_degree resolves its edge conditions to about
/// its tail; a stall within capped_floor_factor of it is that floor (measured: stalls at 0.3-1.5 x
/// the largest tail). No floor above max_capped_floor: a set settled by edges resolved coarser
/// than that is no start for the next degree.
constexpr double capped_floor_factor = 10;
constexpr double max_capped_floor = 1e-3;

/// A flat run that ends with two neighbours closer than this fraction of the smaller contact,
/// their gap narrowing, is reported as those contacts merging (contacts_merge; the profile search
/// then solves them as one contact). WHY: a gap that the iteration keeps closing but cannot
/// resolve is the approach of a merge; a few percent of a length needs degree ~ 10 sqrt(L/gap).
constexpr double flat_merge_gap = 0.02;

/// The closest pair of neighbours in x (by gap relative to neighbour_pair::length) whose gap the move
/// from `before` to `after` narrowed, with that ratio at `after`; none when no gap narrowed.
std::optional<closing_gap> narrowing_pair(const edges& before, const edges& after) {
  std::optional<closing_gap> out;
  for (const auto& [i, j, gap, L] : neighbour_pairs(after.a, after.b)) {
    if (!(gap < before.a[j] - before.b[i])) continue;
    if (!out || gap / L < out->gap_ratio) out = closing_gap{i, j, gap / L, gap <= 0};
  }
  return out;
}

}  // namespace

/// scene::body in the bounded class with more than full_width contacts, all smooth both sides
/// (no wedge, no split form): the coloured Jacobian with the loads' far monopoles (body_far_model).
bool body_colouring(const problem& pb) {
  if (!pb.body_load || pb.full_jacobian || pb.roles.size() <= full_width) return false;
  for (std::size_t i = 0; i < pb.roles.size(); ++i)
    if (pb.roles[i] != role::smooth_both || pb.split[i] != 0 || is_loaded(pb, i)) return false;
  return true;
}

namespace {

/// A rigid body in the bounded class: moving an edge of contact i changes its load P_i, whose
/// action on every other contact is a monopole that hardly decays (the cross kernel ~ d^(alpha-1),
/// Psi ~ d^alpha). The banded (coloured) differences miss it, and Newton then stalls. This model
/// gives the conditions' response to one unit of load added to a far contact i, acting from its
/// centre c_i:
///   * the defect row of contact j: its data changes by -K(c_i - s) on I_j (K = cross_kernel), and
///     its solvability defect by ell_j of that, ell_j the defect functional of a contact alone
///     (abel::solve in the bounded class), applied to the Chebyshev interpolant on `points` points
///     (ell_j(T_k) once per contact); times the row's scale (L_j/2)^alpha / data scale;
///   * the level row of j > 0: Gamma (Psi(a_j - c_i) - Psi(a_(j-1) - c_i)) over the row's scale
///     (surface::approach takes the datum at the leading edge).
/// jacobian applies it to the load change of every contact not near the row's (the moved ones' and
/// those the coupling redistributes, measured in the difference), each owned by the moved contact
/// near it. WHY every contact: on a rough profile the redistribution among a cluster of contacts
/// is as large as the moved contact's own change, and with only the moved ones modelled the
/// coloured Newton stalled from the boundary-element seeds (4000-sample self-affine profile, 32
/// contacts: 0.116 from 1.39 after one step, then no descent; with every load change: 10 steps to
/// 3e-12). The dipoles and the action on the row's own distribution are left out (higher order
/// in L/d): Broyden's updates recover them.
class body_far_model {
 public:
  static constexpr std::size_t points = 8;

  body_far_model(const problem& pb, const edges& x) : pb_(&pb), x_(&x), grid_(points) {
    const auto& st = *pb.st;
    const auto& cx = *pb.cx;
    const std::size_t n = st.size();
    ell_.resize(n);
    defect_scale_.resize(n);
    level_scale_.assign(n, 0.0);
    for (std::size_t j = 0; j < n; ++j) {
      const double a = x.a[j], b = x.b[j];
      const abel::abel_operator<double> op(cx.par, a, b);
      abel::solve_options<double> o;
      o.residual_points = 0;
      o.tolerance = 1e-10;  // entries of a Jacobian: far more than Newton needs
      o.max_degree = 2 * points;
      for (std::size_t k = 0; k < points; ++k) {
        const auto sol = abel::solve(op, abel::edge::bounded, abel::edge::bounded, [&](double s) {
          return std::cos(static_cast<double>(k) * std::acos(std::clamp((2 * s - a - b) / (b - a), -1.0, 1.0)));
        }, o);
        ell_[j][k] = sol.solvability_defect;
      }
      defect_scale_[j] = std::pow((b - a) / 2, cx.alpha) / std::max(data_scale(st[j], cx, a, b), std::numeric_limits<double>::min());
      if (j > 0) level_scale_[j] = level_row_scale(pb, j, x.a, x.b);
    }
  }
  /// d(defect row of j)/d P_i.
  double defect_row(std::size_t j, std::size_t i) const {
    const auto& cx = *pb_->cx;
    const double a = x_->a[j], b = x_->b[j], c = (x_->a[i] + x_->b[i]) / 2;
    std::vector<double> values(points);
    for (std::size_t m = 0; m < points; ++m) {
      const double s = grid_.one_plus_x[m] <= grid_.one_minus_x[m] ? a + (b - a) / 2 * grid_.one_plus_x[m]
                                                                  : b - (b - a) / 2 * grid_.one_minus_x[m];
      values[m] = -abel::cross_kernel(cx.par, c - s);
    }
    const auto coefficients = abel::chebyshev_coefficients(values);
    double sum = 0;
    for (std::size_t k = 0; k < points; ++k) sum += coefficients[k] * ell_[j][k];
    return defect_scale_[j] * sum;
  }
  /// d(level row of j > 0)/d P_i (the datum of surface::approach at the leading edges).
  double level_row(std::size_t j, std::size_t i) const {
    const auto& cx = *pb_->cx;
    const double c = (x_->a[i] + x_->b[i]) / 2, omk = cx.par.one_minus_kappa_over_alpha();
    const double difference =
        psi_distance(x_->a[j] - c, cx.alpha, omk, cx.kappa) - psi_distance(x_->a[j - 1] - c, cx.alpha, omk, cx.kappa);
    return cx.gamma_factor * difference / level_scale_[j];
  }

 private:
  const problem* pb_;
  const edges* x_;
  abel::chebyshev_grid<double> grid_;
  std::vector<std::array<double, points>> ell_;
  std::vector<double> defect_scale_, level_scale_;
};

/// Contacts nearer than this many lengths of the larger one are differenced together in the
/// coloured Jacobian (a column's difference is attributed to them), whatever their ranks along x.
/// WHY: beyond the band of ranks, a row's entries are body_far_model's monopoles (or 0 without a
/// body), which are far off for a contact one or two lengths away, and the contacts of a rough
/// profile cluster (self-affine, 4000 samples, seed 1, load 2e-3: 32 contacts, lengths 5e-5 ..
/// 8e-4, several within 0.002 of one another). Measured on six periodic self-affine scenes of 32
/// to 85 contacts (4000 and 16000 samples, acceptance 1e-6): 79 s in all against 90 s with the
/// band alone or with 1 length (2.7 s against 9 s on the scene above, 46 s against 54 s at 85
/// contacts; 9.8 s against 6.1 s on one other). Without a body (no far model: the rest of a row is
/// 0, and Broyden's updates fill it) the band alone, as measured on rows of parabolas.
constexpr double near_lengths = 4;

/// The Jacobian's Curtis-Powell-Reid colouring: the contacts near each contact (within two ranks
/// along x or a few lengths), and a colour per contact such that no contact is near two contacts of
/// one colour: a row's difference then holds one near column of the colour.
class colouring {
 public:
  /// Every contact its own colour (all near one another) up to full_width contacts or when
  /// `dense`; else greedily in x order, contacts near within `lengths` of the longer one.
  colouring(const edges& x, bool dense, double lengths) : n_(x.a.size()), colour_(n_) {
    std::iota(colour_.begin(), colour_.end(), 0);
    if (n_ <= full_width || dense) {
      colours_ = n_;
      return;
    }
    std::vector<std::size_t> order(n_);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return x.a[i] < x.a[j]; });
    double longest = 0;
    for (std::size_t i = 0; i < n_; ++i) longest = std::max(longest, x.b[i] - x.a[i]);
    near_.assign(n_, {});
    for (std::size_t r = 0; r < n_; ++r) {
      const std::size_t i = order[r];
      // Outwards in rank: the gap to i only grows, and beyond `lengths` of the longest contact
      // nothing is near.
      for (std::size_t q = r + 1; q < n_; ++q) {
        const std::size_t k = order[q];
        const double gap = std::max(x.a[k] - x.b[i], 0.0);
        if (q - r > band && gap > lengths * longest) break;
        if (q - r <= band || gap <= lengths * std::max(x.b[i] - x.a[i], x.b[k] - x.a[k]))
          near_[i].push_back(k), near_[k].push_back(i);
      }
      near_[i].push_back(i);
    }
    for (auto& list : near_) std::sort(list.begin(), list.end());
    // Greedy: the smallest colour not taken by a contact that shares a near set with i (near is
    // symmetric: the sets holding i are those of i's near contacts).
    std::vector<std::size_t> stamp(n_ + 1, n_);
    std::vector<bool> coloured(n_, false);
    colours_ = 0;
    for (std::size_t r = 0; r < n_; ++r) {
      const std::size_t i = order[r];
      for (const std::size_t j : near_[i])
        for (const std::size_t k : near_[j])
          if (coloured[k]) stamp[colour_[k]] = i;
      std::size_t c = 0;
      while (stamp[c] == i) ++c;
      colour_[i] = c;
      colours_ = std::max(colours_, c + 1);
      coloured[i] = true;
    }
  }
  std::size_t colours() const { return colours_; }
  std::size_t colour(std::size_t i) const { return colour_[i]; }
  /// Whether contacts i and k are near (symmetric): i's conditions are differenced against k's
  /// column, and k owns i's load change in the column of k's colour.
  bool near(std::size_t i, std::size_t k) const {
    return near_.empty() || std::binary_search(near_[i].begin(), near_[i].end(), k);
  }

 private:
  static constexpr std::size_t band = full_width / 2;  // ranks each side always near
  std::size_t n_, colours_ = 0;
  std::vector<std::size_t> colour_;
  std::vector<std::vector<std::size_t>> near_;  // sorted, each holding its own contact; empty: all near
};

/// pb for the differences about the point solved as `sol`: its degrees, particulars' degrees and
/// route (problem::fixed_degrees), so that both sides of a difference share one discretisation.
problem at_base_discretisation(const problem& pb, const fixed_solution& sol) {
  problem out = pb;
  out.fixed_degrees = sol.degrees;
  out.fixed_particular_degrees = sol.particular_degrees;
  out.fixed_poles_per_decade = sol.poles_per_decade;
  return out;
}

/// Forward-difference Jacobian of the edge conditions (relative step 1e-7 of each contact's
/// length; backward where the forward step would close a gap). Up to `full_width` contacts: one
/// evaluation per unknown. More: the contacts are coloured (colouring: two ranks each side and, on
/// a rigid body, those within near_lengths are near), and the edges of one side of one colour are moved
/// together (Curtis-Powell-Reid): a condition of contact j is attributed to the moved contact near
/// j, the rest of its row is body_far_model's (a rigid body) or 0. That neglects the dependence on
/// farther contacts (the coupling decays like distance^(alpha - 1)): Broyden's updates recover it,
/// except where a row's unit is tiny (a light contact's level row, whose far entries were measured
/// off by up to a factor 3 and on which its steps stall, where escalate takes over: docs/theory.md
/// section 7, "Where this falls short"). 2 colours evaluations for any N: 2 full_width for rows of
/// contacts of similar lengths.
Eigen::MatrixXd jacobian(const problem& base, const unknowns& u, const edges& x, const evaluation& ev) {
  const problem pb = at_base_discretisation(base, ev.sol);
  const Eigen::VectorXd& r = ev.r;
  const auto m = static_cast<Eigen::Index>(u.state.size());
  const std::size_t n = pb.roles.size();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, m);
  // A rigid body: coloured only in the bounded class of smooth contacts, with the far monopoles of
  // body_far_model (its total load, one dense row, from the load changes each moved contact owns).
  const bool body = body_colouring(pb);
  const colouring cl(x, pb.body_load && !body, body ? near_lengths : 0.0);
  const std::size_t colours = cl.colours();
  auto near = [&](std::size_t i, std::size_t k) { return cl.near(i, k); };
  std::optional<body_far_model> far;
  if (body && colours < n) far.emplace(pb, x);
  std::vector<double> base_load(far ? n : 0);
  for (std::size_t i = 0; i < base_load.size(); ++i) base_load[i] = ev.sol.g[i].integral();
  // The far model's response of each row to a unit load on each contact not near its own (the
  // same for every column group; 0 where near, and in the total load's row).
  Eigen::MatrixXd response = Eigen::MatrixXd::Zero(far ? m : 0, far ? static_cast<Eigen::Index>(n) : 0);
  if (far)
    run_tasks(static_cast<std::size_t>(m), pb.cx->options.threads, [&](std::size_t row) {
      const std::size_t j = u.state[row];
      if (u.trailing[row] && j == 0) return;
      for (std::size_t o = 0; o < n; ++o)
        if (!near(j, o))
          response(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(o)) =
              u.trailing[row] ? far->level_row(j, o) : far->defect_row(j, o);
    });
  std::vector<double> h(static_cast<std::size_t>(m));
  for (std::size_t k = 0; k < h.size(); ++k) h[k] = 1e-7 * (x.b[u.state[k]] - x.a[u.state[k]]);
  // One column (group) per colour and side: the unknowns moved together, their difference of the
  // conditions, or the failure of both differences. Independent of one another: on
  // solve_options::threads threads.
  struct column {
    std::vector<std::size_t> moved_unknowns;
    Eigen::VectorXd dr;
    std::vector<double> dload;  // each contact's load difference (a rigid body's far model)
    std::exception_ptr failure;
  };
  std::vector<column> columns;
  for (std::size_t colour = 0; colour < colours; ++colour) {
    for (int side = 0; side < 2; ++side) {
      column c;
      for (std::size_t k = 0; k < h.size(); ++k)
        if (cl.colour(u.state[k]) == colour && u.trailing[k] == (side == 1)) c.moved_unknowns.push_back(k);
      if (!c.moved_unknowns.empty()) columns.push_back(std::move(c));
    }
  }
  run_tasks(columns.size(), pb.cx->options.threads, [&](std::size_t index) {
    column& c = columns[index];
    auto difference = [&](double sign) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(m);
      for (std::size_t k : c.moved_unknowns) e[static_cast<Eigen::Index>(k)] = sign * h[k];
      const edges y = moved(pb, u, x, e);
      const evaluation at = evaluate(pb, u, y.a, y.b);
      if (far) {
        c.dload.resize(n);
        for (std::size_t i = 0; i < n; ++i) c.dload[i] = sign * (at.sol.g[i].integral() - base_load[i]);
      }
      return Eigen::VectorXd(sign * (at.r - r));
    };
    try {
      try {
        c.dr = difference(1);
      } catch (const std::exception&) {  // the forward step closes a gap (or leaves a domain): backward
        c.dr = difference(-1);
      }
    } catch (...) {
      c.failure = std::current_exception();
    }
  });
  for (column& c : columns) {
    if (c.failure) std::rethrow_exception(c.failure);  // the first failed column, as a serial run would
    // Each contact's load change is owned by the moved contact near it (at most one: colouring).
    std::vector<std::size_t> owner(far ? n : 0, u.state.size());
    for (std::size_t o = 0; o < owner.size(); ++o)
      for (std::size_t k : c.moved_unknowns)
        if (near(o, u.state[k])) owner[o] = k;
    for (Eigen::Index row = 0; row < m; ++row) {
      const std::size_t j = u.state[static_cast<std::size_t>(row)];
      if (far) {
        const bool trailing = u.trailing[static_cast<std::size_t>(row)];
        if (trailing && j == 0) {  // the total load: the load changes each moved contact owns
          for (std::size_t o = 0; o < n; ++o)
            if (owner[o] < u.state.size())
              J(row, static_cast<Eigen::Index>(owner[o])) +=
                  c.dload[o] / (pb.load_factor * *pb.body_load) / h[owner[o]];
          continue;
        }
        // The load changes of the contacts not near j act on its row by their monopoles: out of
        // the difference, into the entry of the moved contact that owns them.
        for (std::size_t o = 0; o < n; ++o) {
          const double action = c.dload[o] * response(row, static_cast<Eigen::Index>(o));
          c.dr[row] -= action;
          if (owner[o] < u.state.size()) J(row, static_cast<Eigen::Index>(owner[o])) += action / h[owner[o]];
        }
      }
      // (+=: a moved contact near j also owns far load changes, whose action was taken out above)
      for (std::size_t k : c.moved_unknowns)
        if (near(j, u.state[k])) J(row, static_cast<Eigen::Index>(k)) += c.dr[row] / h[k];
    }
  }
  return J;
}

newton_result newton_iteration(const problem& pb, const edges& start);

}  // namespace

/// newton_iteration, with any failure of a contact's own solve (std::exception) as a failed result.
newton_result newton(const problem& pb, const edges& start) {
  try {
    return newton_iteration(pb, start);
  } catch (const std::exception& e) {
    newton_result out;
    out.x = start;
    out.failure = e.what();
    return out;
  }
}

namespace {

/// Inexact Newton: far from the solution the conditions need not be evaluated to the tolerance. An
/// evaluation solves the correction to inexact_ratio times the largest condition at the last
/// accepted point (at most first_accuracy, at least the tolerance): the error it makes in the
/// conditions is then a small fraction of their size, and near the solution it is the tolerance.
/// The correction's degree follows (gap 1e-3 L: ~400 points per contact at 1e-10, fewer at 1e-5).
constexpr double inexact_ratio = 1e-3;

constexpr double first_accuracy = 1e-5;

constexpr double trust_factor = 10;

/// One Newton-Broyden iteration on the edges in progress: the problem at the accuracy of the
/// current step, the result being built and the evaluation of the last accepted point.
struct newton_state {
  explicit newton_state(const problem& p)
      : pb(p), u(list_unknowns(p)), tol(std::max(p.cx->options.tolerance, p.accuracy)), q(p) {}

  const problem& pb;
  const unknowns u;
  const double tol;
  problem q;  // the evaluations' problem: pb at the accuracy of the current step
  newton_result out;
  evaluation ev;
  double ev_accuracy = 0;  // the accuracy ev was evaluated at

  /// The accuracy of an evaluation from the largest condition r at the last accepted point.
  double accuracy_for(double r) const { return std::max(tol, std::min(first_accuracy, inexact_ratio * r)); }

  /// Re-evaluates the point x more accurately until its conditions are trusted (below).
  // Conditions evaluated at an accuracy are trusted when they exceed trust_factor times it;
  // below, the point is evaluated again, more accurately, until they do or the accuracy is the
  // tolerance (a superlinear step can land far below the accuracy it was evaluated at; compared
  // with that value, the next, accurate evaluation would never show a decrease).
  void sharpen(const edges& x) {
    while (ev_accuracy > tol && ev.r.lpNorm<Eigen::Infinity>() < trust_factor * ev_accuracy) {
      q.accuracy = accuracy_for(ev.r.lpNorm<Eigen::Infinity>());  // at most inexact_ratio trust_factor ev_accuracy
      ev = evaluate(q, u, x.a, x.b);
      ev_accuracy = q.accuracy;
    }
  }
};

/// The move of an edge, relative to its contact's length, up to which a kept Jacobian
/// (jacobian_memo) starts an iteration. WHY 0.1: a contact's conditions change with its edges on
/// the scale of its length, and the solves that reuse a Jacobian move the edges far less (the next
/// series degree: 1e-6 .. 1e-3 of a length). WHY not also with a few contacts moved further (a
/// repaired contact, its columns differenced again): on rough profiles that start took more
/// iterations than a new Jacobian (1e5-sample periodic profile, 443 contacts: 14 instead of 7).
constexpr double memo_shift = 0.1;

/// Whether pb keeps its Jacobians in a memo: a seeded rigid body (a sampled profile's round)
/// iterated with the coloured Jacobian (body_colouring). WHY seeded only: the other solves'
/// continuations in the load or the heights start each stage far from the last stage's edges.
bool keeps_jacobian(const problem& pb) { return pb.memo && pb.seeded && body_colouring(pb); }

/// Whether pb's memo serves as the Jacobian at the edges x: keeps_jacobian, in a solve's first
/// attempt (problem::read_memo), every contact started from a solved load (indentor_state::
/// seed_load), the memo taken at as many contacts, each edge within memo_shift of its contact's
/// length of where it was. WHY solved loads: a contact whose pressure was negative at an end
/// starts the next round with that edge moved, its load a guess (contact_set.cpp, repair_tension);
/// from the kept Jacobian the round's iteration then closed two contacts ~5e-6 apart until they
/// merged (32000-sample periodic profile, seed 1, load 6e-3), and the search cycled between the
/// merged contact, negative inside, and the pair until its time limit (not_converged at 120 s);
/// with a new Jacobian it is ok with the boundary-element solver's 240 patches in 40 s.
bool memo_serves(const problem& pb, const unknowns& u, const edges& x) {
  if (!keeps_jacobian(pb) || !pb.read_memo) return false;
  for (const indentor_state& s : *pb.st)
    if (!s.seed_load) return false;
  const jacobian_memo& m = *pb.memo;
  if (m.J.rows() != static_cast<Eigen::Index>(u.state.size()) || m.a.size() != x.a.size()) return false;
  for (std::size_t i = 0; i < x.a.size(); ++i) {
    const double shift = memo_shift * (x.b[i] - x.a[i]);
    if (!(std::abs(x.a[i] - m.a[i]) <= shift && std::abs(x.b[i] - m.b[i]) <= shift)) return false;
  }
  return true;
}

/// The floor below which an iteration's stall counts as converged (0: none): problem::stall_floor,
/// raised to capped_floor_factor x the largest tail of a contact whose series stopped at
/// solve_options::max_degree, at most max_capped_floor. WHY: such a contact's edge conditions
/// are resolved only to its series' tail, so Newton stalls there (1e5-sample periodic profile,
/// 230 contacts: tails 6.6e-5 at degree 128, stalls at 2.2e-5; 9.8e-7 at 512, stalls at 1.4e-6),
/// and a round that ends stalled ends the search at that degree with its set unsettled (without
/// this floor: the degree-128 search ended stalled at 2.2e-5 after 4 rounds, and the degree-512
/// rounds from it took 20-70 s each, merging pairs). Accepted at that floor, the round's set is
/// settled and the next degree (contact_set.cpp, raise_degree) starts from it; the contact's own
/// residual of (8) still reports the truncation, so the result is not ok at that degree.
double stall_floor(const problem& pb, const fixed_solution& sol) {
  if (!(pb.stall_floor > 0)) return 0;
  return std::max(pb.stall_floor, std::min(capped_floor_factor * capped_tail(sol, *pb.cx), max_capped_floor));
}

/// jacobian, kept in pb's memo when keeps_jacobian (jacobian_memo).
Eigen::MatrixXd fresh_jacobian(const problem& pb, const unknowns& u, const edges& x, const evaluation& ev) {
  Eigen::MatrixXd J = jacobian(pb, u, x, ev);
  if (keeps_jacobian(pb)) *pb.memo = {J, x.a, x.b};
  return J;
}

/// Broyden's matrix with the bookkeeping of its refreshes by a finite-difference Jacobian.
struct jacobian_state {
  abel::broyden_matrix<double> J;
  bool fresh = true;
  std::size_t since_fresh = 0;  // accepted steps since the last finite-difference Jacobian
  std::size_t flat = 0;         // accepted steps of the current flat run
  bool refreshed_in_flat = false;
  bool krylov = false;  // the steps by krylov_step from now on
  bool wide = false;    // its products differenced at krylov_wide_step from now on
  bool polish = false;  // a ladder round's (krylov_instead)

  /// A new finite-difference Jacobian at the accepted point of s.
  void refresh(newton_state& s) {
    J.reset(fresh_jacobian(s.pb, s.u, s.out.x, s.ev));
    ++s.out.jacobians;
    fresh = true;
    since_fresh = 0;
  }

  /// In a ladder round (polish: a seeded body of coloured contacts, context::ladder), where the
  /// matrix would be refreshed, krylov_step's steps from now on instead (preconditioned by the
  /// matrix as it is); false elsewhere, or when they are taken already. WHY: there the set and
  /// its edges are settled at the degree below, Broyden's steps from the kept Jacobian stall within
  /// a few steps, and a fresh coloured Jacobian costs ~20 evaluations whose step still gains
  /// little (the ~980-patch periodic profile, degree 1024: 1e-6 to 1.7e-7 of the largest condition
  /// in 6 steps and 38 s, then krylov_step's to 1e-9 in 2 steps); its products reach the accuracy
  /// in 2-4 steps.
  bool krylov_instead() {
    if (!polish || krylov) return false;
    krylov = true;
    return true;
  }
};

/// Evaluates the start (edges of apex-ended contacts at their apexes) to a trusted accuracy;
/// false when the iteration ends there (out then final: failed, or converged without unknowns).
bool newton_start(newton_state& s, const edges& start) {
  newton_result& out = s.out;
  s.q.accuracy = s.u.state.empty() ? s.pb.accuracy : s.accuracy_for(std::numeric_limits<double>::infinity());
  out.x = start;
  for (std::size_t i = 0; i < s.pb.roles.size(); ++i)
    if (s.pb.roles[i] == role::apex_ended) out.x.b[i] = (*s.pb.st)[i].apex;
  if (s.pb.cx->out_of_time()) {  // the callers' loops then end after one cheap call each
    out.failure = s.pb.cx->time_limit_message();
    out.residual = std::numeric_limits<double>::infinity();
    return false;
  }
  s.ev_accuracy = s.q.accuracy;
  try {
    s.ev = evaluate(s.q, s.u, out.x.a, out.x.b);
    s.ev_accuracy = s.q.accuracy;
    if (!s.u.state.empty()) s.sharpen(out.x);
  } catch (const merge_error& m) {
    out.failure = m.what();
    out.merged = std::make_pair(m.first, m.second);
    return false;
  } catch (const std::domain_error& e) {  // a contact's own solve failed at the start
    out.failure = e.what();
    return false;
  } catch (const time_limit_reached& e) {
    out.failure = e.what();
    out.residual = std::numeric_limits<double>::infinity();
    return false;
  }
  if (s.u.state.empty()) {
    out.converged = true;
    out.sol = std::move(s.ev.sol);
    return false;
  }
  return true;
}

/// Backtracking's tries: t, t/2, ... at most max_tries; from a point already within its floor
/// (within_floor), at most tries_at_floor, after which the iteration ends there (broyden_steps).
/// WHY: a stall there counts as converged, and the halvings below it bought nothing but their
/// evaluations (the ~980-patch periodic profile: line searches down to t = 2^-11 at conditions of
/// 1.5e-8 .. 2.4e-7, under floors of 1e-6 and more, 12-30 evaluations of 0.3-0.8 s each, in four
/// rounds). WHY two: a step that only overshoots decreases the conditions at half its length.
constexpr int max_tries = 12;
constexpr int tries_at_floor = 2;

/// Backtracking along dx from the accepted point: the first of t, t/2, ... (`tries` tries) whose
/// conditions decrease (Armijo, 1e-4 t), evaluated into next at y; false if none does.
bool backtrack(newton_state& s, const Eigen::VectorXd& dx, double& t, evaluation& next, edges& y, int tries) {
  bool accepted = false;
  for (int k = 0; k < tries; ++k) {
    y = moved(s.pb, s.u, s.out.x, t * dx);
    try {
      next = evaluate(s.q, s.u, y.a, y.b);
      accepted = next.r.allFinite() &&
                 next.r.lpNorm<Eigen::Infinity>() < (1 - 1e-4 * t) * s.ev.r.lpNorm<Eigen::Infinity>() + 1e-14;
    } catch (const merge_error& m) {
      s.out.merged = std::make_pair(m.first, m.second);
      s.out.failure = m.what();
    } catch (const std::domain_error& e) {  // e.g. a wedge's apex left its contact: a shorter step
      s.out.failure = e.what();
    }
    if (accepted) break;
    t /= 2;
  }
  return accepted;
}

/// What a run of flat steps (reduction > flat_gain) leads to.
enum class flat_verdict { go_on, refreshed, stop };

/// The flat run after an accepted step from `before` (reduction of the largest condition, relative
/// step): a new Jacobian at the first run of flat_steps, a stop (stalled, or merging) at the second.
flat_verdict flat_run(newton_state& s, jacobian_state& js, const edges& before, double reduction, double step) {
  if (!(reduction > flat_gain && step > 10 * s.tol)) {
    js.flat = 0;
    js.refreshed_in_flat = false;
    return flat_verdict::go_on;
  }
  if (++js.flat == flat_steps && !js.refreshed_in_flat) {
    if (!js.krylov_instead()) js.refresh(s);
    js.flat = 0;
    js.refreshed_in_flat = true;
    return flat_verdict::refreshed;
  }
  if (js.flat != flat_steps) return flat_verdict::go_on;
  const auto pair = narrowing_pair(before, s.out.x);
  if (pair && pair->gap_ratio < flat_merge_gap) {
    std::ostringstream os;
    os.precision(3);
    os << " where the edge iteration stalls (largest edge condition " << s.ev.r.lpNorm<Eigen::Infinity>()
       << "): they merge";
    s.out.failure = closing_message(s.pb, *pair, os.str());
    s.out.merged = std::make_pair(pair->first, pair->second);
  } else {
    s.out.failure = "the edge iteration stalled";
  }
  return flat_verdict::stop;
}

/// NEWTON-KRYLOV STEP (inexact Newton, Dembo, Eisenstat and Steihaug, SIAM J. Numer. Anal. 19
/// (1982) 400-408; Jacobian-free, Knoll and Keyes, J. Comput. Phys. 193 (2004) 357-397): the step dx
/// with |r + J dx| <= krylov_rtol |r|, J the true Jacobian of the edge conditions
/// (newton_krylov.hpp: GMRES on differences, no edge moved by more than 1e-7 of its contact's
/// length, at the base point's fixed degrees as jacobian's columns), right-preconditioned by
/// Broyden's matrix (its solve). At most krylov_products + 1 evaluations; GMRES's best iterate
/// when they are not enough. WHY: on a rigid body of many seeded contacts the
/// coloured Jacobian (body_far_model) misses couplings among clustered contacts, and a fresh one's
/// step then gains little: 1e5-sample periodic profile, 229 contacts, degree 512: 5e-5 to 1.4e-5
/// of the largest condition in 20 steps and 180 s; with these steps 3e-7 in 12 steps (traced);
/// 4000-sample periodic profile, seed 3, load 3e-3 (34 contacts): 26 s -> 12.7 s. Used only after
/// a fresh Jacobian's step gained less than krylov_after; scenes the coloured Jacobian serves keep
/// Broyden's steps, one evaluation each, and one that it serves slowly pays the products: the
/// 16000-sample one at seed 3 (75 contacts) 19 s -> 26 s (rtol 1e-2: 32 s); the other 34 periodic
/// and 21 finite scenes of studies/scenes/rough_matrix.py end as before, in the same time or less.
constexpr double krylov_after = 0.5;
constexpr double krylov_rtol = 0.1;
constexpr std::size_t krylov_products = 12;
/// The relative steps of krylov_step's products (newton_krylov.hpp): the edges move by
/// krylov_step_size of their contacts' lengths in the root mean square, none by more than
/// krylov_wide_step; once the steps at that have stalled (escalate), every edge up to
/// krylov_wide_step. WHY the root mean square: the edges are absolute abscissae, so a contact
/// 1.8e-7 long at x ~ 0.5 resolves its length only to ~6e-10, and the conditions carry that
/// rounding. With the step set by the largest relative move (every edge within 1e-7 of its
/// length, as before), a product on the ~980-patch periodic profile moved most edges by ~1e-14
/// (~100 ulps of their abscissae) to keep the shortest contact's within 1e-7; forward and backward
/// differences then disagreed by 0.5 % of the product in the median row, 5 % at the 90th
/// percentile and 35 % at the 99th (1e-5: 5e-5, 5e-4, 0.4 %), GMRES's 12 products rarely met
/// krylov_rtol, and the degree-128 iteration stalled at 1.2e-6 of the largest condition for ~80 s
/// per round (traced). With the root mean square it converges below 1e-8 (and stops at its floor,
/// floor_gain), and the profile is ok in 61 iterations and 6.2-6.6 min instead of 84 and 12.7 min
/// (docs/theory.md section 7). WHY krylov_wide_step as the cap: at 1e-5 of a length the
/// curvature's error is still small against the difference (the same trace: a cap of 1e-4 gave the
/// same iterations); the wide products alone, on every edge, steer a search that converges elsewhere (the 1e5-sample periodic profile of seed 2 at load 6e-3 ended
/// not_converged after 14 min, where it is ok in 5). At a light contact's stall (docs/theory.md
/// section 7, "Where this falls short") GMRES on products at 1e-7 left a linear residual of 1.5e-2
/// of |F| 6.8e-3; at 1e-5 it met 0.1 |F| in 7 products.
constexpr double krylov_step_size = 1e-7;
constexpr double krylov_wide_step = 1e-5;

Eigen::VectorXd krylov_step(const newton_state& s, const jacobian_state& js) {
  problem pb = at_base_discretisation(s.pb, s.ev.sol);
  pb.correction_guess = s.ev.sol.correction_unknowns;
  const unknowns& u = s.u;
  Eigen::VectorXd length(static_cast<Eigen::Index>(u.state.size()));
  for (std::size_t k = 0; k < u.state.size(); ++k)
    length[static_cast<Eigen::Index>(k)] = s.out.x.b[u.state[k]] - s.out.x.a[u.state[k]];
  const auto conditions = [&](const Eigen::VectorXd& dx) {
    const edges y = moved(pb, u, s.out.x, dx);
    return evaluate(pb, u, y.a, y.b).r;
  };
  const auto precondition = [&](const Eigen::VectorXd& v) {
    const auto z = js.J.solve(v);
    return z ? Eigen::VectorXd(*z) : v;
  };
  return newton_krylov_step(conditions, s.ev.r, length, precondition, krylov_rtol, krylov_products,
                            js.wide ? krylov_wide_step : krylov_step_size, krylov_wide_step);
}

/// Where a seeded body's iteration (problem::seeded, with body_load) would stop as stalled above
/// its floor (stall_floor; a fresh Jacobian's step gaining too little, or none decreasing the
/// conditions), its next remedy instead: krylov_step's steps if Broyden's were taken, else its
/// products at krylov_wide_step if not yet; false (stop) when both were tried, for any other
/// iteration, or where two contacts merge. WHY only there: taken in the pre-solves of the
/// loads-imposed start (coupled_solve.cpp), the wide products changed the 1e5-sample periodic
/// profile of seed 3 (load 6e-3) from its first round and it lost contacts; where the floor accepts
/// the stall, they changed seed 1's path and doubled its time (128 s -> 246 s). Measured on seed 3:
/// its fourth round, 426 contacts, stalled at 6.8e-3 on a light contact's level row (without them
/// the search ended not_converged there); with the wide products it converged. Its fifth, 427
/// contacts, found no decreasing Broyden step from its fresh Jacobian (1.1e-2); with krylov_step's
/// it converged in 13 steps; the search does not end ok yet (docs/theory.md section 7).
bool escalate(newton_state& s, jacobian_state& js, bool colouring) {
  const problem& pb = s.pb;
  if (!colouring || !pb.seeded || !pb.body_load || s.out.merged || js.wide ||
      !(s.ev.r.lpNorm<Eigen::Infinity>() > stall_floor(pb, s.ev.sol)))
    return false;
  if (js.krylov)
    js.wide = true;
  else
    js.krylov = true;
  s.out.failure.clear();
  return true;
}

/// After an accepted step (t dx, the condition's reduction, the relative step): true when the
/// iteration ends (stalled far from the solution, a contact vanishes, or converged); may refresh J.
bool newton_step_ends(newton_state& s, jacobian_state& js, bool colouring, bool step_was_fresh, double t,
                      double reduction, double step) {
  const problem& pb = s.pb;
  // Many contacts (coloured Jacobian): when even a new Jacobian's step gains less than a
  // quarter, this start is too far from the solution (rows of 300 parabolas from the isolated
  // contacts: 27 steps from 3.8 to 0.95, each gaining 1 ... 11 %): the caller's continuation in
  // the load takes over. A rigid body's steps are often shortened by step_limit far from the
  // solution (a contact about to vanish): only a full step that gains little gives up there.
  // Seeded contacts first go on with krylov_step (a fresh step gaining less than krylov_after),
  // and give up only when a fresh step gains that little again (on a body, above its floor: with
  // the products at krylov_wide_step too, escalate).
  if (colouring && pb.seeded && step_was_fresh && !js.krylov && reduction > krylov_after && step > 10 * s.tol) {
    js.krylov = true;  // the coloured Jacobian misses a coupling: exact products from now on
  } else if (colouring && step_was_fresh && reduction > 0.75 && step > 10 * s.tol && (!pb.body_load || t == 1)) {
    if (!escalate(s, js, colouring)) {
      s.out.failure = "the edge iteration stalled";
      return true;
    }
  }
  // Otherwise Broyden's updates from a start far from the solution crawl (rows of 100
  // parabolas: the condition fell by less than half per step for 12 steps, then converged in 2
  // after a new Jacobian; two parabolas 1e-3 L apart, the Jacobian taken at the continuation's
  // last gap of 1e-2 L: 12 steps each gaining ~ a factor 1.5); a new one when a step gains less
  // than a factor 2 two steps after the last. Its columns are differenced at a fixed degree
  // without a residual: 2 full_width evaluations when coloured, else one per unknown.
  if (reduction > 0.5 && (colouring || t == 1) && js.since_fresh >= 2 && step > 10 * s.tol && !js.krylov_instead())
    js.refresh(s);
  if (pb.body_load) {
    const edges& y = s.out.x;
    for (std::size_t i = 0; i < pb.roles.size(); ++i)
      if (pb.roles[i] == role::smooth_both && y.b[i] - y.a[i] < vanishing_length * pb.start_length[i]) s.out.lost = i;
    if (s.out.lost) {
      s.out.failure = "a contact vanishes";
      return true;
    }
  }
  // Converged when the step is within the tolerance and the point was evaluated to it.
  if (step <= 10 * s.tol && s.ev_accuracy <= s.tol) {
    s.out.converged = true;
    return true;
  }
  return false;
}

/// Below its floor (stall_floor), a seeded body's Newton-Krylov step gaining less than this factor
/// ends the iteration there: stalled at the floor, so converged (newton_iteration). WHY: with the
/// products' root-mean-square step (krylov_step_size) the steps below the floor still gain, but
/// a few percent each: the 443-contact periodic profile (1e5 samples, seed 1, load 6e-3) went from
/// 5.1e-7 to 4.5e-8 of the largest condition in 15 steps and 50 s, its floor 4.8e-4, and took 124
/// s instead of 69; with this stop, 72 s, C_f the same to 4e-12 (traced, one core, another solve
/// on the other). A flat run (flat_gain) is the same stop for Broyden's steps.
constexpr double floor_gain = 0.5;

/// Whether the conditions at the accepted point of s are within its floor (stall_floor), evaluated
/// to a tenth of it: where a stall counts as converged.
bool within_floor(const newton_state& s) {
  const double floor = stall_floor(s.pb, s.ev.sol);
  return floor > 0 && s.ev.r.lpNorm<Eigen::Infinity>() <= floor && s.ev_accuracy <= 0.1 * floor;
}

/// Whether the accepted step just taken (its reduction of the largest condition) ends the
/// iteration at its floor (floor_gain).
bool slow_below_floor(const newton_state& s, const jacobian_state& js, double reduction) {
  return js.krylov && s.pb.seeded && reduction > floor_gain && within_floor(s);
}

/// The Newton-Broyden steps from the evaluated start of s, at most 60.
// Up to 64 unknowns the updated matrix is factorised with full pivoting at every step (robust
// when it is nearly singular, e.g. contacts about to merge); above, J0's LU with Broyden's
// updates by the Woodbury identity (rows of 1000 parabolas: the factorisations were 32 % of the
// time).
void broyden_steps(newton_state& s) {
  const problem& pb = s.pb;
  const unknowns& u = s.u;
  newton_result& out = s.out;
  // From the kept Jacobian when it serves (jacobian_memo); then not fresh, so that a step it fails
  // refreshes it.
  const bool kept = memo_serves(pb, u, out.x);
  jacobian_state js{abel::broyden_matrix<double>(kept ? pb.memo->J : fresh_jacobian(pb, u, out.x, s.ev))};
  js.fresh = !kept;
  if (!kept) ++out.jacobians;
  const bool colouring = pb.roles.size() > full_width && (!pb.body_load || body_colouring(pb));
  js.polish = colouring && pb.seeded && pb.body_load && pb.cx->ladder;
  for (std::size_t it = 0; it < 60; ++it) {
    if (pb.cx->out_of_time()) {
      out.failure = pb.cx->time_limit_message();
      break;
    }
    out.iterations = it + 1;
    // (krylov_step returns the step; Broyden's solve returns minus it)
    const auto solved = js.krylov ? std::optional<Eigen::VectorXd>(-krylov_step(s, js)) : js.J.solve(s.ev.r);
    if (!solved) {  // Broyden's updates made the matrix singular (a fresh one has none): a new Jacobian
      js.refresh(s);
      continue;
    }
    const Eigen::VectorXd dx = -*solved;
    if (!dx.allFinite()) {
      out.failure = "singular Jacobian of the edge conditions";
      break;
    }
    std::optional<closing_gap> closing;
    double t = step_limit(pb, u, out.x, dx, closing);
    if (closing) {
      std::ostringstream os;
      if (pb.seeded)
        os << ": they merge (a sampled profile's contacts nearer than " << seeded_merge_gap
           << " of a contact length are solved as one)";
      else
        os << (closing->closes ? " (the next step closes the gap: they merge)" : "") << "; gaps below " << resolved_gap
           << " of the contact length are not resolved";
      out.failure = closing_message(pb, *closing, os.str());
      if (closing->closes || pb.seeded) out.merged = std::make_pair(closing->first, closing->second);
      break;
    }
    if (const auto starved = starved_contact(pb, u, out.x, dx, s.ev.sol, s.ev.r.lpNorm<Eigen::Infinity>(), out.spared)) {
      out.lost = starved;
      out.failure = "a contact vanishes";
      break;
    }
    evaluation next;
    edges y;
    s.q.accuracy = s.accuracy_for(s.ev.r.lpNorm<Eigen::Infinity>());
    const bool at_floor = within_floor(s);
    if (!backtrack(s, dx, t, next, y, at_floor ? tries_at_floor : max_tries)) {
      if (at_floor) break;  // stalled within the floor: converged (newton_iteration)
      if (!js.fresh) {  // Broyden's matrix went stale: a new finite-difference Jacobian
        if (js.krylov_instead()) continue;
        js.refresh(s);
        continue;
      }
      if (escalate(s, js, colouring)) continue;
      if (out.failure.empty()) out.failure = "the edge iteration stalled";
      break;
    }
    out.merged.reset();
    out.failure.clear();
    // Broyden's (good) update with the step taken.
    const Eigen::VectorXd step_taken = t * dx;
    const Eigen::VectorXd dr = next.r - s.ev.r;
    js.J.update(step_taken, dr);
    const bool step_was_fresh = js.fresh;
    js.fresh = false;
    double step = 0;
    for (std::size_t k = 0; k < u.state.size(); ++k) {
      const std::size_t i = u.state[k];
      step = std::max(step, std::abs(step_taken[static_cast<Eigen::Index>(k)]) / (y.b[i] - y.a[i]));
    }
    const edges before = out.x;
    out.x = y;
    const double reduction = next.r.lpNorm<Eigen::Infinity>() / s.ev.r.lpNorm<Eigen::Infinity>();
    s.ev = std::move(next);
    s.ev_accuracy = s.q.accuracy;
    s.sharpen(out.x);
    ++js.since_fresh;
    if (slow_below_floor(s, js, reduction)) {
      out.failure = "the edge iteration stalled";
      break;
    }
    const flat_verdict verdict = flat_run(s, js, before, reduction, step);
    if (verdict == flat_verdict::refreshed) continue;
    if (verdict == flat_verdict::stop) break;
    if (newton_step_ends(s, js, colouring, step_was_fresh, t, reduction, step)) break;
  }
}

newton_result newton_iteration(const problem& pb, const edges& start) {
  newton_state s(pb);
  if (!newton_start(s, start)) return std::move(s.out);
  // The time limit (time_limit_reached from any evaluation) ends the iteration at the last
  // accepted point, whose evaluation ev is reported.
  try {
    broyden_steps(s);
  } catch (const time_limit_reached& e) {
    s.out.failure = e.what();
    s.out.merged.reset();
  }
  s.out.residual = s.ev.r.lpNorm<Eigen::Infinity>();
  if (s.ev.r.size() > 0) {
    Eigen::Index worst = 0;
    s.ev.r.cwiseAbs().maxCoeff(&worst);
    s.out.worst = condition_name(pb, s.u, static_cast<std::size_t>(worst));
  }
  // Stalled at the floor of the evaluations (problem::stall_floor): converged; the caller's
  // independent checks (the residual of (8), loads, pressure) judge the result. (Not when out of
  // time, as after time_limit_reached: the time limit is reported.)
  if (!s.out.converged && !s.out.merged && !s.out.lost && within_floor(s) && !pb.cx->out_of_time()) {
    s.out.converged = true;
    s.out.failure.clear();
  }
  if (!s.out.converged && !s.out.merged && !s.out.lost && !pb.cx->out_of_time())
    s.out.lost = stalled_on_starved(pb, s.u, s.ev);
  if (s.out.lost) s.out.failure = "a contact vanishes";
  s.out.sol = std::move(s.ev.sol);
  return std::move(s.out);
}

}  // namespace

/// (The start's evaluation of newton, without its steps.)
Eigen::VectorXd edge_conditions(const problem& pb, const edges& x) {
  newton_state s(pb);
  if (!newton_start(s, x) && !s.out.converged)
    throw std::domain_error(s.out.failure.empty() ? "the edge conditions could not be evaluated" : s.out.failure);
  return s.ev.r;
}

}  // namespace rhabel::punch::detail::coupled
