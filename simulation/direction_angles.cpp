#include "simulation/direction_angles.hpp"

#include <cmath>
#include <numbers>

#include "illumination/vector_math.hpp"

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
