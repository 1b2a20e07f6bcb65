#include "simulation/block_product.hpp"

#include "geometry/error.hpp"
#include "simulation/openblas.hpp"

namespace daylit {

namespace {

int blas_size(Eigen::Index n) { return blas_int(n, "block product: size"); }

}  // namespace

RowBlocks::RowBlocks(Eigen::Index rows, std::size_t first)
    : offset(Eigen::Index(first % std::size_t(kProductRows))),
      height((offset + rows + kProductRows - 1) / kProductRows * kProductRows) {}

Eigen::MatrixXd block_product(const Eigen::Ref<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>& a,
                              const Eigen::MatrixXd& b) {
  if (a.cols() != b.rows()) throw Error("block product: the matrices do not match");
  if (a.rows() % kProductRows != 0) throw Error("block product: the rows are not whole blocks");
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(a.rows(), b.cols());
  if (a.rows() == 0 || b.cols() == 0 || a.cols() == 0) return c;
  openblas_set_num_threads(1);
  const int m = int(kProductRows), n = blas_size(b.cols()), k = blas_size(a.cols());
  const int lda = blas_size(a.outerStride()), ldb = blas_size(b.rows()), ldc = blas_size(c.rows());
  const double one = 1, zero = 0;
  for (Eigen::Index first = 0; first < a.rows(); first += kProductRows)
    dgemm_("N", "N", &m, &n, &k, &one, a.data() + first, &lda, b.data(), &ldb, &zero, c.data() + first, &ldc, 1, 1);
  return c;
}

}  // namespace daylit
