#pragma once
// What input geometry is accepted, shared by the readers (.rad, .pts) and `daylit eval`: a bound on
// coordinates, and shape checks on polygons (area, planarity within a tolerance, boundaries that
// cross themselves). Plain doubles, with tolerances far above rounding, except where the area is
// within the rounding of Newell's normal: that is decided exactly (exactly_zero_area); the exact
// geometry (convex_pieces) decides everything after.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "geometry/convex_pieces.hpp"
#include "geometry/polygon.hpp"

namespace daylit {

// Coordinates of polygon vertices and sensors must lie within ±kMaxCoordinate. No model needs
// more (millimetres in Earth-centred coordinates stay below 6.4e9), and it keeps the products
// that the clipping forms in double and interval arithmetic (up to sixth powers of coordinate
// differences, about 1e75) far from overflow, and the sensor-relative kernels finite.
inline constexpr double kMaxCoordinate = 1e12;

struct PolygonShape {
  Vec3 normal;            // Newell's normal: twice the vector area
  double extent = 0;      // largest distance of a vertex from the first one
  double deviation = 0;   // largest distance of a vertex from the mean plane (0 if the area is zero)
  bool zero_area = true;  // |normal| ≤ 1e-24·extent², or 0 exactly: collinear or repeated
                          // vertices, or lobes of opposite orientation that cancel
};

// O(n). The mean plane passes through the centroid of the vertices with Newell's normal.
inline PolygonShape polygon_shape(const std::vector<Vec3>& v) {
  PolygonShape s;
  if (v.empty()) return s;
  s.normal = newell_normal(v);
  for (const Vec3& p : v) s.extent = std::max(s.extent, norm(p - v[0]));
  const double area2 = norm(s.normal);
  s.zero_area = !(area2 > 0) || area2 <= 1e-24 * s.extent * s.extent;
  // A normal within its own rounding ((m + 8) u Σ|v_i − v_0||v_{i+1} − v_0| per component, twice
  // that for its length) may be nothing but rounding, and is decided exactly: a triangle in
  // x = −1.0000000000001137 with collinear (y, z) had a double normal of 1e-13 and went on to a
  // triangulation of a segment (found by fuzz_visibility).
  const double terms = double(v.size() + 8) * 0x1p-52;  // Σ|a||b| ≤ m·extent²: most polygons stop here
  if (!s.zero_area && area2 <= terms * double(v.size()) * s.extent * s.extent) {
    double size = 0;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) size += norm(v[i] - v[0]) * norm(v[i + 1] - v[0]);
    if (area2 <= terms * size) s.zero_area = exactly_zero_area(v);
  }
  if (s.zero_area) return s;
  const Vec3 unit = s.normal / area2;
  Vec3 centroid;
  for (const Vec3& p : v) centroid += p - v[0];
  centroid = centroid / double(v.size());
  for (const Vec3& p : v) s.deviation = std::max(s.deviation, std::abs(dot(unit, p - v[0] - centroid)));
  return s;
}

// True when all vertices lie within `tolerance`·extent of the line through the first vertex and
// the one farthest from it.
inline bool vertices_collinear(const std::vector<Vec3>& v, double tolerance) {
  if (v.size() < 3) return true;
  std::size_t far = 0;
  double extent = 0;
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (norm(v[i] - v[0]) > extent) {
      extent = norm(v[i] - v[0]);
      far = i;
    }
  }
  if (!(extent > 0)) return true;
  const Vec3 d = (v[far] - v[0]) / extent;
  for (const Vec3& p : v)
    if (norm(cross(p - v[0], d)) > tolerance * extent) return false;
  return true;
}

// True when two edges that share no vertex cross at a point interior to both, in the plane
// obtained by dropping the dominant axis of `normal` (non-zero). Edges that only touch, overlap
// along a line or meet at a vertex (the seams of Radiance's holes) do not count. The orientations
// are taken in double; a crossing within rounding of a touch may go either way. O(n²): callers
// bound n.
inline bool boundary_crosses_itself(const std::vector<Vec3>& v, const Vec3& normal) {
  const double ax = std::abs(normal.x), ay = std::abs(normal.y), az = std::abs(normal.z);
  const int drop = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
  const int i0 = (drop + 1) % 3, i1 = (drop + 2) % 3;
  const std::size_t n = v.size();
  const auto orient = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const double d = (b[i0] - a[i0]) * (c[i1] - a[i1]) - (b[i1] - a[i1]) * (c[i0] - a[i0]);
    return (d > 0) - (d < 0);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 &a = v[i], &b = v[(i + 1) % n];
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      const Vec3 &c = v[j], &d = v[(j + 1) % n];
      if (a == c || a == d || b == c || b == d) continue;
      if (orient(a, b, c) * orient(a, b, d) < 0 && orient(c, d, a) * orient(c, d, b) < 0) return true;
    }
  }
  return false;
}

}  // namespace daylit
