#include "simulation/grid_statistics.hpp"

#include <algorithm>
#include <numeric>

namespace daylit {

GridStatistics grid_statistics(const std::vector<double>& values, const std::vector<double>& thresholds) {
  GridStatistics s;
  s.thresholds = thresholds;
  s.share_at_or_above.assign(thresholds.size(), 0.0);
  s.count = values.size();
  if (s.count == 0) return s;
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  s.min = sorted.front();
  s.max = sorted.back();
  s.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / double(s.count);
  const std::size_t h = s.count / 2;
  s.median = s.count % 2 ? sorted[h] : 0.5 * (sorted[h - 1] + sorted[h]);
  s.min_over_mean = s.mean > 0 ? s.min / s.mean : 0;
  s.min_over_median = s.median > 0 ? s.min / s.median : 0;
  for (std::size_t t = 0; t < thresholds.size(); ++t) {
    const auto first = std::lower_bound(sorted.begin(), sorted.end(), thresholds[t]);
    s.share_at_or_above[t] = double(sorted.end() - first) / double(s.count);
  }
  return s;
}

}  // namespace daylit
