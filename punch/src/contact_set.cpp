// punch/src/contact_set.cpp: a sampled profile on one rigid body, its set of contacts unknown
// (rhabel/punch/profile.hpp; docs/theory.md section 9).
//
// The active set lives on the profile's bumps (profile_curve.hpp, find_bumps): a contact is a run
// of adjacent bumps (one bump, or several after contacts merged), solved as a general profile
// whose edges are sought inside the run's basins, all contacts on one rigid body (contact.cpp's
// prepare_states / solve_states: the coupled solve with the loads unknown). Each round changes the
// set by the evidence of the last solve: a contact that vanished is dropped, contacts that met
// are merged, bumps whose samples penetrate the deformed surface are added. The first set is the
// coarse boundary-element solve's at the full load (coarse_contact.hpp, predicted_start), and
// every round of that seeded search starts each contact's Newton iteration from its edges in the
// last converged round (run::seed), at each series degree it needs (raise_degree); when these do
// not end ok, the search starts again from the highest tip alone by load continuation
// (continuation_start). The last round's solve is reported with contact.cpp's checks plus the
// clearance at every sample.
#include "coarse_contact.hpp"
#include "coupled_problem.hpp"
#include "internal.hpp"
#include "profile_curve.hpp"
#include "profile_search.hpp"
#include "surface.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace rhabel::punch {

namespace detail {
namespace {

constexpr const char* who = "rhabel::punch::solve_profile";

// Bumps penetrating within this factor of the deepest are added in one round. WHY: adding a bump
// moves the body up (the load is shared by more contacts), so a barely penetrating bump is
// often clear once the deeper ones carry load; adding it anyway costs a round to drop it again.
constexpr double add_fraction = 0.25;
// Samples within this fraction of a contact's length of its edges are not checked: there the
// surface's moments (surface.hpp) are not resolved (report.cpp, worst_gaps), and the edge
// conditions with a non-negative pressure already give the clearance.
constexpr double edge_margin = 1.0 / 64;
// Load continuation (solve_profile): when the highest tip alone cannot carry the fraction t of
// the load inside its basin, t is divided by shrink_factor (at most max_shrinks times: 16^-12 ~
// 3e-15); once the set settles at t, t is multiplied by load_step. A contact's length grows like
// load^(1/(2 - alpha)): a step of 4 moves the edges by a factor 2 at most, close enough for the
// last set to be the next start.
constexpr double shrink_factor = 16;
constexpr std::size_t max_shrinks = 12;
constexpr double load_step = 4;
// The first fraction: 4^-4. WHY: the contact set grows with the load; a set found at t is nearly
// the set at 4 t, so few bumps are added at each step and almost none is lost again (a bump added
// and then lifted costs a failed coupled solve: measured 3-8 s for 9 contacts, against 0.4 s for a
// solve that converges). 4^-4: the contacts of ten equal cosine bumps at 1/4 of their period shrink
// to ~ 1/16 of their basin.
constexpr double start_fraction = 1.0 / 256;
// A coupled solve that fails right after a load step is tried again at the geometric mean of the
// settled fraction and the new one, at most this many times (4 -> 2 -> 1.41 -> 1.19).
constexpr std::size_t max_halvings = 3;
// A bump dropped (its contact vanished) is added again when it penetrates later at the same load,
// once: the coupled solve names the vanishing contact by the levels at an equal split, which can
// name a bump that does touch (measured: 50 cosine bumps, a tip dropped at the full load then
// penetrated by 1.2 of the profile's span). A second drop is final (the iteration could cycle).
constexpr std::size_t max_drops = 2;

// A coarse contact at an end of the samples with this share of the load or more: the contact set
// leaves the data, and the scene is refused (predicted_start). WHY: the surface displacement of a
// load grows with the distance (Psi ~ -d^alpha/alpha, -log d at alpha = 0), so far from the loads
// the surface rises above any profile of bounded height: a long profile under a heavy load (or at
// alpha near 1) touches at the end of its data, which has no continuation to solve (measured: 50
// cosine bumps at alpha 0.7 put 74 % of the load on the first panel; the search ran 124 s
// into not_converged). Smaller coarse contacts there are left to the search and its clearance
// check.
constexpr double end_share = 1e-3;
// The degrees to which a search whose contacts missed the acceptance at solve_options::max_degree
// is solved again, in turn (needs_degree). WHY 1024 and 2048 too: a contact over a few samples of
// a self-affine profile converges algebraically (the spline's f''' jumps at the knots): residual
// of (8) 1.8e-6 at 511 and 4.2e-7 at 1023 (4000 samples, seed 1, load 1e-3: ok in 6.6 s; 8.3e-7
// for seed 3, 4.0 s); contacts of 4-8 spacings 1.1e-6 .. 1.6e-6 at 1023 and 3.5e-8 .. 2.7e-7 at
// 2047 (self_affine_profile.py 4000 2 6e-3 and 32000 2 3e-3 periodic, 16000 2 1e-3 finite: each
// not_converged by that one contact at 1023, ok in 14, 20 and 4 s with it at 2047). Only the
// contacts that missed the acceptance climb (capped_below); when all could, 2048 took over a
// minute for 21 contacts.
constexpr std::size_t profile_degrees[] = {512, 1024, 2048};

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(std::string(who) + ": " + what); }

std::string num(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

// "field[i]" (formed in a stream: GCC 12 warns falsely on "literal" + std::string&& under -O2).
std::string element(const char* field, std::size_t i) {
  std::ostringstream os;
  os << field << '[' << i << ']';
  return os.str();
}

}  // namespace

void validate_profile(const profile_scene& s, const char* caller) {
  auto refuse = [caller](const std::string& what) { throw std::invalid_argument(std::string(caller) + ": " + what); };
  validate_material(s.material, s.speed, caller);
  if (!(s.load > 0) || !std::isfinite(s.load)) refuse("load = " + num(s.load) + " must be finite and > 0");
  const auto& p = s.profile;
  if (p.x.size() != p.z.size())
    refuse("profile.x has " + std::to_string(p.x.size()) + " samples and profile.z " + std::to_string(p.z.size()) +
        "; give one z per x");
  if (p.x.size() < 4) refuse("profile.x has " + std::to_string(p.x.size()) + " samples; give at least 4");
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    if (!std::isfinite(p.x[i])) refuse(element("profile.x", i) + " = " + num(p.x[i]) + " must be finite");
    if (!std::isfinite(p.z[i])) refuse(element("profile.z", i) + " = " + num(p.z[i]) + " must be finite");
    if (i > 0 && !(p.x[i] > p.x[i - 1]))
      refuse(element("profile.x", i) + " = " + num(p.x[i]) + " must be > " + element("profile.x", i - 1) + " = " + num(p.x[i - 1]));
  }
  // Spacing and heights far from the double range: the spline forms differences and their
  // squares (the relative spacing 1e-12 leaves 4 digits to a slope).
  const double span_x = p.x.back() - p.x.front();
  for (std::size_t i = 1; i < p.x.size(); ++i)
    if (!((p.x[i] - p.x[i - 1]) >= 1e-12 * span_x) || !(std::abs(p.x[i]) < 1e100 && span_x > 1e-100))
      refuse(element("profile.x", i) + " - " + element("profile.x", i - 1) + " = " +
          num(p.x[i] - p.x[i - 1]) + " must be >= 1e-12 of the profile's length " + num(span_x) +
          " and the abscissae within (1e-100, 1e100)");
  const auto [lo, hi] = std::minmax_element(p.z.begin(), p.z.end());
  if (!(*hi - *lo > 0)) refuse("profile.z is constant; a flat profile has no contact with smooth edges");
  if (!(*hi - *lo > 1e-100 * span_x) || !(std::max(std::abs(*hi), std::abs(*lo)) < 1e100))
    refuse("profile.z spans " + num(*hi - *lo) + " over a length " + num(span_x) +
        ": the slopes must be within (1e-100, 1e100) and the heights below 1e100");
  if (!(p.period >= 0) || !std::isfinite(p.period))
    refuse("profile.period = " + num(p.period) + " must be finite and > 0 (or absent: a finite window)");
  if (p.period > 0) {
    if (!(p.x.back() < p.x.front() + p.period) || !(p.x.front() + p.period - p.x.back() >= 1e-12 * p.period))
      refuse("profile.period = " + num(p.period) + ": the samples must lie in [x_0, x_0 + period) = [" + num(p.x.front()) +
          ", " + num(p.x.front() + p.period) + "), the last at least 1e-12 of the period before its end; profile.x[" +
          std::to_string(p.x.size() - 1) + "] = " + num(p.x.back()));
    if (!p.corners.empty()) refuse("profile.corners cannot be given with profile.period (the periodic spline has no corners)");
  }
  std::vector<double> corners = p.corners;
  std::sort(corners.begin(), corners.end());
  std::size_t previous = 0;
  for (std::size_t k = 0; k < p.corners.size(); ++k) {
    const double c = corners[k];
    const auto it = std::lower_bound(p.x.begin() + 1, p.x.end() - 1, c);
    const std::string name = "profile.corners (" + num(c) + ")";
    if (it == p.x.end() - 1 || *it != c) refuse(name + " must each be one of profile.x[1] .. profile.x[n-2]");
    const std::size_t at = static_cast<std::size_t>(it - p.x.begin());
    if (at - previous < 3) refuse(name + ": give at least 4 samples between corners and from the ends");
    previous = at;
  }
  if (p.x.size() - 1 - previous < 3) refuse("profile.corners: give at least 4 samples between the last corner and the end");
}

namespace {

/// A contact candidate: a run of adjacent bumps [first, last] (indices into the bumps). In a
/// seeded search (every run has one) its seed: the edges (absolute) its contact's next coupled
/// solve starts from and its load there (in units of int g at the full load): the coarse solve's
/// at first, then the last converged round's, and near its deepest sample for a run added on a
/// penetration.
struct run {
  std::size_t first = 0, last = 0;
  std::optional<coarse_patch> seed;
};

/// Runs in the order of x: by first bump, runs on one bump by their seeds.
void sort_runs(std::vector<run>& runs) {
  std::sort(runs.begin(), runs.end(), [&](const run& p, const run& q) {
    return p.first != q.first ? p.first < q.first : p.seed && q.seed && p.seed->a < q.seed->a;
  });
}

/// Everything one round needs: the curve, its bumps and the reference height.
struct profile_model {
  const profile_scene* source = nullptr;
  profile_curve curve;
  std::vector<bump> bumps;
  double top = 0, span = 0;  // max z and max z - min z
  // The last Jacobian of the rounds' coupled solves, kept for the next (coupled::jacobian_memo).
  std::shared_ptr<coupled::jacobian_memo> jacobian = std::make_shared<coupled::jacobian_memo>();

