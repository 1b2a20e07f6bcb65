#pragma once
// The externally and internally reflected components of the daylight factor (DESIGN.md §4): a
// radiosity solution over every reflecting polygon of the scene and every aperture's pane that
// reflects (Aperture::reflectance: glass, trans; a surface on both sides that also lets light
// through), first lit by the sky and the far ground exactly, then evaluated at the sensors.
//
// Per unit zenith luminance, as the sky component (sky_component.hpp); DF = 100·E/E_out.
//   First bounce at a receiver (x, n): (a) through each aperture the sky above the horizon and the
//   far ground below it (uniform luminance ρ_g·E_out/π, as gensky's ground glow), times the
//   aperture's transmittance; (b) the sky and far ground seen directly, through the six inward
//   faces of a box around the model, past every opaque and aperture polygon. The sun, where set
//   (ReflectionOptions::sun), integrated over each element instead (sunlit_elements.hpp).
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
//   Reciprocity (the default, reciprocal_transport): the collocated K replaced by the nearest K'
//   whose exchanges w_u K'_uj are symmetric and whose rows keep every node's emission accounted
//   for (reciprocal_transport.hpp), so that the discrete system conserves energy exactly on every
//   mesh. Against path-traced references it is as close as the collocated rows (the office
//   sample's mean IRC −0.12 % against −0.22 %, its room alone −0.21 % against −0.08 %, the room
//   sample within 0.03 % of them; README, 2026-12-03). Without it the collocated rows' energy
//   mismatch is reported (their reciprocity defect, O(h²)).
//   Solve: M = ρ (E₀ + K' M) by Gauss–Seidel to roundoff.
//   Error: the first round solves two meshes, a coarse one (elements twice the asked size) and
//   its uniform split, and reports the finer solution; every sensor's estimate is the difference
//   of the two (ERC and IRC each, per coarse element: |what it gives − what its children give|)
//   plus, through glass, the spread of T(μ) over each element's directions times what the element
//   gives. That is the finer solution's error where halving the elements at least halves the
//   error (first order; linear elements converge at second order where the exitance is smooth,
//   measured 2.6 on a window room, so the actual error is then about a sixth of the estimate): an
//   estimate, not a rigorous bound. While a sensor's estimate exceeds the tolerance and rounds
//   remain, the mesh is refined locally: the sensors over it flag the elements whose split lowers
//   their estimate most (local_refinement in the .cpp), the finer mesh becomes the coarse one and only the
//   flagged elements are split; the others keep their terms in the estimate, and the new rows
//   keep every entry of the elements not split (a round costs about the new elements' rows, the
//   refined surfaces' visibility from the old nodes, and the sensors).
//   Left out exactly: surface sides from which no light can reach a sensor (find_live_sides).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "simulation/radiosity_mesh.hpp"
#include "simulation/reciprocal_transport.hpp"
#include "simulation/sky_component.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

