// punch/src/shapes.cpp: the shapes and their forcing: F = f'/Gamma(1 - alpha) as smooth part +
// steps, its projection on the image basis (steps in closed form), own slope and mean slope.
// See internal.hpp for the layout of punch/src.
#include "internal.hpp"

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"
#include "rhabel/riemann/abel_solver.hpp"

#include <Eigen/Dense>
#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/minima.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace rhabel::punch::detail {

// ---------------------------------------------------------------------------------------------
// Jacobi polynomials for exponents that may be <= -1 (the image family of the nu = -1 class above
// the boundary has p = gam - 1 < -1): abel::plain_jacobi_values, the plain three-term
// recurrence, valid as long as no denominator vanishes, which docs/theory.md section 4's families
// guarantee for alpha not an integer >= 1.
using abel::plain_jacobi_values;

// Position s of [a, b] -> (x, 1 + x, 1 - x) with both distances computed directly.
mapped map_to_reference(double s, double a, double b) {
  const double L = b - a;
  const double one_plus = 2 * (s - a) / L, one_minus = 2 * (b - s) / L;
  return {one_plus <= one_minus ? one_plus - 1 : 1 - one_minus, one_plus, one_minus};
}

// ---------------------------------------------------------------------------------------------
// Image coefficients: F(s) = sum_m d_m P_m^(p, q)(y) on [a, b], p = gam + nu (at y = +1),
// q = del + nu (at y = -1). Returns d_0 .. d_M. Not abel::solve_piecewise (which overlaps it), for
// four reasons: (1) the steps' coefficients here are in closed form (Rodrigues), where
// solve_piecewise integrates each piece by Gauss-Jacobi (M/2 + 24 nodes per piece); (2) d_0 alone
// (M = 0) is what the orthogonality root of coupled wedges and of general profiles with corners
// evaluates ~30 times per solve, while solve_piecewise always builds the full solution; (3) the
// adaptive degree is judged on the smooth part's tail alone (image_expansion::tail); (4) the
// Chebyshev fallback for a non-integrable image weight (nu = -1 above the boundary), which
// solve_piecewise rejects. The smooth part: M + 8 Gauss-Jacobi nodes.

image_expansion image_coefficients(double a, double b, const edge_exponents& e, const forcing& F,
                                   std::size_t M) {
  const double p = e.gam + e.nu, q = e.del + e.nu;
  image_expansion out;
  if (p > -1 && q > -1) {
    // Orthogonal projection with the (integrable) image weight (1 - y)^p (1 + y)^q: the smooth part
    // by M + 8 Gauss-Jacobi nodes (abel's process-wide rule cache; the shared_ptr keeps the rule
    // alive while in use), kept apart because the adaptive degree is judged on it alone (the step
    // coefficients below are exact).
    std::vector<double> smooth(M + 1, 0.0);
    if (F.smooth) {
      const auto rule_ptr = abel::cached_gauss_jacobi_rule<double>(M + 8, p, q);
      const auto& rule = *rule_ptr;
      for (std::size_t i = 0; i < rule.size(); ++i) {
        const double s = rule.x_minus_lo[i] <= rule.hi_minus_x[i] ? a + (b - a) * rule.x_minus_lo[i] / 2
                                                                  : b - (b - a) * rule.hi_minus_x[i] / 2;
        const double f = F.smooth(s) * rule.weight[i];
        const auto P = plain_jacobi_values(M, p, q, rule.x[i]);
        for (std::size_t m = 0; m <= M; ++m) smooth[m] += f * P[m];
      }
    }
    out.d = smooth;
    // Steps H(s - s_k): int_{y_k}^1 w' P_m, by Rodrigues' formula (DLMF 18.9.16) for m >= 1 and by
    // the incomplete beta function for m = 0.
    for (const auto& [position, jump] : F.steps) {
      if (position >= b) continue;
      if (position <= a) {
        out.d[0] += jump * std::exp(quadrature::log_jacobi_norm_squared<double>(0, p, q));
        continue;
      }
      const mapped y = map_to_reference(position, a, b);
      out.d[0] += jump * std::pow(2.0, p + q + 1) * boost::math::beta(p + 1, q + 1, y.one_minus / 2);
      if (M >= 1) {
        const auto P = plain_jacobi_values(M - 1, p + 1, q + 1, y.x);
        const double W = std::pow(y.one_minus, p + 1) * std::pow(y.one_plus, q + 1);
        for (std::size_t m = 1; m <= M; ++m) out.d[m] += jump * W * P[m - 1] / (2.0 * static_cast<double>(m));
      }
    }
    double largest = 0, tail = 0;
    for (std::size_t m = 0; m <= M; ++m) {
      const double norm = quadrature::jacobi_norm_squared<double>(m, p, q);
      out.d[m] /= norm;
      largest = std::max(largest, std::abs(out.d[m]));
      if (4 * m >= 3 * M && m > 0) tail = std::max(tail, std::abs(smooth[m] / norm));
    }
    out.tail = largest > 0 ? tail / largest : 0;
    return out;
  }
  // Non-integrable image weight (nu = -1 above the boundary): interpolate F at Chebyshev points
  // in the image basis. The expansion of a polynomial is still unique (the family has exact
  // degrees), and d_0 = 0 is the analytic continuation of the orthogonality condition.
  const std::size_t n = M + 1;
  Eigen::MatrixXd V(n, n);
  Eigen::VectorXd rhs(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double theta = pi * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    const double y = std::cos(theta);
    const double s = a + (b - a) * (1 + y) / 2;
    double f = F.smooth ? F.smooth(s) : 0.0;
    for (const auto& [position, jump] : F.steps)
      if (s > position) f += jump;
    rhs[static_cast<Eigen::Index>(i)] = f;
    const auto P = plain_jacobi_values(M, p, q, y);
    for (std::size_t m = 0; m < n; ++m) V(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(m)) = P[m];
  }
  const Eigen::VectorXd d = V.partialPivLu().solve(rhs);
  out.d.assign(n, 0.0);
  double largest = 0, tail = 0;
  for (std::size_t m = 0; m < n; ++m) {
    out.d[m] = d[static_cast<Eigen::Index>(m)];
    largest = std::max(largest, std::abs(out.d[m]));
    if (4 * m >= 3 * M && m > 0) tail = std::max(tail, std::abs(out.d[m]));
  }
  out.tail = largest > 0 ? tail / largest : 0;
  return out;
}


