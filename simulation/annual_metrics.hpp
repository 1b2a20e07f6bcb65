#pragma once
// Climate-based daylight metrics from hourly illuminances (issue 14, deliverable 4).
//
// Sources: IES LM-83-12 (sDA300/50%, ASE1000,250; occupied hours 8:00–18:00 local standard time,
// 3,650 a year); Reinhart and Walkenhorst 2001 (DA), Rogers 2006 (continuous DA: an hour below
// the threshold counts E/300 of itself); Nabil and Mardaljevic 2005/2006 with the 100/300/3000 lx
// bands as the issue sets them (UDI fell short < 100, supplementary [100, 300), autonomous
// [300, 3000], exceeded > 3000); EN 17037:2018 §A.2 (illuminance method: the target over 50 % of
// the reference plane and the minimum target over 95 % of it, each for at least half of the
// daylight hours), LEED v4.1 EQ "Daylight" Option 1 (sDA300/50% ≥ 40 % one point, ≥ 55 % two,
// ≥ 75 % three; ASE1000,250 is reported beside it, ≤ 10 % being the v4 prerequisite of the option).

#include <cstddef>
#include <string>
#include <vector>

namespace daylit {

struct SensorMetrics {
  int direct_sun_hours = 0;  // occupied hours with direct sun (blinds open) ≥ 1000 lx
  double da_300_percent = 0, cda_300_percent = 0;
  double udi_fell_short_percent = 0, udi_supplementary_percent = 0, udi_autonomous_percent = 0,
         udi_exceeded_percent = 0;
  // EN 17037, per-sensor variant (labelled so in outputs): the share of daylight hours in which this
  // sensor reaches each target (100, 300, 500, 750 lx).
  double en17037_hours_at_100_percent = 0, en17037_hours_at_300_percent = 0, en17037_hours_at_500_percent = 0,
         en17037_hours_at_750_percent = 0;
};

// illuminance and direct_sun: [sensor × hours] row-major; occupied and daylight: per hour.
std::vector<SensorMetrics> sensor_metrics(const std::vector<float>& illuminance, const std::vector<float>& direct_sun,
                                          std::size_t sensors, std::size_t hours, const std::vector<bool>& occupied,
                                          const std::vector<bool>& daylight);

struct En17037IlluminanceLevel {
  std::string name;              // minimum, medium, high
  double target_lux, minimum_target_lux;
  // The standard's reading: the share of daylight hours in which ≥ 50 % of the sensors reach the
  // target and ≥ 95 % the minimum target (each hour its own spatial test).
  double hours_target_met_percent, hours_minimum_met_percent;
  bool pass;                     // both ≥ 50 % of the daylight hours
  // The per-sensor variant: the share of sensors reaching the target (resp. minimum target) in
  // at least half of the daylight hours; passes at ≥ 50 % (resp. ≥ 95 %).
  double sensors_target_percent, sensors_minimum_percent;
  bool pass_per_sensor;
};

struct GridMetrics {
  double sda_300_50_percent = 0;    // share of sensors with DA300 ≥ 50 %
  double ase_1000_250_percent = 0;  // share of sensors with more than 250 direct sun hours
  int leed_sda_points = 0;          // 0–3 (LEED v4.1 thresholds above)
  bool leed_ase_at_most_10_percent = false;
  double mean_da_300_percent = 0, mean_udi_autonomous_percent = 0;
  std::vector<En17037IlluminanceLevel> en17037;
  std::size_t occupied_hours = 0, daylight_hours = 0;
};

GridMetrics grid_metrics(const std::vector<float>& illuminance, const std::vector<SensorMetrics>& sensors,
                         std::size_t hours, const std::vector<bool>& occupied, const std::vector<bool>& daylight);

// EN 17037's daylight hours: the `count` hours (4,380: half the year) of highest sun altitude
// (ties by file order). The standard counts half of the year's hours as daylight hours; taking the
// highest suns is this tool's reading of which half (stated in the summary).
std::vector<bool> en17037_daylight_hours(const std::vector<double>& sun_altitude_deg, std::size_t count = 4380);

}  // namespace daylit
