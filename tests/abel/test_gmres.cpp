// GMRES as a free function (rhabel/abel/gmres.hpp), the algorithm behind
// block_gmres and punch's active-set solves, against Eigen's LU of the same matrix (no shared
// code): the residual it reports is reached, a first guess is used (the exact solution costs one
// product, a near one fewer products than zero), and a preconditioner that is the exact inverse
// converges in one step.
#include <doctest/doctest.h>

#include "rhabel/abel/gmres.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

namespace {
using rhabel::abel::gmres;
using vec = Eigen::VectorXd;

// A nonsymmetric, well conditioned system (dominant diagonal, random rest), n = 120.
Eigen::MatrixXd test_matrix(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const Eigen::Index n = 120;
  Eigen::MatrixXd A(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) A(i, j) = u(rng) / std::sqrt(static_cast<double>(n));
  A.diagonal().array() += 3;
  return A;
}

// The relative residual asked of GMRES; the solution then differs from the LU's by at most
// condition (~2 here) x rtol of its size, with a margin of 10.
constexpr double rtol = 1e-12;
constexpr double solution_tol = 20 * rtol;
}  // namespace

TEST_CASE("gmres: reaches its residual, uses the first guess, and an exact preconditioner in one step") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const Eigen::MatrixXd A = test_matrix(rng);
  vec b(A.rows());
  for (auto& x : b) x = u(rng);
  const vec exact = A.partialPivLu().solve(b);
  auto apply = [&](const vec& v) { return vec(A * v); };
  auto identity = [](const vec& v) { return v; };

  vec x;  // empty: started from zero
  std::size_t from_zero = 0;
  REQUIRE(gmres(apply, identity, b, x, rtol, 500, 60, &from_zero));
  CHECK((b - A * x).norm() <= rtol * b.norm());
  CHECK((x - exact).norm() <= solution_tol * exact.norm());

  vec near = exact;
  for (auto& v : near) v *= 1 + 1e-6 * u(rng);
  std::size_t from_near = 0;
  REQUIRE(gmres(apply, identity, b, near, rtol, 500, 60, &from_near));
  CHECK((near - exact).norm() <= solution_tol * exact.norm());
  CHECK(from_near < from_zero);

  vec at = exact;
  std::size_t from_exact = 0;
  REQUIRE(gmres(apply, identity, b, at, 1e-10, 500, 60, &from_exact));
  CHECK(from_exact == 1);  // the first residual only

  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
  vec y;
  std::size_t preconditioned = 0;
  REQUIRE(gmres(apply, [&](const vec& v) { return vec(lu.solve(v)); }, b, y, rtol, 500, 60, &preconditioned));
  CHECK(preconditioned <= 3);  // one Arnoldi step (and a second for round-off) and the final residual
  CHECK((y - exact).norm() <= solution_tol * exact.norm());

  std::size_t capped = 0;
  vec z;
  // eps cannot be reached in 5 products: false, after the cap and the residual of the iterate.
  CHECK_FALSE(gmres(apply, identity, b, z, std::numeric_limits<double>::epsilon(), 5, 60, &capped));
  CHECK(capped == 6);
}
