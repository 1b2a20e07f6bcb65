// The site: WGS84 and UTM against the model frame (GeographicLib's published examples, the signs of
// the north angle and of the meridian convergence), the site and GeoJSON readers' errors, and the
// context buildings: a prism from GeoJSON gives the same sky component as the same prism written
// in model coordinates, and the culling rules leave out what they say.

#include <catch2/catch.hpp>

#include <GeographicLib/TransverseMercator.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "sky/context_buildings.hpp"
#include "simulation/illuminance.hpp"
#include "sky/site.hpp"
#include "simulation/sky_component.hpp"
#include "test_scenes.hpp"

using namespace daylit;
using Catch::Contains;

namespace {

// ---------------------------------------------------------------------------------------------
// GeoJSON text from plan rings given in model coordinates (converted with the site's inverse).

using Ring = std::vector<PlanPoint>;

std::string position(const Site& site, const PlanPoint& p) {
  const GeographicPosition g = site.wgs84_from_model({p.x, p.y, site.ground_z_m()});
  char text[80];
  std::snprintf(text, sizeof text, "[%.17g, %.17g]", g.longitude_deg, g.latitude_deg);
  return text;
}

std::string rings_json(const Site& site, const std::vector<Ring>& rings) {
  std::string s = "[";
  for (std::size_t r = 0; r < rings.size(); ++r) {
    s += r ? ", [" : "[";
    for (const PlanPoint& p : rings[r]) s += position(site, p) + ", ";
    s += position(site, rings[r][0]) + "]";
  }
  return s + "]";
}

std::string polygon_feature(const Site& site, const std::vector<Ring>& rings, const std::string& properties) {
  return R"({"type": "Feature", "properties": )" + properties + R"(, "geometry": {"type": "Polygon", "coordinates": )" +
         rings_json(site, rings) + "}}";
}

std::string collection(const std::vector<std::string>& features) {
  std::string s = R"({"type": "FeatureCollection", "features": [)";
  for (std::size_t i = 0; i < features.size(); ++i) s += (i ? ",\n" : "\n") + features[i];
  return s + "]}";
}

Ring rectangle(double x0, double x1, double y0, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// The same prism written directly in model coordinates, independently of the reader: walls
// (a, b, b', a') along each ring as given and a roof with seams to the holes. `outline` must be
// anticlockwise and holes clockwise (seen from above).
std::vector<Polygon> prism_in_model(const std::vector<Ring>& rings, double z0, double z1) {
  std::vector<Polygon> faces;
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const PlanPoint a = ring[i], b = ring[(i + 1) % ring.size()];
      faces.push_back(test::polygon({{a.x, a.y, z0}, {b.x, b.y, z0}, {b.x, b.y, z1}, {a.x, a.y, z1}}, "wall"));
    }
  std::vector<Vec3> roof;
  for (const PlanPoint& p : rings[0]) roof.push_back({p.x, p.y, z1});
  for (std::size_t h = 1; h < rings.size(); ++h) {
    roof.push_back({rings[0][0].x, rings[0][0].y, z1});
    for (const PlanPoint& p : rings[h]) roof.push_back({p.x, p.y, z1});
    roof.push_back({rings[h][0].x, rings[h][0].y, z1});
  }
  faces.push_back(test::polygon(roof, "roof"));
  return faces;
}

// A room's window: an opening x 0..3, z 1..2.5 in the plane y = 0, lighting the room at y > 0.
Scene window_scene() {
  Scene scene;
  scene.apertures.push_back({test::polygon({{0, 0, 1}, {0, 0, 2.5}, {3, 0, 2.5}, {3, 0, 1}}, "window"), 1.0});
  return scene;
}

SensorGrid room_grid() {
  SensorGrid grid;
  grid.name = "room";
  for (double x : {0.25, 1.5, 2.9})
    for (double y : {0.5, 1.5, 3.0}) grid.sensors.push_back({{x, y, 0.85}, {0, 0, 1}});
  // Vertical sensors on the window's inner side, facing out (a vertical sky component).
  grid.sensors.push_back({{1.5, 0.01, 1.75}, {0, -1, 0}});
  grid.sensors.push_back({{0.2, 0.3, 2.2}, {0, -1, 0}});
  return grid;
}

// The sun's illuminance (lux, 1000 lux direct normal) at every sensor of the grid.
std::vector<double> sun_illuminance(const Scene& scene, const SensorGrid& grid, const Vec3& sun) {
  const VisibilityEngine engine(scene, GeometryMode::exact);
  DaylightConditions c;
  c.sky = DaylightConditions::Sky::uniform;
  c.zenith_luminance = 1;
  c.sun = sun;
  c.direct_normal = 1000;
  return illuminance(engine, scene, grid, c).sun_lux;
}

std::vector<double> sky_components(const Scene& scene, const SensorGrid& grid) {
  const VisibilityEngine engine(scene, GeometryMode::exact);
  std::vector<double> sc;
  VisibilityCounters counters;
  for (const Sensor& s : grid.sensors) sc.push_back(sky_component_percent(engine, scene, s, SkyModel::cie_overcast, counters));
  return sc;
}

ContextBuildings parse(const std::string& text, const Site& site) {
  return parse_context_buildings(text, "city.geojson", site);
}

const Site kParis = Site::geographic(48.8566, 2.3522, 60, 23.5);

}  // namespace

