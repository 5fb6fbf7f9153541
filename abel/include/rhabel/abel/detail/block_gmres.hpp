// rhabel/abel/detail/block_gmres.hpp: the iterative linear solve of abel::solve_union
// (multi_interval.hpp, multi_solve_options::iterative_from) for unions of many intervals.
//
// The collocation matrix A of K intervals (M unknowns and M equations each, T = K M) is dense, and
// its LU costs 2/3 T^3: at K = 100, M = 16 that is 2.7 GFlop per solve, against 2 T^2 = 5 MFlop per
// product A v. Its diagonal blocks A_jj are the intervals' own operators (the spectral relation:
// lambda_n times image polynomials at the collocation points), the off-diagonal ones the coupling,
// smooth and small for separated intervals. So A is solved by GMRES (restarted, right
// preconditioned, Gram-Schmidt with one reorthogonalisation) with the block-diagonal
// preconditioner P = diag(A_jj) (an LU of each M x M block: K M^3 in all): A P^-1 y = b, x = P^-1 y.
// Right preconditioning minimises the residual of the original system, |b - A x|, and that is what
// the stopping test measures: |b - A x| <= rtol |b|, recomputed from x at every restart (not only
// the Arnoldi estimate). rtol = 1e-14 (solve_union): a relative residual of the collocation system
// ~100 eps, below the 1e-10 .. 1e-12 at which solve_union's own residual accepts a solve.
// Returns false when the iteration limit is reached first (the caller then falls back to LU).
// The algorithm itself is the free function `gmres` (any preconditioner, a first guess): punch's
// boundary-element active set (punch/src/active_solve.cpp) calls it with a two-level
// preconditioner and the last solve as the guess.
#pragma once

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

namespace rhabel::abel::detail {

/// Restarted GMRES, right preconditioned by `precondition` (v -> P^-1 v), Gram-Schmidt with one
/// reorthogonalisation: A x = b from the first guess x (zero: no product for the first residual)
/// to |b - A x| <= rtol |b|, the true residual recomputed at every restart. Returns false when
/// max_products products of A were not enough; `products`, when given, gets the number taken.
/// Vector: a dynamic Eigen column vector; apply and precondition: callables vector -> vector.
template <class Vector, class Apply, class Precondition>
bool gmres(const Apply& apply, const Precondition& precondition, const Vector& b, Vector& x,
           const typename Vector::Scalar& rtol, std::size_t max_products, std::size_t restart = 60,
           std::size_t* products_taken = nullptr) {
  using Real = typename Vector::Scalar;
  using Matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  using std::abs;
  using std::sqrt;
  const Eigen::Index T = b.size();
  std::size_t products = 0;
  struct count_out {  // reports the products however the function returns
    std::size_t& n;
    std::size_t* out;
    ~count_out() {
      if (out) *out = n;
    }
  } report{products, products_taken};
  const Real b_norm = b.norm();
  if (b_norm == 0) {
    x = Vector::Zero(T);
    return true;
  }
  Vector r = b;
  if (x.size() != T) x = Vector::Zero(T);
  else if (!x.isZero(0)) {
    r = b - apply(x);
    ++products;
  }
  const auto m = static_cast<Eigen::Index>(restart);
  Matrix V(T, m + 1);
  Matrix H = Matrix::Zero(m + 1, m);
  Vector cs(m), sn(m), g(m + 1);
  for (;;) {
    const Real beta = r.norm();
    if (beta <= rtol * b_norm) return true;
    if (products >= max_products) return false;
    V.col(0) = r / beta;
    g.setZero();
    g[0] = beta;
    H.setZero();
    Eigen::Index k = 0;
    for (; k < m && products < max_products; ++k) {
      Vector w = apply(precondition(Vector(V.col(k))));
      ++products;
      // Gram-Schmidt against V(:, 0..k), twice (the second pass restores orthogonality lost to
      // cancellation; "twice is enough").
      for (int pass = 0; pass < 2; ++pass) {
        const Vector h = V.leftCols(k + 1).transpose() * w;
        w -= V.leftCols(k + 1) * h;
        H.col(k).head(k + 1) += h;
      }
      H(k + 1, k) = w.norm();
      const bool breakdown = !(H(k + 1, k) > 0);  // A P^-1 V(:, 0..k) spans the solution: exact
      if (!breakdown) V.col(k + 1) = w / H(k + 1, k);
      // Givens rotations: H(0..k+1, k) to upper triangular form, g along.
      for (Eigen::Index i = 0; i < k; ++i) {
        const Real t = cs[i] * H(i, k) + sn[i] * H(i + 1, k);
        H(i + 1, k) = -sn[i] * H(i, k) + cs[i] * H(i + 1, k);
        H(i, k) = t;
      }
      const Real rho = sqrt(H(k, k) * H(k, k) + H(k + 1, k) * H(k + 1, k));
      cs[k] = rho == 0 ? Real(1) : H(k, k) / rho;
      sn[k] = rho == 0 ? Real(0) : H(k + 1, k) / rho;
      H(k, k) = rho;
      H(k + 1, k) = 0;
      g[k + 1] = -sn[k] * g[k];
      g[k] = cs[k] * g[k];
      // The Arnoldi estimate of |b - A x| (a safety factor of 1/10: the true residual decides).
      if (abs(g[k + 1]) <= rtol * b_norm / 10 || breakdown) {
        ++k;
        break;
      }
    }
    // y = H(0..k-1, 0..k-1)^-1 g(0..k-1); x += P^-1 V y.
    const Vector y = H.topLeftCorner(k, k).template triangularView<Eigen::Upper>().solve(g.head(k));
    x += precondition(Vector(V.leftCols(k) * y));
    r = b - apply(x);
    ++products;
  }
}

template <class Real>
class block_gmres {
 public:
  using matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  using vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;

