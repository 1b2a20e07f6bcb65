#include "simulation/dense_lu.hpp"

#include <algorithm>
#include <string>

#include "geometry/error.hpp"
#include "simulation/openblas.hpp"

namespace daylit {

namespace {

// The width of every triangular solve (see DenseLU::solve).
constexpr Eigen::Index kColumns = 128;

int lapack_size(Eigen::Index n) { return blas_int(n, "dense LU: unknowns"); }

}  // namespace

DenseLU::DenseLU(Eigen::MatrixXd a, int threads) : lu_(std::move(a)) {
  if (lu_.rows() != lu_.cols()) throw Error("dense LU: the matrix is not square");
  const int n = lapack_size(lu_.rows());
  pivots_.assign(std::size_t(n), 0);
  if (n == 0) return;
  openblas_set_num_threads(threads);
  int info = 0;
  dgetrf_(&n, &n, lu_.data(), &n, pivots_.data(), &info);
  if (info < 0) throw Error("dense LU: dgetrf's argument " + std::to_string(-info) + " is invalid");
  if (info > 0) throw Error("dense LU: the matrix is singular (pivot " + std::to_string(info) + " is 0)");
}

Eigen::MatrixXd DenseLU::solve(Eigen::MatrixXd b, std::size_t first_column) const {
  if (b.rows() != lu_.rows()) throw Error("dense LU: the right-hand side has the wrong number of rows");
  if (lu_.rows() == 0 || b.cols() == 0) return b;
  // P B, then L⁻¹ and U⁻¹ by OpenBLAS's dtrsm on blocks of exactly kColumns columns, one after
  // another. The blocks are those of the larger system (columns k·kColumns … (k+1)·kColumns − 1),
  // the places of columns not in B filled with zeros, so that a column always takes the same
  // place in a call of the same width. That is what makes its digits its own: OpenBLAS's kernels
  // treat the places of a block differently (on an AVX-512 processor the last 8 of 128 columns
  // are summed in another order than the first 120; on Haswell, not), and dgetrs on all the
  // columns at once would also split them between threads by their number. One thread: two
  // split each block's columns between them (64 and 64), which on this machine's kernel gives
  // the same digits and 1.65 times the speed (the office sample's 10,380 nodes, 300 sensors:
  // 2.02 → 1.22 s, 2026-12-07), but on a kernel that treats the last places of a block otherwise
  // (AVX-512's) would make a column's digits depend on the threads (--threads 1 against more,
  // an MPI rank's against one process's). Not the blocks spread over threads either: OpenBLAS's
  // OpenMP build does not promise that concurrent calls from other threads are safe.
  for (Eigen::Index i = 0; i < lu_.rows(); ++i) {
    const Eigen::Index p = pivots_[std::size_t(i)] - 1;  // LAPACK's pivots count from 1
    if (p != i) b.row(i).swap(b.row(p));
  }
  const int n = lapack_size(lu_.rows()), width = int(kColumns);
  openblas_set_num_threads(1);
  Eigen::MatrixXd x(lu_.rows(), kColumns);
  // `place`: the place in its block of B's column `first`.
  Eigen::Index first = 0, place = Eigen::Index(first_column % std::size_t(kColumns));
  while (first < b.cols()) {
    const Eigen::Index count = std::min(kColumns - place, b.cols() - first);
    x.setZero();
    x.middleCols(place, count) = b.middleCols(first, count);
    const double one = 1;
    dtrsm_("L", "L", "N", "U", &n, &width, &one, lu_.data(), &n, x.data(), &n, 1, 1, 1, 1);
    dtrsm_("L", "U", "N", "N", &n, &width, &one, lu_.data(), &n, x.data(), &n, 1, 1, 1, 1);
    b.middleCols(first, count) = x.middleCols(place, count);
    first += count;
    place = 0;
  }
  return b;
}

}  // namespace daylit
