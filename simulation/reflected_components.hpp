#pragma once
// The externally and internally reflected components of the daylight factor (DESIGN.md §4): a
// radiosity solution over every reflecting polygon of the scene, first lit by the sky and the far
// ground exactly, then evaluated at the sensors.
//
// Per unit zenith luminance, as the sky component (sky_component.hpp); DF = 100·E/E_out.
//   First bounce at a receiver (x, n): (a) through each aperture the sky above the horizon and the
//   far ground below it (uniform luminance ρ_g·E_out/π, as gensky's ground glow), times the
//   aperture's transmittance; (b) the sky and far ground seen directly, through the six inward
//   faces of a box around the model, past every opaque and aperture polygon.
//   Transport: the irradiance from every element of every other reflecting surface P, over the
//   exactly visible part of P (element_transport.hpp). Visibility between surfaces uses engines
//   built once whose apertures are the reflecting surfaces, queried as luminaires
//   (VisibilityOptions::occluders_beyond = false: what lies past P's plane cannot hide it, and what
//   crosses it is clipped to the receiver's side exactly, inside the engine) with P itself
//   excluded (DESIGN.md §1). Two occluder sets besides the opaque polygons:
//   the aperture polygons ("inside": seen without crossing an aperture; IRC at sensors) and,
//   per group of apertures of equal transmittance, without that group's polygons ("through"); the
//   difference is what is seen through those apertures (ERC at sensors), weighted by their
//   transmittance (glass: T(μ) at the direction of the element's centroid, whose spread over the
//   element's vertices is counted in the error estimate).
//   Solve: M = ρ (E₀ + K M) by Gauss–Seidel to roundoff.
//   Error: the residual r = M_h − ρ(E₀ + K M_h) at check points other than the nodes (the
//   centroid and three points near the vertices of every element side), its mean |r| per element
//   side (a sensor integrates the exitance's error over each element), carried to the elements
//   by ē = |r̄| + ρ|K| ē (the discrete form of ‖r‖/(1 − ρ_max), element by element) and to each
//   sensor by the magnitudes of its coefficients: an estimate, not a rigorous bound (the
//   residual is sampled, not maximised). Elements whose estimated contribution is largest are
//   split until every sensor's estimate is within the tolerance or the refinement cap is met.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <string>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "simulation/radiosity_mesh.hpp"
#include "simulation/sky_component.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

struct ReflectionOptions {
  SkyModel sky = SkyModel::cie_overcast;
  GeometryMode mode = GeometryMode::exact;
  double ground_reflectance = 0.2;   // ρ_g of the far ground, in [0, 1)
  double tolerance_percent = 0.01;   // target of every sensor's error estimate, DF points
  double element_size = 1.0;         // longest element edge near the sensors and apertures (model units)
  double grading = 0.5;              // farther away: edge ≤ grading × distance to them
  int max_refinements = 3;           // rounds of splitting after the first solution
};

// The reflectance of every occluder (Scene::occluders order) from its material
// (materials/surface_reflectance.hpp is the caller's: simulation/ takes the numbers).
struct SensorReflections {
  std::vector<double> erc_percent, irc_percent, error_percent;
};

struct ReflectionResult {
  std::vector<SensorReflections> grids;  // in the order given
  bool black = false;                    // nothing reflects: no radiosity work at all
  std::size_t elements = 0, unknowns = 0;
  int max_level = 0, refinements = 0;
  int sweeps = 0;
  double solver_change = 0;
  double residual_max = 0;       // max |r| at the check points, exitance per unit zenith luminance
  double reflectance_max = 0;
  double max_error_percent = 0;  // over the sensors
  std::size_t receivers_direct_empty = 0, receivers_direct = 0;
  // Energy balance of the whole model (per unit zenith luminance, model units² × irradiance):
  // what the sky and far ground put on the surfaces (first bounce, integrated over every element
  // side by the nodes' degree-2 rule) = what they absorb + what leaves them for the sky and the
  // far ground. The last is integrated independently: the exitance that leaves each element side
  // minus what other elements receive from it, through the transport of the receivers' nodes.
  double flux_first_bounce = 0, flux_absorbed = 0, flux_escaping = 0, balance_mismatch = 0;
  std::vector<double> error_by_round;  // max sensor estimate after each solution
  VisibilityCounters counters;
};

// The discrete system of a scene at its first mesh, for tests and audits: the mesh, and per
// unknown (6 per element: side 0 along the element's normal, then side 1, three nodes each) the
// first bounce E₀ at its node, its surface's reflectance and its row of K.
struct RadiositySystem {
  RadiosityMesh mesh;
  std::vector<double> first_bounce, reflectance;
  std::vector<std::vector<std::pair<std::uint32_t, double>>> rows;
};
RadiositySystem radiosity_system(const Scene& scene, const std::vector<double>& reflectance,
                                 const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                 const ReflectionOptions& options);

// `reflectance`: per Scene::occluders entry, in [0, 1). `engine`: the sky component's (apertures
// = scene apertures, occluders = opaque polygons). Throws daylit::Error for a reflectance outside
// [0, 1) or a ground reflectance outside [0, 1).
ReflectionResult reflected_components(const Scene& scene, const std::vector<double>& reflectance,
                                      const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                      const ReflectionOptions& options, const ProgressCallback& progress = {});

}  // namespace daylit