// Density from the image coefficients of F (abel::solve_image_series: c_n = d_(n - nu) / lambda_n on
// F~ = (L/2)^(-alpha) F). For nu = +1 the homogeneous coefficient c_0 is left at 0 (the caller adds the load).
contact_density density_from_image(double a, double b, const abel::abel_parameters<double>& par, const edge_exponents& e,
                                   const image_expansion& img) {
  const abel::abel_operator<double> op(par, a, b);
  const double scale = std::pow((b - a) / 2, -par.alpha());
  std::vector<double> d = img.d;
  for (double& v : d) v *= scale;
  auto sol = abel::solve_image_series(op, leading_edge(e.nu), trailing_edge(e.nu), d);
  contact_density g;
  g.jacobi = std::move(sol.density);
  g.nu = e.nu;
  g.tail = img.tail;
  return g;
}

// Own slope f' of an indentor at absolute position s.
double own_slope(const indentor_state& st, double s) {
  const double x = s - st.apex;
  switch (st.k) {
    case kind::parabola: return -x / std::get<parabolic>(st.source->shape).radius;
    case kind::wedge: {
      const auto& w = std::get<wedge>(st.source->shape);
      return x < 0 ? w.slope_leading : -w.slope_trailing;
    }
    case kind::flat: return 0;
    case kind::general: return std::get<general_profile>(st.source->shape).slope(x);
  }
  return 0;
}

double max_slope(const indentor_state& st, double a, double b) {
  double m = 0;
  for (int k = 0; k <= 8; ++k) m = std::max(m, std::abs(own_slope(st, a + (b - a) * k / 8.0)));
  return m;
}

// C_f = int f' g / int g for a density without apex part (abel::jacobi_density::integrate, split at
// the corners; with knots' terms also at the knots, where f''' jumps, and each term by its
// composite rule).
double mean_slope(const indentor_state& st, const contact_density& g) {
  std::vector<double> cuts;
  if (st.k == kind::general) {
    const auto& gp = std::get<general_profile>(st.source->shape);
    for (double c : gp.corners) cuts.push_back(st.apex + c);
    if (!g.kinks.empty())
      for (const auto& [at, jump] : gp.knots)
        if (st.apex + at > g.a() && st.apex + at < g.b()) cuts.push_back(st.apex + at);
  }
  const auto slope = [&](double t) { return own_slope(st, t); };
  double moment = g.jacobi.integrate(slope, cuts);
  for (const auto& term : g.kinks) moment += term.integrate(slope, cuts);
  return moment / (g.jacobi.integral() + g.kinks_integral);
}

// F = f'/Gamma(1 - alpha) of the indentor's own profile as smooth part + steps (the coupled solve
// adds the others' action as data of its own: coupled_fixed.cpp).
forcing own_forcing(const indentor_state& st, const context& cx) {
  forcing F;
  const double gf = cx.gamma_factor;
  switch (st.k) {
    case kind::parabola: {
      const double R = std::get<parabolic>(st.source->shape).radius, apex = st.apex;
      F.smooth = [=](double s) { return -(s - apex) / (R * gf); };
      break;
    }
    case kind::wedge: {
      const auto& w = std::get<wedge>(st.source->shape);
      const double S1 = w.slope_leading;
      F.smooth = [=](double) { return S1 / gf; };
      F.steps.push_back({st.apex, -(w.slope_leading + w.slope_trailing) / gf});
      break;
    }
    case kind::flat:
      break;
    case kind::general: {
      const auto& gp = std::get<general_profile>(st.source->shape);
      const auto slope = gp.slope;
      const double apex = st.apex;
      // Jumps of f' at the corners are taken out as steps so that the smooth part is continuous.
      std::vector<std::pair<double, double>> jumps;
      for (double c : gp.corners) {
        const double h = 1e-9 * std::max(1.0, std::abs(c));
        jumps.push_back({apex + c, (slope(c + h) - slope(c - h)) / gf});
      }
      F.steps = jumps;
      for (const auto& [at, jump] : gp.knots) F.kinks.push_back({apex + at, 2u, jump / gf});
      F.smooth = [=](double s) {
        double v = slope(s - apex) / gf;
        for (const auto& [pos, j] : jumps)
          if (s > pos) v -= j;
        return v;
      };
      break;
    }
  }
  return F;
}

}  // namespace rhabel::punch::detail
