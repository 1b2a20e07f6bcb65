#pragma once
// Decomposition of input polygons into convex, exactly planar pieces: the unit the visibility
// routine clips. Internal to geometry/ (no CGAL in the interface).

#include <vector>

#include "geometry/polygon.hpp"

namespace daylit {

// A convex polygon whose vertices are input coordinates (no constructed points, so exact), lying
// exactly in one plane, ordered counter-clockwise in the coordinates (x_i, x_j) obtained by
// dropping `drop_axis` k, with (i, j) = (k+1, k+2) mod 3; the exact normal
// (v[b]−v[0])×(v[c]−v[0]) then has a positive k-th component.
struct ConvexPiece {
  std::vector<Vec3> vertices;
  int drop_axis = 2;
  int base_b = 1, base_c = 2;  // indices of the base triple (0, b, c) that defines the plane
  std::size_t source = 0;      // index of the polygon it came from
};

// Whether Newell's normal of the vertices, Σ (v_i − v_0) × (v_{i+1} − v_0), is zero in exact
// arithmetic (rationals from the input doubles): the polygon's vector area is zero.
bool exactly_zero_area(const std::vector<Vec3>& v);

// Splits `polygon` into convex pieces. A planar convex polygon stays whole; a convex polygon that
// is planar only within tolerance is fanned into triangles; a non-convex one is triangulated by a
// constrained Delaunay triangulation in its plane, after cancelling edges that are traversed in
// both directions (the "seams" by which Radiance models cut holes into walls). Throws
// daylit::Error naming the polygon's source line if its boundary crosses itself.
std::vector<ConvexPiece> convex_pieces(const Polygon& polygon, std::size_t source);

}  // namespace daylit
