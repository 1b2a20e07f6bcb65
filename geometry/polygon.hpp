#pragma once
// Planar polygons as read from scene files, with their provenance.

#include <algorithm>
#include <cmath>
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

// Whether b is a copy of a's outline: as many vertices, each of b within 1e-6 of a's extent of a
// vertex of a moved along a's unit normal by the distance between their planes, where that
// distance is at most max_gap × the extent and, unless it is 0, the two face opposite ways.
// max_gap 0: the same vertices (an HBJSON lists an interior window once per room, each copy
// with the same vertices, in opposite orders). Honeybee's Radiance folders need max_gap > 0: its
// translator moves one face of each pair shared by two rooms 2 × tolerance into its room, its
// window with it.
inline bool same_outline(const Polygon& a, const Polygon& b, double max_gap = 0) {
  if (a.vertices.size() != b.vertices.size() || a.vertices.empty()) return false;
  double extent = 0;
  for (const Vec3& u : a.vertices)
    for (const Vec3& v : a.vertices) extent = std::max(extent, norm(u - v));
  const double tolerance = 1e-6 * extent;
  Vec3 shift{0, 0, 0};
  if (max_gap > 0) {
    const Vec3 na = newell_normal(a.vertices), nb = newell_normal(b.vertices);
    if (!(norm(na) > 0 && norm(nb) > 0)) return false;
    const Vec3 n = na / norm(na);
    const double gap = dot(n, b.vertices.front() - a.vertices.front());
    if (std::abs(gap) > tolerance) {
      if (std::abs(gap) > max_gap * extent || !(dot(n, nb / norm(nb)) < -1 + 1e-9)) return false;
      shift = gap * n;
    }
  }
  return std::all_of(a.vertices.begin(), a.vertices.end(), [&](const Vec3& u) {
    return std::any_of(b.vertices.begin(), b.vertices.end(), [&](const Vec3& v) { return norm(u + shift - v) <= tolerance; });
  });
}

}  // namespace daylit
