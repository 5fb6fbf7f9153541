// Several contacts at once: paper system (41). See internal.hpp for where this sits. This file: the
// starts, the retries and the result (solve_coupled); the stages it drives, with the state they share
// (coupled_problem.hpp): coupled_fixed.cpp (THE LINEAR PROBLEM FOR GIVEN EDGES below) and
// coupled_newton.cpp (THE EDGES, A RIGID BODY, OUTCOMES).
//
// THE LINEAR PROBLEM FOR GIVEN EDGES. On the union of the contact intervals I_j (each with its own
// edge class: bounded at both smooth edges, nu = -1; a wedge above the boundary ends at its apex,
// nu = 0; a flat punch below the boundary has two corners, nu = +1; above it is a line load at its
// leading corner) the densities satisfy
//     sum_i A_i g_i (s) = F_j(s) - (L_j/2)^alpha d_j,      s in I_j,
// d_j the solvability defect of a nu = -1 contact (zero at the true edges), with int g_j = P_j
// imposed on nu = +1 contacts. It is solved in two parts:
//   * a particular solution p_j of every contact alone with its own data, A_j p_j = F_j - h^alpha
//     d^p_j, by the single-contact builders (spectral for smooth data, abel::solve_step's apex
//     enrichment for a wedge, steps in closed form for corners): whatever is singular inside a
//     contact lives here;
//   * the coupling correction c_j with SMOOTH data D_j = -sum_{i != j} A_i p_i (the others'
//     particular solutions seen from I_j, smooth on I_j because the intervals are disjoint), by
//     abel::solve_union: one collocation solve on the union with the cross blocks by graded
//     quadrature (diagonal blocks diagonal in the Jacobi bases), adaptive in the degree until its
//     independent residual is within the tolerance (relative to the original data's scale).
//     From iterative_from (6) contacts on: GMRES with the block-diagonal preconditioner, and
//     separated contacts act on one another through abel's far field (abel/far_field.hpp,
//     a tree with Chebyshev moments and local values): both in the union's products and in D_j,
//     where the particulars' moments give every contact's far data at once (particular_field);
//     only near pairs (on a row, the two neighbours) are summed pair by pair. An evaluation of
//     the edge conditions then costs O(N), not O(N^2); the report's residual and surface
//     displacement sum the far contacts through the same tree (far_action.hpp).
//     Below iterative_from contacts, when two neighbours are closer than
//     solve_options::layered_below of the shorter: abel::solve_union_layered instead, the Jacobi
//     series of degree 24 (to 48) plus simple poles clustered beyond the facing ends (8 a
//     decade; an inexact evaluation, below, half of each: coarse_layered_accuracy), whose
//     unknowns grow like log(L/gap) where the series alone needs a degree ~ 10 sqrt(L/gap). The
//     poles stay in contact_density::layer while Newton iterates (the defects, loads and
//     intensities include them) and are projected onto the Jacobi series
//     (contact_density::absorb_layer) for a rigid body's levels and for the report.
//   g_j = p_j + c_j, d_j = d^p_j + d^c_j.
//
// THE EDGES. Unknowns: a_j, b_j of every smooth contact (nu = -1), a_j of a wedge ending at its
// apex. Conditions: d_j = 0 and int g_j = P_j (nu = -1), int g_j = P_j (nu = 0). Newton's method
// on all of them at once, the Jacobian by forward differences (relative step 1e-7 of each contact's
// length) and then Broyden's update, the step limited so that no contact loses more than half its
// length and no gap closes by more than 80 % in one step. Started from the isolated contacts; when
// those overlap (or Newton from them fails), by continuation in the load: all loads scaled by t (contacts then
// shrink like t^(1/(2 - alpha)) (parabola) or t^(1/(1 - alpha)) (wedge) about their apexes and
// separate), t raised to 1 in steps, each solve starting from the previous one, the stages below
// t = 1 only to continuation_accuracy. Independent parabolas that no continuation brings to the
// full loads (there may be no path with one interval per indentor:
// coarse_bodies.hpp) start from the coarse boundary-element solve of all of them at once. Seeded
// contacts (a sampled profile's, from its coarse solve) from which Newton fails follow the Newton
// homotopy from the seeds' own conditions (offset_continuation).
//   The Newton iteration is INEXACT: an evaluation solves the coupling correction only to 1e-3 of
// the largest condition at the last point (at most 1e-5, at least the tolerance), so that the
// correction's degree, which near contacts is what an evaluation costs, follows the progress
// (inexact_ratio; a converged result is always an evaluation at the tolerance). Two parabolas
// 1e-3 L apart: 1.1-1.6 s instead of 3.9-6.7 s at tolerance 1e-12.
//   With more than full_width contacts, smooth contacts without steps in their data (parabolas,
// general profiles without corners) below the boundary are iterated with their LOADS IMPOSED
// instead (loaded_form; the bounded class again if that fails): the class nu = +1,
// singular at both edges, whose homogeneous solution carries int g_j = P_j, with the conditions
// that both intensity factors vanish; once converged they are re-solved in the bounded class for
// the report. Moving an edge then changes a contact's far field only by a dipole, and the
// coloured Jacobian of many contacts stays accurate (rows of 10 / 20 / 40 parabolas: 13 / 16 / 21
// Newton iterations instead of 25 / 39 / 56). With the coloured Jacobian a new one is taken when
// Broyden's steps gain less than a factor 2, and a start from which even a new Jacobian's step
// gains less than a quarter is given up for the continuation in the load (rows of 300 parabolas:
// the isolated contacts are too far from the coupled ones). The linear system of a Newton step is
// solved with full pivoting up to 64 unknowns; above, each finite-difference Jacobian is factorised
// once and Broyden's updates enter by the Woodbury identity (abel/broyden_matrix.hpp).
//
// A RIGID BODY (scene::body). The loads are unknowns and the heights of the indentors are given:
// every contact keeps its first condition (d_j = 0 or its split-form intensity), and its second
// becomes the total load (contact 0) or equal levels approach_j + height_j = approach_(j-1) +
// height_(j-1) (the others), approach_j = w - f_j on the contact from the surface displacement of
// surface.hpp. The start is an equal split of the load; when Newton fails from there, continuation
// in the height differences (0 to 1). A contact that shrinks below vanishing_length of its start
// is status_code::contact_lost: its indentor would carry no load. The Jacobian: with more than
// full_width smooth contacts, coloured as above, and the far entries, which the loads' monopoles
// make large, from a model of a unit load's action (body_far_model) applied to every contact's
// measured load change in a column's difference, owned by the moved contact near it: ~2 full_width
// evaluations instead of 2 N (50 cosine bumps, 29 contacts: the last round 0.55 s instead of
// 1.3 s). When that iteration fails, again with every column differenced. A seeded body (a sampled
// profile's coarse contacts) skips the continuation in the load (attempt), and starts from the
// edges that carry the seeds' own loads, solved first as independent contacts with the loads
// imposed (loads_imposed_start); a contact that starves on the way (below a hundredth of the mean
// load) vanishes (status_code::contact_lost, for the profile search to drop).
//
// OUTCOMES. Converged: every edge step below 10 tolerance L. A gap that closes (below 1e-12 of the
// smaller contact) is status_code::contacts_merge with the two contacts named, and so is a flat run
// (steps that no longer lower the conditions; see flat_gain) that ends with two neighbours closing
// under flat_merge_gap of a length; any other stalled iteration, and one stopped by
// solve_options::time_limit, is status_code::not_converged with its residuals. The caller
// (contact.cpp) then checks the result independently (residual of (8), sign of the pressure, loads)
// before it says ok.
#include "coupled_problem.hpp"

