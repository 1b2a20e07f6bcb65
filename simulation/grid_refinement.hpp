#pragma once
// Where a sensor grid is too coarse, from the exact gradient of the daylight factor (Holzschuch
// and Sillion 1995, §3.2: the gradient measures how far the discretisation's assumption is from
// the function over a cell, and says where to refine).
//
// The grid's mean DF is the mean of the sensors' values, each standing for its cell: a midpoint
// rule. Its error per cell is what a linear variation cannot see, the curvature: for a square
// cell of side w centred on the sensor, (1/w²)∫ DF − DF(centre) = (w²/24)(H_11 + H_22) + O(w⁴),
// H the Hessian in the cell's plane. H_aa is taken from the exact gradients of the neighbours
// along axis a, (g_a(p + w t_a) − g_a(p − w t_a))/(2w) (one-sided at the grid's border), which is
// exact for a quadratic DF: Holzschuch and Sillion's use of values and gradients to fit a higher-
// order interpolant and compare it with the lower-order assumption, here for the midpoint rule.
// Cells whose |estimate| exceeds a tolerance are split into 2×2 children, computed exactly, and
// their own estimates taken from their siblings' gradients.

#include <cstddef>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

// A sensor's cell, inferred from its neighbours (the .pts grid carries no structure): a square of
// side `width` (the distance to the nearest sensor with the same normal in the same plane) with
// axes t1, t2 in the sensor's plane (t1 along the world axis most nearly in it), and the index of
// the sensor at p + w t1, p − w t1, p + w t2, p − w t2, if there is one (within 1e-3 w).
struct SensorCell {
  double width = 0;  // 0: no other sensor in the plane
  Vec3 t1, t2;
  long neighbour[4] = {-1, -1, -1, -1};
};

// O(N) expected (a hash grid with bucket size from the grid's extent and count).
std::vector<SensorCell> infer_cells(const SensorGrid& grid);

// The midpoint-rule error of every cell's mean, (w²/24)(H_11 + H_22), in the unit of df, from the
// in-plane gradients (see above); 0 where a cell has no neighbour along either axis.
std::vector<double> cell_mean_errors(const std::vector<SensorCell>& cells, const std::vector<Vec3>& gradient);

struct GridRefinement {
  double tolerance = 0;              // split cells whose |estimated error| exceeds this (DF %)
  std::vector<Sensor> added;         // four per split cell, in order of their parents
  std::vector<std::size_t> parent;   // index of the split sensor of each added one
  std::vector<double> added_df;      // DF % at the added sensors (sky component)
  std::vector<Vec3> added_gradient;  // ∇DF there
  std::vector<double> cell_area;     // the area each sensor stands for after refinement: the
                                     // original sensors (0 where split), then the added ones
  std::size_t cells_split = 0;
  std::size_t cells_without_neighbours = 0;  // no curvature estimate possible (kept as they are)
  // Area-weighted mean DF % of the grid and the estimated error of that mean, |Σ A e| / Σ A, before
  // and after refinement.
  double mean_before = 0, mean_after = 0;
  double error_before = 0, error_after = 0;
};

// One round of refinement of `grid`, whose DF % and gradients are given; the children are computed
// with sky_component_with_gradient (exact, like their parents; with the sky seen directly through
// `direct` where the grid sees it: sky_component).
GridRefinement refine_grid(const VisibilityEngine& engine, const Scene& scene, SkyModel sky, const SensorGrid& grid,
                           const std::vector<double>& df_percent, const std::vector<Vec3>& gradient, double tolerance,
                           VisibilityCounters& counters, const VisibilityEngine* direct = nullptr);

}  // namespace daylit
