#pragma once
// Snyder's area-light shading functions (J. M. Snyder, "Area Light Sources for Real-Time
// Graphics", Microsoft Research MSR-TR-96-11, 1996), with his normalisations: Lambertian
// I = (1/π) ∫ F(u) (N·u) dΩ (I_norm = π), Phong I = ((n + 1)/2π) ∫ F(u) (R·u)^n dΩ over the
// hemisphere around R (I_norm-Phong = 2π/(n + 1)). Multiply a Lambertian value by π L to get the
// irradiance from a source of uniform radiance L.
//
// Angles are in radians: ω ∈ [0, π] is the angle between the source's axis L and the normal N
// (Lambertian) or the reflection direction R (Phong), σ the angular radius of a sub-hemispherical
// source; ω outside [0, π] is clamped. Accuracy is relative, for the arguments as given (exact
// doubles), measured while writing them against 40- to 120-digit mpmath quadrature (about 2,500
// cases) and checked in tests/illumination/test_snyder.cpp against long-double quadrature. It holds also where
// the value is ill-conditioned in its arguments (ω within δ of π/2 + σ, where I_hemi_sub vanishes
// like δ^{5/2}): there the inputs' own rounding, not the evaluation, limits what the value means.

#include "geometry/spherical_region.hpp"
#include "geometry/vec3.hpp"

