// study_multi_contact: several contacts at once (paper system 41): error against time of rhabel's
// coupled solve, the usual boundary-element method side by side, cost against the number of
// contacts, mixed shapes (issue 13's evidence).
//
// Material: E1 = 1, nu = 0, speed 1, so p = (pi/2) Gamma(1 - alpha) g (the "pressure scale");
// beta from the Coulomb coefficient k by tan(beta pi/2) = k/2 (as tests/punch/test_coupled_bem.cpp).
// Loads are given as load_g = int g; rhabel's load is load_g times the pressure scale.
//
// PART two_parabola: parabolas R = 1, load_g = 0.3 each, apexes at 0 and D; alpha in
//   {0, 0.1, 0.3, 0.5, 0.7, 0.9}, beta 0 (and 0.3 at alpha 0, 0.3, 0.7, gaps 1 and 0.01); target
//   gaps between the contacts 1, 0.1, 0.01, 1e-3 of the smaller contact length L, and at alpha 0
//   and 0.3 only (a second or more a solve) 1e-4, 1e-6 (--quick: alpha 0.3, 0.7, gaps 1, 0.01).
//   D for a target gap: a short secant in D (at most 5 solves at tolerance 1e-10, stopping within
//   10 % of the target) on rhabel's own coupled result, started from the previous (larger) gap of
//   the same alpha or from the isolated contacts; gap_over_L is the gap reached. At alpha 0.3
//   below 1e-3 L D is extrapolated linearly from the 1e-3 placement (the coupled contacts push
//   apart as the apexes approach there, so the secant does not reach the target), one solve at
//   tolerance 1e-12 is timed once and its status recorded (gap_over_L from its edges, empty if the
//   contacts merged).
//   Reference: rhabel at solve_options::tolerance 1e-13; its self-convergence (ref_err_edges,
//   ref_err_Cf) is the difference to the solve at 1e-12. And, independent of rhabel, the oracle
//   tests/punch/bem_oracle.hpp solve() (moving meshes, 25 ... 800 panels per contact, Richardson
//   extrapolated, with its error bar, an estimate) at alpha 0, 0.3, 0.7, beta 0, gaps 1 ... 0.01
//   and at beta 0.3, gap 1 (it needs alpha + beta <= 1; seconds a scene; --quick: one scene); its
//   windows split at the middle of the gap and reach 3 L beyond the outer edges. Rows:
//     method rhabel     setting tol=1e-8, 1e-10, 1e-12: seconds (with the independent residual) and
//                       seconds_no_residual (solve_options::residual false), minimum per call over
//                       a time budget (rhabel_study::min_time_per_call; a solve slower than the
//                       budget is timed once); errors against the 1e-13 reference. A scene whose
//                       solve at 1e-12 takes over 1 s (slow_solve_seconds) gets only that row,
//                       timed once, seconds_no_residual empty. (Tolerances
//                       above 1e-8 mostly give not_converged: the acceptance of an ok status is
//                       1e-9.)
//     method bem_oracle the extrapolated oracle: err_* = |oracle - rhabel reference|, bar_* its
//                       error bar (edges relative to L), seconds one call.
//     method bem_grid   the usual BEM, at beta 0 and gaps 1, 0.01, 1e-3: bem_oracle's solve_grid
//                       (uniform panels over each of the two windows above, dense LU,
//                       non-negativity by an active set) at setting panels=200, 400, ... 3200 per
//                       window; edges = hull of the active panels (known to a panel width), C_f =
//                       sum g_i (f(t1_i) - f(t0_i)) / sum g_i h_i from the discrete density;
//                       errors against the rhabel reference; seconds one call (a fine grid starts
//                       from a grid 4x coarser, solved inside the call). The next count (~4x the
//                       cost) is skipped when one took over a quarter of the per-scene budget
//                       (default 6 s, --quick 1 s).
// PART rows: N parabolas (R = 1, load_g 0.3, alpha 0.3, beta 0) with apexes 1.5 isolated contact
//   lengths apart, N = 2, 5, 10, 20, 40, 100, 300 (--quick: up to 10); 1000 only with --rows-only
//   or when N = 300 took under 10 s. seconds = one solve at tolerance 1e-10 (minimum of 3 where a solve takes
//   under 1 s), iterations = scene_result::diagnostics.iterations, peak_rss_mb = the process's peak
//   resident set after the solve (getrusage ru_maxrss: monotone over the run, so an upper bound
//   for this N).
// PART mixed: alpha 0 and 0.3, beta 0, gaps 1 and 0.1 L (--quick: 1; secant as above; flat punches: exactly,
//   gap = D - width): parabola (R 1, load_g 0.3) then wedge (load_g 0.1) with slopes 0.4/0.4 and
//   0.02/0.9; two flat punches (width 1, load_g 0.5 each). Tolerance 1e-10, time and status.
//
// Errors: err_edges = max over the four edges of |x - x_ref| / L_ref (L of that contact);
// err_Cf = max over the contacts of |C_f - C_f_ref| (C_f is dimensionless, of order R/L here).
//
// CSV on stdout, one row per measurement; an empty cell = no value:
//   part,alpha,beta,N,shape,target_gap,gap_over_L,apex_distance,method,setting,seconds,
//   seconds_no_residual,status,residual,iterations,err_edges,err_Cf,ref_err_edges,ref_err_Cf,
//   bar_edges,bar_Cf,peak_rss_mb
// Markdown summary tables on stderr. Options: --quick (under 60 s), --rows-only (PART rows only,
// with N = 1000),
// --budget-ms X (timing budget per rhabel measurement).
#include "support/study_support.hpp"

