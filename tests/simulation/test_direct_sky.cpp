// The sky seen directly, not through an aperture (geometry/sky_box.hpp): a grid outdoors, on a
// façade or in a courtyard. Against closed forms in the open, and against the same sky given as
// an aperture over a courtyard (an independent path through the engine: the aperture's own view
// rather than the six faces of the box), for SC, its gradient, the sun and the far ground.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "geometry/sky_box.hpp"
#include "simulation/annual.hpp"
#include "simulation/illuminance.hpp"
#include "simulation/reflected_components.hpp"
#include "simulation/sky_component.hpp"
#include "test_scenes.hpp"
#include "test_support.hpp"

using namespace daylit;
using daylit::test::polygon;
using daylit::test::relative_error;

namespace {

constexpr double kPi = std::numbers::pi;

SensorGrid outdoor_grid(std::vector<Sensor> sensors) {
  SensorGrid g;
  g.name.push_back('g');  // not = "g": GCC 12 warns falsely (-Wrestrict) on that here
  g.sensors = std::move(sensors);
  g.sees_sky_directly = true;
  return g;
}

// Nothing above any sensor's horizon here: the aperture every scene needs (a black hatch far
// below, behind the sensors' planes) and a reflecting wall low and behind them.
Scene in_the_open() {
  Scene s;
  s.apertures.push_back({polygon({{-1, -3, -50}, {1, -3, -50}, {1, -1, -50}, {-1, -1, -50}}, "hatch"), 1.0});
  s.occluders.push_back(polygon({{20, -10, 0}, {20, -10, 5}, {20, -5, 5}, {20, -5, 0}}, "low wall"));
  return s;
}

// A courtyard 10 × 8 m, walls 12 m high, with its floor; in its east wall a window (glass
// aperture) into a closed room behind it. `roof_opening`: the courtyard's top given as an open
// aperture, so that its sky comes through an aperture instead of directly.
Scene courtyard(bool roof_opening) {
  Scene s;
  const double w = 10, d = 8, h = 12;
  s.occluders = {polygon({{0, 0, 0}, {w, 0, 0}, {w, d, 0}, {0, d, 0}}, "floor"),
                 polygon({{0, 0, 0}, {0, 0, h}, {w, 0, h}, {w, 0, 0}}, "south"),
                 polygon({{0, d, 0}, {w, d, 0}, {w, d, h}, {0, d, h}}, "north"),
                 polygon({{0, 0, 0}, {0, d, 0}, {0, d, h}, {0, 0, h}}, "west"),
                 // the east wall with the window x = 10, y ∈ [3, 5], z ∈ [1, 3] cut out by a seam
                 polygon({{w, 0, 0}, {w, 0, h}, {w, d, h}, {w, d, 0}, {w, 5, 0}, {w, 5, 1}, {w, 3, 1}, {w, 3, 3}, {w, 5, 3},
                          {w, 5, 1}, {w, 5, 0}},
                         "east"),
                 // the room behind the window: x ∈ [10, 14], closed
                 polygon({{w, 0, 0}, {14, 0, 0}, {14, d, 0}, {w, d, 0}}, "room floor"),
                 polygon({{w, 0, 4}, {w, d, 4}, {14, d, 4}, {14, 0, 4}}, "room ceiling"),
                 polygon({{14, 0, 0}, {14, d, 0}, {14, d, 4}, {14, 0, 4}}, "room back"),
                 polygon({{w, 0, 0}, {w, 0, 4}, {14, 0, 4}, {14, 0, 0}}, "room south"),
                 polygon({{w, d, 0}, {14, d, 0}, {14, d, 4}, {w, d, 4}}, "room north")};
  s.apertures.push_back({polygon({{w, 3, 1}, {w, 5, 1}, {w, 5, 3}, {w, 3, 3}}, "window"), 0.7});
  if (roof_opening) s.apertures.push_back({polygon({{0, 0, h}, {w, 0, h}, {w, d, h}, {0, d, h}}, "roof opening"), 1.0});
  return s;
}

std::vector<Sensor> courtyard_sensors() {
  return {{{2, 2, 0.85}, {0, 0, 1}},  {{5, 4, 0.85}, {0, 0, 1}},  {{9, 7, 0.1}, {0, 0, 1}},
          {{5, 0.01, 6}, {0, 1, 0}},  {{9.99, 2, 2}, {-1, 0, 0}}, {{3, 7.99, 11}, {0, -1, 0}},
          {{7, 3, 5}, normalized(Vec3{0.3, -0.5, 0.8})}};
}

}  // namespace

