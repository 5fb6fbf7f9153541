// rhabel/punch/detail/contact_density.hpp: the density on one contact interval
// (internal to rhabel::punch; compiled in double in punch/src).
//
// The mathematics lives in rhabel::abel (abel_operator.hpp, abel_solver.hpp, step_enrichment.hpp);
// this header only bundles what one contact needs:
//   * jacobi: the Jacobi series abel::jacobi_density<double>
//         g(t) = w(x) sum_n c_n P_n^(del, gam)(x),   w(x) = (1 - x)^del (1 + x)^gam,  x = -1 + 2 (t - a)/L,
//     (gam at the leading edge a, del at the trailing edge b; coefficients from abel::solve,
//     abel::solve_image_series or the smooth part of abel::solve_step);
//   * apex: for the wedge below the boundary, the singular enrichment C phi of abel::solve_step
//     (phi = w q E, E = kappa (x - x0)_+^(-alpha) + (x0 - x)_+^(-alpha), log form for alpha < 0.01)
//     stored as an abel::enriched_density whose own smooth series is EMPTY (the series lives in
//     `jacobi`), so that g = jacobi + apex everywhere and each part keeps abel's evaluators; for an
//     apex near an edge (|x0| > 1/2) solve_step's Moebius map makes the series live in the mapped
//     variable: then apex holds the WHOLE density (apex.mobius != 0) and jacobi only a c_0 (zero
//     until set_load corrects the load);
//   * for an isolated wedge with the apex in the outer quarters of the contact: jacobi the closed
//     form for the long side's constant data and apex the rest, both in the class singular at the
//     edge next to the apex, and `physical` the bounded class they sum to (see `physical`);
//   * a line load (flat punch on/above the boundary);
//   * layer: while the coupled solve iterates on nearly touching contacts, the boundary-layer
//     part of abel::solve_union_layered (simple poles beyond the ends facing a neighbour, in the
//     class of `jacobi`); absorb_layer turns it into Jacobi coefficients before the density is
//     reported, so the report, the fields and the surface see a series and an apex only;
//   * kinks: for a general profile with knots (f''' jumps) inside the contact, the singular term
//     C phi of each knot (abel::solve_kinks' terms, enriched_densities with empty series): g =
//     jacobi + sum kinks. They act on other points through their composite rules (kink_rule);
//   * forcing: the right side of (8) as smooth part + steps (projected in contact.cpp with the steps'
//     coefficients in closed form) + knots.
#pragma once

#include "rhabel/abel.hpp"

#include <cstddef>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace rhabel::punch::detail {

/// Edge exponents of one contact interval and the index nu = -(gam + del + alpha).
using edge_exponents = abel::edge_exponents<double>;

/// Right side of (8) on one interval: F(s) = smooth(s) + sum_k jump_k H(s - position_k).
struct forcing {
  std::function<double(double)> smooth;               ///< may be empty (zero)
  std::vector<std::pair<double, double>> steps;       ///< (position, jump)
  /// Points where smooth'' jumps (a general profile's knots: F = f'/Gamma(1 - alpha)).
  std::vector<abel::kink<double>> kinks;
};

/// The density of one contact: Jacobi series + (wedge below the boundary) the apex enrichment of
/// abel::solve_step, or a line load (g = line_weight delta(t - a)).
struct contact_density {
  abel::jacobi_density<double> jacobi;  ///< the series part of g on [lo, hi] = [a, b]
  int nu = -1;                 ///< index of the class of jacobi (gam = jacobi.gam, del = jacobi.del)
  double tail = 0;             ///< estimated relative error of the density
  bool line_load = false;
  double line_weight = 0;      ///< int g for a line load
  bool has_apex = false;       ///< g additionally holds apex = C phi (wedge below the boundary)
  abel::enriched_density<double> apex;  ///< C phi; apex.smooth carries [a, b], gam, del, no coefficients
  double apex_integral = 0;    ///< int C phi (a composite quadrature: computed once, kept by scale)
  /// Isolated wedge with the apex in the outer quarters (contact.cpp, build_wedge_near_edge): jacobi
  /// holds the closed-form solution for the long side's constant data in the class singular at the
  /// edge next to the apex (nu = 0) and apex the rest (abel::apex_placement::centred), in the same
  /// class. Their singular parts at that edge cancel (the orthogonality condition), so g has these
  /// exponents (nu = -1); empty otherwise (g has jacobi's).
  std::optional<edge_exponents> physical;
  /// The boundary-layer part g_layer = w(x) sum_k a_k d_k/(d_k + 1 -+ x) of the coupled solve for
  /// nearly touching contacts (abel::solve_union_layered), in the class of `jacobi`; empty
  /// otherwise. value, integral, intensity and scale include it; absorb_layer removes it.
  abel::layer_density<double> layer;
  /// The knots' terms C phi (abel::solve_kinks), each with an empty series, in jacobi's class;
  /// value, integral(s), intensity, scale and set_interval include them.
  std::vector<abel::enriched_density<double>> kinks;
  double kinks_integral = 0;  ///< sum of int C phi over kinks (composite quadratures: kept, scaled)
  std::size_t particular_degree = 0;  ///< with kinks: the image coefficients of the series' solve

