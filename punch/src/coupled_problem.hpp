// punch/src/coupled_problem.hpp: the state shared by the stages of the coupled solve of several
// contacts (paper system (41)), internal to punch/src. One file per stage:
//   coupled_fixed.cpp   the linear problem for given edges: each contact's particular solution and
//                       the coupling correction on the union, near pairs directly and far ones
//                       through the far field (solve_fixed);
//   coupled_newton.cpp  Newton-Broyden on the edge conditions (newton);
//   coupled_solve.cpp   the starts (isolated contacts; continuations in the load, the heights and
//                       the loads' ratio), the retries and the result (solve_coupled).
// The mathematics of the three: the top of coupled_solve.cpp.
#pragma once

#include "internal.hpp"

#include "rhabel/abel.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rhabel::punch::detail::coupled {

/// How a contact enters the coupled system.
enum class role {
  smooth_both,  ///< nu = -1: both edges smooth and unknown (parabola, general profile, wedge below)
  apex_ended,   ///< nu = 0: wedge on/above the boundary, trailing edge at the apex, leading unknown
  fixed_faces,  ///< nu = +1: flat punch below the boundary, corners fixed, load imposed
  line_load,    ///< flat punch on/above the boundary: line load at the leading corner
};

inline role role_of(const indentor_state& st, const context& cx) {
  const bool above = cx.offset >= -boundary_width;
  switch (st.k) {
    case kind::flat: return above ? role::line_load : role::fixed_faces;
    case kind::wedge: return above ? role::apex_ended : role::smooth_both;
    default: return role::smooth_both;
  }
}

inline int nu_of(role r) {
  switch (r) {
    case role::smooth_both: return -1;
    case role::apex_ended: return 0;
    default: return 1;
  }
}

/// Contact length ~ load^(1/p): p = 2 - alpha (parabola, general), 1 - alpha (wedge).
inline double load_exponent(const indentor_state& st, const context& cx) {
  return st.k == kind::wedge ? 1 - cx.alpha : 2 - cx.alpha;
}

/// Two contacts met (their gap closed): who and where.
struct merge_error : std::runtime_error {
  std::size_t first, second;
  merge_error(std::size_t i, std::size_t j, const std::string& what) : std::runtime_error(what), first(i), second(j) {}
};

/// From this many contacts on: the union's collocation system by block-preconditioned GMRES
/// (abel/detail/block_gmres.hpp) with its far part and the particulars' far action through the far
/// field (abel/far_field.hpp).
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

  std::shared_ptr<const abel::far_field<double>> covering(
      const std::vector<abel::far_field<double>::box>& intervals, const context& cx) {
    std::shared_ptr<const abel::far_field<double>> boxes;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!boxes_ || !boxes_->covers(intervals)) boxes_ = build(intervals, cx);
      boxes = boxes_;
    }
    return std::make_shared<const abel::far_field<double>>(*boxes, intervals);
  }

 private:
  static std::shared_ptr<const abel::far_field<double>> build(
      const std::vector<abel::far_field<double>::box>& intervals, const context& cx) {
    const double inf = std::numeric_limits<double>::infinity();
    auto boxes = intervals;
    for (std::size_t k = 0; k < intervals.size(); ++k) {
      const double margin = box_margin * (intervals[k].hi - intervals[k].lo);
      const double left = k > 0 ? (intervals[k].lo - intervals[k - 1].hi) / 4 : inf;
      const double right = k + 1 < intervals.size() ? (intervals[k + 1].lo - intervals[k].hi) / 4 : inf;
      boxes[k] = {intervals[k].lo - std::min(margin, left), intervals[k].hi + std::min(margin, right)};
    }
    return std::make_shared<const abel::far_field<double>>(
        cx.par, boxes, abel::far_field<double>::order_for(1e-3 * cx.options.tolerance));
  }

  std::mutex mutex_;
  std::shared_ptr<const abel::far_field<double>> boxes_;
};

