// punch/src/active_solve.cpp: the linear solve of one active set (active_solve.hpp).
#include "active_solve.hpp"

#include "rhabel/abel/gmres.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rhabel::punch::detail {
namespace {

using Eigen::Index;
using piece = std::pair<Index, Index>;  // [start, end) positions into idx

// Active panels up to which the linear solve is one LU (at 600 it costs 1.4e8 flops against ~1e6
// per GMRES product).
constexpr Index dense_limit = 600;
// The largest preconditioner block: with the coarse space carrying the coupling between blocks,
// small blocks converge in as many products as large ones and cost far less to factor (measured
// on a 96-patch profile at 128000 panels: ~20 products a solve for blocks of 25 .. 600 panels;
// 1.3 s for the whole solve at 50 or 100, 4.2 s at 600, 2.0 s at 25 where the coarse matrix
// grows).
constexpr Index block_limit = 100;
// GMRES: at most max_products products a solve.
constexpr std::size_t max_products = 600;

/// The cost of one FFT product of transform length M (toeplitz_product::transform_length) in units
/// of a multiply-add of the direct sum: the direct sum over m active panels is used when m^2 is
/// below it. Calibrated with Eigen's kissfft and a direct sum that gathered every column through
/// idx (M = 8e5: 38 ms a product by FFT; the direct sum over 13550 panels, 130 ms). Both are faster
/// now, by about as much: FFTW (toeplitz_product.hpp) and the direct sum by runs of adjacent panels
/// (solve_active), so the crossing stays near the break-even. Measured on a grid of 2^21 panels
/// (a throwaway microbenchmark beside the repository, another job on the cores): 10632 active
/// panels in 443 runs of 24, 43 ms a product (104 ms gathered) against 51 ms by FFTW (the
/// crossing: direct); 24500 panels in 980 runs, 400 ms (610 ms) against 51 ms (FFT). WHY not
/// recalibrated: moved, the coarse seeds' rounding changes and with it the searches' paths (the
/// ~980-patch periodic profile took 441-456 s against 377 s in one such trial).
double fft_cost(std::size_t M) {
  const auto m = static_cast<double>(M);
  return 5 * m * std::log2(m);
}

/// The preconditioner's blocks: neighbouring runs of active panels (runs_of) share a block up to
/// block_limit panels (longer runs cut).
std::vector<piece> blocks_of(const std::vector<piece>& runs) {
  std::vector<piece> pieces;
  for (auto [s, e] : runs)
    for (; s < e; s += block_limit) {
      const Index end = std::min(s + block_limit, e);
      if (!pieces.empty() && end - pieces.back().first <= block_limit) pieces.back().second = end;
      else pieces.emplace_back(s, end);
    }
  return pieces;
}

/// The two-level preconditioner of active_solve.hpp: v -> P^-1 v.
class two_level {
 public:
  /// sigma: the scale of the load row (see solve_active).
  two_level(const panel_grid& gr, const std::vector<std::size_t>& idx, std::vector<piece> pieces, double sigma)
      : gr_(gr), idx_(idx), pieces_(std::move(pieces)) {
    const std::size_t K = pieces_.size();
    for (const auto& [s, e] : pieces_) {
      Eigen::MatrixXd B(e - s, e - s);
      for (Index c = 0; c < e - s; ++c)
        for (Index r = 0; r < e - s; ++r) B(r, c) = at(s + r, idx_[static_cast<std::size_t>(s + c)]);
      lu_.emplace_back(B);
      Z_.push_back(lu_.back().solve(Eigen::VectorXd::Ones(e - s)));
      const Eigen::VectorXd& z = Z_.back();
      q_.push_back(z.sum());
      // The monopole's panel: the Z-weighted centre (the block's middle if the weights cancel).
      double moment = 0, weight = 0;
      for (Index r = 0; r < e - s; ++r) moment += std::abs(z[r]) * static_cast<double>(idx_[static_cast<std::size_t>(s + r)]), weight += std::abs(z[r]);
      const double mid = 0.5 * static_cast<double>(idx_[static_cast<std::size_t>(s)] + idx_[static_cast<std::size_t>(e - 1)]);
      centre_.push_back(static_cast<std::size_t>(std::lround(weight > 0 ? moment / weight : mid)));
    }
    near_.resize(K);
    far_.resize(K);
    // The coarse system of (c, D): [E, -W^T 1; sigma h q^T, 0], E(k, l) = 1_k^T A Z_l.
    const auto Ki = static_cast<Index>(K);
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(Ki + 1, Ki + 1);
    for (std::size_t k = 0; k < K; ++k) {
      const auto [s, e] = pieces_[k];
      E(static_cast<Index>(k), static_cast<Index>(k)) = static_cast<double>(e - s);  // A Z_k = 1 on block k
      E(static_cast<Index>(k), Ki) = -static_cast<double>(e - s);
      E(Ki, static_cast<Index>(k)) = sigma * gr.h * q_[k];
      for (std::size_t l = 0; l < K; ++l) {
        if (l == k) continue;
        if (near(k, l)) {
          Eigen::VectorXd v = Eigen::VectorXd::Zero(e - s);  // (A Z_l) on block k, exactly
          const auto [sl, el] = pieces_[l];
          for (Index c = 0; c < el - sl; ++c) {
            const std::size_t p = idx_[static_cast<std::size_t>(sl + c)];
            for (Index r = 0; r < e - s; ++r) v[r] += at(s + r, p) * Z_[l][c];
          }
          E(static_cast<Index>(k), static_cast<Index>(l)) = v.sum();
          near_[k].push_back({l, std::move(v)});
        } else {
          double sum = 0;
          for (Index r = s; r < e; ++r) sum += at(r, centre_[l]);
          E(static_cast<Index>(k), static_cast<Index>(l)) = q_[l] * sum;
          far_[k].push_back(l);
        }
      }
    }
    E_.compute(E);
  }