#include "bem_oracle.hpp"
#include "rhabel/punch.hpp"

#include <sys/resource.h>

#include <boost/math/special_functions/gamma.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace pu = rhabel::punch;
namespace bem = punch_test::bem;
using rhabel_study::format_duration;
using rhabel_study::format_number;

namespace {
constexpr double pi = 3.141592653589793238462643383279502884;
const double nan = std::numeric_limits<double>::quiet_NaN();

/// A two-parabola scene whose solve at tolerance 1e-12 takes longer is not swept in tolerance.
constexpr double slow_solve_seconds = 1.0;

struct config {
  bool quick = false;
  bool rows_only = false;         // --rows-only: only PART rows
  double budget_seconds = 0.1;    // per rhabel timing
  double grid_budget = 6.0;       // per scene, BEM grid sweep
};

pu::material material_of(double alpha, double beta) { return {alpha, 1.0, 0.0, 2 * std::tan(beta * pi / 2)}; }
double pressure_scale(double alpha) { return pi / 2 * boost::math::tgamma(1 - alpha); }

double seconds_of(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // kB on Linux
}

std::string status_of(const pu::scene_result& r) { return pu::to_string(r.diagnostics.code); }

/// A two-indentor scene as both codes see it: rhabel's indentor and the oracle's profile.
struct shape_pair {
  pu::indentor ours;
  bem::profile theirs;
};
shape_pair parabola(double R, double load_g, double ps) { return {{pu::parabolic{R}, load_g * ps, 0.0}, bem::parabola{R}}; }
shape_pair wedge_shape(double S1, double S2, double load_g, double ps) {
  return {{pu::wedge{S1, S2}, load_g * ps, 0.0}, bem::wedge{S1, S2}};
}
shape_pair flat_shape(double w, double load_g, double ps) { return {{pu::flat{w}, load_g * ps, 0.0}, bem::flat{w}}; }

pu::scene two_scene(double alpha, double beta, const shape_pair& first, const shape_pair& second, double D) {
  pu::scene s{material_of(alpha, beta), 1.0, {first.ours, second.ours}};
  s.indentors[1].apex = D;
  return s;
}

pu::scene_result solve_at(const pu::scene& s, double tol, bool residual = true) {
  pu::solve_options o;
  o.tolerance = tol;
  o.residual = residual;
  return pu::solve(s, o);
}

/// Gap between the two contacts (in x order) relative to the smaller contact length; NaN when the
/// contacts merged (a not_converged, tension or penetration result still has edges that solve the
/// slope equations to about the tolerance: good enough to place a scene).
double relative_gap(const pu::scene_result& r) {
  if (r.diagnostics.code == pu::status_code::contacts_merge) return nan;
  const auto& p = r.indentors[0];
  const auto& q = r.indentors[1];
  const double gap = p.a < q.a ? q.a - p.b : p.a - q.b;
  return gap / std::min(p.contact_length, q.contact_length);
}

/// Apex distance D giving the target relative gap: secant in D on rhabel's result (tolerance
/// 1e-10), at most 5 solves, started from `from` (a previous placement of the same pair) or from
/// the isolated contacts. Returns D, the gap reached (NaN if the contacts merged) and the slope
/// d(gap/L)/dD of the last secant step.
struct placed {
  double D, gap, slope = nan;
};
placed place(double alpha, double beta, const shape_pair& first, const shape_pair& second, double target,
             const placed* from = nullptr) {
  const auto m = material_of(alpha, beta);
  const auto s0 = pu::solve_single(m, 1.0, first.ours), s1 = pu::solve_single(m, 1.0, second.ours);
  const double L = std::min(s0.contact_length, s1.contact_length);
  // Isolated contacts: gap(D) = D + a1 - b0.
  std::vector<double> Ds, gaps;
  double D = target * L + s0.b - s1.a;
  if (from && !std::isnan(from->gap)) D = from->D + (target - from->gap) / (std::isnan(from->slope) ? 1 / L : from->slope);
  auto slope_of = [&] {
    const std::size_t n = gaps.size();
    return n >= 2 && gaps[n - 1] != gaps[n - 2] ? (gaps[n - 1] - gaps[n - 2]) / (Ds[n - 1] - Ds[n - 2])
                                                : (from && !std::isnan(from->slope) ? from->slope : 1 / L);
  };
  for (int k = 0; k < 5; ++k) {
    const double g = relative_gap(solve_at(two_scene(alpha, beta, first, second, D), 1e-10));
    if (!std::isnan(g)) {
      Ds.push_back(D);
      gaps.push_back(g);
      if (std::abs(g / target - 1) < 0.1) return {D, g, slope_of()};
    }
    if (gaps.empty()) return {D, nan};
    D = Ds.back() + (target - gaps.back()) / slope_of();
  }
  return {D, relative_gap(solve_at(two_scene(alpha, beta, first, second, D), 1e-10)), slope_of()};
}

/// Edges and C_f of a two-contact result.
struct values {
  double a[2], b[2], L[2], Cf[2];
};
values values_of(const pu::scene_result& r) {
  values v{};
  for (int j = 0; j < 2; ++j) {
    const auto& c = r.indentors[static_cast<std::size_t>(j)];
    v.a[j] = c.a, v.b[j] = c.b, v.L[j] = c.contact_length, v.Cf[j] = c.hysteretic_friction;
  }
  return v;
}
struct errors {
  double edges = nan, Cf = nan;
};
errors difference(const values& x, const values& ref) {
  errors e{0, 0};
  for (int j = 0; j < 2; ++j) {
    e.edges = std::max({e.edges, std::abs(x.a[j] - ref.a[j]) / ref.L[j], std::abs(x.b[j] - ref.b[j]) / ref.L[j]});
    e.Cf = std::max(e.Cf, std::abs(x.Cf[j] - ref.Cf[j]));
  }
  return e;
}

// ---------------------------------------------------------------------------------------------
// Output: one CSV writer and markdown lines collected per table.

struct row {
  std::string part;
  double alpha = nan, beta = nan;
  std::size_t N = 2;
  std::string shape;
  double target_gap = nan, gap = nan, D = nan;
  std::string method, setting;
  double seconds = nan, seconds_no_residual = nan;
  std::string status;
  double residual = nan, iterations = nan;
  errors err, ref_err, bar;
  double rss = nan;
};

class output {
 public:
  output()
      : csv_(std::cout, {"part", "alpha", "beta", "N", "shape", "target_gap", "gap_over_L", "apex_distance", "method", "setting",
                         "seconds", "seconds_no_residual", "status", "residual", "iterations", "err_edges", "err_Cf",
                         "ref_err_edges", "ref_err_Cf", "bar_edges", "bar_Cf", "peak_rss_mb"}) {}
  void write(const row& r) {
    auto n = [](double v) { return format_number(v, 4); };
    csv_.row({r.part, n(r.alpha), n(r.beta), std::to_string(r.N), r.shape, n(r.target_gap), n(r.gap), format_number(r.D, 12),
              r.method, r.setting, n(r.seconds), n(r.seconds_no_residual), r.status, n(r.residual), n(r.iterations),
              n(r.err.edges), n(r.err.Cf), n(r.ref_err.edges), n(r.ref_err.Cf), n(r.bar.edges), n(r.bar.Cf), n(r.rss)});
  }

