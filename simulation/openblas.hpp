#pragma once
// LAPACK's and BLAS's Fortran interfaces as OpenBLAS exports them (reference LAPACK's dgetrf.f,
// BLAS's dgemm.f and dtrsm.f), for the dense LU and the fixed-block products, and the check that
// a size fits their int.

#include <Eigen/Core>

#include <cstddef>
#include <string>

#include "geometry/error.hpp"

extern "C" {
void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv, int* info);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc, std::size_t transa_length, std::size_t transb_length);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb, std::size_t side_length,
            std::size_t uplo_length, std::size_t transa_length, std::size_t diag_length);
void openblas_set_num_threads(int threads);
}

namespace daylit {

// n as the int the Fortran interfaces take; `what` names the caller and the count in the error.
inline int blas_int(Eigen::Index n, const std::string& what) {
  if (n > Eigen::Index(1) << 30) throw Error(what + ": " + std::to_string(n) + " is beyond LAPACK's and BLAS's int");
  return int(n);
}

}  // namespace daylit
