#pragma once
// A Monte Carlo path tracer for the daylight factor's three components (SC, ERC, IRC; DESIGN.md
// §3, §4): the honest baseline that `daylit bench reflections` measures the radiosity against, and
// an independent reference for tests. Independent of the exact path on purpose: its own ray
// casting in double precision (a BVH over triangles, Möller–Trumbore), nothing of
// geometry/visibility.*, nothing of the kernels.
//
// Physics (the radiosity's conventions):
// - Occluders are opaque planar polygons, two-sided Lambertian reflectors of diffuse reflectance ρ
//   (materials/surface_reflectance.hpp; no material: black) on both sides.
// - A ray that crosses an aperture is multiplied by its transmittance at that incidence (τ, or
//   glass's Σ c_k μ^k with μ = |cos| of incidence on the pane, unclamped, as the exact sky
//   component integrates it) and goes on. Panes in series multiply (the exact `sky_component`
//   adds them instead: README, "apertures do not occlude each other"). A pane of diffuse
//   reflectance ρ_p > 0 (Aperture::reflectance: glass, trans) is also a two-sided Lambertian
//   reflector: at each pane met the ray passes with probability T/(T + ρ_p) or reflects there,
//   each branch weighted so that both are unbiased (path_tracer.cpp, walk).
// - A ray that meets nothing sees the environment: the sky (overcast (1 + 2u_z)/3 or uniform 1)
//   for u_z > 0, the far ground of uniform luminance ρ_g·E_out/π for u_z < 0 (Radiance gensky's
//   ground glow).
// - Components, from the first segment leaving the sensor: SC, environment sky reached without a
//   surface bounce; ERC, far ground reached without a bounce, or a surface hit after crossing at
//   least one aperture; IRC, a surface hit crossing no aperture. Sky or ground reached with no
//   aperture crossed (a sensor outdoors) counts as SC or ERC too; in a closed room it cannot happen.
//   Bounce k of a component: the light that reached the sensor after exactly k surface reflections
//   (the far ground's own reflection not counted: ERC bounce 0 is the far ground seen through the
//   windows).
//
// The sun, where given, by next-event estimation alone (the environment the paths reach has no
// sun in it, so nothing is counted twice): at the sensor and at every surface vertex a direction
// uniform over the disk's cone, its shadow ray walked through the apertures to the environment,
// E_sun (n·d) T. A shadow edge is then seen with the disk's penumbra, as daylit cuts the disk.
//
// Estimator, per sensor: the first direction by stratified cosine sampling (nx × ny strata of the
// unit square, one jittered sample each, Malley's method). At every surface vertex (1 ≤ k ≤ B):
// next-event estimation towards the apertures (one aperture drawn with probability ∝ area, a point
// on it uniformly by area, the shadow ray through it to the environment, counted only if that
// aperture is the first one the ray crosses, so that every direction is one aperture's), and a
// cosine-sampled continuation; environment light that the continuation reaches through an aperture
// is combined with the NEE sample by multiple importance sampling (Veach 1997, §9.2, power
// heuristic β = 2); environment light reached crossing no aperture (an exterior surface seeing the
// sky) only the continuation can sample, with weight 1. No Russian roulette: paths stop after B
// surface reflections, so the estimate is of Σ_{k ≤ B}; the tail beyond is not estimated (it falls
// roughly as ρ_avg^k; `by_bounce` shows how fast).
//
// Self-intersection: a ray leaving a surface ignores the polygon it leaves (planar: it cannot meet
// it again) and starts offset along the normal, to the side it leaves from, by 1e-9 of the scene's
// bounding-box diagonal (kRelativeOffset in path_tracer.cpp): what that costs is that occluders
// nearer than that to a surface (gaps under 0.1 µm in a 100 m model) are seen a little displaced,
// a relative change of the same order, 1e-9, in a form factor.
//
// Standard errors: the sample standard deviation of the N per-path estimates over √N. With
// stratification the true error is smaller, so they are conservative.

#include <cstdint>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "simulation/sky_patches.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

struct PathTracerOptions {
  long samples_per_sensor = 1024;  // first directions per sensor, ≥ 1
  int max_bounces = 8;             // B ≥ 0: surface reflections a path may have
  double ground_reflectance = 0.2;  // ρ_g of the far ground, in [0, 1]
  std::uint64_t seed = 1;
  SkyModel sky = SkyModel::cie_overcast;
  // The sun: a uniform disk 0.533° across about `sun` (unit, towards it, above the horizon), of
  // direct normal irradiance `sun_normal` times the sky's unobstructed horizontal irradiance
  // E_out (0: no sun). Its light at the sensor is `sun`; reflected, it joins ERC or IRC as the
  // sky's does; the far ground's luminance is then ρ_g (E_out + sun_normal E_out sun_z)/π (sky
  // and sun, as daylit illuminance takes it).
  Vec3 sun{0, 0, 1};
  double sun_normal = 0;
};

// A Monte Carlo estimate in percent of E_out, with its standard error (same unit).
struct TracedEstimate {
  double value = 0;
  double standard_error = 0;
};

struct PathTracedSensor {
  TracedEstimate sc, erc, irc, df;  // df = sc + sun + erc + irc, its standard error from the same paths
  TracedEstimate sun;               // the sun's disk seen directly (0 without a sun)
  // Index k = 0 … B: the part reached after exactly k surface reflections (irc_by_bounce[0] = 0;
  // the sky component is bounce 0 only).
  std::vector<TracedEstimate> erc_by_bounce, irc_by_bounce;
};

// Path-traces every sensor (in parallel over sensors with oneTBB; each sensor's generator is seeded
// from options.seed and its index, so the results do not depend on the thread count). Throws
// daylit::Error for options out of range and for a scene that surface_reflectance rejects.
// Cost: O(samples · B · log(triangles)) per sensor.
std::vector<PathTracedSensor> path_trace(const Scene& scene, const std::vector<Sensor>& sensors,
                                         const PathTracerOptions& options);

// The sky's daylight coefficients per patch as a patch-based tool samples them (Radiance's
// rfluxmtx into Reinhart patches with no ambient bounce, the 2-phase method's sky part): per
// sensor, `samples` stratified cosine-distributed directions from its normal, cast by this file's
// own ray casting; each that ends at the sky above the horizon, having crossed at least one
// aperture and no occluder, adds π T / samples to the patch it falls in (T the product of the
// transmittances of the apertures crossed). An unbiased estimate of ∫_{patch ∩ visible} (n·u) T dσ,
// what add_patch_coefficients (simulation/sky_patches.hpp) computes exactly. [sensor][patch].
std::vector<std::vector<double>> sampled_patch_coefficients(const Scene& scene, const std::vector<Sensor>& sensors,
                                                            const std::vector<SkyPatch>& patches, long samples,
                                                            std::uint64_t seed);

}  // namespace daylit