struct ReflectionOptions {
  SkyModel sky = SkyModel::cie_overcast;
  // Another sky (and the sun) for the first bounce, where set (daylit illuminance): the
  // irradiance on a receiver with normal n from the directions `above` (above the horizon) seen
  // through `aperture` (nullptr: directly), in the units of light_horizontal, the unobstructed
  // horizontal irradiance, which also sets the far ground's luminance ρ_g·light_horizontal/π
  // and the unit of the results (percent of it, as DF is of E_out). Unset: `sky`, per unit
  // zenith luminance.
  std::function<double(const SphericalRegion& above, const Vec3& n, const Aperture* aperture)> light;
  double light_horizontal = 0;
  // The sun, where set along with `light` (which then leaves it out): its first bounce integrated
  // over each element (sunlit_elements.hpp), not read at the nodes, whose samples of a sun patch
  // narrower than the elements can be far off. Its direction (unit, towards it) and its direct
  // normal irradiance in light_horizontal's units.
  struct Sun {
    Vec3 direction{0, 0, 1};
    double direct_normal = 0;
  };
  std::optional<Sun> sun;
  GeometryMode mode = GeometryMode::exact;
  double ground_reflectance = 0.2;   // ρ_g of the far ground, in [0, 1)
  double tolerance_percent = 0.05;   // target of every sensor's error estimate, DF points
  // Longest element edge near the sensors and apertures (model units); 0: automatic_element_size.
  double element_size = 0;
  double grading = 0.5;              // farther away: edge ≤ grading × distance to them
  // Further rounds while some sensor's estimate exceeds the tolerance, each splitting only the
  // elements those sensors flag (local refinement; see the top of this file). The command line's
  // default is 2; here 0, the uniform first mesh that reflection_operator also uses.
  int max_refinements = 0;
  // A local round takes each sensor's transport of the elements not split from the round before
  // where all sensors' together fit in this many bytes (40 per element side a sensor sees: about
  // 0.5 GB on the office sample's 2,400 sensors), else finds it again (same result to roundoff).
  std::size_t sensor_cache_bytes = std::size_t(1) << 30;
  // true: the collocated rows made reciprocal and closed (reciprocal_transport.hpp), conserving
  // energy to roundoff on every mesh; false: the rows as collocated at the nodes, whose energy
  // balance is off by the mesh's reciprocity defect (reported).
  bool reciprocal_transport = true;
  // The memory the rows of K may take, in bytes (0: no limit). A mesh's rows are estimated from
  // the coarser mesh's before they are found (their entries grow with the square of the number of
  // elements: rows_bytes_estimate): a refinement round that would need more is not started (the
  // run stops refining and says so, ReflectionResult::stopped); a first mesh that would, is refused
  // with an error that names the sizes, instead of a machine that runs out of memory.
  std::size_t memory_bytes = 0;
  // Called now and then with a stage's name ("radiosity: the mesh's rows", …), what it counts
  // ("element sides", "sensors"), how many are done and their number, from one thread at a time:
  // for a progress bar over the whole run.
  std::function<void(const std::string& stage, const std::string& unit, std::size_t done, std::size_t total)>
      on_progress;
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
  double over_relaxation = 1;  // of the sweeps (radiosity_solver.hpp): above 1 with the reciprocal transport
  double solver_change = 0;
  double reflectance_max = 0;
  double max_error_percent = 0;  // over the sensors
  std::size_t receivers_direct_empty = 0, receivers_direct = 0;
  // Of the empty ones, those a closed surface of the model encloses (geometry/closed_shells.hpp).
  std::size_t receivers_direct_enclosed = 0;
  // Surface sides (two per reflecting surface) solved, and left out because no light from them
  // can reach a sensor, directly or by reflection (the outside of a room's walls).
  std::size_t sides_solved = 0, sides_left_out = 0;
  // Energy balance of the whole model (per unit zenith luminance, model units² × irradiance):
  // what the sky and far ground put on the surfaces (first bounce, integrated over every element
  // side by the nodes' degree-2 rule) = what they absorb + what leaves them for the sky and the
  // far ground. The last is integrated independently: the exitance that leaves each element side
  // minus what other elements receive from it, through the transport of the receivers' nodes.
  double flux_first_bounce = 0, flux_absorbed = 0, flux_escaping = 0, balance_mismatch = 0;
  ReciprocityReport reciprocity;       // of the reported mesh's transport (zeros where not made reciprocal)
  std::vector<double> error_by_round;  // max sensor estimate after each round
  // Why refining stopped before the tolerance was met, where that was memory
  // (ReflectionOptions::memory_bytes); empty otherwise.
  std::string stopped;
  // Where the run's wall time went, stage by stage in order ("mesh and visibility engines",
  // "coarse mesh: rows", …, "round 0: sensors"), for the summary.
  struct StageTime {
    std::string stage;
    double wall_s = 0;
  };
  std::vector<StageTime> stages;
  double element_size = 0;             // as used (the asked one, or the automatic one)
  VisibilityCounters counters;
};

// A fifth of a grid's extent, the median over the grids. A grid's extent: the longest side of the
// box around its sensors (a room's grid spans the room: elements a fifth of the room, in the
// model's own units; measured on the 4 × 5 × 3 m room sample, its IRC within 0.2 % of a mesh with
// four times the elements), but no less than half the room's span around them (the longest of
// its length, width and height through a sensor, the median over the sensors), so that a grid
// of a few sensors close together does not mesh the whole model at a fraction of their spacing
// (two sensors 0.5 m apart in the room sample gave 0.1 m elements: 7,956 of them and 30 s,
// against 876 and 2 s for its 80-sensor grid, for IRC the same to 0.2 %). No grid with an
// extent: a fifth of the box around the apertures and the sensors.
double automatic_element_size(const Scene& scene, const std::vector<const SensorGrid*>& grids);

// The peak bytes of a round's rows of K: kRowBytesPerEntry per entry of its rows (16 for the
// entry, each row allocated at its size; 12 for the reciprocity's symmetric values and columns)
// plus kKeptBytesPerEntry per entry of the round before's, kept beside the new rows while they
// are found (K' and K's collocated values). `entries`: the earlier mesh's count over `elements`
// elements; the new mesh has `next_elements`, each row seeing that many times more elements, and
// that many times more rows.
inline constexpr double kRowBytesPerEntry = 28, kKeptBytesPerEntry = 24;
double rows_bytes_estimate(double entries, double elements, double next_elements, bool earlier_kept);

// The discrete system of a scene at its first mesh (elements of the asked size, both sides of
// every surface, whether or not light from them reaches a sensor), for tests and audits: the mesh, and per
// unknown (6 per element: side 0 along the element's normal, then side 1, three nodes each) the
// first bounce E₀ at its node, its surface's reflectance, its row of K as collocated and as solved
// (made reciprocal, with options.reciprocal_transport; every unknown of weight area/3).
struct RadiositySystem {
  RadiosityMesh mesh;
  std::vector<double> first_bounce, reflectance;
  std::vector<TransportRow> collocated_rows, rows;
  ReciprocityReport reciprocity;
};
RadiositySystem radiosity_system(const Scene& scene, const std::vector<double>& reflectance,
                                 const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                 const ReflectionOptions& options);

