#pragma once
// Arvo 1995 §6: directional (Phong) luminaires, glossy reflection and glossy transmission of
// uniform polygonal luminaires, all double-axis moments of the luminaire's visible directions,
// and the normalisation N(w, v, n) of §6.4.
//
// Conventions: every direction u points away from the receiving point; regions are those of
// geometry/spherical_region.hpp (the luminaire as seen from the point, occluders already clipped
// away); radiances in any unit, results in the same unit times sr (irradiance) or as radiance.

#include "geometry/spherical_region.hpp"

namespace daylit {

// N(w, v, n) = ∫_{L2} (w·u)^n (v·u) dσ over the lune L2 = {w·u ≥ 0, v·u ≥ 0} (Arvo eq. 25), for
// unit w, v and n ≥ 0, O(n). With d = w·v and c = √(1 − d²), eq. 14 on the lune's two
// semicircular edges (w·u = 0 on one, v·n_out = −1 on the other) gives
//     (n + 2) N = n d τ^{n−1} + c^n W_n,   W_k = ∫_{−π/2}^{π/2} cos^k s ds,
// and eq. 11 on the same edges gives the lune's axial moments
//     (k + 1) τ^k = (k − 1) τ^{k−2} + π [k = 1] + d c^{k−1} W_{k−1},   τ^0 = 2(π − acos d).
// Relative accuracy ~1e-14 for d ≥ 0; for d < 0 the terms alternate and the result carries an
// absolute error of ~1e-16·n.
double phong_normalisation(const Vec3& w, const Vec3& v, int n);

// Largest coefficient c of Arvo's glossy BRDF ρ = c (w·u')^n (eq. 24) that conserves energy at
// every incidence: the directional albedo c·N(w, v, n) peaks at normal incidence (w = v), where
// N = 2π/(n + 2); hence c ≤ (n + 2)/(2π).
double max_glossy_coefficient(int n);

// §6.1, eq. 22: irradiance at a receiver with unit normal `receiver_normal` from a polygonal
// luminaire of radiance L(u) = peak_radiance · max(0, −a·u)^n, a = unit `luminaire_axis` (the
// direction of maximum emission): L0 ∫ (−a·u)^n (v·u) dσ over the region cut to both hemispheres.
double phong_luminaire_irradiance(const SphericalRegion& luminaire, const Vec3& luminaire_axis, int n,
                                  const Vec3& receiver_normal, double peak_radiance);

// §6.2, eqs. 23–24: radiance reflected towards `to_viewer` (unit, in front of the surface) by a
// surface with unit normal v and BRDF c·max(0, w·u')^n about the mirror direction
// w = 2(v·e)v − e, lit by a uniform luminaire of radiance L: L c ∫ (w·u')^n (v·u') dσ(u') over the
// luminaire cut to both hemispheres. Throws daylit::Error if c > max_glossy_coefficient(n).
double glossy_reflected_radiance(const SphericalRegion& luminaire, const Vec3& normal, const Vec3& to_viewer, int n,
                                 double coefficient, double radiance);

// §6.3: radiance transmitted towards `to_viewer` through a thin frosted pane whose unit normal
// `normal` faces the viewer, from a uniform luminaire of radiance L behind it. The lobe is about
// the unscattered direction w = −e and the cosine is taken on the far side: L c ∫ (w·u')^n
// (−v·u') dσ(u') over the luminaire cut to the far hemisphere and the lobe's. Same bound on c.
double glossy_transmitted_radiance(const SphericalRegion& luminaire, const Vec3& normal, const Vec3& to_viewer, int n,
                                   double coefficient, double radiance);

}  // namespace daylit
