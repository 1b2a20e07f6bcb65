#pragma once
// A region of directions seen from a receiver, bounded by great arcs: what geometry/ hands to the
// kernels of illumination/ (DESIGN.md §2, step 5).

#include <algorithm>
#include <cstdint>
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

// Whether two directions are nearly opposite: a cosine below −0.9, an arc between them longer
// than 154°. Both the clipper (an arc that long is split at its middle) and the solid angle's fan
// (no diagonal that long) keep away from such pairs, whose great circle rounding leaves uncertain.
inline bool nearly_opposite(const Vec3& a, const Vec3& b) {
  const double d = dot(a, b);
  return d < 0 && d < -0.9 * norm(a) * norm(b);
}

// Where an edge of a region comes from (DESIGN.md §7, "Gradients behind occluders"): every edge
// lies in the plane through the receiver of a line fixed in the model. When the receiver moves,
// the edges of an aperture or occluder line turn about that line (Arvo 1994, "The Irradiance
// Jacobian for Partially Occluded Polyhedral Sources"), while those on the receiver's tangent
// plane or on the horizon stay where they are in direction space. `a` and `b` are two input
// points of the line (model coordinates, not relative to the receiver) for the segment kinds.
struct EdgeSource {
  enum class Kind : std::uint8_t { unknown, aperture, occluder, receiver_plane, horizon };
  Kind kind = Kind::unknown;
  Vec3 a{}, b{};

  friend bool operator==(const EdgeSource&, const EdgeSource&) = default;
};
using EdgeSourceLoop = std::vector<EdgeSource>;

// A region is a set of loops whose signed integrals add up: outer boundaries positive, holes
// negative, or a partition into positively oriented pieces (interior edges then cancel).
// `edge_sources` is filled only where asked for (VisibilityOptions::edge_sources): then it has
// one entry per loop, and edge_sources[l][i] is the source of the edge from loops[l][i] to
// loops[l][i + 1] (cyclically). Code that builds new loops from old ones leaves it empty.
struct SphericalRegion {
  std::vector<DirectionLoop> loops;
  std::vector<EdgeSourceLoop> edge_sources{};

  bool empty() const noexcept { return loops.empty(); }
  bool has_edge_sources() const noexcept { return !loops.empty() && edge_sources.size() == loops.size(); }
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
