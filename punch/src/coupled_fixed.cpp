// punch/src/coupled_fixed.cpp: the coupled solve's linear problem for given edges (solve_fixed):
// each contact's particular solution and the coupling correction on the union of the contacts
// (coupled_problem.hpp; the mathematics: "THE LINEAR PROBLEM FOR GIVEN EDGES" at the top of
// coupled_solve.cpp).
#include "coupled_problem.hpp"

#include "rhabel/abel.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <vector>

namespace rhabel::punch::detail::coupled {

namespace {

struct particular {
  contact_density g;
  double defect = 0;  // nu = -1: A g = F - h^alpha defect on the contact (abel's normalisation)
};

/// From this alpha on, a general profile's knots inside a contact are built into its particular
/// (abel::solve_kinks); below it they are left to the series. WHY: the own contact's datum of a
/// knot's term is exact from exact_datum_alpha on (surface.hpp, datum: one Gauss-Jacobi sum with
/// the weight shifted by alpha), and its small-alpha forms are not written for the terms.
constexpr double kink_alpha = 1e-2;

/// How a particular with knots is solved: to `accuracy` (the evaluation's: problem::accuracy, not
/// below the tolerance; a knot's term is exact, the rest converges spectrally, and at tighter
/// tolerances the slope data's rounding, ~1e-12 on a short contact, sends the ladder to its cap),
/// at exactly `degree` image coefficients when non-zero (the Jacobian's differences: the base
/// point's, problem::fixed_particular_degrees).
struct kink_settings {
  double accuracy = 0;
  std::size_t degree = 0;
};

/// F with knots, no step inside [a, b]: abel::solve_kinks, the knots' terms into g.kinks.
particular kinked_particular(const abel::abel_operator<double>& op, const edge_exponents& e, const forcing& F,
                             std::vector<abel::kink<double>> inside, std::size_t max_degree, const kink_settings& ks,
                             double load) {
  abel::solve_options<double> o;
  o.residual_points = 0;
  o.tolerance = ks.accuracy;
  o.max_degree = max_degree + 1;
  o.degree = ks.degree;
  if (e.nu == 1) o.load = load;
  const auto smooth = F.smooth;
  auto F_at = [&](double s) { return smooth ? smooth(s) : 0.0; };
  auto sol = abel::solve_kinks(op, leading_edge(e.nu), trailing_edge(e.nu), F_at, inside, o);
  particular out;
  out.g.jacobi = std::move(sol.smooth.density);
  if (e.nu == 1 && out.g.jacobi.coefficients.empty()) out.g.jacobi.coefficients.assign(1, 0.0);
  out.g.kinks = std::move(sol.terms);
  for (const auto& term : out.g.kinks) out.g.kinks_integral += term.integral();
  out.g.nu = e.nu;
  out.g.tail = std::max(sol.smooth.coefficient_tail, sol.rounding_floor);
  out.g.particular_degree = sol.smooth.degree;
  out.defect = e.nu == -1 ? sol.smooth.solvability_defect : 0.0;
  return out;
}

/// F of the class e on [a, b] without the apex enrichment: spectral (abel::solve) when no step lies
/// inside, with the knots inside built in (kinked_particular), else the projection with the steps'
/// coefficients in closed form, adaptive in the smooth part's tail.
particular series_particular(double a, double b, const edge_exponents& e, const forcing& F, const context& cx,
                              std::size_t cap, const kink_settings& ks, double load = 0) {
  const std::size_t max_degree = std::max<std::size_t>(cap, 8);
  bool step_inside = false;
  for (const auto& [position, jump] : F.steps) step_inside = step_inside || (position > a && position < b);
  particular out;
  const abel::abel_operator<double> op(cx.par, a, b);
  std::vector<abel::kink<double>> inside;
  for (const auto& k : F.kinks)
    if (k.position > a && k.position < b) inside.push_back(k);
  if (!step_inside && !inside.empty() && cx.alpha >= kink_alpha && cx.options.profile_knots)
    return kinked_particular(op, e, F, std::move(inside), max_degree, ks, load);
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

/// The series' largest degree: solve_options::max_degree, or the contact's own cap below it.
std::size_t series_cap(const indentor_state& st, const context& cx) {
  return st.degree_cap > 0 ? std::min(st.degree_cap, cx.options.max_degree) : cx.options.max_degree;
}

particular solve_particular(const indentor_state& st, const context& cx, role r, double a, double b, double load,
                            bool loaded, const kink_settings& ks) {
  particular out;
  const std::size_t cap = series_cap(st, cx);
  if (loaded) return series_particular(a, b, cx.exponents(1), own_forcing(st, cx), cx, cap, ks, load);
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
  return series_particular(a, b, e, F, cx, cap, ks);
}

// The action of one contact's density at points of another (disjoint) interval [lo, hi].
class cross_field {
 public:
  cross_field(const contact_density& g, const abel::abel_parameters<double>& par, double lo, double hi)
      : g_(&g), par_(par), right_of_(g.a() > hi) {
    if (g.line_load) return;
    const double gap = right_of_ ? g.a() - hi : lo - g.b();
    // abel's cross-term nodes, graded toward the end facing [lo, hi] at the TRUE gap (no floor);
    // [lo, hi] at least a half-length of g away (gap >= h): one panel, whose node count
    // abel::separated_cross_nodes takes from the separation (the kernel's analyticity
    // ellipse; eps/100 relative), n/2 + 20 for neighbours one half-length apart, n/2 + 7 far away.
    const std::size_t n = g.jacobi.coefficients.size();
    std::size_t count = std::max<std::size_t>(n / 2 + 24, 32);
    if (const std::size_t separated = abel::separated_cross_nodes(gap / g.jacobi.half_length(), n); separated > 0)
      count = std::min(count, separated);
    nodes_ = abel::make_cross_nodes(g.jacobi, gap, right_of_, count);
    // The series at all nodes in one call (the same sums bit for bit, interleaved: ~3 times
    // faster than a call a node, which was 10 % of a 233-contact profile's search).
    weighted_.resize(nodes_.x.size());
    g.jacobi.series_evaluator().evaluate(nodes_.x.data(), weighted_.data(), nodes_.x.size());
    for (std::size_t q = 0; q < nodes_.x.size(); ++q) weighted_[q] *= nodes_.weight[q];
    // The knots' terms by their own composite rules, graded toward the facing end at the gap.
    if (!g.kinks.empty()) {
      const double inf = std::numeric_limits<double>::infinity(), h = g.jacobi.half_length(), d = gap / h;
      const auto rule = g.kink_rule(right_of_ ? d : inf, right_of_ ? inf : d);
      for (std::size_t j = 0; j < rule.size(); ++j) {
        nodes_.t_minus_lo.push_back(h * rule.one_plus_x[j]);
        nodes_.hi_minus_t.push_back(h * rule.one_minus_x[j]);
        weighted_.push_back(rule.value[j]);
      }
    }
    if (g.has_apex) op_ = std::make_unique<abel::abel_operator<double>>(par, g.a(), g.b());
  }
  double operator()(double s) const {
    if (g_->line_load) return g_->line_weight * abel::cross_kernel(par_, g_->a() - s);
    double sum = 0;
    for (std::size_t q = 0; q < weighted_.size(); ++q) {
      // t - s from the distances to the facing end (no cancellation).
      const double t_minus_s = right_of_ ? nodes_.t_minus_lo[q] + (g_->a() - s) : -(nodes_.hi_minus_t[q] + (s - g_->b()));
      sum += weighted_[q] * abel::cross_kernel(par_, t_minus_s);
    }
    if (op_) sum += abel::apply(*op_, g_->apex, s);
    return sum;
  }

 private:
  const contact_density* g_;
  abel::abel_parameters<double> par_;
  bool right_of_;
  abel::cross_nodes<double> nodes_;
  std::vector<double> weighted_;
  std::unique_ptr<abel::abel_operator<double>> op_;
};

/// The action of the contacts' particular solutions on the other contacts through the far field:
/// each contact's moments from its Jacobi series (exact Gauss-Jacobi quadrature), the local values
/// of every contact once, the knots' terms through contact_density::kink_moments. A contact
/// with an apex enrichment, and line loads (not among the targets), act directly on every contact
/// (direct()), and so do near pairs.
class particular_field {
 public:
  /// Null when the field would have nothing far (or there is no tree: too few contacts).
  static std::shared_ptr<const particular_field> build(const std::vector<contact_density>& g,
                                                       const std::vector<std::size_t>& targets,
                                                       const std::vector<abel::interval_spec<double>>& intervals,
                                                       const context& cx, far_tree* tree) {
    if (!tree || targets.size() < 2) return nullptr;
    std::vector<abel::far_field<double>::box> boxes;
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
      if (!gi.has_apex) W.back() += gi.kink_moments(*out->field_);
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
  const std::shared_ptr<const abel::far_field<double>>& field() const { return field_; }

 private:
  std::shared_ptr<const abel::far_field<double>> field_;
  std::vector<long> target_of_;
  std::vector<bool> plain_;
  std::vector<Eigen::VectorXd> local_;
};

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

/// Throws merge_error when two contacts meet (gap below 1e-12 of the pair's length).
void refuse_meeting(const problem& pb, const std::vector<double>& a, const std::vector<double>& b) {
  const auto& st = *pb.st;
  for (const auto& [i, j, gap, length] : neighbour_pairs(a, b)) {
    if (!(gap > 1e-12 * length)) {
      std::ostringstream os;
      os.precision(10);
      os << "the contacts of " << indentor_name(st[i].scene_index, *st[i].source) << " [" << a[i] << ", " << b[i]
         << "] and " << indentor_name(st[j].scene_index, *st[j].source) << " [" << a[j] << ", " << b[j] << "] meet";
      throw merge_error(i, j, os.str());
    }
  }
}

/// Each contact's particular solution into out.g, out.defect and out.particular_degrees.
void add_particulars(const problem& pb, const std::vector<double>& a, const std::vector<double>& b, fixed_solution& out) {
  const auto& st = *pb.st;
  const auto& cx = *pb.cx;
  const std::size_t n = st.size();
  out.g.resize(n);
  out.defect.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const kink_settings ks{std::max(cx.options.tolerance, pb.accuracy),
                           pb.fixed_particular_degrees.empty() ? 0 : pb.fixed_particular_degrees[i]};
    const particular_memo::key key{a[i],      b[i],     pb.load(i), ks.accuracy, nu_of(pb.roles[i]), is_loaded(pb, i),
                                   ks.degree, series_cap(st[i], cx)};
    particular p;
    // Knotted particulars (solve_options::profile_knots) and a sampled profile's are kept; the
    // other scenes skip the memo's lock, which the Jacobian's threads would otherwise share.
    const bool memo = (cx.options.profile_knots || pb.seeded) && pb.split[i] == 0;
    if (auto kept = memo ? pb.particulars->find(i, key) : std::nullopt) {
      p.g = std::move(kept->g);
      p.defect = kept->defect;
    } else {
      p = pb.split[i] != 0 ? split_particular(st[i], cx, a[i], b[i], pb.split[i])
                           : solve_particular(st[i], cx, pb.roles[i], a[i], b[i], pb.load(i), is_loaded(pb, i), ks);
      if (memo) pb.particulars->store(i, {key, p.g, p.defect});
    }
    out.particular_degrees.push_back(p.g.kinks.empty() ? 0 : p.g.particular_degree);
    out.g[i] = std::move(p.g);
    out.defect[i] = p.defect;
  }
}

/// The correction's union problem: the contacts it is solved on (targets, in the order of x, line
/// loads left out), their intervals and data (minus the other particulars' action), the loads it
/// carries (o.loads), and max over targets of (scale of its data) / (scale of the contact's own).
struct correction_problem {
  std::vector<std::size_t> targets;
  std::vector<abel::interval_spec<double>> intervals;
  std::vector<std::function<double(double)>> data;
  abel::multi_solve_options<double> o;
  double worst_ratio = 0;
  std::shared_ptr<const particular_field> far;
};

correction_problem correction_of(const problem& pb, const std::vector<double>& a, const std::vector<double>& b,
                                 const fixed_solution& out) {
  const auto& st = *pb.st;
  const auto& cx = *pb.cx;
  const std::size_t n = st.size();
  correction_problem c;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return a[i] < a[j]; });
  for (std::size_t k : order)
    if (pb.roles[k] != role::line_load) c.targets.push_back(k);
  if (c.targets.empty()) return c;
  for (std::size_t j : c.targets) {
    const auto [leading, trailing] = series_edges(pb, j);
    c.intervals.push_back({a[j], b[j], leading, trailing});
  }
  // From iterative_from contacts on, the particulars' action on the other contacts through the
  // far field (abel/far_field.hpp), whose relative accuracy 1e-3 of the tolerance keeps
  // its error below the correction's residual tolerance; near pairs (and apex enrichments, which
  // the moments of a Jacobi series do not cover) by cross_field.
  c.far = particular_field::build(out.g, c.targets, c.intervals, cx, n >= iterative_from ? pb.tree.get() : nullptr);
  for (std::size_t k = 0; k < c.targets.size(); ++k) {
    const std::size_t j = c.targets[k];
    auto f = std::make_shared<std::vector<cross_field>>();
    for (std::size_t i = 0; i < n; ++i)
      if (i != j && (!c.far || c.far->direct(k, i))) f->emplace_back(out.g[i], cx.par, a[j], b[j]);
    c.data.push_back([f, far = c.far, k, lo = a[j], h = (b[j] - a[j]) / 2](double s) {
      double v = far ? -far->at(k, (s - lo) / h - 1) : 0.0;
      for (const auto& field : *f) v -= field(s);
      return v;
    });
    // A flat face's correction carries no net load (its particular carries all of it).
    c.o.loads.push_back(pb.roles[j] == role::fixed_faces || is_loaded(pb, j) ? std::optional<double>(0.0) : std::nullopt);
    // Scales for the correction's residual tolerance.
    double d_scale = 0;
    for (int m = 0; m <= 8; ++m) d_scale = std::max(d_scale, std::abs(c.data.back()(a[j] + (b[j] - a[j]) * (0.5 + m) / 9.0)));
    const double f_scale = data_scale(st[j], cx, a[j], b[j]);
    // A flat face has no data of its own: D (and the load) is all of it.
    c.worst_ratio = std::max(c.worst_ratio, f_scale > 0 ? d_scale / f_scale : 1.0);
  }
  return c;
}

/// The union solve's tolerance, degrees and route for c (c.o set); the boundary-layer route's
/// poles a decade, 0 on the polynomial route.
std::size_t set_correction_options(const problem& pb, correction_problem& c) {
  const auto& cx = *pb.cx;
  auto& o = c.o;
  // Residual tolerance of the correction relative to ITS data, so that the error relative to the
  // original data is ~ the tolerance: a weak coupling (D small) needs less relative accuracy.
  const double tol = std::max(cx.options.tolerance, pb.accuracy);
  o.residual_tolerance = std::clamp(10 * tol / std::max(c.worst_ratio, 1e-300), 10 * tol, 1e-4);
  constexpr std::size_t first_degree = 16;
  const bool fixed = !pb.fixed_degrees.empty();
  o.residual_points = fixed ? 0 : 8;
  // Memory: at most 1 GiB for the union's system (the far route's estimate when it is used).
  o.max_memory_bytes = std::size_t(1) << 30;
  const std::size_t memory_degree = c.far ? abel::union_far_degree_limit(*c.far->field(), o.max_memory_bytes)
                                          : abel::union_degree_limit<double>(c.intervals.size(), o.max_memory_bytes);
  const std::size_t top_degree = std::max(first_degree, std::min<std::size_t>(600, memory_degree));
  // Each contact's degree: the base point's (fixed), else one rung below its last (hints), each
  // adapting on its own residual (abel's adapt_each_interval).
  for (const std::size_t j : c.targets)
    o.degrees.push_back(fixed ? pb.fixed_degrees[j] : std::min(top_degree, std::max(first_degree, 2 * pb.hints->at(j) / 3)));
  o.degree = *std::max_element(o.degrees.begin(), o.degrees.end());
  o.max_degree = fixed ? 0 : top_degree;
  o.adapt_each_interval = true;
  o.homogeneous = false;  // the loads are imposed through o.loads; the homogeneous solutions are not used
  // From iterative_from contacts: GMRES, with the far part through the particulars' far field
  // (the same intervals): 11-19 products for rows of 10-300 parabolas 1.5 L apart.
  o.iterative_from = iterative_from;
  if (c.far) o.far_field = c.far->field();
  if (fixed) o.first_guess = pb.correction_guess;
  // (A Jacobian's differences take the base point's route: a difference must not cross routes.)
  const bool layered = !c.far && (fixed ? pb.fixed_poles_per_decade > 0
                                        : nearly_touching(c.intervals, cx.options.layered_below));
  if (!layered) return 0;
  // The boundary-layer route: the polynomial part at layered_degree (it adapts up to twice
  // that), poles for the layers, or the coarse basis for an inexact evaluation; a Jacobian's
  // differences at the base point's basis. Its degree is not a hint for the polynomial route.
  const bool coarse = tol >= coarse_layered_accuracy;
  const std::size_t first = coarse ? layered_degree / 2 : layered_degree;
  o.degree = fixed ? o.degree : first;  // (fixed: the base point's one degree for all)
  o.max_degree = fixed ? 0 : 2 * first;
  o.degrees.clear();
  return fixed ? pb.fixed_poles_per_decade : (coarse ? layered_poles_per_decade / 2 : layered_poles_per_decade);
}

/// The union solve's correction added to the particulars of out.
void add_correction(const problem& pb, const correction_problem& c, const abel::multi_solution<double>& sol,
                    std::size_t per_decade, fixed_solution& out) {
  const std::size_t K = c.targets.size();
  out.degree = sol.degree;
  out.degrees.assign(pb.st->size(), 0);
  for (std::size_t k = 0; k < K; ++k) out.degrees[c.targets[k]] = sol.degrees[k];
  out.poles_per_decade = per_decade;
  if (pb.fixed_degrees.empty() && per_decade == 0) pb.hints->store(out.degrees);
  out.correction_residual = sol.residual * std::max(c.worst_ratio, 0.0);
  out.correction_converged = sol.status == abel::solve_status::converged;
  out.correction_unknowns = sol.unknowns;
  for (std::size_t k = 0; k < K; ++k) {
    const std::size_t j = c.targets[k];
    auto& coefficients = out.g[j].jacobi.coefficients;
    const auto& d = sol.densities[k].coefficients;
    if (coefficients.size() < d.size()) coefficients.resize(d.size(), 0.0);
    for (std::size_t m = 0; m < d.size(); ++m) coefficients[m] += d[m];
    if (k < sol.layers.size()) out.g[j].layer = sol.layers[k];
    out.g[j].tail = std::max(out.g[j].tail, sol.status == abel::solve_status::converged ? 0.0 : sol.residual);
    if (sol.exponents[k].nu == -1) out.defect[j] += sol.solvability_defects[k];
  }
}

}  // namespace

fixed_solution solve_fixed(const problem& pb, const std::vector<double>& a, const std::vector<double>& b) {
  refuse_meeting(pb, a, b);
  fixed_solution out;
  add_particulars(pb, a, b, out);
  // The correction on the intervals (line loads only act).
  correction_problem c = correction_of(pb, a, b, out);
  if (c.targets.empty()) return out;
  // A flat face or a loaded form (its correction's load imposed as 0, correction_of).
  const bool any_face = std::any_of(c.o.loads.begin(), c.o.loads.end(), [](const auto& load) { return load.has_value(); });
  if (pb.st->size() == 1 && !any_face) return out;
  const std::size_t per_decade = set_correction_options(pb, c);
  const auto sol = per_decade > 0 ? abel::solve_union_layered(pb.cx->par, c.intervals, c.data, c.o, per_decade)
                                  : abel::solve_union(pb.cx->par, c.intervals, c.data, c.o);
  add_correction(pb, c, sol, per_decade, out);
  return out;
}

}  // namespace rhabel::punch::detail::coupled
