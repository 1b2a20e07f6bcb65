#include "sky/circumsolar_sum.hpp"

#include <cmath>

#include "illumination/vector_math.hpp"

namespace daylit {

namespace {

// G(t) e^{dγ} at one direction, inlined into both vector loops. Each select its own statement:
// nested, or on the sum, they keep GCC from vectorizing.
[[gnu::always_inline]] inline double term(double x, double y, double z, double sx, double sy, double sz, double a,
                                          double b, double d, double t_min) noexcept {
  const double t = z > t_min ? z : t_min;
  const double dot = sx * x + sy * y + sz * z;
  const double below = dot < -1.0 ? -1.0 : dot;
  const double cos_gamma = below > 1.0 ? 1.0 : below;
  return (1 + a * exp(b / t)) * exp(d * acos(cos_gamma));
}

DAYLIT_VECTOR_CLONES
double sum(const double* x, const double* y, const double* z, const double* w, std::size_t n, double sx, double sy,
           double sz, double a, double b, double d, double t_min) noexcept {
  double total = 0;
#pragma omp simd reduction(+ : total)
  for (std::size_t i = 0; i < n; ++i) total += w[i] * term(x[i], y[i], z[i], sx, sy, sz, a, b, d, t_min);
  return total;
}

DAYLIT_VECTOR_CLONES
void values(const double* x, const double* y, const double* z, std::size_t n, double sx, double sy, double sz, double a,
            double b, double c, double d, double t_min, double* out) noexcept {
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) out[i] = c * term(x[i], y[i], z[i], sx, sy, sz, a, b, d, t_min);
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

}  // namespace daylit
