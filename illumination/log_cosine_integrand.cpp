#include "illumination/log_cosine_integrand.hpp"

#include <cmath>

#include "illumination/vector_math.hpp"

namespace daylit::rational {

namespace {

DAYLIT_VECTOR_CLONES
void values(const double* t, std::size_t n, double kappa2, double c2, double* out) noexcept {
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) {
    const double q = kappa2 + t[i] * t[i];
    out[i] = -log1p(q / c2) / (2 * q);
  }
}

}  // namespace

void log_cosine_integrand(const double* t, std::size_t n, double kappa2, double c2, double* out) noexcept {
  const std::size_t whole = (n + 3) / 4 * 4;
  values(t, whole, kappa2, c2, out);
  // Q = 0 (κ = 0 at t = 0), where the quotient is 0/0: its limit. A select inside the loop above
  // keeps GCC from vectorizing it, so it is a pass of its own.
  for (std::size_t i = 0; i < n; ++i)
    if (kappa2 + t[i] * t[i] == 0) out[i] = -0.5 / c2;
}

}  // namespace daylit::rational