TEST_CASE("in the open, the sky seen directly is the whole sky: SC 100 % facing up, (3π + 8)/(14π) facing the horizon") {
  // Nothing above the horizon but sky: it comes only directly.
  const Scene scene = in_the_open();
  const SensorGrid grid = outdoor_grid({{{0, 0, 6}, {0, 0, 1}}, {{3, -2, 7}, {0, 1, 0}}, {{3, -2, 7}, {1, 0, 0}}});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  const auto direct = direct_sky(scene, {grid}, GeometryMode::exact, SubtractionOrder::front_to_back);
  REQUIRE(direct != nullptr);
  const double vsc = 100 * (3 * kPi + 8) / (14 * kPi);
  for (const SkyModel sky : {SkyModel::cie_overcast, SkyModel::uniform}) {
    const SkyComponentResult r = sky_component(engine, scene, grid, sky, {}, false, &direct->engine);
    // Exact regions, closed forms: a few roundings of sums over the box's faces.
    CHECK(relative_error(r.sc_percent[0], 100.0) < 1e-12);
    const double vertical = sky == SkyModel::uniform ? 50.0 : vsc;
    CHECK(relative_error(r.sc_percent[1], vertical) < 1e-12);
    CHECK(relative_error(r.sc_percent[2], vertical) < 1e-12);
    // Without the direct view (a grid indoors), nothing reaches them.
    SensorGrid indoors = grid;
    indoors.sees_sky_directly = false;
    CHECK(sky_component(engine, scene, indoors, sky, {}, false, &direct->engine).sc_percent[0] == 0);
  }
  // The gradient in the open is 0: nothing's edge is seen.
  const SkyComponentResult g = sky_component(engine, scene, grid, SkyModel::cie_overcast, {}, true, &direct->engine);
  for (const Vec3& v : g.sc_gradient) CHECK(norm(v) < 1e-12);
}

TEST_CASE("a courtyard's sky seen directly equals the same sky through an aperture over it, and a window into a room adds none") {
  const Scene open = courtyard(false), roofed = courtyard(true);
  const SensorGrid grid = outdoor_grid(courtyard_sensors());
  const VisibilityEngine open_engine(open, GeometryMode::exact), roofed_engine(roofed, GeometryMode::exact);
  const auto direct = direct_sky(open, {grid}, GeometryMode::exact, SubtractionOrder::front_to_back);
  for (const bool gradient : {false, true}) {
    const SkyComponentResult seen = sky_component(open_engine, open, grid, SkyModel::cie_overcast, {}, gradient, &direct->engine);
    const SkyComponentResult through = sky_component(roofed_engine, roofed, grid, SkyModel::cie_overcast, {}, gradient);
    for (std::size_t i = 0; i < grid.sensors.size(); ++i) {
      INFO("sensor " << i << " directly " << seen.sc_percent[i] << " through the opening " << through.sc_percent[i]);
      CHECK(through.sc_percent[i] > 0.5);
      // One visible region, two partitions of it into loops: roundoff of the sums.
      CHECK(relative_error(seen.sc_percent[i], through.sc_percent[i]) < 1e-11);
      if (gradient) {
        // The faces' shared edges cancel; the walls' top edges give the whole gradient. Both are
        // computed to kGradientTolerance (1e-7 of |∇SC|).
        CHECK(norm(seen.sc_gradient[i] - through.sc_gradient[i]) <= 1e-6 * norm(through.sc_gradient[i]) + 1e-12);
      }
    }
  }
  // Without the direct view the courtyard's sensors get nothing: the window's view ends on the
  // room's walls (occluders beyond an aperture hide the sky behind it), so no sky comes that way.
  SensorGrid indoors = grid;
  indoors.sees_sky_directly = false;
  for (const double v : sky_component(open_engine, open, indoors, SkyModel::cie_overcast, {}, false, &direct->engine).sc_percent)
    CHECK(v == 0);
}

