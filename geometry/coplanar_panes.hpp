#pragma once
// Panes that lie in one plane and overlap: a double-sided shade modelled as two coincident
// polygons facing opposite ways (Honeybee's sample tree crowns: eight 361-gons in four planes,
// each plane holding two discs 0.003 ft apart along it), or a pane drawn twice. A ray that crosses
// one crosses the other at the same point. Radiance filters it once: the second intersection lies
// within FTINY of the transmitted ray's origin, and o_face skips it. Taken as panes in series
// they are neither: neither lies behind the other, each pane's view counts the directions through
// both (T1 − 1 and T2 − 1 on top of what passes the panes in front), and the overlap passes
// T1 + T2 − 1 instead of T1 (measured: −1.8 % of the sky component behind the tree sample,
// against a ray caster that filters each crossing of a plane once).
// So where two such panes overlap, the overlap is the earlier pane's (by index), as in Radiance
// (VisibilityEngine): the later pane's view takes the earlier one's pieces as opaque (exact
// clipping, as for a wall in the aperture's plane), the earlier one's view passes the later one
// by, and a view through both from beyond counts the earlier one only (a direction that crosses
// both crosses their common plane once, inside both).

#include <cstddef>
#include <utility>
#include <vector>

#include "geometry/convex_pieces.hpp"
#include "geometry/polygon.hpp"

namespace daylit {

// Whether every vertex of each piece lies within 1e-9 of the two pieces' extent of the other's
// plane. (Radiance's FTINY is 1e-6 absolute; a relative bound keeps the test independent of
// units, and far below any gap a model means.)
bool coplanar_pieces(const ConvexPiece& a, const ConvexPiece& b);

// For coplanar convex pieces: whether they share area beyond rounding (not when disjoint, nor
// when they touch along an edge). The part of q inside w, cut at the lines of w's edges in turn.
bool overlap_in_plane(const ConvexPiece& q, const ConvexPiece& w);

// The pairs (i, j), i < j, of panes (each given as its convex pieces) that lie in one plane (every
// piece of each coplanar with every piece of the other) and overlap, in increasing order. Panes
// whose pieces are not all in one plane (a warped polygon fanned into triangles, partly in the
// other's plane) are left as panes in series: there a direction may cross both at two points.
std::vector<std::pair<std::size_t, std::size_t>> overlapping_coplanar_panes(const std::vector<std::vector<ConvexPiece>>& panes);

// The same for polygons, with the share of the later one's area that lies inside the earlier
// (for the notice that says which panes filter once, and for the reflected components, where a
// pane inside another is the same pane: simulation/model_inputs.cpp).
struct CoplanarOverlap {
  std::size_t earlier = 0, later = 0;
  double later_share = 0;  // of the later polygon's area, within the rounding of the cut's vertices
};
std::vector<CoplanarOverlap> coplanar_overlaps(const std::vector<Polygon>& polygons);

}  // namespace daylit
