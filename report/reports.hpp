#pragma once
// Writers for the results of `daylit df`: CSV table, JSON summary, falsecolour plan image.

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "geometry/plan_drawing.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "simulation/grid_refinement.hpp"
#include "simulation/grid_statistics.hpp"

namespace daylit::cli {

// The colour scale of a plan image (df and illuminance: --image-scale, --image-range,
// --image-contours).
struct ImageScale {
  bool logarithmic = false;
  // The legend's ends; unset: 0 (linear) or a round number near the 5th percentile of the
  // positive values, at least a thousandth of the top (log), and a round number at or above the
  // 95th percentile, so that a few bright sensors by a window do not leave the rest in one colour.
  std::optional<double> low, high;
  std::vector<double> contours;  // values whose iso-lines are drawn over the map
};

struct GridReport {
  const SensorGrid* grid = nullptr;
  std::vector<double> sc_percent;
  // With reflected components (df --components all): ERC, IRC and the estimated error of their
  // sum, per sensor; empty for a sky-component-only run.
  std::vector<double> erc_percent, irc_percent, reflection_error_percent;
  std::vector<double> df_percent;
  // The largest bound over the sensors of what panes taken as constant over a region may cost
  // (SkyComponentResult::pane_bound_percent), DF points.
  double pane_bound_percent = 0;
  // What the falsecolour image maps: df_percent in % unless `shown` is set (`daylit illuminance`
  // shows lux).
  std::vector<double> shown;
  std::string shown_title = "Daylight factor (%)", shown_unit = "%";
  // What a cell stands for, and the line under the map (empty: the plan view's size in metres);
  // `daylit annual`'s temporal map draws records as cells.
  std::string cell_noun = "sensors", footer;
  const std::vector<double>& image_values() const { return shown.empty() ? df_percent : shown; }
  // What the plan image draws over the values (walls cut at the grid's height, apertures from
  // above; null: nothing, as on annual's temporal maps) and its colour scale.
  const PlanDrawing* plan = nullptr;
  ImageScale scale;
  GridStatistics statistics;
  VisibilityCounters counters;
  double run_time_s = 0;
  std::vector<Vec3> df_gradient;             // `df --gradient`: ∇DF per sensor (percent per model unit)
  std::optional<GridRefinement> refinement;  // `df --refine`
};

// One row per sensor, grids in the order given: grid,index,x,y,z,dx,dy,dz,sc_percent,df_percent;
// with reflected components grid,index,x,y,z,dx,dy,dz,sc_percent,erc_percent,irc_percent,
// df_percent,reflection_error_estimate_percent (df_percent last but one); with gradients, ddf_dx,ddf_dy,ddf_dz; with refinement, added,cell_area, and the added sensors
// after each grid's own (indices continuing; a split sensor's cell_area is 0). The columns are
// those of the first report (df computes gradients and refinements for all grids or none).
void write_csv(const std::string& path, const std::vector<GridReport>& reports);
void write_csv(std::FILE* out, const std::vector<GridReport>& reports);

// Image path for one of several grids: the given path itself for one grid, else with the grid's
// name inserted before the extension.
inline std::string image_path_for(const std::string& image, const std::string& grid_name, std::size_t grid_count) {
  if (grid_count == 1) return image;
  const std::filesystem::path p(image);
  return (p.parent_path() / (p.stem().string() + "-" + grid_name + p.extension().string())).string();
}

// Plan view (looking down −z) of one grid in falsecolour with a legend (DF % or lux).
void write_falsecolour_image(const std::string& path, const GridReport& report);

}  // namespace daylit::cli
