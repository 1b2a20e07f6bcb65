#pragma once
// The part of a region of directions in the hemisphere {u : c·u ≥ 0}.

#include "geometry/spherical_region.hpp"

namespace daylit {

// Clips every loop of `region` by the plane through the origin with normal c (Sutherland–Hodgman
// on the direction vectors: the plane passes through the apex of the cone they span, so a straight
// cut of the vectors is a great-arc cut of the directions). Orientation is kept. A non-convex loop
// may come back with zero-area bridges along the cut, whose edge terms cancel in every kernel.
// Accuracy: the new vertices are rounded once (double).
SphericalRegion clip_to_hemisphere(const SphericalRegion& region, const Vec3& c);

// The same into `out` (which must not be `region`), reusing its storage: for callers that clip
// many times per receiver (the radiosity's elements), where allocation was a tenth of the cost.
void clip_to_hemisphere(const SphericalRegion& region, const Vec3& c, SphericalRegion& out);

}  // namespace daylit
