// studies/support/tables.hpp: the tables of docs/tables.md, computed with rhabel::punch::solve.
//
// Shared by the study that writes them (studies/tables.cpp -> build/bin/study_tables, which writes
// docs/tables/*.csv and docs/tables.md) and the regression test that recomputes them
// (tests/punch/test_tables.cpp, CTest punch.test_tables). Nothing here is copied from theory: the
// exponents are measured from the sampled pressure; the theoretical values of docs/theory.md
// section 3 sit beside them for comparison only.
//
// 1. Exponent table (docs/tables/exponents.csv). For every shape (flat, parabolic, wedge) and every
//    (alpha, beta) of `exponent_materials()` (alpha + beta/2 below, at and above 1/2, beta = 0 and
//    0.3, plus the elastic alpha = beta = 0) one indentor is solved alone (E_U = 1, load 1, R = 1,
//    S1 = S2 = 1, width 1) with `grid_points` = 200000 uniformly spaced pressure samples
//    (t_k = a + L (k + 1/2)/n). Near each singular point the exponent is the slope of a local
//    least-squares fit over the samples at distances d in [1e-5 L, 1e-3 L] from it:
//      * an edge (p ~ K d^gam (1 + c d)):  log p = gam log d + c0 + c1 d;
//      * the apex of a wedge below the boundary (p ~ A |d|^(-alpha) + B + C d, logarithmic at
//        alpha = 0), on each side: the same fit of the divided differences |p_{k+1} - p_k| / h of
//        neighbouring samples, placed at their mean-value points, whose slope is gam - 1 (so the
//        additive constant B drops out and the logarithm gives gam = 0).
//    A flat punch at or above the boundary degenerates to a line load: no interval, no exponent
//    (row kept with empty measured value).
// 2. Wedge table (docs/tables/wedge.csv): S1 = S2 = 1, E_U = 1, load 1, beta in {0, 0.3}, alpha on
//    a grid from 0 to 0.9: eps = (apex - a)/L, L and C_f / S1 (C_f = S1 on and above the boundary).
// 3. Parabola table (docs/tables/parabola.csv): R = 1, E_U = 1, load 1: b/L, L and C_f R / L beside
//    the closed forms of docs/theory.md section 5.
#pragma once

#include "rhabel/punch.hpp"

#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace rhabel_tables {

constexpr double pi = 3.141592653589793238462643383279502884;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// Pressure samples per indentor for the exponent fits (spacing 5e-6 L).
constexpr std::size_t exponent_grid_points = 200000;
/// Fit window: distances from the singular point, relative to the contact length L.
constexpr double fit_window_lo = 1e-5;
constexpr double fit_window_hi = 1e-3;

struct material_case {
  double alpha;
  double beta;
};

/// (alpha, beta) of the exponent table: elastic; beta = 0 below / at / above; beta = 0.3 below / at / above.
inline std::vector<material_case> exponent_materials() {
  return {{0.0, 0.0}, {0.25, 0.0}, {0.5, 0.0}, {0.7, 0.0}, {0.1, 0.3}, {0.35, 0.3}, {0.55, 0.3}};
}

/// The material with friction parameter beta exactly (nu = 0: tan(beta pi/2) = k/2) and E_U = 1 at U = 1.
inline rhabel::punch::material make_material(double alpha, double beta) {
  rhabel::punch::material m;
  m.alpha = alpha;
  m.poisson = 0.0;
  m.coulomb = 2.0 * std::tan(beta * pi / 2);
  m.E1 = 1.0 / boost::math::tgamma(1.0 - alpha);
  return m;
}

inline rhabel::punch::indentor make_indentor(const std::string& shape) {
  rhabel::punch::indentor ind;
  ind.load = 1.0;
  ind.apex = 0.0;
  if (shape == "parabolic") ind.shape = rhabel::punch::parabolic{1.0};
  else if (shape == "wedge") ind.shape = rhabel::punch::wedge{1.0, 1.0};
  else ind.shape = rhabel::punch::flat{1.0};
  return ind;
}

/// Slope of the least-squares fit  y = s log d + c0 + c1 (d / L)  (modified Gram-Schmidt, long double).
inline double log_log_slope(const std::vector<double>& d, const std::vector<double>& y) {
  const std::size_t n = d.size();
  if (n < 8) return nan;
  std::vector<long double> c0(n, 1.0L), c1(n), c2(n), r(y.begin(), y.end());
  for (std::size_t i = 0; i < n; ++i) {
    c1[i] = std::log(static_cast<long double>(d[i]));
    c2[i] = static_cast<long double>(d[i]) / fit_window_hi;
  }
  // Columns in the order (1, d, log d): the last one's coefficient is the slope after the others
  // are projected out.
  std::vector<std::vector<long double>*> cols = {&c0, &c2, &c1};
  auto dot = [n](const std::vector<long double>& u, const std::vector<long double>& v) {
    long double s = 0;
    for (std::size_t i = 0; i < n; ++i) s += u[i] * v[i];
    return s;
  };
  for (std::size_t j = 0; j < cols.size(); ++j) {
    for (std::size_t k = 0; k < j; ++k) {
      const long double f = dot(*cols[j], *cols[k]) / dot(*cols[k], *cols[k]);
      for (std::size_t i = 0; i < n; ++i) (*cols[j])[i] -= f * (*cols[k])[i];
    }
  }
  // Project y on the first two orthogonal columns, then the slope is <r, q3> / <q3, q3>.
  for (std::size_t k = 0; k < 2; ++k) {
    const long double f = dot(r, *cols[k]) / dot(*cols[k], *cols[k]);
    for (std::size_t i = 0; i < n; ++i) r[i] -= f * (*cols[k])[i];
  }
  return static_cast<double>(dot(r, c1) / dot(c1, c1));
}

