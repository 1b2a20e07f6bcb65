#pragma once
// The great arc between two directions, with the robust edge terms of DESIGN.md §7.

#include <optional>

#include "geometry/spherical_region.hpp"
#include "illumination/real_vector.hpp"

namespace daylit {

template <class R>
struct ArcEdge {
  R length;         // θ ∈ [0, π], radians
  R sin_length;     // sin θ
  R one_minus_cos;  // 1 − cos θ, from the chord so that short arcs keep their digits
  real::V3<R> normal;         // unit (a×b)/|a×b|: the pole of the arc's great circle
  real::V3<R> start, end;     // unit a and unit b
  real::V3<R> chord;          // end − start, from e = b − a so that short arcs keep their digits
  real::V3<R> start_tangent;  // unit tangent at a, towards b (normal × start)
  real::V3<R> end_tangent;    // unit tangent at b, onwards (normal × end)
};

// Edge from direction a to direction b (any non-zero lengths). θ = atan2(|a×e|, a·b) and the
// normal from a×e with e = b − a: acos(â·b̂) loses every digit for an emitter 1e8 away, and a×b
// loses six for rotated geometry 1e6 away, while these forms cost the same (DESIGN.md §7).
// Returns nothing for a degenerate edge (a and b parallel), which contributes nothing.
template <class R>
std::optional<ArcEdge<R>> arc_edge(const real::V3<R>& a, const real::V3<R>& b) noexcept {
  using real::norm;
  const real::V3<R> e = b - a;
  const real::V3<R> c = cross(a, e);
  const R cn = norm(c);
  if (!(cn > 0)) return std::nullopt;
  ArcEdge<R> arc;
  const R la = norm(a), lb = norm(b);
  arc.length = real::atan2(cn, dot(a, b));
  arc.sin_length = cn / la / lb;
  arc.normal = c / cn;
  arc.start = a / la;
  arc.end = b / lb;
  // b/|b| − a/|a| = e/|b| + a (|a| − |b|)/(|a||b|) with |a| − |b| = −e·(a + b)/(|a| + |b|): no
  // difference of nearly equal unit vectors, so a 1e-9 rad arc keeps full relative precision.
  arc.chord = e / lb - (dot(e, a + b) / (la * lb * (la + lb))) * a;
  arc.one_minus_cos = R(0.5) * dot(arc.chord, arc.chord);
  arc.start_tangent = cross(arc.normal, arc.start);
  arc.end_tangent = cross(arc.normal, arc.end);
  return arc;
}

// Calls f(arc) for every non-degenerate edge of every loop of a region, in precision R.
template <class R, class F>
void for_each_edge(const SphericalRegion& region, F&& f) {
  for (const auto& loop : region.loops) {
    const std::size_t m = loop.size();
    for (std::size_t i = 0; i < m; ++i)
      if (const auto arc = arc_edge(real::V3<R>(loop[i]), real::V3<R>(loop[(i + 1) % m]))) f(*arc);
  }
}

}  // namespace daylit
