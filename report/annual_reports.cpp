#include "report/annual_reports.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "geometry/error.hpp"
#include "report/model_reports.hpp"
#include "report/reports.hpp"

namespace daylit::cli {

void write_annual_csv(std::FILE* out, const std::vector<AnnualGridReport>& grids) {
  fmt::print(out,
             "grid,index,x,y,z,dx,dy,dz,direct_sun_hours,da_300_percent,cda_300_percent,udi_fell_short_percent,"
             "udi_supplementary_percent,udi_autonomous_percent,udi_exceeded_percent,en17037_sensor_hours_at_100_percent,"
             "en17037_sensor_hours_at_300_percent,en17037_sensor_hours_at_500_percent,en17037_sensor_hours_at_750_percent,"
             "max_hour_bound_lux\n");
  for (const auto& g : grids) {
    for (std::size_t i = 0; i < g.grid->sensors.size(); ++i) {
      const Sensor& s = g.grid->sensors[i];
      const SensorMetrics& m = g.sensors[i];
      fmt::print(out, "{},{},{},{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.3g}\n",
                 g.grid->name, i, s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z,
                 m.direct_sun_hours, m.da_300_percent, m.cda_300_percent, m.udi_fell_short_percent,
                 m.udi_supplementary_percent, m.udi_autonomous_percent, m.udi_exceeded_percent,
                 m.en17037_hours_at_100_percent, m.en17037_hours_at_300_percent, m.en17037_hours_at_500_percent,
                 m.en17037_hours_at_750_percent, g.result.max_bound_lux[i]);
    }
  }
}

void write_annual_csv(const std::string& path, const std::vector<AnnualGridReport>& grids) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) throw Error(path + ": cannot open for writing");
  write_annual_csv(out, grids);
  const bool failed = std::ferror(out) != 0;
  if (std::fclose(out) != 0 || failed) throw Error(path + ": cannot write CSV");
}

void write_temporal_map(const std::string& path, const AnnualGridReport& g, const AnnualSky& sky) {
  // Day of the year from the month and day (29 February, where a file has it, is its own day).
  constexpr int kBefore[12] = {0, 31, 60, 91, 121, 152, 182, 213, 244, 274, 305, 335};
  SensorGrid cells;
  cells.name = g.grid->name;
  GridReport r;
  r.grid = &cells;
  for (std::size_t h = 0; h < g.result.hours; ++h) {
    const WeatherRecord& rec = *sky.hours[h].record;
    const int day = kBefore[rec.month - 1] + rec.day - 1;
    // Hour cells 5 days tall, so that the map is about 365 × 120 cells wide and high.
    cells.sensors.push_back({{double(day), 5.0 * (sky.hours[h].hour_ending - 1), 0}, {0, 0, 1}});
    double mean = 0;
    for (std::size_t i = 0; i < g.result.sensors; ++i) mean += g.result.illuminance[i * g.result.hours + h];
    r.shown.push_back(g.result.sensors ? mean / double(g.result.sensors) : 0.0);
  }
  r.shown_title = "Grid-mean illuminance (lux) by hour";
  r.cell_noun = "hours";
  r.footer = "temporal map: day of the year along x (1 January at the left), hour of the day along y (midnight at the bottom)";
  r.shown_unit = "lux";
  r.statistics = grid_statistics(r.shown, kIlluminanceThresholds);
  write_falsecolour_image(path, r);
}

