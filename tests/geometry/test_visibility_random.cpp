// Randomised scenes on a coarse grid (every coordinate a multiple of 0.25 m, so that faces share
// planes, edges and vertices, and edges end on other edges, as in real models): the certified
// exact path must reproduce the all-rational reference at every sensor.

#include <catch2/catch.hpp>

#include <cmath>
#include "illumination/xoshiro256.hpp"
#include "simulation/sky_component.hpp"
#include "test_scenes.hpp"

using namespace daylit;
using test::polygon;

namespace {

// The six faces of an axis-aligned box.
void add_box(Scene& scene, Vec3 lo, Vec3 hi) {
  const double x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  scene.occluders.push_back(polygon({{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}}, "bottom"));
  scene.occluders.push_back(polygon({{x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1}}, "top"));
  scene.occluders.push_back(polygon({{x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}}, "south"));
  scene.occluders.push_back(polygon({{x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}}, "north"));
  scene.occluders.push_back(polygon({{x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}}, "west"));
  scene.occluders.push_back(polygon({{x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}}, "east"));
}

double sc(const VisibilityEngine& engine, const Scene& scene, const Sensor& s, VisibilityCounters& counters) {
  return sky_component_percent(engine, scene, s, SkyModel::cie_overcast, counters);
}

}  // namespace

TEST_CASE("on random grid-aligned scenes the certified path equals the rational reference") {
  // Xoshiro256, not std::uniform_int_distribution: the scenes are the same on every platform.
  Xoshiro256 rng(20261122);
  auto grid = [&](int lo, int hi) { return 0.25 * double(rng.uniform_int(lo, hi)); };
  int lit = 0;
  VisibilityCounters counters, reference_counters;
  for (int trial = 0; trial < 40; ++trial) {
    Scene scene;
    // A window in the plane y = 0 (room at y > 0) and a skylight at z = 4.
    const double wx0 = grid(0, 8), wz0 = grid(2, 6);
    const double wx1 = wx0 + grid(2, 8), wz1 = wz0 + grid(2, 6);
    scene.apertures.push_back({polygon({{wx0, 0, wz0}, {wx1, 0, wz0}, {wx1, 0, wz1}, {wx0, 0, wz1}}, "window"), 1.0});
    const double sx0 = grid(0, 10), sy0 = grid(2, 10);
    scene.apertures.push_back({polygon({{sx0, sy0, 4}, {sx0, sy0 + 1, 4}, {sx0 + 1.5, sy0 + 1, 4}, {sx0 + 1.5, sy0, 4}}, "skylight"), 1.0});
    // Reveals flush with the window, a wall around it, and random boxes in and around the room.
    add_box(scene, {wx0 - 0.5, -0.5, wz0 - 0.25}, {wx0, 0, wz1 + 0.25});
    add_box(scene, {wx1, -0.5, wz0 - 0.25}, {wx1 + 0.5, 0, wz1 + 0.25});
    scene.occluders.push_back(polygon({{wx0, 0, wz1}, {wx0, -0.5, wz1}, {wx1, -0.5, wz1}, {wx1, 0, wz1}}, "head"));
    for (int b = 0; b < 6; ++b) {
      const Vec3 lo{grid(-8, 12), grid(-16, 10), grid(0, 12)};
      add_box(scene, lo, {lo.x + grid(1, 8), lo.y + grid(1, 8), lo.z + grid(1, 8)});
    }
    const VisibilityEngine exact(scene, GeometryMode::exact), reference(scene, GeometryMode::rational);
    for (int s = 0; s < 25; ++s) {
      // Sensors on grid points too, facing up or sideways.
      const Sensor sensor{{grid(0, 12), grid(1, 12), grid(2, 10)}, s % 3 == 0 ? Vec3{0, -1, 0} : Vec3{0, 0, 1}};
      const double value = sc(exact, scene, sensor, counters), ref = sc(reference, scene, sensor, reference_counters);
      lit += ref > 0;
      INFO("trial " << trial << " sensor " << sensor.position.x << " " << sensor.position.y << " " << sensor.position.z);
      // Directions certified to 2^-45 of their length: a few 1e-14 of the result, or of the
      // aperture's whole contribution when what is left is a sliver.
      CHECK(std::abs(value - ref) <= 1e-12 * std::max(std::abs(ref), 1e-3));
    }
  }
  // Both modes make the same exact decisions (culling by exact predicates, the same occluders
  // clipped): only how the constructions are carried differs.
  CHECK(counters.pairs == reference_counters.pairs);
  CHECK(counters.pairs_clipped == reference_counters.pairs_clipped);
  CHECK(counters.occluders_clipped == reference_counters.occluders_clipped);
  // The scenes must exercise the clipping: most sensors see some sky, and many pairs are clipped.
  CHECK(lit > 500);
  CHECK(counters.pairs_clipped > 500);
}

TEST_CASE("front to back gives the same regions as the default order, partitioned otherwise") {
  // SubtractionOrder::front_to_back sorts the shadows nearest first and skips those whose boxes
  // miss a remaining piece: the region is the same set, only its loops differ, so the sky
  // components agree to the rounding of the sums over a partition (a few 1e-14 observed; bounded
  // here as the certified path is bounded against the rationals). Among 30 boxes, most shadows
  // hidden behind nearer ones must be skipped.
  Xoshiro256 rng(20261201);
  auto grid = [&](int lo, int hi) { return 0.25 * double(rng.uniform_int(lo, hi)); };
  VisibilityCounters counters, front_counters;
  int compared = 0;
  for (int trial = 0; trial < 10; ++trial) {
    Scene scene;
    scene.apertures.push_back({polygon({{0, 0, 1}, {2, 0, 1}, {2, 0, 2.5}, {0, 0, 2.5}}, "window"), 1.0});
    for (int b = 0; b < 30; ++b) {
      const Vec3 lo{grid(-40, 40), grid(-60, -4), 0};
      add_box(scene, lo, {lo.x + grid(1, 8), lo.y + grid(1, 8), grid(2, 40)});
    }
    const VisibilityEngine as_built(scene, GeometryMode::exact), front(scene, GeometryMode::exact, SubtractionOrder::front_to_back);
    for (int s = 0; s < 20; ++s) {
      const Sensor sensor{{grid(0, 8), grid(1, 16), grid(2, 5)}, {0, 0, 1}};
      const double value = sc(as_built, scene, sensor, counters), other = sc(front, scene, sensor, front_counters);
      INFO("trial " << trial << " sensor " << sensor.position.x << " " << sensor.position.y << " " << sensor.position.z);
      CHECK(std::abs(value - other) <= 1e-12 * std::max(std::abs(value), 1e-3));
      compared += value > 0;
    }
  }
  CHECK(compared > 100);
  CHECK(front_counters.occluders_clipped == counters.occluders_clipped);  // the same survivors, in another order
  CHECK(front_counters.occluders_skipped > front_counters.occluders_clipped / 4);
  CHECK(counters.occluders_skipped == 0);
}