#include "coarse_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace rhabel::punch::detail {

namespace coupled {
namespace {

// ---------------------------------------------------------------------------------------------
// Start: isolated contacts, scaled for the continuation.

/// Contacts scaled about their apexes as isolated ones would be when contact i's load is
/// multiplied by factor[i] (lengths like load^(1/p)): both edges of a smooth contact, the leading
/// one of a wedge ending at its apex (the trailing edge is the apex); a line load and a flat
/// punch's fixed faces keep theirs.
edges rescaled(const problem& pb, const edges& x, const std::vector<double>& factor) {
  edges out = x;
  const auto& st = *pb.st;
  for (std::size_t i = 0; i < st.size(); ++i) {
    if (pb.roles[i] != role::smooth_both && pb.roles[i] != role::apex_ended) continue;
    const double f = std::pow(factor[i], 1 / load_exponent(st[i], *pb.cx));
    out.a[i] = st[i].apex + (x.a[i] - st[i].apex) * f;
    if (pb.roles[i] == role::smooth_both) out.b[i] = st[i].apex + (x.b[i] - st[i].apex) * f;
  }
  return out;
}

/// Isolated contacts at the scene's loads scaled by t: lengths and apex offsets scale like t^(1/p).
edges scaled_guess(const problem& pb, const edges& isolated, double t) {
  return rescaled(pb, isolated, std::vector<double>(pb.st->size(), t));
}

/// Smallest gap between neighbours relative to the smaller of the two lengths (inf for one contact,
/// negative when two overlap); with movable_only, only pairs of which one contact has free edges
/// (two flat punches keep their gap at any load).
double gap_ratio(const problem& pb, const edges& x, bool movable_only = false) {
  auto movable = [&](std::size_t c) { return pb.roles[c] == role::smooth_both || pb.roles[c] == role::apex_ended; };
  double worst = std::numeric_limits<double>::infinity();
  for (const auto& p : neighbour_pairs(x.a, x.b))
    if (!movable_only || movable(p.first) || movable(p.second)) worst = std::min(worst, p.gap / p.length);
  return worst;
}

/// The continuation's stages below the full load only start the next stage: their Newton
/// iterations stop at this accuracy (edge steps below 10x it, relative to a contact) instead of
/// the tolerance. Measured on two parabolas 1e-3 L apart at alpha 0.3 / 0.7 / 0.9: 57 / 66 / 125
/// Newton iterations at the tolerance (1e-12), 41 / 48 / 58 at 1e-6, results within 1e-13 L; at
/// 1e-4 the alpha = 0.9 scene's stage at 1/64 of the load closed the gap (contacts_merge).
constexpr double continuation_accuracy = 1e-6;

/// Seeded contacts (a sampled profile's) are solved to this fraction of the acceptance (when that
/// is above the tolerance): the edges' Newton iteration stops at conditions below it, and the
/// coupling correction is solved to it. WHY: the profile's evidence is judged at the acceptance
/// (~1e-6 for sampled data), and its error terms here are a thousandth of that; the steps from
/// 1e-9 to the default tolerance 1e-12 took 12 % of a 4000-sample search and kept a 16000-sample
/// one from finishing within its minute (periodic, seed 3, load 3e-3: largest edge condition
/// 5e-10 at the time limit).
constexpr double seeded_accuracy = 1e-3;

/// The rounds of a search at a higher degree from the contacts of the search before
/// (context::ladder) are solved to this fraction of the acceptance instead. WHY: their set was
/// found at the degree below and they polish it; the evidence still judges at the acceptance.
/// Measured (one core, another solve on the other; `self_affine_profile.py N SEED LOAD --periodic`,
/// acceptance 1e-6) against seeded_accuracy throughout: 1e5 samples, seed 1, load 6e-3 (443
/// contacts) 68 s against 86 s; seed 2 (437) 72 s against 88 s; seed 3 (428) 102 s against
/// 120 s; the nine 32000-sample scenes of seeds 1-3 at loads 2e-3, 3e-3, 6e-3 130 s against 142 s
/// in all: the same contacts, C_f within 1e-11 relative. Not in the first search: at 1e-2 there,
/// the ~980-contact profile (load 1.4e-2) closed two contacts 4e-5 of a length apart in its second
/// round, which the boundary-element solver has as two.
constexpr double ladder_accuracy = 1e-2;

/// Whether a contact's series stopped at solve_options::max_degree with its tail above the
/// acceptance: the edge conditions then have a floor above it, and no retry at this degree ends
/// ok. WHY: a seeded round of a rough profile whose contacts span several samples stalled at the
/// largest condition 1e-3 at degree 128, and its retries (the homotopy from the seeds) took 20 s
/// of it before the profile search raised the degree (4000 samples, periodic, seed 3, load 3e-3;
/// at 512 it is ok).
bool series_capped(const fixed_solution& sol, const context& cx) { return capped_tail(sol, cx) > cx.options.acceptance; }

/// Whether a contact starts from a seed (a sampled profile's coarse or solved contacts).
bool any_seeded(const std::vector<indentor_state>& st) {
  return std::any_of(st.begin(), st.end(), [](const indentor_state& s) { return s.seed.has_value(); });
}

/// Newton directly from the isolated contacts when they do not overlap, else (or when that fails)
/// by continuation in the load; pb.load_factor ends at the last load factor solved.
newton_result attempt(problem& pb, const edges& isolated) {
  const auto& st = *pb.st;
  pb.load_factor = 1;
  newton_result result;
  bool done = false;
  // Directly from the isolated contacts when they do not overlap (measured: fewer iterations than
  // the continuation down to gaps of a few percent of a contact length).
  if (gap_ratio(pb, isolated) > 0) {
    result = newton(pb, isolated);
    done = result.converged;
  }
  if (done) return result;
  // A rigid body from seeds (a sampled profile's coarse contacts): no continuation in the load.
  // WHY: the seeds are the contacts at the full load, and scaled down about their apexes they are
  // nothing like the contacts at a small one (at 4^-10 of the load the body rests on its highest
  // tips: the first step lost a contact, which then barred the retries; 4000-sample self-affine
  // profile, 32 seeds). The seeded retries (offset_continuation, full Jacobian) start from them.
  if (pb.body_load && gap_ratio(pb, isolated) > 0 && any_seeded(st)) return result;
  // Continuation in the load from a t at which the scaled isolated contacts are well apart.
  // (Only gaps that the load changes count; t >= 4^-10: a contact ~1e-3 of its full size.)
  double t = 1;
  for (int k = 0; k < 10 && !(gap_ratio(pb, scaled_guess(pb, isolated, t), true) > 1); ++k) t /= 4;
  // Already well apart at the full load: the continuation would repeat the direct attempt.
  if (t == 1 && gap_ratio(pb, isolated) > 0) return result;
  pb.load_factor = t;
  const double requested = pb.accuracy;
  // The stages below the full load only start the next one: solved to continuation_accuracy.
  const auto stage = [&](problem p) {
    if (p.load_factor < 1) p.accuracy = std::max(requested, continuation_accuracy);
    return p;
  };
  result = newton(stage(pb), scaled_guess(pb, isolated, t));
  double step = 4;  // factor by which t grows
  std::size_t total = result.iterations;
  while (result.converged && t < 1) {
    const double t_next = std::min(1.0, t * step);
    problem next = pb;
    next.load_factor = t_next;
    // Predictor: the current contacts scaled about their apexes as isolated ones would be.
    edges guess = rescaled(pb, result.x, std::vector<double>(st.size(), t_next / t));
    if (gap_ratio(next, guess) <= 0) guess = result.x;  // the predictor would overlap: corrector only
    auto trial = newton(stage(next), guess);
    total += trial.iterations;
    if (trial.converged) {
      result = std::move(trial);
      t = t_next;
      pb = next;
      step = std::min(4.0, step * 1.5);
      // Contacts already within 1e-3 of a length: every further step is a costly solve (the
      // correction's degree grows like sqrt(L/gap)); go to the full load at once, where Newton
      // either converges or finds the gap closing (contacts_merge).
      if (gap_ratio(pb, result.x) < 1e-3) step = 1 / t;
    } else if (trial.merged) {  // the contacts meet between t and t_next: that is the answer
      result = std::move(trial);
      break;
    } else if (step > 1.0001) {
      step = std::sqrt(step);  // a smaller increment
      if (step < 1.01) {
        result = std::move(trial);
        break;
      }
    } else {
      result = std::move(trial);
      break;
    }
  }
  result.iterations = total;
  if (result.converged && pb.load_factor < 1) result.converged = false;
  return result;
}

/// A continuation in one parameter s of the problem, from a solution r at s = 0 to s = 1:
/// stage(s) is the problem at s, each stage's Newton starts from the last solution, the step in s
/// grows by 1.5 (up to max_step) after a success and halves after a failure, and ends(t, s, step)
/// says whether a failed stage t ends it (t is then the result, not converged). p ends as the
/// problem of the last stage tried; the result is converged only at s = 1.
template <class Stage, class Ends>
newton_result continue_to_one(problem& p, newton_result r, double step, double max_step, Stage stage, Ends ends) {
  std::size_t total = r.iterations;
  double s = 0;
  while (r.converged && s < 1) {
    const double s_next = std::min(1.0, s + step);
    problem q = stage(s_next);
    auto t = newton(q, r.x);
    total += t.iterations;
    if (t.converged) {
      r = std::move(t);
      s = s_next;
      step = std::min(max_step, 1.5 * step);
    } else if (ends(t, s_next, step)) {
      r = std::move(t);
      r.converged = false;
    } else {
      step /= 2;
      continue;
    }
    p = std::move(q);
    if (!r.converged) break;
  }
  r.iterations = total;
  return r;
}

/// scene::body, when Newton from the isolated contacts fails (typically one indentor set much
/// higher than the others): continuation in the heights, from all at one level (height factor 0)
/// to theirs, each Newton solve starting from the last; the contact of an indentor that the rising
/// heights lift off vanishes on the way (newton_result::lost).
newton_result height_continuation(problem& pb, const edges& isolated) {
  problem p = pb;
  p.height_factor = 0;
  newton_result r = continue_to_one(
      p, attempt(p, isolated), 0.25, 0.5,
      [&](double s) {
        problem q = p;  // the last stage solved (attempt's at s = 0: its load factor)
        q.height_factor = s;
        return q;
      },
      [](const newton_result& t, double, double step) { return t.lost.has_value() || step < 1e-3; });
  pb = p;
  return r;
}

/// A seeded start (contact_set.cpp: the edges of a coarse boundary-element solve) from which
/// Newton failed: the Newton homotopy F(x) - (1 - s) F(x0) = 0 from s = 0 (solved by the start
/// x0) to s = 1, each stage's Newton from the last solution (continue_to_one; offset_failures
/// failed stages in all end it). WHY: the seeds'
/// edges are known to a panel, so a light contact's level row can start at ~40 of its unit
/// (self-affine profile, 4000 samples, 35 contacts); Newton's first step from there shrank it to
/// nothing ("a contact vanishes"), while the path in s keeps every stage near its start. The
/// limit: a path that stalls near s = 1 (a contact set that is not the physical one: 35
/// contacts of a 16000-sample profile, stages of 1e-3 in s failing for 60 s) is left to the search.
constexpr std::size_t offset_failures = 4;

newton_result offset_continuation(problem& pb, const edges& start) {
  problem p = pb;
  p.load_factor = 1;
  newton_result r;
  r.x = start;
  try {
    p.offset = edge_conditions(p, start);
  } catch (const std::exception& e) {
    r.failure = e.what();
    r.residual = std::numeric_limits<double>::infinity();
    return r;
  }
  r.converged = true;  // x0 solves the stage s = 0
  const Eigen::VectorXd full = p.offset;
  const double requested = pb.accuracy;
  std::size_t failures = 0;
  r = continue_to_one(
      p, std::move(r), 0.25, 1.0,
      [&](double s) {
        problem q = p;
        q.offset = (1 - s) * full;
        q.accuracy = s < 1 ? std::max(requested, continuation_accuracy) : requested;  // a stage only starts the next
        return q;
      },
      [&](const newton_result& t, double s, double) {
        return t.merged.has_value() || (t.lost.has_value() && s == 1) || ++failures > offset_failures ||
               pb.cx->out_of_time();
      });
  p.offset = Eigen::VectorXd();
  p.accuracy = requested;
  pb = p;
  return r;
}

/// Independent indentors of unequal loads, when the other starts failed: continuation in the
/// loads' ratios, from every load equal to the largest (weights w_i = (P_max/P_i)^(1 - s) at s = 0)
/// to the scene's (s = 1), each stage's Newton starting from the last solution, its contacts
/// rescaled to the new loads. WHY: a light contact next to a heavy one sits on the surface the
/// heavy one shaped, far from where its isolated contact would be; the continuation in the load
/// (attempt) scales both together and keeps that mismatch at every stage (measured: parabolas
/// R = 1 at alpha 0.4, loads 1 and 0.01, apexes 0.4 apart: not_converged; with loads 1 and 0.03,
/// ok from the isolated contacts in 0.9 s; 0.01 from 0.03's solution converges).
newton_result ratio_continuation(problem& pb, const edges& isolated) {
  const auto& st = *pb.st;
  double top = 0;
  for (const auto& s : st) top = std::max(top, s.target_load);
  std::vector<double> ratio(st.size());
  for (std::size_t i = 0; i < st.size(); ++i) ratio[i] = top / st[i].target_load;
  const auto weights = [&](double s) {
    std::vector<double> w(st.size());
    for (std::size_t i = 0; i < st.size(); ++i) w[i] = std::pow(ratio[i], 1 - s);
    return w;
  };
  problem p = pb;
  p.load_weights = weights(0);
  newton_result r = attempt(p, rescaled(p, isolated, p.load_weights));
  std::size_t total = r.iterations;
  double s = 0, step = 0.25;
  const double requested = pb.accuracy;
  while (r.converged && s < 1) {
    problem q = p;
    const double s_next = std::min(1.0, s + step);
    q.load_weights = weights(s_next);
    q.accuracy = s_next < 1 ? std::max(requested, continuation_accuracy) : requested;  // a stage only starts the next
    std::vector<double> change(st.size());
    for (std::size_t i = 0; i < st.size(); ++i) change[i] = q.load_weights[i] / p.load_weights[i];
    edges guess = rescaled(q, r.x, change);
    if (gap_ratio(q, guess) <= 0) guess = r.x;  // the predictor would overlap: corrector only
    auto t = newton(q, guess);
    total += t.iterations;
    if (t.converged) {
      r = std::move(t);
      p = std::move(q);
      s = s_next;
      step = std::min(0.5, 1.5 * step);
    } else if (t.merged || step < 1.0 / 64) {
      r = std::move(t);
      p = std::move(q);
      break;
    } else {
      step /= 2;
    }
  }
  r.iterations = total;
  if (s < 1) r.converged = false;
  p.load_weights.clear();
  p.accuracy = requested;
  pb = std::move(p);
  return r;
}

/// The projection of the boundary-layer poles (contact_density::absorb_layer) into the reported
/// series: its degree grows like sqrt(L/gap), up to 2^15 for contacts 1e-7 L apart, and its cost
/// and the report's (surface moments, mean slope and gap checks at that degree) like the square:
/// measured ~5 s a contact at degree 32767 (three parabolas closing to 4e-7 L at alpha 0.6).
/// A result that is not ok anyway (not converged, or out of time) is projected coarsely, at most
/// to coarse_degree; with a time limit the degree is capped so that the estimated cost,
/// seconds_per_degree_squared n^2 a contact, fits in the time left. What a cap leaves out and the
/// projection's measured error join the error estimate, so a capped result is never ok unless
/// its estimate still meets the acceptance.
constexpr double coarse_projection = 1e-4;
constexpr std::size_t coarse_degree = 1024;
constexpr double seconds_per_degree_squared = 5e-9;

std::size_t projection_degree(const context& cx, std::size_t contacts) {
  const double left = cx.seconds_left();
  if (!std::isfinite(left)) return contact_density::max_absorbed_degree;
  const double n = std::sqrt(std::max(left, 0.0) / (seconds_per_degree_squared * static_cast<double>(contacts)));
  return static_cast<std::size_t>(std::clamp(n, double(coarse_degree), double(contact_density::max_absorbed_degree)));
}

/// `pb` with every contact in the bounded class (no load imposed).
problem bounded_form(problem pb) {
  pb.loaded.assign(pb.loaded.size(), false);
  return pb;
}

/// After `result` failed: `run` on `other` (a variant of pb); the variant and its result replace
/// pb and result when better(second, first) says so. The iterations of both count.
template <class Run, class Better>
void retry(problem& pb, newton_result& result, problem other, Run run, Better better) {
  if (pb.cx->out_of_time()) return;  // a retry would return at once with nothing to compare
  auto second = run(other);
  second.iterations += result.iterations;
  second.jacobians += result.jacobians;
  if (better(second, result)) {
    result = std::move(second);
    pb = std::move(other);
  }
}

/// scene::body, a contact vanished: which indentor would carry no load. The contact that shrank
/// in the iteration need not be that indentor's (Newton from an equal split can wander), so it is
/// named by the physical criterion: at the equal split (st's isolated contacts, their action on
/// one another included) the indentor with the highest level approach + height is the one that
/// must shed load (measured: alpha 0.6, a parabola ahead of a wedge on one body: the iteration
/// shrank the parabola, the boundary-element oracle lifts the wedge off, which is the highest).
std::string lost_contact_message(const std::vector<indentor_state>& st, const context& cx, std::size_t& i) {
  std::vector<contact_density> start(st.size());
  for (std::size_t k = 0; k < st.size(); ++k) start[k] = st[k].g;
  const auto level = body_levels(st, start, cx, 1.0);
  i = static_cast<std::size_t>(std::max_element(level.begin(), level.end()) - level.begin());
  return "a contact vanishes in the iteration: at this body load and these heights an indentor would carry no "
         "load, which is not solved; by the levels at an equal share of the load it is " +
         indentor_name(st[i].scene_index, *st[i].source) + " (lower it, or remove it from the scene)";
}

/// Whether a contact is iterated with its load imposed: a smooth contact whose own data has no
/// step (parabola, general profile without corners), below the boundary.
/// WHY: in the bounded class the load of each contact is an output of its edges, so moving one
/// edge changes that contact's load and thus its action on every other contact, which decays only
/// like distance^(alpha - 1) (a monopole): the Jacobian is dense, and its banded (coloured)
/// approximation converges linearly (rows of parabolas 1.5 L apart at alpha = 0.3: 25 Newton
/// iterations for 10, 39 for 20, 56 for 40). With the loads imposed, moving an edge changes a
/// contact's action only by a dipole, ~ distance^(alpha - 2), and the banded Jacobian is nearly
/// exact: 13, 16 and 21 iterations (studies/results/multi_contact.log). A wedge (its apex enrichment) and a split wedge keep the
/// bounded class.
bool loaded_form(const indentor_state& s, role r, const context& cx, bool body, std::size_t contacts) {
  if (body) return false;  // the loads are unknowns
  // Up to full_width contacts the Jacobian is complete either way, and the bounded class is the
  // more robust for nearly touching contacts (two parabolas at gap 0.01 L, alpha 0, beta 0.3: ok
  // in 0.5 s bounded; loads imposed, the iteration closed the gap).
  if (contacts <= full_width) return false;
  // The class singular at both edges exists (gam = -(1 + 2 alpha + beta)/2 > -1) only below the
  // boundary alpha + beta/2 = 1/2.
  if (r != role::smooth_both || cx.offset >= -boundary_width) return false;
  if (s.k == kind::parabola) return true;
  return s.k == kind::general && std::get<general_profile>(s.source->shape).corners.empty();
}

/// Whether every indentor is a parabola (coarse_bodies' shapes).
bool parabolas_only(const std::vector<indentor_state>& st) {
  return std::all_of(st.begin(), st.end(), [](const indentor_state& s) { return s.k == kind::parabola; });
}

/// A seeded body's loads-imposed start is solved to this accuracy (edge steps below 10x it,
/// relative to a contact): only a start for the body's iteration, which polishes it.
constexpr double preload_accuracy = 1e-4;

/// A seeded body (a sampled profile's round) of more than full_width smooth contacts whose seeds
/// all carry their own loads (indentor_state::seed_load): the edges of the contacts with those
/// loads imposed (the loaded form, as independent indentors: loaded_form), Newton from the seeds
/// to preload_accuracy; none when the seeds already meet that, when a contact has no loaded form
/// or no seed load, or when the iteration fails. `iterations` and `jacobians` gain its own.
/// WHY: the coarse solve's edges are known to a panel, and for a contact narrower than a sample a
/// panel is a large part of its length: its level condition starts tens to hundreds of its units
/// off (1e5-sample periodic profile, 233 seeds: largest condition 242), the step limit shortens
/// every step to a few percent, and the body's iteration starved real contacts (3 rounds lost one
/// each, 443 seeds: 8 rounds, then a stall and not_converged after 400 s). With the loads imposed
/// the contacts are nearly independent (a moved edge acts on the others by a dipole), the coloured
/// Jacobian is nearly exact, and each contact's edges come to fit its coarse load: 10 iterations,
/// after which the body's iteration converged in 9 (233 seeds) and 11 (443) with every seed kept.
std::optional<edges> loads_imposed_start(const problem& pb, const edges& seeds, std::size_t& iterations,
                                         std::size_t& jacobians) {
  const auto& st = *pb.st;
  if (st.size() <= full_width) return std::nullopt;
  problem pre = pb;
  pre.body_load.reset();
  pre.stall_floor = 0;
  pre.tree = std::make_shared<far_tree>();  // the body's problem keeps its own
  for (std::size_t i = 0; i < st.size(); ++i) {
    pre.loaded[i] = loaded_form(st[i], pb.roles[i], *pb.cx, false, st.size());
    if (!pre.loaded[i] || !st[i].seed_load || !(st[i].target_load > 0)) return std::nullopt;
  }
  pre.accuracy = std::max(pb.accuracy, preload_accuracy);
  try {  // seeds that already meet the loads-imposed conditions (a converged round's): as they are
    if (edge_conditions(pre, seeds).lpNorm<Eigen::Infinity>() <= pre.accuracy) return std::nullopt;
  } catch (const std::domain_error&) {  // the seeds cannot be evaluated: the body's iteration says why
    return std::nullopt;
  } catch (const merge_error&) {
    return std::nullopt;
  }
  const newton_result r = newton(pre, seeds);
  iterations += r.iterations;
  jacobians += r.jacobians;
  if (!r.converged) return std::nullopt;
  return r.x;
}

/// The problem of st (roles, splits, loaded forms, starting lengths; a seeded one's floor and
/// accuracy) and its starting edges `isolated`: a seeded contact's seed, else the isolated
/// contact's solution (solve_isolated, which sets st[i].g).
problem set_up(std::vector<indentor_state>& st, const context& cx, std::optional<double> body_load,
               std::shared_ptr<jacobian_memo> memo, edges& isolated) {
  problem pb;
  pb.st = &st;
  pb.cx = &cx;
  pb.body_load = body_load;
  pb.memo = std::move(memo);
  // Seeded contacts (a sampled profile's): their series converge algebraically across the spline's
  // knots, and their conditions have a floor there. WHY: 16000-sample self-affine profile, seed 3,
  // load 2e-3, degree 1024 from the contacts solved at 512: the largest condition 5.8e-7 at the
  // start, no step descended from it, and the retries spent 55 s (the residual of (8) there: 5.1e-7,
  // within the acceptance 1e-6).
  pb.seeded = any_seeded(st);
  if (pb.seeded) {
    pb.stall_floor = cx.options.acceptance;
    pb.accuracy = std::max(cx.options.tolerance, (cx.ladder ? ladder_accuracy : seeded_accuracy) * cx.options.acceptance);
  }
  for (auto& s : st) {
    s.solved.reset();  // set by hand_back for a result in the boundary-layer basis
    pb.roles.push_back(role_of(s, cx));
    if (s.seed && s.k == kind::general) {
      // A seeded start (contact_set.cpp): its edges instead of the isolated contact's.
      isolated.a.push_back(s.seed->first);
      isolated.b.push_back(s.seed->second);
      s.g.set_interval(s.seed->first, s.seed->second);
    } else {
      solve_isolated(s, cx);  // the isolated contact: the start (its closed-form paths)
      isolated.a.push_back(s.g.a());
      isolated.b.push_back(pb.roles.back() == role::line_load ? s.g.a() : s.g.b());
    }
    int split = 0;
    if (s.k == kind::wedge && pb.roles.back() == role::smooth_both && s.epsilon) {
      const double e = *s.epsilon, one_minus_e = (s.g.b() - s.apex) / s.g.length();
      if (one_minus_e * 1e14 < 1) {
        // The isolated contact ends at the apex to double precision (solve_wedge): so does this one.
        pb.roles.back() = role::apex_ended;
      } else if (cx.options.wedge_apex_split && std::min(e, one_minus_e) < 0.25) {
        split = one_minus_e <= e ? 1 : -1;
      }
    }
    pb.split.push_back(split);
    pb.loaded.push_back(loaded_form(s, pb.roles.back(), cx, body_load.has_value(), st.size()));
  }
  for (std::size_t i = 0; i < st.size(); ++i) pb.start_length.push_back(isolated.b[i] - isolated.a[i]);
  return pb;
}

/// Whether any of a problem's per-contact flags (problem::loaded, problem::split) is set.
template <class Flags>
bool any_set(const Flags& flags) {
  return std::any_of(flags.begin(), flags.end(), [](auto v) { return v != 0; });
}

/// Newton from the start, then the retries in turn while it fails, each kept when it does better
/// (retry): pb ends as the variant whose result is returned, with the densities of a loaded form
/// re-solved in the bounded class.
newton_result solve_with_retries(problem& pb, const edges& isolated) {
  const auto& st = *pb.st;
  const auto& cx = *pb.cx;
  const bool seeded = pb.seeded;
  auto again = [&](problem& p) { return attempt(p, isolated); };
  // A seeded body: from the edges that carry the seeds' loads (loads_imposed_start), and when the
  // iteration from there stalls, from the seeds themselves. WHY the latter: a 1000-sample periodic
  // profile (seed 3, load 3e-3, 17 contacts) stalled at its first step from the loads-imposed
  // edges (largest condition 1.5e-4, a contact's series capped at degree 128) and converged from
  // the seeds in 9 iterations.
  std::size_t preload_iterations = 0, preload_jacobians = 0;
  const auto start =
      seeded && pb.body_load ? loads_imposed_start(pb, isolated, preload_iterations, preload_jacobians) : std::nullopt;
  newton_result result = attempt(pb, start ? *start : isolated);
  result.iterations += preload_iterations;
  result.jacobians += preload_jacobians;
  pb.read_memo = false;  // (the retries below copy pb)
  // A seeded body whose iteration failed after it kept a starving contact (spare_light, far from
  // the solution: coupled_newton.cpp, trusted_residual): again from the same start,
  // every starving contact dropped (problem::starve_untrusted); kept when it converged or dropped
  // one. WHY: a contact kept there can stall the iteration at a large condition on its level.
  if (seeded && pb.body_load && !result.converged && !result.merged && !result.lost && result.spared) {
    problem eager = pb;
    eager.starve_untrusted = true;
    retry(pb, result, std::move(eager), [&](problem& p) { return attempt(p, start ? *start : isolated); },
          [](const newton_result& second, const newton_result&) { return second.converged || second.lost; });
  }
  if (start && !result.converged && !result.merged && !result.lost)
    retry(pb, result, pb, again, [](const newton_result&, const newton_result&) { return true; });
  // Seeded contacts whose series cannot reach the acceptance at this degree: no retries.
  const bool capped = seeded && !result.converged && series_capped(result.sol, cx);
  // The loads-imposed iteration failed (or saw contacts merge): again in the bounded class.
  if (!result.converged && any_set(pb.loaded))
    retry(pb, result, bounded_form(pb), again,
          [](const newton_result& second, const newton_result& first) { return second.converged || !first.merged; });
  // A seeded start from which Newton failed: the homotopy from the seeds' own conditions.
  if (seeded && !result.converged && !result.merged && !capped)
    retry(pb, result, pb, [&](problem& p) { return offset_continuation(p, isolated); },
          [](const newton_result& second, const newton_result&) { return second.converged; });
  // A rigid body's coloured Jacobian (body_far_model) failed: again with every column differenced.
  if (!result.converged && !result.merged && !result.lost && !capped && body_colouring(pb)) {
    problem full = pb;
    full.full_jacobian = true;
    retry(pb, result, std::move(full), again, [](const newton_result& second, const newton_result&) {
      return second.converged || second.lost.has_value();
    });
  }
  // A rigid body from an equal split failed: continuation in the heights (which finds a lost contact).
  const bool uneven = std::any_of(st.begin(), st.end(), [&](const indentor_state& s) { return s.height != st[0].height; });
  if (pb.body_load && !result.converged && !result.merged && !capped && uneven)
    retry(pb, result, pb, [&](problem& p) { return height_continuation(p, isolated); },
          [](const newton_result& second, const newton_result&) { return second.converged || second.lost.has_value(); });
  // A split wedge whose apex left its contact (its contact moved onto one face) or that did not
  // converge: again with the plain forms, which take any position of the apex.
  if (!result.converged && !result.merged && any_set(pb.split)) {
    problem plain = pb;
    plain.split.assign(plain.split.size(), 0);
    retry(pb, result, std::move(plain), again, [](const newton_result& second, const newton_result& first) {
      return second.converged || second.residual < first.residual;
    });
  }
  // Independent parabolas that no continuation reached: a start from the coarse solve of all
  // of them on one grid (coarse_bodies.hpp), which needs no path in the load; Newton from there at
  // the full loads. Nothing when that solve sees the contacts touch (a merge stands).
  if (!pb.body_load && !result.converged && !result.lost && st.size() > 1 && parabolas_only(st) && !cx.out_of_time()) {
    std::vector<std::pair<double, double>> from;
    for (std::size_t i = 0; i < st.size(); ++i) from.emplace_back(isolated.a[i], isolated.b[i]);
    if (const auto coarse = coarse_bodies(st, from, cx)) {
      edges coarse_start;
      for (const auto& [a, b] : *coarse) coarse_start.a.push_back(a), coarse_start.b.push_back(b);
      // Kept when it converged, or when it stalled nearer to it than the continuations got (a
      // light contact's edge conditions may stall at ~1e-10 from a start whose edges are a panel
      // off: that state, not_converged with its residuals, is closer to the answer than a merge
      // met on the way).
      retry(pb, result, pb, [&](problem& p) { p.load_factor = 1; return newton(p, coarse_start); },
            [](const newton_result& second, const newton_result& first) {
              return second.converged || (!second.merged && second.residual < first.residual);
            });
    }
  }
  // Independent indentors of unequal loads: continuation in the loads' ratios (also after a merge,
  // which the continuation in the load can meet on its way with the ratios kept).
  const auto unequal = std::any_of(st.begin(), st.end(), [&](const indentor_state& s) { return s.target_load != st[0].target_load; });
  if (!pb.body_load && !result.converged && !result.lost && unequal)
    retry(pb, result, pb, [&](problem& p) { return ratio_continuation(p, isolated); },
          [](const newton_result& second, const newton_result&) { return second.converged; });
  if (any_set(pb.loaded) && !result.sol.g.empty()) {
    // The reported densities in the bounded class (the iteration's are bounded only to the
    // tolerance of its intensity conditions, and their edge exponents would be the singular ones).
    try {
      result.sol = solve_fixed(bounded_form(pb), result.x.a, result.x.b);
    } catch (const std::exception& e) {
      if (result.converged) result.failure = e.what();
      result.converged = false;
    }
  }
  return result;
}

/// The outcome's code, message and counts from the iteration's result.
coupled_outcome outcome_of(const problem& pb, const newton_result& result) {
  const auto& st = *pb.st;
  coupled_outcome out;
  out.iterations = result.iterations;
  out.jacobians = result.jacobians;
  out.union_degree = result.sol.degree;
  if (!result.converged && result.lost) {
    out.code = status_code::contact_lost;
    std::size_t named = 0;
    if (pb.seeded) {
      // From seeds (a sampled profile's coarse contacts, near the physical ones) the
      // contact that shrank is the one named; the equal split's levels mean nothing there (the
      // seeds' densities are not solved), and naming by them dropped the same real contact
      // round after round (16000-sample profile: 9 of 17 rounds).
      named = *result.lost;
      out.message = "a contact vanishes in the iteration: at this body load and these heights " +
                    indentor_name(st[named].scene_index, *st[named].source) + " would carry no load";
    } else {
      out.message = lost_contact_message(st, *pb.cx, named);
    }
    out.lost = named;
  }
  if (!result.converged && out.code == status_code::ok) {
    std::ostringstream os;
    os.precision(3);
    if (result.merged) {
      out.code = status_code::contacts_merge;
      out.merged = result.merged;
      os << result.failure;
    } else {
      out.code = status_code::not_converged;
      os << "coupled edge iteration did not converge: " << (result.failure.empty() ? "iteration limit" : result.failure);
      if (std::isfinite(result.residual)) {
        os << "; largest edge condition " << result.residual;
        if (!result.worst.empty()) os << " (" << result.worst << ")";
      }
    }
    if (pb.load_factor < 1) os << " (at " << pb.load_factor << " of the loads)";
    out.message = os.str();
  }
  return out;
}

/// Moves the solved densities into st (pb's states; projected onto a Jacobi series, their loads
/// the solved shares on a body) and marks a correction that did not converge in out. Whatever was
/// reached is handed back (with a non-ok code when it did not converge), unless the solve was
/// interrupted: then nothing is (each contact's projection takes seconds for contacts nearly
/// touching, and checks nothing inside; the caller wants none of it).
void hand_back(std::vector<indentor_state>& st, const problem& pb, newton_result& result, coupled_outcome& out) {
  const auto& cx = *pb.cx;
  if (result.sol.g.empty()) return;
  for (std::size_t i = 0; i < st.size(); ++i) {
    cx.throw_if_interrupted("rhabel::punch::solve", true);
    st[i].g = std::move(result.sol.g[i]);
    // The report, fields and surface take a Jacobi series (and apex): the layer joins the series;
    // the residual of (8) is evaluated on the density as solved. The projection's measured error
    // joins the error estimate, which an ok status needs within the acceptance: projected to a
    // tenth of it at least (at tolerance 1e-8, to the acceptance's default 1e-9, every scene of
    // gap 1e-3 L in study_multi_contact came back not_converged).
    if (!st[i].g.layer.empty()) st[i].solved = st[i].g;
    // Not ok anyway (not converged, out of time): coarsely (see coarse_projection).
    if (!result.converged || cx.out_of_time())
      st[i].g.absorb_layer(coarse_projection, coarse_degree);
    else
      st[i].g.absorb_layer(std::min(cx.options.tolerance, 0.1 * cx.options.acceptance),
                           projection_degree(cx, st.size() - i));
    if (pb.body_load) st[i].target_load = st[i].g.integral();  // the solved share (checked by the caller)
    st[i].friction.reset();
    st[i].rh_unit.reset();
    st[i].status = "ok";
    if (st[i].k == kind::wedge && !st[i].g.line_load) st[i].epsilon = (st[i].apex - st[i].g.a()) / st[i].g.length();
  }
  cx.throw_if_interrupted("rhabel::punch::solve", true);  // the report's own cost is next
  if (!result.sol.correction_converged && out.code == status_code::ok) {
    std::ostringstream os;
    os.precision(3);
    os << "coupling correction not converged at up to " << result.sol.degree << " points a contact (residual "
       << result.sol.correction_residual << " of the data)";
    out.code = status_code::not_converged;
    out.message = os.str();
  }
}

}  // namespace
}  // namespace coupled

coupled_outcome solve_coupled(std::vector<indentor_state>& st, const context& cx, std::optional<double> body_load,
                              std::shared_ptr<coupled::jacobian_memo> memo) {
  using namespace coupled;
  edges isolated;
  problem pb = set_up(st, cx, body_load, std::move(memo), isolated);
  newton_result result = solve_with_retries(pb, isolated);
  coupled_outcome out = outcome_of(pb, result);
  hand_back(st, pb, result, out);
  return out;
}

}  // namespace rhabel::punch::detail
