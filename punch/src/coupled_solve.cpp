// Several contacts at once: paper system (41). See internal.hpp for where this sits.
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
//     separated contacts act on one another through abel's far field (abel/detail/far_field.hpp,
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
// t = 1 only to continuation_accuracy.
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
// once and Broyden's updates enter by the Woodbury identity (abel/detail/broyden_matrix.hpp).
//
// A RIGID BODY (scene::body). The loads are unknowns and the heights of the indentors are given:
// every contact keeps its first condition (d_j = 0 or its split-form intensity), and its second
// becomes the total load (contact 0) or equal levels approach_j + height_j = approach_(j-1) +
// height_(j-1) (the others), approach_j = w - f_j on the contact from the surface displacement of
// surface.hpp. The start is an equal split of the load; when Newton fails from there, continuation
// in the height differences (0 to 1). A contact that shrinks below vanishing_length of its start
// is status_code::contact_lost: its indentor would carry no load. The Jacobian: with more than
// full_width smooth contacts, coloured as above, and the far entries, which the loads' monopoles
// make large, from a model of a unit load's action (body_far_model): 2 full_width evaluations
// instead of 2 N (50 cosine bumps, 29 contacts: the last round 0.55 s instead of 1.3 s). When
// that iteration fails, again with every column differenced.
//
// OUTCOMES. Converged: every edge step below 10 tolerance L. A gap that closes (below 1e-12 of the
// smaller contact) is status_code::contacts_merge with the two contacts named, and so is a flat run
// (steps that no longer lower the conditions; see flat_gain) that ends with two neighbours closing
// under flat_merge_gap of a length; any other stalled iteration, and one stopped by
// solve_options::time_limit, is status_code::not_converged with its residuals. The caller
// (contact.cpp) then checks the result independently (residual of (8), sign of the pressure, loads)
// before it says ok.
#include "internal.hpp"
#include "parallel.hpp"
#include "surface.hpp"

#include "rhabel/abel.hpp"
#include "rhabel/abel/detail/broyden_matrix.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <sstream>
#include <utility>
#include <variant>
#include <stdexcept>
#include <vector>

namespace rhabel::punch::detail {

namespace {

/// How a contact enters the coupled system.
enum class role {
  smooth_both,  ///< nu = -1: both edges smooth and unknown (parabola, general profile, wedge below)
  apex_ended,   ///< nu = 0: wedge on/above the boundary, trailing edge at the apex, leading unknown
  fixed_faces,  ///< nu = +1: flat punch below the boundary, corners fixed, load imposed
  line_load,    ///< flat punch on/above the boundary: line load at the leading corner
};

role role_of(const indentor_state& st, const context& cx) {
  const bool above = cx.offset >= -boundary_width;
  switch (st.k) {
    case kind::flat: return above ? role::line_load : role::fixed_faces;
    case kind::wedge: return above ? role::apex_ended : role::smooth_both;
    default: return role::smooth_both;
  }
}

int nu_of(role r) {
  switch (r) {
    case role::smooth_both: return -1;
    case role::apex_ended: return 0;
    default: return 1;
  }
}

/// Contact length ~ load^(1/p): p = 2 - alpha (parabola, general), 1 - alpha (wedge).
double load_exponent(const indentor_state& st, const context& cx) {
  return st.k == kind::wedge ? 1 - cx.alpha : 2 - cx.alpha;
}

/// Two contacts met (their gap closed): who and where.
struct merge_error : std::runtime_error {
  std::size_t first, second;
  merge_error(std::size_t i, std::size_t j, const std::string& what) : std::runtime_error(what), first(i), second(j) {}
};

// ---------------------------------------------------------------------------------------------
// The particular solution of one contact alone.

struct particular {
  contact_density g;
  double defect = 0;  // nu = -1: A g = F - h^alpha defect on the contact (abel's normalisation)
};

/// F of the class e on [a, b] without the apex enrichment: spectral (abel::solve) when no step lies
/// inside, else the projection with the steps' coefficients in closed form, adaptive in the smooth
/// part's tail.
particular series_particular(double a, double b, const edge_exponents& e, const forcing& F, const context& cx,
                              double load = 0) {
  const std::size_t max_degree = std::max<std::size_t>(cx.options.max_degree, 8);
  bool step_inside = false;
  for (const auto& [position, jump] : F.steps) step_inside = step_inside || (position > a && position < b);
  particular out;
  const abel::abel_operator<double> op(cx.par, a, b);
  if (!step_inside) {
    abel::solve_options<double> o;
    o.residual_points = 0;
    o.tolerance = cx.options.tolerance;
    o.max_degree = max_degree + 1;
    const auto smooth = F.smooth;
    const auto steps = F.steps;
    auto sol = abel::solve(op, leading_edge(e.nu), trailing_edge(e.nu), [&](double s) {
      double v = smooth ? smooth(s) : 0.0;
      for (const auto& [position, jump] : steps)
        if (s > position) v += jump;
      return v;
    }, o);
    out.g.jacobi = e.nu == 1 ? sol.with_load(load) : std::move(sol.density);
    out.g.nu = e.nu;
    out.g.tail = sol.coefficient_tail;
    out.defect = e.nu == -1 ? sol.solvability_defect : 0.0;
    return out;
  }
  for (std::size_t M = 8;; M = std::min(2 * M, max_degree)) {
    const auto img = image_coefficients(a, b, e, F, M);
    if (img.tail <= cx.options.tolerance || M >= max_degree) {
      out.g = density_from_image(a, b, cx.par, e, img);
      out.defect = e.nu == -1 ? img.d[0] * std::pow(op.half_length(), -cx.alpha) : 0.0;
      return out;
    }
  }
}

/// The split form of a wedge on [a, b] (see problem::split), its series in the class nu = 0 singular
/// at the near edge; the correction then lives in that class too.
particular split_particular(const indentor_state& st, const context& cx, double a, double b, int near) {
  const auto& w = std::get<wedge>(st.source->shape);
  const double L = b - a;
  if (!(st.apex > a && st.apex < b))
    throw std::domain_error("the apex of " + indentor_name(st.scene_index, *st.source) +
                            " left its contact during the coupled iteration");
  particular out;
  out.g = build_wedge_near_edge((st.apex - a) / L, (b - st.apex) / L, cx, w.slope_leading / cx.gamma_factor,
                                -w.slope_trailing / cx.gamma_factor, near);
  out.g.scale(std::pow(L, -cx.alpha));  // g_L(t) = L^-alpha g_1((t - apex)/L)
  out.g.set_interval(a, b);
  return out;
}

particular solve_particular(const indentor_state& st, const context& cx, role r, double a, double b, double load,
                            bool loaded) {
  particular out;
  if (loaded) return series_particular(a, b, cx.exponents(1), own_forcing(st, cx), cx, load);
  if (r == role::line_load) {
    out.g.jacobi.lo = out.g.jacobi.hi = a;
    out.g.line_load = true;
    out.g.line_weight = load;
    return out;
  }
  const edge_exponents e = cx.exponents(nu_of(r));
  if (r == role::fixed_faces) {
    // A flat face: F = 0, so the particular is the homogeneous solution w (A w = 0) carrying the
    // whole load, c_0 = load / (h int w); the correction then carries no net load, and its data
    // (the others' action, the neighbours' including this load's) is never identically zero.
    const double h0 = quadrature::jacobi_norm_squared<double>(0, e.del, e.gam);
    out.g.jacobi = {a, b, e.gam, e.del, {load / ((b - a) / 2 * h0)}};
    out.g.nu = 1;
    return out;
  }
  const forcing F = own_forcing(st, cx);
  const double L = b - a;
  if (st.k == kind::wedge && r == role::smooth_both && cx.options.wedge_apex_split && st.apex - a > enrich_limit * L &&
      b - st.apex > enrich_limit * L) {
    out.g = build_wedge_step(a, b, st.apex, -1, cx, F, &out.defect);
    return out;
  }
  return series_particular(a, b, e, F, cx);
}

// ---------------------------------------------------------------------------------------------
// The action of one contact's density at points of another (disjoint) interval [lo, hi].

class cross_field {
 public:
  cross_field(const contact_density& g, const abel::abel_parameters<double>& par, double lo, double hi)
      : g_(&g), par_(par), right_of_(g.a() > hi) {
    if (g.line_load) return;
    const double gap = right_of_ ? g.a() - hi : lo - g.b();
    // abel's cross-term nodes, graded toward the end facing [lo, hi] at the TRUE gap (no floor);
    // [lo, hi] at least a half-length of g away (gap >= h): one panel, whose node count
    // abel::detail::separated_cross_nodes takes from the separation (the kernel's analyticity
    // ellipse; eps/100 relative), n/2 + 20 for neighbours one half-length apart, n/2 + 7 far away.
    const std::size_t n = g.jacobi.coefficients.size();
    std::size_t count = std::max<std::size_t>(n / 2 + 24, 32);
    if (const std::size_t separated = abel::detail::separated_cross_nodes(gap / g.jacobi.half_length(), n); separated > 0)
      count = std::min(count, separated);
    nodes_ = abel::detail::make_cross_nodes(g.jacobi, gap, right_of_, count);
    const auto series = g.jacobi.series_evaluator();
    weighted_.resize(nodes_.x.size());
    for (std::size_t q = 0; q < nodes_.x.size(); ++q) weighted_[q] = nodes_.weight[q] * series(nodes_.x[q]);
    if (g.has_apex) op_ = std::make_unique<abel::abel_operator<double>>(par, g.a(), g.b());
  }
  double operator()(double s) const {
    if (g_->line_load) return g_->line_weight * abel::detail::cross_kernel(par_, g_->a() - s);
    double sum = 0;
    for (std::size_t q = 0; q < weighted_.size(); ++q) {
      // t - s from the distances to the facing end (no cancellation).
      const double t_minus_s = right_of_ ? nodes_.t_minus_lo[q] + (g_->a() - s) : -(nodes_.hi_minus_t[q] + (s - g_->b()));
      sum += weighted_[q] * abel::detail::cross_kernel(par_, t_minus_s);
    }
    if (op_) sum += abel::apply(*op_, g_->apex, s);
    return sum;
  }

