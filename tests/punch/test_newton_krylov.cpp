// The Jacobian-free Newton-Krylov step (punch/src/newton_krylov.hpp, internal) against the
// analytic Jacobian of a smooth nonlinear system: F(x) = A x + c sin(x) - b with A a fixed
// non-symmetric, diagonally weighted matrix. The step's linear residual |r + F'(x) dx| is
// computed with F'(x) = A + c diag(cos x), which the step never sees.
#include <doctest/doctest.h>

#include "../punch/src/newton_krylov.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {
namespace d = rhabel::punch::detail;

constexpr Eigen::Index m = 24;
constexpr double c = 0.7;

Eigen::MatrixXd matrix() {
  Eigen::MatrixXd A(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j)
      A(i, j) = (i == j ? 4.0 + double(i % 5) : 0.0) + std::sin(double(3 * i + 7 * j + 1)) / (1.0 + std::abs(double(i - j)));
  return A;
}

Eigen::VectorXd F(const Eigen::MatrixXd& A, const Eigen::VectorXd& x) {
  Eigen::VectorXd b(m);
  for (Eigen::Index i = 0; i < m; ++i) b[i] = std::cos(double(i));
  return A * x + c * x.array().sin().matrix() - b;
}

Eigen::MatrixXd jacobian(const Eigen::MatrixXd& A, const Eigen::VectorXd& x) {
  return A + Eigen::MatrixXd(c * x.array().cos().matrix().asDiagonal());
}

// The differences' error with a relative step of 1e-7 on unit scales: ~1e-7 |F''| |v| (c = 0.7), so
// 1e-5 is met with a margin of ~100 and stays far above the GMRES tolerance's reach in double.
constexpr double rtol = 1e-5;

}  // namespace

TEST_CASE("newton_krylov_step: |r + F'(x) dx| <= rtol |r| with the analytic Jacobian, within its products") {
  const Eigen::MatrixXd A = matrix();
  Eigen::VectorXd x(m);
  for (Eigen::Index i = 0; i < m; ++i) x[i] = 0.3 * std::sin(double(2 * i + 1));
  const Eigen::VectorXd r = F(A, x), scale = Eigen::VectorXd::Ones(m);
  const Eigen::MatrixXd J = jacobian(A, x);
  std::size_t calls = 0;
  const auto moved = [&](const Eigen::VectorXd& dx) {
    ++calls;
    return F(A, x + dx);
  };
  SUBCASE("preconditioned by the diagonal of A (a poor approximation): GMRES does the rest") {
    const Eigen::VectorXd diagonal = A.diagonal();
    const auto precondition = [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(v.cwiseQuotient(diagonal)); };
    bool reached = false;
    const Eigen::VectorXd dx = d::newton_krylov_step(moved, r, scale, precondition, rtol, 40, 1e-7, 1e-7, &reached);
    CHECK(reached);
    CHECK((r + J * dx).norm() <= rtol * r.norm());
    CHECK(calls <= 41);  // max_products + 1
    // Not the preconditioner's step alone: that misses by far more.
    CHECK((r - J * precondition(r)).norm() > 100 * rtol * r.norm());
  }
  SUBCASE("too few products: the best iterate, reached = false, the limit kept") {
    const auto identity = [](const Eigen::VectorXd& v) { return v; };
    bool reached = true;
    const Eigen::VectorXd dx = d::newton_krylov_step(moved, r, scale, identity, rtol, 3, 1e-7, 1e-7, &reached);
    CHECK_FALSE(reached);
    CHECK(calls <= 4);
    CHECK((r + J * dx).norm() < r.norm());  // GMRES never increases the residual from dx = 0
  }
  SUBCASE("a forward move F refuses is taken backward") {
    // F refuses any move that raises x_0 (as a closing gap makes the edge conditions throw).
    const auto guarded = [&](const Eigen::VectorXd& dx) {
      if (dx[0] > 0) throw std::domain_error("refused");
      return F(A, x + dx);
    };
    const auto identity = [](const Eigen::VectorXd& v) { return v; };
    bool reached = false;
    const Eigen::VectorXd dx = d::newton_krylov_step(guarded, r, scale, identity, rtol, 60, 1e-7, 1e-7, &reached);
    CHECK(reached);
    CHECK((r + J * dx).norm() <= rtol * r.norm());
  }
}

TEST_CASE("newton_krylov_step: the products move the unknowns by relative_step in the root mean square, none beyond "
          "max_relative_step") {
  const Eigen::MatrixXd A = matrix();
  Eigen::VectorXd x(m), scale(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    x[i] = 0.3 * std::sin(double(2 * i + 1));
    scale[i] = i < 2 ? 1e-4 : 1.0;  // two unknowns with scales far below the others'
  }
  const Eigen::VectorXd r = F(A, x);
  const auto identity = [](const Eigen::VectorXd& v) { return v; };
  // The relative moves of every product (dx / scale), rms and largest.
  std::vector<std::pair<double, double>> moves;
  const auto moved = [&](const Eigen::VectorXd& dx) {
    const Eigen::ArrayXd move = dx.array() / scale.array();
    moves.emplace_back(std::sqrt(move.square().mean()), move.abs().maxCoeff());
    return F(A, x + dx);
  };
  // (Relative to the step: the rms and the cap are each met to rounding.)
  constexpr double rounding = 1e-12;
  SUBCASE("the cap not reached: the root mean square is relative_step") {
    d::newton_krylov_step(moved, r, scale, identity, rtol, 6, 1e-7, 1e-3);
    REQUIRE(moves.size() >= 6);
    for (const auto& [rms, largest] : moves) {
      CHECK(std::abs(rms - 1e-7) <= rounding * 1e-7);
      CHECK(largest <= 1e-3 * (1 + rounding));
      CHECK(largest > 1e-7);  // the small-scale unknowns move by more than relative_step of theirs
    }
  }
  SUBCASE("max_relative_step = relative_step: no unknown moves by more than it") {
    d::newton_krylov_step(moved, r, scale, identity, rtol, 6, 1e-7, 1e-7);
    REQUIRE(moves.size() >= 6);
    for (const auto& [rms, largest] : moves) {
      CHECK(std::abs(largest - 1e-7) <= rounding * 1e-7);
      CHECK(rms < 1e-7);
    }
  }
}
