#include "simulation/daylight_criteria.hpp"

#include <cmath>

#include "geometry/error.hpp"

namespace daylit {

En17037Assessment en17037_df_method(const std::vector<double>& df_percent, double median_diffuse_lux) {
  if (!(median_diffuse_lux > 0) || !std::isfinite(median_diffuse_lux))
    throw Error("the median diffuse illuminance must be a positive number of lux");
  if (df_percent.empty()) throw Error("EN 17037: a grid without sensors");
  // EN 17037:2018, Table A.1: target illuminance E_T over 50 % of the reference plane and minimum
  // target illuminance E_TM over 95 %, for the three levels of recommendation.
  struct Row {
    const char* name;
    double e_t, e_tm;
  };
  static const Row kTable[] = {{"minimum", 300, 100}, {"medium", 500, 300}, {"high", 750, 500}};
  En17037Assessment a;
  a.median_diffuse_lux = median_diffuse_lux;
  a.level_met = "none";
  const auto share_at_or_above = [&](double threshold) {
    std::size_t n = 0;
    for (const double df : df_percent) n += df >= threshold;
    return double(n) / double(df_percent.size());
  };
  for (const Row& row : kTable) {
    En17037Level level;
    level.name = row.name;
    level.target_lux = row.e_t;
    level.minimum_target_lux = row.e_tm;
    level.target_df = 100 * row.e_t / median_diffuse_lux;
    level.minimum_target_df = 100 * row.e_tm / median_diffuse_lux;
    level.share_at_target = share_at_or_above(level.target_df);
    level.share_at_minimum_target = share_at_or_above(level.minimum_target_df);
    level.met = level.share_at_target >= 0.5 && level.share_at_minimum_target >= 0.95;
    if (level.met) a.level_met = level.name;
    a.levels.push_back(level);
  }
  return a;
}

}  // namespace daylit