struct exponent_row {
  std::string shape;
  double alpha = 0;
  double beta = 0;
  std::string regime;
  std::string point;      ///< leading_edge, trailing_edge, apex_leading_side, apex_trailing_side
  double position = nan;  ///< abscissa of the singular point (apex at 0)
  double theory = nan;    ///< docs/theory.md section 3 (apex: -alpha; 0 stands for the log at alpha = 0)
  double measured = nan;  ///< slope of the local fit (NaN: line load, nothing to measure)
  std::size_t samples = 0;
  std::string status;     ///< the solver's status code
};

/// Theoretical exponents (docs/theory.md sections 3 and 5) of one shape and material.
struct theory_exponents {
  bool line_load = false;
  double leading = nan, trailing = nan, apex = nan;
};

inline theory_exponents theoretical(const std::string& shape, double alpha, double beta, const std::string& regime) {
  const double gam_bounded = (1 - 2 * alpha - beta) / 2, gam_unbounded = -(1 + 2 * alpha + beta) / 2;
  const double del_bounded = (1 + beta) / 2, del_unbounded = (beta - 1) / 2;
  theory_exponents t;
  if (shape == "parabolic") {
    t.leading = gam_bounded;
    t.trailing = del_bounded;
  } else if (shape == "wedge") {
    t.leading = gam_bounded;
    if (regime == "below") {
      t.trailing = del_bounded;
      t.apex = -alpha;
    } else {
      t.trailing = del_unbounded;  // the contact ends at the apex
    }
  } else {
    if (regime == "below") {
      t.leading = gam_unbounded;
      t.trailing = del_unbounded;
    } else {
      t.line_load = true;
    }
  }
  return t;
}

/// Solves one shape alone and measures its exponents.
inline std::vector<exponent_row> measure_exponents(const std::string& shape, double alpha, double beta) {
  using namespace rhabel::punch;
  scene s;
  s.material = make_material(alpha, beta);
  s.speed = 1.0;
  s.indentors = {make_indentor(shape)};
  solve_options o;
  o.grid_points = exponent_grid_points;
  o.displacement = false;
  const scene_result res = solve(s, o);
  const indentor_result& r = res.indentors.at(0);
  const theory_exponents th = theoretical(shape, alpha, beta, rhabel::punch::to_string(res.regime));

  std::vector<exponent_row> rows;
  auto row = [&](const std::string& point, double position, double theory) {
    exponent_row e;
    e.shape = shape;
    e.alpha = alpha;
    e.beta = beta;
    e.regime = rhabel::punch::to_string(res.regime);
    e.point = point;
    e.position = position;
    e.theory = theory;
    e.status = to_string(r.code);
    return e;
  };
  if (th.line_load || !(r.contact_length > 0)) {
    exponent_row e = row("leading_edge", r.a, nan);
    e.status += " (line load)";
    rows.push_back(e);
    return rows;
  }
  const double L = r.contact_length;
  const auto& x = r.grid_x;
  const auto& p = r.pressure;
  const std::size_t n = x.size();

  auto edge_fit = [&](bool leading) {
    std::vector<double> d, y;
    for (std::size_t k = 0; k < n; ++k) {
      const double dist = leading ? (x[k] - r.a) : (r.b - x[k]);
      if (dist >= fit_window_lo * L && dist <= fit_window_hi * L && p[k] > 0) {
        d.push_back(dist / L);
        y.push_back(std::log(p[k]));
      }
    }
    exponent_row e = row(leading ? "leading_edge" : "trailing_edge", leading ? r.a : r.b,
                         leading ? th.leading : th.trailing);
    e.measured = log_log_slope(d, y);
    e.samples = d.size();
    return e;
  };
  rows.push_back(edge_fit(true));
  rows.push_back(edge_fit(false));

  if (!std::isnan(th.apex)) {
    const double apex = 0.0;
    for (int side = -1; side <= 1; side += 2) {
      // Pairs of neighbouring samples on this side: distances d1 < d2 from the apex, divided difference.
      std::vector<double> d1, d2, y;
      for (std::size_t k = 0; k + 1 < n; ++k) {
        if ((x[k] - apex) * (x[k + 1] - apex) <= 0) continue;  // the pair straddles the apex
        const double u = side * (x[k] - apex), v = side * (x[k + 1] - apex);
        const double lo = std::min(u, v), hi = std::max(u, v);
        if (lo >= fit_window_lo * L && hi <= fit_window_hi * L) {
          const double slope = std::abs(p[k + 1] - p[k]) / (x[k + 1] - x[k]);
          if (slope > 0) {
            d1.push_back(lo / L);
            d2.push_back(hi / L);
            y.push_back(std::log(slope));
          }
        }
      }
      // The divided difference of A d^e is A e xi^(e-1) at the mean-value point xi of the pair, not
      // at its midpoint (which biases the slope by ~(h/d)^2: 3e-3 over this window). xi depends on
      // e, so the fit is repeated with xi from the previous slope (the logarithmic mean at e = 0).
      auto mean_value_point = [](double a, double b, double e) {
        if (std::abs(e) < 1e-9) return (b - a) / std::log(b / a);
        return std::pow((std::pow(b, e) - std::pow(a, e)) / (e * (b - a)), 1.0 / (e - 1.0));
      };
      double e_fit = th.apex;  // starting point only: three fixed-point steps make it irrelevant
      std::vector<double> xi(y.size());
      for (int it = 0; it < 4; ++it) {
        for (std::size_t j = 0; j < y.size(); ++j) xi[j] = mean_value_point(d1[j], d2[j], e_fit);
        e_fit = log_log_slope(xi, y) + 1.0;
      }
      exponent_row e = row(side < 0 ? "apex_leading_side" : "apex_trailing_side", apex, th.apex);
      e.measured = e_fit;
      e.samples = y.size();
      rows.push_back(e);
    }
  }
  return rows;
}

