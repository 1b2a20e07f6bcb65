#pragma once
// Where a ray first crosses a set of polygons, in floating point: for estimates of a scene's
// scale (the span of the room around a sensor, which sets the radiosity mesh's automatic element
// size), never for a result. A ray through a shared edge or vertex may pass between the
// polygons; callers take medians over many rays.

#include <vector>

#include "geometry/polygon.hpp"

namespace daylit {

// The least t > 0 at which origin + t·direction lies in one of the polygons (each taken in the
// plane of its Newell normal); infinity where it meets none.
double nearest_crossing(const std::vector<Polygon>& polygons, const Vec3& origin, const Vec3& direction);

}  // namespace daylit