struct fixed_solution {
  std::vector<contact_density> g;  // per state
  std::vector<double> defect;      // per state: nu = -1 defect (abel's normalisation), else 0
  std::size_t degree = 0;          // the most collocation points of a contact's correction (0: none)
  std::vector<std::size_t> degrees;  // per state: its correction's collocation points (0: none)
  // per state: the image coefficients of a particular with knots built in (0: none)
  std::vector<std::size_t> particular_degrees;
  std::size_t poles_per_decade = 0;  // the boundary-layer route's (0: the polynomial route)
  double correction_residual = 0;  // its independent residual, relative to the original data
  bool correction_converged = true;
  // The correction's unknowns on the matrix-free route (null on the others): the first guess of
  // the differences about this point (problem::correction_guess).
  std::shared_ptr<const abel::union_unknowns<double>> correction_unknowns;
};

/// The largest tail (estimated relative error of the series) among the contacts whose series
/// stopped at solve_options::max_degree; 0 when none did. Their edge conditions are resolved only
/// to about it (coupled_solve.cpp, series_capped; coupled_newton.cpp, stall_floor).
inline double capped_tail(const fixed_solution& sol, const context& cx) {
  double tail = 0;
  for (const auto& g : sol.g)
    if (g.jacobi.coefficients.size() >= cx.options.max_degree) tail = std::max(tail, g.tail);
  return tail;
}

/// Scale of the data on a contact: max |f'|/Gamma(1 - alpha) at 9 points (0 for a flat face).
inline double data_scale(const indentor_state& st, const context& cx, double a, double b) {
  return max_slope(st, a, b) / cx.gamma_factor;
}

/// The correction's degrees of the last adaptive evaluation (problem::hints), per state; read and
/// written under a lock (a Jacobian's threads read them through their copies of the problem).
class degree_hints {
 public:
  /// Contact i's hint (0: none yet).
  std::size_t at(std::size_t i) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return i < degrees_.size() ? degrees_[i] : 0;
  }
  void store(std::vector<std::size_t> degrees) {
    const std::lock_guard<std::mutex> lock(mutex_);
    degrees_ = std::move(degrees);
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::size_t> degrees_;
};

/// The particulars of the last evaluation, per state, with what they were solved for (edges, load,
/// class, accuracy, degree and cap): an evaluation that asks a state's particular for exactly the
/// same (bit for bit) takes the kept one. WHY: a Jacobian's difference moves a few contacts' edges
/// and solves all contacts again. A knotted particular costs ~3 us a term and interpolation point
/// (abel::solve_kinks): a 4000-sample periodic profile (86 patches) took 67 s with every particular
/// solved anew, where the plain series had taken 10 s. A plain series of a seeded (sampled-profile)
/// problem is kept too, the same bits for less time: a coloured Jacobian's column moves a few
/// contacts of hundreds (1e5-sample periodic profile, 233 contacts: 22.3 s -> 21.5 s). Thread-safe
/// (copies of a problem share it).
class particular_memo {
 public:
  struct key {
    double a = 0, b = 0, load = 0, accuracy = 0;
    int nu = 0;
    bool loaded = false;
    std::size_t degree = 0;  // requested: 0 adaptive, else fixed
    std::size_t cap = 0;     // the series' largest degree (coupled_fixed.cpp, series_cap)
    bool operator==(const key& o) const {
      return a == o.a && b == o.b && load == o.load && accuracy == o.accuracy && nu == o.nu && loaded == o.loaded &&
             cap == o.cap;
    }
  };
  /// A kept particular: its density and its solvability defect (nu = -1, abel's normalisation).
  struct entry {
    key k;
    contact_density g;
    double defect = 0;
  };
  /// The kept particular of state i when `k` matches and the requested degree is the same
  /// request or the degree the kept one ended at.
  std::optional<entry> find(std::size_t i, const key& k) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (i >= kept_.size() || !kept_[i]) return std::nullopt;
    const entry& e = *kept_[i];
    if (!(e.k == k) || !(k.degree == e.k.degree || k.degree == e.g.particular_degree)) return std::nullopt;
    return e;
  }
  void store(std::size_t i, entry e) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (kept_.size() <= i) kept_.resize(i + 1);
    kept_[i] = std::move(e);
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::optional<entry>> kept_;
};