 private:
  const contact_density* g_;
  abel::abel_parameters<double> par_;
  bool right_of_;
  abel::detail::cross_nodes<double> nodes_;
  std::vector<double> weighted_;
  std::unique_ptr<abel::abel_operator<double>> op_;
};

// ---------------------------------------------------------------------------------------------
// The coupled linear solve for given edges.

/// From this many contacts on: the union's collocation system by block-preconditioned GMRES
/// (abel/detail/block_gmres.hpp) with its far part and the particulars' far action through the far
/// field (abel/detail/far_field.hpp).
constexpr std::size_t iterative_from = 6;

/// The far field's tree (its boxes, admissible pairs and their kernel matrices, which are most of a
/// build's cost: p^2 powers a pair) kept across the evaluations of one problem: built on the
/// contacts widened by box_margin of their length on each side (at most a quarter of the gap to a
/// neighbour), and built again only when a contact leaves its box. Each evaluation takes the far
/// field of its own intervals from it by the exact re-expansion of
/// far_field(boxes, intervals): the Jacobian's differences (steps of 1e-7 of a contact) and the
/// last Newton steps share one tree (rows of 300 parabolas: the builds were 23 % of the time).
/// Shared by the Jacobian's threads; the lock guards only the lookup (a far_field is read-only).
class far_tree {
 public:
  static constexpr double box_margin = 0.05;

  std::shared_ptr<const abel::detail::far_field<double>> covering(
      const std::vector<abel::detail::far_field<double>::box>& intervals, const context& cx) {
    std::shared_ptr<const abel::detail::far_field<double>> boxes;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!boxes_ || !boxes_->covers(intervals)) boxes_ = build(intervals, cx);
      boxes = boxes_;
    }
    return std::make_shared<const abel::detail::far_field<double>>(*boxes, intervals);
  }

 private:
  static std::shared_ptr<const abel::detail::far_field<double>> build(
      const std::vector<abel::detail::far_field<double>::box>& intervals, const context& cx) {
    const double inf = std::numeric_limits<double>::infinity();
    auto boxes = intervals;
    for (std::size_t k = 0; k < intervals.size(); ++k) {
      const double margin = box_margin * (intervals[k].hi - intervals[k].lo);
      const double left = k > 0 ? (intervals[k].lo - intervals[k - 1].hi) / 4 : inf;
      const double right = k + 1 < intervals.size() ? (intervals[k + 1].lo - intervals[k].hi) / 4 : inf;
      boxes[k] = {intervals[k].lo - std::min(margin, left), intervals[k].hi + std::min(margin, right)};
    }
    return std::make_shared<const abel::detail::far_field<double>>(
        cx.par, boxes, abel::detail::far_field<double>::order_for(1e-3 * cx.options.tolerance));
  }

  std::mutex mutex_;
  std::shared_ptr<const abel::detail::far_field<double>> boxes_;
};

