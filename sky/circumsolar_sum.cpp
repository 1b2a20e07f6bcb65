#include "sky/circumsolar_sum.hpp"

#include <cmath>

#if defined(DAYLIT_LIBMVEC)
// glibc declares these vector variants only under -ffast-math (bits/math-vector.h); declaring them
// here lets the loop below use them without fast-math's licence to reorder everything else.
extern "C" {
__attribute__((simd("notinbranch"))) double exp(double) noexcept;
__attribute__((simd("notinbranch"))) double acos(double) noexcept;
}
#define DAYLIT_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define DAYLIT_VECTOR_CLONES
#endif

namespace daylit {

namespace {

DAYLIT_VECTOR_CLONES
double sum(const double* x, const double* y, const double* z, const double* w, std::size_t n, double sx, double sy,
           double sz, double a, double b, double d, double t_min) noexcept {
  double total = 0;
#pragma omp simd reduction(+ : total)
  for (std::size_t i = 0; i < n; ++i) {
    // Each select its own statement: nested, or on the sum, they keep GCC from vectorizing.
    const double t = z[i] > t_min ? z[i] : t_min;
    const double dot = sx * x[i] + sy * y[i] + sz * z[i];
    const double below = dot < -1.0 ? -1.0 : dot;
    const double cos_gamma = below > 1.0 ? 1.0 : below;
    total += w[i] * (1 + a * exp(b / t)) * exp(d * acos(cos_gamma));
  }
  return total;
}

DAYLIT_VECTOR_CLONES
void values(const double* x, const double* y, const double* z, std::size_t n, double sx, double sy, double sz, double a,
            double b, double c, double d, double t_min, double* out) noexcept {
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) {
    const double t = z[i] > t_min ? z[i] : t_min;
    const double dot = sx * x[i] + sy * y[i] + sz * z[i];
    const double below = dot < -1.0 ? -1.0 : dot;
    const double cos_gamma = below > 1.0 ? 1.0 : below;
    out[i] = c * (1 + a * exp(b / t)) * exp(d * acos(cos_gamma));
  }
}

}  // namespace

void circumsolar_values(const double* x, const double* y, const double* z, std::size_t n, const Vec3& sun, double a,
                        double b, double c, double d, double t_min, double* out) noexcept {
  values(x, y, z, n, sun.x, sun.y, sun.z, a, b, c, d, t_min, out);
  // Below the horizon there is no sky (there the vector pass may have made inf or NaN of b/0):
  // a select inside the loop above keeps GCC from vectorizing it, so it is a pass of its own.
  for (std::size_t i = 0; i < n; ++i)
    if (!(z[i] > 0)) out[i] = 0;
}

double circumsolar_sum(const DirectionNodes& nodes, std::size_t begin, std::size_t end, const Vec3& sun, double a,
                       double b, double c, double d, double t_min) noexcept {
  return c * sum(nodes.x.data() + begin, nodes.y.data() + begin, nodes.z.data() + begin, nodes.weight.data() + begin,
                 end - begin, sun.x, sun.y, sun.z, a, b, d, t_min);
}

double circumsolar_sum(const DirectionNodes& nodes, const Vec3& sun, double a, double b, double c, double d,
                       double t_min) noexcept {
  return circumsolar_sum(nodes, 0, nodes.size(), sun, a, b, c, d, t_min);
}

}  // namespace daylit
