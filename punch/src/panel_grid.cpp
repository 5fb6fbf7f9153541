// punch/src/panel_grid.cpp: the boundary-element grid of a sampled profile and its active-set
// solve (panel_grid.hpp).
#include "panel_grid.hpp"

#include "rhabel/abel/detail/block_gmres.hpp"

#include <gsl/gsl_sf_zeta.h>

#include <algorithm>
#include <cmath>

namespace rhabel::punch::detail {
namespace {

// Active panels up to which the linear solve is one LU (above: block GMRES; at 600 an LU costs
// 1.4e8 flops against ~1e6 per GMRES product).
constexpr Eigen::Index dense_limit = 600;
// GMRES: a relative residual far below the discretisation's error, within max_products products.
constexpr double gmres_tolerance = 1e-11;
constexpr std::size_t max_products = 600;
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

panel_grid make_panel_grid(const profile_curve& curve, std::size_t n, const context& cx, double top) {
  panel_grid gr;
  gr.n = n;
  gr.h = 1.0 / static_cast<double>(n);
  gr.periodic = curve.period() > 0;
  gr.lo = curve.lo();
  gr.length = gr.periodic ? curve.period() : curve.hi() - curve.lo();
  const double h = gr.h, alpha = cx.alpha, theta = collocation_theta;
  const double scale = cx.gamma_factor * std::pow(gr.length, alpha);
  const double kappa = cx.kappa, c1 = cx.par.one_minus_kappa_over_alpha();
  gr.kernel.resize(2 * n - 1);
  const auto last = static_cast<std::ptrdiff_t>(n) - 1;
  if (gr.periodic) {
    // Circulant: A(i, j) = c((i - j) mod n), c(m) the periodic kernel at sigma = (m + theta) h.
    const periodic_panel_kernel W(alpha, kappa, c1);
    std::vector<double> c(n);
    for (std::size_t m = 0; m < n; ++m) {
      if (m % 65536 == 0) cx.check_time();  // ~0.1 s of kernel values between checks
      c[m] = scale * W(h, (static_cast<double>(m) + theta) * h);
    }
    for (std::ptrdiff_t m = -last; m <= last; ++m)  // m = j - i
      gr.kernel[static_cast<std::size_t>(m + last)] = c[static_cast<std::size_t>((-m + static_cast<std::ptrdiff_t>(n)) % static_cast<std::ptrdiff_t>(n))];
  } else {
    for (std::ptrdiff_t m = -last; m <= last; ++m) {  // m = j - i: panel [m h, (m + 1) h] from theta h
      const double k = static_cast<double>(m);
      gr.kernel[static_cast<std::size_t>(m + last)] = scale * panel_integral((k - theta) * h, (k + 1 - theta) * h, alpha, kappa, c1);
    }
  }
  gr.product = std::make_unique<toeplitz_product>(gr.kernel, n);
  gr.z.resize(n);
  gr.rise.resize(n);
  double at_edge = curve.value(gr.edge(0));  // z at the panel's lower edge, carried to the next
  for (std::size_t i = 0; i < n; ++i) {
    gr.z[i] = curve.value(gr.lo + gr.length * (static_cast<double>(i) + theta) * h) - top;
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

namespace {

/// The cost of one FFT product on a grid of n panels in units of a multiply-add of the direct sum
/// (two transforms of M = 2^ceil(log2 2n) points, ~5 M log2 M flops each; the direct sum gathers
/// from the table, ~2x a streamed multiply-add): the direct sum over m active panels is cheaper
/// when m^2 is below it (measured: 672 active panels of 1.6e6: 0.36 s a product by FFT, 0.3 ms
/// by the sum).
double fft_cost(std::size_t n) {
  double M = 1;
  while (M < 2.0 * static_cast<double>(n)) M *= 2;
  return 5 * M * std::log2(M);
}

/// g on the active panels idx and the level D: A g - D = z there, h sum g = load. As g1 + D g0
/// with A g1 = z and A g0 = 1. False when the solve fails. Checks the time limit at each product.
bool solve_active(panel_grid& gr, const std::vector<std::size_t>& idx, double load, Eigen::VectorXd& g, double& D,
                  const context& cx) {
  const auto m = static_cast<Eigen::Index>(idx.size());
  auto at = [&](Eigen::Index r, Eigen::Index c) {
    return gr.A(idx[static_cast<std::size_t>(r)], idx[static_cast<std::size_t>(c)]);
  };
  Eigen::MatrixXd rhs(m, 2), X(m, 2);
  for (Eigen::Index r = 0; r < m; ++r) rhs(r, 0) = gr.z[idx[static_cast<std::size_t>(r)]];
  rhs.col(1).setOnes();
  if (m <= dense_limit) {
    Eigen::MatrixXd A(m, m);
    for (Eigen::Index c = 0; c < m; ++c)
      for (Eigen::Index r = 0; r < m; ++r) A(r, c) = at(r, c);
    X = A.partialPivLu().solve(rhs);
  } else {
    // No m x m matrix is stored. The preconditioner's blocks: neighbouring runs of active panels
    // share a block up to dense_limit panels (longer runs cut; memory <= dense_limit m). The
    // coupling of nearby contacts is the strongest, and GMRES needs about one iteration per block
    // for the far coupling (the loads' split between blocks), so fewer, larger blocks converge
    // faster (measured: 159 patches on 4500 active panels, ~270 products a solve with one block
    // per run, 73 with the runs grouped).
    std::vector<std::pair<Eigen::Index, Eigen::Index>> pieces;
    for (auto [s, e] : runs_of(idx))
      for (; s < e; s += dense_limit) {
        const Eigen::Index end = std::min(s + dense_limit, e);
        if (!pieces.empty() && end - pieces.back().first <= dense_limit) pieces.back().second = end;
        else pieces.emplace_back(s, end);
      }
    std::vector<Eigen::MatrixXd> blocks;
    for (const auto& [s, e] : pieces) {
      const Eigen::Index size = e - s;
      Eigen::MatrixXd B(size, size);
      for (Eigen::Index c = 0; c < size; ++c)
        for (Eigen::Index r = 0; r < size; ++r) B(r, c) = at(s + r, s + c);
      blocks.push_back(std::move(B));
    }
    // The product: by FFT over the whole grid, or, when the active panels are few against the
    // grid (small contacts on a fine grid), as the sum over the active pairs from the table.
    const bool direct = static_cast<double>(m) * static_cast<double>(m) < fft_cost(gr.n);
    auto product = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      cx.check_time();  // a step on a fine grid may take many products: the limit is checked at each
      if (!direct) return gr.product->apply(idx, idx, v);
      Eigen::VectorXd out(m);
      for (Eigen::Index r = 0; r < m; ++r) {
        const double* row = gr.kernel.data() + gr.n - 1 - idx[static_cast<std::size_t>(r)];
        double sum = 0;
        for (Eigen::Index c = 0; c < m; ++c) sum += row[idx[static_cast<std::size_t>(c)]] * v[c];
        out[r] = sum;
      }
      return out;
    };
    const abel::detail::block_gmres<double> solver(product, blocks);
    for (Eigen::Index k = 0; k < 2; ++k) {
      Eigen::VectorXd x;
      if (!solver.solve(rhs.col(k), x, gmres_tolerance, max_products)) return false;
      X.col(k) = x;
    }
  }
  D = (load / gr.h - X.col(0).sum()) / X.col(1).sum();
  g = X.col(0) + D * X.col(1);
  return std::isfinite(D) && g.allFinite();
}

}  // namespace

bool settle(panel_grid& gr, double load, double span, std::vector<char>& active, Eigen::VectorXd& g,
            std::vector<std::size_t>& idx, double& D, const context& cx, std::size_t& steps, std::size_t max_steps) {
  for (std::size_t step = 0; step < max_steps; ++step) {
    cx.check_time();
    ++steps;
    idx.clear();
    for (std::size_t i = 0; i < gr.n; ++i)
      if (active[i]) idx.push_back(i);
    if (idx.empty() || !solve_active(gr, idx, load, g, D, cx)) return false;
    bool dropped = false;
    for (std::size_t c = 0; c < idx.size(); ++c)
      if (g[static_cast<Eigen::Index>(c)] < 0) active[idx[c]] = 0, dropped = true;
    if (dropped) continue;
    bool added = false;
    const Eigen::VectorXd w = gr.product->apply(idx, g);  // at every panel
    for (std::size_t i = 0; i < gr.n; ++i) {
      if (active[i]) continue;
      if (w[static_cast<Eigen::Index>(i)] - D - gr.z[i] < -penetration_floor * span) active[i] = 1, added = true;
    }
    if (!added) return true;
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