/// A rigid body's last finite-difference Jacobian of the edge conditions (coupled_newton.cpp,
/// jacobian: coloured, with the far model) and the contacts' edges where it was taken, kept for
/// the next coupled solve of nearly the same contacts (each edge within memo_shift of its
/// contact's length), whose Newton-Broyden iteration then starts from it instead of differencing
/// a new one. WHY: a sampled profile's search solves one set of contacts again and again from the
/// last solution, at each series degree (contact_set.cpp, raise_degree) and in each pass of a
/// periodic profile (periodic_profile.cpp), and there the new Jacobian was most of a solve's time
/// (1e5-sample periodic profile, 233 contacts: 16 evaluations of 0.1-0.3 s for one Newton step).
/// Broyden's updates and the usual refresh (a step that gains too little) correct what is stale.
struct jacobian_memo {
  Eigen::MatrixXd J;
  std::vector<double> a, b;
};

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
  // Contacts started from seeds (a sampled profile's coarse or solved contacts; contact_set.cpp):
  // a starved contact vanishes and a closing gap merges sooner (coupled_newton.cpp,
  // vanishing_share and seeded_merge_gap), as the profile search then drops or merges them.
  bool seeded = false;
  // Seeded: starved_contact drops a contact with indentor_state::spare_light from any largest
  // condition too (not only from those up to trusted_residual: coupled_newton.cpp); set by the
  // retry of an iteration that failed after it kept one (coupled_solve.cpp).
  bool starve_untrusted = false;
  // > 0: an iteration that stalls (no step descends, or a flat run) with every condition at most
  // this, evaluated to a tenth of it, has converged to the floor of its evaluations (newton).
  double stall_floor = 0;
  std::vector<double> start_length;  // the isolated contacts' lengths (a body's vanishing contact)
  double load_factor = 1;  // continuation: every load times this
  // ratio_continuation: contact i's load times load_weights[i] as well (empty: 1).
  std::vector<double> load_weights;
  /// The load contact i is solved for at this stage of the continuations.
  double load(std::size_t i) const {
    return load_factor * (*st)[i].target_load * (load_weights.empty() ? 1.0 : load_weights[i]);
  }
  // Non-empty (per state): the correction at exactly these many points on each contact, without
  // its residual (the finite differences of the Jacobian: the base point's degrees,
  // fixed_solution::degrees, so that both sides of a difference share one discretisation)
  std::vector<std::size_t> fixed_degrees;
  // Likewise the particulars with knots (fixed_solution::particular_degrees; 0: adaptive).
  std::vector<std::size_t> fixed_particular_degrees;
  // With fixed_degrees on the boundary-layer route: the base point's poles a decade.
  std::size_t fixed_poles_per_decade = 0;
  // With fixed_degrees: the base point's correction (fixed_solution::correction_unknowns), from
  // which the correction's GMRES starts (abel::multi_solve_options::first_guess); set by the
  // Newton-Krylov products (coupled_newton.cpp, krylov_step). WHY: a product moves the edges by
  // 1e-7 .. 1e-5 of their lengths, so the base point's solution is that near the product's; from
  // zero GMRES reaches its 1e-14 in 15-19 products (233-contact periodic profile, traced).
  // Measured beside the same code without it (one core each, side by side; 1e5-sample periodic
  // profiles, acceptance 1e-6; the coarse products' FFT crossing then at 1.5 M log2 M, see
  // active_solve.cpp, fft_cost): seed 1 at load 6e-3 (443 contacts) 52 s against 62 s, the same 37
  // iterations; seed 3 (428) 77 s against 81 s, 22 iterations each; seed 1 at 1.4e-2 (979) ok in
  // 441 s, where the other had not finished after 13 min (stopped). WHY not the Jacobian's columns
  // too: with them the 443-contact profile took 58 s, and the 16000-sample profile of seed 4
  // (tests/punch/test_rough_profile.cpp) ended ok with one of its two narrow contacts missing.
  std::shared_ptr<const abel::union_unknowns<double>> correction_guess;
  // The Jacobian kept across solves (jacobian_memo; copies share it); null: none. Read only by a
  // solve's first attempt (read_memo): a retry follows a failure, and differences its own.
  std::shared_ptr<jacobian_memo> memo;
  bool read_memo = true;
  // The far field's tree, kept across evaluations (copies of the problem share it).
  std::shared_ptr<far_tree> tree = std::make_shared<far_tree>();
  // The degrees the last adaptive evaluation needed, per state (copies share them). The next one
  // starts each contact's ladder one rung (x 2/3) below, so that a degree can also fall: the edges
  // move little between evaluations, and near contacts need high degrees (gap 1e-3 L: ~400 at
  // 1e-12), which the ladder from 16 reaches after 9 solves, each with its residual (measured at
  // that gap: 190 ms an evaluation from 16, 145 ms from the hint; starting AT the hint, the degree
  // only grows, and one overshoot toward a merge kept every later evaluation at the cap of 600).
  // Per contact (abel's adapt_each_interval): only the contacts with a near neighbour climb.
  std::shared_ptr<degree_hints> hints = std::make_shared<degree_hints>();
  // The particulars of the last evaluations (copies share them: see particular_memo).
  std::shared_ptr<particular_memo> particulars = std::make_shared<particular_memo>();
  // > the requested tolerance: the accuracy to which an evaluation solves the correction (an
  // inexact Newton step far from the solution; see newton_iteration).
  double accuracy = 0;
  // offset_continuation: subtracted from the conditions (in the order of newton's unknowns;
  // empty: none), so that a start x0 solves the conditions minus (1 - s) times its own.
  Eigen::VectorXd offset;
};

