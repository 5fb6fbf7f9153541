// rhabel/punch/detail/contact_density.hpp: the density on one contact interval
// (internal to rhabel::punch; compiled in double in punch/src).
//
// The mathematics lives in rhabel::abel (abel_operator.hpp, abel_solver.hpp); this header only adds
// what is physical or not (yet) in abel:
//   * contact_density: the Jacobi series abel::jacobi_density<double>
//         g(t) = w(x) sum_n c_n P_n^(del, gam)(x),   w(x) = (1 - x)^del (1 + x)^gam,  x = -1 + 2 (t - a)/L,
//     (gam at the leading edge a, del at the trailing edge b; its coefficients come from
//     abel::solve_image_series, i.e. the spectral relation of abel_operator.hpp), plus the apex part
//     of the wedge below the boundary, or a line load;
//   * apex_part: the wedge's apex singularity, split off before the spectral solve. It is kept here
//     rather than replaced by abel::solve_step, which (as of this writing) fails when the apex is one
//     of its Chebyshev interpolation nodes: the symmetric elastic wedge (alpha = 0, S1 = S2, apex at
//     the centre, every odd node count) gives int_apex^b g / int g = 0.396 instead of 1/2 and a
//     solvability defect 5e-2; with the apex moved by 1e-9 L it is right. It also diverges for the
//     apex near an edge (alpha = 0.4, S2/S1 = 3, 1 - eps = 3e-6: defect 7e3 at 65 points).
//   * forcing: the right side of (8) as smooth part + steps (projected in contact.cpp with the steps'
//     coefficients in closed form).
#pragma once

#include "rhabel/abel.hpp"

#include <cstddef>
#include <optional>
#include <functional>
#include <utility>
#include <vector>

namespace rhabel::punch::detail {

/// Edge exponents of one contact interval and the index nu = -(gam + del + alpha).
using edge_exponents = abel::edge_exponents<double>;

/// Right side of (8) on one interval: F(s) = smooth(s) + sum_k jump_k H(s - position_k).
struct forcing {
  std::function<double(double)> smooth;               ///< may be empty (zero)
  std::vector<std::pair<double, double>> steps;       ///< (position, jump)
};

/// Singular part of the wedge density at its apex x0 (reference coordinates x in [-1, 1]):
///     h(x) = chi(x) psi(x),  psi = kappa e(x - x0) H(x - x0) + e(x0 - x) H(x0 - x) - ((1-kappa)/alpha) H(x - x0),
///     e(r) = (r^-alpha - 1)/alpha  (-> -log r at alpha = 0),   chi = (1 - u^3)^4, u = ((x - x0)/r)^2 < 1.
/// On the whole line A[psi] is piecewise constant with the jump
///     J = -pi ((1 - kappa)^2 + 4 kappa sin^2(pi alpha/2)) / (alpha sin(pi alpha))   (-> -pi^2 - (pi tan(beta pi/2))^2),
/// (derived from int_0^inf r^-alpha (1 + r)^(alpha-1) - log = psi(1) - psi(1 - alpha) and its mirror; checked
/// with 30-digit quadrature at alpha = 0.3, kappa = 0.4), so A[chi psi] = J H(y - x0) + (a smooth function) and
/// the remainder of the density is smooth times the edge weights: spectral convergence is restored.
struct apex_part {
  double alpha = 0, kappa = 1, one_minus_kappa_over_alpha = 0;
  double x0 = 0, r = 1;
  double sigma = 0;  ///< coefficient of h in the density (reference coordinates)
  double chi(double x) const;
  double psi(double x) const;
  double psi_of(double dx0) const;  ///< psi at x0 + dx0 (dx0 exact: no rounding of x0 + dx0)
  double h_of(double dx0) const;    ///< chi psi at x0 + dx0
  double h(double x) const { return h_of(x - x0); }
  /// A_x[h](y) = int h(x) K(x, y) dx on the reference axis (any y != x0; y outside [-1,1] allowed).
  double apply(double y) const;
  /// int_lo^hi h(x) dx.
  double integral(double lo, double hi) const;
  /// The jump J of A[psi] across x0.
  double jump() const;
};

/// The density of one contact: the Jacobi series of rhabel::abel (abel::jacobi_density: weight,
/// coefficients, evaluation, integrals, intensities), plus the apex part of the wedge below the
/// boundary, or a line load (g = line_weight delta(t - a), flat punch on/above the boundary).
struct contact_density {
  abel::jacobi_density<double> jacobi;  ///< g / (apex part) on [lo, hi] = [a, b]
  int nu = -1;                 ///< index of the class of jacobi (gam = jacobi.gam, del = jacobi.del)
  double tail = 0;             ///< size of the last coefficients relative to the largest (estimate)
  bool line_load = false;
  double line_weight = 0;      ///< int g for a line load
  bool has_apex = false;       ///< g additionally holds apex.sigma * h(x) (wedge below the boundary)
  apex_part apex;

  double a() const { return jacobi.lo; }
  double b() const { return jacobi.hi; }
  double length() const { return jacobi.hi - jacobi.lo; }
  edge_exponents exponents() const { return {jacobi.gam, jacobi.del, nu}; }
  /// g(t) for a < t < b (0 outside).
  double value(double t) const;
  /// int_a^b g.
  double integral() const;
  /// int_s^b g for a <= s <= b.
  double integral_from(double s) const;
};

}  // namespace rhabel::punch::detail
