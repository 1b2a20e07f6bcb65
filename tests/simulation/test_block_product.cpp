// The fixed-block product (simulation/block_product.hpp): against a product in long double
// (Eigen's, over 11 more bits), and each row's digits its own — the same computed with the whole
// grid's rows or with any block of them at its place, as an MPI rank's block is.

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>

#include "geometry/error.hpp"
#include "illumination/xoshiro256.hpp"
#include "simulation/block_product.hpp"

using namespace daylit;

namespace {

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  Xoshiro256 random(seed);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = random.uniform();
  return m;
}

// Rows first … first + a.rows() − 1 of a larger system, in their blocks (RowBlocks).
Eigen::MatrixXd in_blocks(const Eigen::MatrixXd& a, std::size_t first) {
  const RowBlocks blocks(a.rows(), first);
  Eigen::MatrixXd padded = Eigen::MatrixXd::Zero(blocks.height, a.cols());
  padded.middleRows(blocks.offset, a.rows()) = a;
  return padded;
}

}  // namespace

TEST_CASE("the block product's rows lie in whole blocks aligned to the larger system") {
  CHECK(RowBlocks(0, 0).height == 0);
  CHECK(RowBlocks(1, 0).offset == 0);
  CHECK(RowBlocks(1, 0).height == kProductRows);
  CHECK(RowBlocks(kProductRows, 0).height == kProductRows);
  CHECK(RowBlocks(kProductRows + 1, 0).height == 2 * kProductRows);
  CHECK(RowBlocks(27, 54).offset == 54);
  CHECK(RowBlocks(100, 100).height == 2 * kProductRows);  // places 100 … 199
  CHECK(RowBlocks(5, 3 * std::size_t(kProductRows) + 7).offset == 7);
}

TEST_CASE("the block product is the product, and each row's digits do not depend on the rows computed with it") {
  // Sizes of the annual hourly products' shape (sensors × kept directions or lit nodes, times a
  // block of hours), large enough for OpenBLAS's blocked paths; 300 rows span three blocks.
  const Eigen::Index rows = 300, inner = 1100, hours = 128;
  const Eigen::MatrixXd a = random_matrix(rows, inner, 1), b = random_matrix(inner, hours, 2);
  const Eigen::MatrixXd all = block_product(in_blocks(a, 0), b);
  // Against long double: entries are sums of 1,100 products of numbers in [0, 1), each summed
  // with a relative error below inner × ε (Higham, Accuracy and Stability, §3.1): 1e-12 is a
  // margin of four over 1100 × 2.2e-16.
  const Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> exact =
      a.cast<long double>() * b.cast<long double>();
  CHECK(((all.topRows(rows).cast<long double>() - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff()) < 1e-12L);
  // Every row alone at its place, and blocks that start anywhere and straddle the blocks.
  for (Eigen::Index i = 0; i < rows; ++i) {
    INFO("row " << i << " alone");
    const Eigen::MatrixXd one = block_product(in_blocks(a.middleRows(i, 1), std::size_t(i)), b);
    CHECK(one.row(RowBlocks(1, std::size_t(i)).offset) == all.row(i));
  }
  for (const Eigen::Index first : {Eigen::Index(0), Eigen::Index(27), Eigen::Index(127), Eigen::Index(128), Eigen::Index(250)})
    for (const Eigen::Index count : {Eigen::Index(1), Eigen::Index(26), Eigen::Index(50)}) {
      if (first + count > rows) continue;
      INFO("rows " << first << " to " << first + count - 1);
      const RowBlocks blocks(count, std::size_t(first));
      const Eigen::MatrixXd part = block_product(in_blocks(a.middleRows(first, count), std::size_t(first)), b);
      CHECK(part.middleRows(blocks.offset, count) == all.middleRows(first, count));
    }
}

TEST_CASE("the block product refuses matrices that do not match or are not whole blocks") {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Zero(kProductRows, 3), b = Eigen::MatrixXd::Zero(4, 2);
  CHECK_THROWS_WITH(block_product(a, b), Catch::Contains("do not match"));
  CHECK_THROWS_WITH(block_product(Eigen::MatrixXd::Zero(5, 4), b), Catch::Contains("whole blocks"));
}