/// The action of the contacts' particular solutions on the other contacts through the far field:
/// each contact's moments from its Jacobi series (exact Gauss-Jacobi quadrature), the local values
/// of every contact once. A contact with an apex enrichment, and line loads (not among the
/// targets), act directly on every contact (direct()), and so do near pairs.
class particular_field {
 public:
  /// Null when the field would have nothing far (or there is no tree: too few contacts).
  static std::shared_ptr<const particular_field> build(const std::vector<contact_density>& g,
                                                       const std::vector<std::size_t>& targets,
                                                       const std::vector<abel::interval_spec<double>>& intervals,
                                                       const context& cx, far_tree* tree) {
    if (!tree || targets.size() < 2) return nullptr;
    std::vector<abel::detail::far_field<double>::box> boxes;
    for (const auto& iv : intervals) boxes.push_back({iv.lo, iv.hi});
    auto out = std::make_shared<particular_field>();
    out->field_ = tree->covering(boxes, cx);
    if (out->field_->pairs() == 0) return nullptr;
    out->target_of_.assign(g.size(), -1);
    for (std::size_t k = 0; k < targets.size(); ++k) out->target_of_[targets[k]] = static_cast<long>(k);
    std::vector<Eigen::VectorXd> W;
    for (std::size_t k = 0; k < targets.size(); ++k) {
      const auto& gi = g[targets[k]];
      out->plain_.push_back(!gi.has_apex);
      W.push_back(gi.has_apex ? Eigen::VectorXd::Zero(static_cast<Eigen::Index>(out->field_->order()))
                              : out->field_->density_moments(k, gi.jacobi));
    }
    out->local_ = out->field_->far_values(W);
    return out;
  }
  /// Whether source contact i acts on target k (index among the targets) directly.
  bool direct(std::size_t k, std::size_t i) const {
    const long t = target_of_[i];
    if (t < 0 || !plain_[static_cast<std::size_t>(t)]) return true;
    const auto& near = field_->near_leaves(k);
    return std::binary_search(near.begin(), near.end(), static_cast<std::size_t>(t));
  }
  /// The far action on target k at reference coordinate x of its interval.
  double at(std::size_t k, double x) const { return field_->interpolate(local_[k], x); }
  /// The field itself (the union solve's far part reuses it).
  const std::shared_ptr<const abel::detail::far_field<double>>& field() const { return field_; }

 private:
  std::shared_ptr<const abel::detail::far_field<double>> field_;
  std::vector<long> target_of_;
  std::vector<bool> plain_;
  std::vector<Eigen::VectorXd> local_;
};

struct fixed_solution {
  std::vector<contact_density> g;  // per state
  std::vector<double> defect;      // per state: nu = -1 defect (abel's normalisation), else 0
  std::size_t degree = 0;          // collocation points per contact of the correction (0: none)
  std::size_t poles_per_decade = 0;  // the boundary-layer route's (0: the polynomial route)
  double correction_residual = 0;  // its independent residual, relative to the original data
  bool correction_converged = true;
};

/// Scale of the data on a contact: max |f'|/Gamma(1 - alpha) at 9 points (0 for a flat face).
double data_scale(const indentor_state& st, const context& cx, double a, double b) {
  return max_slope(st, a, b) / cx.gamma_factor;
}

struct problem {
  const std::vector<indentor_state>* st = nullptr;
  const context* cx = nullptr;
  std::vector<role> roles;
  // Wedges below the boundary with the apex in an outer quarter of the isolated contact: the split
  // form (build_wedge_near_edge) in the class nu = 0 singular at the near edge (+1 trailing, -1
  // leading; 0: not split), whose condition is a vanishing intensity there instead of d_j = 0.
  std::vector<int> split;
  // Contacts solved with their load imposed (the Newton phase; see loaded_form): the class nu = +1
  // singular at both edges, the load carried by the homogeneous solution, the conditions the two
  // intensity factors. Empty or false: the bounded class nu = -1 with the solvability defect.
  std::vector<bool> loaded;
  // scene::body: the total load (units of int g); the loads are then unknowns and each contact's
  // second condition is its level (see body_conditions).
  std::optional<double> body_load;
  double height_factor = 1;          // scene::body continuation: every height times this
  bool full_jacobian = false;        // scene::body: every column differenced (no body_far_model)
  std::vector<double> start_length;  // the isolated contacts' lengths (a body's vanishing contact)
  double load_factor = 1;  // continuation: every load times this
  // ratio_continuation: contact i's load times load_weights[i] as well (empty: 1).
  std::vector<double> load_weights;
  /// The load contact i is solved for at this stage of the continuations.
  double load(std::size_t i) const {
    return load_factor * (*st)[i].target_load * (load_weights.empty() ? 1.0 : load_weights[i]);
  }
  // > 0: the correction at exactly this many points per contact, without its residual (the
  // finite differences of the Jacobian: the base point's degree, so that both sides of a
  // difference share one discretisation)
  std::size_t fixed_degree = 0;
  // With fixed_degree on the boundary-layer route: the base point's poles a decade.
  std::size_t fixed_poles_per_decade = 0;
  // The far field's tree, kept across evaluations (copies of the problem share it).
  std::shared_ptr<far_tree> tree = std::make_shared<far_tree>();
  // The degree the last adaptive evaluation needed (copies share it). The next one starts its
  // ladder one rung (x 2/3) below, so that the degree can also fall: the edges move little
  // between evaluations, and near contacts need high degrees (gap 1e-3 L: ~400 at 1e-12), which
  // the ladder from 16 reaches after 9 solves, each with its residual (measured at that gap:
  // 190 ms an evaluation from 16, 145 ms from the hint; starting AT the hint, the degree only
  // grows, and one overshoot toward a merge kept every later evaluation at the cap of 600).
  std::shared_ptr<std::atomic<std::size_t>> degree_hint = std::make_shared<std::atomic<std::size_t>>(0);
  // > the requested tolerance: the accuracy to which an evaluation solves the correction (an
  // inexact Newton step far from the solution; see newton_iteration).
  double accuracy = 0;
};

bool is_loaded(const problem& pb, std::size_t i) { return i < pb.loaded.size() && pb.loaded[i]; }

/// Two contacts next to each other along x: their gap (negative when they overlap) and the length
/// it is measured in, the shorter of the two, where a line load (no length) takes its neighbour's.
struct neighbour_pair {
  std::size_t first, second;  // first's contact lies behind second's (smaller x)
  double gap, length;
};

/// The neighbour pairs of the contacts [a_i, b_i], in the order of their leading edges.
std::vector<neighbour_pair> neighbour_pairs(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = a.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return a[i] < a[j]; });
  std::vector<neighbour_pair> out;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const std::size_t i = order[k], j = order[k + 1];
    const double Li = b[i] - a[i], Lj = b[j] - a[j];
    const double L = std::max(std::min(Li > 0 ? Li : Lj, Lj > 0 ? Lj : Li), std::numeric_limits<double>::min());
    out.push_back({i, j, a[j] - b[i], L});
  }
  return out;
}

