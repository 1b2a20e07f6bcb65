#pragma once
// Moments over a spherical cap, whole or cut to a hemisphere, in closed form: the regions of
// Snyder's sub-hemispherical light sources (Snyder 1996, §2.2 and §3.2; appendices C–E), for every
// exponent n ≥ 0 and every cap half-angle σ ∈ (0, π].
//
// Notation: the cap C = {u : L·u ≥ cos σ} about the unit axis L, the clip hemisphere
// H = {u : c·u ≥ 0}, ω ∈ [0, π] the angle between L and c, z = c·u.
//
// Method (cap_moment.cpp has the derivations). Stokes' theorem on the sphere (Snyder's appendix C)
// gives, for P(n) = (n + 1) ∫_{C∩H} z^n dΩ and the boundary integrals
// J(i) = ∮ z^{i−1} (x dy − y dx) over the part of the cap's circle above the horizon,
//     forward:  P(n) = Σ_{i ≡ n (2), i ≤ n} J(i)  (+ K, the horizon arc, in J(1); + I(0) for even n),
//     tail:     P(n) = 2π·[c ∈ C] − Σ_{k ≥ 0} J(n + 2 + 2k),
// the second because (n + 1) I(n) → 2π·[c ∈ C] as n → ∞. The forward sum loses a factor of about
// z_top^−n to cancellation when the region lies below the pole; the tail loses nothing there and
// converges like z_max^{2k}, z_max = cos(ω − σ) the top of the circle. The forward sum is
// evaluated first and the tail only where the forward terms cancel; the form whose terms cancel
// least is kept. The J(i) need the arc integrals f_m = ∫ z^m dφ and g_m = ∫ z^m cos φ dφ over the
// arc (Snyder's F and G, appendix D): by his upward recurrence where the top of the circle is the
// nearest point to the pole (every term positive), and otherwise, where that recurrence grows the
// unwanted solution like (|z_min|/z_max)^m, by the backward three-term recurrence (again every
// term positive) started from a positive series and normalised to f_0 (Miller). Caps larger than
// a hemisphere are the hemisphere minus the cap (−L, π − σ).
// Measured: Snyder's own code (appendices E–F, odd n, double) returns −3e−17 for 2.2e−119 at
// n = 1001, ω = 1, σ = 0.3, and 6e−16 for 3.6e−59 at n = 1001, ω = 1.7, σ = 1.2 (relative errors
// 1e+102 and 2e+43); at n = 101 in the second case it is still off by 2e−9.
//
// Accuracy: every result is computed in long double with the magnitude of its terms, and again in
// __float128 when 2^−64·κ·(16 + 2√m) exceeds 4e−16 (κ = Σ|terms|/|result|, m the recurrence
// length). Measured against 40-digit mpmath integrals over z on 2,176 cases (n from 0 to 10,000,
// σ from 1e−6 to π, ω at and within 1e−9 of 0, σ, π/2 ± σ and π): at most 1.1e−15 relative,
// typically below 3e−16, as long as the result is a normal double (results below 1e−308 may lose
// digits; below 1e−330 they are returned as 0).

#include <optional>
#include <vector>

#include "geometry/vec3.hpp"
#include "illumination/factor_moment.hpp"

namespace daylit {

// ∫_{C∩H} z^n dΩ (sr) for the cap of half-angle σ ∈ (0, π] whose axis makes the angle ω ∈ [0, π]
// (radians) with the pole c of H; n ≥ 0. Snyder's I(n) of eq. 16; Snyder's I_hemi-sub-Phong is
// (n + 1)/(2π) times this (eq. 24), for even n as well as odd.
double clipped_cap_axial_moment(double omega, double half_angle, int n);

// ∫_{C∩H} z^n (L·u) dΩ (sr), same arguments. From the divergence theorem on the sphere with the
// field z^{n+1}(L − (L·u)u), which vanishes on the horizon:
//     (n + 2) ∫ z^n (L·u) dΩ = n cos ω I(n − 1) + sin²σ ∫_arc z^n dφ.
double clipped_cap_double_axis_moment(double omega, double half_angle, int n);

// ∫_{C ∩ H} Π_k (a_k·u)^{p_k} dΩ, H the hemisphere {c·u ≥ 0} when `clip` is c, else the whole
// sphere. cap_axis: any finite non-zero vector (normalised here); half_angle σ ∈ (0, π] radians
// (π/2 is a hemisphere, π the whole sphere). Factor axes need not be unit vectors; each must be
// parallel to the clip normal c or to the cap axis L with a positive factor (within 1e−12
// radians); factors on the same axis are merged. Supported, all in closed form:
//   with a clip:    () the solid angle of C∩H;  (c^n) Snyder's I(n);  (c^n, L^1), n ≥ 0;
//   without a clip: () = 2π(1 − cos σ);  (L^k) = 2π(1 − cos^{k+1} σ)/(k + 1).
// Anything else, or invalid arguments, throws daylit::Error naming the problem. Accuracy: as
// above, ≤ 1e−10 relative guaranteed (it throws if its own estimate were worse).
double cap_moment(const Vec3& cap_axis, double half_angle, const std::optional<Vec3>& clip,
                  const std::vector<Factor>& factors);

}  // namespace daylit
