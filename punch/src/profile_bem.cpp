// punch/src/profile_bem.cpp: a sampled profile on one rigid body by the boundary-element method
// (rhabel/punch/profile_bem.hpp): grids refined until the extrapolated loads and C_f meet the
// acceptance.
#include "rhabel/punch/profile_bem.hpp"

#include "internal.hpp"
#include "active_solve.hpp"
#include "panel_grid.hpp"
#include "profile_curve.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace rhabel::punch {
namespace detail {
namespace {

constexpr const char* who = "rhabel::punch::solve_profile_bem";
// The first grid (every panel active; its LU: 256^3 flops) and the grids below n0, refined by 4.
constexpr std::size_t first_panels = 256;
// Geometric convergence is taken as observed when the ratio of the last two differences is
// positive and below this (h^1 gives 0.5, h^2 0.25; above 0.75 the extrapolation would multiply
// the last difference by more than 3 on a guess).
constexpr double max_ratio = 0.75;

std::string num(double v, int digits = 3) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

/// One patch of one grid: edges, int g and int z' g (units of int g; z' g physical / length).
struct raw_patch {
  double a = 0, b = 0, load = 0, moment = 0, peak = 0;
  double first = 0, second = 0;  // int g (x - a) and int g (x - a)^2 [m, m^2 times units of int g]
  /// 4 standard deviations of the patch's density (bem_patch::pressure_width).
  double pressure_width() const {
    const double mean = first / load;
    return 4 * std::sqrt(std::max(0.0, second / load - mean * mean));
  }
};

/// What one grid gives: its patches and the body's C_f and contact fraction.
struct level {
  std::size_t n = 0;
  double h_length = 0;  // a panel [m]
  std::vector<raw_patch> patches;
  double friction = 0, fraction = 0;
};

/// The patches of the active panels idx with densities g (periodic: a run through the window's end
/// and one through its start are one patch, reported from its start in the last period).
level measure(const panel_grid& gr, const std::vector<std::size_t>& idx, const Eigen::VectorXd& g, double load) {
  level lv;
  lv.n = gr.n;
  lv.h_length = gr.h * gr.length;
  for (const auto& [s, e] : runs_of(idx)) {
    raw_patch p;
    p.a = gr.edge(idx[static_cast<std::size_t>(s)]);
    p.b = gr.edge(idx[static_cast<std::size_t>(e - 1)] + 1);
    const double panel = lv.h_length;
    for (Eigen::Index c = s; c < e; ++c) {
      const double gc = g[c];
      p.load += gr.h * gc;
      p.moment += gc * gr.rise[idx[static_cast<std::size_t>(c)]] / gr.length;
      p.peak = std::max(p.peak, gc / gr.length);
      // The panel's moments exactly for a constant density: centre u, int (x - a)^2 = h (u^2 + h^2/12).
      const double u = (static_cast<double>(c - s) + 0.5) * panel;
      p.first += gr.h * gc * u;
      p.second += gr.h * gc * (u * u + panel * panel / 12);
    }
    lv.patches.push_back(p);
  }
  if (gr.periodic && lv.patches.size() > 1 && idx.front() == 0 && idx.back() == gr.n - 1) {
    raw_patch& first = lv.patches.front();
    raw_patch& last = lv.patches.back();
    // The wrapped part's moments about the last run's start: its offset is last.b - last.a.
    const double shift = last.b - last.a;
    last.first += first.first + shift * first.load;
    last.second += first.second + 2 * shift * first.first + shift * shift * first.load;
    last.b = first.b + gr.length;
    last.load += first.load;
    last.moment += first.moment;
    last.peak = std::max(last.peak, first.peak);
    lv.patches.erase(lv.patches.begin());
  }
  double moment = 0, width = 0;
  for (const auto& p : lv.patches) moment += p.moment, width += p.b - p.a;
  lv.friction = moment / load;
  lv.fraction = width / gr.length;
  return lv;
}

/// The limit of v0, v1, v2 (grids h, h/2, h/4) with its error estimate (profile_bem.hpp, THE METHOD).
bem_estimate extrapolate(double v0, double v1, double v2) {
  const double d1 = v1 - v0, d2 = v2 - v1;
  if (d1 != 0 && d2 / d1 > 0 && d2 / d1 < max_ratio) {
    const double r = d2 / d1, limit = v2 + d2 * r / (1 - r);
    return {limit, std::abs(limit - v2) + std::abs(d2)};
  }
  return {v2, 2 * std::max(std::abs(d1), std::abs(d2))};
}

/// The finite window's contacts must stay inside the samples (profile_bem.hpp, LIMITS).
void refuse_end_contact(const panel_grid& gr, const std::vector<std::size_t>& idx, double load_phys) {
  if (gr.periodic || idx.empty() || (idx.front() != 0 && idx.back() != gr.n - 1)) return;
  const double at = idx.front() == 0 ? gr.edge(0) : gr.edge(gr.n);
  throw std::domain_error(std::string(who) + ": at body.load = " + num(load_phys, 17) +
                          " the contacts reach the end of the samples at x = " + num(at, 17) +
                          ": extend profile.x and profile.z beyond it, lower body.load, or give profile.period");
}

/// The panels n0 of the first extrapolation grid: the samples' intervals doubled to >= 256.
std::size_t base_panels(const profile_curve& curve) {
  std::size_t n = curve.period() > 0 ? curve.x().size() : curve.x().size() - 1;
  while (n < first_panels) n *= 2;
  return n;
}

/// The patches of the last three levels matched (the extrapolation's premise). A patch of the last
/// level that carries more than `floor` (acceptance x P) is matched to the one patch of each
/// coarser level that overlaps it (within that level's panel; periodic: modulo the period) when
/// there is exactly one and no other patch of the last level claims it (else the patches split
/// or merged between the grids). Patches at or below the floor may come and go between grids (a
/// patch that may or may not exist within the acceptance): they are not matched.
struct patch_match {
  std::vector<std::optional<std::array<std::size_t, 3>>> of;  ///< per patch of the last level
  bool complete = false;  ///< every patch above the floor (on any of the three levels) matched
};

patch_match match_patches(const std::vector<level>& lv, double floor, double length, bool periodic) {
  patch_match out;
  const std::size_t m = lv.size();
  if (m == 0) return out;
  const level& last = lv.back();
  out.of.resize(last.patches.size());
  if (m < 3) return out;
  // The length common to p and q (shifted by a period where that is more), plus the slack: > 0
  // when they overlap within the slack.
  auto common = [&](const raw_patch& p, const raw_patch& q, double slack) {
    double best = -1;
    for (int shift = periodic ? -1 : 0; shift <= (periodic ? 1 : 0); ++shift) {
      const double d = shift * length;
      best = std::max(best, std::min(p.b + d, q.b) - std::max(p.a + d, q.a) + slack);
    }
    return best;
  };
  out.complete = true;
  std::array<std::vector<std::size_t>, 2> claims{std::vector<std::size_t>(lv[m - 3].patches.size(), 0),
                                                 std::vector<std::size_t>(lv[m - 2].patches.size(), 0)};
  for (std::size_t k = 0; k < last.patches.size(); ++k) {
    const raw_patch& p = last.patches[k];
    if (p.load <= floor) continue;
    std::array<std::size_t, 3> at{0, 0, k};
    bool found = true;
    for (std::size_t j = 0; j < 2 && found; ++j) {
      const level& coarse = lv[m - 3 + j];
      double best = 0;
      found = false;
      for (std::size_t c = 0; c < coarse.patches.size(); ++c)
        if (const double o = common(coarse.patches[c], p, coarse.h_length); o > best) best = o, at[j] = c, found = true;
    }
    if (!found) {
      out.complete = false;
      continue;
    }
    ++claims[0][at[0]], ++claims[1][at[1]];
    out.of[k] = at;
  }
  std::array<std::vector<char>, 2> chosen{std::vector<char>(claims[0].size(), 0), std::vector<char>(claims[1].size(), 0)};
  for (auto& at : out.of) {
    if (!at) continue;
    chosen[0][(*at)[0]] = chosen[1][(*at)[1]] = 1;
    if (claims[0][(*at)[0]] > 1 || claims[1][(*at)[1]] > 1) at.reset(), out.complete = false;
  }
  // A patch of a coarser level with more than twice the floor that no patch of the last level above
  // the floor took as its partner vanished or merged (twice: a patch near the floor may fall below
  // it on the finer grid without having changed by more than the floor).
  for (std::size_t j = 0; j < 2; ++j)
    for (std::size_t c = 0; c < chosen[j].size(); ++c)
      if (!chosen[j][c] && lv[m - 3 + j].patches[c].load > 2 * floor) out.complete = false;
  return out;
}

/// The search over the grids: levels holds the grids n0 2^k solved (the evidence), match their
/// last three's patches (match_patches, updated with each level).
struct grid_search {
  std::vector<level> levels;
  patch_match match;
  std::size_t steps = 0;
  std::string stopped;  // why the refinement stopped before the acceptance was met ("" if it was)
};

/// Whether the last three levels, their patches matched, meet the acceptance (profile_bem.hpp,
/// STATUS).
bool accepted(const std::vector<level>& lv, const patch_match& match, double tol, double slope, double load) {
  if (!match.complete) return false;
  const level &l0 = lv[lv.size() - 3], &l1 = lv[lv.size() - 2], &l2 = lv.back();
  if (extrapolate(l0.friction, l1.friction, l2.friction).error > tol * slope) return false;
  for (const auto& at : match.of)
    if (at && extrapolate(l0.patches[(*at)[0]].load, l1.patches[(*at)[1]].load, l2.patches[(*at)[2]].load).error > tol * load)
      return false;
  return true;
}

grid_search refine(const profile_curve& curve, double load, double load_phys, const context& cx, const bem_options& bo,
                   double slope) {
  const auto [lo, hi] = std::minmax_element(curve.z().begin(), curve.z().end());
  const double top = *hi, span = *hi - *lo;
  const std::size_t n0 = base_panels(curve);
  grid_search gs;
  std::size_t n = std::min(first_panels, n0);
  std::vector<char> active(n, 1);
  Eigen::VectorXd g;
  std::vector<std::size_t> idx;
  warm_start ws;  // each solve starts from the last one
  try {
    for (;;) {
      panel_grid gr = make_panel_grid(curve, n, cx, top);
      double D = 0;
      if (!settle(gr, load, span, active, g, idx, D, cx, gs.steps, gs.steps == 0 ? first_grid_steps : refined_grid_steps, ws)) {
        gs.stopped = "the active set did not settle on " + std::to_string(n) + " panels";
        return gs;
      }
      if (n >= n0) {
        if (n == n0) refuse_end_contact(gr, idx, load_phys);
        gs.levels.push_back(measure(gr, idx, g, load));
        gs.match = match_patches(gs.levels, cx.options.acceptance * load, gr.length, gr.periodic);
        if (accepted(gs.levels, gs.match, cx.options.acceptance, slope, load)) return gs;
      }
      const std::size_t next = n < n0 ? std::min(4 * n, n0) : 2 * n;
      if (next > bo.max_panels) {
        gs.stopped = "the next grid would exceed max_panels = " + std::to_string(bo.max_panels);
        return gs;
      }
      active = refine_active(active, next);
      n = next;
    }
  } catch (const time_limit_reached&) {
    gs.stopped = cx.time_limit_message();
  }
  return gs;
}

/// The reported values from the last (up to three) levels.
void report(const grid_search& gs, double pressure_scale, double length, profile_bem_result& out) {
  const level& last = gs.levels.back();
  const std::size_t m = gs.levels.size();
  const patch_match& match = gs.match;
  const bool three = match.complete;
  auto estimate = [&](auto value_of) -> bem_estimate {
    if (three) return extrapolate(value_of(gs.levels[m - 3]), value_of(gs.levels[m - 2]), value_of(last));
    if (m >= 2) return {value_of(last), 2 * std::abs(value_of(last) - value_of(gs.levels[m - 2]))};
    return {value_of(last), std::abs(value_of(last))};
  };
  for (std::size_t k = 0; k < last.patches.size(); ++k) {
    const raw_patch& p = last.patches[k];
    bem_patch bp;
    bp.a = p.a;
    bp.b = p.b;
    bp.edge_error = last.h_length;
    if (const auto& at = match.of[k]) {
      const raw_patch &p0 = gs.levels[m - 3].patches[(*at)[0]], &p1 = gs.levels[m - 2].patches[(*at)[1]];
      bp.load = extrapolate(p0.load, p1.load, p.load);
      bp.hysteretic_friction = extrapolate(p0.moment / p0.load, p1.moment / p1.load, p.moment / p.load);
    } else {  // a patch not matched on three grids (or at most the floor): its own size as its error
      bp.load = {p.load, p.load};
      bp.hysteretic_friction = {p.moment / p.load, std::abs(p.moment / p.load)};
    }
    bp.load.value *= pressure_scale;
    bp.load.error *= pressure_scale;
    bp.peak_pressure = pressure_scale * p.peak;
    bp.pressure_width = p.pressure_width();
    out.patches.push_back(bp);
  }
  out.hysteretic_friction = estimate([](const level& l) { return l.friction; });
  out.contact_fraction = {last.fraction, 2 * static_cast<double>(last.patches.size()) * last.h_length / length};
  for (const level& l : gs.levels) {
    out.diagnostics.level_panels.push_back(l.n);
    out.diagnostics.level_patches.push_back(l.patches.size());
    out.diagnostics.level_friction.push_back(l.friction);
  }
  out.diagnostics.panels = last.n;
}

}  // namespace
}  // namespace detail

