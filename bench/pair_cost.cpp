// Cost per sensor–aperture pair of the sky component (visibility + kernels), single thread, on
// the bundled samples and on an unobstructed window, in exact and float geometry.
//
//   build/bin/daylit-bench-pairs samples      (the path of the samples folder)
//
// Prints one row per case and mode (exact: certified intervals; float; ratnl: rationals
// throughout, the reference): pairs, µs per pair (best of 3 runs), the share of pairs that needed
// clipping, and the share that needed exact rationals after interval arithmetic.

#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "materials/scene_materials.hpp"
#include "simulation/sky_component.hpp"

using namespace daylit;

namespace {

struct Case {
  std::string name;
  Scene scene;
  SensorGrid grid;
};

double best_time_per_pair(const VisibilityEngine& engine, const Case& c, VisibilityCounters& counters) {
  double best = 1e300;
  for (int run = 0; run < 3; ++run) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto result = sky_component(engine, c.scene, c.grid, SkyModel::cie_overcast);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    counters = result.counters;
    best = std::min(best, seconds);
  }
  return 1e6 * best / double(counters.pairs);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SAMPLES_DIR\n", argv[0]);
    return 2;
  }
  const std::string samples = argv[1];
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);

  std::vector<Case> cases;
  {
    Case c{"unobstructed window", {}, {}};
    Polygon window;
    window.vertices = {{0.8, -0.3, 0.9}, {3.2, -0.3, 0.9}, {3.2, -0.3, 2.4}, {0.8, -0.3, 2.4}};
    window.name = "window";
    c.scene.apertures.push_back({window, 1.0});
    c.grid = read_sensor_grid(samples + "/office/grid-dense.pts");
    cases.push_back(std::move(c));
  }
  for (const char* name : {"office", "hall"}) {
    Case c{name, load_scene({samples + "/" + name + "/scene.rad"}, {samples + "/" + name + "/apertures.rad"}), {}};
    c.grid = read_sensor_grid(samples + "/" + name + (std::string(name) == "office" ? "/grid-dense.pts" : "/grid.pts"));
    cases.push_back(std::move(c));
  }

  std::printf("%-20s %-6s %9s %12s %10s %10s\n", "case", "mode", "pairs", "us_per_pair", "clipped", "rational");
  for (const auto& c : cases) {
    for (const GeometryMode mode : {GeometryMode::exact, GeometryMode::floating, GeometryMode::rational}) {
      const VisibilityEngine engine(c.scene, mode);
      VisibilityCounters counters;
      // The rational reference is slow: every 25th sensor is enough to time it.
      Case sub{c.name, c.scene, {}};
      for (std::size_t i = 0; i < c.grid.sensors.size(); i += 25) sub.grid.sensors.push_back(c.grid.sensors[i]);
      const double us = best_time_per_pair(engine, mode == GeometryMode::rational ? sub : c, counters);
      std::printf("%-20s %-6s %9llu %12.3f %9.1f%% %9.2f%%\n", c.name.c_str(), mode == GeometryMode::exact ? "exact" : (mode == GeometryMode::floating ? "float" : "ratnl"),
                  (unsigned long long)counters.pairs, us, 100.0 * double(counters.pairs_clipped) / double(counters.pairs),
                  100.0 * double(counters.pairs_rational) / double(counters.pairs));
    }
  }
  return 0;
}