nlohmann::json annual_grid_json(const AnnualGridReport& g, const std::vector<std::string>& group_names) {
  const GridMetrics& m = g.metrics;
  nlohmann::json en = nlohmann::json::array();
  for (const En17037IlluminanceLevel& l : m.en17037)
    en.push_back({{"level", l.name},
                  {"target_lux", l.target_lux},
                  {"minimum_target_lux", l.minimum_target_lux},
                  {"hours_target_met_percent", l.hours_target_met_percent},
                  {"hours_minimum_target_met_percent", l.hours_minimum_met_percent},
                  {"pass", l.pass},
                  {"per_sensor_variant",
                   {{"sensors_reaching_target_percent", l.sensors_target_percent},
                    {"sensors_reaching_minimum_target_percent", l.sensors_minimum_percent},
                    {"pass", l.pass_per_sensor}}}});
  std::string en_level = "none";
  for (const En17037IlluminanceLevel& l : m.en17037)
    if (l.pass) en_level = l.name;
  double worst_bound = 0, worst_relative = 0;
  for (std::size_t i = 0; i < g.result.sensors; ++i) {
    worst_bound = std::max(worst_bound, g.result.max_bound_lux[i]);
    worst_relative = std::max(worst_relative, g.result.max_bound_relative[i]);
  }
  nlohmann::json blinds = nlohmann::json::array();
  for (std::size_t k = 0; k < g.result.groups; ++k) {
    std::size_t closed = 0;
    for (std::size_t h = 0; h < g.result.hours; ++h) closed += g.result.blinds_closed[h * g.result.groups + k];
    blinds.push_back({{"window_group", group_names[k]}, {"hours_closed", closed}});
  }
  const double sensor_years = double(g.result.sensors);
  nlohmann::json reflected = "not computed (--components sc)";
  if (g.result.reflections) {
    double worst = 0, worst_relative_reflected = 0;
    for (std::size_t i = 0; i < g.result.sensors; ++i) {
      worst = std::max(worst, g.result.max_reflection_estimate_lux[i]);
      worst_relative_reflected = std::max(worst_relative_reflected, g.result.max_reflection_estimate_relative[i]);
    }
    reflected = {{"share_of_occupied_illuminance", g.result.reflected_share},
                 {"max_estimate_lux", worst},
                 {"max_estimate_relative", worst_relative_reflected},
                 {"max_estimate_relative_over", "sensor-hours of at least 100 lx"},
                 {"estimate_is", "per sensor and hour: |fine - half-resolution direction grid| + |fine - mesh of elements "
                                 "twice as large|, with the hour's largest blinds factor; an estimate, not a bound"}};
  }
  return {{"name", g.grid->name},
          {"path", g.grid->path},
          {"count", g.result.sensors},
          {"sees_sky_directly", g.grid->sees_sky_directly},
          {"sda_300_50_percent", m.sda_300_50_percent},
          {"ase_1000_250_percent", m.ase_1000_250_percent},
          {"mean_da_300_percent", m.mean_da_300_percent},
          {"mean_udi_autonomous_percent", m.mean_udi_autonomous_percent},
          {"leed_v4_1",
           {{"sda_points", m.leed_sda_points},
            {"thresholds", "sDA300/50% >= 40 %: 1 point, >= 55 %: 2, >= 75 %: 3"},
            {"ase_1000_250_at_most_10_percent", m.leed_ase_at_most_10_percent}}},
          {"en17037_illuminance_method",
           {{"levels", en},
            {"level_reached", en_level},
            {"reading", "each daylight hour its own spatial test (target over >= 50 % of the sensors, minimum target "
                        "over >= 95 %), passed when both hold in >= 50 % of the daylight hours; the per-sensor variant "
                        "counts each sensor's hours first"}}},
          {"occupied_hours", m.occupied_hours},
          {"daylight_hours", m.daylight_hours},
          {"blinds", blinds},
          {"per_hour_bound",
           {{"max_lux", worst_bound},
            {"max_relative", worst_relative},
            {"what", "per sensor and hour: the gradation fit's sampled maximum error over the u_z range the sensor sees "
                     "times (1 + |e|) times its lambert weight, plus the moments' two-order difference, plus the "
                     "circumsolar cubature's estimate, all in lux"}}},
          {"reflected", reflected},
          {"moment_error_relative_max", g.result.max_moment_error},
          {"circumsolar_adaptive_sensor_hours", g.result.adaptive_circumsolar},  // any piece by cubature
          {"run_time_s", {{"coefficients", g.result.coefficient_time_s}, {"hourly", g.result.hourly_time_s}}},
          {"run_time_per_sensor_year_ms",
           sensor_years > 0 ? 1e3 * (g.result.coefficient_time_s + g.result.hourly_time_s) / sensor_years : 0.0},
          {"left_out", counters_json(g.result.counters)}};
}