profile_bem_result solve_profile_bem(const profile_scene& s, const solve_options& options, const bem_options& bem) {
  using namespace detail;
  const auto start = std::chrono::steady_clock::now();
  validate_profile(s, who);
  validate_options(options, who);
  if (bem.max_panels < first_panels)
    throw std::invalid_argument(std::string(who) + ": bem_options::max_panels = " + std::to_string(bem.max_panels) +
                                " must be >= " + std::to_string(first_panels));
  const context cx = make_context(s.material, s.speed, options);
  const profile_curve curve(s.profile);
  const double length = s.profile.period > 0 ? s.profile.period : s.profile.x.back() - s.profile.x.front();
  // max |z'| of the spline at the samples: the scale of C_f.
  double slope = 0;
  for (double x : s.profile.x) slope = std::max(slope, std::abs(curve.slope(x)));
  const grid_search gs = refine(curve, s.load / cx.pressure_scale, s.load, cx, bem, slope);
  cx.throw_if_interrupted(who);

  profile_bem_result out;
  out.beta = cx.beta;
  out.kappa = cx.kappa;
  out.regime = regime(s.material);
  out.period = s.profile.period;
  out.mean_pressure = s.load / length;
  out.diagnostics.active_set_steps = gs.steps;
  if (gs.levels.empty()) {
    out.diagnostics.code = status_code::not_converged;
    out.diagnostics.status = "no grid of " + std::to_string(base_panels(curve)) + " panels or more was solved: " +
                             gs.stopped;
  } else {
    report(gs, cx.pressure_scale, length, out);
    if (!gs.stopped.empty()) {
      out.diagnostics.code = status_code::not_converged;
      std::ostringstream os;
      os.precision(3);
      os << gs.stopped << " before the acceptance " << options.acceptance << " was met: C_f "
         << out.hysteretic_friction.value << " +- " << out.hysteretic_friction.error << " (bar "
         << options.acceptance * slope << " = acceptance x max |z'|), patches on the last grids:";
      const auto& lp = out.diagnostics.level_patches;
      for (std::size_t k = lp.size() > 3 ? lp.size() - 3 : 0; k < lp.size(); ++k) os << ' ' << lp[k];
      out.diagnostics.status = os.str();
    } else {
      out.diagnostics.status = "ok";
    }
  }
  out.total_friction = out.hysteretic_friction.value + s.material.coulomb;
  out.diagnostics.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rhabel::punch
