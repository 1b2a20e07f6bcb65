#pragma once
// Moments of regions of directions bounded by great arcs (Arvo 1995, §4–5).
//
// All take positively oriented loops (outer boundaries counter-clockwise seen from outside the
// sphere); Arvo's outward boundary normal is then −m for the edge pole m = unit(a×b), which turns
// the minus signs of his eqs. 11 and 14 into plus signs below. Axes need not be unit vectors.
// Accuracy: a few ulps of the sum of absolute edge terms; cancellation between edge terms (a
// region small and far off the axes) is not yet detected here.

#include <vector>

#include "geometry/spherical_region.hpp"

namespace daylit {

// ∫_A (n·u) dσ = ½ Σ_edges θ (m·n): Lambert's formula, the irradiance from a uniform source of
// unit radiance on a receiver with normal n (the part of A behind the receiver counts negative).
double lambert(const SphericalRegion& region, const Vec3& n) noexcept;

// Axial moments τ^k = ∫_A (w·u)^k dσ for k = 0..n, by Arvo's eq. 11 with our orientation:
//     (k + 1) τ^k = (k − 1) |w|² τ^{k−2} + Σ_edges (w·m) ∫_arc (w·u)^{k−1} ds,  τ^0 = σ(A).
std::vector<double> axial_moments(const SphericalRegion& region, const Vec3& w, int n);

// Double-axis moment ∫_A (w·u)^n (v·u) dσ by Arvo's eq. 14 with our orientation:
//     (n + 2) τ^{n,1} = n (w·v) τ^{n−1} + Σ_edges (v·m) ∫_arc (w·u)^n ds.
double double_axis_moment(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n);

}  // namespace daylit
