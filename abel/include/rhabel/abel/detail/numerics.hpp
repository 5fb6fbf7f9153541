// rhabel/abel/detail/numerics.hpp: private numerical kernels of the abel module.
//
// Gauss-Jacobi rules, Jacobi polynomial values and sums, recurrence coefficients and the
// bad-parameter exception come from the quadrature module (quadrature::gauss_jacobi,
// jacobi_p_all, jacobi_clenshaw, detail::jacobi_recurrence_coefficients). What is here is what
// that module does not provide:
//  * jacobi_sum_any, jacobi_values_any: sum_k c_k P_k^(p,q)(x) and P_0..P_n(x) for ANY real
//    p, q with p + q != -2, -3, ... They forward to quadrature::jacobi_clenshaw / jacobi_p_all
//    for p, q > -1 and run their own plain recurrence only for p <= -1 or q <= -1, which
//    quadrature rejects (the image family of the class nu = -1 has p < -1 when
//    2 alpha + beta > 1; the polynomials exist, only the weight is not integrable).
//  * chebyshev_to_jacobi: coefficients of a Chebyshev series in the basis P_m^(p,q) by the
//    exact connection matrix (built from x T_k = (T_{k+1} + T_|k-1|)/2) and back substitution.
//    Uniform in p, q (works through p = -1), O(M^2).
//  * panel_integrator: int_0^len (len - u)^p u^q f(u, len - u) du for f with singularities at
//    known distances outside [0, len]: geometric panels (ratio 2) toward each near singularity,
//    quadrature::gauss_jacobi on the panels that touch an end, Gauss-Legendre elsewhere. A
//    singularity at distance d from an end sits 3 panel half-widths from the centre of every
//    panel, so each panel converges like (3 + sqrt 8)^(-2 n_panel): 16 nodes give ~ 1e-24.
//  * cached_gauss_jacobi_rule: quadrature::gauss_jacobi from a thread-safe cache keyed by (n, p, q).
//  * gauss_log_power_rule: Gauss rule on [0, 1] for the weight (t^-alpha - 1)/alpha (-log t at
//    alpha = 0), the end rule of the step enrichment at x0 for small alpha.
//  * chebyshev_grid / chebyshev_coefficients, exprel, lgamma_difference_over_alpha.
#pragma once

#include "rhabel/quadrature/gauss_jacobi.hpp"
#include "rhabel/quadrature/jacobi_polynomial.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/digamma.hpp>
#include <boost/math/special_functions/expm1.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace rhabel::abel::detail {

// The quadrature module's checked-input helper and recurrence coefficients
// (P_{k+1} = (A_k x + B_k) P_k - C_k P_{k-1}, DLMF 18.9.1-2; the formula itself has no range
// restriction on p, q).
using rhabel::quadrature::detail::jacobi_recurrence_coefficients;
using rhabel::quadrature::detail::throw_bad_parameter;

/// P_0(x), ..., P_n(x) of P^(p,q) by the plain forward three-term recurrence, for ANY real p, q
/// with p + q != -2, -3, ... (no difference forms near the ends, no exponent check).
template <class Real>
std::vector<Real> plain_jacobi_values(std::size_t n, const Real& p, const Real& q, const Real& x) {
  std::vector<Real> v(n + 1);
  v[0] = 1;
  if (n >= 1) v[1] = (p + q + 2) / 2 * x + (p - q) / 2;
  for (std::size_t k = 1; k < n; ++k) {
    const auto r = jacobi_recurrence_coefficients(k, p, q);
    v[k + 1] = (r.A * x + r.B) * v[k] - r.C * v[k - 1];
  }
  return v;
}

