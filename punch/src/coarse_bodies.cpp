// punch/src/coarse_bodies.cpp: the coarse solve of several independent indentors on one grid
// (coarse_bodies.hpp).
#include "coarse_bodies.hpp"

#include "panel_grid.hpp"
#include "surface.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace rhabel::punch::detail {
namespace {

using Eigen::Index;

// Panels of the first window (the isolated contacts' hull and its length on each side) and of the
// second (the loaded hull and a quarter of its length on each side): the second resolves the
// three parabolas of coarse_bodies.hpp to ~1/700 of their hull, gaps of 0.04-0.06 to 10-15 panels.
constexpr std::size_t first_window_panels = 256, second_window_panels = 512;
// A window whose end panel is loaded is widened (twice over) at most this many times.
constexpr int max_widenings = 3;
// Steps of the active set at given levels (started from the last levels' set: a few).
constexpr std::size_t max_press_steps = 200;
// A panel is penetrated when w < phi by more than this fraction of the profiles' span over the
// window (round-off of the dense solve).
constexpr double owner_floor = 1e-9;
// Matching the loads (match_loads): Newton's method on the levels aims at load_match (relative),
// at most max_level_iterations steps, its Jacobian by steps of level_step of the span. The loads
// are piecewise smooth in the levels and jump where a panel changes hands between two indentors
// (measured: a light contact of 3 panels on the first window, its load jumping from +4 % to -25 %
// of its own), so a window is solved when every load is within coarse_within (first window: it
// only places the second) or fine_within (second window; its edges are a panel off anyway).
constexpr std::size_t max_level_iterations = 40;
constexpr double load_match = 1e-8, level_step = 1e-6;
constexpr double coarse_within = 0.1, fine_within = 0.01;
// Gauss-Seidel sweeps (one level alone, the others fixed) before Newton while some indentor
// carries less than carried_share of its load (no derivative there), and after Newton stalls:
// at most max_sweeps a round, max_rounds rounds. A level alone is bracketed from bracket_step of
// the span, and at a jump its nearer end is taken when within jump_within. (The three parabolas of
// coarse_bodies.hpp start with two indentors carrying nothing: one sweep, then Newton in 4 steps.)
constexpr std::size_t max_sweeps = 30, max_rounds = 4;
constexpr double carried_share = 0.01, bracket_step = 1e-3, jump_within = 0.25;
// Indentors at most: each costs a column of the levels' Jacobian (an evaluation of the loads) and
// a level of the sweeps, and 512 panels resolve no more than a few tens of contacts anyway (fewer
// than min_owned_panels each gives no start).
constexpr std::size_t max_bodies = 16;
// Panels an indentor needs on the second window for its interval to be a start (fewer: the grid
// does not resolve it, and no start is better than a wrong one).
constexpr std::size_t min_owned_panels = 6;

/// The window [lo, lo + length] cut into n panels (unit width h = 1/n after scaling, as in
/// panel_grid.hpp) and each indentor's rigid profile at the collocation points.
struct body_grid {
  double lo = 0, length = 0, h = 0;
  std::size_t n = 0;
  std::vector<double> kernel;          ///< finite_panel_kernel
  std::vector<std::vector<double>> z;  ///< z[k][i]: f_k at collocation point i, f_k(apex) = 0
  double A(std::size_t i, std::size_t j) const { return kernel[j + n - 1 - i]; }
  double edge(std::size_t k) const { return lo + length * static_cast<double>(k) * h; }
  double at(std::size_t i, double theta) const { return lo + length * (static_cast<double>(i) + theta) * h; }
};

body_grid make_body_grid(const std::vector<indentor_state>& st, double lo, double hi, std::size_t n, const context& cx) {
  body_grid gr;
  gr.lo = lo;
  gr.length = hi - lo;
  gr.n = n;
  gr.h = 1.0 / static_cast<double>(n);
  gr.kernel = finite_panel_kernel(n, gr.length, cx);
  const surface sf(st, cx);
  gr.z.assign(st.size(), std::vector<double>(n));
  for (std::size_t k = 0; k < st.size(); ++k)
    for (std::size_t i = 0; i < n; ++i) gr.z[k][i] = sf.rise(k, st[k].apex, gr.at(i, collocation_theta));
  return gr;
}

/// g on the panels idx, panel c loaded by indentor of[c] (0 .. K-1, each at least once), and the
/// levels D of the K indentors whose profiles are z[k]: one LU of
/// [A, -S; sigma h S^T, 0] (g, D) = (z_of, sigma P), sigma putting the load rows on the kernel's
/// scale. False when the solve is not finite.
bool solve_loaded(const body_grid& gr, const std::vector<std::size_t>& idx, const std::vector<std::size_t>& of,
                  const std::vector<const std::vector<double>*>& z, const std::vector<double>& load, Eigen::VectorXd& g,
                  Eigen::VectorXd& D) {
  const auto m = static_cast<Index>(idx.size()), K = static_cast<Index>(load.size());
  double sigma = 0;
  for (const double v : gr.kernel) sigma = std::max(sigma, std::abs(v));
  sigma /= gr.h;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(m + K, m + K);
  Eigen::VectorXd rhs(m + K);
  for (Index r = 0; r < m; ++r) {
    const std::size_t i = idx[static_cast<std::size_t>(r)], o = of[static_cast<std::size_t>(r)];
    for (Index c = 0; c < m; ++c) M(r, c) = gr.A(i, idx[static_cast<std::size_t>(c)]);
    M(r, m + static_cast<Index>(o)) = -1;
    M(m + static_cast<Index>(o), r) = sigma * gr.h;
    rhs[r] = (*z[o])[i];
  }
  for (Index k = 0; k < K; ++k) rhs[m + k] = sigma * load[static_cast<std::size_t>(k)];
  const Eigen::VectorXd sol = M.partialPivLu().solve(rhs);
  if (!sol.allFinite()) return false;
  g = sol.head(m);
  D = sol.tail(K);
  return true;
}

/// The surface pressed at given levels D: the obstacle phi = max_k (z_k + D_k), its panels'
/// owners the maximising k, w = A g >= phi with equality where g > 0.
struct pressed {
  std::vector<char> active;       ///< the contact set (also the next solve's start)
  std::vector<int> owner;         ///< argmax_k (z_k + D_k) at every panel
  std::vector<double> load;       ///< h sum g over each indentor's active panels
  std::vector<double> w;          ///< the surface A g at the collocation points
};

/// The obstacle problem at the levels D by the active set of panel_grid.hpp's settle (drop every
/// negative panel; when none, add every penetrated one), from s.active; false when it does not
/// settle in max_press_steps or a solve fails.
bool press(const body_grid& gr, const Eigen::VectorXd& D, pressed& s, double span, const context& cx) {
  const std::size_t K = gr.z.size();
  std::vector<double> phi(gr.n);
  s.owner.assign(gr.n, 0);
  for (std::size_t i = 0; i < gr.n; ++i) {
    for (std::size_t k = 1; k < K; ++k)
      if (gr.z[k][i] + D[static_cast<Index>(k)] > gr.z[static_cast<std::size_t>(s.owner[i])][i] + D[s.owner[i]]) s.owner[i] = static_cast<int>(k);
    phi[i] = gr.z[static_cast<std::size_t>(s.owner[i])][i] + D[s.owner[i]];
  }
  std::vector<std::size_t> idx;
  Eigen::VectorXd g;
  for (std::size_t step = 0; step < max_press_steps; ++step) {
    cx.check_time();
    idx.clear();
    for (std::size_t i = 0; i < gr.n; ++i)
      if (s.active[i]) idx.push_back(i);
    const auto m = static_cast<Index>(idx.size());
    if (m > 0) {
      Eigen::MatrixXd M(m, m);
      Eigen::VectorXd rhs(m);
      for (Index r = 0; r < m; ++r) {
        for (Index c = 0; c < m; ++c) M(r, c) = gr.A(idx[static_cast<std::size_t>(r)], idx[static_cast<std::size_t>(c)]);
        rhs[r] = phi[idx[static_cast<std::size_t>(r)]];
      }
      g = M.partialPivLu().solve(rhs);
      if (!g.allFinite()) return false;
    } else {
      g.resize(0);
    }
    bool changed = false;
    for (Index c = 0; c < m; ++c)
      if (g[c] < 0) s.active[idx[static_cast<std::size_t>(c)]] = 0, changed = true;
    if (changed) continue;
    // None negative: the surface once, every panel it leaves below phi joins the set.
    s.w.assign(gr.n, 0.0);
    for (std::size_t i = 0; i < gr.n; ++i) {
      for (Index c = 0; c < m; ++c) s.w[i] += gr.A(i, idx[static_cast<std::size_t>(c)]) * g[c];
      if (!s.active[i] && s.w[i] - phi[i] < -owner_floor * span) s.active[i] = 1, changed = true;
    }
    if (changed) continue;
    s.load.assign(K, 0.0);
    for (Index c = 0; c < m; ++c) s.load[static_cast<std::size_t>(s.owner[idx[static_cast<std::size_t>(c)]])] += gr.h * g[c];
    return true;
  }
  return false;
}

/// Indentor k's level alone, the others' fixed, until it carries its load within `within`
/// (relative): P_k grows with D_k, so the root is bracketed (from the level at which it touches
/// the surface when it carries nothing, steps doubling from bracket_step of the span) and found by
/// regula falsi with the Illinois modification. D and s updated; false when no bracket or no
/// convergence in max_level_iterations.
bool level_alone(const body_grid& gr, const std::vector<double>& load, std::size_t k, Eigen::VectorXd& D, pressed& s,
                 double span, double within, const context& cx) {
  const auto ki = static_cast<Index>(k);
  pressed last;  // the state of the last evaluation
  const auto at = [&](double level) {
    Eigen::VectorXd Dk = D;
    Dk[ki] = level;
    last = s;  // each evaluation starts from s's contact set
    if (!press(gr, Dk, last, span, cx)) return std::numeric_limits<double>::quiet_NaN();
    return last.load[k] / load[k] - 1;
  };
  double a = D[ki], fa = s.load[k] / load[k] - 1;
  if (std::abs(fa) <= within) return true;
  if (s.load[k] == 0) {
    // Carrying nothing: from the level at which its profile first reaches the surface.
    double touch = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < gr.n; ++i) touch = std::min(touch, s.w[i] - gr.z[k][i]);
    a = std::max(a, touch);
    fa = at(a);
  }
  double b = a, fb = fa, step = bracket_step * span * (fa < 0 ? 1 : -1);
  for (std::size_t n = 0; fb * fa > 0 || n == 0; ++n, step *= 2) {
    if (n == max_level_iterations || !std::isfinite(fb)) return false;
    a = b, fa = fb;
    b = a + step;
    fb = at(b);
  }
  for (std::size_t n = 0; n < max_level_iterations; ++n) {
    if (std::abs(b - a) < level_step * span) {
      // The load jumps here (a panel changing hands between two indentors): the nearer end.
      const double c = std::abs(fa) < std::abs(fb) ? a : b, fc = at(c);
      if (!(std::abs(fc) <= std::max(within, jump_within))) return false;
      D[ki] = c;
      s = std::move(last);
      return true;
    }
    const double c = (a * fb - b * fa) / (fb - fa), fc = at(c);
    if (!std::isfinite(fc)) return false;
    if (std::abs(fc) <= within) {
      D[ki] = c;
      s = std::move(last);
      return true;
    }
    if (fc * fb < 0) a = b, fa = fb;
    else fa /= 2;  // Illinois: the end kept twice is pulled in
    b = c, fb = fc;
  }
  return false;
}

