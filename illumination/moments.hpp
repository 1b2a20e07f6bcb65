#pragma once
// Moments of regions of directions bounded by great arcs (Arvo 1995, §4–5).
//
// All take positively oriented loops (outer boundaries counter-clockwise seen from outside the
// sphere); Arvo's outward boundary normal is then −m for the edge pole m = unit(a×b), which turns
// the minus signs of his eqs. 11 and 14 into plus signs below. Axes need not be unit vectors.
//
// Accuracy: each result is first computed in double together with the sum of the absolute values
// of its terms; where the estimated error (10 + n)·u·κ (κ that sum over |result|, n the order)
// exceeds 1e-13 (terms that cancel: a region grazing the receiver's plane, or small and far off
// the axes; DESIGN.md §7) it is recomputed in long double, and if need be in __float128. The
// result is then within about 1e-13 relative of the exact value for the given (double) input.

#include <vector>

#include "geometry/spherical_region.hpp"
#include "illumination/precision_escalation.hpp"

namespace daylit {

// ∫_A (n·u) dσ = ½ Σ_edges θ (m·n): Lambert's formula, the irradiance from a uniform source of
// unit radiance on a receiver with normal n (the part of A behind the receiver counts negative).
double lambert(const SphericalRegion& region, const Vec3& n);

// Axial moments τ^k = ∫_A (w·u)^k dσ for k = 0..n, by Arvo's eq. 11 with our orientation:
//     (k + 1) τ^k = (k − 1) |w|² τ^{k−2} + Σ_edges (w·m) ∫_arc (w·u)^k−1 ds,  τ^0 = σ(A),
// all orders in one O(n·edges) pass. Far off the axis at high orders the result is the small
// difference of large terms; use axial_moment() there.
std::vector<double> axial_moments(const SphericalRegion& region, const Vec3& w, int n);

// τ^n alone (Arvo's AxialMoment), O(n·edges), accurate at every order: where eq. 11 cancels (the
// region far from ±w relative to the lobe's width ~1/√n), the complementary form
//     (n + 1) τ^n = 2π N − Σ_edges (w·m) Σ_{j ≥ 0} ∫_arc (w·u)^{n+1+2j} ds,
// with N = [w ∈ A] + (−1)^n [−w ∈ A] (DESIGN.md §7), whose terms are as small as the result.
// N is an integer computed, not tested for: the series summed to infinity have closed forms
// (cosine_power_arc.hpp), and eq. 11 extended to infinity says σ[n even] + their sum = 2π N.
// The tails are summed by the upward or Miller's downward recurrence, whichever is stable.
double axial_moment(const SphericalRegion& region, const Vec3& w, int n);

// Double-axis moment ∫_A (w·u)^n (v·u) dσ (Arvo's eq. 14), O(n·edges), accurate at every order
// through the split v = (v·w) w + v⊥ (w unit here; other lengths scale the result by |w|^n):
//     τ^{n,1} = (v·w) τ^{n+1} + Σ_edges (v⊥·m) ∫_arc (w·u)^n ds / (n + 2),
// which is eq. 14 with eq. 11 substituted; the first term is an axial moment (stable as above),
// the second sums terms no larger than the result's own scale.
double double_axis_moment(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n);

// ∫_A (w·u)^n (a·u)(b·u) dσ, the factor pattern (n, 1, 1), O(n·edges). With a = (a·ŵ)ŵ + a⊥ and
// b likewise, the recurrence of Chen and Arvo (2000, eq. 29, q = 0) taken about b⊥ gives
//     (n + 3) ∫ (w·u)^n (a⊥·u)(b⊥·u) dσ = (a⊥·b⊥) τ^n + Σ_edges (b⊥·m) ∫_arc (w·u)^n (a⊥·u) ds,
// and the terms with a·ŵ or b·ŵ are double-axis and axial moments as above. The arc integral is
// c^n [(a⊥·p) F_{n+1} + (a⊥·q)(cos^{n+1} s0 − cos^{n+1} s1)/(n + 1)] in the frame of
// cosine_power_arc.hpp.
double triple_axis_moment(const SphericalRegion& region, const Vec3& w, const Vec3& a, const Vec3& b, int n);

// Early termination (Arvo 1995 §5.4, eq. 21): the series of eq. 11 over the cosine powers of one
// edge, Σ_i c^i F_i, is stopped once what is left, bounded by c^k ∫|cos|^k (c r)²/(1 − (c r)²)
// (r = max |cos| on the arc, so |F_{k+2j}| ≤ r^{2j} ∫|cos|^k), is below `tolerance` times the
// edge's partial sum; for the double-axis moment the top-order term of eq. 14 is dropped as well
// when its bound c^n θ r^n is below tolerance of the result. Faster where the axis is far from
// every edge's plane (c r well below 1); never more accurate than the exact functions above.
struct TruncatedMoment {
  double value;
  double error_bound;  // bound on |value − exact|: the dropped terms plus the rounding estimate
  int terms;           // cosine-power integrals evaluated, summed over the edges
};
TruncatedMoment axial_moment_truncated(const SphericalRegion& region, const Vec3& w, int n, double tolerance);
TruncatedMoment double_axis_moment_truncated(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n,
                                             double tolerance);

// ∫_A (n·u) dσ and ∫_A (w·u)(n·u) dσ together, in one pass over the edges: the two moments a
// sky luminance linear in u needs (the CIE overcast sky). Same formulas as lambert() and
// double_axis_moment(region, w, n, 1), same accuracy.
struct CosineMoments {
  double cosine;         // ∫ (n·u) dσ
  double cosine_linear;  // ∫ (w·u)(n·u) dσ
};
CosineMoments cosine_moments(const SphericalRegion& region, const Vec3& n, const Vec3& w);

// Σ_k c_k ∫_A (a·u)^k (n·u) dσ and Σ_k c_k ∫_A (a·u)^k (z·u)(n·u) dσ for k = 0..K in one pass over
// the edges, O(K·edges): the sky through glazing whose transmittance is a polynomial in the cosine
// of incidence a·u (a unit). The orders come from eq. 11 (τ^k about a), eq. 14 (∫ (a·u)^k (n·u)
// and ∫ (a·u)^k (z·u)) and Chen and Arvo's eq. 29 taken about n:
//     (k + 3) ∫ (a·u)^k (z·u)(n·u) = k (a·n) ∫ (a·u)^{k−1} (z·u) + (n·z) τ^k + Σ_edges (n·m) ∫_arc (a·u)^k (z·u) ds.
// Meant for K ≲ 20 (it uses the upward recurrence, exact there). Accuracy 1e-9 relative: the
// cancellation among the c_k (fitted coefficients reach 1e5) counts in κ and sends the sum to
// long double (moments.cpp says why the target is not 1e-13: the c_k are a fit, good to ~1e-3).
struct PolynomialCosineMoments {
  double cosine;         // Σ c_k ∫ (a·u)^k (n·u) dσ
  double cosine_linear;  // Σ c_k ∫ (a·u)^k (z·u)(n·u) dσ
};
PolynomialCosineMoments polynomial_cosine_moments(const SphericalRegion& region, const Vec3& a, const Vec3& n,
                                                  const Vec3& z, const std::vector<double>& c);

// The same moments with their accuracy (precision_escalation.hpp): the value, the estimated
// relative error (10 + n)·u·κ, κ = Σ|terms| / |result| (an estimate above 1e-10 means
// cancellation beyond what __float128 carries), the precision that settled it (0 double, 1 long
// double, 2 __float128) and the κ of the double pass.
Escalated<double> lambert_with_accuracy(const SphericalRegion& region, const Vec3& n);
// The same to a caller's target: relative `tolerance`, or `absolute_tolerance` where that is
// positive (escalate()), for a term whose digits beyond some level are nobody's (the radiosity
// transport's, element_transport.cpp).
Escalated<double> lambert_with_accuracy(const SphericalRegion& region, const Vec3& n, double tolerance,
                                        double absolute_tolerance);
Escalated<std::vector<double>> axial_moments_with_accuracy(const SphericalRegion& region, const Vec3& w, int n);
Escalated<double> axial_moment_with_accuracy(const SphericalRegion& region, const Vec3& w, int n);
Escalated<double> double_axis_moment_with_accuracy(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n);
Escalated<double> triple_axis_moment_with_accuracy(const SphericalRegion& region, const Vec3& w, const Vec3& a,
                                                   const Vec3& b, int n);

}  // namespace daylit