/// P_0(x), ..., P_n(x) of P^(p,q) for ANY real p, q with p + q != -2, -3, ... For p, q > -1
/// this is quadrature::jacobi_p_all; the plain recurrence runs only for p <= -1 or q <= -1
/// (rejected by quadrature). The abel headers themselves call jacobi_p_all directly;
/// this entry point remains because studies/abel_convergence.cpp uses it.
template <class Real>
std::vector<Real> jacobi_values_any(std::size_t n, const Real& p, const Real& q, const Real& x) {
  if (p > -1 && q > -1) return rhabel::quadrature::jacobi_p_all(n, p, q, x);
  return plain_jacobi_values(n, p, q, x);
}

/// Clenshaw sum_k c_k P_k^(p,q)(x) for ANY real p, q with p + q != -2, -3, ... For p, q > -1
/// this is quadrature::jacobi_clenshaw (difference-form recurrence near the ends). The plain
/// Clenshaw recurrence below is kept only for p <= -1 or q <= -1, which the quadrature module
/// rejects (its weight is not integrable there): the image family (gam - 1, del - 1) of the
/// class nu = -1 has p = gam - 1 < -1 when 2 alpha + beta > 1; the polynomials still exist.
template <class Real>
Real jacobi_sum_any(const std::vector<Real>& c, const Real& p, const Real& q, const Real& x) {
  if (p > -1 && q > -1) return rhabel::quadrature::jacobi_clenshaw(c, p, q, x);
  Real b1 = 0, b2 = 0;
  for (std::size_t k = c.size(); k-- > 0;) {
    const auto r = jacobi_recurrence_coefficients(k, p, q);
    const Real C_next =
        c.size() > k + 1 ? jacobi_recurrence_coefficients(k + 1, p, q).C : Real(0);
    const Real b0 = c[k] + (r.A * x + r.B) * b1 - C_next * b2;
    b2 = b1;
    b1 = b0;
  }
  return b1;
}

/// quadrature::gauss_jacobi(n, p, q) from a process-wide cache keyed by (n, p, q) (exact keys: the
/// rule depends on the exact exponents). Building a rule costs O(n^2)-O(n^3) operations
/// (quadrature::gauss_jacobi); the abel quadratures (panel_integrator, jacobi_density::integrate,
/// abel_operator::apply outside [lo, hi], the enrichment of step_enrichment.hpp) need the same few
/// rules thousands of times per solve. Thread-safe (one mutex; the rules are immutable and
/// shared). The cache is emptied when it holds more than 512 rules, so memory stays bounded when
/// the exponents sweep a continuum (a rule of n nodes holds 4n numbers).
template <class Real>
std::shared_ptr<const rhabel::quadrature::quadrature_rule<Real>> cached_gauss_jacobi_rule(std::size_t n, const Real& p,
                                                                                         const Real& q) {
  using rule_type = rhabel::quadrature::quadrature_rule<Real>;
  static std::mutex mutex;
  static std::map<std::tuple<std::size_t, Real, Real>, std::shared_ptr<const rule_type>> cache;
  const auto key = std::make_tuple(n, p, q);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
  }
  // Built outside the lock (two threads may build the same rule once each; both are identical).
  auto rule = std::make_shared<const rule_type>(rhabel::quadrature::gauss_jacobi<Real>(n, p, q));
  const std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() >= 512) cache.clear();
  return cache.emplace(key, std::move(rule)).first->second;
}

/// Chebyshev points of the first kind x_j = cos(pi (j + 1/2)/m), j = 0..m-1, with 1 -+ x_j
/// computed as 2 sin^2 / 2 cos^2 of the half angle (no cancellation near the ends).
template <class Real>
struct chebyshev_grid {
  std::vector<Real> x, one_minus_x, one_plus_x;
  explicit chebyshev_grid(std::size_t m) : x(m), one_minus_x(m), one_plus_x(m) {
    using std::cos;
    using std::sin;
    const Real pi = boost::math::constants::pi<Real>();
    for (std::size_t j = 0; j < m; ++j) {
      const Real theta = pi * (Real(j) + Real(0.5)) / Real(m);
      x[j] = cos(theta);
      const Real s = sin(theta / 2), c = cos(theta / 2);
      one_minus_x[j] = 2 * s * s;
      one_plus_x[j] = 2 * c * c;
    }
  }
};