/// The relative mismatch of the loads, P_k(D)/P_k - 1.
Eigen::VectorXd mismatch(const pressed& p, const std::vector<double>& load) {
  Eigen::VectorXd F(static_cast<Index>(load.size()));
  for (std::size_t k = 0; k < load.size(); ++k) F[static_cast<Index>(k)] = p.load[k] / load[k] - 1;
  return F;
}

/// Newton's method on the mismatch F (D and s updated, F theirs) until every load is within
/// load_match: the Jacobian by forward differences (a step of level_step of the span), each step
/// halved until |F| falls. False when an evaluation fails; true when it stops, converged or not.
bool newton_levels(const body_grid& gr, const std::vector<double>& load, Eigen::VectorXd& D, pressed& s,
                   Eigen::VectorXd& F, double span, const context& cx) {
  const auto K = static_cast<Index>(load.size());
  for (std::size_t iteration = 0; iteration < max_level_iterations; ++iteration) {
    if (F.cwiseAbs().maxCoeff() <= load_match) return true;
    Eigen::MatrixXd J(K, K);
    const double delta = level_step * span;
    for (Index k = 0; k < K; ++k) {
      pressed t = s;
      Eigen::VectorXd Dk = D;
      Dk[k] += delta;
      if (!press(gr, Dk, t, span, cx)) return false;
      J.col(k) = (mismatch(t, load) - F) / delta;
    }
    const Eigen::VectorXd step = J.fullPivLu().solve(-F);
    if (!step.allFinite()) return true;
    bool fell = false;
    for (double t = 1; t > 1.0 / 1024 && !fell; t /= 2) {
      pressed trial = s;
      const Eigen::VectorXd Dt = D + t * step;
      if (!press(gr, Dt, trial, span, cx)) continue;
      const Eigen::VectorXd Ft = mismatch(trial, load);
      if (Ft.norm() < F.norm()) D = Dt, s = std::move(trial), F = Ft, fell = true;
    }
    if (!fell) return true;  // stalled (at a kink or a jump of the loads)
  }
  return true;
}

