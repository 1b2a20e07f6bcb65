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

}  // namespace daylit::test