 private:
  rhabel_study::csv_writer csv_;
};

std::string e2(double v) { return std::isnan(v) ? "-" : format_number(v, 2); }
std::string count(double v) { return std::isnan(v) ? "-" : format_number(v, 6); }

// ---------------------------------------------------------------------------------------------
// Part 1 and 2: two-parabola scenes.

struct two_parabola_case {
  double alpha, beta, target;
};

/// The oracle's windows: split at the middle of the gap, 3 L beyond the outer edges.
bem::scene oracle_scene(double alpha, double beta, const shape_pair& first, const shape_pair& second, double D,
                        const values& ref) {
  const double ps = pressure_scale(alpha);
  bem::scene bs;
  bs.alpha = alpha;
  bs.beta = material_of(alpha, beta).beta();
  const double mid = (ref.b[0] + ref.a[1]) / 2;
  bs.indentors.push_back({first.theirs, 0.0, first.ours.load / ps, ref.a[0] - 3 * ref.L[0], mid});
  bs.indentors.push_back({second.theirs, D, second.ours.load / ps, mid, ref.b[1] + 3 * ref.L[1]});
  return bs;
}

values values_of(const bem::grid_result& g, const bem::scene& bs) {
  values v{};
  for (std::size_t j = 0; j < 2; ++j) {
    v.a[j] = g.a[j], v.b[j] = g.b[j], v.L[j] = g.b[j] - g.a[j];
    double P = 0, M = 0;
    const auto& d = g.density;
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (static_cast<std::size_t>(d.owner[i]) != j) continue;
      P += d.g[i] * (d.t1[i] - d.t0[i]);
      M += d.g[i] * (bem::height(bs.indentors[j], d.t1[i]) - bem::height(bs.indentors[j], d.t0[i]));
    }
    v.Cf[j] = M / P;
  }
  return v;
}

