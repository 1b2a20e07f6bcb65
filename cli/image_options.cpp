#include "cli/image_options.hpp"

#include <fmt/format.h>

#include "cli/number_checks.hpp"
#include "geometry/error.hpp"

namespace daylit::cli {

void add_image_options(CLI::App& command, ImageCliOptions& options, CLI::Option* image, const std::string& unit) {
  command.add_option("--image-scale", options.scale, "Colour scale of the --image plans: linear (default) or log")
      ->check(CLI::IsMember({"linear", "log"}))
      ->needs(image);
  command
      .add_option("--image-range", options.range,
                  fmt::format("Bottom and top of the --image plans' colour scale ({}; default: 0, or on a log scale a round "
                              "number near the 5th percentile, and a round number at or above the 95th percentile)",
                              unit))
      ->expected(2)
      ->check(number_in(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max()))
      ->needs(image);
  command
      .add_option("--image-contours", options.contours,
                  fmt::format("Values ({}) whose iso-lines the --image plans draw, e.g. --image-contours 1 2 5", unit))
      ->check(number_in(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max()))
      ->needs(image);
}

ImageScale image_scale(const ImageCliOptions& options) {
  ImageScale s;
  s.logarithmic = options.scale == "log";
  if (!options.range.empty()) {
    const double low = options.range[0], high = options.range[1];
    if (!(low < high)) throw Error(fmt::format("--image-range {:g} {:g}: the bottom must be below the top", low, high));
    if (s.logarithmic && !(low > 0))
      throw Error(fmt::format("--image-range {:g} {:g}: a log scale needs a bottom above 0", low, high));
    s.low = low;
    s.high = high;
  }
  s.contours = options.contours;
  return s;
}

std::vector<PlanDrawing> plan_drawings(const Scene& scene, const std::vector<const SensorGrid*>& grids) {
  std::vector<PlanDrawing> out;
  for (const SensorGrid* g : grids) out.push_back(plan_drawing(scene, plan_height(*g)));
  return out;
}

}  // namespace daylit::cli
