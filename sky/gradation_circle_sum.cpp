#include "sky/gradation_circle_sum.hpp"

#include <cmath>

#include "illumination/vector_math.hpp"

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