  double a() const { return jacobi.lo; }
  double b() const { return jacobi.hi; }
  double length() const { return jacobi.hi - jacobi.lo; }
  edge_exponents exponents() const { return physical ? *physical : edge_exponents{jacobi.gam, jacobi.del, nu}; }
  /// Abscissa of the apex (has_apex only), from the enrichment's reference breakpoint.
  double apex_position() const { return a() + (1 + apex.apex_reference()) * length() / 2; }
  /// The kinks' terms as one composite rule (abel::enrichment_nodes of each, concatenated): int f g_kinks
  /// ~= sum_j value_j f(t_j) for f whose nearest singular points lie beyond_lo / beyond_hi
  /// half-lengths below a / above b. Empty without kinks.
  abel::enrichment_rule<double> kink_rule(double beyond_lo, double beyond_hi) const;
  /// The far field's moments of the knots' terms on the leaf whose interval is [a, b] (the
  /// Lagrange polynomials of `field`'s grid at the rule's nodes, times their values: kink_rule),
  /// to add to far_field::density_moments of the series; zero without knots. The polynomials are
  /// smooth on [a, b], so the rules are as accurate here as for int C phi.
  Eigen::VectorXd kink_moments(const abel::far_field<double>& field) const;
  /// Moves the density to [lo, hi] (same reference shape).
  void set_interval(double lo, double hi);
  /// Sets apex_integral from apex (call after building the enrichment).
  void update_apex_integral() { apex_integral = has_apex ? apex.integral() : 0.0; }
  /// Multiplies g by `factor` (series and enrichment).
  void scale(double factor);
  /// g(t) for a < t < b (0 outside).
  double value(double t) const;
  /// int_a^b g.
  double integral() const;
  /// int_a^s g for a <= s <= b, accurate relative to itself when small (s near a).
  double integral_to(double s) const;
  /// int_s^b g for a <= s <= b, accurate relative to itself when small (s near b).
  double integral_from(double s) const;
  /// Edge intensity K = lim g(t) |t - edge|^(-exponent) of the series, the apex and the layer
  /// parts in jacobi's class (abel::jacobi_density::intensity_leading/_trailing).
  double intensity(bool trailing) const;
  /// Adds the layer to the Jacobi coefficients and empties it: the projection of the layer's
  /// factor onto P_n^(del, gam) by an n-point Gauss-Jacobi rule (exact for polynomials of degree
  /// < n), n chosen so that every pole's coefficients, which decay like rho^-n with
  /// rho = 1 + d + sqrt(d (d + 2)) for a pole d beyond an end (Bernstein ellipse), fall below
  /// `relative_accuracy` of the density's scale (the largest series coefficient, or the layer's
  /// factor at 11 points), at most max_degree (<= max_absorbed_degree); at that cap the size of the coefficients
  /// left out joins `tail`, and so does the projection's error measured afterwards (the new
  /// series against the old one plus the poles, at 64 Chebyshev points and at geometric distances
  /// from the ends with poles, relative to that scale). Cost O(n^2): n <~ 30/sqrt(2 d_min), ~500
  /// at a gap of 1e-3 of the length, ~800 at 4e-4 (measured: ~15 sqrt(L/gap)), ~1.5e4 at 1e-6.
  /// Returns the degree used (0: no layer).
  std::size_t absorb_layer(double relative_accuracy, std::size_t max_degree = max_absorbed_degree);
  static constexpr std::size_t max_absorbed_degree = 1 << 15;
};

}  // namespace rhabel::punch::detail