  /// v = (r_g, r_load) -> (g, D).
  Eigen::VectorXd operator()(const Eigen::VectorXd& v) const {
    const std::size_t K = pieces_.size();
    const auto Ki = static_cast<Index>(K);
    Eigen::VectorXd w(Ki + 1);
    for (std::size_t k = 0; k < K; ++k) w[static_cast<Index>(k)] = v.segment(pieces_[k].first, size(k)).sum();
    w[Ki] = v[v.size() - 1];
    const Eigen::VectorXd c = E_.solve(w);  // (c, D)
    const double D = c[Ki];
    std::vector<double> cq(K);
    for (std::size_t l = 0; l < K; ++l) cq[l] = c[static_cast<Index>(l)] * q_[l];
    Eigen::VectorXd out(v.size());
    for (std::size_t k = 0; k < K; ++k) {
      const auto [s, e] = pieces_[k];
      Eigen::VectorXd r1 = v.segment(s, e - s).array() - c[static_cast<Index>(k)] + D;
      for (const auto& nb : near_[k]) r1 -= c[static_cast<Index>(nb.l)] * nb.AZ;
      for (Index r = 0; r < e - s; ++r) {
        double far = 0;
        for (std::size_t l : far_[k]) far += at(s + r, centre_[l]) * cq[l];
        r1[r] -= far;
      }
      out.segment(s, e - s) = lu_[k].solve(r1) + c[static_cast<Index>(k)] * Z_[k];
    }
    out[v.size() - 1] = D;
    return out;
  }

 private:
  /// A at the active panel of position r and the panel p.
  double at(Index r, std::size_t p) const { return gr_.A(idx_[static_cast<std::size_t>(r)], p); }
  Index size(std::size_t k) const { return pieces_[k].second - pieces_[k].first; }

  /// Blocks k and l are coupled exactly when next in order (cyclically on a periodic grid) or
  /// nearer than half the wider of them (the monopole's error ~ (width / distance)^2 is then
  /// no longer small).
  bool near(std::size_t k, std::size_t l) const {
    const std::size_t K = pieces_.size(), d = k > l ? k - l : l - k;
    if (d == 1 || (gr_.periodic && d == K - 1)) return true;
    auto lo = [&](std::size_t b) { return idx_[static_cast<std::size_t>(pieces_[b].first)]; };
    auto hi = [&](std::size_t b) { return idx_[static_cast<std::size_t>(pieces_[b].second - 1)] + 1; };
    const std::size_t a = std::min(k, l), b = std::max(k, l);
    std::size_t gap = lo(b) - hi(a);
    if (gr_.periodic) gap = std::min(gap, lo(a) + gr_.n - hi(b));
    const std::size_t width = std::max(hi(a) - lo(a), hi(b) - lo(b));
    return 2 * gap < width;
  }