  explicit profile_model(const profile_scene& s) : profile_model(s, profile_curve(s.profile)) {}
  /// s's profile given by `c` (its samples c.x(), c.z()).
  profile_model(const profile_scene& s, profile_curve c) : source(&s), curve(std::move(c)), bumps(find_bumps(curve.z())) {
    const auto [lo, hi] = std::minmax_element(curve.z().begin(), curve.z().end());
    top = *hi;
    span = *hi - *lo;
  }
  /// The highest tip of a run (the contact's apex).
  std::size_t tip(const run& r) const {
    std::size_t best = bumps[r.first].tip;
    for (std::size_t k = r.first; k <= r.last; ++k)
      if (curve.z()[bumps[k].tip] > curve.z()[best]) best = bumps[k].tip;
    return best;
  }
};

/// The scene of the current runs: one general profile per run on one rigid body. Its slope reads
/// the curve, which outlives the scene (both are solve_profile's).
scene make_scene(const profile_model& m, const std::vector<run>& runs, double load) {
  scene s;
  s.material = m.source->material;
  s.speed = m.source->speed;
  s.body = rigid_body{load};
  const auto& x = m.curve.x();
  for (const run& r : runs) {
    const std::size_t t = m.tip(r);
    const double apex = x[t];
    general_profile gp;
    const profile_curve* curve = &m.curve;
    gp.slope = [curve, apex](double u) { return curve->slope(apex + u); };
    gp.value = [curve, apex](double u) { return curve->value(apex + u); };
    gp.search_lo = x[m.bumps[r.first].first] - apex;
    gp.search_hi = x[m.bumps[r.last].last] - apex;
    for (const double c : m.curve.corners())
      if (c > apex + gp.search_lo && c < apex + gp.search_hi) gp.corners.push_back(c - apex);
    for (const auto& [at, jump] : m.curve.knots(apex + gp.search_lo, apex + gp.search_hi))
      gp.knots.push_back({at - apex, jump});
    indentor ind;
    ind.shape = std::move(gp);
    ind.apex = apex;
    // Equal levels approach + height on the body: on a contact w = z + const, so approach_k =
    // const + z(apex_k) and height_k = top - z(apex_k) (the highest sample at height 0).
    ind.height = m.top - m.curve.z()[t];
    s.indentors.push_back(std::move(ind));
  }
  return s;
}

/// The start of the body's coupled solve: the loads of the last solved set (shares, per unit of
/// the load fraction, keyed by tip) where a contact has one, a quarter of the smallest of them for
/// a new contact, scaled to the body's load. Without any (the first round), the equal split of
/// prepare_states stays. WHY: the coupled solve starts from the isolated contacts at this split,
/// and an equal split of contacts whose loads differ by a factor 10 stalled its Newton iteration.
void start_split(const profile_model& m, const std::vector<run>& runs, const std::map<std::size_t, double>& shares,
                 scene_states& ss) {
  if (shares.empty()) return;
  double smallest = std::numeric_limits<double>::infinity(), total = 0, sum = 0;
  for (const auto& [tip, load] : shares) smallest = std::min(smallest, load);
  for (auto& state : ss.st) {
    total += state.target_load;  // the equal split adds up to the body's load
    const auto it = shares.find(m.tip(runs[state.scene_index]));
    state.target_load = it != shares.end() ? it->second : smallest / 4;
    sum += state.target_load;
  }
  for (auto& state : ss.st) state.target_load *= total / sum;
}

/// Runs i .. j (in the order of x) become one (seeded: its seed spans theirs and carries their loads).
void merge_runs(std::vector<run>& runs, std::size_t i, std::size_t j) {
  runs[i].last = runs[j].last;
  if (std::all_of(runs.begin() + static_cast<std::ptrdiff_t>(i), runs.begin() + static_cast<std::ptrdiff_t>(j) + 1,
                  [](const run& r) { return r.seed.has_value(); })) {
    double load = 0;
    bool solved = true;
    for (std::size_t k = i; k <= j; ++k) load += runs[k].seed->load, solved = solved && runs[k].seed->load_solved;
    runs[i].seed = coarse_patch{runs[i].seed->a, runs[j].seed->b, load, 0, solved};
  }
  runs.erase(runs.begin() + static_cast<std::ptrdiff_t>(i) + 1, runs.begin() + static_cast<std::ptrdiff_t>(j) + 1);
}

/// A contact that reaches beyond its run's basins covers the valley to the next bump: the run
/// takes that bump in, merging with the run that has it unless both are seeded and their
/// contacts apart (then they share the bump, as a flank's contact does). Returns whether a run
/// changed. WHY apart: two contacts a sample spacing apart across a shallow valley are two
/// patches (4000 samples, seed 4 of the tests' profiles, load 6e-3: the boundary-element
/// solution has both); merged, the round converged to one contact with a negative pressure
/// between them.
bool widen(const profile_model& m, std::vector<run>& runs, const scene_states& ss) {
  const auto& x = m.curve.x();
  const auto meet = [](const run& p, const run& q) { return !(p.seed && q.seed && p.seed->b < q.seed->a); };
  for (const auto& state : ss.st) {
    const std::size_t k = state.scene_index;
    const double a = state.g.a() + ss.origin, b = state.g.b() + ss.origin;
    run& r = runs[k];
    if (a < x[m.bumps[r.first].first] && r.first > 0) {
      --r.first;
      if (k > 0 && runs[k - 1].last >= r.first && meet(runs[k - 1], r)) merge_runs(runs, k - 1, k);
      return true;
    }
    if (b > x[m.bumps[r.last].last] && r.last + 1 < m.bumps.size()) {
      ++r.last;
      if (k + 1 < runs.size() && runs[k + 1].first <= r.last && meet(r, runs[k + 1])) merge_runs(runs, k, k + 1);
      return true;
    }
  }
  return false;
}

/// The clearance of the surface at the samples outside the contacts: per bump the deepest
/// penetration (relative to the profile's span; 0 when clear), and the smallest clearance overall.
/// With it the levels: the largest |w(a_i) - w(a_(i-1)) - (z(a_i) - z(a_(i-1)))| over neighbouring
/// contacts (relative to the span), w the surface of the reported densities (surface::height),
/// z the body's profile: all contacts lie on one rigid body.
struct clearance_check {
  std::vector<double> depth;      // per bump
  std::vector<double> deepest_at; // per bump: the abscissa of its deepest sample
  double worst = std::numeric_limits<double>::infinity();
  double worst_at = 0;
  double level = 0;     // the largest level mismatch
  double level_at = 0;  // the leading edge of the contact where it is
};

/// The clearances w(s) - w(a_i) - (z(s) - z(a_i)) relative to the span at the abscissae `s` (the
/// states' frame) off the contacts, i = reference[k] (a contact whose leading edge a_i is where
/// both are known), w[k] = w(s[k]) - w(a_i) (surface::heights): negative where the profile
/// penetrates the surface.
std::vector<double> clearances(const profile_model& m, const scene_states& ss, const std::vector<double>& w,
                               const std::vector<double>& s, const std::vector<std::size_t>& reference) {
  std::vector<double> out(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double za = m.curve.value(ss.st[reference[k]].g.a() + ss.origin);
    out[k] = (w[k] - (m.curve.value(s[k] + ss.origin) - za)) / m.span;
  }
  return out;
}

/// The contacts of a round in the order of x, to find the one nearest an abscissa in O(log n).
/// The contacts of a converged round are disjoint (the coupled solve reports contacts that meet).
class contact_locator {
 public:
  explicit contact_locator(const scene_states& ss) : ss_(ss), order_(ss.st.size()) {
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = i;
    std::sort(order_.begin(), order_.end(), [&](std::size_t i, std::size_t j) { return ss.st[i].g.a() < ss.st[j].g.a(); });
  }
  /// The contact nearest s (the states' frame), or none when s lies within `margin` of a contact's
  /// length of it (inside it included).
  std::optional<std::size_t> reference(double s, double margin) const {
    const auto p = static_cast<std::size_t>(
        std::partition_point(order_.begin(), order_.end(), [&](std::size_t i) { return ss_.st[i].g.a() <= s; }) - order_.begin());
    std::optional<std::size_t> nearest;
    double distance = std::numeric_limits<double>::infinity();
    // Disjoint contacts: the nearest is the last starting at or before s or the first after it;
    // one more each side for a margin that reaches past a neighbour.
    for (std::size_t j = p > 1 ? p - 2 : 0; j < std::min(p + 2, order_.size()); ++j) {
      const std::size_t i = order_[j];
      const double a = ss_.st[i].g.a(), b = ss_.st[i].g.b(), pad = margin * (b - a);
      if (s > a - pad && s < b + pad) return std::nullopt;
      const double d = s < a ? a - s : s - b;
      if (d < distance) distance = d, nearest = i;
    }
    return nearest;
  }