// ---------------------------------------------------------------------------------------------
// Coordinates.

TEST_CASE("LocalCartesian reproduces CartConvert's published example, and round-trips") {
  // GeographicLib, man page CartConvert(1): echo 33.3 44.4 6000 | CartConvert -l 33 44 20
  // => 37288.97 33374.29 5783.64 (printed to 1 cm).
  const Site site = Site::geographic(33, 44, 20, 0);
  const Vec3 p = site.model_from_wgs84(33.3, 44.4, 6000);
  CHECK(std::abs(p.x - 37288.97) < 0.01);
  CHECK(std::abs(p.y - 33374.29) < 0.01);
  CHECK(std::abs(p.z - 5783.64) < 0.01);
  const GeographicPosition back = site.wgs84_from_model(p);
  CHECK(std::abs(back.latitude_deg - 33.3) < 1e-12);
  CHECK(std::abs(back.longitude_deg - 44.4) < 1e-12);
  CHECK(std::abs(back.height_m - 6000) < 1e-6);
  // Turned by north_deg = 90: true north along +x, east along −y.
  const Site turned = Site::geographic(33, 44, 20, 90);
  const Vec3 q = turned.model_from_wgs84(33.3, 44.4, 6000);
  CHECK(std::abs(q.x - p.y) < 1e-9);
  CHECK(std::abs(q.y + p.x) < 1e-9);
  CHECK(q.z == p.z);
  const GeographicPosition back2 = turned.wgs84_from_model(q);
  CHECK(std::abs(back2.latitude_deg - 33.3) < 1e-12);
  CHECK(std::abs(back2.longitude_deg - 44.4) < 1e-12);
}

TEST_CASE("UTM origins reproduce GeoConvert's published examples") {
  // GeoConvert(1): "33.3 44.4" and "38n 444140.54 3684706.36" are the same point (to 1 cm).
  const Site a = Site::utm(38, true, 444140.54, 3684706.36, 0);
  CHECK(std::abs(a.origin().latitude_deg - 33.3) < 1e-7);  // 1 cm ≈ 9e-8°
  CHECK(std::abs(a.origin().longitude_deg - 44.4) < 1e-7);
  // echo 38SMB4488 | GeoConvert => 33.33424 44.40363; the square's centre is 38n 444500 3688500.
  const Site b = Site::utm(38, true, 444500, 3688500, 0);
  CHECK(std::abs(b.origin().latitude_deg - 33.33424) < 5e-6);
  CHECK(std::abs(b.origin().longitude_deg - 44.40363) < 5e-6);
  // echo -1 3 | GeoConvert -u => 31s 500000 9889470: on the central meridian, no convergence.
  const Site c = Site::utm(31, false, 500000, 9889470, 0);
  CHECK(std::abs(c.origin().latitude_deg + 1) < 1e-5);
  CHECK(std::abs(c.origin().longitude_deg - 3) < 1e-12);
  CHECK(std::abs(c.north_deg()) < 1e-12);
  // The convergence is TransverseMercator's at the zone's central meridian (45° for zone 38), and
  // west of it grid north lies west of true north (γ < 0): true north is then east of +y.
  double x = 0, y = 0, gamma = 0, k = 0;
  GeographicLib::TransverseMercator::UTM().Forward(45, 33.3, 44.4, x, y, gamma, k);
  REQUIRE(a.utm_grid().has_value());
  CHECK(std::abs(a.utm_grid()->convergence_deg - gamma) < 1e-6);  // the origin is 33.3, 44.4 to 1 cm
  CHECK(gamma < 0);
  CHECK(a.north_deg() == -a.utm_grid()->convergence_deg);
  CHECK(a.true_north_in_model().x > 0);
}

