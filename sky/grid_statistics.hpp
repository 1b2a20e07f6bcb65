#pragma once
// Summary statistics of daylight factors over a sensor grid, as daylighting standards use them.

#include <array>
#include <vector>

namespace daylit {

struct GridStatistics {
  std::size_t count = 0;
  double mean = 0, median = 0, min = 0, max = 0;
  double min_over_mean = 0;    // uniformity (a ratio, not a percentage); 0 when the mean is 0
  double min_over_median = 0;  // likewise
  // Share of sensors (0..1) with DF at or above 1, 2, 3 and 5 %.
  static constexpr std::array<double, 4> kThresholds{1, 2, 3, 5};
  std::array<double, 4> share_at_or_above{};
};

GridStatistics grid_statistics(const std::vector<double>& df_percent);

}  // namespace daylit