 private:
  const scene_states& ss_;
  std::vector<std::size_t> order_;
};

/// A point between two neighbouring checked samples where the profile may penetrate the surface
/// deeper than at both: s in the states' frame, its reference contact, and the sample of the pair
/// whose bump it is counted in (the higher one).
struct inner_point {
  double s = 0;
  std::size_t reference = 0, bump_sample = 0;
};

/// The inner points of check_clearance: for each pair of neighbouring checked samples q, q + 1
/// (relative gaps[k], gaps[k + 1]), the penetration e(x) = z(x) - w(x) + const is taken as the
/// cubic of Hermite's data z(x_q), z'(x_q), z(x_q+1), z'(x_q+1) (exact on a cubic spline piece)
/// minus w's chord, w(x_q) .. w(x_q+1). Where that cubic has an interior maximum within `tol` of
/// penetrating, its abscissa is returned, the surface to be evaluated there. WHY the chord: w is
/// smooth away from the contacts, and the deepest point lies where z' equals w' (not at the
/// crest, where z' = 0: a surface slope of 0.05 on a crest with z'' = 900 moves the deepest point
/// by 5.6e-5 and the depth by 1.4e-6); the location's error costs only second order in the depth,
/// which is evaluated exactly there.
std::vector<inner_point> between_samples(const profile_model& m, const scene_states& ss, const std::vector<double>& xs,
                                         const std::vector<std::size_t>& index, const std::vector<double>& gaps,
                                         const std::vector<std::size_t>& reference, const std::vector<double>& w,
                                         const std::vector<double>& z_a, double tol) {
  std::vector<inner_point> out;
  const auto& z = m.curve.z();
  // The contacts' extents in order: a pair with one between its samples is skipped (a contact
  // narrower than a spacing can lie between two checked samples).
  std::vector<std::pair<double, double>> extents;
  for (const auto& state : ss.st) extents.emplace_back(state.g.a(), state.g.b());
  std::sort(extents.begin(), extents.end());
  std::vector<double> ends(extents.size());  // running maximum of the ends, for the search below
  for (std::size_t i = 0; i < extents.size(); ++i) ends[i] = std::max(extents[i].second, i ? ends[i - 1] : extents[i].second);
  const auto holds_contact = [&](double lo, double hi) {
    // the first contact whose running end passes lo; it or a later one starting before hi
    const auto i = static_cast<std::size_t>(std::upper_bound(ends.begin(), ends.end(), lo) - ends.begin());
    for (std::size_t j = i; j < extents.size() && extents[j].first < hi; ++j)
      if (extents[j].second > lo) return true;
    return false;
  };
  for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
    const std::size_t q = index[k];
    if (index[k + 1] != q + 1 || holds_contact(xs[k], xs[k + 1])) continue;
    const double h = xs[k + 1] - xs[k];
    // The penetration (absolute) at both ends relative to the first's reference, and its slopes.
    const double e0 = -gaps[k] * m.span, e1 = -gaps[k + 1] * m.span;
    const double chord = (w[k + 1] - w[k] + (z_a[reference[k + 1]] - z_a[reference[k]])) / h;
    const double d0 = m.curve.slope(xs[k] + ss.origin) - chord, d1 = m.curve.slope(xs[k + 1] + ss.origin) - chord;
    if (!(d0 > 0 && d1 < 0)) continue;  // no interior maximum (e' changes sign from + to - inside)
    // Hermite's cubic on u in [0, 1]: e(u) = e0 h00 + h d0 h10 + e1 h01 + h d1 h11; its derivative
    // (per unit u) A u^2 + B u + C with:
    const double A = 6 * (e0 - e1) + 3 * h * (d0 + d1), B = -6 * (e0 - e1) - h * (4 * d0 + 2 * d1), C = h * d0;
    double u;
    if (std::abs(A) < 1e-14 * (std::abs(B) + std::abs(C))) {
      u = -C / B;
    } else {
      const double disc = std::max(0.0, B * B - 4 * A * C), r = std::sqrt(disc);
      // The root where the derivative falls through zero (the maximum).
      const double u1 = (-B + r) / (2 * A), u2 = (-B - r) / (2 * A);
      const auto falls = [&](double v) { return 2 * A * v + B < 0; };
      u = (u1 > 0 && u1 < 1 && falls(u1)) ? u1 : u2;
    }
    if (!(u > 0 && u < 1)) continue;
    const double u2 = u * u, u3 = u2 * u;
    const double e = e0 * (2 * u3 - 3 * u2 + 1) + h * d0 * (u3 - 2 * u2 + u) + e1 * (-2 * u3 + 3 * u2) + h * d1 * (u3 - u2);
    if (!(e > -tol * m.span) || !(e > std::max(e0, e1))) continue;
    out.push_back({xs[k] + u * h, reference[k], z[q + 1] > z[q] ? q + 1 : q});
  }
  return out;
}

clearance_check check_clearance(const profile_model& m, const scene_states& ss, const context& cx) {
  const auto& st = ss.st;
  const auto& x = m.curve.x();
  clearance_check out;
  out.depth.assign(m.bumps.size(), 0.0);
  out.deepest_at.assign(m.bumps.size(), 0.0);
  // The samples off the contacts (in order), each with the nearest contact as its reference (its datum).
  std::vector<double> xs;
  std::vector<std::size_t> index, reference;
  const contact_locator near(ss);
  for (std::size_t q = 0; q < x.size(); ++q) {
    const double s = x[q] - ss.origin;
    const auto nearest = near.reference(s, edge_margin);
    if (!nearest) continue;
    xs.push_back(s);
    index.push_back(q);
    reference.push_back(*nearest);
  }
  std::vector<std::size_t> bump_of(x.size(), 0);
  for (std::size_t b = 0; b < m.bumps.size(); ++b)
    for (std::size_t q = m.bumps[b].first; q <= m.bumps[b].last; ++q) bump_of[q] = b;
  const surface heights(st, cx);
  for (std::size_t i = 1; i < st.size(); ++i) {
    const double a = st[i].g.a(), before = st[i - 1].g.a();
    const double rise = m.curve.value(a + ss.origin) - m.curve.value(before + ss.origin);
    const double mismatch = std::abs(heights.height(i - 1, a) - rise) / m.span;
    if (mismatch > out.level) out.level = mismatch, out.level_at = a + ss.origin;
  }
  std::vector<double> z_a(st.size());
  for (std::size_t i = 0; i < st.size(); ++i) z_a[i] = m.curve.value(st[i].g.a() + ss.origin);
  const auto w = heights.heights(xs, reference);
  const auto gaps = clearances(m, ss, w, xs, reference);
  const auto note = [&](double gap, double at, std::size_t bump) {
    if (gap < out.worst) out.worst = gap, out.worst_at = at;
    if (-gap > out.depth[bump]) out.depth[bump] = -gap, out.deepest_at[bump] = at;
  };
  for (std::size_t k = 0; k < xs.size(); ++k) note(gaps[k], x[index[k]], bump_of[index[k]]);
  // Between two checked samples the spline can rise above both: its crests lie up to
  // h^2 |z''| / 8 above the samples (a 16000-sample self-affine profile: ~1e-4 of the span), and
  // there a contact narrower than a spacing touches while both samples clear the surface.
  const auto inside = between_samples(m, ss, xs, index, gaps, reference, w, z_a, cx.options.acceptance);
  if (!inside.empty()) {
    std::vector<double> at;
    std::vector<std::size_t> ref;
    for (const auto& c : inside) at.push_back(c.s), ref.push_back(c.reference);
    const auto gap = clearances(m, ss, heights.heights(at, ref), at, ref);
    for (std::size_t k = 0; k < inside.size(); ++k) note(gap[k], at[k] + ss.origin, bump_of[inside[k].bump_sample]);
  }
  return out;
}

/// The lowest clearance (relative to the span) of the surface of `ss` over [lo, hi] (absolute) at
/// 33 points, each against its nearest contact's leading edge as in check_clearance; +infinity
/// when every point lies on a contact.
double lowest_gap(const profile_model& m, const scene_states& ss, const surface& heights, double lo, double hi) {
  std::vector<double> xs;
  std::vector<std::size_t> reference;
  const contact_locator near(ss);
  for (int k = 0; k <= 32; ++k) {
    const double s = lo + (hi - lo) * k / 32.0 - ss.origin;
    const auto nearest = near.reference(s, 0);
    if (!nearest) continue;
    xs.push_back(s);
    reference.push_back(*nearest);
  }
  if (xs.empty()) return std::numeric_limits<double>::infinity();
  const auto gap = clearances(m, ss, heights.heights(xs, reference), xs, reference);
  return *std::min_element(gap.begin(), gap.end());
}

/// "indentors[k] (general_profile)" of the coupled solve's messages -> "the contact at x = tip".
std::string rename(std::string text, const profile_model& m, const std::vector<run>& runs) {
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const std::string from = "indentors[" + std::to_string(k) + "] (general_profile)";
    std::ostringstream to;
    to.precision(6);
    to << "the contact at the tip x = " << m.curve.x()[m.tip(runs[k])];
    for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at))
      text.replace(at, from.size(), to.str());
    const std::string see = "see indentors[" + std::to_string(k) + "]";
    for (auto at = text.find(see); at != std::string::npos; at = text.find(see, at))
      text.replace(at, see.size(), "see contacts[" + std::to_string(k) + "]");
  }
  return text;
}

/// A solved round: its runs, the scene built from them, the solved states and the outcome.
struct round_state {
  std::vector<run> runs;
  double t = 1;  // the fraction of the body's load it carries
  scene sc;
  scene_states states;
  coupled_outcome outcome;

  round_state() = default;
  round_state(round_state&&) = default;
  round_state& operator=(round_state&&) = default;
  /// A copy's states refer to its own scene's indentors (indentor_state::source; a move keeps the
  /// indentors where they are).
  round_state(const round_state& o) : runs(o.runs), t(o.t), sc(o.sc), states(o.states), outcome(o.outcome) {
    for (auto& state : states.st) state.source = &sc.indentors[state.scene_index];
  }
  round_state& operator=(const round_state&) = delete;
};

/// What the search found: the last solved round and its evidence.
struct search_result {
  std::optional<round_state> last;  // empty when no round could be solved at all
  clearance_check clear;            // of `last` when its outcome is ok
  std::string failure;              // why the search stopped short of a verified set ("" if it did not)
  std::size_t rounds = 0, iterations = 0;
  std::map<std::size_t, coarse_patch> lost;  // contacts lost once at the full load and not restored
  // Stopped to search again with search_start::spare: it was about to add back a contact it dropped.
  bool respare = false;
};

/// The runs of the first round: the highest tip alone.
std::vector<run> first_runs(const profile_model& m) {
  for (std::size_t k = 0; k < m.bumps.size(); ++k)
    if (m.curve.z()[m.bumps[k].tip] == m.top) return {run{k, k, std::nullopt}};
  return {};
}

/// Where a search starts: its runs (seeded, or each from its isolated contact), the loads of their
/// tips (per unit of t; empty: an equal split) and the fraction t of the load.
struct search_start {
  std::vector<run> runs;
  std::map<std::size_t, double> shares;
  double t = start_fraction;
  /// Bumps whose lone contact an earlier search of the same load lost once, with its seed (restore_lost).
  std::map<std::size_t, coarse_patch> lost;
  /// Every seeded contact kept while the coupled iteration is far from the solution
  /// (indentor_state::spare_light), from the first round. Without it, a search that is about to
  /// add back a contact it dropped, whose seed was not light (needed_share), stops
  /// (search_result::respare), and solve_model searches again with it. WHY: such a search has
  /// dropped a contact the solution needs, and from there it can cycle (1e5-sample periodic
  /// profile, seed 3, load 6e-3: it lost and regained contacts, seven of its last contacts not ok,
  /// until --time-limit 900; spared from the start it ends ok with the boundary-element oracle's
  /// 428 patches). Not from the start for every search: the ~980-patch
  /// profile (seed 1, load 1.4e-2) converges by dropping a coarse seed in its first round, and
  /// with it kept, its search ended at another set that the degree-512 search could not solve.
  bool spare = false;
};

