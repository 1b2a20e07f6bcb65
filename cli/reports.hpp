#pragma once
// Writers for the results of `daylit df`: CSV table, JSON summary, falsecolour plan image.

#include <cstdio>
#include <string>
#include <vector>

#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "sky/grid_statistics.hpp"

namespace daylit::cli {

struct GridReport {
  const SensorGrid* grid = nullptr;
  std::vector<double> sc_percent;
  std::vector<double> df_percent;
  GridStatistics statistics;
  VisibilityCounters counters;
  double run_time_s = 0;
};

// One row per sensor, grids in the order given: grid,index,x,y,z,dx,dy,dz,sc_percent,df_percent.
void write_csv(const std::string& path, const std::vector<GridReport>& reports);
void write_csv(std::FILE* out, const std::vector<GridReport>& reports);

// Plan view (looking down −z) of one grid in falsecolour with a legend in DF %.
void write_falsecolour_image(const std::string& path, const GridReport& report);

}  // namespace daylit::cli