TEST_CASE("the sun seen directly: its whole disk in the open, none of it behind a courtyard's wall") {
  Scene scene = courtyard(false);
  const Vec3 sun = normalized(Vec3{0.2, -0.3, 0.9});  // from the south-east, 68° up
  const SensorGrid grid = outdoor_grid({{{50, -40, 0.5}, {0, 0, 1}},   // in the open, outside the courtyard
                                        {{5, 1, 0.85}, {0, 0, 1}},     // in the south wall's shadow
                                        {{5, 7, 0.85}, {0, 0, 1}}});   // in the sun
  const VisibilityEngine engine(scene, GeometryMode::exact);
  const auto direct = direct_sky(scene, {grid}, GeometryMode::exact, SubtractionOrder::front_to_back);
  DaylightConditions c;
  c.sky = DaylightConditions::Sky::cie_overcast;
  c.zenith_luminance = 1;
  c.sun = sun;
  c.direct_normal = 80000;
  const IlluminanceResult r = illuminance(engine, scene, grid, c, {}, &direct->engine);
  // A uniform disk wholly visible gives E_dn (n · sun) to the disk's flattening, (ρ²/4)·(n·sun)
  // relative (ρ = 4.65 mrad): 6e-6.
  CHECK(relative_error(r.sun_lux[0], 80000 * sun.z) < 1e-5);
  // The south wall's top is 11.15 m above the sensor and 1 m south: the sun is behind it; from
  // 7 m north of the wall it passes 9.7 m above the wall's top.
  CHECK(r.sun_lux[1] == 0);
  CHECK(relative_error(r.sun_lux[2], 80000 * sun.z) < 1e-5);
  // The sky by the illuminance path is the sky component's (L_z = 1: E = SC/100 · 7π/9).
  const SkyComponentResult sc = sky_component(engine, scene, grid, SkyModel::cie_overcast, {}, false, &direct->engine);
  for (std::size_t i = 0; i < grid.sensors.size(); ++i) CHECK(relative_error(r.sky_lux[i], sc.sc_percent[i] / 100 * 7 * kPi / 9) < 1e-12);
}

TEST_CASE("a facade sensor in the open sees the far ground directly: ERC ρ_g/2, all of its reflected light external") {
  // The sensor, facing +y, sees the lower quarter-sphere of far ground of luminance ρ_g E_out/π,
  // which gives ρ_g E_out/π · π/2: ERC = 50 ρ_g %.
  const Scene scene = in_the_open();
  const SensorGrid grid = outdoor_grid({{{0, 0, 10}, {0, 1, 0}}});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  ReflectionOptions o;
  o.ground_reflectance = 0.2;
  o.element_size = 2;
  const ReflectionResult r = reflected_components(scene, {0.5}, engine, {&grid}, o);
  CHECK(relative_error(r.grids[0].erc_percent[0], 10.0) < 1e-12);
  CHECK(r.grids[0].irc_percent[0] == 0);
  // Indoors (no direct view), the far ground would reach it only through the hatch: none.
  SensorGrid indoors = grid;
  indoors.sees_sky_directly = false;
  const ReflectionResult none = reflected_components(scene, {0.5}, engine, {&indoors}, o);
  CHECK(none.grids[0].erc_percent[0] == 0);
  // The annual runs' operator keeps it per sensor, ∫(n·u) dσ over the lower quarter-sphere: π/2.
  const ReflectionOperator op = reflection_operator(scene, {0.5}, engine, {&grid}, o);
  CHECK(relative_error(op.sensor_ground_direct[0][0], kPi / 2) < 1e-12);
  const ReflectionOperator op_indoors = reflection_operator(scene, {0.5}, engine, {&indoors}, o);
  CHECK(op_indoors.sensor_ground_direct[0][0] == 0);
  // Outdoors is what df takes it for: anything seen directly, sky or far ground alone. A sensor
  // facing down sees no sky, only far ground (π, all of it; below the hatch, nothing of the scene
  // is in front of it): it is outdoors too, so that annual runs give it the light from outdoors
  // undimmed by any window's blinds, as df does.
  CHECK(op.sensor_outdoors[0][0] == 1);
  CHECK(op_indoors.sensor_outdoors[0][0] == 0);
  const SensorGrid down = outdoor_grid({{{0, 0, -60}, {0, 0, -1}}});
  const ReflectionOperator op_down = reflection_operator(scene, {0.5}, engine, {&down}, o);
  CHECK(op_down.sensor_outdoors[0][0] == 1);
  CHECK(relative_error(op_down.sensor_ground_direct[0][0], kPi) < 1e-12);
  const ReflectionResult r_down = reflected_components(scene, {0.5}, engine, {&down}, o);
  CHECK(relative_error(r_down.grids[0].erc_percent[0], 20.0) < 1e-12);
  CHECK(r_down.grids[0].irc_percent[0] == 0);
}

