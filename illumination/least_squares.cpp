#include "illumination/least_squares.hpp"

#include <cmath>

namespace daylit {

std::vector<long double> least_squares(std::vector<long double> A, std::vector<long double> b, std::size_t m,
                                       std::size_t n) {
  std::vector<long double> scale(n, 1);
  for (std::size_t j = 0; j < n; ++j) {
    long double s = 0;
    for (std::size_t i = 0; i < m; ++i) s += A[i * n + j] * A[i * n + j];
    scale[j] = s > 0 ? 1 / std::sqrt(s) : 1;
    for (std::size_t i = 0; i < m; ++i) A[i * n + j] *= scale[j];
  }
  std::vector<long double> v(m);
  for (std::size_t k = 0; k < n; ++k) {
    long double norm = 0;
    for (std::size_t i = k; i < m; ++i) norm += A[i * n + k] * A[i * n + k];
    norm = std::sqrt(norm);
    const long double alpha = A[k * n + k] > 0 ? -norm : norm;
    for (std::size_t i = k; i < m; ++i) v[i] = A[i * n + k];
    v[k] -= alpha;
    long double vv = 0;
    for (std::size_t i = k; i < m; ++i) vv += v[i] * v[i];
    if (vv == 0) continue;
    for (std::size_t j = k; j < n; ++j) {
      long double s = 0;
      for (std::size_t i = k; i < m; ++i) s += v[i] * A[i * n + j];
      s = 2 * s / vv;
      for (std::size_t i = k; i < m; ++i) A[i * n + j] -= s * v[i];
    }
    long double s = 0;
    for (std::size_t i = k; i < m; ++i) s += v[i] * b[i];
    s = 2 * s / vv;
    for (std::size_t i = k; i < m; ++i) b[i] -= s * v[i];
  }
  std::vector<long double> x(n, 0);
  for (std::size_t k = n; k-- > 0;) {
    long double s = b[k];
    for (std::size_t j = k + 1; j < n; ++j) s -= A[k * n + j] * x[j];
    const long double diagonal = A[k * n + k];
    x[k] = std::abs(diagonal) > 1e-30L ? s / diagonal : 0;
  }
  for (std::size_t j = 0; j < n; ++j) x[j] *= scale[j];
  return x;
}

}  // namespace daylit
