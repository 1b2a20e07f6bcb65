#pragma once
// The irradiance a receiver gets from one radiosity element of linearly varying exitance, over the
// exactly visible part of the element's surface: the transport K of DESIGN.md §4, one element at
// a time (Chen and Arvo 2000, "Closed-form expressions for irradiance from non-uniform Lambertian
// luminaires, Part I", eq. 67: the linearly varying luminaire).

#include <array>
#include <cstddef>
#include <vector>

#include "geometry/spherical_region.hpp"
#include "simulation/radiosity_mesh.hpp"

namespace daylit {

// The irradiance at receiver (x, n) is Σ_k c_k M_k for the element's node values M_k (the exitance
// on the side facing x). With w the unit plane normal facing away from x, h = w·(v_0 − x) > 0, and
// y = x + (h/(w·u)) u the point seen in direction u, φ_k(y) = φ_k(x) + h (∇φ_k·u)/(w·u) (∇φ_k lies
// in the plane), so
//     c_k = (1/π) [φ_k(x) ∫ (n·u) dσ + h Σ_i (∇φ_k·e_i) ∫ (e_i·u)(n·u)/(w·u) dσ],  i = 1, 2,
// e_i an orthonormal basis of the plane: Lambert's formula and two rational moments T^{2;1}
// (linear_exitance_moment, rational_moments.hpp), over the part of `surface_region` (the visible
// directions to the element's surface, as the visibility engine gives them, with the receiver's
// hemisphere cut) inside the element's cone. The cone cut is three great-circle clips of the
// direction vectors (hemisphere_clip.hpp): exact but for one rounding per new vertex, and the
// pieces of neighbouring elements tile the surface's region, so their sum is the surface's.
// `unobstructed`: surface_region is the whole surface cut by the receiver's plane only, so the
// element's own directions are used (no clipping of the surface's other pieces).
// Accuracy: the kernels' (about 1e-13 relative to the terms' magnitude). Returns zeros where x
// lies in the element's plane or sees none of it.
std::array<double, 3> element_irradiance_coefficients(const SphericalRegion& surface_region, bool unobstructed,
                                                      const RadiosityElement& element, const Vec3& x, const Vec3& n);

// The same with the part of the region that the element covers, for callers that weigh
// directions further (glazing): the clipped region itself.
SphericalRegion element_region(const SphericalRegion& surface_region, bool unobstructed,
                               const RadiosityElement& element, const Vec3& x, const Vec3& n);
// The same into `out` (not `surface_region`), reusing its storage.
void element_region(const SphericalRegion& surface_region, bool unobstructed, const RadiosityElement& element,
                    const Vec3& x, const Vec3& n, SphericalRegion& out);

std::array<double, 3> element_irradiance_coefficients(const SphericalRegion& element_part,
                                                      const RadiosityElement& element, const Vec3& x, const Vec3& n);

// The coefficients of every element of `surface` at (x, n) where nothing hides any of it (the
// `unobstructed` case above: the surface's region is its polygon, cut by the receiver's plane
// only), in the order of its element list. The same values as element_irradiance_coefficients
// per element (to roundoff), at about half the cost: the terms of each mesh edge are computed
// once for the two elements that share it (linear_element_edge_terms). An element whose sums fail
// that function's accuracy test, or which crosses the receiver's plane or lies in it, is left to
// element_irradiance_coefficients.
void unobstructed_surface_coefficients(const RadiosityMesh& mesh, std::size_t surface, const Vec3& x, const Vec3& n,
                                       std::vector<std::array<double, 3>>& out);

}  // namespace daylit