TEST_CASE("a façade sensor facing a long obstruction of profile angle 25° sees BRE's 27.3 % directly") {
  // The wall 1e7 long either way: it misses O(1/L) of the sky (SKY.md's closed form for an
  // infinitely long obstruction: VSC = (3π(1 − sin α) + 8 cos² α)/(14π)).
  const double L = 1e7, alpha = 25 * kPi / 180, distance = 11, top = 10 + distance * std::tan(alpha);
  Scene scene = in_the_open();
  scene.occluders.push_back(polygon({{-L, distance, 0}, {L, distance, 0}, {L, distance, top}, {-L, distance, top}}, "building"));
  const SensorGrid grid = outdoor_grid({{{0, 0, 10}, {0, 1, 0}}});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  const auto direct = direct_sky(scene, {grid}, GeometryMode::exact, SubtractionOrder::front_to_back);
  const double expected = (3 * kPi * (1 - std::sin(alpha)) + 8 * std::cos(alpha) * std::cos(alpha)) / (14 * kPi);
  const double value = sky_component(engine, scene, grid, SkyModel::cie_overcast, {}, false, &direct->engine).sc_percent[0];
  CHECK(std::abs(value / 100 - expected) < 1e-6);
}

TEST_CASE("annual: a sensor in the open gets the whole diffuse horizontal illuminance and the sun, every hour") {
  const Scene scene = in_the_open();
  const SensorGrid grid = outdoor_grid({{{0, 0, 10}, {0, 0, 1}}});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  const auto direct = direct_sky(scene, {grid}, GeometryMode::exact, SubtractionOrder::front_to_back);
  PerezConditionInput in;
  in.diffuse_horizontal_irradiance = 100;
  in.direct_normal_irradiance = 600;
  in.sun_zenith_deg = 40;
  const Vec3 sun = normalized(Vec3{0, -1, 1.2});
  const PerezSky sky(perez_condition(in, PerezClamps::radiance), sun, PerezClamps::radiance);
  AnnualOptions options;
  options.degree = 8;
  AnnualSky year;
  for (const double dn : {0.0, 3000.0, 60000.0}) {
    AnnualHour h = annual_hour(sky, sun, 12000, dn, options);
    h.occupied = true;
    year.hours.push_back(std::move(h));
  }
  const AnnualGridResult r = annual_grid(engine, scene, grid, year, options, {}, nullptr, {}, direct.get());
  for (std::size_t h = 0; h < year.hours.size(); ++h) {
    const double sun_lux = year.hours[h].direct_normal_lux * sun.z;
    INFO("hour " << h << ": " << r.illuminance[h] << " lx, bound " << r.max_bound_lux[0]);
    // The Perez sky is normalised to the diffuse horizontal illuminance exactly: the sky part is
    // it, within the hour's stated bound (the smooth fit and the circumsolar cubature) and the
    // float the hourly results are kept in; the sun's disk whole, to its flattening (6e-6).
    CHECK(std::abs(r.illuminance[h] - (12000 + sun_lux)) <= r.max_bound_lux[0] + 1e-6 * (12000 + sun_lux));
    // The bound is the fit's worst case over the sky times ∫(n·u) (308 lx here); the residual
    // itself averages out over the whole hemisphere: measured 0.6 lx (5e-5). A direct view that
    // missed a face of the box, or counted one twice, would be off by a sixth of the sky or more.
    CHECK(std::abs(r.illuminance[h] - (12000 + sun_lux)) <= 1e-4 * (12000 + sun_lux));
    CHECK(std::abs(r.direct_sun[h] - sun_lux) <= 1e-5 * sun_lux);
  }
  // A grid indoors (no direct view) here gets nothing.
  SensorGrid indoors = grid;
  indoors.sees_sky_directly = false;
  const AnnualGridResult none = annual_grid(engine, scene, indoors, year, options, {}, nullptr, {}, direct.get());
  for (const float v : none.illuminance) CHECK(v == 0);
}
