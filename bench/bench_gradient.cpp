// `daylit bench gradient`: the cost of the irradiance gradient relative to the irradiance alone
// (illumination/irradiance_gradient.hpp), one thread, thread CPU time, the best of 5 alternating
// runs (bench/timing.hpp; alternating so that a loaded machine's drift hits both). gradient.csv
// and a table on stderr.
//
// Rows: the kernels alone on the exact visible regions of the office and hall samples (the
// overcast sky through their glazing: sky_irradiance_through_glazing against
// directional_irradiance_gradient, regions computed once beforehand), the whole per-sensor
// pipeline (sky_component against sky_component with gradients, visibility included: what
// `daylit df --gradient` adds), and a luminaire of uniform and of linear exitance behind an
// occluder (Lambert against the gradient; polynomial_luminaire_irradiance against
// polynomial_luminaire_gradient).

#include <tbb/global_control.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "bench/bench_suites.hpp"
#include "geometry/error.hpp"
#include "report/staged_output.hpp"

#include "illumination/irradiance_gradient.hpp"
#include "illumination/moments.hpp"
#include "materials/scene_materials.hpp"
#include "simulation/sky_component.hpp"

namespace daylit::cli {

namespace {

struct GradientRow {
  std::string what;
  double us_e, us_gradient;
};
std::vector<GradientRow>* rows_out = nullptr;

// Runs a and b alternately, best of `runs` each (bench/timing.hpp), and records the best thread
// CPU time of each in µs per call of their `count` calls.
void row(const std::string& what, const std::function<void()>& a, const std::function<void()>& b, std::size_t count,
         int runs = 5) {
  double best_a = 1e300, best_b = 1e300;
  for (int run = 0; run < runs; ++run) {
    best_a = std::min(best_a, bench::best_cpu_seconds(a, 1));
    best_b = std::min(best_b, bench::best_cpu_seconds(b, 1));
  }
  const double us = 1e6 / double(count);
  rows_out->push_back({what, best_a * us, best_b * us});
}

volatile double sink = 0;

void sample(const std::string& folder, const std::string& name, bool quick) {
  const std::string dir = folder + "/" + name + "/";
  const Scene scene = load_scene({dir + "scene.rad"}, {dir + "apertures.rad"});
  SensorGrid grid = read_sensor_grid(dir + "grid.pts");
  if (quick) grid.sensors.resize(std::min<std::size_t>(grid.sensors.size(), 100));
  const VisibilityEngine engine(scene, GeometryMode::exact);
  VisibilityOptions options;
  options.edge_sources = true;
  struct Item {
    SphericalRegion region;
    const Sensor* sensor;
    const Aperture* aperture;
    Vec3 pane;
  };
  std::vector<Item> items;
  for (const Sensor& s : grid.sensors)
    for (std::size_t a = 0; a < engine.aperture_count(); ++a) {
      VisibilityCounters counters;
      SphericalRegion r = engine.visible_region(s.position, s.normal, a, counters, options);
      if (r.empty()) continue;
      const Aperture& ap = scene.apertures[a];
      Vec3 pane = normalized(newell_normal(ap.polygon.vertices)), inside{};
      for (const Vec3& u : r.loops.front()) inside += normalized(u);
      if (dot(pane, inside) < 0) pane = -1.0 * pane;
      items.push_back({std::move(r), &s, &ap, pane});
    }
  row(name + ": kernels per visible region (us)",
      [&] {
        for (const Item& i : items)
          sink = sink + (i.aperture->angular_transmittance.empty()
                             ? sky_irradiance(i.region, i.sensor->normal, SkyModel::cie_overcast)
                             : sky_irradiance_through_glazing(i.region, i.sensor->normal, SkyModel::cie_overcast, i.pane,
                                                              i.aperture->angular_transmittance));
      },
      [&] {
        DirectionalRadiance L;
        L.alpha = 1.0 / 3;
        L.beta = {0, 0, 2.0 / 3};
        for (const Item& i : items) {
          L.axis = i.pane;
          L.c = i.aperture->angular_transmittance.empty() ? std::vector<double>{1} : i.aperture->angular_transmittance;
          sink = sink + directional_irradiance_gradient(i.region, i.sensor->position, i.sensor->normal, L, 1e-7).value.x;
        }
      },
      items.size());
  row(name + ": df per sensor, visibility included (us)",
      [&] { sink = sink + sky_component(engine, scene, grid, SkyModel::cie_overcast).sc_percent[0]; },
      [&] { sink = sink + sky_component(engine, scene, grid, SkyModel::cie_overcast, {}, true).sc_percent[0]; },
      grid.sensors.size());
}

void luminaire() {
  Scene scene;
  Polygon lum;
  lum.vertices = {{-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}};
  scene.apertures.push_back({lum, 1.0});
  Polygon plate;
  plate.vertices = {{-0.2, -0.1, 1.5}, {0.6, -0.3, 1.5}, {0.7, 0.5, 1.5}, {-0.1, 0.6, 1.5}};
  scene.occluders.push_back(plate);
  const VisibilityEngine engine(scene, GeometryMode::exact);
  VisibilityOptions options;
  options.clip_to_horizon = false;
  options.edge_sources = true;
  std::vector<std::pair<Vec3, SphericalRegion>> regions;
  for (int i = 0; i < 400; ++i) {
    const Vec3 p{-1.5 + 3.0 * (i % 20) / 19, -1.5 + 3.0 * (i / 20) / 19, 0.3};
    VisibilityCounters counters;
    regions.emplace_back(p, engine.visible_region(p, {0, 0, 1}, 0, counters, options));
  }
  const Vec3 n{0, 0, 1};
  row(
      "uniform luminaire behind an occluder (us)",
      [&] {
        for (const auto& [p, r] : regions) sink = sink + lambert(r, n) / std::numbers::pi;
      },
      [&] {
        DirectionalRadiance L;
        L.alpha = 1 / std::numbers::pi;
        for (const auto& [p, r] : regions) sink = sink + directional_irradiance_gradient(r, p, n, L).value.x;
      },
      regions.size());
  const ExitancePolynomial M{{1, 0, 0, 0}, {0.5, 1, 0, 0}, {0.3, 0, 1, 0}};
  row(
      "linear luminaire behind an occluder (us, E and E + gradient)",
      [&] {
        for (const auto& [p, r] : regions) sink = sink + polynomial_luminaire_irradiance(r, p, n, lum.vertices[0], {0, 0, 1}, M).value;
      },
      [&] {
        for (const auto& [p, r] : regions)
          sink = sink + polynomial_luminaire_gradient(r, p, n, lum.vertices[0], {0, 0, 1}, M).gradient.x;
      },
      regions.size());
}

}  // namespace

int run_bench_gradient(const BenchOptions& opt) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  std::vector<GradientRow> rows;
  rows_out = &rows;
  for (const char* name : {"office", "hall"}) sample(opt.samples, name, opt.quick);
  luminaire();
  std::filesystem::create_directories(opt.out);
  const std::string csv = (std::filesystem::path(opt.out) / "gradient.csv").string();
  StagedOutputs outputs;
  std::ofstream f(outputs.stage(csv));
  f << "case,us_irradiance,us_gradient,ratio\n";
  if (!opt.quiet) std::cerr << fmt::format("{:<64} {:>10} {:>10} {:>8}\n", "case", "E", "gradient", "ratio");
  for (const GradientRow& r : rows) {
    f << fmt::format("\"{}\",{:.4f},{:.4f},{:.4f}\n", r.what, r.us_e, r.us_gradient, r.us_gradient / r.us_e);
    if (!opt.quiet) std::cerr << fmt::format("{:<64} {:>10.2f} {:>10.2f} {:>8.2f}\n", r.what, r.us_e, r.us_gradient, r.us_gradient / r.us_e);
  }
  f.close();
  if (!f) throw Error(csv + ": cannot write");
  outputs.commit();
  return 0;
}

}  // namespace daylit::cli