  /// A: the T x T system (kept by reference); blocks: K diagonal blocks of size `block` (T = K block).
  block_gmres(const matrix& A, Eigen::Index block) : apply_([&A](const vector& v) { return vector(A * v); }), size_(A.rows()) {
    const Eigen::Index K = A.rows() / block;
    for (Eigen::Index k = 0; k < K; ++k) {
      diagonal_.emplace_back(matrix(A.block(k * block, k * block, block, block)));
      offsets_.push_back(k * block);
    }
  }

  /// A given as its product (matrix-free: multi_interval.hpp's far field), with its diagonal
  /// blocks in order, square and of any sizes (T is the sum of their sizes; punch's coarse contact
  /// solve has one block per run of active panels).
  block_gmres(std::function<vector(const vector&)> apply, const std::vector<matrix>& diagonal)
      : apply_(std::move(apply)), size_(0) {
    for (const auto& d : diagonal) {
      offsets_.push_back(size_);
      size_ += d.rows();
      diagonal_.emplace_back(d);
    }
  }

  /// Solves A x = b to |b - A x| <= rtol |b|; false if max_iterations products were not enough.
  bool solve(const vector& b, vector& x, const Real& rtol, std::size_t max_iterations = 200,
             std::size_t restart = 60) const {
    x = vector::Zero(size_);
    return gmres(apply_, [this](const vector& v) { return precondition(v); }, b, x, rtol, max_iterations, restart);
  }

 private:
  vector precondition(const vector& v) const {
    vector out(v.size());
    for (std::size_t k = 0; k < diagonal_.size(); ++k) {
      const Eigen::Index size = diagonal_[k].rows();
      out.segment(offsets_[k], size) = diagonal_[k].solve(v.segment(offsets_[k], size));
    }
    return out;
  }

  std::function<vector(const vector&)> apply_;
  Eigen::Index size_;
  std::vector<Eigen::Index> offsets_;  // where each diagonal block starts
  std::vector<Eigen::PartialPivLU<matrix>> diagonal_;
};

}  // namespace rhabel::abel::detail