/// The levels at which every indentor carries its load within `within` (relative), from D (s: the
/// contact set to start the first press from), both updated: rounds of Gauss-Seidel sweeps (each
/// level alone) and Newton's method (newton_levels). The first round sweeps only the indentors
/// that carry (almost) nothing, where Newton has no derivative to follow; after Newton stalls (the
/// loads are piecewise smooth in the levels, and jump where a panel changes hands), every level
/// off by more than `within`. False when the loads are not matched.
bool match_loads(const body_grid& gr, const std::vector<double>& load, Eigen::VectorXd& D, pressed& s, double span,
                 double within, const context& cx) {
  if (!press(gr, D, s, span, cx)) return false;
  Eigen::VectorXd F = mismatch(s, load);
  for (std::size_t round = 0; round < max_rounds; ++round) {
    for (std::size_t sweep = 0; sweep < max_sweeps; ++sweep) {
      bool swept = false;
      for (std::size_t k = 0; k < load.size(); ++k) {
        const double f = F[static_cast<Index>(k)];
        if (round == 0 ? f >= carried_share - 1 : std::abs(f) <= within) continue;
        if (!level_alone(gr, load, k, D, s, span, within / 4, cx)) return false;
        F = mismatch(s, load);
        swept = true;
      }
      if (!swept) break;
    }
    if (!newton_levels(gr, load, D, s, F, span, cx)) return false;
    if (F.cwiseAbs().maxCoeff() <= within) return true;
  }
  return false;
}