/// Chebyshev coefficients a_0..a_{m-1} of the interpolant of values f_j at chebyshev_grid(m).
/// T_k(x_j) = cos(pi k (2j+1)/(2m)) is taken from a table of cos(pi r/(2m)) by reducing
/// k (2j+1) modulo 4m: every entry is a correctly rounded cosine (no recurrence drift). The index
/// advances by 2k modulo 4m from j to j + 1 (a subtraction, not an integer division per term:
/// the same entries, ~2x faster at m = 195).
template <class Real>
std::vector<Real> chebyshev_coefficients(const std::vector<Real>& f) {
  using std::cos;
  const std::size_t m = f.size();
  const Real pi = boost::math::constants::pi<Real>();
  std::vector<Real> table(4 * m);
  for (std::size_t r = 0; r < 4 * m; ++r) table[r] = cos(pi * Real(r) / Real(2 * m));
  std::vector<Real> a(m, Real(0));
  const std::size_t period = 4 * m;
  for (std::size_t k = 0; k < m; ++k) {
    Real sum = 0;
    const std::size_t step = (2 * k) % period;
    std::size_t index = k % period;  // k (2j + 1) mod 4m at j = 0
    for (std::size_t j = 0; j < m; ++j) {
      sum += f[j] * table[index];
      index += step;
      if (index >= period) index -= period;
    }
    a[k] = sum * (k == 0 ? Real(1) : Real(2)) / Real(m);
  }
  return a;
}

/// Coefficients d_m of sum_k a_k T_k in the basis P_m^(p,q), m = 0..size-1 (exact re-expansion
/// of the same polynomial). Any real p, q with p + q + 1 + m != 0 for the degrees used.
template <class Real>
std::vector<Real> chebyshev_to_jacobi(const std::vector<Real>& a, const Real& p, const Real& q) {
  const std::size_t m = a.size();
  if (m == 0) return {};
  // columns[j] = Chebyshev coefficients of P_j^(p,q), length j + 1.
  std::vector<std::vector<Real>> col(m);
  col[0] = {Real(1)};
  auto times_x = [](const std::vector<Real>& c) {
    std::vector<Real> r(c.size() + 1, Real(0));
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (k == 0) {
        r[1] += c[0];
      } else {
        r[k + 1] += c[k] / 2;
        r[k - 1] += c[k] / 2;
      }
    }
    return r;
  };
  for (std::size_t j = 0; j + 1 < m; ++j) {
    const auto r = jacobi_recurrence_coefficients(j, p, q);
    std::vector<Real> next = times_x(col[j]);
    for (auto& v : next) v *= r.A;
    for (std::size_t k = 0; k <= j; ++k) next[k] += r.B * col[j][k];
    if (j >= 1)
      for (std::size_t k = 0; k < j; ++k) next[k] -= r.C * col[j - 1][k];
    col[j + 1] = std::move(next);
  }
  std::vector<Real> d(m);
  for (std::size_t i = m; i-- > 0;) {
    Real s = a[i];
    for (std::size_t j = i + 1; j < m; ++j) s -= col[j][i] * d[j];
    d[i] = s / col[i][i];
  }
  return d;
}

/// Composite integrator for int_0^len (len - u)^p u^q f(u, len - u) du where f may be
/// singular at u = -d_left and u = len + d_right (pass +inf when absent).
template <class Real>
class panel_integrator {
 public:
  /// The four rules come from cached_gauss_jacobi_rule: constructing an integrator is cheap
  /// after the first use of (nodes, p, q).
  panel_integrator(const Real& p, const Real& q, std::size_t nodes = 16)
      : p_(p), q_(q),
        legendre_(cached_gauss_jacobi_rule<Real>(nodes, Real(0), Real(0))),
        left_(cached_gauss_jacobi_rule<Real>(nodes, Real(0), q)),
        right_(cached_gauss_jacobi_rule<Real>(nodes, p, Real(0))),
        both_(cached_gauss_jacobi_rule<Real>(nodes, p, q)) {}

