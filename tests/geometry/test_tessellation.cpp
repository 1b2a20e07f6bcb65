// Radiance's curved primitives as inscribed facets (rad_tessellation.hpp): vertices on the true
// surface, facets within the stated deviation of it, closed where the surface is, oriented as
// Radiance orients it; and what the tessellation changes, bounded: the sky seen through a
// tessellated disk lies between the closed forms for the disk and for the disk inscribed in the
// polygon.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "geometry/rad_reader.hpp"
#include "geometry/rad_tessellation.hpp"
#include "materials/scene_materials.hpp"
#include "simulation/sky_component.hpp"

using namespace daylit;
using Catch::Contains;

namespace {

constexpr double kPi = std::numbers::pi;

Tessellation tessellate(const std::string& type, const std::vector<double>& reals) {
  return tessellate_primitive(type, "x", "void", reals, {"scene.rad", 1});
}

Vec3 centroid(const Polygon& p) {
  Vec3 c;
  for (const Vec3& v : p.vertices) c += v;
  return (1.0 / double(p.vertices.size())) * c;
}

double area(const Polygon& p) { return norm(newell_normal(p.vertices)) / 2; }

}  // namespace

TEST_CASE("tessellation: a sphere's facets are inscribed, closed, outward, and within the stated deviation") {
  const Vec3 c{1, -2, 3};
  const double r = 0.7;
  const Tessellation t = tessellate("sphere", {c.x, c.y, c.z, r});
  REQUIRE(t.facets.size() > 100);
  CHECK(t.max_deviation <= 0.01 * r);
  Vec3 total{};
  double volume = 0;
  for (const Polygon& f : t.facets) {
    for (const Vec3& v : f.vertices) CHECK(std::abs(norm(v - c) - r) <= 1e-15 * 8 * r);
    const Vec3 n = newell_normal(f.vertices);
    total += n;
    // Outward, and the facet's plane no farther inside than the stated deviation.
    const Vec3 u = normalized(n);
    CHECK(dot(u, centroid(f) - c) > 0);
    CHECK(dot(u, f.vertices[0] - c) >= r - t.max_deviation * (1 + 1e-12));
    volume += dot(f.vertices[0] - c, n) / 6;  // divergence theorem: (1/3) Σ (x·n̂) A
  }
  CHECK(norm(total) <= 1e-12 * r * r);  // closed
  const double exact = 4.0 / 3 * kPi * r * r * r;
  CHECK(volume < exact);  // inscribed
  CHECK(volume > exact * std::pow(1 - t.max_deviation / r, 3));
  // A negative radius turns the normals inward (Radiance's bubble).
  const Tessellation bubble = tessellate("sphere", {c.x, c.y, c.z, -r});
  for (const Polygon& f : bubble.facets) CHECK(dot(newell_normal(f.vertices), centroid(f) - c) < 0);
}

TEST_CASE("tessellation: rings, cylinders, tubes, cones and cups have the inscribed polygons' areas and Radiance's sides") {
  SECTION("ring: the annulus of n chords, along its normal") {
    const Tessellation t = tessellate("ring", {0, 0, 2, 0, 0, 3, 0.5, 1.5});
    double a = 0;
    for (const Polygon& f : t.facets) {
      a += area(f);
      CHECK(newell_normal(f.vertices).z > 0);
    }
    const int n = t.segments;
    CHECK(std::abs(a - n * 0.5 * (1.5 * 1.5 - 0.5 * 0.5) * std::sin(2 * kPi / n)) <= 1e-13 * a);
    CHECK(t.max_deviation == Approx(1.5 * (1 - std::cos(kPi / n))).epsilon(1e-14));
  }
  SECTION("cylinder outward, tube inward; n rectangles of the inscribed prism") {
    for (const char* type : {"cylinder", "tube"}) {
      const Tessellation t = tessellate(type, {0, 0, 0, 0, 0, 2, 0.3});
      double a = 0;
      for (const Polygon& f : t.facets) {
        a += area(f);
        const Vec3 radial{centroid(f).x, centroid(f).y, 0};
        CHECK((dot(newell_normal(f.vertices), radial) > 0) == (std::string(type) == "cylinder"));
      }
      const int n = t.segments;
      CHECK(std::abs(a - n * 2 * 0.3 * std::sin(kPi / n) * 2) <= 1e-13 * a);
    }
  }
  SECTION("cone outward, cup inward, to a point") {
    for (const char* type : {"cone", "cup"}) {
      const Tessellation t = tessellate(type, {0, 0, 0, 0, 0, 1, 0.5, 0});
      for (const Polygon& f : t.facets) {
        CHECK(f.vertices.size() == 3);
        const Vec3 radial{centroid(f).x, centroid(f).y, 0};
        CHECK((dot(newell_normal(f.vertices), radial) > 0) == (std::string(type) == "cone"));
      }
    }
  }
}

TEST_CASE("tessellation: the sky through a tessellated disk lies between the circumscribed and inscribed disks' closed forms") {
  // A skylight as a Radiance ring (a disk of radius R, h above a horizontal receiver on its axis):
  // under the uniform sky SC = 100 R²/(R² + h²) (Howell's coaxial disk). The n-gon lies between
  // the disks of radii R cos(π/n) and R, so its SC lies between theirs.
  const double R = 0.6, h = 2.5;
  RadContent content;
  read_rad_text("void ring skylight 0 0 8 0 0 3 0 0 -1 0 0.6\n", "apertures.rad", true, content);
  REQUIRE(content.polygons.size() == 1);
  bool said = false;
  for (const auto& notice : content.notices) said |= notice.find("tessellated") != std::string::npos;
  CHECK(said);
  const Scene scene = assemble_scene(content);
  REQUIRE(scene.apertures.size() == 1);
  const VisibilityEngine engine(scene, GeometryMode::exact);
  VisibilityCounters counters;
  const double sc = sky_component_percent(engine, scene, {{0, 0, 3 - h}, {0, 0, 1}}, SkyModel::uniform, counters);
  const int n = tessellate("ring", {0, 0, 3, 0, 0, -1, 0, R}).segments;
  const auto disk = [&](double r) { return 100 * r * r / (r * r + h * h); };
  const double inner = R * std::cos(kPi / n);
  INFO("sc " << sc << " between " << disk(inner) << " and " << disk(R));
  CHECK(sc <= disk(R));
  CHECK(sc >= disk(inner));
  // The n-gon's area is sin(2π/n)/(2π/n) of the disk's (1.2 % less at n = 23): the SC of a small
  // source is nearly proportional to its area, so the shortfall is about that (measured 1.17 %).
  const double area_ratio = std::sin(2 * kPi / n) / (2 * kPi / n);
  CHECK(std::abs(sc - disk(R)) / disk(R) <= 1 - area_ratio);
}
