#include "simulation/daylight_criteria.hpp"

#include <algorithm>
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

BreeamHea01 breeam_hea01(const SensorGrid& grid, const std::vector<double>& df_percent, const PlanDrawing& plan,
                         double band) {
  if (df_percent.size() != grid.sensors.size()) throw Error("BREEAM Hea 01: one daylight factor per sensor is needed");
  BreeamHea01 b;
  b.band = band;
  double sum = 0, least = 0;
  for (std::size_t i = 0; i < grid.sensors.size(); ++i) {
    const Vec3& p = grid.sensors[i].position;
    if (plan_distance(plan.walls, p.x, p.y) < band) {
      ++b.sensors_in_band;
      continue;
    }
    least = b.sensors == 0 ? df_percent[i] : std::min(least, df_percent[i]);
    sum += df_percent[i];
    ++b.sensors;
  }
  if (b.sensors > 0) {
    b.average_df = sum / double(b.sensors);
    b.minimum_df = least;
    b.uniformity = *b.average_df > 0 ? least / *b.average_df : 0.0;
  }
  return b;
}

}  // namespace daylit