  template <class F>
  Real integrate(const Real& len, const Real& d_left, const Real& d_right, F&& f) const {
    Real sum = 0;
    for_each_node(len, d_left, d_right, [&](const Real& u, const Real& v, const Real& weight) { sum += weight * f(u, v); });
    return sum;
  }

  /// Calls visit(u, len - u, weight) for every node of the composite rule (weight includes
  /// (len-u)^p u^q and the panel scaling).
  template <class Visit>
  void for_each_node(const Real& len, const Real& d_left, const Real& d_right, Visit&& visit) const {
    visit_nodes<false>(len, d_left, d_right, visit);
  }

  /// for_each_node with the powers that the Gauss-Jacobi weights do not carry left to the
  /// visitor: visit(u, len - u, weight, q_here, p_here), where weight has the rule weight and the
  /// panel scaling, and the node's full weight is weight u^q_here (len - u)^p_here (q_here = 0 on
  /// the panel touching 0, where u^q is the rule's weight, else q; p_here likewise). For visitors
  /// that fold these powers into a detail::power_product of their own: one log each and a shared
  /// exp instead of a pow each (the quadrature of A[phi] in solve_step, ~4 powers a node).
  template <class Visit>
  void for_each_node_deferred(const Real& len, const Real& d_left, const Real& d_right, Visit&& visit) const {
    visit_nodes<true>(len, d_left, d_right, visit);
  }

 private:
  template <bool deferred, class Visit>
  void visit_nodes(const Real& len, const Real& d_left, const Real& d_right, Visit& visit) const {
    using std::pow;
    // Breakpoints as pairs (distance from 0, distance from len): 0, then d, 3d, 7d, ... (panel
    // widths doubling) up to the middle, graded toward a singularity at distance d from that end.
    const Real half = len / 2;
    const auto graded_breaks = [&half](const Real& d) {
      std::vector<Real> breaks{Real(0)};
      if (d > 0 && d < half) {
        Real w = d;
        for (Real pos = d; pos < half; w *= 2, pos += w) breaks.push_back(pos);
      }
      return breaks;
    };
    const std::vector<Real> from_left = graded_breaks(d_left);
    const std::vector<Real> from_right = graded_breaks(d_right);
    // Assemble panels [u_k, u_{k+1}] with both distances.
    struct point {
      Real left, right;
    };
    std::vector<point> pts;
    for (const auto& v : from_left) pts.push_back({v, len - v});
    for (std::size_t k = from_right.size(); k-- > 0;) pts.push_back({len - from_right[k], from_right[k]});
    for (std::size_t k = 0; k + 1 < pts.size(); ++k) {
      const point a = pts[k], b = pts[k + 1];
      // The width from the distances to the nearer end: the breaks graded toward len are exact as
      // distances from len and rounded as distances from 0, so b.left - a.left would be off by
      // ~eps len there, ~eps len/d relative next to a singularity at distance d from len (the
      // quadrature of A g at 1e-8 from an unbounded end was off by 1e-6 relative at alpha = 0).
      const Real width = b.right < a.left ? a.right - b.right : b.left - a.left;
      if (!(width > 0)) continue;
      const bool touches_left = k == 0, touches_right = k + 2 == pts.size();
      const auto& rule = *(touches_left ? (touches_right ? both_ : left_) : (touches_right ? right_ : legendre_));
      const Real h = width / 2;
      const Real scale = pow(h, (touches_left ? q_ : Real(0)) + (touches_right ? p_ : Real(0)) + 1);
      for (std::size_t i = 0; i < rule.size(); ++i) {
        const Real from_a = rule.x_minus_lo[i] * h, to_b = rule.hi_minus_x[i] * h;
        const Real u = a.left + from_a;              // distance from 0
        const Real v = b.right + to_b;               // distance from len
        Real weight = rule.weight[i];
        if constexpr (deferred) {
          visit(u, v, scale * weight, touches_left ? Real(0) : q_, touches_right ? Real(0) : p_);
        } else {
          if (!touches_left && q_ != 0) weight *= pow(u, q_);  // (the exponent is often exactly 0)
          if (!touches_right && p_ != 0) weight *= pow(v, p_);
          visit(u, v, scale * weight);
        }
      }
    }
  }

