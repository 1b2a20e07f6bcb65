#pragma once
// Moments of regions of directions bounded by great arcs (Arvo 1995, §4–5).
//
// All take positively oriented loops (outer boundaries counter-clockwise seen from outside the
// sphere); Arvo's outward boundary normal is then −m for the edge pole m = unit(a×b), which turns
// the minus signs of his eqs. 11 and 14 into plus signs below. Axes need not be unit vectors.
//
// Accuracy: each result is first computed in double together with the sum of the absolute values
// of its terms; where that sum exceeds the result by more than a factor of 64 (terms that cancel:
// a region grazing the receiver's plane, or small and far off the axes; DESIGN.md §7) it is
// recomputed in long double, and beyond 64·2^11 in __float128. The result is then within about
// 1e-13 relative of the exact value for the given (double) directions.

#include <vector>

#include "geometry/spherical_region.hpp"

namespace daylit {

// ∫_A (n·u) dσ = ½ Σ_edges θ (m·n): Lambert's formula, the irradiance from a uniform source of
// unit radiance on a receiver with normal n (the part of A behind the receiver counts negative).
double lambert(const SphericalRegion& region, const Vec3& n);

// Axial moments τ^k = ∫_A (w·u)^k dσ for k = 0..n, by Arvo's eq. 11 with our orientation:
//     (k + 1) τ^k = (k − 1) |w|² τ^{k−2} + Σ_edges (w·m) ∫_arc (w·u)^{k−1} ds,  τ^0 = σ(A).
std::vector<double> axial_moments(const SphericalRegion& region, const Vec3& w, int n);

// Double-axis moment ∫_A (w·u)^n (v·u) dσ by Arvo's eq. 14 with our orientation:
//     (n + 2) τ^{n,1} = n (w·v) τ^{n−1} + Σ_edges (v·m) ∫_arc (w·u)^n ds.
double double_axis_moment(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n);

// ∫_A (n·u) dσ and ∫_A (w·u)(n·u) dσ together, in one pass over the edges: the two moments a
// sky luminance linear in u needs (the CIE overcast sky). Same formulas as lambert() and
// double_axis_moment(region, w, n, 1), same accuracy.
struct CosineMoments {
  double cosine;         // ∫ (n·u) dσ
  double cosine_linear;  // ∫ (w·u)(n·u) dσ
};
CosineMoments cosine_moments(const SphericalRegion& region, const Vec3& n, const Vec3& w);

// What the last call on this thread needed and achieved: the precision (0 double, 1 long double,
// 2 __float128) and the estimated relative error 10·u·κ, κ = Σ|terms| / |result|. An estimate
// above 1e-10 means cancellation beyond what __float128 carries (high orders far off the axis:
// the stable complementary form is not implemented yet).
struct MomentAccuracy {
  int precision = 0;
  double relative_error = 0;
};
MomentAccuracy last_moment_accuracy() noexcept;

}  // namespace daylit