/// The profiles' span over the window (the scale of levels and of the penetration floor).
double profile_span(const body_grid& gr) {
  double span = 0;
  for (const auto& zk : gr.z) {
    const auto [lo, hi] = std::minmax_element(zk.begin(), zk.end());
    span = std::max(span, *hi - *lo);
  }
  return span;
}

/// The panels of `gr` whose collocation points lie in [a, b] (at least the one nearest its middle).
std::vector<std::size_t> panels_in(const body_grid& gr, double a, double b) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < gr.n; ++i) {
    const double x = gr.at(i, collocation_theta);
    if (x >= a && x <= b) out.push_back(i);
  }
  if (out.empty()) {
    const double p = std::clamp((0.5 * (a + b) - gr.lo) / (gr.length * gr.h), 0.0, static_cast<double>(gr.n - 1));
    out.push_back(static_cast<std::size_t>(p));
  }
  return out;
}

/// The first window's start: each indentor's isolated contact alone on this grid, its level from
/// one loaded solve; the contact set their union.
bool isolated_start(const body_grid& gr, const std::vector<std::pair<double, double>>& isolated,
                    const std::vector<double>& load, Eigen::VectorXd& D, pressed& s) {
  const std::size_t K = load.size();
  D.resize(static_cast<Index>(K));
  s.active.assign(gr.n, 0);
  for (std::size_t k = 0; k < K; ++k) {
    const auto idx = panels_in(gr, isolated[k].first, isolated[k].second);
    Eigen::VectorXd g, level;
    if (!solve_loaded(gr, idx, std::vector<std::size_t>(idx.size(), 0), {&gr.z[k]}, {load[k]}, g, level)) return false;
    D[static_cast<Index>(k)] = level[0];
    for (const std::size_t i : idx) s.active[i] = 1;
  }
  return true;
}

/// The second window's start: the first window's contact set and owners carried over (the panel
/// under each panel's centre), the levels from one loaded solve of all of them.
bool carried_start(const body_grid& from, const pressed& was, const body_grid& gr, const std::vector<double>& load,
                   Eigen::VectorXd& D, pressed& s) {
  const std::size_t K = load.size();
  s.active.assign(gr.n, 0);
  std::vector<std::size_t> idx, of;
  std::vector<char> seen(K, 0);
  for (std::size_t i = 0; i < gr.n; ++i) {
    const double p = (gr.at(i, 0.5) - from.lo) / (from.length * from.h);
    if (p < 0 || p >= static_cast<double>(from.n)) continue;
    const auto j = static_cast<std::size_t>(p);
    if (!was.active[j]) continue;
    s.active[i] = 1;
    idx.push_back(i);
    of.push_back(static_cast<std::size_t>(was.owner[j]));
    seen[of.back()] = 1;
  }
  if (std::find(seen.begin(), seen.end(), 0) != seen.end()) return false;  // an indentor with no contact
  std::vector<const std::vector<double>*> z;
  for (const auto& zk : gr.z) z.push_back(&zk);
  Eigen::VectorXd g;
  return solve_loaded(gr, idx, of, z, load, g, D);
}

