#pragma once
// Planar polygons as read from scene files, with their provenance.

#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/vec3.hpp"

namespace daylit {

struct Polygon {
  std::vector<Vec3> vertices;
  std::string name;
  std::string material;
  SourceLocation where;
};

// Newell's normal: twice the vector area (zero for a degenerate polygon). Vertices are taken
// relative to the first one so that a polygon far from the origin keeps its digits.
inline Vec3 newell_normal(const std::vector<Vec3>& v) noexcept {
  Vec3 n;
  if (v.empty()) return n;
  for (std::size_t i = 1; i + 1 < v.size(); ++i) n += cross(v[i] - v[0], v[i + 1] - v[0]);
  return n;
}

}  // namespace daylit
