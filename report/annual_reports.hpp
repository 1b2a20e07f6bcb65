#pragma once
// Writers for `daylit annual`: the per-sensor metrics CSV and the summary's per-grid and sky sections.

#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/sensor_grid.hpp"
#include "simulation/annual.hpp"
#include "simulation/annual_metrics.hpp"

namespace daylit::cli {

struct AnnualGridReport {
  const SensorGrid* grid = nullptr;
  AnnualGridResult result;
  std::vector<SensorMetrics> sensors;
  GridMetrics metrics;
};

// One row per sensor: grid,index,x,y,z,dx,dy,dz (as `df`), then direct_sun_hours, da_300_percent,
// cda_300_percent, udi_fell_short_percent, udi_supplementary_percent, udi_autonomous_percent,
// udi_exceeded_percent, the EN 17037 per-sensor variant en17037_sensor_hours_at_{100,300,500,750}_percent
// (share of daylight hours at or above each target), and max_hour_bound_lux (the largest per-hour
// bound on the sky illuminance's error).
void write_annual_csv(std::FILE* out, const std::vector<AnnualGridReport>& grids);
void write_annual_csv(const std::string& path, const std::vector<AnnualGridReport>& grids);

// The temporal map of a grid: its mean illuminance (with blinds) for every record, as a
// falsecolour image with a legend, day of the year along x (1 January on the left) and hour of
// the day along y (midnight at the bottom, 23:00–24:00 at the top), drawn by the plan renderer of
// write_falsecolour_image with one cell per record.
void write_temporal_map(const std::string& path, const AnnualGridReport& g, const AnnualSky& sky);

nlohmann::json annual_grid_json(const AnnualGridReport& g, const std::vector<std::string>& group_names);
nlohmann::json annual_sky_json(const AnnualSky& sky, const AnnualOptions& options);
// How the sky was taken: exact, or in patches (--sky-patches).
nlohmann::json annual_sky_mode_json(const AnnualSky& sky, const AnnualOptions& options);

}  // namespace daylit::cli
