#pragma once
// Solid angle of a region of directions bounded by great arcs.

#include "geometry/spherical_region.hpp"
#include "illumination/real_vector.hpp"
#include "illumination/tracked_sum.hpp"

namespace daylit {

// Signed solid angle (sr) of one loop: positive for a positively oriented loop (DESIGN.md §1 of
// spherical_region.hpp). Sum over a fan of triangles (from the apex fan_apex() picks) of Van Oosterom and
// Strackee's formula, tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|), on
// unnormalised vectors, with the numerator written a·((b−a)×(c−a)): for a square 1e6 away it
// stays at 1e-16 relative where a·(b×c) gives 2e-5 (DESIGN.md §7). The loop must lie in an open
// hemisphere (always true of directions through a planar polygon).
double solid_angle(const DirectionLoop& loop) noexcept;

// Sum over the loops of a region.
double solid_angle(const SphericalRegion& region) noexcept;

// Where a loop's fan of triangles starts. Every apex gives the loop's solid angle in exact
// arithmetic, but a triangle with a side near π (two nearly opposite directions, δ from
// antipodal) keeps only ε/δ of its terms: a receiver within 1e-12 of the plane x = y of an
// aperture sees a lune whose two tips lie 1e-12 from opposite, and the fan from a tip cost 6.5e-4
// of its 3.14 sr (found by fuzz_visibility, CI's seed-1 run). A loop's own arcs carry that
// conditioning whatever the fan; its diagonals need not. The first vertex stays the apex while no
// diagonal from it has a cosine below −0.9 (δ > 0.45: a few ulps at most), so that ordinary loops
// are summed as before; otherwise the apex is the vertex whose worst diagonal is widest, or a
// direction inside the loop (its edges' unit normals summed: the pole of a lune, ~90° from every
// vertex) when that is wider still, as in a receiver just under a skylight's plane, whose square
// outline puts every corner opposite another.
struct FanApex {
  std::size_t vertex = 0;  // the apex's index in the loop, unless `interior`
  bool interior = false;   // the apex is `direction`, not a vertex: the fan has a triangle per edge
  Vec3 direction{};        // unit
};
FanApex fan_apex(const DirectionLoop& loop) noexcept;

// The term 2·atan2(num, den) of the triangle (a, b, c) in precision R (above).
template <class R>
R solid_angle_triangle_term(real::V3<R> a, R la, real::V3<R> b, real::V3<R> c) {
  R lb = real::norm(b), lc = real::norm(c);
  // The difference form loses a vector much shorter than another (c − a ≈ −a): a vertex 1e-12
  // from the receiver, where it almost lies in an aperture's plane, cost 1e-5 of the solid
  // angle (found by fuzz_visibility). The formula is homogeneous of degree 1 in each vector, so
  // such a triangle is evaluated on unit vectors; triangles whose lengths differ by less than a
  // factor 2 (all those of small, distant polygons) keep their exact input differences.
  const R longest = std::max({la, lb, lc}), shortest = std::min({la, lb, lc});
  if (shortest > 0 && longest > 2 * shortest) {
    a = a / la;
    b = b / lb;
    c = c / lc;
    la = lb = lc = R(1);
  }
  const R numerator = dot(a, cross(b - a, c - a));
  const R ab = dot(a, b), bc = dot(b, c), ca = dot(c, a);
  R denominator = la * lb * lc + ab * lc + ca * lb + bc * la;
  // One vertex nearly opposite both others (within 25° of π: a receiver close to an aperture's
  // plane sees its near edge run from one side of the horizon to the other, and a triangle with
  // that edge may have its third vertex nearly opposite both ends): the denominator is then
  // O(δ²) (δ the angles from antipodal), and the sum of four O(1) terms keeps only ε/δ² of it
  // (1.4e-3 and 5.8e-4 of the solid angle at δ = 5e-7; found by fuzz_visibility). On unit
  // vectors it is exactly (a + c)·(b + c) for any naming of the three; with c the opposite vertex
  // both sums are small and formed directly, ε/δ. (One opposite pair alone leaves the
  // denominator O(δ), which the general form already keeps to ε/δ: it is left as it was.)
  const bool opposite_ab = ab < R(-0.9) * la * lb, opposite_bc = bc < R(-0.9) * lb * lc,
             opposite_ca = ca < R(-0.9) * lc * la;
  if (int(opposite_ab) + int(opposite_bc) + int(opposite_ca) >= 2) {
    const real::V3<R> ua = a / la, ub = b / lb, uc = c / lc;
    // The vertex whose cosines with the other two sum lowest stands opposite.
    const R cab = ab / (la * lb), cbc = bc / (lb * lc), cca = ca / (lc * la);
    const R sa = cab + cca, sb = cab + cbc, sc = cbc + cca;
    const R unit = sa <= sb && sa <= sc ? dot(ub + ua, uc + ua) : sb <= sc ? dot(ua + ub, uc + ub) : dot(ua + uc, ub + uc);
    denominator = la * lb * lc * unit;  // degree 1 in each vector, as the general form
  }
  return R(2) * real::atan2(numerator, denominator);
}

// The fan terms 2·atan2(num, den) above, in precision R, each passed to add(term): shared by
// solid_angle() and the moments, which also need their magnitudes to detect cancellation.
template <class R, class Add>
void for_each_solid_angle_term(const DirectionLoop& loop, Add&& add) {
  const std::size_t m = loop.size();
  if (m < 3) return;
  const FanApex apex = fan_apex(loop);
  if (apex.interior) {
    const real::V3<R> c(apex.direction);
    for (std::size_t i = 0; i < m; ++i)
      add(solid_angle_triangle_term<R>(c, R(1), real::V3<R>(loop[i]), real::V3<R>(loop[(i + 1) % m])));
    return;
  }
  const std::size_t k = apex.vertex;
  const real::V3<R> a(loop[k]);
  const R la = real::norm(a);
  for (std::size_t i = 1; i + 1 < m; ++i)
    add(solid_angle_triangle_term<R>(a, la, real::V3<R>(loop[(k + i) % m]), real::V3<R>(loop[(k + i + 1) % m])));
}

// σ(A) in precision R with the magnitude of its fan terms (tracked_sum.hpp), for the kernels
// that measure their cancellation.
template <class R>
real::Tracked<R> solid_angle_tracked(const SphericalRegion& region) {
  real::Tracked<R> sum;
  for (const auto& loop : region.loops) for_each_solid_angle_term<R>(loop, [&](R term) { sum.add(term); });
  return sum;
}

}  // namespace daylit