  Real p_, q_;
  std::shared_ptr<const rhabel::quadrature::quadrature_rule<Real>> legendre_, left_, right_, both_;
};

/// n-point Gauss rule on [0, 1] for the weight W(t) = (t^-alpha - 1)/alpha, 0 <= alpha < 1
/// (W = -log t at alpha = 0; W > 0 on (0, 1)): int_0^1 W(t) f(t) dt ~ sum_i weight[i] f(x[i]),
/// exact for polynomials of degree < 2n. It is the end rule of the normalized step enrichment at
/// x0, where E = (|u|^-alpha - 1)/alpha is log-type and no Gauss-Jacobi weight
/// (detail::enrichment_piece).
/// Construction (Gautschi, "Orthogonal Polynomials: Computation and Approximation", 2004,
/// sections 2.1.7 and 3.1.1): the recurrence coefficients of the monic orthogonal polynomials come
/// from the modified Chebyshev algorithm with the shifted monic Legendre polynomials
/// pi_l = P_l(2t - 1)/binomial(2l, l) (a_l = 1/2, b_l = l^2/(4(4l^2 - 1))), whose modified moments
/// are closed forms, no cancellation, uniform to alpha = 0 (from int_0^1 t^c P_l(2t - 1) dt =
/// c (c-1) ... (c-l+1)/((c+1) ... (c+l+1))):
///     int W P_0(2t-1) = 1/(1 - alpha),
///     int W P_l(2t-1) = (-1)^l prod_{j=1}^{l-1} (j + alpha) / prod_{j=1}^{l+1} (j - alpha),  l >= 1.
/// For this logarithmic-type weight the map from these moments to the recurrence is well
/// conditioned (Gautschi's example 2.30; the monomial moments are not). Nodes: Golub-Welsch
/// eigenvalues in double as starting values, then Newton in Real on the recurrence; weights by the
/// Christoffel numbers 1/sum_k p_k(x_i)^2/||p_k||^2 (||p_k||^2 = beta_0 ... beta_k). Tests: the
/// exact monomial moments 1/((k+1)(k+1-alpha)) (an independent formula), in double and at 50
/// digits. Computed once per (Real, n, alpha) and shared (function-local static map behind a
/// mutex; one entry per alpha a program uses).
template <class Real>
struct log_power_rule {
  std::vector<Real> x, weight;
};

