#pragma once
// Small builders for the scenes of the tests.

#include <string>
#include <vector>

#include "geometry/polygon.hpp"

namespace daylit::test {

// A polygon with a name and a nominal source location, as a reader would make it.
inline Polygon polygon(std::vector<Vec3> vertices, std::string name = "p") {
  Polygon p;
  p.vertices = std::move(vertices);
  p.name = std::move(name);
  p.where = {"test", 1};
  return p;
}

// The window of the visibility tests: y = 0, x ∈ [0, 2], z ∈ [1, 2]; the room is at y > 0.
inline const std::vector<Vec3> kWindow{{0, 0, 1}, {2, 0, 1}, {2, 0, 2}, {0, 0, 2}};

// A wall in the plane of the window, x ∈ [−3, 5], z ∈ [0, 3], with the window cut out by a seam:
// the outer boundary, in along the cut, around the hole the other way, and back out.
inline Polygon wall_with_seam_hole() {
  return polygon({{-3, 0, 0}, {5, 0, 0}, {5, 0, 3}, {-3, 0, 3}, {-3, 0, 1}, {0, 0, 1}, {0, 0, 2}, {2, 0, 2}, {2, 0, 1}, {0, 0, 1}, {-3, 0, 1}},
                 "wall");
}

// Four faces of a reveal of depth d outside the window (y ∈ [−d, 0]).
inline std::vector<Polygon> reveal(double d) {
  return {polygon({{0, 0, 1}, {0, -d, 1}, {0, -d, 2}, {0, 0, 2}}, "left"), polygon({{2, 0, 1}, {2, 0, 2}, {2, -d, 2}, {2, -d, 1}}, "right"),
          polygon({{0, 0, 1}, {2, 0, 1}, {2, -d, 1}, {0, -d, 1}}, "sill"), polygon({{0, 0, 2}, {0, -d, 2}, {2, -d, 2}, {2, 0, 2}}, "head")};
}

}  // namespace daylit::test
