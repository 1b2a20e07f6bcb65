#include "simulation/dense_lu.hpp"

#include <algorithm>
#include <string>


#include "geometry/error.hpp"

// LAPACK's and BLAS's Fortran interfaces (reference LAPACK's dgetrf.f, BLAS's dtrsm.f); OpenBLAS
// exports them.
extern "C" {
void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv, int* info);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb, std::size_t side_length,
            std::size_t uplo_length, std::size_t transa_length, std::size_t diag_length);
void openblas_set_num_threads(int threads);
}

namespace daylit {

namespace {

// The width of every triangular solve (see DenseLU::solve).
constexpr Eigen::Index kColumns = 128;

int lapack_size(Eigen::Index n) {
  if (n > Eigen::Index(1) << 30) throw Error("dense LU: " + std::to_string(n) + " unknowns is beyond LAPACK's int");
  return int(n);
}

}  // namespace

DenseLU::DenseLU(Eigen::MatrixXd a, int threads) : lu_(std::move(a)), threads_(threads) {
  if (lu_.rows() != lu_.cols()) throw Error("dense LU: the matrix is not square");
  const int n = lapack_size(lu_.rows());
  pivots_.assign(std::size_t(n), 0);
  if (n == 0) return;
  openblas_set_num_threads(threads_);
  int info = 0;
  dgetrf_(&n, &n, lu_.data(), &n, pivots_.data(), &info);
  if (info < 0) throw Error("dense LU: dgetrf's argument " + std::to_string(-info) + " is invalid");
  if (info > 0) throw Error("dense LU: the matrix is singular (pivot " + std::to_string(info) + " is 0)");
}

Eigen::MatrixXd DenseLU::solve(Eigen::MatrixXd b) const {
  if (b.rows() != lu_.rows()) throw Error("dense LU: the right-hand side has the wrong number of rows");
  if (lu_.rows() == 0 || b.cols() == 0) return b;
  // P B, then L⁻¹ and U⁻¹ by OpenBLAS's dtrsm on blocks of exactly kColumns columns (the last
  // padded with zeros), one after another on one thread. dgetrs on all the columns at once would
  // not do: OpenBLAS's kernels for a block's leftover columns, and its split of the columns
  // between threads, sum in other orders than its kernels for whole blocks, so a column's last
  // bits would depend on how many columns are solved with it. With every call the same width on
  // one thread, each column goes through the same kernels wherever it sits (the header's promise;
  // tested). One thread, not the blocks spread over threads: OpenBLAS's OpenMP build does not
  // promise that concurrent calls from other threads are safe, and one thread on blocks this wide
  // is about as fast as two on narrower ones (the solve streams the factors once per block:
  // 6,000 nodes, 640 columns: 1.0 s either way, 2026-12-06).
  for (Eigen::Index i = 0; i < lu_.rows(); ++i) {
    const Eigen::Index p = pivots_[std::size_t(i)] - 1;  // LAPACK's pivots count from 1
    if (p != i) b.row(i).swap(b.row(p));
  }
  const int n = lapack_size(lu_.rows()), width = int(kColumns);
  openblas_set_num_threads(1);
  Eigen::MatrixXd x(lu_.rows(), kColumns);
  for (Eigen::Index first = 0; first < b.cols(); first += kColumns) {
    const Eigen::Index count = std::min(kColumns, b.cols() - first);
    x.leftCols(count) = b.middleCols(first, count);
    x.rightCols(kColumns - count).setZero();
    const double one = 1;
    dtrsm_("L", "L", "N", "U", &n, &width, &one, lu_.data(), &n, x.data(), &n, 1, 1, 1, 1);
    dtrsm_("L", "U", "N", "N", &n, &width, &one, lu_.data(), &n, x.data(), &n, 1, 1, 1, 1);
    b.middleCols(first, count) = x.leftCols(count);
  }
  return b;
}

}  // namespace daylit
