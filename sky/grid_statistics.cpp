#include "sky/grid_statistics.hpp"

#include <algorithm>
#include <numeric>

namespace daylit {

GridStatistics grid_statistics(const std::vector<double>& df_percent) {
  GridStatistics s;
  s.count = df_percent.size();
  if (s.count == 0) return s;
  std::vector<double> sorted = df_percent;
  std::sort(sorted.begin(), sorted.end());
  s.min = sorted.front();
  s.max = sorted.back();
  s.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / double(s.count);
  const std::size_t h = s.count / 2;
  s.median = s.count % 2 ? sorted[h] : 0.5 * (sorted[h - 1] + sorted[h]);
  s.min_over_mean = s.mean > 0 ? s.min / s.mean : 0;
  s.min_over_median = s.median > 0 ? s.min / s.median : 0;
  for (std::size_t t = 0; t < GridStatistics::kThresholds.size(); ++t) {
    const auto first = std::lower_bound(sorted.begin(), sorted.end(), GridStatistics::kThresholds[t]);
    s.share_at_or_above[t] = double(sorted.end() - first) / double(s.count);
  }
  return s;
}

}  // namespace daylit
