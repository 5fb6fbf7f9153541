// Tests of rhabel/abel/broyden_matrix.hpp (a factorised Jacobian plus Broyden's rank-one
// updates, solved by the Woodbury identity): against a direct dense solve of the updated matrix
// (the oracle forms J0 + sum u_i s_i^T itself and factorises it with full pivoting), the secant
// condition J s = dr of every update, and the singular update a step that no longer changes the
// residual makes.
#include <doctest/doctest.h>

#include "rhabel/abel/broyden_matrix.hpp"
#include "support.hpp"

#include <Eigen/Dense>

#include <random>

using namespace abel_test;
using bm = rhabel::abel::broyden_matrix<double>;

namespace {

/// A well-conditioned random m x m matrix (unit diagonal dominance).
Eigen::MatrixXd random_matrix(Eigen::Index m, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd A(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j) A(i, j) = u(rng) / static_cast<double>(m);
  A.diagonal().array() += 2.0;
  return A;
}

Eigen::VectorXd random_vector(Eigen::Index m, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd v(m);
  for (Eigen::Index i = 0; i < m; ++i) v[i] = u(rng);
  return v;
}

}  // namespace

TEST_CASE("broyden_matrix: the Woodbury solve equals the dense solve of the updated matrix, both paths") {
  // 12 updates of a matrix with condition ~10: the two solves differ by rounding, amplified by the
  // condition of J and of the 12 x 12 capacitance matrix; 1e4 eps relative is a loose bar for that
  // (measured below 1e2 eps), and a sign or transposition error in the identity is O(1).
  const double tol = 1e4 * eps;
  std::mt19937 rng(5);
  for (Eigen::Index m : {20, 64, 65, 200}) {  // up to 64: full pivoting of the updated matrix
    CAPTURE(m);
    const Eigen::MatrixXd J0 = random_matrix(m, rng);
    bm J(J0);
    Eigen::MatrixXd oracle = J0;
    for (int k = 0; k < 12; ++k) {
      const Eigen::VectorXd s = random_vector(m, rng), dr = random_vector(m, rng);
      J.update(s, dr);
      CHECK((J.current() * s - dr).norm() <= tol * dr.norm());  // the secant condition
      oracle += (dr - oracle * s) * s.transpose() / s.squaredNorm();
    }
    CHECK((J.current() - oracle).norm() <= tol * oracle.norm());
    CHECK(J.updates() == (m > bm::full_pivoting_up_to ? 12 : 0));
    const Eigen::VectorXd r = random_vector(m, rng);
    const auto x = J.solve(r);
    REQUIRE(x);
    const Eigen::VectorXd direct = oracle.fullPivLu().solve(r);
    CHECK((*x - direct).norm() <= tol * direct.norm());
    J.reset(J0);
    CHECK(J.updates() == 0);
    CHECK((*J.solve(r) - J0.fullPivLu().solve(r)).norm() <= tol * direct.norm());
  }
}

TEST_CASE("broyden_matrix: an update that cancels the matrix along its step is refused, not solved") {
  // dr = 0 (the step did not change the residual): J + u s^T annihilates s, and so does the
  // capacitance matrix. The Woodbury solve must give nothing (the caller takes a new Jacobian);
  // solved regardless it returned a step ~1e-24 that an iteration took for convergence.
  std::mt19937 rng(7);
  const Eigen::Index m = 100;
  bm J(random_matrix(m, rng));
  J.update(random_vector(m, rng), random_vector(m, rng));  // a regular update first
  const Eigen::VectorXd r = random_vector(m, rng);
  REQUIRE(J.solve(r));
  const Eigen::VectorXd s = random_vector(m, rng);
  J.update(s, Eigen::VectorXd::Zero(m));
  CHECK((J.current() * s).norm() <= 1e3 * eps * J.current().norm() * s.norm());  // singular along s
  CHECK_FALSE(J.solve(r));
  // A nearly cancelling update (dr 1e-12 of J s) is refused too; one of 1e-3 is solved.
  bm K(random_matrix(m, rng));
  const Eigen::VectorXd t = random_vector(m, rng);
  K.update(t, 1e-12 * (K.current() * t));
  CHECK_FALSE(K.solve(r));
  bm P(random_matrix(m, rng));
  P.update(t, 1e-3 * (P.current() * t));
  CHECK(P.solve(r));
}
