#pragma once
// What a plan image draws over a grid's values (issue 15, "results people read"): the walls cut
// at the height of the grid, as an architect's plan is a section at about the work plane, and the
// apertures seen from above. Drawing data only, in double: it decides no value.

#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"

namespace daylit {

struct PlanSegment {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct PlanDrawing {
  // Every occluder polygon that crosses the horizontal plane z = height, cut by it: the parts of
  // the plane's line through the polygon that lie inside it (a polygon with a notch gives several).
  // Polygons in the plane (floors at that height) and those that do not reach it give none.
  std::vector<PlanSegment> walls;
  // Every aperture's outline projected on the plan: a window in a vertical wall becomes a
  // segment along it, a skylight its outline. Edges that project to a point are left out.
  std::vector<PlanSegment> apertures;
};

PlanDrawing plan_drawing(const Scene& scene, double height);

// The height a grid's plan is cut at: the median of its sensors' heights (the work plane; 0 for
// an empty grid).
double plan_height(const SensorGrid& grid);

// The distance in plan (x, y) from a point to the nearest of `segments`; infinity where there are
// none.
double plan_distance(const std::vector<PlanSegment>& segments, double x, double y) noexcept;

}  // namespace daylit
