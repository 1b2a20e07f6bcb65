#pragma once
// Which receivers a closed surface of the model encloses, so that their view of the sky box
// (geometry/sky_box.hpp: what is seen past every polygon) is known to be empty without clipping
// six box faces against the whole model for each of them.
//
// The argument is the one of ray parity. A set of polygons whose boundary edges cancel in pairs
// (every piece of every edge, cut at the vertices that lie on it, is an edge of an even number of
// the polygons: a closed surface, possibly of several shells, in mod-2 homology) is a cycle; for a
// cycle, every ray from a point off it to infinity crosses it a number of times of the same parity
// (rays through its edges or in its planes aside). Where that parity is odd, every ray crosses it
// at least once, so nothing beyond it is seen: a node inside a room whose walls, floor, ceiling
// and window panes close (a hole in a wall filled by its window, as Radiance and Honeybee models
// are written) sees the sky only through its apertures.
//
// The cycle is found by peeling: polygons with an edge piece of odd count (shades, a ground
// plane, a partition that ends on a wall not cut along it, a pane set inside a reveal) are set
// aside until none is left; what stays closes. The ray's crossings are decided exactly (CGAL's
// filtered orientation predicates on the input coordinates of the polygons' convex pieces, the
// pieces the visibility engine clips), and a ray that meets an edge, a vertex or a plane through
// its origin answers "not known", as does anything this test cannot certify: the caller then does
// the exact visibility computation as before, so the answer is never guessed.

#include <cstddef>
#include <vector>

#include "geometry/polygon.hpp"

namespace daylit {

class ClosedShells {
 public:
  ClosedShells() = default;
  // `polygons`: every polygon that blocks the view (the sky box's occluders: the opaque polygons,
  // then the apertures' panes).
  explicit ClosedShells(const std::vector<Polygon>& polygons);

  // How many of the polygons the closed surface kept (0: nothing encloses anything).
  std::size_t polygon_count() const { return shell_polygon_count_; }

  // True only where certain: every direction of the open hemisphere about n at x meets one of the
  // closed surface's polygons other than `own` (the receiver's own polygon, whose plane x lies in
  // to roundoff; any value not an index of `polygons` for none).
  bool encloses(const Vec3& x, const Vec3& n, std::size_t own) const;

 private:
  struct Triangle {
    Vec3 a, b, c;
    std::size_t polygon;
  };
  std::vector<Triangle> triangles_;  // the kept polygons' convex pieces, fanned
  std::size_t shell_polygon_count_ = 0;
  Vec3 centre_;        // of the triangles' box
  double reach_ = 0;   // its diagonal and 1: every triangle lies within reach_ of centre_
};

}  // namespace daylit