/// The contact set's panels by owner (-1: not in contact).
std::vector<int> loaded_owners(const pressed& s) {
  std::vector<int> out(s.owner);
  for (std::size_t i = 0; i < out.size(); ++i)
    if (!s.active[i]) out[i] = -1;
  return out;
}

/// One interval per indentor from the settled owners (see coarse_bodies for when there is none).
std::optional<std::vector<std::pair<double, double>>> intervals(const body_grid& gr, const std::vector<int>& owner,
                                                                std::size_t K) {
  std::vector<std::pair<double, double>> out(K, {0.0, 0.0});
  std::vector<std::size_t> count(K, 0);
  int previous = -1;  // the owner of the last loaded panel
  std::size_t previous_at = 0;
  for (std::size_t i = 0; i < gr.n; ++i) {
    const int o = owner[i];
    if (o < 0) continue;
    const auto k = static_cast<std::size_t>(o);
    if (previous >= 0 && previous != o && previous_at + 1 == i) return std::nullopt;  // two contacts touch
    if (count[k] == 0) {
      out[k].first = gr.edge(i);
    } else if (previous != o) {
      return std::nullopt;  // another indentor's contact lies between two of this one's panels
    }
    out[k].second = gr.edge(i + 1);
    ++count[k];
    previous = o;
    previous_at = i;
  }
  for (const std::size_t c : count)
    if (c < min_owned_panels) return std::nullopt;
  return out;
}

}  // namespace

std::optional<std::vector<std::pair<double, double>>> coarse_bodies(const std::vector<indentor_state>& st,
                                                                    const std::vector<std::pair<double, double>>& isolated,
                                                                    const context& cx) try {
  if (st.size() > max_bodies) return std::nullopt;
  std::vector<double> load;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t k = 0; k < st.size(); ++k) {
    load.push_back(st[k].target_load);
    lo = std::min(lo, isolated[k].first);
    hi = std::max(hi, isolated[k].second);
  }
  // Each window: started by `start`, solved, widened twice over while its end panel is loaded.
  const auto solve_window = [&](double wlo, double whi, std::size_t n, double within, const auto& start,
                                body_grid& gr, pressed& s) {
    for (int widened = 0;; ++widened) {
      gr = make_body_grid(st, wlo, whi, n, cx);
      Eigen::VectorXd D;
      if (!start(gr, D, s) || !match_loads(gr, load, D, s, profile_span(gr), within, cx)) return false;
      if (!s.active.front() && !s.active.back()) return true;
      if (widened == max_widenings) return false;
      const double centre = 0.5 * (wlo + whi), width = whi - wlo;
      wlo = centre - width, whi = centre + width;
    }
  };
  body_grid coarse, fine;
  pressed first, second;
  if (!solve_window(lo - (hi - lo), hi + (hi - lo), first_window_panels, coarse_within,
                    [&](const body_grid& gr, Eigen::VectorXd& D, pressed& s) { return isolated_start(gr, isolated, load, D, s); },
                    coarse, first))
    return std::nullopt;
  // The second window: the contact set's hull and a quarter of its length on each side.
  const auto in_contact = [](char c) { return c != 0; };
  const auto first_loaded = static_cast<std::size_t>(std::find_if(first.active.begin(), first.active.end(), in_contact) - first.active.begin());
  const auto end_loaded = static_cast<std::size_t>(first.active.rend() - std::find_if(first.active.rbegin(), first.active.rend(), in_contact));
  const double a = coarse.edge(first_loaded), b = coarse.edge(end_loaded);
  if (!solve_window(a - 0.25 * (b - a), b + 0.25 * (b - a), second_window_panels, fine_within,
                    [&](const body_grid& gr, Eigen::VectorXd& D, pressed& s) { return carried_start(coarse, first, gr, load, D, s); },
                    fine, second))
    return std::nullopt;
  return intervals(fine, loaded_owners(second), st.size());
} catch (const time_limit_reached&) {
  return std::nullopt;  // the caller's retry sees the time gone
}

}  // namespace rhabel::punch::detail