/// Edge classes of a contact's series (and of its correction).
std::pair<abel::edge, abel::edge> series_edges(const problem& pb, std::size_t i) {
  if (is_loaded(pb, i)) return {abel::edge::unbounded, abel::edge::unbounded};
  if (pb.split[i] > 0) return {abel::edge::bounded, abel::edge::unbounded};
  if (pb.split[i] < 0) return {abel::edge::unbounded, abel::edge::bounded};
  const int nu = nu_of(pb.roles[i]);
  return {leading_edge(nu), trailing_edge(nu)};
}

/// The boundary-layer route's polynomial degree (abel's measurements: residual ~1e-12 at 24 with
/// 8 poles a decade, gaps down to 1e-6 of a length); it adapts up to twice this.
constexpr std::size_t layered_degree = 24;
constexpr std::size_t layered_poles_per_decade = 8;

/// An inexact evaluation (see newton_iteration) at this accuracy or looser takes the boundary-layer
/// route with a coarse basis: degree layered_degree / 2 (adapting up to layered_degree) and 4 poles
/// a decade, whose residual stalls at ~1e-10 of the data, about a third of the fine basis's cost.
/// Two parabolas 1e-3 L apart, alpha 0 / 0.1 / 0.5 / 0.7 / 0.9 (tolerance 1e-12): 0.39 / 0.61 /
/// 0.28 / 0.37 / 0.49 s with the fine basis throughout, 0.39 / 0.30 / 0.24 / 0.32 / 0.47 s so, the
/// same Newton iterations and edges within 1e-13 L (throwaway driver, one run each). Coarse at
/// every accuracy, tolerance 1e-12 is missed (not_converged at 5e-10).
constexpr double coarse_layered_accuracy = 1e-7;

/// Whether two neighbours of the sorted intervals are closer than `below` of the shorter: then
/// the correction is solved by abel's boundary-layer route (solve_options::layered_below).
bool nearly_touching(const std::vector<abel::interval_spec<double>>& intervals, double below) {
  for (std::size_t k = 0; k + 1 < intervals.size(); ++k) {
    const double shorter = std::min(intervals[k].hi - intervals[k].lo, intervals[k + 1].hi - intervals[k + 1].lo);
    if (intervals[k + 1].lo - intervals[k].hi < below * shorter) return true;
  }
  return false;
}

fixed_solution solve_fixed(const problem& pb, const std::vector<double>& a, const std::vector<double>& b) {
  const auto& st = *pb.st;
  const auto& cx = *pb.cx;
  const std::size_t n = st.size();
  // Order along x (by leading edge); contacts must be disjoint.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return a[i] < a[j]; });
  for (const auto& [i, j, gap, length] : neighbour_pairs(a, b)) {
    if (!(gap > 1e-12 * length)) {
      std::ostringstream os;
      os.precision(10);
      os << "the contacts of " << indentor_name(st[i].scene_index, *st[i].source) << " [" << a[i] << ", " << b[i]
         << "] and " << indentor_name(st[j].scene_index, *st[j].source) << " [" << a[j] << ", " << b[j] << "] meet";
      throw merge_error(i, j, os.str());
    }
  }
  fixed_solution out;
  out.g.resize(n);
  out.defect.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    auto p = pb.split[i] != 0 ? split_particular(st[i], cx, a[i], b[i], pb.split[i])
                              : solve_particular(st[i], cx, pb.roles[i], a[i], b[i], pb.load(i),
                                                 is_loaded(pb, i));
    out.g[i] = std::move(p.g);
    out.defect[i] = p.defect;
  }
  // The correction on the intervals (line loads only act).
  std::vector<std::size_t> targets;
  for (std::size_t k : order)
    if (pb.roles[k] != role::line_load) targets.push_back(k);
  if (targets.empty()) return out;
  std::vector<abel::interval_spec<double>> intervals;
  std::vector<std::function<double(double)>> data;
  abel::multi_solve_options<double> o;
  double worst_ratio = 0;  // max over targets of (scale of D) / (scale of the data)
  const bool any_coupling = n > 1;
  for (std::size_t j : targets) {
    const auto [leading, trailing] = series_edges(pb, j);
    intervals.push_back({a[j], b[j], leading, trailing});
  }
  // From iterative_from contacts on, the particulars' action on the other contacts through the
  // far field (abel/detail/far_field.hpp), whose relative accuracy 1e-3 of the tolerance keeps
  // its error below the correction's residual tolerance; near pairs (and apex enrichments, which
  // the moments of a Jacobi series do not cover) by cross_field.
  const std::shared_ptr<const particular_field> far =
      particular_field::build(out.g, targets, intervals, cx, n >= iterative_from ? pb.tree.get() : nullptr);
  for (std::size_t k = 0; k < targets.size(); ++k) {
    const std::size_t j = targets[k];
    auto f = std::make_shared<std::vector<cross_field>>();
    for (std::size_t i = 0; i < n; ++i)
      if (i != j && (!far || far->direct(k, i))) f->emplace_back(out.g[i], cx.par, a[j], b[j]);
    data.push_back([f, far, k, lo = a[j], h = (b[j] - a[j]) / 2](double s) {
      double v = far ? -far->at(k, (s - lo) / h - 1) : 0.0;
      for (const auto& field : *f) v -= field(s);
      return v;
    });
    // A flat face's correction carries no net load (its particular carries all of it).
    o.loads.push_back(pb.roles[j] == role::fixed_faces || is_loaded(pb, j) ? std::optional<double>(0.0) : std::nullopt);
    // Scales for the correction's residual tolerance.
    double d_scale = 0;
    for (int k = 0; k <= 8; ++k) d_scale = std::max(d_scale, std::abs(data.back()(a[j] + (b[j] - a[j]) * (0.5 + k) / 9.0)));
    const double f_scale = data_scale(st[j], cx, a[j], b[j]);
    // A flat face has no data of its own: D (and the load) is all of it.
    worst_ratio = std::max(worst_ratio, f_scale > 0 ? d_scale / f_scale : 1.0);
  }
  const bool any_face = std::any_of(targets.begin(), targets.end(),
                                    [&](std::size_t j) { return pb.roles[j] == role::fixed_faces || is_loaded(pb, j); });
  if (!any_coupling && !any_face) return out;
  // Residual tolerance of the correction relative to ITS data, so that the error relative to the
  // original data is ~ the tolerance: a weak coupling (D small) needs less relative accuracy.
  const double tol = std::max(cx.options.tolerance, pb.accuracy);
  o.residual_tolerance = std::clamp(10 * tol / std::max(worst_ratio, 1e-300), 10 * tol, 1e-4);
  constexpr std::size_t first_degree = 16;
  o.degree = pb.fixed_degree > 0 ? pb.fixed_degree : std::max(first_degree, 2 * pb.degree_hint->load() / 3);
  o.residual_points = pb.fixed_degree > 0 ? 0 : 8;
  const std::size_t K = intervals.size();
  // Memory: at most 1 GiB for the union's system (the far route's estimate when it is used).
  o.max_memory_bytes = std::size_t(1) << 30;
  const std::size_t memory_degree = far ? abel::detail::union_far_degree_limit(*far->field(), o.max_memory_bytes)
                                        : abel::detail::union_degree_limit<double>(K, o.max_memory_bytes);
  const std::size_t top_degree = std::max(first_degree, std::min<std::size_t>(600, memory_degree));
  if (pb.fixed_degree == 0) o.degree = std::min(o.degree, top_degree);
  o.max_degree = pb.fixed_degree > 0 ? 0 : std::max(o.degree, top_degree);
  o.homogeneous = false;  // the loads are imposed through o.loads; the homogeneous solutions are not used
  // From iterative_from contacts: GMRES, with the far part through the particulars' far field
  // (the same intervals): 11-19 products for rows of 10-300 parabolas 1.5 L apart.
  o.iterative_from = iterative_from;
  if (far) o.far_field = far->field();
  // (A Jacobian's differences take the base point's route: a difference must not cross routes.)
  const bool layered = !far && (pb.fixed_degree > 0 ? pb.fixed_poles_per_decade > 0
                                                    : nearly_touching(intervals, cx.options.layered_below));
  std::size_t per_decade = 0;
  if (layered) {
    // The boundary-layer route: the polynomial part at layered_degree (it adapts up to twice
    // that), poles for the layers, or the coarse basis for an inexact evaluation; a Jacobian's
    // differences at the base point's basis. Its degree is not a hint for the polynomial route.
    const bool coarse = tol >= coarse_layered_accuracy;
    const std::size_t first = coarse ? layered_degree / 2 : layered_degree;
    per_decade = pb.fixed_degree > 0 ? pb.fixed_poles_per_decade : (coarse ? layered_poles_per_decade / 2 : layered_poles_per_decade);
    o.degree = pb.fixed_degree > 0 ? pb.fixed_degree : first;
    o.max_degree = pb.fixed_degree > 0 ? 0 : 2 * first;
  }
  const auto sol = layered ? abel::solve_union_layered(cx.par, intervals, data, o, per_decade)
                           : abel::solve_union(cx.par, intervals, data, o);
  out.degree = sol.degree;
  out.poles_per_decade = per_decade;
  if (pb.fixed_degree == 0 && !layered) pb.degree_hint->store(sol.degree);
  out.correction_residual = sol.residual * std::max(worst_ratio, 0.0);
  out.correction_converged = sol.status == abel::solve_status::converged;
  for (std::size_t k = 0; k < K; ++k) {
    const std::size_t j = targets[k];
    auto& coefficients = out.g[j].jacobi.coefficients;
    const auto& c = sol.densities[k].coefficients;
    if (coefficients.size() < c.size()) coefficients.resize(c.size(), 0.0);
    for (std::size_t m = 0; m < c.size(); ++m) coefficients[m] += c[m];
    if (k < sol.layers.size()) out.g[j].layer = sol.layers[k];
    out.g[j].tail = std::max(out.g[j].tail, sol.status == abel::solve_status::converged ? 0.0 : sol.residual);
    if (sol.exponents[k].nu == -1) out.defect[j] += sol.solvability_defects[k];
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Newton on the edge conditions.

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
  return ev;
}