template <class Real>
const log_power_rule<Real>& gauss_log_power_rule(std::size_t n, const Real& alpha) {
  using std::abs;
  if (n == 0 || n > 100) throw_bad_parameter("gauss_log_power_rule", "n", double(n), "[1, 100]");
  if (!(alpha >= 0 && alpha < 1)) throw_bad_parameter("gauss_log_power_rule", "alpha", alpha, "[0, 1)");
  static std::mutex mutex;
  static std::map<std::pair<std::size_t, Real>, std::shared_ptr<const log_power_rule<Real>>> cache;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{n, alpha}];
  if (slot) return *slot;
  // Working precision: long double for double (the recurrence from the moments loses ~30 eps of
  // the working precision: measured 20-90 double eps in nodes and weights when run in double),
  // Real otherwise.
  using Work = std::conditional_t<std::is_floating_point_v<Real>, long double, Real>;
  const Work work_alpha = static_cast<Work>(alpha);
  // Modified moments of the monic shifted Legendre polynomials, l = 0 .. 2n - 1.
  const std::size_t m = 2 * n;
  std::vector<Work> moment(m);
  {
    Work legendre_moment = 1 / (1 - work_alpha);  // int W P_l(2t - 1)
    Work numerator = 1, denominator = (1 - work_alpha);
    Work binomial = 1;  // binomial(2l, l)
    for (std::size_t l = 0; l < m; ++l) {
      if (l > 0) {
        // numerator = prod_{j=1}^{l-1} (j + alpha), denominator = prod_{j=1}^{l+1} (j - alpha).
        if (l > 1) numerator *= Work(l - 1) + work_alpha;
        denominator *= Work(l + 1) - work_alpha;
        legendre_moment = (l % 2 == 0 ? 1 : -1) * numerator / denominator;
        binomial = binomial * Work(2 * l) * Work(2 * l - 1) / (Work(l) * Work(l));
      }
      moment[l] = legendre_moment / binomial;
    }
  }
  auto b_of = [](std::size_t l) { return l == 0 ? Work(0) : Work(l * l) / (4 * (4 * Work(l * l) - 1)); };
  const Work a_legendre = Work(1) / 2;
  std::vector<Work> rec_a(n), rec_b(n);
  std::vector<Work> before(m, Work(0)), current = moment, next(m, Work(0));  // sigma_{k-2}, sigma_{k-1}, sigma_k
  rec_a[0] = a_legendre + moment[1] / moment[0];
  rec_b[0] = moment[0];
  for (std::size_t k = 1; k < n; ++k) {
    for (std::size_t l = k; l + k < m; ++l)
      next[l] = current[l + 1] - (rec_a[k - 1] - a_legendre) * current[l] - rec_b[k - 1] * before[l] + b_of(l) * current[l - 1];
    rec_a[k] = a_legendre + next[k + 1] / next[k] - current[k] / current[k - 1];
    rec_b[k] = next[k] / current[k - 1];
    before.swap(current);
    current.swap(next);
  }
  Eigen::VectorXd diagonal(static_cast<Eigen::Index>(n));
  Eigen::VectorXd off(static_cast<Eigen::Index>(n > 1 ? n - 1 : 0));
  for (std::size_t k = 0; k < n; ++k) diagonal[static_cast<Eigen::Index>(k)] = static_cast<double>(rec_a[k]);
  for (std::size_t k = 1; k < n; ++k) off[static_cast<Eigen::Index>(k - 1)] = std::sqrt(static_cast<double>(rec_b[k]));
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
  eigen.computeFromTridiagonal(diagonal, off, Eigen::EigenvaluesOnly);
  // p_n(t), p_n'(t) and sum_k p_k(t)^2/||p_k||^2 by the monic recurrence.
  auto evaluate = [&](const Work& t, Work& p, Work& dp, Work& christoffel_sum) {
    Work p_prev = 0, p_cur = 1, d_prev = 0, d_cur = 0, norm = rec_b[0];
    christoffel_sum = 1 / norm;
    for (std::size_t k = 0; k < n; ++k) {
      const Work b = k == 0 ? Work(0) : rec_b[k];
      const Work p_next = (t - rec_a[k]) * p_cur - b * p_prev;
      const Work d_next = p_cur + (t - rec_a[k]) * d_cur - b * d_prev;
      p_prev = p_cur, p_cur = p_next, d_prev = d_cur, d_cur = d_next;
      if (k + 1 < n) {
        norm *= rec_b[k + 1];
        christoffel_sum += p_cur * p_cur / norm;
      }
    }
    p = p_cur, dp = d_cur;
  };
  auto rule = std::make_shared<log_power_rule<Real>>();
  const Work tiny = std::numeric_limits<Work>::epsilon();
  for (std::size_t i = 0; i < n; ++i) {
    Work t = Work(eigen.eigenvalues()[static_cast<Eigen::Index>(i)]);
    Work p = 0, dp = 0, christoffel_sum = 0;
    for (int it = 0; it < 20; ++it) {
      evaluate(t, p, dp, christoffel_sum);
      const Work step = p / dp;
      t -= step;
      if (abs(step) <= tiny * abs(t)) break;
    }
    evaluate(t, p, dp, christoffel_sum);
    rule->x.push_back(static_cast<Real>(t));
    rule->weight.push_back(static_cast<Real>(1 / christoffel_sum));
  }
  slot = rule;
  return *slot;
}

