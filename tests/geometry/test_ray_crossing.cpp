// nearest_crossing: where a ray first meets a set of polygons, the floating-point estimate of a
// room's span that sets the radiosity mesh's automatic element size. The distances below are
// sums of dyadic rationals, exact in double, so they are compared exactly.

#include <catch2/catch.hpp>

#include <cmath>

#include "geometry/ray_crossing.hpp"
#include "test_scenes.hpp"

using namespace daylit;
using daylit::test::polygon;

TEST_CASE("nearest_crossing: the first polygon a ray meets, either side, ahead only") {
  // Two parallel walls x = 1 and x = 3, a wall x = -2 behind the origin, facing either way.
  const std::vector<Polygon> walls{polygon({{3, -1, -1}, {3, 1, -1}, {3, 1, 1}, {3, -1, 1}}),
                                   polygon({{1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1}}),
                                   polygon({{-2, -1, -1}, {-2, 1, -1}, {-2, 1, 1}, {-2, -1, 1}})};
  CHECK(nearest_crossing(walls, {0, 0, 0}, {1, 0, 0}) == 1.0);
  CHECK(nearest_crossing(walls, {0, 0, 0}, {-1, 0, 0}) == 2.0);
  CHECK(nearest_crossing(walls, {2, 0.5, 0.5}, {1, 0, 0}) == 1.0);
  // The direction's length scales t: t is in units of the direction.
  CHECK(nearest_crossing(walls, {0, 0, 0}, {4, 0, 0}) == 0.25);
  // Oblique: through (1, 0.5, 0) on the first wall.
  CHECK(nearest_crossing(walls, {0, 0, 0}, {1, 0.5, 0}) == 1.0);
  // Past the walls' edges, parallel to them, or pointing away: nothing.
  CHECK(std::isinf(nearest_crossing(walls, {0, 0, 0}, {1, 2, 0})));
  CHECK(std::isinf(nearest_crossing(walls, {0, 0, 0}, {0, 1, 0})));
  CHECK(std::isinf(nearest_crossing(walls, {5, 0, 0}, {1, 0, 0})));
}

TEST_CASE("nearest_crossing: a non-convex polygon is met only inside its outline, in any plane") {
  // An L in the plane z = x (tilted 45°), its notch at u, v ∈ (1, 2]: the polygon's points are
  // (u, v, u) for the L's (u, v).
  const std::vector<Polygon> l{polygon({{0, 0, 0}, {2, 0, 2}, {2, 1, 2}, {1, 1, 1}, {1, 2, 1}, {0, 2, 0}})};
  // Straight up from (u, v, 0) the ray meets the plane at height u.
  CHECK(nearest_crossing(l, {0.5, 1.5, 0}, {0, 0, 1}) == 0.5);
  CHECK(nearest_crossing(l, {1.5, 0.5, 0}, {0, 0, 1}) == 1.5);
  CHECK(std::isinf(nearest_crossing(l, {1.5, 1.5, 0}, {0, 0, 1})));  // the notch
  CHECK(std::isinf(nearest_crossing(l, {2.5, 0.5, 0}, {0, 0, 1})));  // beyond the outline
  // A degenerate polygon (collinear vertices) is never met.
  const std::vector<Polygon> line{polygon({{0, 0, 1}, {1, 0, 1}, {2, 0, 1}})};
  CHECK(std::isinf(nearest_crossing(line, {1, 0, 0}, {0, 0, 1})));
}