TEST_CASE("a point due true north lands on the model's north vector, one due east on its east vector") {
  for (double north_deg : {0.0, 30.0, -75.0, 180.0, 311.5}) {
    const Site site = Site::geographic(52.52, 13.405, 40, north_deg);
    INFO("north_deg " << north_deg);
    const Vec3 n = site.true_north_in_model(), e = site.east_in_model();
    CHECK(std::abs(norm(n) - 1) < 1e-15);
    CHECK(std::abs(dot(n, e)) < 1e-15);
    CHECK(cross(e, n).z == Approx(1));  // east, north, up: right-handed
    // North: on the origin's meridian, so exactly in the plane of up and north.
    const Vec3 p = site.model_from_wgs84(52.52 + 0.002, 13.405, 40);
    const Vec3 horizontal = normalized(Vec3{p.x, p.y, 0});
    CHECK(norm(horizontal - n) < 1e-12);
    // true north clockwise from +y by north_deg (seen from above: from +y towards +x)
    CHECK(std::atan2(n.x, n.y) * 180 / std::numbers::pi == Approx(std::remainder(north_deg, 360)).margin(1e-12));
    // East: a parallel curves towards the pole, by Δλ sin φ / 2 ≈ 1.4e-5 rad here.
    const Vec3 q = site.model_from_wgs84(52.52, 13.405 + 0.002, 40);
    CHECK(norm(normalized(Vec3{q.x, q.y, 0}) - e) < 3e-5);
    // Directions of the sky: azimuth clockwise from true north.
    CHECK(norm(site.model_direction(0, 0) - n) < 1e-15);
    CHECK(norm(site.model_direction(90, 0) - e) < 1e-15);
    CHECK(norm(site.model_direction(123, 90) - Vec3{0, 0, 1}) < 1e-15);
    // Points round-trip.
    const Vec3 m{123.4, -56.7, 8.9};
    const GeographicPosition g = site.wgs84_from_model(m);
    CHECK(norm(site.model_from_wgs84(g.latitude_deg, g.longitude_deg, g.height_m) - m) < 1e-8);
  }
}

