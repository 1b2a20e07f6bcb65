// daylit grid's geometry (simulation/floor_grid.hpp) against sensor positions computed by hand,
// EN 17037's daylight-factor method and BREEAM Hea 01's figures (simulation/daylight_criteria.hpp)
// on values chosen by hand, and what a plan image draws (geometry/plan_drawing.hpp).

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "geometry/error.hpp"
#include "geometry/plan_drawing.hpp"
#include "simulation/daylight_criteria.hpp"
#include "simulation/floor_grid.hpp"

using namespace daylit;

namespace {

std::vector<std::pair<double, double>> xy(const std::vector<Sensor>& sensors) {
  std::vector<std::pair<double, double>> v;
  for (const auto& s : sensors) v.emplace_back(s.position.x, s.position.y);
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

TEST_CASE("floor grid: a 4 x 3 room, spacing 1, offset 0.5: six cell centres at 0.85") {
  // Inset by 0.5 the floor is [0.5, 3.5] x [0.5, 2.5]: cells of side 1 from (0.5, 0.5), centres
  // x = 1, 2, 3 and y = 1, 2. The floor's orientation (Honeybee's face down, Radiance's up) and its
  // height do not matter.
  for (const bool reversed : {false, true}) {
    std::vector<Vec3> floor{{0, 0, 2}, {4, 0, 2}, {4, 3, 2}, {0, 3, 2}};
    if (reversed) std::reverse(floor.begin(), floor.end());
    const auto sensors = floor_grid({FloorOutline{{floor}}}, {1.0, 0.85, 0.5});
    REQUIRE(sensors.size() == 6);
    CHECK(xy(sensors) == std::vector<std::pair<double, double>>{{1, 1}, {1, 2}, {2, 1}, {2, 2}, {3, 1}, {3, 2}});
    for (const auto& s : sensors) {
      CHECK(s.position.z == 2.85);
      CHECK(s.normal.z == 1);
    }
  }
}

TEST_CASE("floor grid: an L-shaped room keeps the centres at least the offset from every edge") {
  // L: [0,4] x [0,2] and [0,2] x [2,4]. Offset 0.5, spacing 0.5: the inset is [0.5,3.5] x [0.5,1.5]
  // together with [0.5,1.5] x [1.5,3.5] (the re-entrant corner at (2, 2) sits 0.5 from its inset
  // corner (1.5, 1.5) along both axes, so the inset is exactly these two rectangles). Cells of 0.5
  // from (0.5, 0.5): centres 0.75, 1.25, ... Kept: x in {0.75 ... 3.25} with y in {0.75, 1.25}
  // (6 x 2 = 12), and x in {0.75, 1.25} with y in {1.75 ... 3.25} (2 x 4 = 8): 20.
  const std::vector<Vec3> floor{{0, 0, 0}, {4, 0, 0}, {4, 2, 0}, {2, 2, 0}, {2, 4, 0}, {0, 4, 0}};
  const auto sensors = floor_grid({FloorOutline{{floor}}}, {0.5, 0.85, 0.5});
  CHECK(sensors.size() == 20);
  for (const auto& s : sensors) {
    const double x = s.position.x, y = s.position.y;
    CHECK(((x >= 0.5 && x <= 3.5 && y >= 0.5 && y <= 1.5) || (x >= 0.5 && x <= 1.5 && y >= 0.5 && y <= 3.5)));
  }
}

TEST_CASE("floor grid: a hole (Radiance's seams or a separate loop) is kept clear by the offset") {
  // A 6 x 6 floor with a 2 x 2 atrium in its middle, offset 0.5, spacing 1: of the 5 x 5 centres
  // x, y = 1 ... 5, those closer than 0.5 to the atrium [2,4]^2 (x and y in {2, 3, 4}: 9) go: 16.
  const std::vector<Vec3> outer{{0, 0, 0}, {6, 0, 0}, {6, 6, 0}, {0, 6, 0}};
  const std::vector<Vec3> hole{{2, 2, 0}, {2, 4, 0}, {4, 4, 0}, {4, 2, 0}};
  const auto separate = floor_grid({FloorOutline{{outer, hole}}}, {1.0, 0.85, 0.5});
  CHECK(separate.size() == 16);
  std::vector<Vec3> seams = outer;
  seams.push_back(outer[0]);
  seams.insert(seams.end(), hole.begin(), hole.end());
  seams.push_back(hole[0]);
  const auto seamed = floor_grid({FloorOutline{{seams}}}, {1.0, 0.85, 0.5});
  CHECK(xy(seamed) == xy(separate));
}

TEST_CASE("floor grid: cells past the far wall keep their centre inside, offset 0 keeps the edge band") {
  // 2.5 x 1 at spacing 1, offset 0: three cells, centres x = 0.5, 1.5, 2.5 at y = 0.5; the last lies
  // on the far edge, which the half-open even-odd rule counts as outside.
  const std::vector<Vec3> floor{{0, 0, 0}, {2.5, 0, 0}, {2.5, 1, 0}, {0, 1, 0}};
  CHECK(xy(floor_grid({FloorOutline{{floor}}}, {1.0, 0.85, 0.0})) == std::vector<std::pair<double, double>>{{0.5, 0.5}, {1.5, 0.5}});
  CHECK(floor_grid({FloorOutline{{floor}}}, {1.0, 0.85, 0.6}).empty());  // narrower than twice the offset
  const std::vector<Vec3> tilted{{0, 0, 0}, {2, 0, 0.5}, {2, 2, 0.5}, {0, 2, 0}};
  CHECK_THROWS_AS(floor_grid({FloorOutline{{tilted}}}, {}), Error);
}

TEST_CASE("EN 17037's daylight-factor method: targets 100 E / E_med over 50 % and 95 % of the sensors") {
  // E_med = 10,000 lx: minimum level D_T = 3 %, D_TM = 1 %; medium 5 % and 3 %; high 7.5 % and 5 %.
  // Twenty sensors: one at 0.5 %, nine at 2 %, ten at 4 %: 95 % at or above 1 %, 50 % at or above 3 %.
  std::vector<double> df(1, 0.5);
  df.insert(df.end(), 9, 2.0);
  df.insert(df.end(), 10, 4.0);
  const En17037Assessment a = en17037_df_method(df, 10000);
  REQUIRE(a.levels.size() == 3);
  CHECK(a.levels[0].target_df == 3);
  CHECK(a.levels[0].minimum_target_df == 1);
  CHECK(a.levels[0].share_at_target == 0.5);
  CHECK(a.levels[0].share_at_minimum_target == 0.95);
  CHECK(a.levels[0].met);
  CHECK(a.levels[1].target_df == 5);
  CHECK_FALSE(a.levels[1].met);
  CHECK(a.levels[2].target_df == 7.5);
  CHECK(a.level_met == "minimum");
  // One sensor fewer at 4 % (replaced by 0.5 %): 45 % at the target, 90 % at the minimum: none.
  df.back() = 0.5;
  CHECK(en17037_df_method(df, 10000).level_met == "none");
  CHECK_THROWS_AS(en17037_df_method(df, 0), Error);
}

namespace {

Polygon plan_polygon(std::vector<Vec3> vertices) {
  Polygon p;
  p.vertices = std::move(vertices);
  return p;
}

// A 4 × 3 × 3 m room (x 0..4, y 0..3): floor, ceiling, four walls, the south wall (y = 0) with a
// notch from the floor up to 1 m at x 1..2 (a door), and a window x 2.5..3.5, z 1..2 in it.
Scene plan_room() {
  Scene scene;
  scene.occluders.push_back(plan_polygon({{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}}));
  scene.occluders.push_back(plan_polygon({{0, 0, 3}, {0, 3, 3}, {4, 3, 3}, {4, 0, 3}}));
  scene.occluders.push_back(plan_polygon({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {2, 0, 1}, {2, 0, 0}, {4, 0, 0}, {4, 0, 3}, {0, 0, 3}}));
  scene.occluders.push_back(plan_polygon({{4, 0, 0}, {4, 3, 0}, {4, 3, 3}, {4, 0, 3}}));
  scene.occluders.push_back(plan_polygon({{4, 3, 0}, {0, 3, 0}, {0, 3, 3}, {4, 3, 3}}));
  scene.occluders.push_back(plan_polygon({{0, 3, 0}, {0, 0, 0}, {0, 0, 3}, {0, 3, 3}}));
  Aperture window;
  window.polygon = plan_polygon({{2.5, 0, 1}, {3.5, 0, 1}, {3.5, 0, 2}, {2.5, 0, 2}});
  scene.apertures.push_back(window);
  return scene;
}

double length(const PlanSegment& s) { return std::hypot(s.x1 - s.x0, s.y1 - s.y0); }

}  // namespace

TEST_CASE("plan drawing: the walls cut at the grid's height, the door's notch open, the window seen from above") {
  const Scene scene = plan_room();
  SECTION("at 0.85 m the south wall is cut in two by the door; floor and ceiling are not cut") {
    const PlanDrawing d = plan_drawing(scene, 0.85);
    REQUIRE(d.walls.size() == 5);
    double south = 0, total = 0;
    for (const PlanSegment& s : d.walls) {
      total += length(s);
      if (s.y0 == 0 && s.y1 == 0) south += length(s);
    }
    CHECK(south == Approx(3).epsilon(1e-14));  // 4 m less the 1 m door
    CHECK(total == Approx(3 + 3 + 4 + 3).epsilon(1e-14));
    // The window projects to its sill's segment (its jambs project to points, left out).
    REQUIRE(d.apertures.size() == 2);
    for (const PlanSegment& s : d.apertures) CHECK(length(s) == Approx(1).epsilon(1e-14));
  }
  SECTION("at 1.5 m, above the door, the south wall is whole") {
    const PlanDrawing d = plan_drawing(scene, 1.5);
    CHECK(d.walls.size() == 4);
  }
  SECTION("a vertex on the plane counts once: the door's head at exactly 1 m") {
    const PlanDrawing d = plan_drawing(scene, 1.0);
    double total = 0;
    for (const PlanSegment& s : d.walls) total += length(s);
    CHECK(total == Approx(4 + 3 + 4 + 3).epsilon(1e-14));
  }
  SECTION("distances in plan") {
    const PlanDrawing d = plan_drawing(scene, 0.85);
    CHECK(plan_distance(d.walls, 2, 1.5) == Approx(1.5).epsilon(1e-14));  // to the north and south walls
    CHECK(plan_distance(d.walls, 1.5, 0.2) == Approx(std::hypot(0.5, 0.2)).epsilon(1e-14));  // in the doorway: to a jamb's end
    CHECK(std::isinf(plan_distance({}, 0, 0)));
  }
}

TEST_CASE("BREEAM Hea 01: the average, minimum and uniformity outside the 0.5 m band, by hand") {
  const Scene scene = plan_room();
  const PlanDrawing plan = plan_drawing(scene, 0.85);
  SensorGrid grid;
  // (0.25, 1.5) and (3.8, 1.5) lie within 0.5 m of the west and east walls; the other three not.
  for (const double x : {0.25, 1.0, 2.0, 3.0, 3.8}) grid.sensors.push_back({{x, 1.5, 0.85}, {0, 0, 1}});
  const std::vector<double> df{9, 4, 2, 3, 0.5};
  const BreeamHea01 b = breeam_hea01(grid, df, plan);
  CHECK(b.sensors == 3);
  CHECK(b.sensors_in_band == 2);
  CHECK(*b.average_df == Approx(3).epsilon(1e-15));
  CHECK(*b.minimum_df == 2);
  CHECK(*b.uniformity == Approx(2.0 / 3).epsilon(1e-15));
  SECTION("every sensor in the band: no figures, not NaN") {
    const BreeamHea01 none = breeam_hea01(grid, df, plan, 5.0);
    CHECK(none.sensors == 0);
    CHECK_FALSE(none.average_df.has_value());
    CHECK_FALSE(none.uniformity.has_value());
  }
  CHECK_THROWS_AS(breeam_hea01(grid, {1, 2}, plan), Error);
}
