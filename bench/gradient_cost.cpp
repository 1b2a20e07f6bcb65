// Cost of the irradiance gradient relative to the irradiance alone (illumination/
// irradiance_gradient.hpp), single thread, best of 5 alternating runs:
//
//   build/bin/daylit-bench-gradient samples      (the path of the samples folder)
//
// Rows: the kernels alone on the exact visible regions of the office and hall samples (the
// overcast sky through their glazing: sky_irradiance_through_glazing against
// directional_irradiance_gradient, regions computed once beforehand), the whole per-sensor
// pipeline (sky_component against sky_component with gradients, visibility included: what
// `daylit df --gradient` adds), and a luminaire of uniform and of linear exitance behind an
// occluder (Lambert against the gradient; polynomial_luminaire_irradiance against
// polynomial_luminaire_gradient).

#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include "illumination/irradiance_gradient.hpp"
#include "illumination/moments.hpp"
#include "materials/scene_materials.hpp"
#include "simulation/sky_component.hpp"

using namespace daylit;

namespace {

// Runs a and b alternately 5 times each (so that a loaded machine's drift hits both) and prints
// the best time of each in µs per call of their `count` calls, and the ratio b/a.
void row(const char* what, const std::function<void()>& a, const std::function<void()>& b, std::size_t count) {
  double best_a = 1e300, best_b = 1e300;
  const auto time = [](const std::function<void()>& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  for (int run = 0; run < 5; ++run) {
    best_a = std::min(best_a, time(a));
    best_b = std::min(best_b, time(b));
  }
  const double us = 1e6 / double(count);
  std::printf("%-58s %10.2f %10.2f %8.2f\n", what, best_a * us, best_b * us, best_b / best_a);
}

volatile double sink = 0;

void sample(const std::string& folder, const std::string& name) {
  const std::string dir = folder + "/" + name + "/";
  const Scene scene = load_scene({dir + "scene.rad"}, {dir + "apertures.rad"});
  const SensorGrid grid = read_sensor_grid(dir + "grid.pts");
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
  row((name + ": kernels per visible region (us)").c_str(),
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
  row((name + ": df per sensor, visibility included (us)").c_str(),
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

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SAMPLES_FOLDER\n", argv[0]);
    return 2;
  }
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  std::printf("%-58s %10s %10s %8s\n", "case", "E", "gradient", "ratio");
  for (const char* name : {"office", "hall"}) sample(argv[1], name);
  luminaire();
  return 0;
}
