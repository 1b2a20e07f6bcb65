// The reflected part of annual runs (annual_reflections.hpp): the reflection operator against the
// radiosity solution it rewrites, the direction grid's first bounce against the exact one, and the
// sun's interpolation between grid directions, each within what the run's estimate says.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "illumination/moments.hpp"
#include "simulation/annual_reflections.hpp"
#include "simulation/reflected_components.hpp"
#include "sky/sky_model.hpp"
#include "test_scenes.hpp"
#include "window_room.hpp"

using namespace daylit;
using daylit::test::polygon;

namespace {

constexpr double kPi = std::numbers::pi;

// The window room with glass that transmits T(μ) = 0.1 + 0.8 μ, and optionally a ground polygon
// outside the window (lit by the sky directly: the "lit outdoors" channel; seen through the window).
struct GlazedRoom : test::WindowRoom {
  explicit GlazedRoom(bool ground) {
    scene.apertures[0].angular_transmittance = {0.1, 0.8};
    scene.apertures[0].polygon.material = "glass";
    if (ground) {
      scene.occluders.push_back(polygon({{-4, -6, 0}, {6, -6, 0}, {6, 0, 0}, {-4, 0, 0}}, "ground"));
      reflectance.push_back(0.2);
    }
  }
};

ReflectionOptions options(double element_size) {
  ReflectionOptions o;
  o.element_size = element_size;
  o.tolerance_percent = 1e-9;
  return o;
}

// ERC + IRC at every sensor (lux) through the operator, each node's first bounce computed from its
// views exactly: the uniform sky of luminance 1 (and the far ground ρ_g E_h/π, E_h = π).
std::vector<double> operator_uniform_sky(const Scene& scene, const ReflectionOperator& op, double rho_g) {
  const std::size_t n = op.nodes.size(), apertures = scene.apertures.size();
  std::vector<double> first(n, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    for (const LightView& v : op.nodes[k].views) {
      const Aperture* a = v.aperture >= 0 ? &scene.apertures[std::size_t(v.aperture)] : nullptr;
      double sky = 0;
      if (!v.above.empty())
        sky = a != nullptr && !a->angular_transmittance.empty()
                  ? sky_irradiance_through_glazing(v.above, op.nodes[k].normal, SkyModel::uniform,
                                                   normalized(newell_normal(a->polygon.vertices)), a->angular_transmittance)
                  : (a != nullptr ? a->transmittance : 1.0) * lambert(v.above, op.nodes[k].normal);
      first[k] += sky + rho_g * v.ground;
    }
  const std::vector<double>& w = op.response[0];
  const std::size_t sensors = op.sensor_ground[0].size() / apertures;
  std::vector<double> out(sensors, 0.0);
  for (std::size_t s = 0; s < sensors; ++s) {
    for (std::size_t k = 0; k < n; ++k) out[s] += w[s * n + k] * first[k];
    for (std::size_t a = 0; a < apertures; ++a) out[s] += rho_g * op.sensor_ground[0][s * apertures + a];
  }
  return out;
}

double total(const ReflectedHours& r, std::size_t sensor, std::size_t hour) {
  double sum = 0;
  for (std::size_t c = 0; c < r.channels; ++c) sum += r.lux[(sensor * r.hours + hour) * r.channels + c];
  return sum;
}

}  // namespace

TEST_CASE("reflection operator: W times the exact first bounce is the radiosity solution on the same mesh") {
  for (bool ground : {false, true}) {
    const GlazedRoom room(ground);
    const VisibilityEngine engine(room.scene, GeometryMode::exact);
    ReflectionOptions o = options(1.0);
    o.sky = SkyModel::uniform;
    const ReflectionResult solved = reflected_components(room.scene, room.reflectance, engine, {&room.grid}, o);
    const ReflectionOperator op = reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, o);
    CHECK(op.elements == solved.elements);
    const std::vector<double> e = operator_uniform_sky(room.scene, op, o.ground_reflectance);
    for (std::size_t s = 0; s < e.size(); ++s) {
      // Percent of E_out = π L; Gauss–Seidel to roundoff against a dense LU: the two solutions of one
      // system, which agree to its condition number (below 10 for ρ ≤ 0.7) times roundoff.
      const double solved_lux = (solved.grids[0].erc_percent[s] + solved.grids[0].irc_percent[s]) * kPi / 100;
      INFO("ground " << ground << ", sensor " << s << ": operator " << e[s] << ", solution " << solved_lux);
      CHECK(e[s] > 0);
      CHECK(std::abs(e[s] - solved_lux) <= 1e-10 * solved_lux);
    }
  }
}

