// Illuminance in lux from the sky and the sun (sky/illuminance.hpp): the overcast sky agrees with
// the daylight factor, the CIE fit stays within the bound it reports against cubature, glazing
// under a CIE sky (cubature) agrees with the closed forms where both exist, and the sun switches
// exactly at a shadow edge worked out by hand.

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "test_scenes.hpp"
#include "materials/glass_transmittance.hpp"
#include "simulation/illuminance.hpp"

using namespace daylit;
using test::polygon;

namespace {

constexpr double pi = std::numbers::pi;

// A south-facing window (y = 0, x ∈ [0, 2], z ∈ [1, 2.2], the room at y > 0) with a fin beside
// it, and three sensors inside, one tilted.
Scene window_scene(bool glazed) {
  Scene scene;
  Aperture window{polygon({{0, 0, 1}, {2, 0, 1}, {2, 0, 2.2}, {0, 0, 2.2}}), 1.0};
  if (glazed) {
    const TransmittancePolynomial t = fit_glass_transmittance({{0.96, 0.96, 0.96}});
    window.angular_transmittance = t.coefficients;
    window.transmittance = t.coefficients[0];
  }
  scene.apertures.push_back(window);
  scene.occluders.push_back(polygon({{2.2, 0, 0}, {2.2, -1.5, 0}, {2.2, -1.5, 3}, {2.2, 0, 3}}));
  return scene;
}

SensorGrid sensors() {
  SensorGrid g;
  g.name.push_back('g');  // not = "g": GCC 12 warns falsely (-Wrestrict) on that here
  g.sensors = {{{0.6, 1.5, 0.85}, {0, 0, 1}}, {{1.7, 3.0, 0.85}, {0, 0, 1}}, {{1.0, 0.8, 1.2}, normalized(Vec3{0.2, -1, 0.5})}};
  return g;
}

DaylightConditions cie_general(int type, const Vec3& sun, DaylightConditions::Method method) {
  DaylightConditions c;
  c.sky = DaylightConditions::Sky::cie_general;
  c.cie.emplace(type, sun);
  if (method == DaylightConditions::Method::fit) c.fit = fit_cie_sky(*c.cie);
  c.method = method;
  c.quadrature_tolerance = 1e-12;
  c.zenith_luminance = 1;
  return c;
}

}  // namespace

TEST_CASE("under the overcast sky the illuminance is the daylight factor times the sky's E_out") {
  for (const bool glazed : {false, true}) {
    const Scene scene = window_scene(glazed);
    const VisibilityEngine engine(scene, GeometryMode::exact);
    DaylightConditions c;
    c.zenith_luminance = 10000 / (7 * pi / 9);  // E_out = 10,000 lux
    REQUIRE(unobstructed_sky_irradiance(c) == 7 * pi / 9);
    const IlluminanceResult lux = illuminance(engine, scene, sensors(), c);
    const SkyComponentResult df = sky_component(engine, scene, sensors(), SkyModel::cie_overcast);
    for (std::size_t i = 0; i < 3; ++i) {
      INFO("glazed " << glazed << ", sensor " << i);
      REQUIRE(lux.sky_lux[i] > 0);
      // The same closed form scaled two ways: a few roundings apart.
      CHECK(lux.sky_lux[i] == Approx(df.sc_percent[i] * 100).epsilon(1e-14));
      CHECK(lux.sky_error_lux[i] == 0);
      CHECK(lux.sun_lux[i] == 0);
    }
  }
}

TEST_CASE("a CIE general sky's fit stays within the error bound it reports, against cubature") {
  const Scene scene = window_scene(false);
  const VisibilityEngine engine(scene, GeometryMode::exact);
  // Suns in front of the window, beside it and behind the building.
  for (const Vec3& sun : {normalized(Vec3{0.3, -1, 0.8}), normalized(Vec3{1, 0.1, 0.4}), normalized(Vec3{0, 1, 1.5})}) {
    for (const int type : {3, 7, 12, 15}) {
      const IlluminanceResult fit = illuminance(engine, scene, sensors(), cie_general(type, sun, DaylightConditions::Method::fit));
      const IlluminanceResult quadrature =
          illuminance(engine, scene, sensors(), cie_general(type, sun, DaylightConditions::Method::quadrature));
      for (std::size_t i = 0; i < 3; ++i) {
        INFO("type " << type << ", sensor " << i << ": fit " << fit.sky_lux[i] << " ± " << fit.sky_error_lux[i]
                     << ", cubature " << quadrature.sky_lux[i] << " ± " << quadrature.sky_error_lux[i]);
        REQUIRE(quadrature.sky_lux[i] > 0);
        // The cubature's own estimate: 1e-12 of the region's integral, give or take its estimate.
        CHECK(quadrature.sky_error_lux[i] < 1e-9 * quadrature.sky_lux[i]);
        CHECK(std::abs(fit.sky_lux[i] - quadrature.sky_lux[i]) <= fit.sky_error_lux[i] + quadrature.sky_error_lux[i]);
        CHECK(fit.sky_error_lux[i] > 0);
      }
    }
  }
}

