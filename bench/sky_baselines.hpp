#pragma once
// The approximate sky components that `daylit bench scenes` measures beside the exact closed form
// (DESIGN.md §6): Monte Carlo ray casting in doubles, the way Radiance-like tools compute a daylight
// factor, and adaptive cubature over the exact visible region. Both are honest baselines, not straw
// men: the Monte Carlo rays are importance-sampled and stratified, the cubature is adaptive, and
// both integrate the same sky luminance and the same glazing transmittance polynomial as the exact
// path, so that their errors against it are errors of method alone.
//
// They live in sky/ beside the exact sky component they are measured against (DESIGN.md §1: sky
// models and their reference integrators); `daylit bench scenes` is their user.

#include <cstdint>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

// ── Ray casting ─────────────────────────────────────────────────────────────────────────────

// The scene's polygons for ray queries in double precision: a plane and a 2D outline per polygon
// (dominant axis dropped, coordinates relative to the first vertex), and a bounding volume
// hierarchy over the occluders (median split on the longest axis, ≤ 4 polygons per leaf).
// Point-in-polygon is the crossing-number test (Franklin's PNPOLY), which handles non-convex
// polygons and Radiance's seamed holes: a seam edge traversed once each way is crossed an even
// number of times. Rays exactly through an edge (probability 0 for sampled directions) may count
// either way.
class RayScene {
 public:
  explicit RayScene(const Scene& scene);

  // Whether the ray o + t·u, t > 0, meets any occluder (before or beyond any aperture: the sky
  // is at infinity). u need not be unit.
  bool occluded(const Vec3& o, const Vec3& u) const noexcept;

  // Σ over the apertures that the ray o + t·u, t > 0, crosses of their transmittance for the
  // direction u (constant, or Σ c_k μ^k with μ = |a·û|, a the pane's unit normal, as
  // sky_irradiance_through_glazing integrates it). Apertures do not occlude each other (README).
  double transmittance(const Vec3& o, const Vec3& u) const noexcept;

  std::size_t occluder_count() const noexcept { return occluders_.size(); }

 private:
  struct Face {
    Vec3 normal;      // unit
    Vec3 origin;      // first vertex
    int axis_u, axis_v;
    std::uint32_t first, count;  // outline points_[first, first + count)
    Vec3 box_min, box_max;
  };
  struct Node {
    Vec3 box_min, box_max;
    std::uint32_t first, count;  // leaf: faces order_[first, first + count); inner: count = 0, children first, first + 1
  };
  struct ApertureFace {
    Face face;
    double transmittance;
    std::vector<double> angular;  // empty: constant
  };

  Face make_face(const std::vector<Vec3>& vertices);
  bool hits(const Face& f, const Vec3& o, const Vec3& u) const noexcept;
  std::uint32_t build(std::uint32_t first, std::uint32_t count, std::vector<Vec3>& centres);

  std::vector<Face> occluders_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
  std::vector<ApertureFace> apertures_;
  std::vector<double> points_;  // u, v pairs
};

// Monte Carlo sky component (percent) at one sensor from `samples` rays (≥ 1), stratified on an
// nx × ny grid of the unit square (nx·ny = samples, nx the largest divisor ≤ √samples), one jittered
// ray per cell, seeded (xoshiro256** through SplitMix64).
//
// Sampling: for a receiver facing straight up under the CIE overcast sky, the ray density is
// proportional to the sky's luminance times the cosine, p(u) ∝ (1 + 2u_z)·u_z (the cosine of
// elevation μ from 4μ³ + 3μ² = 7ξ₁ by Newton's method, the azimuth 2πξ₂), so every ray weighs
// the same (7π/9, the unobstructed illuminance) and only the visibility and the glazing vary:
// SC = 100·mean(T·V). Under the uniform sky, and for tilted receivers, the density is the cosine
// about the receiver's normal (Malley's method) and each ray weighs π·L(u) above the horizon.
// Error O(N^{-3/4}) where the visible region's boundary cuts the strata, O(N^{-1}) where it does not.
double sky_component_monte_carlo(const RayScene& rays, const Sensor& sensor, SkyModel sky, long samples,
                                 std::uint64_t seed);

// ── Adaptive cubature over the exact visible region ─────────────────────────────────────────

struct CubatureResult {
  double sc_percent;
  long evaluations;  // integrand evaluations
};

// Sky component (percent) at one sensor: each aperture's exact visible region (engine), each loop
// cut into a signed fan of spherical triangles from its first vertex, and ∫ L(u)·T(u)·(n·u) dσ
// over each by globally adaptive cubature: a spherical triangle is the central projection of the
// flat triangle through its unit vertices, dσ = det[a, b, c]/|x|³ ds dt (signed, so a non-convex
// loop's fan still adds up), integrated with the 7-point degree-5 rule of Radon (Stroud T2:5-1);
// a triangle's error estimate is the difference between that rule on it and on its four midpoint
// children. The triangle with the largest estimate is split until the estimates sum to at most
// `relative_tolerance` times |SC| (or 4 million evaluations). The region is the exact one, so
// this measures the cubature against the closed form on the same region.
CubatureResult sky_component_cubature(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor,
                                      SkyModel sky, double relative_tolerance, VisibilityCounters& counters);

}  // namespace daylit