  struct near_block {
    std::size_t l;
    Eigen::VectorXd AZ;  ///< (A Z_l) on the block
  };
  const panel_grid& gr_;
  const std::vector<std::size_t>& idx_;
  std::vector<piece> pieces_;
  std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> lu_;
  std::vector<Eigen::VectorXd> Z_;
  std::vector<double> q_;
  std::vector<std::size_t> centre_;
  std::vector<std::vector<near_block>> near_;
  std::vector<std::vector<std::size_t>> far_;
  Eigen::PartialPivLU<Eigen::MatrixXd> E_;
};

/// The first guess (g, D) on idx from the last solve (see the top of active_solve.hpp); zero if none.
Eigen::VectorXd first_guess(const warm_start& ws, const std::vector<std::size_t>& idx, std::size_t n) {
  const auto m = static_cast<Index>(idx.size());
  Eigen::VectorXd y = Eigen::VectorXd::Zero(m + 1);
  if (ws.n == 0) return y;
  const double ratio = static_cast<double>(ws.n) / static_cast<double>(n);
  for (std::size_t r = 0; r < idx.size(); ++r) {
    const auto old = static_cast<std::size_t>((static_cast<double>(idx[r]) + 0.5) * ratio);
    const auto it = std::lower_bound(ws.idx.begin(), ws.idx.end(), old);
    if (it != ws.idx.end() && *it == old) y[static_cast<Index>(r)] = ws.g[it - ws.idx.begin()];
  }
  y[m] = ws.D;
  return y;
}

}  // namespace

bool solve_active(panel_grid& gr, const std::vector<std::size_t>& idx, double load, double span, Eigen::VectorXd& g,
                  double& D, const context& cx, warm_start& ws, double rtol) {
  const auto m = static_cast<Index>(idx.size());
  // The bordered system [A, -1; sigma h 1^T, 0] (g, D) = (z, sigma load); sigma puts the load row
  // on the scale of the displacements' norm (GMRES's residual weighs both), floored by 1e-3 of
  // the profile's span a panel where the active z vanish.
  Eigen::VectorXd rhs(m + 1);
  for (Index r = 0; r < m; ++r) rhs[r] = gr.z[idx[static_cast<std::size_t>(r)]];
  const double sigma = std::max(rhs.head(m).norm(), 1e-3 * span * std::sqrt(static_cast<double>(m))) / load;
  rhs[m] = sigma * load;
  Eigen::VectorXd y;
  if (m <= dense_limit) {
    Eigen::MatrixXd A(m + 1, m + 1);
    for (Index c = 0; c < m; ++c) {
      for (Index r = 0; r < m; ++r) A(r, c) = gr.A(idx[static_cast<std::size_t>(r)], idx[static_cast<std::size_t>(c)]);
      A(m, c) = sigma * gr.h;
      A(c, m) = -1;
    }
    A(m, m) = 0;
    y = A.partialPivLu().solve(rhs);
  } else {
    // The product: by FFT over the whole grid, or, when the active panels are few against the
    // grid (small contacts on a fine grid), as the sum over the active pairs from the table.
    const bool direct = static_cast<double>(m) * static_cast<double>(m) < fft_cost(gr.product->transform_length());
    // The runs of adjacent active panels: the preconditioner's blocks, and the direct sum's
    // pieces (over a run both the table's entries, A(i, j) = kernel[j - i + n - 1], and the
    // unknowns are contiguous, so each run is one dot product, vectorised, not gathers through idx).
    const std::vector<piece> runs = runs_of(idx);
    auto product = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      cx.check_time();  // a step on a fine grid may take many products: the limit is checked at each
      Eigen::VectorXd out(m + 1);
      const Eigen::VectorXd gv = v.head(m);
      if (!direct) {
        out.head(m) = gr.product->apply(idx, idx, gv);
      } else {
        for (Index r = 0; r < m; ++r) {
          const double* row = gr.kernel.data() + gr.n - 1 - idx[static_cast<std::size_t>(r)];
          double sum = 0;
          for (const auto& [s, e] : runs)
            sum += Eigen::Map<const Eigen::VectorXd>(row + idx[static_cast<std::size_t>(s)], e - s).dot(gv.segment(s, e - s));
          out[r] = sum;
        }
      }
      out.head(m).array() -= v[m];
      out[m] = sigma * gr.h * gv.sum();
      return out;
    };
    const two_level precondition(gr, idx, blocks_of(runs), sigma);
    y = first_guess(ws, idx, gr.n);
    if (!abel::gmres(product, precondition, rhs, y, rtol, max_products)) return false;
  }
  g = y.head(m);
  D = y[m];
  ws.n = gr.n;
  ws.idx = idx;
  ws.g = g;
  ws.D = D;
  return std::isfinite(D) && g.allFinite();
}

}  // namespace rhabel::punch::detail
