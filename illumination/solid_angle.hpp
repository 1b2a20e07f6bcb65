#pragma once
// Solid angle of a region of directions bounded by great arcs.

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "geometry/spherical_region.hpp"
#include "illumination/real_vector.hpp"
#include "illumination/tracked_sum.hpp"

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

// The fan terms 2·atan2(num, den) above, in precision R, each passed to add(term): shared by
// solid_angle() and the moments, which also need their magnitudes to detect cancellation.
//
// The fan's apex is the first vertex unless a diagonal from it spans more than 120°: a loop with
// two nearly opposite vertices (a receiver 1e-6 from an aperture's plane sees its near edge run
// from one side of the horizon to the other) then has a fan triangle whose other two vertices lie
// nearly opposite the apex, where the denominator above is a cancellation of O(1) terms down to
// O(δ²) (δ the angle from antipodal): 1e-16 / δ² relative, 1.4e-3 of the solid angle at δ = 5e-7
// (found by fuzz_visibility). The apex is then the vertex whose widest diagonal is narrowest; a
// nearly opposite pair left on one triangle shares an edge of the loop, where the error is
// 1e-16 / δ, the conditioning of that edge itself (its great circle is defined to δ⁻¹ of its
// ends' rounding). Loops without such diagonals (all of an ordinary scene's) are summed as before.
inline std::size_t solid_angle_fan_apex(const DirectionLoop& loop) {
  const std::size_t m = loop.size();
  const auto cosine = [&](std::size_t i, std::size_t j) {
    return dot(loop[i], loop[j]) / std::sqrt(dot(loop[i], loop[i]) * dot(loop[j], loop[j]));
  };
  // The widest diagonal from apex k: the vertices not adjacent to it.
  const auto widest = [&](std::size_t k) {
    double lowest = 1;
    for (std::size_t d = 2; d + 1 < m; ++d) lowest = std::min(lowest, cosine(k, (k + d) % m));
    return lowest;
  };
  if (m < 4 || widest(0) >= -0.5) return 0;
  std::size_t best = 0;
  double best_cosine = widest(0);
  for (std::size_t k = 1; k < m; ++k)
    if (const double c = widest(k); c > best_cosine) best = k, best_cosine = c;
  return best;
}

template <class R, class Add>
void for_each_solid_angle_term(const DirectionLoop& loop, Add&& add) {
  if (loop.size() < 3) return;
  const std::size_t m = loop.size(), apex = solid_angle_fan_apex(loop);
  const real::V3<R> a0(loop[apex]);
  const R la0 = real::norm(a0);
  for (std::size_t i = 1; i + 1 < m; ++i) {
    real::V3<R> a = a0, b(loop[(apex + i) % m]), c(loop[(apex + i + 1) % m]);
    R la = la0, lb = real::norm(b), lc = real::norm(c);
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
    R denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    // One vertex nearly opposite both others (within 25° of π; a receiver close to an aperture's
    // plane sees its near edge run from one side of the horizon to the other): the denominator
    // is then O(δ²) (δ the angles from antipodal), and the sum of four O(1) terms keeps only
    // ε/δ² of it (5.8e-4 of a triangle's 0.68 sr at δ = 5e-7; found by fuzz_visibility). On unit
    // vectors it is exactly (a + c)·(b + c) for any naming of the three; with c the opposite
    // vertex both sums are small and formed directly, ε/δ. (One opposite pair alone leaves the
    // denominator O(δ), which the general form already keeps to ε/δ: it is left as it was.)
    const R cab = dot(a, b) / (la * lb), cbc = dot(b, c) / (lb * lc), cca = dot(c, a) / (lc * la);
    if (int(cab < R(-0.9)) + int(cbc < R(-0.9)) + int(cca < R(-0.9)) >= 2) {
      const real::V3<R> ua = a / la, ub = b / lb, uc = c / lc;
      // The vertex whose cosines with the other two sum lowest stands opposite.
      const R sa = cab + cca, sb = cab + cbc, sc = cbc + cca;
      const R unit = sa <= sb && sa <= sc ? dot(ub + ua, uc + ua) : sb <= sc ? dot(ua + ub, uc + ub) : dot(ua + uc, ub + uc);
      denominator = la * lb * lc * unit;  // degree 1 in each vector, as the general form
    }
    add(R(2) * real::atan2(numerator, denominator));
  }
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
