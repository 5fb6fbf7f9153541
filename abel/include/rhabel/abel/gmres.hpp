// rhabel/abel/gmres.hpp: restarted GMRES (Saad and Schultz, SIAM J. Sci. Stat. Comput. 7 (1986)
// 856-869; Saad, "Iterative Methods for Sparse Linear Systems", 2nd ed., SIAM 2003, section 9.3.2)
// with right preconditioning, for a linear operator given as a product v -> A v.
//
// gmres(apply, precondition, b, x, rtol, max_products, restart, products_taken) solves A x = b
// from the first guess x, with the preconditioner v -> P^-1 v applied on the right (A P^-1 y = b,
// x = P^-1 y: the residual minimised is that of the original system). Arnoldi with classical
// Gram-Schmidt and one reorthogonalisation (the basis orthogonal to ~eps), Givens rotations for
// the small least-squares problem. Stopping test: |b - A x| <= rtol |b|, with the TRUE residual
// recomputed from x at every restart (not only the Arnoldi estimate), so the returned x meets it
// whenever true is returned; rtol down to ~100 eps cond(A P^-1) is reachable. Returns false when
// max_products products of A were not enough (x then holds the last iterate). Vector: a dynamic
// Eigen column vector of any real scalar. Used by abel::solve_union (detail/block_gmres.hpp) and
// the punch layer's boundary-element active set.
#pragma once

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <vector>

namespace rhabel::abel {

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

}  // namespace rhabel::abel
