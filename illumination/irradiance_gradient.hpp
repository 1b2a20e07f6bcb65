#pragma once
// The gradient of irradiance with respect to the receiver's position, occluders included: Arvo's
// irradiance Jacobian for partially occluded polyhedral sources (Arvo, SIGGRAPH 1994) with the
// interior term of Holzschuch and Sillion (Eurographics Rendering Workshop 1995, eqs. 7–9) for
// luminaires whose exitance varies over them.
//
// The derivation used throughout (DESIGN.md §7, "Gradients behind occluders"). In direction space
// E(p) = ∫_{A(p)} L(p, u) (n·u) dσ, the normal n fixed. Every edge of A lies in the plane through p
// of a line ℓ fixed in the model (an aperture, luminaire or occluder edge; edges on the receiver's
// tangent plane or on the horizon have fixed planes, and do not move). With c = (a − p) × d for a
// point a and direction d of ℓ, the plane's unit normal is ĉ (taken towards the region's inside,
// μ), and moving p by δp moves the boundary point u, whose ray meets ℓ at distance r, outwards by
// (μ·δp)/r; in the plane 1/r = (f·u)/h = w·u with w = (d × c)/|c|² (h = |c|/|d| the distance
// from p to ℓ, f the unit direction of its foot). Reynolds' transport theorem then gives
//     ∇E = Σ_moving edges μ ∫_arc L(p, u) (n·u) (w·u) ds  +  ∫_A ∇_p L(p, u) (n·u) dσ,
// the boundary term (Arvo's Jacobian, occluder edges included) and the interior term (zero when
// the radiance depends on the direction only: a uniform luminaire, or a sky).
//
// Plain doubles in and out (no CGAL); regions must carry edge sources (SphericalRegion::
// edge_sources, VisibilityOptions::edge_sources), else daylit::Error.

#include <vector>

#include "geometry/spherical_region.hpp"
#include "illumination/polynomial_luminaire.hpp"

namespace daylit {

// A radiance that depends on the direction only, L(u) = (α + β·u) · Σ_k c_k (a·u)^k: a uniform
// source (α = L, β = 0, c = {1}), the CIE overcast sky (α = 1/3, β = (0, 0, 2/3)), either seen
// through glazing of transmittance Σ_k c_k μ^k in the cosine of incidence μ = a·u (a unit).
struct DirectionalRadiance {
  double alpha = 1;
  Vec3 beta{};
  Vec3 axis{0, 0, 1};
  std::vector<double> c{1};
};

struct IrradianceGradient {
  Vec3 value;                 // ∇_p E, in the units of E per unit length of the model
  double relative_error = 0;  // estimated, relative to |value| (see below)
  int precision = 0;          // 0 double, 1 long double, 2 __float128
};

// ∇_p ∫_A L(u) (n·u) dσ over a region whose edges carry their sources: the boundary term alone,
// exact. Along each arc u(t) = A cos t + S sin t the integrand is a trigonometric polynomial of
// degree deg(c) + 3 (at most 60), expanded in e^{ikt} and integrated term by term in closed form
// (∫_0^θ e^{ikt} dt = (sin kθ + i(1 − cos kθ))/k, formed without cancellation for short arcs).
// Edge terms cancel as the region shrinks (each is O(θ/h), the sum O(θ²/h) for a source of
// angular size θ: DESIGN.md §7), so the sum is formed in double with the magnitude of its terms
// and redone in long double, then __float128, while the estimated error 10·u·κ (κ = Σ|terms|
// bounded with |c_k| over |result|) exceeds `tolerance`. O(deg(c)² · edges).
IrradianceGradient directional_irradiance_gradient(const SphericalRegion& region, const Vec3& origin, const Vec3& n,
                                                   const DirectionalRadiance& radiance, double tolerance = 1e-13);

// The irradiance E = (1/π) ∫_region M(x(u)) (n·u) dσ from a planar Lambertian luminaire whose
// exitance M is a polynomial in position (polynomial_luminaire.hpp), x(u) = p + t(u) u its point
// seen in the direction u, and ∇_p E with the normal fixed. Both terms of the derivation above:
//  - interior: with ν the plane's unit normal, D = ν·(plane_point − p) ≠ 0 and g = (I − νν^T)∇M
//    (only M's variation along the plane matters), x(u) = p + D u/(ν·u) gives
//    ∇_p M(x(u)) = g(x) − ν (u·g(x))/(ν·u) = g(x) − ν ((x − p)·g(x))/D, so the interior term is
//    E[g] − (ν/D) E[(x − p)·g], irradiances of polynomial exitances (Holzschuch and Sillion's
//    X1/X2 terms of appendix A.2, here in closed form through Chen and Arvo's rational moments);
//  - boundary: μ ∫_arc M(x(u)) (n·u)(w·u) ds/π per moving edge. For a constant M this is the
//    closed form above; otherwise M(x(u)) is rational in u (denominators (ν·u)^deg), and the arc
//    integral is taken by adaptive Gauss–Kronrod (7/15 points, QUADPACK's error estimate) on the
//    arc's angle, to `tolerance` of |∇E| in all (each arc to tolerance/(2κ) of its ∫|integrand|;
//    the integrand is analytic on the arc: ν·u > 0 there). Not a closed form: the default
//    tolerance, 1e-11, is what double can promise for it; tighter ones go to long double.
// relative_error combines the estimates of both terms (relative to |∇E|) and of E. Throws
// daylit::Error where polynomial_luminaire_irradiance does, and for an origin in the plane.
struct LuminaireGradient {
  double value = 0;           // E
  Vec3 gradient{};            // ∇_p E
  double relative_error = 0;  // the larger of the estimates for E and for ∇E
};
LuminaireGradient polynomial_luminaire_gradient(const SphericalRegion& region, const Vec3& origin, const Vec3& n,
                                                const Vec3& plane_point, const Vec3& plane_normal,
                                                const ExitancePolynomial& exitance, double tolerance = 1e-11);

}  // namespace daylit
