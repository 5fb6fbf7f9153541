// rhabel/punch/detail/interval_density.hpp: the spectral density on one contact interval
// (internal to rhabel::punch; compiled in double in punch/src).
//
// On [a, b], x = -1 + 2 (t - a)/L, the density of eq. (8) is represented as
//     g(t) = w(x) sum_n c_n P_n^(del, gam)(x),   w(x) = (1 - x)^del (1 + x)^gam,
// so gam is the exponent at the leading edge a (x = -1) and del at the trailing edge b (x = +1).
// Spectral relation (math.md section 4), with nu = -(gam + del + alpha) in {-1, 0, 1}:
//     A[w P_n](y) = (L/2)^alpha lambda_n P_(n-nu)^(gam+nu, del+nu)(y),
//     lambda_n = -2^(-nu) pi (1-alpha)_n / (n! sin(pi del)).
// The image family has its exponent gam+nu at y = +1 and del+nu at y = -1 (the ends swap).
#pragma once

#include <cstddef>
#include <optional>
#include <functional>
#include <utility>
#include <vector>

namespace rhabel::punch::detail {

/// Edge exponents of one contact interval and the index nu = -(gam + del + alpha).
struct edge_exponents {
  double gam = 0;  ///< exponent at the leading edge a
  double del = 0;  ///< exponent at the trailing edge b
  int nu = -1;
};

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

/// The density on one interval (or a line load when line_load is true: g = load delta(t - a)).
struct interval_density {
  double a = 0, b = 0;
  double alpha = 0;
  edge_exponents e;
  std::vector<double> c;       ///< Jacobi coefficients of g / w
  double d0 = 0;               ///< coefficient of the missing image polynomial (nu = -1 only)
  double tail = 0;             ///< size of the last coefficients relative to the largest (estimate)
  bool line_load = false;
  double line_weight = 0;      ///< int g for a line load
  bool has_apex = false;       ///< g additionally holds apex.sigma * h(x) (wedge below the boundary)
  apex_part apex;

  double length() const { return b - a; }
  /// g(t) for a < t < b (0 outside).
  double value(double t) const;
  /// int_a^b g.
  double integral() const;
  /// int_s^b g for a <= s <= b (Rodrigues formula term by term).
  double integral_from(double s) const;
  /// g(t) / w(x(t)): the smooth factor.
  double smooth_factor(double x) const;
};

}  // namespace rhabel::punch::detail
