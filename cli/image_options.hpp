#pragma once
// The plan image's command-line options, shared by `daylit df`, `daylit illuminance` and `daylit
// annual` (its percentage plans): --image-scale, --image-range and --image-contours; and what
// every grid's image draws over its values (the walls cut at the grid's height and the apertures:
// geometry/plan_drawing.hpp).

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "geometry/plan_drawing.hpp"
#include "geometry/scene.hpp"
#include "report/reports.hpp"

namespace daylit::cli {

struct ImageCliOptions {
  std::string scale = "linear";
  std::vector<double> range, contours;
};

// Registers the options on `command`, each needing `image` (the --image option); `unit` names what
// the image shows ("DF %" or "lux").
void add_image_options(CLI::App& command, ImageCliOptions& options, CLI::Option* image, const std::string& unit);

// The colour scale the options ask for; throws daylit::Error for a range that is not one.
ImageScale image_scale(const ImageCliOptions& options);

// Each grid's plan drawing, cut at its median sensor height, in grid order.
std::vector<PlanDrawing> plan_drawings(const Scene& scene, const std::vector<const SensorGrid*>& grids);

}  // namespace daylit::cli
