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
//  * gauss_log_power_rule: Gauss rule on [0, 1] for the weight (t^-alpha - 1)/alpha (-log t at
//    alpha = 0), the end rule of the step enrichment at x0 for small alpha.
//  * exprel, lgamma_difference_over_alpha.
// The public kernels the other modules use as well (plain_jacobi_values, cached_gauss_jacobi_rule,
// chebyshev_grid, chebyshev_coefficients, panel_integrator) are in rhabel/abel/numerics.hpp.
#pragma once

#include "rhabel/abel/numerics.hpp"
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

/// The connection matrix of chebyshev_to_jacobi: C(i, j) = the Chebyshev coefficient i of
/// P_j^(p,q), i <= j < m (upper triangular), stored by rows: row i holds C(i, i..m-1) from
/// start[i]. Built from x T_k = (T_{k+1} + T_|k-1|)/2 and the three-term recurrence.
template <class Real>
struct jacobi_connection {
  std::vector<Real> entries;
  std::vector<std::size_t> start;
  std::size_t size() const { return entries.size(); }

  jacobi_connection(std::size_t m, const Real& p, const Real& q) : start(m) {
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
    entries.reserve(m * (m + 1) / 2);
    for (std::size_t i = 0; i < m; ++i) {
      start[i] = entries.size();
      for (std::size_t j = i; j < m; ++j) entries.push_back(col[j][i]);
    }
  }
};

/// Coefficients d_m of sum_k a_k T_k in the basis P_m^(p,q), m = 0..size-1 (exact re-expansion
/// of the same polynomial) by back substitution with the connection matrix, which is built once
/// per (size, p, q) (cached_table, up to 2^24 entries in all; a solve re-expands series of a few
/// sizes with the same exponents thousands of times: m = 513, 2.5 ms -> ~0.1 ms a call). Any real
/// p, q with p + q + 1 + m != 0 for the degrees used.
template <class Real>
std::vector<Real> chebyshev_to_jacobi(const std::vector<Real>& a, const Real& p, const Real& q) {
  const std::size_t m = a.size();
  if (m == 0) return {};
  const auto C = cached_table<jacobi_connection<Real>>(std::make_tuple(m, p, q), [&] {
    return jacobi_connection<Real>(m, p, q);
  }, std::size_t(1) << 24);
  std::vector<Real> d(m);
  for (std::size_t i = m; i-- > 0;) {
    Real s = a[i];
    const Real* row = C->entries.data() + C->start[i];  // row[j - i] = C(i, j)
    for (std::size_t j = i + 1; j < m; ++j) s -= row[j - i] * d[j];
    d[i] = s / row[0];
  }
  return d;
}

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
  if (n == 0 || n > 100) throw_bad_parameter("rhabel::abel::gauss_log_power_rule", "n", double(n), "[1, 100]");
  if (!(alpha >= 0 && alpha < 1)) throw_bad_parameter("rhabel::abel::gauss_log_power_rule", "alpha", alpha, "[0, 1)");
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