struct edges {
  std::vector<double> a, b;
};

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

/// Two neighbours whose gap the step (x + dx) would close while it is already below resolved_gap.
struct closing_gap {
  std::size_t first, second;
  double gap_ratio;
  bool closes;  // the full step makes the gap negative
};

/// Largest t in (0, 1] such that x + t dx keeps every contact at least half as long and every gap
/// at least a fifth as wide as now (the contacts' order is kept); `closing` reports a gap below
/// resolved_gap that the step narrows.
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
    if (dgap < 0 && gap < resolved_gap * L) closing = closing_gap{i, j, gap / L, gap + dgap <= 0};
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

struct newton_result {
  bool converged = false;
  edges x;
  fixed_solution sol;
  std::size_t iterations = 0;
  double residual = 0;  // max |condition|
  std::string failure;
  std::optional<std::pair<std::size_t, std::size_t>> merged;
  std::optional<std::size_t> lost;  // scene::body: the contact that shrank below vanishing_length
};

/// scene::body: a contact shorter than this fraction of its isolated length (at an equal share of
/// the load) is taken as vanishing: its indentor would carry no load.
constexpr double vanishing_length = 1e-3;

/// A FLAT RUN: accepted steps that each lower the largest edge condition by less than
/// flat_gain (the line search shortened them to almost nothing). After flat_steps of them a new
/// Jacobian is taken; flat_steps more end the iteration. WHY: the conditions have reached the
/// floor of what the evaluation resolves, and the sufficient-decrease test (1 - 1e-4 t) accepts
/// steps of t ~ 1e-5 for ever (measured: a 12-sample profile whose two contacts closed in on
/// each other at 0.009 of a contact length; 30 steps at the same condition, 6e-4, at 0.36 s
/// each, then the iteration limit).
constexpr double flat_gain = 0.99;
constexpr std::size_t flat_steps = 4;
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

/// Forward-difference Jacobian of the edge conditions (relative step 1e-7 of each contact's
/// length; backward where the forward step would close a gap). Up to `full_width` contacts: one
/// evaluation per unknown. More: the contacts are coloured by their rank along x modulo
/// full_width, and the edges of one side of one colour are moved together (Curtis-Powell-Reid): a
/// condition of contact j is attributed to the moved contact within full_width/2 ranks of j, the
/// rest of its row is left 0. That neglects the dependence on farther contacts (the coupling decays
/// like distance^(alpha - 1)): Broyden's updates recover it. 2 full_width evaluations for any N.
constexpr std::size_t full_width = 5;

/// scene::body in the bounded class with more than full_width contacts, all smooth both sides
/// (no wedge, no split form): the coloured Jacobian with the loads' far monopoles (body_far_model).
bool body_colouring(const problem& pb) {
  if (!pb.body_load || pb.full_jacobian || pb.roles.size() <= full_width) return false;
  for (std::size_t i = 0; i < pb.roles.size(); ++i)
    if (pb.roles[i] != role::smooth_both || pb.split[i] != 0 || is_loaded(pb, i)) return false;
  return true;
}

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
/// The coupled correction's redistribution is left out (higher order in L/d): Broyden's updates
/// recover it.
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
      values[m] = -abel::detail::cross_kernel(cx.par, c - s);
    }
    const auto coefficients = abel::detail::chebyshev_coefficients(values);
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
  abel::detail::chebyshev_grid<double> grid_;
  std::vector<std::array<double, points>> ell_;
  std::vector<double> defect_scale_, level_scale_;
};