/// prod_i d_i^(e_i) over positive distances d_i, accumulated as exp(sum_i e_i log d_i): one exp and
/// one log per factor instead of one pow (glibc's correctly rounded pow costs about twice log + exp;
/// these products are the inner loops of the step enrichment's quadratures: 30-55% of a wedge solve
/// was pow). Factors with e_i = 0 are skipped (0^0 = 1, never 0 * log 0). Relative error <=
/// (sum_i |e_i log d_i| + 2 n) eps for products between sqrt(min) (~1.5e-154 in double) and
/// its reciprocal: ~10 eps for distances above 1e-4. e_i = -1 (the kernel at alpha = 0) is a
/// division while the running factor stays in that range, else it joins the logarithms.
template <class Real>
class power_product {
 public:
  power_product& times(const Real& d, const Real& e) {
    using std::log;
    using std::sqrt;
    // Range in which a division keeps factor_ far from overflow and underflow.
    static const Real small = sqrt((std::numeric_limits<Real>::min)()), large = 1 / small;
    if (e == -1 && d > small && d < large) {  // the alpha = 0 kernel: a division, exact to rounding
      factor_ /= d;
      if (!(factor_ > small && factor_ < large)) exponent_ += log(factor_), factor_ = 1;
    } else if (e != 0) {
      exponent_ += e * log(d);
    }
    return *this;
  }
  Real value() const {
    using std::exp;
    return exponent_ == 0 ? factor_ : factor_ * exp(exponent_);
  }

 private:
  Real exponent_ = 0, factor_ = 1;
};

/// expm1(x)/x, = 1 at x = 0. For |x| below (720 eps)^(1/5) the Taylor series 1 + x/2 + x^2/6 +
/// x^3/24 + x^4/120 (remainder < |x|^5/720 < eps): the normalized step enrichment calls this at
/// every quadrature node with x = -alpha log|u|, tiny for alpha ~ 1e-8 (expm1 was ~15% of that
/// path's cost).
template <class Real>
Real exprel(const Real& x) {
  using std::abs;
  using std::pow;
  if (x == 0) return Real(1);
  static const Real series_limit = pow(720 * std::numeric_limits<Real>::epsilon(), Real(1) / 5);
  if (abs(x) < series_limit) return 1 + x * (Real(1) / 2 + x * (Real(1) / 6 + x * (Real(1) / 24 + x / 120)));
  return boost::math::expm1(x) / x;
}

/// E(c) = [lgamma(c + 1 + alpha) - lgamma(c + 1)] / alpha, uniform as alpha -> 0 (= psi(c + 1)).
/// For alpha <= c + 1: (1/2) int_{-1}^{1} psi(c + 1 + alpha (1 + u)/2) du by 24-point
/// Gauss-Legendre (the poles of psi are >= 3 half-lengths away: error < 1e-30).
template <class Real>
Real lgamma_difference_over_alpha(const Real& c, const Real& alpha) {
  using boost::math::digamma;
  using boost::math::lgamma;
  if (alpha > c + 1) return (lgamma(c + 1 + alpha) - lgamma(c + 1)) / alpha;
  static thread_local std::vector<Real> nodes, weights;
  if (nodes.empty()) {
    const auto rule = rhabel::quadrature::gauss_jacobi<Real>(24, Real(0), Real(0));
    nodes = rule.x;
    weights = rule.weight;
  }
  Real sum = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) sum += weights[i] * digamma(c + 1 + alpha * (1 + nodes[i]) / 2);
  return sum / 2;
}

}  // namespace rhabel::abel::detail