/// The continuation's start: the highest tip alone at start_fraction of the load.
search_start continuation_start(const profile_model& m) { return {first_runs(m), {}, start_fraction, {}}; }

/// std::domain_error naming body.load when a coarse contact at an end of the samples carries
/// end_share of the load (in units of int g) or more: the contacts would leave the data.
void refuse_end_contacts(const profile_model& m, const std::vector<coarse_patch>& patches, double load) {
  for (const coarse_patch& p : patches) {
    if (!(p.a == m.curve.lo() || p.b == m.curve.hi()) || p.load < end_share * load) continue;
    std::ostringstream os;
    os.precision(3);
    os << who << ": at body.load = " << m.source->load << " the contacts reach the end of the samples at x = "
       << (p.a == m.curve.lo() ? p.a : p.b) << " (a coarse boundary-element solve puts " << 100 * p.load / load
       << " % of the load on [" << p.a << ", " << p.b
       << "]): extend profile.x and profile.z beyond it, or lower body.load";
    throw std::domain_error(os.str());
  }
}

/// Where start_from's contacts come from: a coarse solve (edges known to a panel) or a search
/// (edges solved).
enum class seed_edges { coarse, solved };

/// The first round's runs and seeds from contacts (absolute edges, loads in units of int g): each
/// the run of bumps whose tips it covers (predicted_start); solved edges: and every basin an edge
/// lies in.
std::optional<search_start> start_from(const profile_model& m, const std::vector<coarse_patch>& patches,
                                       seed_edges edges) {
  if (patches.empty()) return std::nullopt;
  const auto& x = m.curve.x();
  search_start out;
  out.t = 1;
  for (const coarse_patch& p : patches) {
    // The bumps whose tips it covers; none (a contact off its tip, as above alpha = 1/2): the bump
    // whose basin holds its middle. WHY not every basin it meets: a coarse edge is known to a
    // panel, and a contact reaching one panel into the next basin would merge two bumps.
    run r{m.bumps.size(), 0, p};
    for (std::size_t k = 0; k < m.bumps.size(); ++k)
      if (x[m.bumps[k].tip] >= p.a && x[m.bumps[k].tip] <= p.b) r.first = std::min(r.first, k), r.last = k;
    if (r.first == m.bumps.size()) {
      const double middle = (p.a + p.b) / 2;
      r.first = 0;
      while (r.first + 1 < m.bumps.size() && x[m.bumps[r.first].last] < middle) ++r.first;
      r.last = r.first;
    }
    // A solved contact that reaches beyond the basins of its tips keeps the basins it reached, as
    // the search's widen gave it (its neighbours' contacts are apart: they share a bump, not
    // merge). WHY: from its tips alone, every degree of the ladder (raise_degree) widened the same
    // run again after its first round and solved the whole set once more (the ~980-patch periodic
    // profile: a second round of 8-17 s at each of 512, 1024 and 2048).
    if (edges == seed_edges::solved) {
      while (r.first > 0 && p.a < x[m.bumps[r.first].first]) --r.first;
      while (r.last + 1 < m.bumps.size() && p.b > x[m.bumps[r.last].last]) ++r.last;
    }
    out.runs.push_back(r);
    out.shares[m.tip(r)] += p.load;
  }
  if (out.runs.empty()) return std::nullopt;
  return out;
}

/// Lost contacts (absolute edges) on the bumps of `m` that hold their middles, the first of a bump
/// kept. WHY by position: a periodic profile's next pass searches the window's profile corrected
/// by new images, whose bumps can differ from the last pass's.
std::map<std::size_t, coarse_patch> lost_on_bumps(const profile_model& m, const std::vector<coarse_patch>& lost) {
  const auto& x = m.curve.x();
  std::map<std::size_t, coarse_patch> out;
  for (const coarse_patch& p : lost) {
    const double middle = (p.a + p.b) / 2;
    // the first bump whose basin ends at or after the middle
    const auto it = std::partition_point(m.bumps.begin(), m.bumps.end(), [&](const bump& b) { return x[b.last] < middle; });
    if (it != m.bumps.end() && x[it->first] <= middle) out.emplace(static_cast<std::size_t>(it - m.bumps.begin()), p);
  }
  return out;
}

/// The coarse solve's contacts (coarse_contact.hpp) at the full load, each the run of bumps whose
/// tips it covers (two may share a bump: a bump's flank can carry a contact of its own), with its
/// coarse edges and load as the seed of the first round; empty when the coarse solve did not
/// settle. Refuses a scene whose contacts reach an end of the samples.
std::optional<search_start> predicted_start(const profile_model& m, const context& cx) {
  const double load = m.source->load / cx.pressure_scale;
  std::vector<coarse_patch> patches;
  try {
    patches = coarse_contacts(m.curve, load, cx, seed_panels * m.curve.x().size(), seed_panels_fine * m.curve.x().size());
  } catch (const time_limit_reached&) {
    return std::nullopt;  // the search's first round runs anyway: it has a result to report
  }
  refuse_end_contacts(m, patches, load);
  return start_from(m, patches, seed_edges::coarse);
}

/// The length of the two sample spacings about the sample at `at`.
double spacings_about(const profile_model& m, double at) {
  const auto& x = m.curve.x();
  const auto q = static_cast<std::size_t>(std::lower_bound(x.begin(), x.end(), at) - x.begin());
  return x[std::min(q + 1, x.size() - 1)] - x[q > 0 ? q - 1 : 0];
}

/// Whether a contact of `ss` comes within `pad` of [lo, hi] (absolute).
bool near_contact(const scene_states& ss, double lo, double hi, double pad) {
  return std::any_of(ss.st.begin(), ss.st.end(), [&](const indentor_state& state) {
    return lo < state.g.b() + ss.origin + pad && hi > state.g.a() + ss.origin - pad;
  });
}

/// The bumps a round may add a run on: those without one that were not dropped max_drops times
/// and, in a seeded search, also a bump with runs whose deepest sample lies more than a sample
/// spacing from every contact (a bump's flank can carry a contact of its own; its run starts from
/// a seed there, see new_seed). WHY the latter: the coarse solve can miss a flank's contact
/// narrower than its panels (self-affine, 1000 samples, seed 1, load 2e-3: a penetration of 5e-6
/// of the span 1.7 samples beside a contact of the same bump), and without it the round ended
/// unverified and the continuation from the highest tip fell short of the load.
std::vector<bool> addable(const profile_model& m, const scene_states& ss, const clearance_check& clear,
                          const std::vector<run>& runs, const std::vector<std::size_t>& dropped, bool seeded) {
  std::vector<bool> active(m.bumps.size(), false);
  for (const run& r : runs)
    for (std::size_t b = r.first; b <= r.last; ++b) active[b] = true;
  std::vector<bool> out(m.bumps.size(), false);
  for (std::size_t b = 0; b < m.bumps.size(); ++b) {
    if (dropped[b] >= max_drops || !(clear.depth[b] > 0)) continue;
    if (!active[b]) {
      out[b] = true;
      continue;
    }
    if (!seeded) continue;
    const double at = clear.deepest_at[b];
    out[b] = !near_contact(ss, at, at, spacings_about(m, at) / 2);
  }
  return out;
}

/// The seed of a run added at a penetrating sample `at`: a quarter of a sample spacing each side,
/// `load` (a quarter of the smallest contact's, as start_split gives a new contact).
coarse_patch new_seed(const profile_model& m, double at, double load) {
  const double h = spacings_about(m, at);
  return {std::max(at - h / 8, m.curve.lo()), std::min(at + h / 8, m.curve.hi()), load, 0, false};
}

/// After a round that converged: each bump whose lone contact was lost once at this load (in this
/// search, or in an earlier search of the same window that seeded it: search_start::lost), with no
/// contact within a sample spacing of the lost one's edges and where the profile penetrates the
/// surface by more than the acceptance (relative to the span) anywhere within those edges and a
/// quarter spacing about them, gets it back, seeded as it was lost, at most `at_most` of them (in
/// the order of x); returns the bumps that got one. A contact lost again is lost for good
/// (`dropped` reaches max_drops), and so is a lone one whose round then fails
/// (contact_search::undo_restoring, restore_point).
/// WHY: the rigid body's iteration from the coarse seeds can starve a real contact narrower than a
/// sample spacing (a seed load under a hundredth of the mean; coupled_newton.cpp, vanishing_share);
/// from the converged set and its coarse edges it is kept. Measured: 16000 samples, seed 4, load
/// 2e-3, periodic: two contacts 2e-6 and 2.9e-6 wide (3e-5 and 1.2e-4 of the load), lost in rounds
/// 1 and 2, penetrating by 5.8e-6 and 7.6e-6 of the span after round 3; restored, the search ends
/// ok with all 60 contacts and C_f 0.03229008 (the test oracle: 60 patches, 0.03229008 +- 5.8e-6),
/// where without them it ended ok with 58 and C_f 0.0322935, 3.4e-6 off. Added as a new contact
/// instead (new_seed, ~16 times wider), the round took 82 iterations and 30 s.
/// WHY no contact near, not no run on the bump: a run widened over the bumps beside its contact
/// holds bumps none of its contacts touches. WHY only beyond the acceptance: shallower, the result
/// is ok without it, and restoring it can cost the search its path (1e5 samples, periodic, load
/// 1.4e-2, 977 contacts: a contact lost in the first round, penetrating by 7.8e-7 of the span once
/// the others settled, given back; that round stalled on another contact's level, and the search
/// from the round before it failed at degree 512, where without it the search ends ok).
std::vector<std::size_t> restore_lost(const profile_model& m, const scene_states& ss, const context& cx,
                                      std::vector<run>& runs, std::map<std::size_t, coarse_patch>& lost,
                                      const std::vector<std::size_t>& dropped, std::size_t at_most) {
  std::vector<std::size_t> back;
  std::optional<surface> heights;  // built once, if a lost contact is to be checked
  for (auto it = lost.begin(); it != lost.end() && back.size() < at_most;) {
    const auto& [b, seed] = *it;
    const double spacings = spacings_about(m, m.curve.x()[m.bumps[b].tip]), quarter = spacings / 8;
    if (dropped[b] >= max_drops || near_contact(ss, seed.a, seed.b, spacings / 2)) {
      ++it;
      continue;
    }
    if (!heights) heights.emplace(ss.st, cx);
    if (!(lowest_gap(m, ss, *heights, seed.a - quarter, seed.b + quarter) < -cx.options.acceptance)) {
      ++it;
      continue;
    }
    runs.push_back({b, b, seed});
    back.push_back(b);
    it = lost.erase(it);
  }
  if (!back.empty()) sort_runs(runs);
  return back;
}

