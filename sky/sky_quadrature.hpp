#pragma once
// Adaptive cubature of a sky luminance that is not a polynomial in the direction (the CIE general
// skies, Perez) over an exact visible region, with the region's fan triangles split at the sun.

#include <functional>

#include "geometry/spherical_region.hpp"
#include "illumination/spherical_quadrature.hpp"

namespace daylit {

// ∫_A L(u) (n·u)₊ T(u) dσ over the region A (above the horizon and in front of the receiver, as
// the visibility routine returns it), L the relative luminance, T the glazing's transmittance
// (1 when not given). The circumsolar terms of both skies have a kink at the sun (χ = 0): every
// fan triangle that holds the sun is split into three with the sun as a vertex, where the
// cubature's refinement converges fastest (SKY.md: 1e-14 with modest orders). `tolerance` is
// relative, as integrate_over_region takes it (spherical_quadrature.hpp).
QuadratureResult sky_irradiance_quadrature(const std::function<double(const Vec3&)>& luminance, const Vec3& sun,
                                           const SphericalRegion& region, const Vec3& n, double tolerance,
                                           const std::function<double(const Vec3&)>& transmittance = {});

// The region's fan triangles, each that holds the sun s split into three with s as a vertex: what
// sky_irradiance_quadrature integrates, for an integrand given in batches (integrate_over_region
// with a DirectionBatch).
SphericalRegion split_at_sun(const SphericalRegion& region, const Vec3& s);

}  // namespace daylit