nlohmann::json annual_sky_json(const AnnualSky& sky, const AnnualOptions& options) {
  std::map<std::string, std::size_t> skipped;
  for (const AnnualHour& h : sky.hours)
    if (!h.sky) ++skipped[h.skipped.rfind("refused", 0) == 0 ? "refused by the published model (--perez-clamps none)" : h.skipped];
  nlohmann::json clamps = nlohmann::json::object();
  for (const auto& [line, count] : sky.clamp_counts) clamps[line] = count;
  return {{"model", "Perez all-weather sky (Perez, Seals and Michalsky 1993), normalised per hour to 1e-12"},
          {"normalisation",
           {{"how", "the integral of L cos(theta) over the sky, as nested 1-D integrals about the sun: a fixed "
                    "Gauss-Legendre rule on smoothstep-mapped panels at orders 48, 64, 96 until two agree to 1e-12, "
                    "else adaptive Gauss-Kronrod to 1e-12; adaptive cubature over the hemisphere where Radiance's "
                    "floor at 0 acts"},
            {"hours_by_fixed_rule", sky.fixed_rule_hours},
            {"hours_by_adaptive_rule", sky.sky_hours - sky.fixed_rule_hours - sky.floored_hours},
            {"hours_by_hemisphere_cubature", sky.floored_hours}}},
          {"clamps", perez_clamps_name(options.clamps)},
          {"clamp_policy", options.clamps == PerezClamps::radiance
                               ? "radiance (the annual default): Radiance's limits, each counted below by the hours it acted in"
                               : "none: hours the published formula cannot serve are skipped (0 lux) and counted"},
          {"hours_by_clamp", clamps},
          {"records", sky.hours.size()},
          {"hours_with_sky", sky.sky_hours},
          {"hours_without_sky", skipped},
          {"floored_hours_by_full_cubature", sky.floored_hours},
          {"basis", {{"kind", "Chebyshev T_k(2 u_z - 1) times {1, u_x^2, u_y^2, u_z^2, u_x u_y, u_x u_z, u_y u_z}"},
                     {"degree", options.degree},
                     {"gradation_fit_bound_max", sky.max_fit_error}}},
          {"circumsolar", {{"method", fmt::format("fixed product rules per sensor (orders {}, {} and {} on each piece: the "
                                                  "fan triangles split to sides of {} rad) on the pieces more than 5 deg from "
                                                  "the sky's sun, adaptive cubature split at the sun on those nearer; order {} "
                                                  "where it and order {} agree within the tolerance, else order {} where it "
                                                  "and order {} do, else the whole term by adaptive cubature",
                                                  kCircumsolarOrderLowest, kCircumsolarOrderLow, kCircumsolarOrderHigh,
                                                  kCircumsolarMaxSide, kCircumsolarOrderLow, kCircumsolarOrderLowest,
                                                  kCircumsolarOrderHigh, kCircumsolarOrderLow)},
                           {"tolerance", options.circumsolar_tolerance}}}};
}

nlohmann::json annual_sky_mode_json(const AnnualSky& sky, const AnnualOptions& options) {
  if (options.sky_patch_mf == 0)
    return {{"mode", "exact"}, {"how", "the smooth basis and the circumsolar term about the sun, per hour, with a bound"}};
  return {{"mode", fmt::format("Reinhart MF:{} patches (--sky-patches)", options.sky_patch_mf)},
          {"patches", sky.patches.size()},
          {"how", "each patch uniform at the Perez luminance of its centre, scaled so that the patches' sum gives the hour's "
                  "diffuse horizontal illuminance (as gendaymtx normalises); each patch integrated exactly over the visible "
                  "regions (its azimuth wedge by two great circles, its altitude band by two caps about the zenith); glass's "
                  "T at each part's mean direction, its spread in the bound. The discretisation itself has no bound: the "
                  "difference from a run without --sky-patches is what the patches change"}};
}

}  // namespace daylit::cli