/// The search's state before restore_lost gave contacts back: the runs of the round that converged
/// without them (seeded from it; the round itself is contact_search's last_converged_) and the
/// lost seeds, and the bumps restored. WHY: a round with
/// contacts restored can fail to converge, and that failure ended the search, the round before it
/// never reported; the search goes back to that round instead, and gives the contacts back one at
/// a time, a lone one that fails being lost for good. Measured (16000 samples, seed 4, load 2e-3,
/// periodic, tolerance 1e-10, degree 512): four restored at once stalled; one at a time, three
/// converged and the fourth made the others vanish again, so that search too ended short and the
/// continuation from the highest tip found all 60 (ok in 8 min, as before).
struct restore_point {
  std::vector<run> runs;
  std::map<std::size_t, coarse_patch> lost;
  std::vector<std::size_t> restored;
};

/// The part of a contact where its pressure is negative, when its lowest is below -tol of its
/// mean (at report.cpp's pressure_probes, as the judge): the run of probes with a negative
/// pressure about the lowest, widened to the pressure's zeros interpolated linearly from the
/// probes beside it, [lo, hi] in abscissae of the solve, and whether it reaches the first or the
/// last probe. WHY the zeros: a dip at one probe gave lo = hi, and the two contacts split there
/// shared an edge and met again at once, round after round (1e5-sample periodic profile: a
/// contact over two boundary-element patches 3e-6 apart, 1/16 of its length).
struct negative_part {
  double lo = 0, hi = 0;
  bool at_lo = false, at_hi = false;
};
std::optional<negative_part> tension_in(const contact_density& g, double tol) {
  if (g.line_load || !(g.length() > 0)) return std::nullopt;
  const std::vector<double> t = pressure_probes(g);
  std::vector<double> v(t.size());
  std::size_t lowest = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    v[k] = g.value(t[k]);
    if (v[k] < v[lowest]) lowest = k;
  }
  if (!(v[lowest] < -tol * std::abs(g.integral() / g.length()))) return std::nullopt;
  std::size_t first = lowest, last = lowest;
  while (first > 0 && v[first - 1] < 0) --first;
  while (last + 1 < t.size() && v[last + 1] < 0) ++last;
  // The zero between probes k (pressure >= 0) and q (< 0).
  const auto zero = [&](std::size_t k, std::size_t q) { return t[k] + (t[q] - t[k]) * v[k] / (v[k] - v[q]); };
  return negative_part{first > 0 ? zero(first - 1, first) : t[first], last + 1 < t.size() ? zero(last + 1, last) : t[last],
                       first == 0, last + 1 == t.size()};
}

/// A seeded round's contacts whose pressure is negative inside start again (runs' seeds; at most
/// max_drops times a tip) without the part where it is negative: an edge moved to it when that
/// part reaches the outermost probe (its load then a guess: coarse_patch::load_solved), else as
/// two contacts each side of it (split_seed). WHY: the edge conditions of a contact over a bump
/// with a shoulder have a root whose pressure has a negative lobe where the physical solution has
/// a gap (32000 samples, seed 1, load 3e-3: -0.19 of the mean pressure inside one contact of a
/// bump; the boundary-element solution has two patches there, a sample spacing apart), and the
/// coupled solve converges to it as well as to the physical one. Returns whether a run changed.
bool repair_tension(const profile_model& m, const scene_states& ss, std::vector<run>& runs,
                    std::map<std::size_t, std::size_t>& repairs, double tol) {
  bool changed = false;
  std::vector<run> split;
  for (const auto& state : ss.st) {
    const auto negative = tension_in(state.g, tol);
    run& r = runs[state.scene_index];
    if (!negative || !r.seed || repairs[m.tip(r)]++ >= max_drops) continue;
    if (negative->at_lo && negative->at_hi) continue;  // negative all over: nothing to keep (the report says tension)
    changed = true;
    coarse_patch& seed = *r.seed;  // the contact's edges (absolute) and load, from this round
    if (negative->at_hi) {
      seed.b = negative->lo + ss.origin;
      seed.load_solved = false;  // its load no longer matches its edges
    } else if (negative->at_lo) {
      seed.a = negative->hi + ss.origin;
      seed.load_solved = false;
    } else {
      auto [before, after] = split_seed(seed, state.g, negative->lo, negative->hi, ss.origin);
      seed = before;
      split.push_back({r.first, r.last, after});
    }
  }
  runs.insert(runs.end(), split.begin(), split.end());
  sort_runs(runs);
  return changed;
}

/// search_result::failure of a search that stopped to search again with search_start::spare.
constexpr const char* needed_again = "a contact dropped in an earlier round is needed again";

/// A contact given back (restore_lost, or added again where the profile penetrates) stops a search
/// without search_start::spare when the seed it was dropped with carried at least this share of
/// the mean seed load: its seed called it no starving contact (the coupled iteration's
/// vanishing_share). WHY not every one: contacts narrower than a sample spacing whose seeds carry
/// less are dropped rightly and given back by restore_lost alone (16000 samples, seed 4, load
/// 2e-3: seeds of 0.2 % and 0.7 % of the mean; searched again, the solve took 3-4 times as long).
constexpr double needed_share = 1e-2;

/// Whether the lost seed of bump b (lost: bump -> seed) carried needed_share of the mean seed load
/// of `runs` (all seeded).
bool seed_needed(const std::map<std::size_t, coarse_patch>& lost, std::size_t b, const std::vector<run>& runs) {
  const auto it = lost.find(b);
  if (it == lost.end() || runs.empty()) return false;
  double total = 0;
  for (const run& r : runs)
    if (r.seed) total += std::abs(r.seed->load);
  return it->second.load >= needed_share * total / double(runs.size());
}

/// The round at fraction t of the load on `runs`: its scene and states, seeded (every run has a
/// seed) each started from its seed (its own load: runs may share a tip; spare:
/// indentor_state::spare_light), else the loads split by `shares` (start_split).
round_state prepare_round(const profile_model& m, const context& cx, const std::vector<run>& runs, bool seeded,
                          double t, const std::map<std::size_t, double>& shares, bool spare) {
  round_state next;
  next.runs = runs;
  next.t = t;
  next.sc = make_scene(m, runs, t * m.source->load);
  next.states = prepare_states(next.sc, cx);
  next.states.jacobian = m.jacobian;
  if (seeded) {
    for (auto& state : next.states.st) {
      const coarse_patch& p = *runs[state.scene_index].seed;
      state.seed = std::pair{p.a - next.states.origin, p.b - next.states.origin};
      state.target_load = p.load * t;
      state.degree_cap = p.degree;
      state.seed_load = p.load_solved;
      state.spare_light = spare;
    }
  } else {
    start_split(m, runs, shares, next.states);
  }
  return next;
}

/// After a converged round: each tip's share of the load per unit t and, seeded, each run's seed
/// from its solved contact (the next round starts from this one's contacts).
void keep_solved(const profile_model& m, const round_state& last, bool seeded, std::vector<run>& runs,
                 std::map<std::size_t, double>& shares) {
  shares.clear();
  for (const auto& state : last.states.st) {
    shares[m.tip(runs[state.scene_index])] = state.target_load / last.t;
    if (seeded)
      runs[state.scene_index].seed = coarse_patch{state.g.a() + last.states.origin, state.g.b() + last.states.origin,
                                                  state.target_load / last.t, state.degree_cap};
  }
}

/// The bumps to add after a converged round: those addable whose penetration is at least
/// add_fraction of the deepest, when the deepest exceeds tol (relative to the span); none else.
std::vector<std::size_t> growth(const profile_model& m, const scene_states& states, const clearance_check& clear,
                                const std::vector<run>& runs, const std::vector<std::size_t>& dropped, bool seeded,
                                double tol) {
  const auto candidate = addable(m, states, clear, runs, dropped, seeded);
  double deepest = 0;
  for (std::size_t b = 0; b < m.bumps.size(); ++b)
    if (candidate[b]) deepest = std::max(deepest, clear.depth[b]);
  std::vector<std::size_t> added;
  if (!(deepest > tol)) return added;
  for (std::size_t b = 0; b < m.bumps.size(); ++b)
    if (candidate[b] && clear.depth[b] >= add_fraction * deepest) added.push_back(b);
  return added;
}

/// A run for each added bump (seeded: at its deepest penetration, with a quarter of the smallest
/// share as its load), the runs sorted again.
void add_runs(const profile_model& m, const clearance_check& clear, const std::vector<std::size_t>& added, bool seeded,
              const std::map<std::size_t, double>& shares, std::vector<run>& runs) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& [tip, share] : shares) smallest = std::min(smallest, share);
  for (std::size_t b : added)
    runs.push_back({b, b, seeded ? std::optional(new_seed(m, clear.deepest_at[b], smallest / 4)) : std::nullopt});
  sort_runs(runs);
}

/// A search that ends in a round that failed (its coupled solve, or stopped by its time or round
/// limit) reports the best state it reached instead: the last converged round at the same load,
/// whose clearances (below) name the contacts it misses, with why the search went no further.
/// WHY: a round that fails is no solution (1e5-sample periodic profile, seed 3, load 6e-3,
/// --time-limit 240: reported as its last round, with residual 1 and C_f 0 after a later search's
/// round; as its best state, 425 contacts, residual 7.4e-5 (a degree-128 round) and C_f 0.052018,
/// where the boundary-element solver gives 0.05202 +- 2.1e-4).
void report_best(const profile_model& m, const context& cx, std::optional<round_state> last_converged,
                 search_result& out) {
  if (out.last && out.last->outcome.code != status_code::ok && last_converged && last_converged->t >= out.last->t) {
    const std::string& why = out.last->outcome.message;
    if (out.failure.empty())
      out.failure = "the round after it, with " + std::to_string(out.last->runs.size()) + " contacts, did not converge" +
                    (why.empty() ? "" : ": " + rename(why, m, out.last->runs));
    out.last.emplace(std::move(*last_converged));
  }
  // The evidence of the round that is reported when it was not the last one checked (a later
  // round failed to solve, the round limit came, or its own solve did not converge): its
  // clearances, recomputed (for a failed solve they locate the contacts it misses).
  if (out.last && (out.last->outcome.code != status_code::ok || !out.failure.empty())) {
    try {
      out.clear = check_clearance(m, out.last->states, cx);
    } catch (const std::exception&) {
      out.clear = {};
    }
  }
}

