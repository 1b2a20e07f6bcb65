#pragma once
// Irradiance from planar Lambertian luminaires whose radiant exitance is a polynomial in position
// (Chen and Arvo 2000, "Closed-form expressions for irradiance from non-uniform Lambertian
// luminaires, Part II", §5), and glossy reflection and transmission of linearly varying
// luminaires (Chen and Arvo, "Simulating non-Lambertian phenomena involving linearly-varying
// luminaires", eqs. 4 and 32).
//
// A point x = origin + t u of the luminaire's plane seen in the direction u lies at t = h/(w·u),
// w the plane's unit normal facing away from the origin and h the origin's distance to the plane.
// In a frame (e1, e2, w) the exitance becomes M(x) = Σ m_ab ξ^a ζ^b with in-plane coordinates
// ξ = h (e1·u)/(w·u), ζ = h (e2·u)/(w·u) about the foot of the perpendicular, so that
//     E = (1/π) Σ_ab m_ab h^{a+b} ∫ (e1·u)^a (e2·u)^b (n·u) / (w·u)^{a+b} dσ,
// a sum of the rational moments T^{a+b+1, a+b} of Theorem 4, contracted in that frame (see
// rational_moments.hpp for the recurrences and their stability).

#include <vector>

#include "geometry/spherical_region.hpp"

namespace daylit {

struct ExitanceTerm {
  double coef;
  int i, j, k;  // c · x^i y^j z^k in world coordinates; i, j, k ≥ 0
};
using ExitancePolynomial = std::vector<ExitanceTerm>;

struct LuminaireIrradiance {
  double value;           // irradiance, in the unit of the exitance
  double relative_error;  // estimated from the cancellation of the terms (rational_moments.hpp)
  int precision = 0;      // the precision the frame recurrences settled in (0 double, 1 long double, 2 __float128)
  double condition = 1;   // κ of their double pass (rational_moments.hpp)
};

// Highest total degree of the exitance accepted. Measured (bench rational; the stress geometries
// of tests/illumination/test_polynomial_luminaire.cpp): in double the recurrences' terms outgrow the result
// (κ ≳ 1e3) from degree ~6 on, and the escalation to long double and __float128 keeps the
// estimated error below 1e-13 through degree 24 on receivers 1e-6 from the plane, luminaires 50
// widths off-axis and 1e-3-wide luminaires 100 away; but from degree ~16 every such call runs in
// __float128 (50–200 ms) and the negative powers cos^{-(D+1)} s of the edge integrals approach
// double's range for grazing directions. Above this, daylit::Error.
constexpr int kMaxExitanceDegree = 16;

// E = ∫ M(x) cosθ_r cosθ_l /(π r²) dA over the part of a planar luminaire whose directions from
// `origin` form `region` (loops of direction vectors x − origin, as geometry hands them; already
// clipped to the receiver's hemisphere and to occluders). `plane_point`/`plane_normal`: the
// luminaire's plane (either orientation). Equivalently E = (1/π) ∫_region M(origin + t(u) u)
// (normal·u) dσ with t(u) the distance along u to the plane.
// Every degree goes through the frame recurrences; at degree 0 they are Lambert's formula, and at
// degrees 1 and 2 they equal Chen and Arvo's closed boundary forms (eqs. 67 and 75–77,
// linear_exitance_moment and quadratic_exitance_moment in rational_moments.hpp) to roundoff. Returns 0 where the origin lies in the plane (the
// luminaire is seen edge-on). Throws daylit::Error for a degree above kMaxExitanceDegree, a
// negative exponent, non-finite input, or a region with a vertex not strictly in front of the
// plane (w·u ≤ 0: not directions to this luminaire).
LuminaireIrradiance polynomial_luminaire_irradiance(const SphericalRegion& region, const Vec3& origin,
                                                    const Vec3& normal, const Vec3& plane_point,
                                                    const Vec3& plane_normal, const ExitancePolynomial& exitance);

}  // namespace daylit