struct scene_summary {
  two_parabola_case c;
  double gap = nan;
  std::string status;
  double iterations = nan, t12 = nan, t12_fast = nan, err12_edges = nan, err12_Cf = nan;
  std::string cheapest = "-";  // the loosest tolerance with edges and C_f within 1e-10: "tol: time / time"

  errors ref_err, oracle, oracle_bar;
  double oracle_seconds = nan;
  std::vector<std::string> grid_lines;
};

void rhabel_rows(const pu::scene& s, const values& ref, const errors& ref_err, const config& cfg, row base, output& out,
                 scene_summary& sum) {
  for (double tol : {1e-8, 1e-10, 1e-12}) {
    row r = base;
    r.method = "rhabel";
    r.setting = "tol=" + format_number(tol, 2);
    r.ref_err = ref_err;
    try {
      pu::scene_result res;  // a solve slower than the budget is timed once: keep its result
      r.seconds = rhabel_study::min_time_per_call([&] { res = solve_at(s, tol); return res.diagnostics.residual; }, cfg.budget_seconds).seconds;
      r.seconds_no_residual = rhabel_study::min_time_per_call([&] { return solve_at(s, tol, false).indentors[0].a; }, cfg.budget_seconds).seconds;
      r.status = status_of(res);
      r.residual = res.diagnostics.residual;
      r.iterations = static_cast<double>(res.diagnostics.iterations);
      r.err = difference(values_of(res), ref);
    } catch (const std::exception& e) {
      r.status = std::string("threw: ") + e.what();
    }
    out.write(r);
    if (sum.cheapest == "-" && r.status == "ok" && r.err.edges <= 1e-10 && r.err.Cf <= 1e-10)
      sum.cheapest = format_number(tol, 2) + ": " + format_duration(r.seconds) + " / " + format_duration(r.seconds_no_residual);
    if (tol == 1e-12) {
      sum.status = r.status, sum.iterations = r.iterations, sum.t12 = r.seconds, sum.t12_fast = r.seconds_no_residual;
      sum.err12_edges = r.err.edges, sum.err12_Cf = r.err.Cf;
    }
  }
}