Eigen::MatrixXd jacobian(const problem& base, const unknowns& u, const edges& x, const evaluation& ev) {
  problem pb = base;
  pb.fixed_degree = ev.sol.degree;
  pb.fixed_poles_per_decade = ev.sol.poles_per_decade;
  const Eigen::VectorXd& r = ev.r;
  const auto m = static_cast<Eigen::Index>(u.state.size());
  const std::size_t n = pb.roles.size();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, m);
  std::vector<std::size_t> order(n), rank(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return x.a[i] < x.a[j]; });
  for (std::size_t k = 0; k < n; ++k) rank[order[k]] = k;
  // A rigid body: coloured only in the bounded class of smooth contacts, with the far monopoles of
  // body_far_model (its total load, one dense row, from each contact's own load change).
  const bool body = body_colouring(pb);
  const std::size_t colours = n <= full_width || (pb.body_load && !body) ? n : full_width;
  auto near = [&](std::size_t ci, std::size_t cj) { return colours == n || 2 * (ci > cj ? ci - cj : cj - ci) < colours; };
  std::optional<body_far_model> far;
  if (body && colours < n) far.emplace(pb, x);
  std::vector<double> base_load(far ? n : 0);
  for (std::size_t i = 0; i < base_load.size(); ++i) base_load[i] = ev.sol.g[i].integral();
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
        if (rank[u.state[k]] % colours == colour && u.trailing[k] == (side == 1)) c.moved_unknowns.push_back(k);
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
    for (Eigen::Index row = 0; row < m; ++row) {
      const std::size_t j = u.state[static_cast<std::size_t>(row)];
      if (far) {
        const bool trailing = u.trailing[static_cast<std::size_t>(row)];
        if (trailing && j == 0) {  // the total load: each moved contact's neighbourhood's loads
          for (std::size_t k : c.moved_unknowns) {
            double sum = 0;
            for (std::size_t o = 0; o < n; ++o)
              if (near(rank[o], rank[u.state[k]])) sum += c.dload[o];
            J(row, static_cast<Eigen::Index>(k)) = sum / (pb.load_factor * *pb.body_load) / h[k];
          }
          continue;
        }
        // The far moved contacts' monopoles: out of the difference, into their own entries.
        for (std::size_t k : c.moved_unknowns) {
          const std::size_t i = u.state[k];
          if (near(rank[j], rank[i])) continue;
          const double response = trailing ? far->level_row(j, i) : far->defect_row(j, i);
          c.dr[row] -= c.dload[i] * response;
          J(row, static_cast<Eigen::Index>(k)) = c.dload[i] / h[k] * response;
        }
      }
      for (std::size_t k : c.moved_unknowns)
        if (near(rank[j], rank[u.state[k]])) J(row, static_cast<Eigen::Index>(k)) = c.dr[row] / h[k];
    }
  }
  return J;
}

newton_result newton_iteration(const problem& pb, const edges& start);

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

/// Inexact Newton: far from the solution the conditions need not be evaluated to the tolerance. An
/// evaluation solves the correction to inexact_ratio times the largest condition at the last
/// accepted point (at most first_accuracy, at least the tolerance): the error it makes in the
/// conditions is then a small fraction of their size, and near the solution it is the tolerance.
/// The correction's degree follows (gap 1e-3 L: ~400 points per contact at 1e-10, fewer at 1e-5).
constexpr double inexact_ratio = 1e-3;
constexpr double first_accuracy = 1e-5;
constexpr double trust_factor = 10;