// The reflected components as a linear map of the light, for runs whose light changes (annual
// runs, DESIGN.md §5: "the reflected part linear in the sky"). The first bounce at every node of
// the mesh is a sum over the node's views (the sky and far ground through each aperture, and
// seen directly past every polygon); the solution and the sensors' transport are linear in it, so
// ERC + IRC at sensor s is Σ_k W_sk E0_k with W = S (I − ρK)⁻¹ diag(ρ) (S: the sensors' rows of
// transport, through apertures weighted by the transmittance as in reflected_components). W is
// found once by a dense LU factorisation of (I − ρK)ᵀ (partial pivoting; I − ρK is strictly
// diagonally dominant by columns where ρ Σ_i K_ij < 1, so it is well conditioned), and a caller
// then forms E0 for any light.
struct LightView {
  std::int32_t aperture = -1;  // the aperture it is seen through (Scene::apertures); −1: directly
  // Where panes lie in front of that aperture: their combined transmittance with its
  // (pane_transmittance.hpp), to be used instead of the aperture's; null otherwise.
  std::shared_ptr<const Aperture> through{};
  std::vector<std::uint32_t> panes{};  // the panes in front (for the sun: transmittance_along)
  double sign = 1;                     // −1: a count taken back (PaneView), to be subtracted
  const Aperture* transmitting(const Scene& scene) const {
    return through ? through.get() : aperture >= 0 ? &scene.apertures[std::size_t(aperture)] : nullptr;
  }
  SphericalRegion above;       // the directions seen above the horizon (the sky)
  double ground = 0;           // ∫ T (n·u) dσ over what is seen below the horizon (the far ground)
};
struct ReflectionNode {
  Vec3 position, normal;
  std::vector<LightView> views;
};
struct ReflectionOperator {
  std::vector<ReflectionNode> nodes;  // the live nodes of the mesh (both sides of an element: two)
  // Per grid, [sensor × node] row-major: ERC + IRC at the sensor per unit first-bounce irradiance
  // at the node.
  std::vector<std::vector<double>> response;
  // Per grid, [sensor × aperture]: ∫ T (n·u) dσ over the far ground seen through each aperture
  // (the part of ERC that comes straight from the far ground, not by way of a node).
  std::vector<std::vector<double>> sensor_ground;
  // Per grid, per sensor: the same over the far ground seen directly, past every surface (a grid
  // that sees the sky directly, SensorGrid::sees_sky_directly; else 0): light from outdoors.
  std::vector<std::vector<double>> sensor_ground_direct;
  // Per grid, per sensor: whether it sees anything directly, sky or far ground (1) — the same test
  // as df's (Transport::direct): such a sensor is outdoors, and takes light from outdoors as it
  // comes, through no window and no blinds.
  std::vector<std::vector<char>> sensor_outdoors;
  // Per grid: the index of its first row in the whole grid (SensorGrid::first: an MPI rank's
  // block starts there), which products whose rows must not depend on the block key on.
  std::vector<std::size_t> response_first;
  // Per live element side, whose nodes are nodes[3i], nodes[3i + 1] and nodes[3i + 2] (normal:
  // theirs): its triangle and the polygon it lies on (Scene::occluders, then the apertures' panes),
  // over which the sun's first bounce is integrated (sunlit_elements.hpp); and the model's size.
  std::vector<RadiosityElement> sides;
  std::vector<std::size_t> side_polygon;
  double scale = 1;
  std::size_t elements = 0;
  double element_size = 0;           // as used
  std::size_t sides_solved = 0, sides_left_out = 0;
  ReciprocityReport reciprocity;
  VisibilityCounters counters;
  std::vector<ReflectionResult::StageTime> stages;  // where the time went, in order
};
// The mesh is reflected_components' reported one (the uniform split of a mesh of elements twice
// the asked size), or with `coarse` that mesh of twice the size itself, for the same error
// estimate. Throws daylit::Error as reflected_components, and for a mesh of more than `max_nodes`
// live nodes (the LU is dense: memory 8 n² bytes, time ~n³/3 operations).
// `grids` set the mesh (its automatic element size, the surface sides light can reach a sensor
// from); `response_grids` (as many, default `grids`) are the sensors whose rows of W and far
// ground are found: a part of each grid (an MPI rank's block of its sensors) gives those rows of
// the whole grid's, bit for bit, since each sensor's transport is its own and W's rows are
// solved column by column.
inline constexpr std::size_t kReflectionMaxNodes = 16000;
ReflectionOperator reflection_operator(const Scene& scene, const std::vector<double>& reflectance,
                                       const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                       const ReflectionOptions& options, bool coarse = false,
                                       std::size_t max_nodes = kReflectionMaxNodes,
                                       const std::vector<const SensorGrid*>* response_grids = nullptr);

// `reflectance`: per Scene::occluders entry, in [0, 1). `engine`: the sky component's (apertures
// = scene apertures, occluders = opaque polygons). Throws daylit::Error for a reflectance outside
// [0, 1), a ground reflectance outside [0, 1) or an element size that is not positive.
ReflectionResult reflected_components(const Scene& scene, const std::vector<double>& reflectance,
                                      const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                      const ReflectionOptions& options);

}  // namespace daylit