TEST_CASE("reflection operator: a black room does no radiosity work, the far ground seen through the window stays") {
  test::WindowRoom room;
  for (double& r : room.reflectance) r = 0;
  const VisibilityEngine engine(room.scene, GeometryMode::exact);
  const ReflectionOperator op = reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, options(1.0));
  CHECK(op.nodes.empty());
  // The sensor facing the window (index 3) sees the far ground below the horizon through it.
  CHECK(op.sensor_ground[0][3] > 0.1);
  CHECK(op.sensor_ground[0][0] == 0);
}

TEST_CASE("reflection operator: one over the node limit says whether a larger element size would help") {
  // The room at 1 m has n nodes; at a size larger than the room, f < n (each surface's own
  // triangles, split once). A limit between them: raise the size; a limit below f: no size helps.
  const test::WindowRoom room;
  const VisibilityEngine engine(room.scene, GeometryMode::exact);
  const std::size_t n = reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, options(1.0)).nodes.size();
  const std::size_t f = reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, options(1e6)).nodes.size();
  REQUIRE(f < n);
  CHECK_THROWS_WITH(reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, options(1.0), false, n - 1),
                    Catch::Contains(std::to_string(n) + " nodes (at most " + std::to_string(n - 1) + ")") &&
                        Catch::Contains("raise --element-size (the coarsest mesh has " + std::to_string(f) + ")"));
  CHECK_THROWS_WITH(reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, options(1.0), false, f - 1),
                    Catch::Contains("and " + std::to_string(f) + " at any --element-size") &&
                        !Catch::Contains("raise --element-size"));
  CHECK(reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, options(1.0), false, n).nodes.size() == n);
}

TEST_CASE("reflection operator: one whose dense LU and rows would not fit the memory allowed is refused, naming its size") {
  const test::WindowRoom room;
  const VisibilityEngine engine(room.scene, GeometryMode::exact);
  ReflectionOptions o = options(1.0);
  const ReflectionOperator fits = reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, o);
  const double n = double(fits.nodes.size());
  // Below the LU's 8 n² bytes: refused before the rows are found; at 9 n², refused after them (a
  // room's node sees most of the room's nodes: its rows hold far more than the n²/24 entries that
  // would fit beside the LU); with room for both: built.
  for (const double bytes : {4 * n * n, 9 * n * n}) {
    o.memory_bytes = std::size_t(bytes);
    CHECK_THROWS_WITH(reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, o),
                      Catch::Contains("nodes would need about") && Catch::Contains("raise --element-size"));
  }
  // Below what the coarsest mesh's LU alone needs, no element size helps, and the message says so.
  const double f = double(reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, options(1e6)).nodes.size());
  o.memory_bytes = std::size_t(4 * f * f);
  CHECK_THROWS_WITH(reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, o),
                    Catch::Contains("its LU alone needs") && Catch::Contains("at any --element-size") &&
                        !Catch::Contains("raise --element-size"));
  o.memory_bytes = std::size_t(1e10);
  CHECK(reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, o).nodes.size() == fits.nodes.size());
}