newton_result newton_iteration(const problem& pb, const edges& start) {
  const unknowns u = list_unknowns(pb);
  const double tol = std::max(pb.cx->options.tolerance, pb.accuracy);
  const auto accuracy_for = [&](double r) { return std::max(tol, std::min(first_accuracy, inexact_ratio * r)); };
  problem q = pb;  // the evaluations' problem: pb at the accuracy of the current step
  q.accuracy = u.state.empty() ? pb.accuracy : accuracy_for(std::numeric_limits<double>::infinity());
  newton_result out;
  out.x = start;
  for (std::size_t i = 0; i < pb.roles.size(); ++i)
    if (pb.roles[i] == role::apex_ended) out.x.b[i] = (*pb.st)[i].apex;
  if (pb.cx->out_of_time()) {  // the callers' loops then end after one cheap call each
    out.failure = pb.cx->time_limit_message();
    out.residual = std::numeric_limits<double>::infinity();
    return out;
  }
  evaluation ev;
  // Conditions evaluated at an accuracy are trusted when they exceed trust_factor times it;
  // below, the point is evaluated again, more accurately, until they do or the accuracy is the
  // tolerance (a superlinear step can land far below the accuracy it was evaluated at; compared
  // with that value, the next, accurate evaluation would never show a decrease).
  double ev_accuracy = q.accuracy;
  const auto sharpen = [&](const edges& x) {
    while (ev_accuracy > tol && ev.r.lpNorm<Eigen::Infinity>() < trust_factor * ev_accuracy) {
      q.accuracy = accuracy_for(ev.r.lpNorm<Eigen::Infinity>());  // at most inexact_ratio trust_factor ev_accuracy
      ev = evaluate(q, u, x.a, x.b);
      ev_accuracy = q.accuracy;
    }
  };
  try {
    ev = evaluate(q, u, out.x.a, out.x.b);
    ev_accuracy = q.accuracy;
    if (!u.state.empty()) sharpen(out.x);
  } catch (const merge_error& m) {
    out.failure = m.what();
    out.merged = std::make_pair(m.first, m.second);
    return out;
  } catch (const std::domain_error& e) {  // a contact's own solve failed at the start
    out.failure = e.what();
    return out;
  } catch (const time_limit_reached& e) {
    out.failure = e.what();
    out.residual = std::numeric_limits<double>::infinity();
    return out;
  }
  if (u.state.empty()) {
    out.converged = true;
    out.sol = std::move(ev.sol);
    return out;
  }
  // Up to 64 unknowns the updated matrix is factorised with full pivoting at every step (robust
  // when it is nearly singular, e.g. contacts about to merge); above, J0's LU with Broyden's
  // updates by the Woodbury identity (rows of 1000 parabolas: the factorisations were 32 % of the
  // time).
  // The time limit (time_limit_reached from any evaluation) ends the iteration at the last
  // accepted point, whose evaluation ev is reported.
  try {
    abel::detail::broyden_matrix<double> J(jacobian(pb, u, out.x, ev));
    bool fresh = true;
    std::size_t since_fresh = 0;  // accepted steps since the last finite-difference Jacobian
    std::size_t flat = 0;         // accepted steps of the current flat run
    bool refreshed_in_flat = false;
    const bool colouring = pb.roles.size() > full_width && (!pb.body_load || body_colouring(pb));
    for (std::size_t it = 0; it < 60; ++it) {
      if (pb.cx->out_of_time()) {
        out.failure = pb.cx->time_limit_message();
        break;
      }
      out.iterations = it + 1;
      const auto solved = J.solve(ev.r);
      if (!solved) {  // Broyden's updates made the matrix singular (a fresh one has none): a new Jacobian
        J.reset(jacobian(pb, u, out.x, ev));
        fresh = true;
        since_fresh = 0;
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
        os << (closing->closes ? " (the next step closes the gap: they merge)" : "") << "; gaps below " << resolved_gap
           << " of the contact length are not resolved";
        out.failure = closing_message(pb, *closing, os.str());
        if (closing->closes) out.merged = std::make_pair(closing->first, closing->second);
        break;
      }
      bool accepted = false;
      evaluation next;
      edges y;
      q.accuracy = accuracy_for(ev.r.lpNorm<Eigen::Infinity>());
      for (int tries = 0; tries < 12; ++tries) {
        y = moved(pb, u, out.x, t * dx);
        try {
          next = evaluate(q, u, y.a, y.b);
          accepted = next.r.allFinite() &&
                     next.r.lpNorm<Eigen::Infinity>() < (1 - 1e-4 * t) * ev.r.lpNorm<Eigen::Infinity>() + 1e-14;
        } catch (const merge_error& m) {
          out.merged = std::make_pair(m.first, m.second);
          out.failure = m.what();
        } catch (const std::domain_error& e) {  // e.g. a wedge's apex left its contact: a shorter step
          out.failure = e.what();
        }
        if (accepted) break;
        t /= 2;
      }
      if (!accepted) {
        if (!fresh) {  // Broyden's matrix went stale: a new finite-difference Jacobian
          J.reset(jacobian(pb, u, out.x, ev));
          fresh = true;
          since_fresh = 0;
          continue;
        }
        if (out.failure.empty()) out.failure = "the edge iteration stalled";
        break;
      }
      out.merged.reset();
      out.failure.clear();
      // Broyden's (good) update with the step taken.
      const Eigen::VectorXd s = t * dx;
      const Eigen::VectorXd dr = next.r - ev.r;
      J.update(s, dr);
      const bool step_was_fresh = fresh;
      fresh = false;
      double step = 0;
      for (std::size_t k = 0; k < u.state.size(); ++k) {
        const std::size_t i = u.state[k];
        step = std::max(step, std::abs(s[static_cast<Eigen::Index>(k)]) / (y.b[i] - y.a[i]));
      }
      const edges before = out.x;
      out.x = y;
      const double reduction = next.r.lpNorm<Eigen::Infinity>() / ev.r.lpNorm<Eigen::Infinity>();
      ev = std::move(next);
      ev_accuracy = q.accuracy;
      sharpen(out.x);
      ++since_fresh;
      if (reduction > flat_gain && step > 10 * tol) {
        if (++flat == flat_steps && !refreshed_in_flat) {
          J.reset(jacobian(pb, u, out.x, ev));
          fresh = true;
          since_fresh = 0;
          flat = 0;
          refreshed_in_flat = true;
          continue;
        }
        if (flat == flat_steps) {
          const auto pair = narrowing_pair(before, out.x);
          if (pair && pair->gap_ratio < flat_merge_gap) {
            std::ostringstream os;
            os.precision(3);
            os << " where the edge iteration stalls (largest edge condition " << ev.r.lpNorm<Eigen::Infinity>()
               << "): they merge";
            out.failure = closing_message(pb, *pair, os.str());
            out.merged = std::make_pair(pair->first, pair->second);
          } else {
            out.failure = "the edge iteration stalled";
          }
          break;
        }
      } else {
        flat = 0;
        refreshed_in_flat = false;
      }
      // Many contacts (coloured Jacobian): when even a new Jacobian's step gains less than a
      // quarter, this start is too far from the solution (rows of 300 parabolas from the isolated
      // contacts: 27 steps from 3.8 to 0.95, each gaining 1 ... 11 %): the caller's continuation in
      // the load takes over. A rigid body's steps are often shortened by step_limit far from the
      // solution (a contact about to vanish): only a full step that gains little gives up there.
      if (colouring && step_was_fresh && reduction > 0.75 && step > 10 * tol && (!pb.body_load || t == 1)) {
        out.failure = "the edge iteration stalled";
        break;
      }
      // Otherwise Broyden's updates from a start far from the solution crawl (rows of 100
      // parabolas: the condition fell by less than half per step for 12 steps, then converged in 2
      // after a new Jacobian; two parabolas 1e-3 L apart, the Jacobian taken at the continuation's
      // last gap of 1e-2 L: 12 steps each gaining ~ a factor 1.5); a new one when a step gains less
      // than a factor 2 two steps after the last. Its columns are differenced at a fixed degree
      // without a residual: 2 full_width evaluations when coloured, else one per unknown.
      if (reduction > 0.5 && (colouring || t == 1) && since_fresh >= 2 && step > 10 * tol) {
        J.reset(jacobian(pb, u, out.x, ev));
        fresh = true;
        since_fresh = 0;
      }
      if (pb.body_load) {
        for (std::size_t i = 0; i < pb.roles.size(); ++i)
          if (pb.roles[i] == role::smooth_both && y.b[i] - y.a[i] < vanishing_length * pb.start_length[i]) out.lost = i;
        if (out.lost) {
          out.failure = "a contact vanishes";
          break;
        }
      }
      // Converged when the step is within the tolerance and the point was evaluated to it.
      if (step <= 10 * tol && ev_accuracy <= tol) {
        out.converged = true;
        break;
      }
    }
  } catch (const time_limit_reached& e) {
    out.failure = e.what();
    out.merged.reset();
  }
  out.residual = ev.r.lpNorm<Eigen::Infinity>();
  out.sol = std::move(ev.sol);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Start: isolated contacts, scaled for the continuation.

/// Isolated contacts at the scene's loads scaled by t: lengths and apex offsets scale like t^(1/p).
edges scaled_guess(const problem& pb, const edges& isolated, double t) {
  edges x = isolated;
  const auto& st = *pb.st;
  for (std::size_t i = 0; i < st.size(); ++i) {
    if (pb.roles[i] != role::smooth_both && pb.roles[i] != role::apex_ended) continue;
    const double f = std::pow(t, 1 / load_exponent(st[i], *pb.cx));
    x.a[i] = st[i].apex + (isolated.a[i] - st[i].apex) * f;
    x.b[i] = st[i].apex + (isolated.b[i] - st[i].apex) * f;
  }
  return x;
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

/// Newton directly from the isolated contacts when they do not overlap, else (or when that fails)
/// by continuation in the load; pb.load_factor ends at the last load factor solved.
newton_result attempt(problem& pb, const edges& isolated) {
  const auto& st = *pb.st;
  const auto& cx = *pb.cx;
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
    edges guess = result.x;
    for (std::size_t i = 0; i < st.size(); ++i) {
      if (pb.roles[i] != role::smooth_both && pb.roles[i] != role::apex_ended) continue;
      const double f = std::pow(t_next / t, 1 / load_exponent(st[i], cx));
      guess.a[i] = st[i].apex + (guess.a[i] - st[i].apex) * f;
      if (pb.roles[i] == role::smooth_both) guess.b[i] = st[i].apex + (guess.b[i] - st[i].apex) * f;
    }
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

/// scene::body, when Newton from the isolated contacts fails (typically one indentor set much
/// higher than the others): continuation in the heights, from all at one level (height factor 0)
/// to theirs, each Newton solve starting from the last; the contact of an indentor that the rising
/// heights lift off vanishes on the way (newton_result::lost).
newton_result height_continuation(problem& pb, const edges& isolated) {
  problem p = pb;
  p.height_factor = 0;
  newton_result r = attempt(p, isolated);
  std::size_t total = r.iterations;
  double step = 0.25;
  while (r.converged && p.height_factor < 1) {
    problem q = p;
    q.height_factor = std::min(1.0, p.height_factor + step);
    auto t = newton(q, r.x);
    total += t.iterations;
    if (t.converged) {
      r = std::move(t);
      p = q;
      step = std::min(0.5, 1.5 * step);
    } else if (t.lost || step < 1e-3) {
      r = std::move(t);
      p = q;
      break;
    } else {
      step /= 2;
    }
  }
  r.iterations = total;
  if (r.converged && p.height_factor < 1) r.converged = false;
  pb = p;
  return r;
}

/// Contacts scaled about their apexes as isolated ones would be when contact i's load is
/// multiplied by factor[i] (lengths like load^(1/p)); a contact of a line load, a flat punch or a
/// wedge keeps its edges.
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

}  // namespace

coupled_outcome solve_coupled(std::vector<indentor_state>& st, const context& cx, std::optional<double> body_load) {
  problem pb;
  pb.st = &st;
  pb.cx = &cx;
  pb.body_load = body_load;
  edges isolated;
  for (auto& s : st) {
    s.solved.reset();  // set below for a result in the boundary-layer basis
    pb.roles.push_back(role_of(s, cx));
    solve_isolated(s, cx);  // the isolated contact: the start (its closed-form paths)
    isolated.a.push_back(s.g.a());
    isolated.b.push_back(pb.roles.back() == role::line_load ? s.g.a() : s.g.b());
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
  coupled_outcome out;
  auto any = [](const auto& flags) { return std::any_of(flags.begin(), flags.end(), [](auto v) { return v != 0; }); };
  auto again = [&](problem& p) { return attempt(p, isolated); };
  newton_result result = attempt(pb, isolated);
  // The loads-imposed iteration failed (or saw contacts merge): again in the bounded class.
  if (!result.converged && any(pb.loaded))
    retry(pb, result, bounded_form(pb), again,
          [](const newton_result& second, const newton_result& first) { return second.converged || !first.merged; });
  // A rigid body's coloured Jacobian (body_far_model) failed: again with every column differenced.
  if (!result.converged && !result.merged && !result.lost && body_colouring(pb)) {
    problem full = pb;
    full.full_jacobian = true;
    retry(pb, result, std::move(full), again, [](const newton_result& second, const newton_result&) {
      return second.converged || second.lost.has_value();
    });
  }
  // A rigid body from an equal split failed: continuation in the heights (which finds a lost contact).
  const bool uneven = std::any_of(st.begin(), st.end(), [&](const indentor_state& s) { return s.height != st[0].height; });
  if (pb.body_load && !result.converged && !result.merged && uneven)
    retry(pb, result, pb, [&](problem& p) { return height_continuation(p, isolated); },
          [](const newton_result& second, const newton_result&) { return second.converged || second.lost.has_value(); });
  // A split wedge whose apex left its contact (its contact moved onto one face) or that did not
  // converge: again with the plain forms, which take any position of the apex.
  if (!result.converged && !result.merged && any(pb.split)) {
    problem plain = pb;
    plain.split.assign(plain.split.size(), 0);
    retry(pb, result, std::move(plain), again, [](const newton_result& second, const newton_result& first) {
      return second.converged || second.residual < first.residual;
    });
  }
  // Independent indentors of unequal loads: continuation in the loads' ratios (also after a merge,
  // which the continuation in the load can meet on its way with the ratios kept).
  const auto unequal = std::any_of(st.begin(), st.end(), [&](const indentor_state& s) { return s.target_load != st[0].target_load; });
  if (!pb.body_load && !result.converged && !result.lost && unequal)
    retry(pb, result, pb, [&](problem& p) { return ratio_continuation(p, isolated); },
          [](const newton_result& second, const newton_result&) { return second.converged; });
  if (any(pb.loaded) && !result.sol.g.empty()) {
    // The reported densities in the bounded class (the iteration's are bounded only to the
    // tolerance of its intensity conditions, and their edge exponents would be the singular ones).
    try {
      result.sol = solve_fixed(bounded_form(pb), result.x.a, result.x.b);
    } catch (const std::exception& e) {
      if (result.converged) result.failure = e.what();
      result.converged = false;
    }
  }
  out.iterations = result.iterations;
  out.union_degree = result.sol.degree;
  if (!result.converged && result.lost) {
    out.code = status_code::contact_lost;
    std::size_t named = 0;
    out.message = lost_contact_message(st, cx, named);
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
      if (std::isfinite(result.residual)) os << "; largest edge condition " << result.residual;
    }
    if (pb.load_factor < 1) os << " (at " << pb.load_factor << " of the loads)";
    out.message = os.str();
  }
  // Whatever was reached is reported (with a non-ok code when it did not converge), unless the
  // solve was interrupted: then nothing is (each contact's projection below takes seconds for
  // contacts nearly touching, and checks nothing inside; the caller wants none of it).
  if (!result.sol.g.empty()) {
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
      if (st[i].k == kind::wedge && !st[i].g.line_load)
        st[i].epsilon = (st[i].apex - st[i].g.a()) / st[i].g.length();
    }
    cx.throw_if_interrupted("rhabel::punch::solve", true);  // the report's own cost is next
    if (!result.sol.correction_converged && out.code == status_code::ok) {
      std::ostringstream os;
      os.precision(3);
      os << "coupling correction not converged at " << result.sol.degree << " points per contact (residual "
         << result.sol.correction_residual << " of the data)";
      out.code = status_code::not_converged;
      out.message = os.str();
    }
  }
  return out;
}

}  // namespace rhabel::punch::detail