void oracle_row(const bem::scene& bs, const values& ref, row base, output& out, scene_summary& sum) {
  row r = base;
  r.method = "bem_oracle";
  r.setting = "extrapolated";
  try {
    bem::result o;
    r.seconds = seconds_of([&] { o = bem::solve(bs); });
    r.status = o.converged ? "converged" : "not_converged";
    r.err = {0, 0}, r.bar = {0, 0};
    for (std::size_t j = 0; j < 2; ++j) {
      const auto& c = o.contacts[j];
      r.err.edges = std::max({r.err.edges, std::abs(c.a.value - ref.a[j]) / ref.L[j], std::abs(c.b.value - ref.b[j]) / ref.L[j]});
      r.bar.edges = std::max({r.bar.edges, c.a.error / ref.L[j], c.b.error / ref.L[j]});
      r.err.Cf = std::max(r.err.Cf, std::abs(c.friction.value - ref.Cf[j]));
      r.bar.Cf = std::max(r.bar.Cf, c.friction.error);
    }
    sum.oracle = r.err, sum.oracle_bar = r.bar, sum.oracle_seconds = r.seconds;
  } catch (const std::exception& e) {
    r.status = std::string("threw: ") + e.what();
  }
  out.write(r);
}

void grid_rows(const bem::scene& bs, const values& ref, const config& cfg, row base, output& out, scene_summary& sum) {
  for (int panels = 200; panels <= 3200; panels *= 2) {
    row r = base;
    r.method = "bem_grid";
    r.setting = "panels=" + std::to_string(panels);
    try {
      bem::grid_result g;
      r.seconds = seconds_of([&] { g = bem::solve_grid(bs, panels); });
      r.status = g.converged ? "converged" : "not_converged";
      r.iterations = g.iterations;
      if (g.runs[0] == 1 && g.runs[1] == 1) r.err = difference(values_of(g, bs), ref);
      else r.status += "; contacts: " + std::to_string(g.runs[0]) + " and " + std::to_string(g.runs[1]) + " runs";
    } catch (const std::exception& e) {
      r.status = std::string("threw: ") + e.what();
    }
    out.write(r);
    sum.grid_lines.push_back(std::to_string(panels) + ": " + format_duration(r.seconds) + ", " + e2(r.err.edges) + " / " + e2(r.err.Cf));
    if (!(r.seconds < cfg.grid_budget / 4)) break;  // the next count costs ~4x
  }
}

row two_parabola_base(const two_parabola_case& c, const placed& at) {
  row base;
  base.part = "two_parabola", base.alpha = c.alpha, base.beta = c.beta, base.shape = "parabola+parabola";
  base.target_gap = c.target, base.gap = at.gap, base.D = at.D;
  return base;
}

/// A scene at a gap the secant reached: the tolerance sweep, the reference, the oracle, the grid.
scene_summary two_parabola_scene(const two_parabola_case& c, const placed& at, bool with_oracle, bool with_grid,
                                 const config& cfg, output& out) {
  scene_summary sum;
  sum.c = c;
  sum.gap = at.gap;
  const auto P = parabola(1.0, 0.3, pressure_scale(c.alpha));
  const auto s = two_scene(c.alpha, c.beta, P, P, at.D);
  const row base = two_parabola_base(c, at);
  pu::scene_result ref_r, r12;
  double t12 = nan;
  try {
    ref_r = solve_at(s, 1e-13);
    t12 = seconds_of([&] { r12 = solve_at(s, 1e-12); });
  } catch (const std::exception& e) {
    row r = base;
    r.method = "rhabel", r.setting = "tol=1e-13", r.status = std::string("threw: ") + e.what();
    out.write(r);
    sum.status = r.status;
    return sum;
  }
  const values ref = values_of(ref_r);
  const bool ref_ok = ref_r.diagnostics.code == pu::status_code::ok;
  sum.ref_err = ref_ok ? difference(values_of(r12), ref) : errors{};
  if (t12 < slow_solve_seconds) {
    rhabel_rows(s, ref, sum.ref_err, cfg, base, out, sum);
  } else {  // a slow scene: only the solve at 1e-12 above, timed once
    row r = base;
    r.method = "rhabel", r.setting = "tol=1e-12", r.seconds = t12, r.ref_err = r.err = sum.ref_err;
    r.status = status_of(r12), r.residual = r12.diagnostics.residual, r.iterations = static_cast<double>(r12.diagnostics.iterations);
    out.write(r);
    sum.status = r.status, sum.iterations = r.iterations, sum.t12 = t12, sum.err12_edges = r.err.edges, sum.err12_Cf = r.err.Cf;
  }
  if (!ref_ok) return sum;  // no reference: the oracle and the grid have nothing to compare with
  const bool oracle_range = c.alpha + material_of(c.alpha, c.beta).beta() <= 1;
  const auto bs = oracle_scene(c.alpha, c.beta, P, P, at.D, ref);
  if (with_oracle && oracle_range) oracle_row(bs, ref, base, out, sum);
  if (with_grid && oracle_range) grid_rows(bs, ref, cfg, base, out, sum);
  return sum;
}