inline std::vector<exponent_row> exponent_table() {
  std::vector<exponent_row> all;
  for (const auto& mc : exponent_materials())
    for (const char* shape : {"flat", "parabolic", "wedge"})
      for (auto& r : measure_exponents(shape, mc.alpha, mc.beta)) all.push_back(r);
  return all;
}

/// alpha grid of the wedge and parabola tables.
inline std::vector<double> table_alphas() {
  return {0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.6, 0.7, 0.8, 0.9};
}
inline std::vector<double> table_betas() { return {0.0, 0.3}; }

struct wedge_row {
  double alpha = 0, beta = 0;
  std::string regime;
  double eps = nan;   ///< (apex - a)/L
  double L = nan;     ///< contact length (E_U = 1, load 1, S1 = S2 = 1)
  double Cf = nan;    ///< C_f / S1
  double residual = nan;
  std::string status;
};

inline wedge_row wedge_values(double alpha, double beta) {
  using namespace rhabel::punch;
  scene s;
  s.material = make_material(alpha, beta);
  s.speed = 1.0;
  s.indentors = {make_indentor("wedge")};
  const scene_result res = solve(s);
  const indentor_result& r = res.indentors.at(0);
  wedge_row w;
  w.alpha = alpha;
  w.beta = beta;
  w.regime = rhabel::punch::to_string(res.regime);
  w.eps = r.epsilon.value_or(nan);
  w.L = r.contact_length;
  w.Cf = r.hysteretic_friction;
  w.residual = r.residual;
  w.status = to_string(r.code);
  return w;
}

struct parabola_row {
  double alpha = 0, beta = 0;
  std::string regime;
  double b_over_L = nan, b_over_L_closed = nan;
  double L = nan, L_closed = nan;
  double CfR_over_L = nan, CfR_over_L_closed = nan;
  double residual = nan;
  std::string status;
};

/// Closed forms of docs/theory.md section 5 with R = 1, E_U = 1, load 1.
inline void parabola_closed(parabola_row& p) {
  const double a = p.alpha, b = p.beta;
  const double gam = (1 - 2 * a - b) / 2, del = (1 + b) / 2;
  p.b_over_L_closed = (1 - 2 * a - b) / (2 * (1 - a));
  p.CfR_over_L_closed = (a + b) * (2 - a) / ((1 - a) * (3 - a));
  // load = (pi/2) int g = (pi/2) cos(beta pi/2) L^(2 - alpha) B(gam + 1, del + 1) / (pi Gamma(2 - alpha))
  const double per_L = 0.5 * std::cos(b * pi / 2) * boost::math::beta(gam + 1, del + 1) / boost::math::tgamma(2 - a);
  p.L_closed = std::pow(1.0 / per_L, 1.0 / (2 - a));
}

inline parabola_row parabola_values(double alpha, double beta) {
  using namespace rhabel::punch;
  scene s;
  s.material = make_material(alpha, beta);
  s.speed = 1.0;
  s.indentors = {make_indentor("parabolic")};
  const scene_result res = solve(s);
  const indentor_result& r = res.indentors.at(0);
  parabola_row p;
  p.alpha = alpha;
  p.beta = beta;
  p.regime = rhabel::punch::to_string(res.regime);
  p.L = r.contact_length;
  p.b_over_L = r.b / r.contact_length;
  p.CfR_over_L = r.hysteretic_friction / r.contact_length;
  p.residual = r.residual;
  p.status = to_string(r.code);
  parabola_closed(p);
  return p;
}

}  // namespace rhabel_tables
