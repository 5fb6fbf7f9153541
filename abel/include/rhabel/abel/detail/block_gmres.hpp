// rhabel/abel/detail/block_gmres.hpp: the iterative linear solve of abel::solve_union
// (multi_interval.hpp, multi_solve_options::iterative_from) for unions of many intervals.
//
// The collocation matrix A of K intervals (M unknowns and M equations each, T = K M; or M_i on
// interval i, multi_solve_options::degrees, the blocks then of unequal sizes) is dense, and
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
// The algorithm itself is the free function `gmres` (rhabel/abel/gmres.hpp).
#pragma once

#include "rhabel/abel/gmres.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

namespace rhabel::abel::detail {

template <class Real>
class block_gmres {
 public:
  using matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;
  using vector = Eigen::Matrix<Real, Eigen::Dynamic, 1>;

  /// A: the T x T system (kept by reference); blocks: the sizes of its diagonal blocks in order
  /// (they add up to T).
  block_gmres(const matrix& A, const std::vector<Eigen::Index>& blocks)
      : apply_([&A](const vector& v) { return vector(A * v); }), size_(A.rows()) {
    Eigen::Index offset = 0;
    for (const Eigen::Index block : blocks) {
      diagonal_.emplace_back(matrix(A.block(offset, offset, block, block)));
      offsets_.push_back(offset);
      offset += block;
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
  /// from_x: GMRES starts from x (of size b's), else from zero; `products`, when given, gets the
  /// number of products of A taken.
  bool solve(const vector& b, vector& x, const Real& rtol, bool from_x = false, std::size_t* products = nullptr,
             std::size_t max_iterations = 200, std::size_t restart = 60) const {
    if (!from_x || x.size() != size_) x = vector::Zero(size_);
    return gmres(apply_, [this](const vector& v) { return precondition(v); }, b, x, rtol, max_iterations, restart,
                 products);
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
