#pragma once
// A spherical cap (the sun's disk, Snyder 1996's sub-hemispherical source) cut by a region bounded
// by great arcs (what stays visible through an aperture and past the occluders): Lambert's
// integral over the intersection, in closed form.

#include "geometry/spherical_region.hpp"

namespace daylit {

// ∫_{C ∩ A} (n·u) dσ for the cap C = {u : s·u ≥ cos ρ} (s unit, 0 < ρ < π/2) and a region A of
// signed loops (holes and partitions count by their winding numbers), by Stokes' theorem:
// ∫_B (n·u) dσ = ½ ∮_{∂B} n·(u × du). ∂(C ∩ A) is made of the parts of A's great arcs inside C,
// each giving ½ (n·m)·(length inside) like Lambert's formula, and the arcs of C's circle weighted
// by A's winding number there, each giving, for u(φ) = cos ρ s + sin ρ (cos φ p + sin φ q),
//     ½ n·[ sin²ρ (φ1 − φ0) s − sin ρ cos ρ ((sin φ1 − sin φ0) p − (cos φ1 − cos φ0) q) ].
// The winding number changes by sign(c·m) where the circle (tangent c) crosses an arc (pole m);
// its value at one point of the circle comes from the closed-form series of cosine_power_arc.hpp.
// The crossings use α = atan2(√(sin²ρ − (s·m)²), cos ρ), which keeps its digits for the sun's
// ρ = 0.0047 rad where acos(cos ρ / c) would lose half of them. Accuracy ~1e-13 relative to
// π sin²ρ; measure-zero tangencies (an arc touching the circle) are resolved by rounding.
double cap_lambert(const SphericalRegion& region, const Vec3& axis, double half_angle, const Vec3& n);

}  // namespace daylit
