#pragma once
// A region of directions seen from a receiver, bounded by great arcs: what geometry/ hands to the
// kernels of illumination/ (DESIGN.md §2, step 5).

#include <vector>

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

}  // namespace daylit