/// The active-set search from `start`, with load continuation when start.t < 1 (profile.hpp, "THE
/// CONTACT SET"): one round after another, each solving the current runs and changing them by its
/// evidence (a contact lost or merged, a restoring that failed, lost contacts given back, a
/// negative pressure repaired, a run widened, penetrating bumps added), until the set settles at
/// the full load or a limit stops it.
class contact_search {
 public:
  contact_search(const profile_model& m, const context& cx, const search_start& start)
      : m_(m), cx_(cx), start_(start), runs_(start.runs), dropped_(m.bumps.size(), 0), lost_seeds_(start.lost),
        shares_(start.shares), t_(start.t), max_rounds_(2 * m.bumps.size() + 40) {
    for (const auto& entry : lost_seeds_) dropped_[entry.first] = 1;
  }

  search_result search() {
    for (;;) {
      if (limit_reached()) break;
      ++out_.rounds;
      const bool seeded = std::all_of(runs_.begin(), runs_.end(), [](const run& r) { return r.seed.has_value(); });
      round_state next = prepare_round(m_, cx_, runs_, seeded, t_, shares_, start_.spare);
      try {
        next.outcome = solve_states(next.sc, next.states, cx_);
      } catch (const std::domain_error& e) {
        if (retry_unsolved()) continue;
        out_.failure = rename(e.what(), m_, runs_);
        break;
      }
      out_.iterations += next.outcome.iterations;
      out_.last = std::move(next);
      if (after_round(seeded) == step::stop) break;
    }
    if (t_ == 1)
      for (const auto& [b, seed] : lost_seeds_)
        if (dropped_[b] < max_drops) out_.lost.emplace(b, seed);
    report_best(m_, cx_, std::move(last_converged_), out_);
    return std::move(out_);
  }

 private:
  enum class step { again, stop };

  /// The round limit or the time limit, with out_.failure set (a first round always runs: it has a
  /// result to report).
  bool limit_reached() {
    if (out_.rounds == max_rounds_) {
      out_.failure = "the contact set did not settle in " + std::to_string(max_rounds_) + " rounds";
      return true;
    }
    if (out_.last && cx_.out_of_time()) {
      out_.failure = cx_.time_limit_message() + " after " + std::to_string(out_.rounds) + " rounds of the contact search";
      return true;
    }
    return false;
  }

  /// A round that failed right after a load step: half the step (in log t), at most max_halvings
  /// times; false when there is no step to halve.
  bool halve_step() {
    if (!(settled_ > 0 && t_ > settled_ * 1.01 && halvings_ < max_halvings)) return false;
    t_ = std::sqrt(t_ * settled_);
    ++halvings_;
    return true;
  }

  /// One contact whose edges are not found: before any fraction settled, a smaller fraction of the
  /// load; after, half the step as for a failed solve. WHY not a smaller fraction again: the
  /// search returns to the fraction that failed (1e5 samples: 1/1024 settled, 1/256 settled, 1/64
  /// failed, down to 1/1024, ... for 38 rounds and 250 s).
  bool retry_unsolved() {
    if (runs_.size() == 1 && settled_ == 0 && shrinks_ < max_shrinks) {
      t_ /= shrink_factor;
      ++shrinks_;
      return true;
    }
    return runs_.size() == 1 && halve_step();
  }

  /// The set changed by the evidence of the round just solved (out_.last).
  step after_round(bool seeded) {
    const round_state& last = *out_.last;
    const auto& co = last.outcome;
    if (co.code == status_code::contact_lost && co.lost && runs_.size() > 1) {
      drop(last.states.st[*co.lost].scene_index);
      return step::again;
    }
    if (co.code == status_code::contacts_merge && co.merged) {
      std::size_t i = last.states.st[co.merged->first].scene_index, j = last.states.st[co.merged->second].scene_index;
      if (i > j) std::swap(i, j);
      merge_runs(runs_, i, j);
      return step::again;
    }
    if (co.code != status_code::ok && restoring_) {
      undo_restoring();
      return step::again;
    }
    if (co.code != status_code::ok) return halve_step() ? step::again : step::stop;  // else reported as it is
    return after_converged(seeded);
  }

  /// Run k's contact vanished: its bumps count a drop, a lone seeded bump keeps its seed.
  void drop(std::size_t k) {
    for (std::size_t b = runs_[k].first; b <= runs_[k].last; ++b) ++dropped_[b];
    if (runs_[k].seed && runs_[k].first == runs_[k].last) lost_seeds_[runs_[k].first] = *runs_[k].seed;
    runs_.erase(runs_.begin() + static_cast<std::ptrdiff_t>(k));
  }

  /// Back to the round that converged without the restored contacts (solved again from its seeds);
  /// several are given back one at a time, a lone one is lost for good.
  void undo_restoring() {
    runs_ = std::move(restoring_->runs);
    lost_seeds_ = std::move(restoring_->lost);
    if (restoring_->restored.size() == 1) {
      dropped_[restoring_->restored.front()] = max_drops;
      lost_seeds_.erase(restoring_->restored.front());
    }
    restore_at_most_ = 1;
    out_.last.emplace(*last_converged_);
    restoring_.reset();
  }

  /// After a round that converged: lost contacts given back, a negative pressure repaired, a run
  /// widened, else the clearance checked and the penetrating bumps added.
  step after_converged(bool seeded) {
    const round_state& last = *out_.last;
    restoring_.reset();
    last_converged_.emplace(last);
    keep_solved(m_, last, seeded, runs_, shares_);
    if (seeded && !lost_seeds_.empty())
      if (const auto s = give_back_lost(last)) return *s;
    if (seeded && repair_tension(m_, last.states, runs_, repaired_, cx_.options.acceptance)) return step::again;
    if (widen(m_, runs_, last.states)) return step::again;
    return grow_or_settle(seeded, last);
  }

  /// restore_lost after a converged round: a round with the contacts it gives back (restoring_
  /// set), a stop to search again with spare lights (search_result::respare), or nothing to do.
  std::optional<step> give_back_lost(const round_state& last) {
    std::vector<run> runs_before = runs_;
    std::map<std::size_t, coarse_patch> lost_before = lost_seeds_;
    auto restored = restore_lost(m_, last.states, cx_, runs_, lost_seeds_, dropped_, restore_at_most_);
    if (!start_.spare && std::any_of(restored.begin(), restored.end(),
                                     [&](std::size_t b) { return seed_needed(lost_before, b, runs_before); }))
      return stop_to_respare();
    if (restored.empty()) return std::nullopt;
    restoring_ = restore_point{std::move(runs_before), std::move(lost_before), std::move(restored)};
    return step::again;
  }

  /// The search stops to search again with spare lights (search_result::respare): it was about to
  /// give back a contact it dropped whose seed was not light.
  step stop_to_respare() {
    out_.respare = true;
    out_.failure = needed_again;
    return step::stop;
  }

  /// The clearance of the converged round `last`: the bumps penetrating by more than the
  /// acceptance are added (again at the full load; below it the grown set starts the next load
  /// step), none settles the set at the full load.
  step grow_or_settle(bool seeded, const round_state& last) {
    out_.clear = check_clearance(m_, last.states, cx_);
    const auto added = growth(m_, last.states, out_.clear, runs_, dropped_, seeded, cx_.options.acceptance);
    if (seeded && !start_.spare && std::any_of(added.begin(), added.end(), [&](std::size_t b) {
          return dropped_[b] > 0 && seed_needed(lost_seeds_, b, runs_);
        }))
      return stop_to_respare();
    const bool grow = !added.empty();  // else nothing penetrates by more than tol: settled at this load
    if (grow) add_runs(m_, out_.clear, added, seeded, shares_, runs_);
    if (t_ == 1) return grow ? step::again : step::stop;  // (stop: settled at the full load)
    // Below the full load the grown set is not solved again at this t: it is the start of the
    // next step (the set only grows with the load; a bump lifted at the next step is dropped there).
    settled_ = t_;
    halvings_ = 0;
    t_ = std::min(1.0, t_ * load_step);
    // A bump dropped at a smaller load may carry load at a larger one.
    dropped_.assign(dropped_.size(), 0);
    lost_seeds_.clear();
    return step::again;
  }

  const profile_model& m_;
  const context& cx_;
  const search_start& start_;
  search_result out_;
  std::vector<run> runs_;
  // Times each bump was dropped at the current load; at max_drops it is not added again.
  std::vector<std::size_t> dropped_;
  // Bump -> the seed of the last contact lost on it alone (edges absolute, load per unit t); those
  // an earlier search at this load lost count as dropped once.
  std::map<std::size_t, coarse_patch> lost_seeds_;
  // Set while the contacts restore_lost gave back have not yet converged in a round.
  std::optional<restore_point> restoring_;
  // The last round whose coupled solve converged (reported when the search ends in a round that
  // failed, and the round a failed restoring goes back to: restoring_ is set only right after it).
  std::optional<round_state> last_converged_;
  // Contacts restore_lost gives back in one round (1 after a round with several failed).
  std::size_t restore_at_most_ = std::numeric_limits<std::size_t>::max();
  // Tip sample -> times a contact on it was started again for a negative pressure.
  std::map<std::size_t, std::size_t> repaired_;
  // Tip sample -> its load at the last solved set, per unit t.
  std::map<std::size_t, double> shares_;
  // t_: the fraction of the load; settled_: the last fraction at which the set settled (a failed
  // step halves towards it).
  double t_, settled_ = 0;
  std::size_t halvings_ = 0, shrinks_ = 0;
  const std::size_t max_rounds_;
};

search_result search_contact_set(const profile_model& m, const context& cx, const search_start& start) {
  return contact_search(m, cx, start).search();
}

