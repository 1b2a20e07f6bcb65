#pragma once
// A region of directions seen from a receiver, bounded by great arcs: what geometry/ hands to the
// kernels of illumination/ (DESIGN.md §2, step 5).

#include <algorithm>
#include <vector>

#include "geometry/polygon.hpp"
#include "geometry/vec3.hpp"

namespace daylit {

// One closed boundary loop. Vertices are direction vectors from the receiver (x − p), not
// necessarily unit: the kernels normalise where they must, and keeping |x − p| lets them form edge
// terms from differences (DESIGN.md §7). A loop is positively oriented when it runs
// counter-clockwise seen from outside the unit sphere, looking towards the receiver
// (a·(b×c) > 0 for a convex loop); its signed solid angle is then positive.
using DirectionLoop = std::vector<Vec3>;

// A region is a set of loops whose signed integrals add up: outer boundaries positive, holes
// negative, or a partition into positively oriented pieces (interior edges then cancel).
struct SphericalRegion {
  std::vector<DirectionLoop> loops;

  bool empty() const noexcept { return loops.empty(); }
};

// The directions from `origin` that hit the planar polygon, whatever its vertex order, as one
// positively oriented loop: with N the polygon's Newell normal, the loop through v − origin is
// positive when N·(origin − v0) < 0 (det[a, b, c] = −N_abc·(origin − a) for a convex polygon).
// Empty when the origin lies in the polygon's plane (measured in double).
inline SphericalRegion directions_through(const std::vector<Vec3>& polygon, const Vec3& origin) {
  const Vec3 n = newell_normal(polygon);
  const double side = dot(n, origin - polygon.at(0));
  if (side == 0) return {};
  DirectionLoop loop;
  for (const Vec3& v : polygon) loop.push_back(v - origin);
  if (side > 0) std::reverse(loop.begin(), loop.end());
  return {{loop}};
}

}  // namespace daylit
