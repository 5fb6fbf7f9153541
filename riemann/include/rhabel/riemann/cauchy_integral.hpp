// rhabel/riemann/cauchy_integral.hpp
//
// Cauchy integrals of Jacobi-weighted, piecewise smooth densities on a segment [lo, hi]:
//
//     w(t) = (hi - t)^p (t - lo)^q ,   p, q > -1     (p at hi, q at lo: the rhabel convention)
//     h(t) = smooth(t) + sum_j size_j [t > position_j]     (a smooth part plus steps)
//
//     transform(z)        = C(z) = int_lo^hi w(t) h(t) / (t - z) dt ,   z in C \ [lo, hi]
//     principal_value(x)  = PV int_lo^hi w(t) h(t) / (t - x) dt ,         lo < x < hi
//     moment()            = int_lo^hi w(t) h(t) dt                          (= -lim z C(z))
//
// The normalisation is the bare integral (no 1/(2 pi i)); the Plemelj limits are
// C_+-(x) = PV(x) +- i pi w(x) h(x)  (Sokhotski-Plemelj; Gakhov, "Boundary Value Problems",
// sec. 4), exposed as plemelj_plus / plemelj_minus.
//
// Method (product integration with singularity subtraction; a different method from the graded
// quadrature of rhabel/quadrature/cauchy_transform.hpp, against which the tests compare - the
// two share only the Gauss-Jacobi rules of rhabel::quadrature, which are tested on their own):
// [lo, hi] is cut into pieces, each touching at most one end of the segment, with a break at
// every step of h; pieces that start at a step close to an end are graded geometrically away
// from it. On a piece [u, v] write w h = omega phi, omega the end factor that is singular on
// the piece ((t - lo)^q, (hi - t)^p or 1; integer parts of p, q are moved into phi) and phi
// analytic on a neighbourhood of the piece. Then
//     int_u^v omega phi/(t - z) dt = sum_i W_i (phi(t_i) - phi(z)) / (t_i - z) + phi(z) Omega(z),
// with (t_i, W_i) the n-point Gauss-Jacobi rule of omega (rhabel::quadrature::gauss_jacobi on
// [-1, 1], cached, mapped to the piece through its distances 1 -+ x; exact for the divided
// difference when phi is a polynomial of degree <= 2n) and Omega(z) = int_u^v omega/(t - z) dt
// in closed form through the single-power Cauchy integral K(q, rho) of detail/power_cauchy.hpp
// (logarithms for omega = 1). On the cut, phi(x) is phi's own formula; off the cut it is
// the barycentric interpolant of phi at the Gauss nodes (so the result is the exact Cauchy
// integral of omega times that interpolant). The subtraction leaves a logarithmic term at
// the artificial breaks that cancels between neighbouring pieces; x is never allowed to sit on
// one (two break layouts, the one farther from x is used), and when x is near a Gauss node the
// n+1-point rule (whose nodes interlace) is used instead, so the divided difference never
// cancels more than O(1) digits.
//
// Accuracy: for h analytic in a neighbourhood of [lo, hi] (Bernstein ratio r per piece) the
// error decays like r^(-2n); at the default order (nodes ~ 1.1 x decimal digits + 8) the
// measured relative error is a few eps relative to int |w h|/|t - x| (the condition number of
// the PV), in double and at 50 digits (tests/riemann/test_cauchy_integral.cpp). Near a step
// the PV grows like log|x - position|, at the ends like (hi - x)^p, (x - lo)^q or log.
// No error estimate is returned by this class: callers (the solvers) compare two orders.
//
// Bad input (non-finite or inverted interval, p or q <= -1, step outside (lo, hi), x outside
// (lo, hi) or on a step, z on the cut) throws std::domain_error naming function, parameter,
// value and valid range.
#pragma once

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/riemann/detail/power_cauchy.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace rhabel::riemann {

/// A step of height `size` at `position`: contributes size * [t > position].
template <class Real>
struct step {
  Real position;
  Real size;
};

/// h(t) = smooth(t) + sum_j steps[j].size [t > steps[j].position].
/// `smooth` must be analytic on a neighbourhood of the segment (it is also evaluated, for the
/// subtraction, at points of the segment on either side of a step).
template <class Real>
struct piecewise_function {
  std::function<Real(Real)> smooth;
  std::vector<step<Real>> steps;

  Real operator()(const Real& t) const {
    Real value = smooth ? smooth(t) : Real(0);
    for (const auto& s : steps)
      if (t > s.position) value += s.size;
    return value;
  }
};

/// Default Gauss order per piece for `Real`.
template <class Real>
std::size_t default_cauchy_order() {
  return static_cast<std::size_t>(1.1 * detail::target_digits<Real>()) + 8;
}

template <class Real>
class jacobi_cauchy_integral {
 public:
  using complex_type = std::complex<Real>;

  /// w(t) = (hi - t)^p (t - lo)^q, density w h; `order` Gauss nodes per piece (0 = default).
  jacobi_cauchy_integral(Real lo, Real hi, Real p, Real q, piecewise_function<Real> h, std::size_t order = 0)
      : lo_(lo), hi_(hi), p_(p), q_(q), h_(std::move(h)) {
    using std::floor;
    using std::isfinite;
    const char* fn = "jacobi_cauchy_integral";
    if (!isfinite(lo)) quadrature::detail::throw_bad_parameter(fn, "lo", lo, "finite, lo < hi");
    if (!isfinite(hi) || !(hi > lo)) quadrature::detail::throw_bad_parameter(fn, "hi", hi, "finite, hi > lo");
    if (!(p > -1) || !isfinite(p)) quadrature::detail::throw_bad_parameter(fn, "p", p, "(-1, inf)");
    if (!(q > -1) || !isfinite(q)) quadrature::detail::throw_bad_parameter(fn, "q", q, "(-1, inf)");
    for (const auto& s : h_.steps) {
      if (!(s.position > lo) || !(s.position < hi))
        quadrature::detail::throw_bad_parameter(fn, "step position", s.position, "(lo, hi)");
      if (!isfinite(s.size)) quadrature::detail::throw_bad_parameter(fn, "step size", s.size, "finite");
    }
    n_ = order == 0 ? default_cauchy_order<Real>() : order;
    if (n_ < 2) quadrature::detail::throw_bad_parameter(fn, "order", n_, "[2, inf) (0 = default)");
    // integer parts of the exponents go into phi, fractional parts (-1 < . < 1) into omega
    p_int_ = p >= 1 ? static_cast<int>(floor(p)) : 0;
    q_int_ = q >= 1 ? static_cast<int>(floor(q)) : 0;
    p_frac_ = p - Real(p_int_);
    q_frac_ = q - Real(q_int_);
    k_lo_.emplace(q_frac_);
    k_hi_.emplace(p_frac_);
    build();
  }

  const Real& lo() const { return lo_; }
  const Real& hi() const { return hi_; }
  std::size_t order() const { return n_; }

  /// w(x) h(x) for lo < x < hi (x not on a step).
  Real density(const Real& x) const { return weight(x) * h_(x); }

  /// w(x) = (hi - x)^p (x - lo)^q.
  Real weight(const Real& x) const {
    using std::pow;
    return pow(hi_ - x, p_) * pow(x - lo_, q_);
  }

  /// int w h dt.
  Real moment() const {
    Real sum = 0;
    for (const auto& piece : layouts_[0])
      for (std::size_t i = 0; i < piece.rule[0].size(); ++i) sum += piece.rule[0].weight[i] * piece.phi[0][i];
    return sum;
  }

  /// PV int w h/(t - x) dt, lo < x < hi, x not on a step.
  Real principal_value(const Real& x) const {
    check_on_cut("rhabel::riemann::jacobi_cauchy_integral::principal_value", x);
    const auto& layout = layouts_[choose_layout(x)];
    Real sum = 0;
    for (const auto& piece : layout) sum += piece_pv(piece, x);
    return sum;
  }

  /// Boundary value from Im z > 0: PV + i pi w h.
  complex_type plemelj_plus(const Real& x) const {
    const Real pi = boost::math::constants::pi<Real>();
    return {principal_value(x), pi * density(x)};
  }
  /// Boundary value from Im z < 0: PV - i pi w h.
  complex_type plemelj_minus(const Real& x) const {
    const Real pi = boost::math::constants::pi<Real>();
    return {principal_value(x), -pi * density(x)};
  }

  /// C(z) = int w h/(t - z) dt for z off [lo, hi].
  complex_type transform(const complex_type& z) const {
    using std::isfinite;
    if (!isfinite(z.real()) || !isfinite(z.imag()))
      quadrature::detail::throw_bad_parameter("rhabel::riemann::jacobi_cauchy_integral::transform", "z", z, "finite, not on [lo, hi]");
    if (z.imag() == 0 && z.real() >= lo_ && z.real() <= hi_)
      quadrature::detail::throw_bad_parameter("rhabel::riemann::jacobi_cauchy_integral::transform", "z", z,
                                              "C \\ [lo, hi] (use principal_value / plemelj_* on the cut)");
    complex_type sum(0);
    for (const auto& piece : layouts_[0]) sum += piece_transform(piece, z);
    return sum;
  }

 private:
  enum class end_kind { touches_lo, touches_hi, interior };

  struct piece {
    Real u, v;
    end_kind kind;
    int source;  // -1: smooth part; j >= 0: step j
    quadrature::quadrature_rule<Real> rule[2];
    std::vector<Real> phi[2];
    std::vector<Real> barycentric;  // for rule[0]
  };

  // phi of a piece at a real point x (its own formula, continued beyond the piece).
  Real phi_at(const piece& pc, const Real& x) const {
    using std::pow;
    const Real value = pc.source < 0 ? h_.smooth(x) : h_.steps[static_cast<std::size_t>(pc.source)].size;
    switch (pc.kind) {
      case end_kind::touches_lo:
        return value * pow(hi_ - x, p_) * pow(x - lo_, Real(q_int_));
      case end_kind::touches_hi:
        return value * pow(x - lo_, q_) * pow(hi_ - x, Real(p_int_));
      default:
        return value * pow(hi_ - x, p_) * pow(x - lo_, q_);
    }
  }

  // Omega(x) = PV int_u^v omega/(t - x) dt for real x (x != u, v unless that end is singular-free).
  Real omega_pv(const piece& pc, const Real& x) const {
    using std::abs;
    using std::log;
    using std::pow;
    const Real length = pc.v - pc.u;
    switch (pc.kind) {
      case end_kind::touches_lo:
        return pow(length, q_frac_) * k_lo_->principal_value((x - pc.u) / length, (pc.v - x) / length);
      case end_kind::touches_hi:
        return -pow(length, p_frac_) * k_hi_->principal_value((pc.v - x) / length, (x - pc.u) / length);
      default:
        return log(abs(pc.v - x)) - log(abs(pc.u - x));
    }
  }

  complex_type omega_complex(const piece& pc, const complex_type& z) const {
    using std::pow;
    const Real length = pc.v - pc.u;
    switch (pc.kind) {
      case end_kind::touches_lo:
        return pow(length, q_frac_) * (*k_lo_)((z - pc.u) / length, (pc.v - z) / length);
      case end_kind::touches_hi:
        return -pow(length, p_frac_) * (*k_hi_)((pc.v - z) / length, (z - pc.u) / length);
      default:
        return detail::log_principal<Real>(pc.v - z) - detail::log_principal<Real>(pc.u - z);
    }
  }

  // Index (0 or 1) of the rule whose nodes keep the divided difference best conditioned at x.
  static int choose_rule(const piece& pc, const Real& x) {
    using std::abs;
    Real worst[2];
    for (int r = 0; r < 2; ++r) {
      worst[r] = 0;
      for (std::size_t i = 0; i < pc.rule[r].size(); ++i) {
        const Real ratio = pc.rule[r].weight[i] / abs(pc.rule[r].x[i] - x);
        if (ratio > worst[r]) worst[r] = ratio;
      }
    }
    return worst[1] < worst[0] ? 1 : 0;
  }

  Real piece_pv(const piece& pc, const Real& x) const {
    using std::abs;
    const Real length = pc.v - pc.u;
    const Real distance = x < pc.u ? pc.u - x : (x > pc.v ? x - pc.v : Real(0));
    if (distance > length / 2) {
      // far: the pole lies outside the Bernstein ellipse of ratio 2 + sqrt 3 = 3.73 of the piece,
      // and the plain Gauss sum converges like 3.73^(-2n) (1e-28 at n = 25). The subtraction
      // below must NOT be used there: it evaluates phi's formula at x, outside the piece, where
      // the end factor of the OTHER end ((x - lo)^q for a piece touching hi) can be huge - x at
      // 1e-7 L from lo made phi(x) ~ 3e3 phi and cost 1e-12 relative in the PV (the density of
      // the Abel route next to its leading edge inherited it, amplified).
      Real sum = 0;
      for (std::size_t i = 0; i < pc.rule[0].size(); ++i)
        sum += pc.rule[0].weight[i] * pc.phi[0][i] / (pc.rule[0].x[i] - x);
      return sum;
    }
    const int r = choose_rule(pc, x);
    const Real phi_x = phi_at(pc, x);
    Real sum = 0;
    for (std::size_t i = 0; i < pc.rule[r].size(); ++i)
      sum += pc.rule[r].weight[i] * (pc.phi[r][i] - phi_x) / (pc.rule[r].x[i] - x);
    return sum + phi_x * omega_pv(pc, x);
  }

  complex_type piece_transform(const piece& pc, const complex_type& z) const {
    const Real length = pc.v - pc.u;
    const Real mid = (pc.u + pc.v) / 2;
    const Real distance = detail::modulus(z - mid) - length / 2;
    const auto& rule = pc.rule[0];
    if (distance > 2 * length) {
      complex_type sum(0);
      for (std::size_t i = 0; i < rule.size(); ++i) sum += rule.weight[i] * pc.phi[0][i] / (rule.x[i] - z);
      return sum;
    }
    // barycentric interpolant of phi at z
    complex_type numerator(0), denominator(0);
    for (std::size_t i = 0; i < rule.size(); ++i) {
      const complex_type d = z - rule.x[i];
      if (d.real() == 0 && d.imag() == 0) {
        numerator = pc.phi[0][i];
        denominator = 1;
        break;
      }
      const complex_type c = pc.barycentric[i] / d;
      numerator += c * pc.phi[0][i];
      denominator += c;
    }
    const complex_type phi_z = numerator / denominator;
    complex_type sum(0);
    for (std::size_t i = 0; i < rule.size(); ++i) sum += rule.weight[i] * (pc.phi[0][i] - phi_z) / (rule.x[i] - z);
    return sum + phi_z * omega_complex(pc, z);
  }

  void check_on_cut(const char* fn, const Real& x) const {
    if (!(x > lo_) || !(x < hi_)) quadrature::detail::throw_bad_parameter(fn, "x", x, "(lo, hi)");
    for (const auto& s : h_.steps)
      if (x == s.position) quadrature::detail::throw_bad_parameter(fn, "x", x, "(lo, hi) minus the steps of h");
  }

  // Standard rules on [-1, 1] for the three kinds of omega, orders n and n+1, cached.
  const quadrature::quadrature_rule<Real>& standard_rule(end_kind kind, int r) {
    const int k = static_cast<int>(kind);
    if (standard_[k][r].size() == 0) {
      const std::size_t n = n_ + static_cast<std::size_t>(r);
      switch (kind) {
        case end_kind::touches_lo:
          standard_[k][r] = quadrature::gauss_jacobi<Real>(n, Real(0), q_frac_);
          break;
        case end_kind::touches_hi:
          standard_[k][r] = quadrature::gauss_jacobi<Real>(n, p_frac_, Real(0));
          break;
        default:
          standard_[k][r] = quadrature::gauss_jacobi<Real>(n, Real(0), Real(0));
      }
    }
    return standard_[k][r];
  }

  void add_piece(std::vector<piece>& layout, Real u, Real v, end_kind kind, int source) {
    using std::pow;
    using std::sqrt;
    piece pc;
    pc.u = u;
    pc.v = v;
    pc.kind = kind;
    pc.source = source;
    const Real half = (v - u) / 2;
    const Real exponent = kind == end_kind::touches_lo ? q_frac_ : (kind == end_kind::touches_hi ? p_frac_ : Real(0));
    const Real scale = pow(half, exponent + 1);
    for (int r = 0; r < 2; ++r) {
      const auto& standard = standard_rule(kind, r);
      auto& rule = pc.rule[r];
      rule = standard;
      for (std::size_t i = 0; i < rule.size(); ++i) {
        rule.hi_minus_x[i] = standard.hi_minus_x[i] * half;
        rule.x_minus_lo[i] = standard.x_minus_lo[i] * half;
        rule.x[i] = rule.x_minus_lo[i] <= rule.hi_minus_x[i] ? u + rule.x_minus_lo[i] : v - rule.hi_minus_x[i];
        rule.weight[i] = standard.weight[i] * scale;
      }
      pc.phi[r].resize(rule.size());
      for (std::size_t i = 0; i < rule.size(); ++i) {
        // evaluate the end factors from the exact distances to the ends of the piece
        const Real t = rule.x[i];
        const Real value = source < 0 ? h_.smooth(t) : h_.steps[static_cast<std::size_t>(source)].size;
        Real factor;
        switch (kind) {
          case end_kind::touches_lo:
            factor = pow(hi_ - t, p_) * pow(rule.x_minus_lo[i], Real(q_int_));
            break;
          case end_kind::touches_hi:
            factor = pow(t - lo_, q_) * pow(rule.hi_minus_x[i], Real(p_int_));
            break;
          default:
            factor = pow(hi_ - t, p_) * pow(t - lo_, q_);
        }
        pc.phi[r][i] = value * factor;
      }
    }
    // barycentric weights of the Gauss nodes: (-1)^i sqrt((1 - x_i^2) W_i) (up to a constant)
    pc.barycentric.resize(pc.rule[0].size());
    for (std::size_t i = 0; i < pc.rule[0].size(); ++i) {
      const Real magnitude = sqrt(pc.rule[0].hi_minus_x[i] * pc.rule[0].x_minus_lo[i] * pc.rule[0].weight[i]);
      pc.barycentric[i] = (i % 2 == 0) ? magnitude : -magnitude;
    }
    layout.push_back(std::move(pc));
  }

  // Pieces of [c, hi] for the step at c: graded away from lo when c is in the lower half.
  void add_step_pieces(std::vector<piece>& layout, Real c, int source, Real split, Real ratio) {
    if (c >= split) {
      add_piece(layout, c, hi_, end_kind::touches_hi, source);
      return;
    }
    Real u = c;
    while (u < split) {
      Real v = lo_ + (u - lo_) * ratio;  // piece length (ratio - 1)(u - lo) <= distance to lo
      if (v > split || split - v < (v - u) / 4) v = split;
      add_piece(layout, u, v, end_kind::interior, source);
      u = v;
    }
    add_piece(layout, split, hi_, end_kind::touches_hi, source);
  }

  void build() {
    const Real length = hi_ - lo_;
    const Real splits[2] = {lo_ + length / 2, lo_ + length * 7 / 16};
    const Real ratios[2] = {Real(2), Real(9) / 4};
    for (int layout = 0; layout < 2; ++layout) {
      auto& pieces = layouts_[layout];
      const Real split = splits[layout];
      if (h_.smooth) {
        add_piece(pieces, lo_, split, end_kind::touches_lo, -1);
        add_piece(pieces, split, hi_, end_kind::touches_hi, -1);
      }
      for (std::size_t j = 0; j < h_.steps.size(); ++j)
        add_step_pieces(pieces, h_.steps[j].position, static_cast<int>(j), split, ratios[layout]);
      // artificial breaks: piece ends that are neither lo, hi nor a step
      for (const auto& pc : pieces)
        for (const Real& e : {pc.u, pc.v}) {
          bool genuine = e == lo_ || e == hi_;
          for (const auto& s : h_.steps) genuine = genuine || e == s.position;
          if (!genuine) artificial_[layout].push_back(e);
        }
    }
  }

  int choose_layout(const Real& x) const {
    using std::abs;
    Real closest[2];
    for (int layout = 0; layout < 2; ++layout) {
      closest[layout] = hi_ - lo_;
      for (const Real& e : artificial_[layout]) closest[layout] = std::min<Real>(closest[layout], abs(x - e));
    }
    return closest[1] > closest[0] ? 1 : 0;
  }

  Real lo_, hi_, p_, q_;
  piecewise_function<Real> h_;
  std::size_t n_ = 0;
  int p_int_ = 0, q_int_ = 0;
  Real p_frac_, q_frac_;
  std::optional<detail::power_cauchy<Real>> k_lo_, k_hi_;  // K(q_frac, .), K(p_frac, .)
  std::vector<piece> layouts_[2];
  std::vector<Real> artificial_[2];
  quadrature::quadrature_rule<Real> standard_[3][2];
};

}  // namespace rhabel::riemann