namespace daylit {

// ---- Lambertian (Snyder §2) ---------------------------------------------------------------------

// Constant hemisphere about L (eq. 3/4): ½(1 + cos ω), written cos²(ω/2) (no cancellation at
// ω → π). ω ∈ [0, π]; within 2 ulps.
double I_hemi_const(double omega) noexcept;

// Cosine-weighted hemisphere, radiance ∝ L·u (eq. 5): (2/3π)(sin³ω + cos ω (π − ω + sin ω cos ω)).
// For ω > π/2 written with ε = π − ω (π to 128 bits) and 2ε − sin 2ε by its series, since the
// terms cancel to O(ε³); long double inside. ω ∈ [0, π]; within 2e−16 relative.
double I_hemi_cos(double omega) noexcept;

// α I_hemi_const + β I_hemi_cos (§2.1.3).
double I_hemi_sum(double omega, double alpha, double beta) noexcept;

// The CIE overcast sky, L(u) ∝ (1 + 2 L·u)/3 with L the zenith: I_hemi_sum(ω, 1/3, 2/3) (§2.1.3;
// 7/9 for a horizontal receiver). Within 2e−16 relative.
double I_hemi_overcast(double omega) noexcept;

// Uniform sub-hemispherical source of angular radius σ (a sphere, or the sun) (eq. 6), exact.
// Eq. 6 simplified with q = √(sin²σ − cos²ω) (its γ has cos γ = q/sin ω): in the fillet
// |ω − π/2| ≤ σ,
//     π I = ψ₁ sin²σ cos ω + atan2(q, cos σ) − q cos σ,   ψ₁ = atan2(q, −cos ω cos σ),
// = π cos ω sin²σ before it and 0 after. The last two terms cancel to O(σ²) relative for small σ
// and are evaluated as t sin²σ − (t − atan t), t = q/cos σ; where ω > π/2 makes the first term
// cancel the others by more than 8× (the thin sliver before the source sets), the value comes from
// clipped_cap_axial_moment (cap_moment.hpp) instead. σ ∈ [0, π] (σ > π/2 too, via the cap
// moments); ω ∈ [0, π]; within 2e−16 relative (measured on 154 cases, σ from 1e−6 to π/2, ω at
// and beside the breakpoints).
double I_hemi_sub(double omega, double sigma);

// Snyder's approximation of I_hemi_sub (§2.2): exact outside the fillet, and in it two cubic
// Hermite segments on [π/2 − σ, π/2] and [π/2, π/2 + σ] matching value and ω-derivative at
// π/2 − σ (sin³σ, −cos σ sin²σ), π/2 ((σ − sin σ cos σ)/π, −½ sin²σ) and π/2 + σ (0, 0).
// Maximum absolute error over σ ∈ (0, π/2], ω ∈ [0, π] (measured on 400 × 2,000 points, bounded in
// tests/illumination/test_snyder.cpp): 6.80e−3, at σ = 1.4035, ω = 2.354 (5.40e−3 at σ = π/2); relative to the
// peak sin²σ at most 7.04e−3 (σ = 1.3635); for small σ it is 3.57e−3 sin³σ. σ ∈ [0, π/2]
// (for σ > π/2, where Snyder defines no fillet, it returns I_hemi_sub).
double I_hemi_sub_hermite(double omega, double sigma);

// Uniform polygonal source (eq. 8): (1/π) ∫ (N·u) dΩ over the region cut to the hemisphere about N
// (Lambert's formula, moments.hpp). Accuracy as lambert().
double I_poly(const SphericalRegion& region, const Vec3& normal);

// ---- Phong (Snyder §3) --------------------------------------------------------------------------

// Snyder's sine-power integral S(n, x) = ∫_0^x sin^n θ dθ (eq. before 13), n ≥ 0, x ∈ [0, π].
// Snyder's upward recurrence (appendix B) loses everything where S is small (x below π/2, n
// large: the recurrence's other solution ~ n^{−1/2} swamps S ~ sin^{n+1}x/((n+1) cos x)). Measured
// in double: 1.9e−18 for 3.0e−154 at n = 1000, x = π/4; 3.5e−18 for 3.5e−56 at n = 100, x = 0.3;
// 1.4e−17 for 6.9e−34 at n = 1000, x = 1.2. Here, for y = min(x, π − x):
//   sin²y ≤ ½ or n cos²y > 2: S(n, y) = sin^{n+1}y cos y/(n+1) Σ_k t_k, t_0 = 1,
//                             t_{k+1} = t_k sin²y (n + 2 + 2k)/(n + 3 + 2k)  (positive terms:
//                             the unrolled downward recurrence, i.e. ₂F₁ after Euler's transform);
//   otherwise:                S(n, π/2) − ∫_0^{π/2−y} cos^n t dt, the latter by its upward
//                             recurrence (positive terms), losing at most a factor e;
// and S(n, x) = S(n, π) − S(n, π − x) for x > π/2. S(n, π) by S(n, π) = (n−1)/n S(n−2, π) (eq. 13).
// Within 4e−16 relative for n ≤ 10,000 (measured; long double inside).
double sine_power_integral(int n, double x) noexcept;

// Constant hemisphere (eq. 14): 1 − S(n, ω)/S(n, π) = S(n, π − ω)/S(n, π), the second form used
// for ω ≥ π/2 where the first cancels. n ≥ 0, ω ∈ [0, π]; within 4e−16 relative for n ≤ 10,000.
double I_hemi_const_phong(double omega, int n) noexcept;

// Cosine-weighted hemisphere (eq. 15):
//     (n+1)/((n+2) S(n+1, π)) [sin^{n+2}ω/(n+1) + cos ω S(n+1, π − ω)].
// For ω > π/2 the bracket cancels; with y = π − ω, s = sin y it equals the positive series
// s^{n+2}/(n+2) Σ_k t_k/(n+1+2k) (t_k as for S(n+1, y)), used where it converges fast.
// n ≥ 0, ω ∈ [0, π]; within 4e−16 relative for n ≤ 10,000.
double I_hemi_cos_phong(double omega, int n) noexcept;

// Uniform sub-hemispherical source (eq. 24) for every n ≥ 0: (n + 1)/(2π) ∫_{C∩H(R)} (R·u)^n dΩ by
// clipped_cap_axial_moment (cap_moment.hpp: Snyder's Stokes series, eq. 16, made stable for large
// n, and for even n with the cut cap's solid angle I(0) = 2α − 2ψ₁ cos σ by Gauss–Bonnet).
// I_hemi_sub_phong(0, σ, n) = 1 − cos^{n+1}σ. σ ∈ [0, π], ω ∈ [0, π], 0 ≤ n ≤ 100,000 (throws
// daylit::Error above); within 1.1e−15 relative for n ≤ 10,000 (see cap_moment.hpp).
double I_hemi_sub_phong(double omega, double sigma, int n);

// Polygonal source (eq. 25): (n + 1)/(2π) ∫ (R·u)^n dΩ over the region cut to the hemisphere about
// R (clip_to_hemisphere), by Arvo's axial moment (eq. 11, with its complementary form far off the
// axis: axial_moment() in moments.hpp), even n included (its τ^0 is the solid angle). R need not
// be a unit vector. Accuracy as axial_moment(), whose estimate axial_moment_with_accuracy() returns.
double I_poly_phong(const SphericalRegion& region, const Vec3& R, int n);

// ---- Spherical luminaires (Snyder eq. 7) --------------------------------------------------------

// Mean angular radius of the sun's disk (0.533° diameter), radians.
inline constexpr double kSunHalfAngle = 0.5 * 0.533 * 3.14159265358979323846 / 180;

// Angular radius σ = asin(r/d) of a sphere of radius r seen from distance d to its centre (eq. 7),
// as atan2(r, √((d − r)(d + r))), exact to rounding even as r → d. d ≥ r ≥ 0 (d = r gives π/2);
// throws daylit::Error when r > d (the point is inside the sphere) or an argument is negative or
// not finite.
double sphere_half_angle(double distance, double radius);

// I_hemi_sub for a uniform sphere (centre, radius) seen from `point` on a receiver with normal
// `normal` (need not be unit): ω = atan2(|N×d|, N·d) with d = centre − point, σ from
// sphere_half_angle. The irradiance is π L times this. Throws as sphere_half_angle does.
double I_hemi_sub_sphere(const Vec3& point, const Vec3& normal, const Vec3& center, double radius);

}  // namespace daylit