TEST_CASE("annual reflections: the direction grid's first bounce against the exact one, within the estimate") {
  const GlazedRoom room(true);
  const VisibilityEngine engine(room.scene, GeometryMode::exact);
  const ReflectionOptions o = options(1.0);
  const ReflectionOperator op = reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, o);
  const std::vector<int> group_of_aperture{0};

  SECTION("a uniform sky: the interpolant is exact, what is left is the product rule's error") {
    const std::vector<double> exact = operator_uniform_sky(room.scene, op, o.ground_reflectance);
    const ReflectedHours r = reflected_light(room.scene, op, nullptr, {0}, group_of_aperture, 1,
                                             {HourLight{[](const Vec3&) { return 1.0; }, {0, 0, 1}, 0, kPi}},
                                             o.ground_reflectance).grids.front();
    for (std::size_t s = 0; s < exact.size(); ++s) {
      INFO("sensor " << s << ": grid " << total(r, s, 0) << ", exact " << exact[s]);
      // float results (the hourly arrays are float32): 1e-6 relative; the rule's own error is below that.
      CHECK(std::abs(total(r, s, 0) - exact[s]) <= 1e-6 * exact[s]);
    }
  }

  SECTION("the CIE overcast sky: against the radiosity solution under it, within the estimate and 2e-4") {
    ReflectionOptions oc = o;
    oc.sky = SkyModel::cie_overcast;
    const ReflectionResult solved = reflected_components(room.scene, room.reflectance, engine, {&room.grid}, oc);
    const double e_out = 7 * kPi / 9;
    const ReflectedHours r = reflected_light(
        room.scene, op, nullptr, {0}, group_of_aperture, 1,
        {HourLight{[](const Vec3& u) { return u.z > 0 ? (1 + 2 * u.z) / 3 : 0.0; }, {0, 0, 1}, 0, e_out}},
        o.ground_reflectance).grids.front();
    for (std::size_t s = 0; s < room.grid.sensors.size(); ++s) {
      const double solved_lux = (solved.grids[0].erc_percent[s] + solved.grids[0].irc_percent[s]) * e_out / 100;
      const double error = std::abs(total(r, s, 0) - solved_lux);
      INFO("sensor " << s << ": grid " << total(r, s, 0) << ", solution " << solved_lux << ", estimate "
                     << r.estimate[s]);
      CHECK(error <= 2e-4 * solved_lux);
      CHECK(error <= r.estimate[s] + 1e-6 * solved_lux);  // float rounding of the results
    }
  }
}

TEST_CASE("annual reflections: the sun's first bounce is reflected_components', on and off the direction grid") {
  const GlazedRoom room(true);
  const VisibilityEngine engine(room.scene, GeometryMode::exact);
  const ReflectionOptions o = options(1.0);
  const ReflectionOperator op = reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, o);
  const DirectionGrid grid;
  const double e_dn = 1e5;
  // The sun through the window (the room lies at y > 0): azimuth 270° from +x is −y.
  const Vec3 on_grid = grid.direction(grid.vertex(14, 54));  // altitude 35°
  const Vec3 off_grid = normalized(Vec3{0.31, -0.8, 0.55});
  for (int which = 0; which < 2; ++which) {
    const Vec3 sun = which == 0 ? on_grid : off_grid;
    // The same sun in reflected_components, integrated over its elements there too
    // (sunlit_elements.hpp), with a dark sky.
    ReflectionOptions os = o;
    os.light = [](const SphericalRegion&, const Vec3&, const Aperture*) { return 0.0; };
    os.light_horizontal = e_dn * sun.z;
    os.sun = ReflectionOptions::Sun{sun, e_dn};
    const ReflectionResult solved = reflected_components(room.scene, room.reflectance, engine, {&room.grid}, os);
    const ReflectedHours r = reflected_light(room.scene, op, nullptr, {0}, {0}, 1,
                                             {HourLight{[](const Vec3&) { return 0.0; }, sun, e_dn, e_dn * sun.z}},
                                             o.ground_reflectance).grids.front();
    for (std::size_t s = 0; s < room.grid.sensors.size(); ++s) {
      const double solved_lux = (solved.grids[0].erc_percent[s] + solved.grids[0].irc_percent[s]) * os.light_horizontal / 100;
      const double error = std::abs(total(r, s, 0) - solved_lux);
      INFO("sun " << sun.x << " " << sun.y << " " << sun.z << ", sensor " << s << ": grid " << total(r, s, 0)
                  << ", solution " << solved_lux << ", estimate " << r.estimate[s]);
      CHECK(solved_lux > 0);
      CHECK(error <= 1e-6 * solved_lux);  // float results; the sky is dark, so no grid error either
      CHECK(r.estimate[s] <= 1e-6 * solved_lux);
    }
  }
}

