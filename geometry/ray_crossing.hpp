#pragma once
// Where a ray first crosses a set of polygons, in floating point: for estimates of a scene's
// scale (the span of the room around a sensor, which sets the radiosity mesh's automatic element
// size), for deciding which grids see the sky directly and which sensors a room encloses, never
// for a result. A ray through a
// shared edge or vertex may pass between the polygons; callers take medians over many rays, or
// confirm a ray by a neighbouring one.

#include <array>
#include <cstddef>
#include <vector>

#include "geometry/polygon.hpp"

namespace daylit {

// The least t > 0 at which origin + t·direction lies in one of the polygons (each taken in the
// plane of its Newell normal); infinity where it meets none.
double nearest_crossing(const std::vector<Polygon>& polygons, const Vec3& origin, const Vec3& direction);

// How many of the polygons the ray crosses at t > 0: its parity says whether origin lies inside a
// closed surface (daylit grid's rooms).
std::size_t crossing_count(const std::vector<Polygon>& polygons, const Vec3& origin, const Vec3& direction);

// Whether rays meet any of a set of polygons at t > 0 (as nearest_crossing), for many rays: the
// planes are found once, and the polygons that blocked the latest rays are tried first (a room's
// ceiling and walls block nearly every ray from its sensors), so that a blocked ray costs a few
// tests and only a ray that escapes tests every polygon. One object per thread: the list of
// recent blockers changes with every query.
class RayBlockers {
 public:
  explicit RayBlockers(const std::vector<Polygon>& polygons);
  bool blocked(const Vec3& origin, const Vec3& direction);

 private:
  struct Plane {
    const Polygon* polygon;
    Vec3 normal;
  };
  std::vector<Plane> planes_;
  std::array<std::size_t, 8> recent_{};
  std::size_t recent_count_ = 0;
};

}  // namespace daylit
