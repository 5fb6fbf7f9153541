// punch/src/coarse_contact.cpp: the coarse non-negative solve of a sampled profile on a rigid body
// (coarse_contact.hpp).
#include "coarse_contact.hpp"

#include "toeplitz_product.hpp"

#include "rhabel/abel/detail/block_gmres.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <memory>

namespace rhabel::punch::detail {
namespace {

// The first grid: every panel active (its LU: 256^3 flops).
constexpr std::size_t first_panels = 256;
// Active panels up to which the linear solve is one LU (above: block GMRES; at 600 an LU costs
// 1.4e8 flops against ~1e6 per GMRES product).
constexpr Eigen::Index dense_limit = 600;
// Active-set steps per grid; more means the set cycles (the caller searches without it).
constexpr std::size_t max_steps = 60;
// Collocation point in each panel (coarse_contact.hpp, ACCURACY).
constexpr double theta = 0.75;
// GMRES: a relative residual far below the method's O(h) error, within max_products products
// (else the caller searches without the coarse set).
constexpr double gmres_tolerance = 1e-10;
constexpr std::size_t max_products = 400;
// Panels at most: the finest grid has one panel per sample up to this many (a predictor needs no
// more). Products and the penetration check go through the FFT (toeplitz_product.hpp), O(n log n)
// each: at 2^17 panels ~9 ms a product and ~16 MB of FFT buffers (measured, one core, -O3).
constexpr std::size_t max_panels = std::size_t{1} << 17;
// A panel penetrates when w - z < D by more than this fraction of the profile's span (round-off).
constexpr double penetration_floor = 1e-9;

/// int_0^d E(u) du, E(u) = (1 - u^alpha)/alpha (-> -log u at alpha = 0):
/// d (1 - (d^alpha - 1)/alpha)/(1 + alpha), with (d^alpha - 1)/alpha = expm1(alpha log d)/alpha.
double integral_e(double d, double alpha) {
  if (d <= 0) return 0;
  const double l = std::log(d);
  return d * (1 - (alpha == 0 ? l : std::expm1(alpha * l) / alpha)) / (1 + alpha);
}

/// Uniform panels on the samples' range mapped to [0, 1]: the Toeplitz matrix and the data.
/// With x = lo + length x', Psi(length d') = length^alpha Psi(d') + (1 - length^alpha)/alpha: the
/// constant acts as a change of D (the total load is fixed), so the kernel on [0, 1] is Psi times
/// Gamma(1 - alpha) length^alpha, and int g' dx' = P for g' = length g.
struct grid {
  std::size_t n = 0;
  double h = 0;
  std::vector<double> kernel;  // A(i, j) = kernel[j - i + n - 1]: panel j at collocation point i
  std::vector<double> z;       // z - max z at the collocation points
  std::unique_ptr<toeplitz_product> product;  // A by FFT
  double A(std::size_t i, std::size_t j) const { return kernel[j + n - 1 - i]; }
};

grid make_grid(const profile_curve& curve, std::size_t n, const context& cx, double top) {
  grid gr;
  gr.n = n;
  gr.h = 1.0 / static_cast<double>(n);
  const double length = curve.hi() - curve.lo(), h = gr.h, alpha = cx.alpha;
  const double scale = cx.gamma_factor * std::pow(length, alpha);
  const double kappa = cx.kappa, c1 = cx.par.one_minus_kappa_over_alpha();
  // Panels behind the point (t < x, distance d): Psi = kappa E(d) + (1 - kappa)/alpha.
  auto behind = [&](double d) { return kappa * integral_e(d, alpha) + c1 * d; };
  gr.kernel.resize(2 * n - 1);
  const auto last = static_cast<std::ptrdiff_t>(n) - 1;
  for (std::ptrdiff_t m = -last; m <= last; ++m) {  // m = j - i
    const double k = static_cast<double>(m);
    double v = 0;
    if (m > 0)
      v = integral_e((k + 1 - theta) * h, alpha) - integral_e((k - theta) * h, alpha);
    else if (m < 0)
      v = behind((theta - k) * h) - behind((theta - k - 1) * h);
    else
      v = integral_e((1 - theta) * h, alpha) + behind(theta * h);
    gr.kernel[static_cast<std::size_t>(m + last)] = scale * v;
  }
  gr.product = std::make_unique<toeplitz_product>(gr.kernel, n);
  gr.z.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    gr.z[i] = curve.value(curve.lo() + length * (static_cast<double>(i) + theta) * h) - top;
  return gr;
}

/// Runs of consecutive indices in idx (sorted): [start, end) positions into idx.
std::vector<std::pair<Eigen::Index, Eigen::Index>> runs_of(const std::vector<std::size_t>& idx) {
  std::vector<std::pair<Eigen::Index, Eigen::Index>> out;
  for (std::size_t c = 0; c < idx.size(); ++c) {
    const auto at = static_cast<Eigen::Index>(c);
    if (c == 0 || idx[c] != idx[c - 1] + 1) out.emplace_back(at, at);
    ++out.back().second;
  }
  return out;
}

/// g on the active panels idx and the level D: A g - D = z there, h sum g = load. As g1 + D g0
/// with A g1 = z and A g0 = 1. False when the solve fails.
bool solve_active(grid& gr, const std::vector<std::size_t>& idx, double load, Eigen::VectorXd& g, double& D) {
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
    // Products from the Toeplitz table (no m x m matrix is stored); the preconditioner's blocks
    // are the runs, cut into pieces of at most dense_limit panels (memory <= dense_limit m).
    std::vector<Eigen::MatrixXd> blocks;
    for (auto [s, e] : runs_of(idx))
      for (; s < e; s += dense_limit) {
        const Eigen::Index size = std::min(dense_limit, e - s);
        Eigen::MatrixXd B(size, size);
        for (Eigen::Index c = 0; c < size; ++c)
          for (Eigen::Index r = 0; r < size; ++r) B(r, c) = at(s + r, s + c);
        blocks.push_back(std::move(B));
      }
    const abel::detail::block_gmres<double> solver(
        [&](const Eigen::VectorXd& v) { return gr.product->apply(idx, idx, v); },
        blocks);
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

/// The active-set steps on one grid from `active`; false when they do not settle.
bool settle(grid& gr, double load, double span, std::vector<char>& active, Eigen::VectorXd& g,
            std::vector<std::size_t>& idx, const context& cx) {
  for (std::size_t step = 0; step < max_steps; ++step) {
    cx.check_time();
    idx.clear();
    for (std::size_t i = 0; i < gr.n; ++i)
      if (active[i]) idx.push_back(i);
    double D = 0;
    if (idx.empty() || !solve_active(gr, idx, load, g, D)) return false;
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

}  // namespace

std::vector<coarse_patch> coarse_contacts(const profile_curve& curve, double load, const context& cx,
                                          std::size_t panels) {
  const auto [lo, hi] = std::minmax_element(curve.z().begin(), curve.z().end());
  const double top = *hi, span = *hi - *lo, length = curve.hi() - curve.lo();
  panels = std::clamp(panels, first_panels, max_panels);
  std::size_t n = first_panels;
  std::vector<char> active(n, 1);
  Eigen::VectorXd g;
  std::vector<std::size_t> idx;
  grid gr;
  for (;;) {
    gr = make_grid(curve, n, cx, top);
    if (!settle(gr, load, span, active, g, idx, cx)) return {};
    if (n == panels) break;
    // The next grid: a panel is active where the centre of its panel on this one was.
    const std::size_t next = std::min(4 * n, panels);
    std::vector<char> finer(next, 0);
    const double ratio = static_cast<double>(n) / static_cast<double>(next);
    for (std::size_t i = 0; i < next; ++i)
      finer[i] = active[std::min(n - 1, static_cast<std::size_t>((static_cast<double>(i) + 0.5) * ratio))];
    active = std::move(finer);
    n = next;
  }
  std::vector<coarse_patch> out;
  for (const auto& [s, e] : runs_of(idx)) {
    coarse_patch p;
    p.a = curve.lo() + length * static_cast<double>(idx[static_cast<std::size_t>(s)]) * gr.h;
    p.b = curve.lo() + length * static_cast<double>(idx[static_cast<std::size_t>(e - 1)] + 1) * gr.h;
    p.load = gr.h * g.segment(s, e - s).sum();
    out.push_back(p);
  }
  return out;
}

}  // namespace rhabel::punch::detail
