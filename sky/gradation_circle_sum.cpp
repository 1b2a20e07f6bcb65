#include "sky/gradation_circle_sum.hpp"

#include <cmath>

#if defined(DAYLIT_LIBMVEC)
// As in circumsolar_sum.cpp: glibc declares the vector variants only under -ffast-math.
extern "C" {
__attribute__((simd("notinbranch"))) double exp(double) noexcept;
__attribute__((simd("notinbranch"))) double cos(double) noexcept;
}
#define DAYLIT_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define DAYLIT_VECTOR_CLONES
#endif

namespace daylit {

DAYLIT_VECTOR_CLONES
double gradation_circle_sum(const double* x, const double* w, std::size_t n, double psi_lo, double h, double A,
                            double B, double a, double b, double t_floor) noexcept {
  double total = 0;
#pragma omp simd reduction(+ : total)
  for (std::size_t j = 0; j < n; ++j) {
    const double raw = A + B * cos(psi_lo + h * x[j]);
    const double t = raw > 0.0 ? raw : 0.0;
    const double c = t > t_floor ? t : t_floor;
    total += w[j] * (1 + a * exp(b / c)) * t;
  }
  return total;
}

}  // namespace daylit
