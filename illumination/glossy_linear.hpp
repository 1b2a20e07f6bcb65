#pragma once
// Glossy reflection and transmission of planar Lambertian luminaires whose exitance varies
// linearly over them (Chen and Arvo, "Simulating non-Lambertian phenomena involving
// linearly-varying luminaires", §2 and §4.2, eqs. 2, 4 and 32), beside Arvo's uniform case in
// glossy.hpp (same conventions: directions away from the shaded point, regions already cut by
// occluders).
//
// On the luminaire's plane (unit normal w facing away from the point, at distance h) the exitance
// M(x) = m0 + g·x seen along u is M = (a·u)/(w·u) with a = (m0 + g·o) w + h g (eq. 2, o the shaded
// point), so the radiance is (a·u)/(π (w·u)) and a Phong lobe c (v·u)^n turns the reflected
// radiance into (c/π) τ^{n,1,1;1}(A, v, b, a; w) (eq. 4), a rational moment of
// rational_moments.hpp (eq. 13, O(n²) per edge).

#include "geometry/spherical_region.hpp"

namespace daylit {

// M(x) = constant + gradient·x, x in world coordinates (exitance, e.g. W/m²).
struct LinearExitance {
  double constant = 0;
  Vec3 gradient;
};

// Eq. 32: the vector t with τ^{n,1,1;1}(A, v, b, a; w) = a·t for every a, so that several
// exitance channels (colours) share one evaluation; t = Σ_i e_i τ^{n,1,1;1}(A, v, b, e_i; w).
Vec3 linear_luminaire_glossy_tensor(const SphericalRegion& region, const Vec3& v, int n, const Vec3& b, const Vec3& w);

// Radiance reflected towards `to_viewer` (unit, in front of the surface) by a surface at `origin`
// with unit normal b and BRDF c·max(0, v·u)^n about the mirror direction v = 2(b·e)b − e, lit by a
// planar luminaire of linear exitance: (c/π) ∫ (v·u)^n (b·u) M(x(u)) dσ over the luminaire cut to
// both hemispheres. The region holds the directions x − origin of the (unoccluded part of the)
// luminaire. Throws daylit::Error if c exceeds max_glossy_coefficient(n) or the region does not
// lie in front of the plane.
double glossy_reflected_radiance_linear(const SphericalRegion& luminaire, const Vec3& origin, const Vec3& normal,
                                        const Vec3& to_viewer, int n, double coefficient, const Vec3& plane_point,
                                        const Vec3& plane_normal, const LinearExitance& exitance);

// Transmission through a thin frosted pane at `origin` whose unit normal faces the viewer, from a
// luminaire of linear exitance behind it: the lobe about the unscattered direction −e and the
// cosine on the far side, (c/π) ∫ (−e·u)^n (−b·u) M dσ over the luminaire cut to the far hemisphere
// and the lobe's (Chen and Arvo §4.2: "v replaced by −u'").
double glossy_transmitted_radiance_linear(const SphericalRegion& luminaire, const Vec3& origin, const Vec3& normal,
                                          const Vec3& to_viewer, int n, double coefficient, const Vec3& plane_point,
                                          const Vec3& plane_normal, const LinearExitance& exitance);

}  // namespace daylit
