#pragma once
// Monte Carlo estimates of the moments ∫_A (w·u)^n (v·u)^m dσ, m ∈ {0, 1}, of a region of
// directions: the baseline against which `daylit bench kernels` measures the closed forms of
// moments.hpp (DESIGN.md §6). Plain doubles, deterministic for a given seed (xoshiro256**).
//
// Both estimators stratify the unit square into N/2 cells of equal measure with two independent
// samples in each: the estimate is the stratified mean, and its standard error comes from the
// spread within each cell, s²_cell = (y₁ − y₂)²/2, which is unbiased (one sample per cell would
// be slightly more accurate, but its variance can only be bounded, by collapsing neighbouring
// cells, which overstates it by up to 2× for smooth integrands: Owen, "Monte Carlo theory,
// methods and examples", §10.3–10.4).
//
// Both need the region to lie within a closed hemisphere (true of every region daylit builds: it
// is clipped to the receiver's tangent plane); they throw daylit::Error otherwise.

#include <cstdint>
#include <optional>

#include "geometry/spherical_region.hpp"

namespace daylit {

// The directions u with axis·u ≥ 1 − height; height ∈ [0, 1] (a hemisphere at most).
struct SphericalCap {
  Vec3 axis;      // unit
  double height;  // 1 − cos(half-angle), kept directly so that tiny caps keep their digits

  double solid_angle() const noexcept;  // 2π·height, sr
};

// Winding number of a region about a direction: how many times its loops wind around u, counted
// positive for positively oriented loops (outer boundaries), so that the kernels' signed boundary
// sums equal ∫ f(u) winding(u) dσ; for a region with holes it is 1 inside and 0 in a hole or
// outside. Computed by counting the signed crossings of the loops' edges with the great arc from
// u to a reference direction q outside the region's bounding cap (winding 0 there). Each crossing
// is decided by the signs of four triple products (the test of S2's CrossingSign), with the side
// of each vertex computed once and shared by its two edges, so that an arc through a vertex
// counts once; a direction exactly on an edge's great circle (probability 0 for random samples)
// may count either way. O(vertices) per direction.
class RegionWinding {
 public:
  // Throws daylit::Error if the region's vertices do not fit in a closed hemisphere.
  explicit RegionWinding(const SphericalRegion& region);

  // A cap that contains the region (the smallest enclosing ball of the unit vertices, by 64
  // Bădoiu–Clarkson iterations, or their normalised mean if that is smaller; enlarged by 1e-9
  // relative against rounding). Any cap of half-angle ≤ π/2 that contains the vertices contains
  // the great arcs between them.
  const SphericalCap& bounding_cap() const noexcept { return cap_; }

  // u must be a unit vector.
  int winding(const Vec3& u) const noexcept;

 private:
  struct Edge {
    std::size_t start, end;  // indices into vertices_
    Vec3 pole;               // a × (b − a): positive side = left of the edge = inside
    int reference_side[2];   // sign of pole·q for the two reference directions
  };
  std::vector<Vec3> vertices_;  // as given (not normalised): only signs are taken from them
  std::vector<Edge> edges_;
  SphericalCap cap_{};
  Vec3 reference_[2];  // two directions outside the cap, 3° apart
};

// ∫_A (w·u)^n (v·u)^m dσ with m = 1 when v is given, else m = 0. w and v need not be unit.
struct MomentIntegrand {
  Vec3 w;
  int n = 0;
  std::optional<Vec3> v;

  double operator()(const Vec3& u) const noexcept;
};

struct MonteCarloEstimate {
  double value;           // the estimate of the moment (sr)
  double standard_error;  // estimated standard deviation of `value` over seeds
};

// Uniform sampling of the region's bounding cap (uniform in solid angle), stratified: the unit
// square maps to the cap by z = 1 − ξ₁·height, φ = 2π ξ₂, which preserves area (Archimedes), so
// equal cells of the square are equal cells of the cap. Chosen over sampling the area of a planar
// polygon with its 1/r²·cos Jacobian because a visible region is a set of loops of directions
// with no plane of its own (clipped windows, holes), and because a pdf constant in solid angle
// is the honest "uniform" baseline. Efficiency σ(A)/σ(cap): 0.4–0.5 for the polygons of
// `daylit bench kernels` (2/π at best for a square).
// Error O(N^−3/4) for the region's indicator (its boundary cuts ~√N cells), O(N^−1) where the
// integrand is smooth. samples ≥ 2.
MonteCarloEstimate moment_uniform_stratified(const SphericalRegion& region, const MomentIntegrand& f, long samples,
                                             std::uint64_t seed);

// Importance sampling of the cosine-power (Phong) lobe: pdf (n+1)/(2π) (ŵ·u)^n on the hemisphere
// around w (cos θ = ξ₁^{1/(n+1)}, φ = 2π ξ₂, stratified), so each sample weighs
// 2π |w|^n (v·u)^m winding(u)/(n+1) and only the region's indicator and the (v·u) factor are left
// to vary. If the region's bounding cap reaches across the plane w·u = 0 both hemispheres are
// sampled (pdf (n+1)/(4π)|ŵ·u|^n); if it lies wholly on the far side, that side is. samples ≥ 2.
MonteCarloEstimate moment_lobe_importance(const SphericalRegion& region, const MomentIntegrand& f, long samples,
                                          std::uint64_t seed);

}  // namespace daylit
