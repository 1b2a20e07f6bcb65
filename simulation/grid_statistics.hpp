#pragma once
// Summary statistics of a quantity over a sensor grid (daylight factor in %, illuminance in lux),
// as daylighting standards use them.

#include <vector>

namespace daylit {

// Thresholds of the shares reported: DF 1, 2, 3 and 5 % (BS 8206-2, BREEAM, EN 17037's targets
// for the daylight factor), and illuminance 100, 300, 500 and 750 lux (EN 17037's minimum and
// target illuminances).
inline const std::vector<double> kDaylightFactorThresholds{1, 2, 3, 5};
inline const std::vector<double> kIlluminanceThresholds{100, 300, 500, 750};

struct GridStatistics {
  std::size_t count = 0;
  double mean = 0, median = 0, min = 0, max = 0;
  double min_over_mean = 0;    // uniformity (a ratio, not a percentage); 0 when the mean is 0
  double min_over_median = 0;  // likewise
  std::vector<double> thresholds;
  std::vector<double> share_at_or_above;  // share of sensors (0..1) at or above each threshold
};

GridStatistics grid_statistics(const std::vector<double>& values,
                               const std::vector<double>& thresholds = kDaylightFactorThresholds);

}  // namespace daylit