TEST_CASE("a UTM model: grid north of the origin lands on +y, true north on true_north_in_model()") {
  // East of zone 33's central meridian (15° E) in the northern hemisphere γ > 0: grid north lies
  // east of true north, so true north lies west of +y in the model.
  const double e0 = 600000, n0 = 5400000;
  const Site site = Site::utm(33, true, e0, n0, 200);
  REQUIRE(site.utm_grid());
  const double gamma = site.utm_grid()->convergence_deg;
  CHECK(gamma > 0.5);
  CHECK(site.north_deg() == -gamma);
  CHECK(site.true_north_in_model().x < 0);
  double lat = 0, lon = 0;
  GeographicLib::UTMUPS::Reverse(33, true, e0, n0 + 300, lat, lon);
  const Vec3 grid_north = site.model_from_wgs84(lat, lon, 200);
  CHECK(grid_north.y > 299);
  // γ changes by ~1e-5° over 300 m; a convergence applied with the wrong sign would give 2 tan γ ≈ 0.03.
  CHECK(std::abs(grid_north.x / grid_north.y) < 1e-5);
  GeographicLib::UTMUPS::Reverse(33, true, e0 + 300, n0, lat, lon);
  const Vec3 grid_east = site.model_from_wgs84(lat, lon, 200);
  CHECK(std::abs(grid_east.y / grid_east.x) < 1e-5);
  const GeographicPosition o = site.origin();
  const Vec3 p = site.model_from_wgs84(o.latitude_deg + 0.003, o.longitude_deg, 200);
  CHECK(norm(normalized(Vec3{p.x, p.y, 0}) - site.true_north_in_model()) < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// The site file.

TEST_CASE("site files in both forms are read") {
  const Site a = parse_site_json(
      R"({"name": "x", "latitude_deg": 41.39, "longitude_deg": 2.16, "elevation_m": 95, "north_deg": 45, "ground_z_m": -1.5})",
      "site.json");
  CHECK(a.origin().latitude_deg == 41.39);
  CHECK(a.north_deg() == 45);
  CHECK(a.ground_z_m() == -1.5);
  CHECK(!a.utm_grid());
  const Site b = parse_site_json(
      R"({"utm": {"zone": 38, "northern": true}, "origin_easting_m": 444140.54, "origin_northing_m": 3684706.36, "elevation_m": 0})",
      "site.json");
  CHECK(std::abs(b.origin().latitude_deg - 33.3) < 1e-7);
  REQUIRE(b.utm_grid());
  CHECK(b.utm_grid()->zone == 38);
  CHECK(b.north_deg() == -b.utm_grid()->convergence_deg);
  CHECK_THAT(b.description(), Contains("UTM zone 38n") && Contains("33.300000° N"));
}

TEST_CASE("bad site files are errors naming the file and the field") {
  const auto bad = [](const std::string& text) { parse_site_json(text, "site.json"); };
  CHECK_THROWS_WITH(bad(R"({"longitude_deg": 2, "elevation_m": 0})"),
                    Contains("site.json: field 'latitude_deg': missing"));
  CHECK_THROWS_WITH(bad(R"({"latitude_deg": "41", "longitude_deg": 2, "elevation_m": 0})"),
                    Contains("field 'latitude_deg': must be a number, not a string"));
  CHECK_THROWS_WITH(bad(R"({"latitude_deg": 91, "longitude_deg": 2, "elevation_m": 0})"),
                    Contains("field 'latitude_deg'") && Contains("between -90 and 90"));
  CHECK_THROWS_WITH(bad(R"({"latitude_deg": 41, "longitude_deg": 2})"), Contains("field 'elevation_m': missing"));
  CHECK_THROWS_WITH(bad(R"({"latitude_deg": 41, "longitude_deg": 2, "elevation_m": 0, "nort_deg": 4})"),
                    Contains("field 'nort_deg': unknown"));
  CHECK_THROWS_WITH(bad(R"({"latitude_deg": 41, "longitude_deg": 2, "elevation_m": 0, "utm": {"zone": 31, "northern": true}})"),
                    Contains("not both"));
  CHECK_THROWS_WITH(bad(R"({"utm": {"zone": 31, "northern": true}, "origin_easting_m": 5e5, "origin_northing_m": 4e6, "elevation_m": 0, "north_deg": 3})"),
                    Contains("field 'north_deg'") && Contains("not allowed"));
  CHECK_THROWS_WITH(bad(R"({"utm": {"zone": 61, "northern": true}, "origin_easting_m": 5e5, "origin_northing_m": 4e6, "elevation_m": 0})"),
                    Contains("field 'utm.zone'"));
  CHECK_THROWS_WITH(bad(R"({"utm": {"zone": 31}, "origin_easting_m": 5e5, "origin_northing_m": 4e6, "elevation_m": 0})"),
                    Contains("field 'utm.northern': missing"));
  // GeographicLib's own range check, passed on with the fields.
  CHECK_THROWS_WITH(bad(R"({"utm": {"zone": 31, "northern": true}, "origin_easting_m": -5e6, "origin_northing_m": 4e6, "elevation_m": 0})"),
                    Contains("site.json: field 'origin_easting_m/origin_northing_m'") && Contains("asting"));
  CHECK_THROWS_WITH(bad("{\n  \"latitude_deg\": 41,\n  ,\n}"), Contains("site.json:3: JSON syntax error"));
  CHECK_THROWS_WITH(bad("[1, 2]"), Contains("site.json: a site description must be a JSON object"));
}

// ---------------------------------------------------------------------------------------------
// The GeoJSON reader.

TEST_CASE("footprints with holes and multipolygons become closed prisms, normals outward") {
  const Site& site = kParis;
  // Outline given clockwise and the hole anticlockwise: the reader turns them.
  Ring outline = rectangle(-10, 20, -30, -12), hole = rectangle(0, 10, -25, -18);
  std::reverse(outline.begin(), outline.end());
  const std::string text = collection({
      polygon_feature(site, {outline, hole}, R"({"height": "14.5 m", "min_height": "2"})"),
      R"({"type": "Feature", "id": "relation/7", "properties": {"height": 9}, "geometry": {"type": "MultiPolygon", "coordinates": [)" +
          rings_json(site, {rectangle(30, 35, -20, -15)}) + ", " + rings_json(site, {rectangle(40, 44, -20, -16)}) + "]}}",
      R"({"type": "Feature", "properties": {"entrance": "yes"}, "geometry": {"type": "Point", "coordinates": [2.35, 48.85]}})",
      R"({"type": "Feature", "properties": {"height": 3}, "geometry": null})",
  });
  const ContextBuildings c = parse(text, site);
  CHECK(c.features == 4);
  CHECK(c.skipped_features == 2);
  REQUIRE(c.notices.size() == 1);
  CHECK_THAT(c.notices[0], Contains("2 features") && Contains("features 2, 3"));
  REQUIRE(c.buildings.size() == 2);
  const ContextBuilding& b = c.buildings[0];
  CHECK(b.base_z == 2);
  CHECK(b.top_z == 14.5);
  CHECK(b.faces.size() == 8 + 1);
  CHECK(std::abs(b.box_min.x + 10) < 1e-8);
  CHECK(std::abs(b.box_max.y + 12) < 1e-8);
  // The solid in plan: inside the outline, outside the hole.
  const auto in_solid = [](double x, double y) {
    return x > -10 && x < 20 && y > -30 && y < -12 && !(x > 0 && x < 10 && y > -25 && y < -18);
  };
  for (const Polygon& f : b.faces) {
    const Vec3 n = newell_normal(f.vertices);
    if (f.name.find("roof") != std::string::npos) {
      CHECK(n.z > 0);
      CHECK(f.vertices.size() == 4 + 1 + 4 + 1);  // outline, seam, hole, back
      CHECK(std::abs(n.z / 2 - (30 * 18 - 10 * 7)) < 1e-6);  // twice the area: outline minus hole
    } else {
      CHECK(n.z == 0);
      // Outward: just in front of the wall is open air, just behind it the solid.
      const Vec3 mid = 0.25 * (f.vertices[0] + f.vertices[1] + f.vertices[2] + f.vertices[3]);
      const Vec3 out = mid + 0.01 * normalized(n), in = mid - 0.01 * normalized(n);
      CHECK(!in_solid(out.x, out.y));
      CHECK(in_solid(in.x, in.y));
    }
    CHECK_THAT(f.where.str(), Contains("city.geojson: feature 0"));
  }
  CHECK(c.buildings[1].parts.size() == 2);
  CHECK(c.buildings[1].faces.size() == 4 + 1 + 4 + 1);
  CHECK_THAT(c.buildings[1].label, Contains("feature 1 (id relation/7)"));
}

TEST_CASE("bad GeoJSON is an error naming the file and the feature") {
  const Site& site = kParis;
  const Ring square = rectangle(0, 10, -20, -10);
  const auto with = [&](const std::string& properties, const std::string& coordinates) {
    return collection({polygon_feature(site, {square}, R"({"height": 5})"),
                       R"({"type": "Feature", "id": "way/42", "properties": )" + properties +
                           R"(, "geometry": {"type": "Polygon", "coordinates": )" + coordinates + "}}"});
  };
  const std::string good = rings_json(site, {square});
  const auto bad = [&](const std::string& text) { parse(text, site); };
  CHECK_THROWS_WITH(bad(with(R"({"name": "x"})", good)),
                    Contains("city.geojson: feature 1 (id way/42): no \"height\" property"));
  CHECK_THROWS_WITH(bad(with(R"({"height": "40 ft"})", good)), Contains("feature 1") && Contains("\"40 ft\""));
  CHECK_THROWS_WITH(bad(with(R"({"height": 5, "min_height": 6})", good)), Contains("must be above the bottom"));
  CHECK_THROWS_WITH(bad(with(R"({"height": 5, "min_height": 1, "base": 2})", good)), Contains("disagree"));
  CHECK_THROWS_WITH(bad(with(R"({"height": 5})", R"([[[2.35, 48.85], ["2.36", 48.85], [2.36, 48.86], [2.35, 48.85]]])")),
                    Contains("feature 1 (id way/42): outline position 1: coordinate \"2.36\" is not a number"));
  CHECK_THROWS_WITH(bad(with(R"({"height": 5})", R"([[[2.35, 48.85], [2.36, 48.85], [2.36, 48.86], [2.35, 48.86]]])")),
                    Contains("feature 1 (id way/42): outline is not closed"));
  CHECK_THROWS_WITH(bad(with(R"({"height": 5})", R"([[[2.35, 48.85], [2.36, 48.85], [2.36, 48.85], [2.35, 48.85]]])")),
                    Contains("feature 1 (id way/42): outline has fewer than 3 distinct vertices"));
  CHECK_THROWS_WITH(bad(with(R"({"height": 5})", R"([[[2.35, 48.85], [2.36, 48.85], [2.35, 48.85]]])")),
                    Contains("at least 4"));
  // A bow tie.
  CHECK_THROWS_WITH(bad(with(R"({"height": 5})", rings_json(site, {{{0, 0}, {10, -10}, {10, 0}, {0, -6}}}))),
                    Contains("feature 1 (id way/42): outline intersects itself"));
  // A hole that crosses the outline, and one outside it.
  CHECK_THROWS_WITH(bad(with(R"({"height": 5})", rings_json(site, {square, rectangle(5, 15, -18, -12)}))),
                    Contains("feature 1 (id way/42): outline and hole 1 cross or touch"));
  CHECK_THROWS_WITH(bad(with(R"({"height": 5})", rings_json(site, {square, rectangle(20, 25, -18, -12)}))),
                    Contains("hole 1 lies outside the outline"));
  // Latitude and longitude swapped: thousands of kilometres away.
  CHECK_THROWS_WITH(bad(with(R"({"height": 5})", R"([[[48.85, 2.35], [48.86, 2.35], [48.86, 2.36], [48.85, 2.35]]])")),
                    Contains("swapped"));
  CHECK_THROWS_WITH(bad(R"({"type": "Polygon", "coordinates": []})"), Contains("city.geojson") && Contains("FeatureCollection"));
  CHECK_THROWS_WITH(bad(R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::25831"}}, "features": []})"),
                    Contains("25831") && Contains("WGS84"));
  CHECK_THROWS_WITH(bad("{\"type\": \"FeatureCollection\",\n\"features\": [\n{\"type\": \"Feature\" \"x\": 1}]}"),
                    Contains("city.geojson:3: JSON syntax error"));
}

// ---------------------------------------------------------------------------------------------
// Context buildings in the sky component.

TEST_CASE("a prism from GeoJSON gives the same sky component as the same prism in model coordinates") {
  const Site& site = kParis;  // turned by 23.5°: the footprint is not axis-aligned in ENU
  // A block across the street with a courtyard and a chamfered corner, floating 2 m up (a passage
  // under it), 14 m high; and a pentagonal tower.
  const std::vector<Ring> block = {{{-10, -30}, {20, -30}, {20, -16}, {16, -12}, {-10, -12}},
                                   {{0, -18}, {10, -18}, {10, -25}, {0, -25}}};
  const std::vector<Ring> tower = {{{25, -14}, {29, -15}, {31, -11}, {28, -8}, {24.5, -10}}};
  const SensorGrid grid = room_grid();

  Scene direct = window_scene();
  for (auto& f : prism_in_model(block, 2, 14)) direct.occluders.push_back(f);
  for (auto& f : prism_in_model(tower, 0, 25)) direct.occluders.push_back(f);
  const std::vector<double> expected = sky_components(direct, grid);

  Scene placed = window_scene();
  const ContextBuildings context =
      parse(collection({polygon_feature(site, block, R"({"height": 14, "base": 2})"),
                        polygon_feature(site, tower, R"({"height": "25"})")}),
            site);
  const ContextPlacement placement = place_context_buildings(context, {grid}, SkyModel::cie_overcast, 0.1, placed);
  CHECK(placement.placed == 2);
  CHECK(placement.faces == direct.occluders.size());
  const std::vector<double> got = sky_components(placed, grid);

  // Vertices go model → WGS84 → model through LocalCartesian, which works in geocentric
  // coordinates of 6.4e6 m whose ulp is 9.3e-10 m (the re-placement at the origin's height adds
  // d³/2R² ≈ 3e-10 m at 30 m): they move by ~1e-9 m, 1e-10 of the distances, and the sky component
  // inherits that times a condition number of order 10 (2.8e-10 seen). Hence 1e-9, not ulps;
  // and 1e-9 of what the window gives without the buildings, since where they hide it all a moved
  // edge may open a sliver (1e-24 % at one sensor here).
  Scene bare = window_scene();
  const std::vector<double> open_sky = sky_components(bare, grid);
  int occluded = 0;
  double worst = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (expected[i] > 1e-3) worst = std::max(worst, std::abs(got[i] - expected[i]) / expected[i]);
    INFO("sensor " << i << ": from GeoJSON " << got[i] << ", in model coordinates " << expected[i] << ", open " << open_sky[i]);
    CHECK(std::abs(got[i] - expected[i]) <= 1e-9 * open_sky[i]);
    if (expected[i] > 1e-3) CHECK(std::abs(got[i] - expected[i]) <= 1e-9 * expected[i]);
    CHECK(expected[i] <= open_sky[i]);
    occluded += expected[i] > 0 && expected[i] < open_sky[i] - 0.01;  // partly hidden by the buildings
  }
  CHECK(occluded >= 4);
  std::printf("context prism from GeoJSON against model coordinates: largest relative difference %.3g\n", worst);
}

TEST_CASE("context culling leaves out what cannot be seen and bounds what is too small to matter") {
  const Site& site = kParis;
  const SensorGrid grid = room_grid();  // sensors at y 0.01..3, z 0.85..2.2; window in y = 0, z 1..2.5
  const std::string text = collection({
      // 0: the model's own building: holds the sensors.
      polygon_feature(site, {rectangle(-5, 8, -0.2, 10)}, R"({"height": 12})"),
      // 1: across the street: placed.
      polygon_feature(site, {rectangle(-10, 20, -30, -12)}, R"({"height": 14})"),
      // 2: behind the window's plane (the sensors' side), beyond the model's box: left out.
      polygon_feature(site, {rectangle(-10, 20, 15, 30)}, R"({"height": 20})"),
      // 3: in front but no higher than the lowest sensor: below the horizon.
      polygon_feature(site, {rectangle(-10, 20, -40, -35)}, R"({"height": 0.8})"),
      // 4: a mast 5 km away, 1 m wide and 6 m high: too small (0.07°).
      polygon_feature(site, {rectangle(100, 101, -5000, -4999)}, R"({"height": 6})"),
      // 5: behind the window, but its box meets the model's box: placed (no rule applies).
      polygon_feature(site, {rectangle(2.95, 3.6, 2.9, 3.6)}, R"({"height": 3})"),
  });
  const ContextBuildings context = parse(text, site);
  REQUIRE(context.buildings.size() == 6);

  Scene culled = window_scene();
  const ContextPlacement p = place_context_buildings(context, {grid}, SkyModel::cie_overcast, 0.1, culled);
  CHECK(p.read == 6);
  CHECK(p.placed == 2);
  CHECK(p.enclosing_model == 1);
  CHECK(p.behind_apertures == 1);
  CHECK(p.below_horizon == 1);
  CHECK(p.too_small == 1);
  CHECK(p.faces == 2 * 5);
  CHECK(p.sc_change_bound_percent > 0);
  CHECK(p.sc_change_bound_percent < 9.8e-5);  // the bound of one building at the threshold
  CHECK_THAT(p.notices.front(), Contains("feature 0") && Contains("left out"));

  // Everything that can be seen, with rule (c) off: only the model's own building is left out.
  Scene all = window_scene();
  const ContextPlacement q = place_context_buildings(context, {grid}, SkyModel::cie_overcast, 0, all);
  CHECK(q.placed == 3);
  CHECK(q.too_small == 0);
  CHECK(q.sc_change_bound_percent == 0);
  const std::vector<double> a = sky_components(culled, grid), b = sky_components(all, grid);
  for (std::size_t i = 0; i < a.size(); ++i) {
    INFO("sensor " << i << ": culled " << a[i] << ", all " << b[i]);
    CHECK(std::abs(a[i] - b[i]) <= p.sc_change_bound_percent + 1e-12 * b[i]);
  }
  // The rules (a) and (b) alone change nothing: place the far mast as well and compare with the
  // buildings that are left out placed too.
  Scene everything = window_scene();
  for (std::size_t k = 1; k < context.buildings.size(); ++k)
    for (const Polygon& f : context.buildings[k].faces) everything.occluders.push_back(f);
  const std::vector<double> c = sky_components(everything, grid);
  for (std::size_t i = 0; i < b.size(); ++i) CHECK(std::abs(b[i] - c[i]) <= 1e-12 * c[i]);

  CHECK_THROWS_WITH(place_context_buildings(context, {grid}, SkyModel::cie_overcast, -1, all), Contains("angular size"));

  // A grid that sees the sky directly (outdoors) sees buildings without any aperture: every
  // building above its lowest sensor is placed, behind the window or small as it may be; the
  // one below the horizon stays out (and the one holding the model).
  SensorGrid outdoors = grid;
  outdoors.sees_sky_directly = true;
  Scene open = window_scene();
  const ContextPlacement o = place_context_buildings(context, {outdoors}, SkyModel::cie_overcast, 0.1, open);
  CHECK(o.placed == 4);
  CHECK(o.behind_apertures == 0);
  CHECK(o.too_small == 0);
  CHECK(o.below_horizon == 1);
  CHECK(o.enclosing_model == 1);
}

TEST_CASE("with the sun on, a small building in the sun's beam is kept and one outside it is left out, changing nothing of the sun") {
  const Site& site = kParis;
  const SensorGrid grid = room_grid();
  // A mast 60 m out, 1 m wide and 8 m high: 8.9° by the rule's bounding sphere, under a 10° threshold.
  const ContextBuildings context = parse(collection({polygon_feature(site, {rectangle(1, 2, -61, -60)}, R"({"height": 8})")}), site);
  // The sun low over the mast as the window sensor at (1.5, 0.01, 1.75) sees it: the mast's top
  // cuts its disk there. Aside: the beam through the window passes the mast 58 m to its side.
  const Vec3 over_mast = normalized(Vec3{0, -60.51, 6.15});
  const Vec3 aside = normalized(Vec3{1, -1, 0.3});
  const double rho = kSunHalfAngleDeg * std::numbers::pi / 180;
  constexpr std::size_t window_sensor = 9;
  REQUIRE(grid.sensors[window_sensor].position.y == 0.01);

  Scene without_sun = window_scene();
  const ContextPlacement no_sun = place_context_buildings(context, {grid}, SkyModel::cie_overcast, 10, without_sun);
  CHECK(no_sun.too_small == 1);
  CHECK_FALSE(no_sun.sun_beam_kept);
  Scene over = window_scene();
  const ContextPlacement in_beam =
      place_context_buildings(context, {grid}, SkyModel::cie_overcast, 10, over, SunBeam{over_mast, rho});
  CHECK(in_beam.placed == 1);
  CHECK(in_beam.kept_in_sun_beam == 1);
  CHECK(in_beam.too_small == 0);
  CHECK(in_beam.sun_beam_kept);
  CHECK_THAT(in_beam.notices.back(), Contains("sun's beam"));
  Scene beside = window_scene();
  const ContextPlacement off_beam =
      place_context_buildings(context, {grid}, SkyModel::cie_overcast, 10, beside, SunBeam{aside, rho});
  CHECK(off_beam.too_small == 1);
  CHECK(off_beam.kept_in_sun_beam == 0);

  // Keeping it matters: over the mast, the mast hides part of the disk from the window sensor.
  Scene all = window_scene();
  for (const Polygon& f : context.buildings[0].faces) all.occluders.push_back(f);
  const std::vector<double> shaded = sun_illuminance(all, grid, over_mast), open = sun_illuminance(without_sun, grid, over_mast);
  INFO("window sensor: " << shaded[window_sensor] << " lux with the mast, " << open[window_sensor] << " without");
  CHECK(shaded[window_sensor] > 0.01 * open[window_sensor]);
  CHECK(shaded[window_sensor] < 0.99 * open[window_sensor]);
  // And leaving it out aside changes nothing of the sun, to roundoff: the regions are clipped by
  // different occluder sets before the same disk cuts them, and cap_clip.hpp is good to ~1e-13 of
  // the disk's π sin²ρ per cut, more where differing pieces have seams across the disk whose terms
  // cancel; 1e-11 of the 1000 lux direct normal (4e-13 seen).
  const std::vector<double> culled = sun_illuminance(beside, grid, aside), kept = sun_illuminance(all, grid, aside);
  int lit = 0;
  for (std::size_t i = 0; i < grid.sensors.size(); ++i) {
    INFO("sensor " << i << ": culled " << culled[i] << ", all " << kept[i]);
    CHECK(std::abs(culled[i] - kept[i]) <= 1e-11 * 1000);
    lit += kept[i] > 0;
  }
  CHECK(lit >= 1);
}
