#pragma once
// EN 17037's daylight-factor method for daylight provision: the illuminance targets of its
// Table A.1 (openings in vertical and inclined surfaces; a target over 50 % of the reference plane
// and a minimum target over 95 %, each for half of the daylight hours) turned into daylight-factor
// targets by the site's median diffuse illuminance, D = 100 · E / E_v,d,med (EN 17037:2018, A.3,
// whose Table A.3 gives E_v,d,med for European capitals).

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "geometry/plan_drawing.hpp"
#include "geometry/sensor_grid.hpp"

namespace daylit {

struct En17037Level {
  std::string name;                   // minimum, medium, high
  double target_lux = 0, minimum_target_lux = 0;  // E_T over 50 %, E_TM over 95 % (Table A.1)
  double target_df = 0, minimum_target_df = 0;     // percent: 100 · E / E_v,d,med
  double share_at_target = 0, share_at_minimum_target = 0;  // of the sensors (0..1)
  bool met = false;  // share_at_target ≥ 0.5 and share_at_minimum_target ≥ 0.95
};

struct En17037Assessment {
  double median_diffuse_lux = 0;
  std::vector<En17037Level> levels;  // minimum (300/100 lx), medium (500/300), high (750/500)
  std::string level_met;             // the highest level met, or "none"
};

// `df_percent`: one value per sensor of equal area (a regular grid: the shares are of sensors).
// `median_diffuse_lux` > 0. Throws daylit::Error otherwise.
En17037Assessment en17037_df_method(const std::vector<double>& df_percent, double median_diffuse_lux);

// BREEAM Hea 01's daylight-factor figures (BREEAM UK New Construction 2018, Hea 01, with CIBSE
// LG10's calculation): the average daylight factor over the working plane, the minimum point
// daylight factor and the uniformity ratio (minimum over average), leaving out the perimeter band
// within 0.5 m of the walls. The criteria a project must meet (per building type and credit) are
// BREEAM's tables, not repeated here: these are the figures they are read against.
struct BreeamHea01 {
  double band = 0.5;                 // model units (metres)
  std::size_t sensors = 0;           // outside the band: those averaged
  std::size_t sensors_in_band = 0;   // left out
  // Unset where every sensor lies in the band (a room narrower than 1 m).
  std::optional<double> average_df, minimum_df, uniformity;
};

// Sensors closer than `band` in plan to a wall of `plan` (anything the grid's plane cuts) are in
// the band. `df_percent`: one value per sensor of equal area.
BreeamHea01 breeam_hea01(const SensorGrid& grid, const std::vector<double>& df_percent, const PlanDrawing& plan,
                         double band = 0.5);

}  // namespace daylit
