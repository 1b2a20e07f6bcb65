// The dense LU (simulation/dense_lu.hpp) against an independent solve in long double (Eigen's
// PartialPivLU over long double: another algorithm's code and 11 more bits), on matrices of the
// reflected components' form (I − ρK)ᵀ, K's rows non-negative and summing to at most 1.

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "geometry/error.hpp"
#include "illumination/xoshiro256.hpp"
#include "simulation/dense_lu.hpp"

using namespace daylit;

namespace {

// (I − ρK)ᵀ of n nodes: each row of K random, non-negative, summing to `view` (a node's view of
// the room's surfaces), each node's ρ in [0, rho_max].
Eigen::MatrixXd reflection_matrix(int n, double rho_max, double view, std::uint64_t seed) {
  Xoshiro256 random(seed);
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd k(n);
    for (int j = 0; j < n; ++j) k(j) = j == i ? 0.0 : random.uniform();
    k *= view / k.sum();
    const double rho = rho_max * random.uniform();
    for (int j = 0; j < n; ++j) a(j, i) -= rho * k(j);
  }
  return a;
}

Eigen::MatrixXd random_columns(int n, int m, std::uint64_t seed) {
  Xoshiro256 random(seed);
  Eigen::MatrixXd b(n, m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) b(i, j) = random.uniform();
  return b;
}

}  // namespace

TEST_CASE("the dense LU solves the reflection system as long double does, to its condition times n epsilon") {
  using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  for (const double rho_max : {0.5, 0.95, 0.999}) {
    const int n = 400, m = 9;
    const Eigen::MatrixXd a = reflection_matrix(n, rho_max, 1.0, 7);
    const Eigen::MatrixXd b = random_columns(n, m, 11);
    const Eigen::MatrixXd x = DenseLU(a, 2).solve(b);
    const LongMatrix reference = a.cast<long double>().partialPivLu().solve(b.cast<long double>());
    // Forward error ≤ κ∞(A) × backward error; partial pivoting's backward error is at most about
    // 2n ε g with growth g ≤ 2 for a matrix diagonally dominant by columns (Golub and Van Loan
    // §3.4.6), and κ∞ ≤ (1 + ρ)/(1 − ρ) for rows of K summing to 1: 3, 39 and 1,999 here.
    const double kappa = (1 + rho_max) / (1 - rho_max);
    const double bound = kappa * 2 * n * 2 * 0x1p-53;
    const double error = double((x.cast<long double>() - reference).cwiseAbs().maxCoeff() /
                                reference.cwiseAbs().maxCoeff());
    INFO("rho_max " << rho_max << ": error " << error << ", bound " << bound);
    CHECK(error <= bound);
  }
}

TEST_CASE("a column of the dense LU's solution depends on its index only, not on the columns solved with it") {
  // How an MPI run stays bit-identical to one process: each rank solves its own block of a
  // grid's sensors, starting at the block's index. Large enough for OpenBLAS's blocked paths (its
  // blocks are a few hundred wide). OpenBLAS's kernels treat the places of a 128-column block
  // differently on some processors (AVX-512: the last 8), so this fails if the blocks are not
  // those of the whole system.
  const int n = 700;
  const DenseLU lu(reflection_matrix(n, 0.9, 0.98, 3), 2);
  const Eigen::MatrixXd b = random_columns(n, 300, 5);
  const Eigen::MatrixXd all = lu.solve(b);
  // Every place a column can take in a block of the solve (128 wide), alone, and blocks of
  // columns that start anywhere and straddle the solve's blocks.
  for (int first = 0; first < 300; ++first) {
    INFO("column " << first << " alone");
    CHECK(lu.solve(b.col(first), std::size_t(first)) == all.col(first));
  }
  for (const int first : {0, 13, 120, 127, 128, 150, 299})
    for (const int count : {1, 5, 8, 140}) {
      if (first + count > b.cols()) continue;
      INFO("columns " << first << " to " << first + count - 1);
      const Eigen::MatrixXd part = lu.solve(b.middleCols(first, count), std::size_t(first));
      CHECK(part == all.middleCols(first, count));
    }
  // A grid's block of an MPI run: the columns' indices in the grid counted from its start.
  const Eigen::MatrixXd tail = lu.solve(b.rightCols(100), 200);
  CHECK(tail == all.rightCols(100));
}

TEST_CASE("the dense LU's solution does not depend on the number of threads") {
  // A run's results do not depend on --threads: OpenBLAS splits the factorisation's products
  // between threads by blocks of the result, each entry summed in one order; the solves run on
  // one thread whatever the factorisation had (300 columns: every place of a 128-column block).
  const int n = 1500;
  const Eigen::MatrixXd a = reflection_matrix(n, 0.9, 0.98, 3);
  const Eigen::MatrixXd b = random_columns(n, 300, 5);
  const Eigen::MatrixXd one = DenseLU(a, 1).solve(b), two = DenseLU(a, 2).solve(b);
  for (Eigen::Index j = 0; j < b.cols(); ++j) {
    INFO("column " << j);
    CHECK(one.col(j) == two.col(j));
  }
}

TEST_CASE("the dense LU refuses a singular matrix and mismatched right-hand sides") {
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(4, 4);
  a(2, 2) = 0;
  CHECK_THROWS_WITH(DenseLU(a, 1), Catch::Contains("singular"));
  CHECK_THROWS_WITH(DenseLU(Eigen::MatrixXd::Zero(3, 4), 1), Catch::Contains("not square"));
  const DenseLU lu(Eigen::MatrixXd::Identity(4, 4), 1);
  CHECK_THROWS_WITH(lu.solve(Eigen::MatrixXd::Zero(5, 1)), Catch::Contains("rows"));
  CHECK(lu.solve(Eigen::MatrixXd::Zero(4, 0)).cols() == 0);
}