/// Below 1e-3 L: D extrapolated linearly from the placement at 1e-3 L, one solve at tolerance
/// 1e-12 (timed once), its status and the gap it reached.
scene_summary tiny_gap_scene(const two_parabola_case& c, const placed& from, output& out) {
  scene_summary sum;
  sum.c = c;
  const placed at{from.D + (c.target - from.gap) / from.slope, nan};
  row r = two_parabola_base(c, at);
  r.method = "rhabel", r.setting = "tol=1e-12";
  try {
    const auto P = parabola(1.0, 0.3, pressure_scale(c.alpha));
    pu::scene_result res;
    r.seconds = seconds_of([&] { res = solve_at(two_scene(c.alpha, c.beta, P, P, at.D), 1e-12); });
    r.status = status_of(res), r.residual = res.diagnostics.residual, r.iterations = static_cast<double>(res.diagnostics.iterations);
    r.gap = relative_gap(res);
  } catch (const std::exception& e) {
    r.status = std::string("threw: ") + e.what();
  }
  out.write(r);
  sum.gap = r.gap, sum.status = r.status, sum.iterations = r.iterations, sum.t12 = r.seconds;
  return sum;
}

void two_parabola_part(const config& cfg, output& out) {
  std::vector<double> alphas = {0, 0.1, 0.3, 0.5, 0.7, 0.9}, gaps = {1, 0.1, 0.01, 1e-3, 1e-4, 1e-6};
  if (cfg.quick) alphas = {0.3, 0.7}, gaps = {1, 0.01};
  std::vector<two_parabola_case> cases;
  for (double a : alphas)
    for (double g : gaps) cases.push_back({a, 0.0, g});
  for (double a : {0.0, 0.3, 0.7})
    for (double g : {1.0, 0.01})
      if (!cfg.quick || (a == 0.3 && g == 1.0)) cases.push_back({a, 0.3, g});
  std::vector<scene_summary> sums;
  placed prev{nan, nan};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const auto& c = cases[k];
    const bool first_of_pair = k == 0 || cases[k - 1].alpha != c.alpha || cases[k - 1].beta != c.beta;
    // The oracle (seconds a scene) on alpha 0, 0.3, 0.7, gaps >= 0.01, and beta 0.3 at gap 1 (quick:
    // one scene); the usual BEM on beta = 0, gaps 1, 0.01, 1e-3 (quick: alpha 0.3).
    const bool oracle = cfg.quick ? c.alpha == 0.3 && c.target == 1 && c.beta == 0
                                  : (c.beta == 0 ? (c.alpha == 0 || c.alpha == 0.3 || c.alpha == 0.7) && c.target >= 0.01 : c.target == 1);
    const bool grid = c.beta == 0 && (c.target == 1 || c.target == 0.01 || c.target == 1e-3) && (!cfg.quick || c.alpha == 0.3);
    if (c.target < 1e-3 && c.alpha != 0.3 && c.alpha != 0) continue;  // a second or more a solve: two alphas
    if (c.target < 1e-3 && c.alpha == 0.3 && !first_of_pair && !std::isnan(prev.gap) && !std::isnan(prev.slope)) {
      sums.push_back(tiny_gap_scene(c, prev, out));
    } else {
      const auto P = parabola(1.0, 0.3, pressure_scale(c.alpha));
      prev = place(c.alpha, c.beta, P, P, c.target, first_of_pair ? nullptr : &prev);
      sums.push_back(two_parabola_scene(c, prev, oracle, grid, cfg, out));
    }
    std::cerr << "." << std::flush;
  }
  std::cerr << "\n\n### Two parabolas (R = 1, load_g 0.3 each): rhabel at tolerance 1e-12 against its 1e-13 reference\n\n"
            << "| alpha | beta | gap/L | status | Newton it. | time (residual / none) | err edges/L | err C_f | to 1e-10: tol, time (residual / none) | ref. self-conv. edges / C_f | oracle - ref.: edges (bar) | C_f (bar) | oracle time |\n"
            << "| ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const auto& s : sums)
    std::cerr << "| " << s.c.alpha << " | " << s.c.beta << " | " << (std::isnan(s.gap) ? "~" + e2(s.c.target) : e2(s.gap)) << " | "
              << s.status << " | " << count(s.iterations) << " | " << format_duration(s.t12) << " / " << format_duration(s.t12_fast)
              << " | " << e2(s.err12_edges) << " | " << e2(s.err12_Cf) << " | " << s.cheapest << " | " << e2(s.ref_err.edges) << " / " << e2(s.ref_err.Cf)
              << " | " << e2(s.oracle.edges) << " (" << e2(s.oracle_bar.edges) << ") | " << e2(s.oracle.Cf) << " ("
              << e2(s.oracle_bar.Cf) << ") | " << format_duration(s.oracle_seconds) << " |\n";
  std::cerr << "\n### The usual BEM (solve_grid, uniform panels per window, dense LU, active set): time, err edges/L / err C_f\n\n"
            << "| alpha | gap/L | panels per window: time, edges / C_f |\n| ---: | ---: | --- |\n";
  for (const auto& s : sums) {
    if (s.grid_lines.empty()) continue;
    std::cerr << "| " << s.c.alpha << " | " << e2(s.gap) << " |";
    for (const auto& l : s.grid_lines) std::cerr << ' ' << l << ';';
    std::cerr << " |\n";
  }
}

