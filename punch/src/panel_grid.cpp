// punch/src/panel_grid.cpp: the boundary-element grid of a sampled profile and its active-set
// solve (panel_grid.hpp).
#include "panel_grid.hpp"

#include "active_solve.hpp"

#include <gsl/gsl_sf_zeta.h>

#include <algorithm>
#include <cmath>

namespace rhabel::punch::detail {
namespace {

// Steps of `settle` a grid whose solves may be loose (active_solve.hpp, moving_tolerance).
constexpr std::size_t loose_steps = 8;
// A panel penetrates when w - z < D by more than this fraction of the profile's span (round-off).
constexpr double penetration_floor = 1e-9;
// Periodic kernel: images |j| <= near_images in closed form; the Taylor series of the rest to
// `taylor_terms` terms, whose ratio is at most 1/(near_images + 1) = 0.2: 0.2^26 < 2e-18.
constexpr int near_images = 4;
constexpr int taylor_terms = 26;

/// int_0^d E(u) du, E(u) = (1 - u^alpha)/alpha (-> -log u at alpha = 0):
/// d (1 - (d^alpha - 1)/alpha)/(1 + alpha), with (d^alpha - 1)/alpha = expm1(alpha log d)/alpha.
double integral_e(double d, double alpha) {
  if (d <= 0) return 0;
  const double l = std::log(d);
  return d * (1 - (alpha == 0 ? l : std::expm1(alpha * l) / alpha)) / (1 + alpha);
}

/// int over the panel [x + u0, x + u1] of Psi(t, x) dt: ahead of x (t > x) Psi = E(t - x), behind
/// kappa E(x - t) + (1 - kappa)/alpha (docs/theory.md section 7).
double panel_integral(double u0, double u1, double alpha, double kappa, double c1) {
  auto behind = [&](double d) { return kappa * integral_e(d, alpha) + c1 * d; };
  if (u0 >= 0) return integral_e(u1, alpha) - integral_e(u0, alpha);
  if (u1 <= 0) return behind(-u0) - behind(-u1);
  return integral_e(u1, alpha) + behind(-u0);
}

// Below this alpha, alpha zeta(1 - alpha) is its series -1 + gamma alpha (the next term is
// O(alpha^2) < 1e-16) and GSL's zeta is not called next to its pole at 1.
constexpr double series_alpha = 1e-8;
constexpr double euler_gamma = 0.57721566490153286061;

}  // namespace

periodic_panel_kernel::periodic_panel_kernel(double alpha, double kappa, double c1)
    : alpha_(alpha), kappa_(kappa), c1_(c1), coef_(taylor_terms + 1, 0.0) {
  // GSL's zeta functions are called only where they cannot fail (s = 1 - alpha < 1 - 1e-8,
  // s = k - alpha > 1): its global error handler is left alone (threads share it).
  const double a0 = near_images + 1;
  // The far images j >= a0 (ahead: Psi = -(j + v)^alpha/alpha + 1/alpha) and j <= -a0 (behind:
  // -kappa (|j| - v)^alpha/alpha + 1/alpha), v = t - sigma in (-1, 1), expanded in v:
  //   sum_j [...] = const - sum_k bc_k (1 + kappa (-1)^k) zeta(k - alpha, a0) v^k,
  //   bc_k = binom(alpha, k)/alpha = prod_{i=1}^{k-1} (alpha - i) / k!   (finite at alpha = 0).
  // k = 1: the sum diverges; its continuation is (1 - kappa) zeta(1 - alpha, a0)
  // = c1 [alpha zeta(1 - alpha, a0)], alpha zeta(1 - alpha, a0) = alpha zeta(1 - alpha) -
  // alpha sum_{i < a0} i^(alpha - 1) (-> -1 as alpha -> 0).
  double alpha_zeta = alpha < series_alpha ? -1 + euler_gamma * alpha : alpha * gsl_sf_zeta(1 - alpha);
  if (alpha > alpha_zero) {
    for (int i = 1; i < near_images + 1; ++i) alpha_zeta -= alpha * std::pow(static_cast<double>(i), alpha - 1);
  }
  coef_[1] = -c1 * alpha_zeta;
  double bc = 1;
  for (int k = 2; k <= taylor_terms; ++k) {
    bc *= (alpha - (k - 1)) / k;
    const double zeta = gsl_sf_hzeta(k - alpha, a0);
    coef_[static_cast<std::size_t>(k)] = -bc * (1 + kappa * (k % 2 == 0 ? 1.0 : -1.0)) * zeta;
  }
}

double periodic_panel_kernel::operator()(double h, double sigma) const {
  sigma -= std::floor(sigma);
  double s = 0;
  for (int j = -near_images; j <= near_images; ++j) s += panel_integral(j - sigma, j + h - sigma, alpha_, kappa_, c1_);
  // int_0^h (t - sigma)^k dt = ((h - sigma)^(k+1) - (-sigma)^(k+1)) / (k + 1)
  double p1 = h - sigma, p0 = -sigma, tail = 0;
  for (int k = 1; k <= taylor_terms; ++k) {
    p1 *= h - sigma;
    p0 *= -sigma;
    tail += coef_[static_cast<std::size_t>(k)] * (p1 - p0) / (k + 1);
  }
  return s + tail;
}

std::pair<double, double> periodic_panel_kernel::images(double v) const {
  // Psi(u) = E(u) ahead (u > 0), kappa E(-u) + c1 behind; E(u) = (1 - u^alpha)/alpha (-log u at
  // alpha = 0), E'(u) = -u^(alpha - 1).
  auto e = [&](double u) { return alpha_ == 0 ? -std::log(u) : -std::expm1(alpha_ * std::log(u)) / alpha_; };
  double value = 0, slope = 0;
  for (int j = -near_images; j <= near_images; ++j) {
    if (j == 0) continue;
    const double u = v + j;
    if (u > 0) {
      value += e(u);
      slope -= std::pow(u, alpha_ - 1);
    } else {
      value += kappa_ * e(-u) + c1_;
      slope += kappa_ * std::pow(-u, alpha_ - 1);
    }
  }
  // sum_k coef_k v^k by Horner (coef_0 = 0).
  double p = 0, dp = 0;
  for (int k = taylor_terms; k >= 1; --k) {
    dp = dp * v + p;
    p = p * v + coef_[static_cast<std::size_t>(k)];
  }
  return {value + p * v, slope + dp * v + p};
}

std::vector<double> finite_panel_kernel(std::size_t n, double length, const context& cx) {
  const double h = 1.0 / static_cast<double>(n), theta = collocation_theta;
  const double scale = cx.gamma_factor * std::pow(length, cx.alpha);
  const double c1 = cx.par.one_minus_kappa_over_alpha();
  std::vector<double> kernel(2 * n - 1);
  const auto last = static_cast<std::ptrdiff_t>(n) - 1;
  for (std::ptrdiff_t m = -last; m <= last; ++m) {  // m = j - i: panel [m h, (m + 1) h] from theta h
    const double k = static_cast<double>(m);
    kernel[static_cast<std::size_t>(m + last)] = scale * panel_integral((k - theta) * h, (k + 1 - theta) * h, cx.alpha, cx.kappa, c1);
  }
  return kernel;
}

panel_grid make_panel_grid(const profile_curve& curve, std::size_t n, const context& cx, double top) {
  panel_grid gr;
  gr.n = n;
  gr.h = 1.0 / static_cast<double>(n);
  gr.periodic = curve.period() > 0;
  gr.lo = curve.lo();
  gr.length = gr.periodic ? curve.period() : curve.hi() - curve.lo();
  const double theta = collocation_theta;
  if (gr.periodic) {
    // Circulant: A(i, j) = c((i - j) mod n), c(m) the periodic kernel at sigma = (m + theta) h.
    const double h = gr.h, scale = cx.gamma_factor * std::pow(gr.length, cx.alpha);
    const periodic_panel_kernel W(cx.alpha, cx.kappa, cx.par.one_minus_kappa_over_alpha());
    gr.kernel.resize(2 * n - 1);
    const auto last = static_cast<std::ptrdiff_t>(n) - 1;
    std::vector<double> c(n);
    for (std::size_t m = 0; m < n; ++m) {
      if (m % 65536 == 0) cx.check_time();  // ~0.1 s of kernel values between checks
      c[m] = scale * W(h, (static_cast<double>(m) + theta) * h);
    }
    for (std::ptrdiff_t m = -last; m <= last; ++m)  // m = j - i
      gr.kernel[static_cast<std::size_t>(m + last)] = c[static_cast<std::size_t>((-m + static_cast<std::ptrdiff_t>(n)) % static_cast<std::ptrdiff_t>(n))];
  } else {
    gr.kernel = finite_panel_kernel(n, gr.length, cx);
  }
  gr.product = std::make_unique<toeplitz_product>(gr.kernel, n, gr.periodic);
  gr.z.resize(n);
  gr.rise.resize(n);
  double at_edge = curve.value(gr.edge(0));  // z at the panel's lower edge, carried to the next
  for (std::size_t i = 0; i < n; ++i) {
    gr.z[i] = curve.value(gr.lo + gr.length * (static_cast<double>(i) + theta) * gr.h) - top;
    const double next = curve.value(gr.edge(i + 1));
    gr.rise[i] = next - at_edge;
    at_edge = next;
  }
  return gr;
}

std::vector<std::pair<Eigen::Index, Eigen::Index>> runs_of(const std::vector<std::size_t>& idx) {
  std::vector<std::pair<Eigen::Index, Eigen::Index>> out;
  for (std::size_t c = 0; c < idx.size(); ++c) {
    const auto at = static_cast<Eigen::Index>(c);
    if (c == 0 || idx[c] != idx[c - 1] + 1) out.emplace_back(at, at);
    ++out.back().second;
  }
  return out;
}

bool settle(panel_grid& gr, double load, double span, std::vector<char>& active, Eigen::VectorXd& g,
            std::vector<std::size_t>& idx, double& D, const context& cx, std::size_t& steps, std::size_t max_steps,
            warm_start& ws) {
  // Until the set stops changing each step's solve only moves towards it (moving_tolerance; at
  // most loose_steps such steps a grid); the set is accepted only after a deciding solve
  // (deciding_tolerance) that changes nothing.
  bool decide = false;
  for (std::size_t step = 0; step < max_steps; ++step) {
    cx.check_time();
    ++steps;
    idx.clear();
    for (std::size_t i = 0; i < gr.n; ++i)
      if (active[i]) idx.push_back(i);
    decide = decide || step >= loose_steps;
    if (idx.empty() || !solve_active(gr, idx, load, span, g, D, cx, ws, decide ? deciding_tolerance : moving_tolerance))
      return false;
    bool changed = false;
    for (std::size_t c = 0; c < idx.size(); ++c)
      if (g[static_cast<Eigen::Index>(c)] < 0) active[idx[c]] = 0, changed = true;
    if (!changed) {
      const Eigen::VectorXd w = gr.product->apply(idx, g);  // at every panel
      for (std::size_t i = 0; i < gr.n; ++i) {
        if (active[i]) continue;
        if (w[static_cast<Eigen::Index>(i)] - D - gr.z[i] < -penetration_floor * span) active[i] = 1, changed = true;
      }
    }
    if (!changed && decide) return true;
    decide = !changed;
  }
  return false;
}

std::vector<char> refine_active(const std::vector<char>& active, std::size_t next) {
  const std::size_t n = active.size();
  std::vector<char> finer(next, 0);
  const double ratio = static_cast<double>(n) / static_cast<double>(next);
  for (std::size_t i = 0; i < next; ++i)
    finer[i] = active[std::min(n - 1, static_cast<std::size_t>((static_cast<double>(i) + 0.5) * ratio))];
  return finer;
}

}  // namespace rhabel::punch::detail
