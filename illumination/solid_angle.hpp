#pragma once
// Solid angle of a region of directions bounded by great arcs.

#include "geometry/spherical_region.hpp"

namespace daylit {

// Signed solid angle (sr) of one loop: positive for a positively oriented loop (DESIGN.md §1 of
// spherical_region.hpp). Sum over a fan of triangles from the first vertex of Van Oosterom and
// Strackee's formula, tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|), on
// unnormalised vectors, with the numerator written a·((b−a)×(c−a)): for a square 1e6 away it
// stays at 1e-16 relative where a·(b×c) gives 2e-5 (DESIGN.md §7). The loop must lie in an open
// hemisphere (always true of directions through a planar polygon).
double solid_angle(const DirectionLoop& loop) noexcept;

// Sum over the loops of a region.
double solid_angle(const SphericalRegion& region) noexcept;

}  // namespace daylit
