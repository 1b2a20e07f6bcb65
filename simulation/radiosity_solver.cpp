#include "simulation/radiosity_solver.hpp"

#include <algorithm>
#include <cmath>

namespace daylit {

RadiositySolution solve_radiosity(const std::vector<TransportRow>& rows, const std::vector<double>& reflectance,
                                  const std::vector<double>& source, const SweepOptions& options) {
  const int max_sweeps = options.max_sweeps;
  const double over_relaxation = options.over_relaxation;
  RadiositySolution s;
  s.exitance = options.start.size() == source.size() ? options.start : source;
  const std::size_t n = rows.size();
  for (s.sweeps = 1; s.sweeps <= max_sweeps; ++s.sweeps) {
    double change = 0, size = 0;
    for (std::size_t i = 0; i < n; ++i) {
      double e = 0;
      for (const auto& [j, k] : rows[i]) e += k * s.exitance[j];
      const double gauss_seidel = source[i] + reflectance[i] * e;
      const double m = over_relaxation == 1.0 ? gauss_seidel : s.exitance[i] + over_relaxation * (gauss_seidel - s.exitance[i]);
      change = std::max(change, std::abs(m - s.exitance[i]));
      size = std::max(size, std::abs(m));
      s.exitance[i] = m;
    }
    s.last_change = size > 0 ? change / size : 0;
    if (change <= 1e-15 * size) break;
    // Rows whose sums exceed 1 (a model whose surfaces overlap) can make the sweeps grow without
    // bound: stop there rather than sweep on to infinity; the caller checks `converged`.
    if (!std::isfinite(size) || size > 1e150) break;
  }
  s.sweeps = std::min(s.sweeps, max_sweeps);
  s.converged = s.sweeps < max_sweeps && std::isfinite(s.last_change) && s.last_change <= 1e-15;
  for (double m : s.exitance) s.converged = s.converged && std::isfinite(m);
  return s;
}

}  // namespace daylit
