// The sky in Reinhart's patches (sky_patches.hpp): the layout tiles the hemisphere, each patch's
// coefficient is the exact integral over its part of the visible region (against the closed form
// of a patch of the whole hemisphere seen by a horizontal receiver, and summing to the region's
// Lambert integral), and the hour's patch luminances give its diffuse horizontal illuminance as
// gendaymtx normalises them.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "illumination/moments.hpp"
#include "simulation/annual.hpp"
#include "simulation/sky_patches.hpp"
#include "test_scenes.hpp"
#include "test_support.hpp"

using namespace daylit;
using daylit::test::polygon;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

// The five faces of a box above a receiver at the origin: with the horizon cut, their regions
// partition the upper hemisphere.
Scene hemisphere_box() {
  Scene s;
  for (const auto& v : std::vector<std::vector<Vec3>>{{{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
                                                      {{-1, -1, 0}, {1, -1, 0}, {1, -1, 1}, {-1, -1, 1}},
                                                      {{1, -1, 0}, {1, 1, 0}, {1, 1, 1}, {1, -1, 1}},
                                                      {{1, 1, 0}, {-1, 1, 0}, {-1, 1, 1}, {1, 1, 1}},
                                                      {{-1, 1, 0}, {-1, -1, 0}, {-1, -1, 1}, {-1, 1, 1}}})
    s.apertures.push_back({polygon(v), 1.0});
  return s;
}

}  // namespace

TEST_CASE("sky patches: 144 MF^2 + 1 patches tile the hemisphere, each holding its centre") {
  const Site site = Site::geographic(41.98, -87.9, 201, 30);  // north turned 30° from +y
  for (int mf : {1, 2, 4, 6}) {
    const std::vector<SkyPatch> patches = reinhart_patches(mf, site);
    CHECK(patches.size() == std::size_t(144 * mf * mf + 1));
    double total = 0;
    for (const SkyPatch& p : patches) {
      total += p.solid_angle;
      const double altitude = std::asin(p.centre.z) / kDeg;
      CHECK(altitude >= p.altitude0_deg);
      CHECK(altitude <= p.altitude1_deg);
      if (p.altitude1_deg >= 90) continue;
      CHECK(dot(p.from, p.centre) > 0);  // inside its wedge
      CHECK(dot(p.to, p.centre) > 0);
      // The patch the sun patches put a direction in (reinhart_patch_centre) is this one.
      const SkyPatchCentre c = reinhart_patch_centre(0.5 * (p.azimuth0_deg + p.azimuth1_deg), altitude, mf);
      CHECK(norm(site.model_direction(c.azimuth_deg, c.altitude_deg) - p.centre) < 1e-12);
    }
    CHECK(std::abs(total - 2 * std::numbers::pi) < 1e-12);
  }
}

TEST_CASE("sky patches: each patch of the whole hemisphere gives a horizontal receiver its closed form") {
  // ∫ over the patch of cos θ dσ = Δφ (sin² α1 − sin² α0) / 2; the polar cap π cos² α0.
  const Site site = Site::geographic(41.98, -87.9, 201, 30);
  const Scene box = hemisphere_box();
  const VisibilityEngine engine(box, GeometryMode::exact);
  const Vec3 up{0, 0, 1};
  for (int mf : {1, 3}) {
    const std::vector<SkyPatch> patches = reinhart_patches(mf, site);
    std::vector<double> dc(patches.size(), 0.0);
    double spread = 0;
    VisibilityCounters counters;
    for (std::size_t a = 0; a < box.apertures.size(); ++a)
      add_patch_coefficients(patches, engine.visible_region({0, 0, 0}, up, a, counters), up, box.apertures[a], dc, spread);
    CHECK(spread == 0);
    double total = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      const SkyPatch& p = patches[i];
      const double s0 = std::sin(p.altitude0_deg * kDeg), s1 = std::sin(p.altitude1_deg * kDeg);
      const double exact = (p.azimuth1_deg - p.azimuth0_deg) * kDeg * (s1 * s1 - s0 * s0) / 2;
      INFO("MF " << mf << " patch " << i);
      // cap_lambert's accuracy is ~1e-13 of π sin²ρ (cap_clip.hpp): 1e-12 absolute is its size here.
      CHECK(std::abs(dc[i] - exact) < 1e-12);
      total += dc[i];
    }
    CHECK(std::abs(total - std::numbers::pi) < 1e-11);
  }
}

TEST_CASE("sky patches: the patches of a window's region add up to its Lambert integral, glazed or not") {
  const Site site = Site::geographic(41.98, -87.9, 201, 0);
  Scene scene;
  scene.apertures.push_back({polygon({{0, 2, 1}, {2, 2, 1}, {2, 2, 2.2}, {0, 2, 2.2}}), 0.7});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  VisibilityCounters counters;
  for (const Vec3 n : {Vec3{0, 0, 1}, normalized(Vec3{0.3, 1, 0.4})}) {
    const SphericalRegion region = engine.visible_region({0.7, -1.5, 0.85}, n, 0, counters);
    REQUIRE(!region.empty());
    for (int mf : {1, 6}) {
      const std::vector<SkyPatch> patches = reinhart_patches(mf, site);
      std::vector<double> dc(patches.size(), 0.0);
      double spread = 0;
      add_patch_coefficients(patches, region, n, scene.apertures[0], dc, spread);
      double total = 0;
      for (double d : dc) total += d;
      CHECK(std::abs(total - 0.7 * lambert(region, n)) <= 1e-12 * lambert(region, n));
    }
  }
}

TEST_CASE("sky patches: an hour's patch luminances give its diffuse horizontal illuminance as gendaymtx sums it") {
  const Site site = Site::geographic(41.98, -87.9, 201, 0);
  PerezConditionInput in;
  in.diffuse_horizontal_irradiance = 120;
  in.direct_normal_irradiance = 600;
  in.sun_zenith_deg = 40;
  const Vec3 sun = normalized(Vec3{0.3, -0.5, std::cos(40 * kDeg) / std::sin(40 * kDeg) * std::hypot(0.3, 0.5)});
  const PerezSky sky(perez_condition(in, PerezClamps::radiance), sun, PerezClamps::radiance);
  for (int mf : {1, 4}) {
    const std::vector<SkyPatch> patches = reinhart_patches(mf, site);
    const std::vector<double> L = patch_luminances(patches, sky, 15000);
    double sum = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      sum += L[i] * patches[i].solid_angle * patches[i].centre.z;
      CHECK(L[i] > 0);
    }
    CHECK(std::abs(sum - 15000) < 1e-9 * 15000);
    // The brightest patch is near the sun (the circumsolar peak).
    std::size_t brightest = 0;
    for (std::size_t i = 1; i < L.size(); ++i)
      if (L[i] > L[brightest]) brightest = i;
    CHECK(std::acos(std::min(1.0, dot(patches[brightest].centre, sky.sun()))) < 20 * kDeg);
  }
}