// ---------------------------------------------------------------------------------------------
// Part 3: rows of N parabolas.

void rows_part(const config& cfg, output& out) {
  const double alpha = 0.3, ps = pressure_scale(alpha);
  const pu::indentor P{pu::parabolic{1.0}, 0.3 * ps, 0.0};
  const double L0 = pu::solve_single(material_of(alpha, 0), 1.0, P).contact_length;
  std::cerr << "\n### Rows of N parabolas (alpha 0.3, R = 1, load_g 0.3, apexes 1.5 L apart; tolerance 1e-10)\n\n"
            << "| N | time | Newton it. | status | residual | peak RSS so far |\n| ---: | ---: | ---: | --- | ---: | ---: |\n";
  double last = 0;
  for (std::size_t N : {2, 5, 10, 20, 40, 100, 300, 1000}) {
    if (cfg.quick && N > 10) {
      std::cerr << "| " << N << " | not run (--quick) | | | | |\n";
      continue;
    }
    if (N == 1000 && !cfg.rows_only && !(last < 10)) {
      std::cerr << "| 1000 | not run (N = 300 took " << format_duration(last) << "; --rows-only runs it) | | | | |\n";
      break;
    }
    pu::scene s{material_of(alpha, 0), 1.0, {}};
    for (std::size_t i = 0; i < N; ++i) s.indentors.push_back({P.shape, P.load, 1.5 * L0 * static_cast<double>(i)});
    row r;
    r.part = "rows", r.alpha = alpha, r.beta = 0, r.N = N, r.shape = "parabola row", r.D = 1.5 * L0;
    r.method = "rhabel", r.setting = "tol=1e-10";
    try {
      pu::scene_result res;
      r.seconds = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3 && (k == 0 || r.seconds < 1); ++k) r.seconds = std::min(r.seconds, seconds_of([&] { res = solve_at(s, 1e-10); }));
      r.status = status_of(res), r.residual = res.diagnostics.residual, r.iterations = static_cast<double>(res.diagnostics.iterations);
      r.rss = peak_rss_mb();
      last = r.seconds;
    } catch (const std::exception& e) {
      r.status = std::string("threw: ") + e.what();
    }
    out.write(r);
    std::cerr << "| " << N << " | " << format_duration(r.seconds) << " | " << count(r.iterations) << " | " << r.status << " | "
              << e2(r.residual) << " | " << format_number(r.rss, 3) << " MB |\n";
  }
}