TEST_CASE("annual reflections: the sun that came in by the window is counted in its group, the sun on the ground outside in the outdoors channel") {
  // Without the ground polygon, every sunlit element is lit through the window: channel 0 holds
  // all of the sun's reflected light and the outdoors channel (1) nothing, exactly. With it, the
  // ground lit directly sends light in through the window too, counted as outdoors.
  const Vec3 sun = normalized(Vec3{0.31, -0.8, 0.55});
  const double e_dn = 1e5;
  for (const bool ground : {false, true}) {
    const GlazedRoom room(ground);
    const VisibilityEngine engine(room.scene, GeometryMode::exact);
    const ReflectionOperator op = reflection_operator(room.scene, room.reflectance, engine, {&room.grid}, options(1.0));
    const ReflectedHours r = reflected_light(room.scene, op, nullptr, {0}, {0}, 1,
                                             {HourLight{[](const Vec3&) { return 0.0; }, sun, e_dn, e_dn * sun.z}}, 0.0).grids.front();
    REQUIRE(r.channels == 2);
    for (std::size_t s = 0; s < room.grid.sensors.size(); ++s) {
      const float window = r.lux[s * r.channels], outdoors = r.lux[s * r.channels + 1];
      INFO("ground " << ground << ", sensor " << s << ": window " << window << ", outdoors " << outdoors);
      CHECK(window > 0);
      if (ground)
        CHECK(outdoors > 0);
      else
        CHECK(outdoors == 0);
    }
  }
}

TEST_CASE("annual reflections: grids found together give each grid what it gets alone, bit for bit") {
  // The per-node work (the direction grids' columns, the sun's first bounce on the elements) is
  // shared by the grids of a batch; what each sensor gets must not depend on which grids share it.
  const GlazedRoom room(true);
  SensorGrid half = room.grid;
  half.name = "half";
  half.sensors.resize(room.grid.sensors.size() / 2);
  for (Sensor& s : half.sensors) s.position.z += 0.3;
  const VisibilityEngine engine(room.scene, GeometryMode::exact);
  const ReflectionOperator op = reflection_operator(room.scene, room.reflectance, engine, {&room.grid, &half}, options(1.0));
  const Vec3 sun = normalized(Vec3{0.31, -0.8, 0.55});
  const std::vector<HourLight> hours{
      HourLight{[](const Vec3& u) { return u.z > 0 ? 1000 * (1 + 2 * u.z) / 3 : 0.0; }, sun, 5e4, 5e4 * sun.z + 2000},
      HourLight{},  // a dark hour
      HourLight{[](const Vec3& u) { return u.z > 0 ? 300.0 : 0.0; }, {0, 0, 1}, 0, 300 * kPi}};
  const ReflectedGrids together = reflected_light(room.scene, op, nullptr, {0, 1}, {0}, 1, hours, 0.2);
  REQUIRE(together.grids.size() == 2);
  for (const std::size_t g : {0, 1}) {
    const ReflectedHours alone = reflected_light(room.scene, op, nullptr, {g}, {0}, 1, hours, 0.2).grids.front();
    INFO("grid " << g);
    CHECK(together.grids[g].sensors == (g == 0 ? room.grid.sensors.size() : half.sensors.size()));
    CHECK(together.grids[g].lux == alone.lux);
    CHECK(together.grids[g].estimate == alone.estimate);
    CHECK(together.grids[g].outdoors == alone.outdoors);
  }

  SECTION("batches follow the grids' order and hold at most the bytes asked, a larger grid alone") {
    // Per grid: sensors × hours × (groups + 2) floats.
    const std::size_t full = room.grid.sensors.size() * 3 * 3 * sizeof(float), part = half.sensors.size() * 3 * 3 * sizeof(float);
    CHECK(reflected_batches(op, 3, 1, full + part) == std::vector<std::vector<std::size_t>>{{0, 1}});
    CHECK(reflected_batches(op, 3, 1, full + part - 1) == std::vector<std::vector<std::size_t>>{{0}, {1}});
    CHECK(reflected_batches(op, 3, 1, 1) == std::vector<std::vector<std::size_t>>{{0}, {1}});
  }
}
