#include "simulation/direction_angles.hpp"

#include <cmath>
#include <numbers>

#if defined(DAYLIT_LIBMVEC)
// As in sky/circumsolar_sum.cpp: glibc declares the vector variants only under -ffast-math.
extern "C" {
__attribute__((simd("notinbranch"))) double asin(double) noexcept;
__attribute__((simd("notinbranch"))) double atan2(double, double) noexcept;
}
#define DAYLIT_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define DAYLIT_VECTOR_CLONES
#endif

namespace daylit {

DAYLIT_VECTOR_CLONES
void altitude_azimuth(const double* x, const double* y, const double* z, double* altitude, double* azimuth,
                      std::size_t n) noexcept {
  constexpr double two_pi = 2 * std::numbers::pi;
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) {
    const double up = z[i] > 0.0 ? z[i] : 0.0;
    const double s = up < 1.0 ? up : 1.0;
    const double a = atan2(y[i], x[i]);
    altitude[i] = asin(s);
    azimuth[i] = a + (a < 0.0 ? two_pi : 0.0);
  }
}

}  // namespace daylit