/// The deepest sample of each bump that penetrates by more than tol (relative to the span),
/// deepest first, at most max_listed.
std::vector<double> missing_contacts(const clearance_check& c, double tol) {
  constexpr std::size_t max_listed = 16;
  std::vector<std::size_t> order;
  for (std::size_t b = 0; b < c.depth.size(); ++b)
    if (c.depth[b] > tol) order.push_back(b);
  std::sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return c.depth[p] > c.depth[q]; });
  if (order.size() > max_listed) order.resize(max_listed);
  std::vector<double> out;
  for (const std::size_t b : order) out.push_back(c.deepest_at[b]);
  return out;
}

/// "; the profile penetrates the surface (contacts missing) at x = .., .." or "".
std::string penetration_list(const std::vector<double>& at) {
  if (at.empty()) return "";
  std::ostringstream os;
  os.precision(6);
  os << "; the profile penetrates the surface (contacts missing) at x = ";
  for (std::size_t k = 0; k < at.size(); ++k) os << (k ? ", " : "") << at[k];
  return os.str();
}

/// The result of the last solved round with contact.cpp's evidence, the clearance, and the
/// search's own failure when it had one.
profile_result report_profile(const profile_model& m, const context& cx, const search_result& sr) {
  const auto& s = *m.source;
  const round_state& last = *sr.last;
  const double tol = cx.options.acceptance;
  const scene_result r = report_scene(last.sc, last.states, cx, last.outcome);
  profile_result out;
  out.beta = r.beta;
  out.kappa = r.kappa;
  out.regime = r.regime;
  out.contacts = r.indentors;
  out.surface_x = r.surface_x;
  out.surface = r.surface;
  for (auto& c : out.contacts) c.status = rename(c.status, m, last.runs);
  for (const run& rn : last.runs) out.tips.push_back(s.profile.x[m.tip(rn)]);
  out.body_approach = r.body_approach.value_or(std::numeric_limits<double>::quiet_NaN());
  out.diagnostics.residual = r.diagnostics.residual;
  out.diagnostics.code = r.diagnostics.code;
  // A converged round with contacts not ok: report_scene's summary again in the profile's terms
  // (its contacts' renamed statuses); else the round's own status, renamed.
  const std::string not_ok = last.outcome.code == status_code::ok ? contacts_not_ok(out.contacts, "contacts") : "";
  out.diagnostics.status = not_ok.empty() ? rename(r.diagnostics.status, m, last.runs) : not_ok;
  out.diagnostics.rounds = sr.rounds;
  out.diagnostics.iterations = sr.iterations;
  out.diagnostics.load_fraction = last.t;
  out.penetrations = missing_contacts(sr.clear, tol);
  const bool checked = last.outcome.code == status_code::ok && !sr.clear.depth.empty();
  out.clearance = !checked ? std::numeric_limits<double>::quiet_NaN()
                  : sr.clear.worst == std::numeric_limits<double>::infinity() ? 0.0
                                                                               : sr.clear.worst;
  out.clearance_at = checked ? sr.clear.worst_at : std::numeric_limits<double>::quiet_NaN();
  out.level_mismatch = checked ? sr.clear.level : std::numeric_limits<double>::quiet_NaN();
  out.level_mismatch_at = checked ? sr.clear.level_at : std::numeric_limits<double>::quiet_NaN();
  auto fail = [&](status_code code, const std::string& why) {
    if (out.diagnostics.code != status_code::ok) return;
    out.diagnostics.code = code;
    out.diagnostics.status = why;
  };
  for (std::size_t k = 0; k < out.contacts.size(); ++k) {
    const auto& c = out.contacts[k];
    if (c.a < s.profile.x.front() || c.b > s.profile.x.back())
      fail(status_code::not_converged, "contacts[" + std::to_string(k) + "] [" + num(c.a) + ", " + num(c.b) +
                                           "] leaves the samples [" + num(s.profile.x.front()) + ", " +
                                           num(s.profile.x.back()) + "]: extend the profile");
  }
  if (last.t < 1) {
    // Never a partial load presented as the answer: the status leads with it, whatever failed.
    std::ostringstream os;
    os.precision(3);
    os << "the search reached only " << last.t << " of body.load (" << last.t * s.load << " of " << s.load
       << ")" << penetration_list(out.penetrations) << ": "
       << (!sr.failure.empty() ? sr.failure : out.diagnostics.status);
    out.diagnostics.code = out.diagnostics.code == status_code::ok ? status_code::not_converged : out.diagnostics.code;
    out.diagnostics.status = os.str();
  }
  if (!sr.failure.empty()) {
    // The search's own reason (the time limit, the round limit) is said even when the round it
    // reports already failed for another.
    if (out.diagnostics.code == status_code::ok)
      fail(status_code::not_converged, sr.failure + penetration_list(out.penetrations));
    else if (out.diagnostics.status.find(sr.failure) == std::string::npos)
      out.diagnostics.status += "; " + sr.failure;
  }
  if (out.clearance < -tol) {
    std::ostringstream os;
    os.precision(3);
    os << "the profile penetrates the surface by " << -out.clearance << " of max z - min z at x = " << out.clearance_at
       << " (outside the contacts found: a contact there vanished in an earlier round, or lies inside a merged "
          "contact's basins)";
    fail(status_code::penetration, os.str());
  }
  if (out.level_mismatch > tol) {
    std::ostringstream os;
    os.precision(3);
    os << "the contact at x = " << out.level_mismatch_at << " lies " << out.level_mismatch
       << " of max z - min z off the body's level (the coupled iteration did not converge there)";
    fail(status_code::not_converged, os.str());
  }
  return out;
}

/// The search from `start` (a seeded start, or continuation_start), reported; empty when not
/// even its first round could be solved.
std::optional<window_solution> search_and_report(const profile_model& m, const context& cx, const search_start& start,
                                                 std::string& failure) {
  const search_result sr = search_contact_set(m, cx, start);
  cx.throw_if_interrupted(who);
  failure = sr.failure;
  if (!sr.last) return std::nullopt;
  window_solution out;
  out.result = report_profile(m, cx, sr);
  out.origin = sr.last->states.origin;
  out.max_degree = cx.options.max_degree;
  out.lost = sr.lost;
  out.respare = sr.respare;
  out.spare = start.spare;
  out.densities.resize(sr.last->states.st.size());
  for (const auto& state : sr.last->states.st) out.densities[state.scene_index] = state.g;
  return out;
}

/// Whether a result missed the acceptance only because a contact's series stopped at
/// solve_options::max_degree (below `degree`), with time left to solve again. WHY: a contact
/// spanning several samples carries the spline's C2 joints, so its series converges algebraically
/// (a self-affine profile's contact over ~10 samples: residual of (8) 5e-6 at degree 127, 2e-8 at
/// 511), while the contacts of smooth bumps need no more than the default (50 cosine bumps: 0.55 s
/// at 128, 11 s when every contact may go to 512 chasing the tolerance).
/// Beyond the first of profile_degrees, only a search that reached the full load without
/// penetrations and whose every failing contact is such a one runs again (a 16000-sample profile
/// that ended at 1/4 of its load spent its remaining 40 s of --time-limit 60 at degree 1024).
bool needs_degree(const profile_result& r, const context& cx, std::size_t degree) {
  if (r.diagnostics.code == status_code::ok || cx.options.max_degree >= degree || cx.out_of_time()) return false;
  const auto capped = [&](const indentor_result& c) {
    return c.degree + 1 >= cx.options.max_degree && c.residual > cx.options.acceptance;
  };
  if (degree > profile_degrees[0]) {
    if (r.diagnostics.load_fraction < 1 || !r.penetrations.empty()) return false;
    for (const auto& c : r.contacts)
      if (c.code != status_code::ok && !capped(c)) return false;
  }
  return std::any_of(r.contacts.begin(), r.contacts.end(), capped);
}

/// Whether result p is nearer the answer than q: ok first, then the larger fraction of the load,
/// then fewer contacts missing (penetrations), then the smaller residual. WHY: the continuation
/// from the highest tip, run when the seeded search did not end ok, can end further from the
/// answer than it (1e5-sample periodic profile: the seeded search ended at the full load with one
/// contact in tension; the continuation's result, reported instead, was further from the answer).
bool nearer(const profile_result& p, const profile_result& q) {
  const auto rank = [](const profile_result& r) {
    return std::tuple(r.diagnostics.code == status_code::ok ? 0 : 1, -r.diagnostics.load_fraction, r.penetrations.size(),
                      std::isnan(r.diagnostics.residual) ? std::numeric_limits<double>::infinity() : r.diagnostics.residual);
  };
  return rank(p) < rank(q);
}

/// Which result keep_nearer keeps when neither is nearer than the other.
enum class on_tie { first, second };

/// The nearer of two searches' results (nearer), `tie`'s when neither is, with the rounds and
/// iterations of both searches.
window_solution keep_nearer(window_solution first, window_solution second, on_tie tie) {
  const auto rounds = first.result.diagnostics.rounds + second.result.diagnostics.rounds;
  const auto iterations = first.result.diagnostics.iterations + second.result.diagnostics.iterations;
  const bool second_kept =
      tie == on_tie::first ? nearer(second.result, first.result) : !nearer(first.result, second.result);
  window_solution out = std::move(second_kept ? second : first);
  out.result.diagnostics.rounds = rounds;
  out.result.diagnostics.iterations = iterations;
  return out;
}

/// The search from `held_start` (seeds holding their degrees, coarse_patch::degree); when it does
/// not end ok and `retry` says of its result that a held contact may be why, once more from
/// `free_start()` (every contact free to climb; made only then), the nearer result of the two
/// (keep_nearer) kept with the rounds and iterations of both. WHY: a contact held at its degree
/// whose edges then moved can miss the acceptance there, and the degree ladder (needs_degree)
/// raises only contacts at the top degree, so the held one would end the search.
template <class Retry, class FreeStart>
std::optional<window_solution> search_held(const profile_model& m, const context& cx, const search_start& held_start,
                                           FreeStart free_start, Retry retry, std::string& failure) {
  auto first = search_and_report(m, cx, held_start, failure);
  if (!first || first->result.diagnostics.code == status_code::ok || first->respare || cx.out_of_time() ||
      !retry(first->result))
    return first;
  auto again = search_and_report(m, cx, free_start(), failure);
  if (!again) return first;
  return keep_nearer(std::move(*first), std::move(*again), on_tie::first);
}