// ---------------------------------------------------------------------------------------------
// Part 4: mixed shapes.

void mixed_part(const config& cfg, output& out) {
  std::cerr << "\n### Mixed shapes (tolerance 1e-10)\n\n| scene | alpha | gap/L | time | Newton it. | status | residual |\n"
            << "| --- | ---: | ---: | ---: | ---: | --- | ---: |\n";
  for (double alpha : {0.0, 0.3}) {
    const double ps = pressure_scale(alpha);
    struct pair_case {
      std::string name;
      shape_pair first, second;
    };
    const std::vector<pair_case> cases = {{"parabola+wedge 0.4/0.4", parabola(1, 0.3, ps), wedge_shape(0.4, 0.4, 0.1, ps)},
                                          {"parabola+wedge 0.02/0.9", parabola(1, 0.3, ps), wedge_shape(0.02, 0.9, 0.1, ps)},
                                          {"flat+flat", flat_shape(1, 0.5, ps), flat_shape(1, 0.5, ps)}};
    for (const auto& c : cases)
      for (double target : {1.0, 0.1}) {
        if (cfg.quick && target != 1.0) continue;
        const bool flat = c.name == "flat+flat";
        row r;
        r.part = "mixed", r.alpha = alpha, r.beta = 0, r.shape = c.name, r.target_gap = target;
        r.method = "rhabel", r.setting = "tol=1e-10";
        try {
          const placed at = flat ? placed{1 + target, target} : place(alpha, 0, c.first, c.second, target);
          r.D = at.D, r.gap = at.gap;
          const auto s = two_scene(alpha, 0, c.first, c.second, at.D);
          pu::scene_result res;
          r.seconds = rhabel_study::min_time_per_call([&] { res = solve_at(s, 1e-10); return res.diagnostics.residual; }, cfg.budget_seconds).seconds;
          r.status = status_of(res), r.residual = res.diagnostics.residual, r.iterations = static_cast<double>(res.diagnostics.iterations);
        } catch (const std::exception& e) {
          r.status = std::string("threw: ") + e.what();
        }
        out.write(r);
        std::cerr << "| " << c.name << " | " << alpha << " | " << (std::isnan(r.gap) ? "~" + e2(target) : e2(r.gap)) << " | "
                  << format_duration(r.seconds) << " | " << count(r.iterations) << " | " << r.status << " | " << e2(r.residual) << " |\n";
      }
  }
}
}  // namespace

int main(int argc, char** argv) {
  config cfg;
  const int code = rhabel_study::parse_command_line(
      argc, argv, "study_multi_contact",
      "two-contact scenes: rhabel's coupled solve against its reference and the BEM oracle, the usual BEM side by side, "
      "cost against N, mixed shapes (CSV on stdout, markdown on stderr)",
      {rhabel_study::switch_option("--quick", "fewer scenes and shorter budgets (under 60 s)", [&] { cfg.quick = true; }),
       rhabel_study::switch_option("--rows-only", "only the rows of N parabolas (cost against N)", [&] { cfg.rows_only = true; }),
       rhabel_study::budget_ms_option(cfg.budget_seconds, "timing budget per rhabel measurement in ms")});
  if (code >= 0) return code;
  if (cfg.quick) cfg.budget_seconds = std::min(cfg.budget_seconds, 0.02), cfg.grid_budget = 1.0;
  const rhabel_study::run_record run;
  std::cerr << "## study_multi_contact" << (cfg.quick ? " --quick" : "") << "\n\n" << rhabel_study::run_record::machine_and_load() << "\n";
  output out;
  if (!cfg.rows_only) two_parabola_part(cfg, out);
  rows_part(cfg, out);
  if (!cfg.rows_only) mixed_part(cfg, out);
  std::cerr << "\n" << run.totals() << "\n";
  return 0;
}
