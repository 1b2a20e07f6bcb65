#pragma once
// Adaptive cubature of a function of direction over a region bounded by great arcs: the reference
// path for sky luminances that have no closed form (DESIGN.md §6), and an honest baseline beside
// the closed forms.

#include <cstddef>
#include <functional>

#include "geometry/spherical_region.hpp"

namespace daylit {

struct QuadratureResult {
  double value;
  double error_estimate;  // Σ over accepted triangles of |coarse − fine|
  long evaluations;       // calls of the integrand
};

// ∫_A g(u) dσ(u), g called with unit u. Each loop is split into a fan of spherical triangles from
// its first vertex (signed, so non-convex loops and holes add up), and each triangle ABC is
// integrated over the planar triangle A + α(B − A) + β(C − A) with the Jacobian of the central
// projection, dσ = |det[A, B − A, C − A]| / |p|³ dα dβ, by a degree-8 Gauss rule on the
// triangle (16 points, Dunavant 1985), compared with the sum over its four midpoint children;
// a triangle is accepted when they agree to `tolerance` × (the region's running |integral| scale),
// else split, to a depth of 16. The error estimate is what the accepted comparisons sum to.
QuadratureResult integrate_over_region(const SphericalRegion& region, const std::function<double(const Vec3&)>& g,
                                       double tolerance);

// The integrand at n unit directions at once (values[i] = g(x[i], y[i], z[i])): the same cubature,
// the rule's 16 directions per triangle passed together, so that an integrand can evaluate them
// four at a time (sky/circumsolar_sum.hpp).
using DirectionBatch =
    std::function<void(const double* x, const double* y, const double* z, std::size_t n, double* values)>;
QuadratureResult integrate_over_region(const SphericalRegion& region, const DirectionBatch& g, double tolerance);

}  // namespace daylit