inline bool is_loaded(const problem& pb, std::size_t i) { return i < pb.loaded.size() && pb.loaded[i]; }

/// Two contacts next to each other along x: their gap (negative when they overlap) and the length
/// it is measured in, the shorter of the two, where a line load (no length) takes its neighbour's.
struct neighbour_pair {
  std::size_t first, second;  // first's contact lies behind second's (smaller x)
  double gap, length;
};

/// The neighbour pairs of the contacts [a_i, b_i], in the order of their leading edges.
inline std::vector<neighbour_pair> neighbour_pairs(const std::vector<double>& a, const std::vector<double>& b) {
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

struct edges {
  std::vector<double> a, b;
};

struct newton_result {
  bool converged = false;
  edges x;
  fixed_solution sol;
  std::size_t iterations = 0;
  std::size_t jacobians = 0;  // finite-difference Jacobians taken (jacobian_memo's start is none)
  double residual = 0;  // max |condition|
  std::string worst;    // which condition that is (coupled_newton.cpp, condition_name)
  std::string failure;
  std::optional<std::pair<std::size_t, std::size_t>> merged;
  std::optional<std::size_t> lost;  // scene::body: the contact that shrank below vanishing_length
  bool spared = false;  // a starving contact was kept (indentor_state::spare_light)
};

/// The Jacobian's band (coupled_newton.cpp, jacobian): up to full_width contacts every column is
/// differenced; more are coloured (Curtis-Powell-Reid), each contact near those within full_width/2
/// ranks along x and those within a few lengths (colouring).
constexpr std::size_t full_width = 5;

// The stages (see the top of the file).

/// The densities for given edges a, b (throws merge_error when two contacts meet).
fixed_solution solve_fixed(const problem& pb, const std::vector<double>& a, const std::vector<double>& b);
/// Newton-Broyden on the edge conditions from `start`; any failure of a contact's own solve is a
/// failed result.
newton_result newton(const problem& pb, const edges& start);
/// The edge conditions at x, in the order of newton's unknowns (pb.offset subtracted), evaluated
/// to a trusted accuracy as newton's start is.
Eigen::VectorXd edge_conditions(const problem& pb, const edges& x);
/// scene::body: the level approach_i + height_i of every contact (equal at the solution).
std::vector<double> body_levels(const std::vector<indentor_state>& states, const std::vector<contact_density>& g,
                                const context& cx, double height_factor);
/// scene::body with the coloured Jacobian and the far model of the loads (body_far_model).
bool body_colouring(const problem& pb);

}  // namespace rhabel::punch::detail::coupled
