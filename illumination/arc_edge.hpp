#pragma once
// The great arc between two directions, with the robust edge terms of DESIGN.md §7.

#include <cmath>
#include <optional>

#include "geometry/vec3.hpp"

namespace daylit {

struct ArcEdge {
  double length;        // θ ∈ [0, π], radians
  double sin_length;    // sin θ
  double one_minus_cos; // 1 − cos θ, from the chord so that short arcs keep their digits
  Vec3 normal;          // unit (a×b)/|a×b|: the pole of the arc's great circle
  Vec3 start, end;      // unit a and unit b
  Vec3 start_tangent;   // unit tangent at a, towards b (normal × start)
  Vec3 end_tangent;     // unit tangent at b, onwards (normal × end)
};

// Edge from direction a to direction b (any non-zero lengths). θ = atan2(|a×e|, a·b) and the
// normal from a×e with e = b − a: acos(â·b̂) loses every digit for an emitter 1e8 away, and a×b
// loses six for rotated geometry 1e6 away, while these forms cost the same (DESIGN.md §7).
// Returns nothing for a degenerate edge (a and b parallel), which contributes nothing.
inline std::optional<ArcEdge> arc_edge(const Vec3& a, const Vec3& b) noexcept {
  const Vec3 c = cross(a, b - a);
  const double cn = norm(c);
  if (!(cn > 0)) return std::nullopt;
  ArcEdge arc;
  const double la = norm(a), lb = norm(b);
  arc.length = std::atan2(cn, dot(a, b));
  arc.sin_length = cn / la / lb;
  arc.normal = c / cn;
  arc.start = a / la;
  arc.end = b / lb;
  const Vec3 chord = arc.end - arc.start;
  arc.one_minus_cos = 0.5 * dot(chord, chord);
  arc.start_tangent = cross(arc.normal, arc.start);
  arc.end_tangent = cross(arc.normal, arc.end);
  return arc;
}

}  // namespace daylit