TEST_CASE("behind glass a CIE sky is integrated by cubature, which agrees with the closed forms where both exist") {
  // ISO 15469's type 5 (a = 0, c = e = 0) is the uniform sky: L = L_z everywhere. Through glass
  // the uniform sky has a closed form (T's polynomial times Lambert's cosine: double-axis moments);
  // type 5 through the same glass goes through cubature of L·T.
  const Scene scene = window_scene(true);
  const VisibilityEngine engine(scene, GeometryMode::exact);
  DaylightConditions uniform;
  uniform.sky = DaylightConditions::Sky::uniform;
  uniform.zenith_luminance = 1;
  const IlluminanceResult closed = illuminance(engine, scene, sensors(), uniform);
  const IlluminanceResult cubature =
      illuminance(engine, scene, sensors(), cie_general(5, normalized(Vec3{0.2, -1, 1}), DaylightConditions::Method::fit));
  CHECK(cubature.regions_by_quadrature == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    INFO("sensor " << i);
    // Cubature to 1e-12 of the region's integral, summed over a few fan triangles.
    CHECK(cubature.sky_lux[i] == Approx(closed.sky_lux[i]).epsilon(1e-10));
  }
}

TEST_CASE("the sun switches exactly at a shadow edge worked out by hand") {
  // A skylight at z = 1 over x ∈ [−10, 0], the sun 45° up from −x: s ∝ (−1, 0, 1). From
  // p = (1, 0, 0) the skylight's edge x = 0 is seen along (−1, 0, 1): the sun's centre lies on the
  // edge's great circle, and half the disk is visible. With the sensor facing the sun (n = s) the
  // reflection in the cut's plane swaps the halves and keeps s·u, so the visible half gives
  // exactly E_dn / 2. A sensor 0.05 m to either side sees the edge 25 mrad away, more than the
  // disk's radius of 4.65 mrad: the whole disk, E_dn (n·s) = E_dn, or none of it.
  Scene scene;
  scene.apertures.push_back({polygon({{-10, -10, 1}, {0, -10, 1}, {0, 10, 1}, {-10, 10, 1}}), 1.0});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  DaylightConditions c;
  c.sky = DaylightConditions::Sky::uniform;
  c.zenith_luminance = 0;  // the sun alone
  c.sun = normalized(Vec3{-1, 0, 1});
  c.direct_normal = 80000;
  SensorGrid grid;
  grid.sensors = {{{1, 0, 0}, c.sun}, {{0.95, 0, 0}, c.sun}, {{1.05, 0, 0}, c.sun}, {{0.95, 0, 0}, {0, 0, 1}}};
  const IlluminanceResult r = illuminance(engine, scene, grid, c);
  CHECK(r.sun_lux[0] == Approx(40000).epsilon(1e-13));
  CHECK(r.sun_lux[1] == Approx(80000).epsilon(1e-13));
  CHECK(r.sun_lux[2] == 0);
  CHECK(r.sun_lux[3] == Approx(80000 * std::sqrt(0.5)).epsilon(1e-13));
  for (double sky : r.sky_lux) CHECK(sky == 0);

  SECTION("through glass the sun takes T at the disk's centre") {
    const TransmittancePolynomial t = fit_glass_transmittance({{0.96, 0.96, 0.96}});
    scene.apertures[0].angular_transmittance = t.coefficients;
    const VisibilityEngine glazed(scene, GeometryMode::exact);
    const IlluminanceResult g = illuminance(glazed, scene, grid, c);
    const double mu = std::sqrt(0.5), t45 = evaluate_polynomial(t.coefficients, mu);
    // μ = |a·s| carries a rounding or two, and Σ c_k μ^k (|c_k| up to 1e6) turns them into
    // relative errors of up to (Σ |c_k μ^k| / T) · u each: allow 8 of those.
    double magnitude = 0;
    for (std::size_t k = 0; k < t.coefficients.size(); ++k) magnitude += std::abs(t.coefficients[k]) * std::pow(mu, double(k));
    const double tolerance = 8 * magnitude / t45 * std::numeric_limits<double>::epsilon() / 2 + 1e-13;
    CHECK(g.sun_lux[1] == Approx(80000 * t45).epsilon(tolerance));
    CHECK(g.sun_lux[0] == Approx(40000 * t45).epsilon(tolerance));
  }
  SECTION("no sun below the horizon or without direct light") {
    c.sun = normalized(Vec3{-1, 0, -0.01});
    CHECK_FALSE(c.has_sun());
    CHECK(illuminance(engine, scene, grid, c).sun_lux[1] == 0);
  }
}

TEST_CASE("a CIE general sky needs the sun above the horizon") {
  CHECK_THROWS_AS(CieSky(7, normalized(Vec3{0, 1, -0.1})), Error);
  const Scene scene = window_scene(false);
  const VisibilityEngine engine(scene, GeometryMode::exact);
  DaylightConditions c;
  c.sky = DaylightConditions::Sky::cie_general;  // no type given
  CHECK_THROWS_AS(illuminance(engine, scene, sensors(), c), Error);
}
