// `daylit bench pairs`: cost per sensor–aperture pair of the sky component (visibility and
// kernels), one thread, on the bundled samples and on an unobstructed window, in exact, float and
// all-rational geometry.
//
// pairs.csv and a table on stderr: one row per case and mode (exact: certified intervals; float;
// rational throughout, the reference): pairs, µs per pair (thread CPU time, best of 3 runs:
// bench/timing.hpp), the share of pairs that needed clipping, and the share that needed exact
// rationals after interval arithmetic.

#include <tbb/global_control.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "bench/bench_suites.hpp"
#include "geometry/error.hpp"
#include "materials/scene_materials.hpp"
#include "report/staged_output.hpp"
#include "simulation/sky_component.hpp"

namespace daylit::cli {

namespace {

struct Case {
  std::string name;
  Scene scene;
  SensorGrid grid;
};

double best_time_per_pair(const VisibilityEngine& engine, const Case& c, VisibilityCounters& counters) {
  const double seconds = bench::best_cpu_seconds(
      [&] { counters = sky_component(engine, c.scene, c.grid, SkyModel::cie_overcast).counters; }, 3);
  return 1e6 * seconds / double(counters.pairs);
}

}  // namespace

int run_bench_pairs(const BenchOptions& opt) {
  const std::string samples = opt.samples;
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);

  std::vector<Case> cases;
  {
    Case c{"unobstructed window", {}, {}};
    Polygon window;
    window.vertices = {{0.8, -0.3, 0.9}, {3.2, -0.3, 0.9}, {3.2, -0.3, 2.4}, {0.8, -0.3, 2.4}};
    window.name = "window";
    c.scene.apertures.push_back({window, 1.0});
    c.grid = read_sensor_grid(samples + "/office/" + (opt.quick ? "grid.pts" : "grid-dense.pts"));
    cases.push_back(std::move(c));
  }
  for (const char* name : {"office", "hall"}) {
    Case c{name, load_scene({samples + "/" + name + "/scene.rad"}, {samples + "/" + name + "/apertures.rad"}), {}};
    c.grid = read_sensor_grid(samples + "/" + name + (std::string(name) == "office" && !opt.quick ? "/grid-dense.pts" : "/grid.pts"));
    if (opt.quick) {  // every 10th sensor: a smoke run of a few seconds
      SensorGrid sub{c.grid.name, c.grid.path, {}};
      for (std::size_t i = 0; i < c.grid.sensors.size(); i += 10) sub.sensors.push_back(c.grid.sensors[i]);
      c.grid = std::move(sub);
    }
    cases.push_back(std::move(c));
  }

  std::filesystem::create_directories(opt.out);
  const std::string csv = (std::filesystem::path(opt.out) / "pairs.csv").string();
  StagedOutputs outputs;
  std::ofstream f(outputs.stage(csv));
  f << "case,mode,pairs,us_per_pair,share_clipped,share_rational\n";
  if (!opt.quiet) std::cerr << fmt::format("{:<20} {:<8} {:>9} {:>12} {:>10} {:>10}\n", "case", "mode", "pairs", "us_per_pair", "clipped", "rational");
  for (const auto& c : cases) {
    for (const GeometryMode mode : {GeometryMode::exact, GeometryMode::floating, GeometryMode::rational}) {
      const VisibilityEngine engine(c.scene, mode);
      VisibilityCounters counters;
      // The rational reference is slow: every 25th sensor is enough to time it.
      Case sub{c.name, c.scene, {}};
      for (std::size_t i = 0; i < c.grid.sensors.size(); i += 25) sub.grid.sensors.push_back(c.grid.sensors[i]);
      const double us = best_time_per_pair(engine, mode == GeometryMode::rational ? sub : c, counters);
      const char* mode_name = mode == GeometryMode::exact ? "exact" : (mode == GeometryMode::floating ? "float" : "rational");
      const double clipped = double(counters.pairs_clipped) / double(counters.pairs);
      const double rational = double(counters.pairs_rational) / double(counters.pairs);
      f << fmt::format("{},{},{},{:.4f},{:.4f},{:.6f}\n", c.name, mode_name, counters.pairs, us, clipped, rational);
      if (!opt.quiet)
        std::cerr << fmt::format("{:<20} {:<8} {:>9} {:>12.3f} {:>9.1f}% {:>9.2f}%\n", c.name, mode_name, counters.pairs, us,
                                 100 * clipped, 100 * rational);
    }
  }
  f.close();
  if (!f) throw Error(csv + ": cannot write");
  outputs.commit();
  return 0;
}

}  // namespace daylit::cli