/// `out` searched again with the series to each of profile_degrees while needs_degree (the clock
/// and the interrupt shared; rounds and iterations add up), from its own contacts when it reached
/// the full load (each within capped_below of the acceptance holding its degree), else from
/// `start`; the nearest of the ladder's results is reported (nearer). WHY its contacts: its set is
/// the answer but for the degree and for the contacts it misses, which the search adds where the
/// surface penetrates; from the coarse seeds each degree repeated the rounds that found it
/// (self-affine, 1000 samples, seed 1, load 2e-3: two rounds of 4.6 s and 13 s at degree 1024; 1e5
/// samples, periodic, 233 contacts: the degree-128 round ended at the full load with 3
/// penetrations, and from the coarse seeds the degree-512 round dropped the same vanishing seeds
/// and merged the same pairs again, each a round of 1-2 min).
window_solution raise_degree(const profile_model& m, const context& cx, window_solution out, const search_start& start) {
  context wide = cx;
  std::optional<window_solution> passed;  // the nearest result the ladder went on from (nearer)
  for (const std::size_t degree : profile_degrees) {
    if (!needs_degree(out.result, wide, degree)) continue;
    // A contact held at an earlier search's top degree (capped_below) that then missed the
    // acceptance (its edges moved): the search from the free contacts follows (search_held).
    const std::size_t below = wide.options.max_degree;  // the last search's top degree
    const auto held_failed = [&](const profile_result& r) {
      return std::any_of(r.contacts.begin(), r.contacts.end(), [&](const indentor_result& c) {
        const std::size_t top = c.degree + 1;
        return c.residual > cx.options.acceptance && (top == below || top == cx.options.max_degree);
      });
    };
    wide.options.max_degree = degree;
    // From its own contacts (capped, then free) when it reached the full load, else from the start.
    const bool own = out.result.diagnostics.load_fraction == 1;
    wide.ladder = own;  // (its rounds polish the set found at the degree below: context::ladder)
    const auto from = [&](bool capped) {
      if (own)
        if (auto seeds = start_from(m, capped ? out.contacts_capped(capped_below * cx.options.acceptance) : out.contacts(),
                                      seed_edges::solved)) {
          seeds->lost = out.lost;  // restore_lost goes on checking them
          seeds->spare = start.spare;
          return std::move(*seeds);
        }
      return start;
    };
    std::string failure;
    auto again = search_held(
        m, wide, from(true), [&] { return from(false); }, [&](const profile_result& r) { return own && held_failed(r); },
        failure);
    if (!again) break;
    again->result.diagnostics.rounds += out.result.diagnostics.rounds;
    again->result.diagnostics.iterations += out.result.diagnostics.iterations;
    if (!passed || nearer(out.result, passed->result)) passed = std::move(out);
    out = std::move(*again);
    if (out.respare) return out;  // (solve_model searches again)
  }
  // A higher degree's search that ended further from the answer than a lower one's (a contact
  // lost or in tension, the time limit reached at a lower load): the nearer is reported, with the
  // rounds and iterations of all.
  if (passed && nearer(passed->result, out.result)) {
    passed->result.diagnostics.rounds = out.result.diagnostics.rounds;
    passed->result.diagnostics.iterations = out.result.diagnostics.iterations;
    return std::move(*passed);
  }
  return out;
}

/// Whether a start's seeds hold degrees (coarse_patch::degree).
bool held(const search_start& start) {
  return std::any_of(start.runs.begin(), start.runs.end(), [](const run& r) { return r.seed && r.seed->degree > 0; });
}

/// The seeded search from `predicted` at each degree it needs (raise_degree); when that does not
/// end ok, the continuation from the highest tip (then its degrees, from `predicted` below the
/// full load), and the nearer of the two results (nearer) is reported. WHY the degrees first: a
/// seeded round whose contacts span several samples stalls at the floor of its series (4000
/// samples, periodic, seed 3, load 3e-3: the largest edge condition 1e-3 at degree 128, ok at
/// 512), and the continuation from one tip spent the time limit before the degree was raised.
window_solution solve_model(const profile_model& m, const context& cx, const std::optional<search_start>& predicted) {
  std::optional<window_solution> seeded;
  std::string failure;
  // The seeded search from `from` at each degree it needs.
  const auto search_seeded = [&](const search_start& from) -> std::optional<window_solution> {
    // Seeds holding their degrees (a periodic profile's next pass) that did not end ok: once more
    // with every contact free to climb (search_held).
    const auto free = [&] {
      search_start out = from;
      for (run& r : out.runs)
        if (r.seed) r.seed->degree = 0;
      return out;
    };
    auto first = search_held(m, cx, from, free, [&](const profile_result&) { return held(from); }, failure);
    if (!first || first->respare) return first;
    return raise_degree(m, cx, std::move(*first), from);
  };
  if (predicted) {
    seeded = search_seeded(*predicted);
    // A search that stopped to add back a contact it dropped: again, sparing light contacts
    // (search_start::spare), its result kept if nearer.
    if (seeded && seeded->respare && !cx.out_of_time()) {
      search_start spared = *predicted;
      spared.spare = true;
      if (auto second = search_seeded(spared))
        seeded = keep_nearer(std::move(*seeded), std::move(*second), on_tie::second);
    }
    if (seeded && (seeded->result.diagnostics.code == status_code::ok || cx.out_of_time())) return std::move(*seeded);
  }
  const search_start from_tip = continuation_start(m);
  auto again = search_and_report(m, cx, from_tip, failure);
  // Not even the highest tip alone at 16^-12 of the load: no contact interval (as solve for one
  // indentor without one).
  if (!again) {
    if (seeded) return std::move(*seeded);
    throw std::domain_error(std::string(who) + ": no contact found: " + failure);
  }
  window_solution out = raise_degree(m, cx, std::move(*again), predicted ? *predicted : from_tip);
  if (seeded) return keep_nearer(std::move(*seeded), std::move(out), on_tie::second);
  return out;
}

}  // namespace

window_solution search_window(const profile_scene& window, const profile_curve& curve, const context& cx,
                              const std::vector<coarse_patch>& seeds, std::shared_ptr<coupled::jacobian_memo> memo,
                              const std::vector<coarse_patch>& lost, bool spare) {
  profile_model m(window, curve);
  if (memo) m.jacobian = std::move(memo);
  if (m.bumps.empty() || first_runs(m).empty())
    throw std::domain_error(std::string(who) + ": the profile corrected by the other periods has no tip inside the window");
  auto start = seeds.empty() ? predicted_start(m, cx) : start_from(m, seeds, seed_edges::coarse);
  if (start) {
    start->lost = lost_on_bumps(m, lost);
    start->spare = spare;
  }
  return solve_model(m, cx, start);
}

/// WHY the integrals, not the lengths: the parts of a contact over two summits of different heights
/// carry different pressures; shared by length (1e5-sample periodic profile, seed 2, load 6e-3: 58 %
/// of the load to the longer part, whose density carries 51 %), the overloaded part grew into the
/// other until their gap closed, and the search cycled between the pair and the merged contact
/// (negative inside, -0.7 % of the mean) until its repairs ran out (repair_tension). Solved loads:
/// the next round starts from the edges that carry them (coupled_solve.cpp, loads_imposed_start).
std::pair<coarse_patch, coarse_patch> split_seed(const coarse_patch& seed, const contact_density& g, double lo, double hi,
                                                 double origin) {
  const double before = g.integral_to(lo), after = g.integral_from(hi);
  // (A part whose integral is not positive, negative elsewhere too: shared by length instead.)
  const double share =
      before > 0 && after > 0 ? after / (before + after) : (seed.b - hi - origin) / (seed.b - seed.a - (hi - lo));
  const double after_load = seed.load * share;
  return {coarse_patch{seed.a, lo + origin, seed.load - after_load, 0, true},
          coarse_patch{hi + origin, seed.b, after_load, 0, true}};
}

/// A result that is not ok from a search whose time ran out says so, whichever stage it was in.
/// WHY: the degree ladder (raise_degree), the continuation after the seeded search (solve_model)
/// and a periodic profile's passes stop at the limit between two searches and report the last
/// one as it failed: a 1e5-sample periodic profile (self_affine_profile.py 100000 2 6e-3) at
/// --time-limit 600 said only "see contacts[44].status" (a contact's residual at degree 512).
void say_time_limit(profile_result& r, const context& cx) {
  if (r.diagnostics.code == status_code::ok || !cx.out_of_time()) return;
  const std::string limit = cx.time_limit_message();
  if (r.diagnostics.status.find(limit) == std::string::npos) r.diagnostics.status += "; " + limit;
}

/// The body's C_f, mean pressure and contact fraction from the contacts (profile_result).
void body_totals(profile_result& r, const profile_scene& s) {
  double load = 0, moment = 0, width = 0;
  for (const auto& c : r.contacts) load += c.load, moment += c.load * c.hysteretic_friction, width += c.contact_length;
  r.hysteretic_friction = load > 0 ? moment / load : 0.0;
  r.total_friction = r.hysteretic_friction + s.material.coulomb;
  const double length = s.profile.period > 0 ? s.profile.period : s.profile.x.back() - s.profile.x.front();
  r.mean_pressure = s.load / length;
  if (!(s.profile.period > 0)) r.window_start = s.profile.x.front();
  r.contact_fraction = width / length;
}

}  // namespace detail

profile_result solve_profile(const profile_scene& s, const solve_options& options) {
  using namespace detail;
  const auto start = std::chrono::steady_clock::now();
  validate_profile(s, who);
  validate_options(options, who);
  if (s.profile.period > 0) {
    const context cx = make_context(s.material, s.speed, options);
    profile_result out = solve_periodic_profile(s, cx);
    cx.throw_if_interrupted(who);
    say_time_limit(out, cx);
    body_totals(out, s);
    out.diagnostics.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  }
  const profile_model m(s);
  if (m.bumps.empty())
    bad("profile.z has no local maximum inside the data (its highest samples are at an end): extend the samples "
        "beyond the contact");
  if (first_runs(m).empty())
    bad("profile.z is highest at an end of the data (x = " +
        num(s.profile.z.front() == m.top ? s.profile.x.front() : s.profile.x.back()) +
        "): the first contact would leave the samples; extend them");
  const context cx = make_context(s.material, s.speed, options);
  profile_result out = solve_model(m, cx, predicted_start(m, cx)).result;
  say_time_limit(out, cx);
  body_totals(out, s);
  out.diagnostics.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rhabel::punch
