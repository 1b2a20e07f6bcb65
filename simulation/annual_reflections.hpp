#pragma once
// The reflected part of annual illuminance (issue 14: annual results use the whole illuminance;
// DESIGN.md §5, "the reflected part linear in the sky"): ERC + IRC at every sensor and hour
// through the reflection operator W (sensor × node) of reflected_components.hpp.
//
// The first bounce at a node is linear in the hour's light: the sky luminance L(u) over each of its
// views' above-horizon regions (times T(u) and n·u), the far ground's ρ_g E_h/π over their parts
// below the horizon, and the sun's disk. Per node, once:
//   sky:    L replaced by its bilinear interpolant on a fixed grid of directions (altitude ×
//           azimuth in the model frame, DirectionGrid), so ∫ L T (n·u) dσ ≈ Σ_b q_b L(d_b) with
//           q_b = ∫ φ_b T (n·u) dσ, φ_b the grid's hat functions, integrated by a product Gauss
//           rule on the view's fan triangles, each cut until no side spans more than
//           kReflectionTriangleDeg (fan_product_rule.hpp);
//   sun:    per hour and element side, not per node: the light of its parallel beam (the disk as
//           a point) past every polygon, each pane's T along it, projected onto the element's
//           linear functions (sunlit_elements.hpp), so that a patch narrower than the elements
//           keeps its flux;
//   ground: the view's far-ground integral, exact (LightView::ground).
// Per sensor then D = W Q (Q: node × column), split by the window group through which the light
// entered the room (a node's view through an aperture: that aperture's group; nodes lit directly,
// outdoors: one more channel), so that the blinds can act on what each group lets in. Per hour
// R = D f_h + W E0_sun, f_h the hour's luminance at the grid's directions and the far ground's:
// products of matrices over blocks of hours.
//
// Error estimate per sensor and hour (not a bound): the same on the grid of half the resolution
// (every other line) and with the operator of a mesh twice as coarse (reflected_components'
// estimate), the absolute differences from the fine result added. Both discretisations converge
// at second order where the light is smooth, so the fine result's error is then about a quarter of
// each difference.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "geometry/scene.hpp"
#include "simulation/annual.hpp"
#include "simulation/reflected_components.hpp"

namespace daylit {

inline constexpr int kReflectionGridRows = 36;     // altitude steps of 2.5°, horizon to zenith
inline constexpr int kReflectionGridColumns = 72;  // azimuth steps of 5°
inline constexpr double kReflectionTriangleDeg = 10;
inline constexpr int kReflectionRuleOrder = 6;     // Gauss points per direction on each fan triangle

// Directions at altitude i·90°/rows (i = 0..rows) and azimuth j·360°/columns from +x towards +y
// (j = 0..columns − 1); the top row is the zenith for every j.
struct DirectionGrid {
  int rows = kReflectionGridRows, columns = kReflectionGridColumns;
  std::size_t vertices() const noexcept { return std::size_t(rows + 1) * std::size_t(columns); }
  std::size_t vertex(int i, int j) const noexcept {
    return std::size_t(i) * std::size_t(columns) + std::size_t(((j % columns) + columns) % columns);
  }
  Vec3 direction(std::size_t vertex) const noexcept;
  // The four vertices of the cell holding the direction at altitude ∈ [0, π/2] and azimuth ∈
  // [0, 2π) (radians) and their bilinear weights in (altitude, azimuth), summing to 1.
  void interpolation_at(double altitude, double azimuth, std::size_t vertex_out[4], double weight_out[4]) const noexcept;
};

// Every sensor's reflected illuminance per hour, blinds open, per channel.
struct ReflectedHours {
  std::size_t sensors = 0, hours = 0, channels = 0;  // channels: window groups, then "lit outdoors"
  std::vector<float> lux;                            // [(sensor × hours + hour) × channels]
  std::vector<float> estimate;                       // [sensor × hours]: the error estimate, all channels
  std::vector<char> outdoors;                        // [sensor]: sees the sky or far ground directly
};

// The reflected hours of several grids, found together: what does not depend on the sensors (each
// node's columns of the direction grids, the skies, the sun's first bounce on the elements) once
// for all of them.
struct ReflectedGrids {
  std::vector<ReflectedHours> grids;  // in the order of the grid indices asked for
  double time_s = 0;
};

// One hour's light: the sky's luminance above the horizon (lux/sr; empty: a dark hour), the sun
// and the unobstructed horizontal illuminance that sets the far ground's luminance ρ_g E_h/π.
struct HourLight {
  std::function<double(const Vec3&)> luminance;
  Vec3 sun{0, 0, 1};
  double direct_normal_lux = 0, horizontal_lux = 0;
};

// `fine`: the operator of the asked mesh; `coarse`: of a mesh twice as coarse (nullptr: no mesh
// estimate). `grid_indices`: which of the operators' grids. `group_of_aperture`, `groups`: the
// window groups (annual_coefficients.hpp).
ReflectedGrids reflected_light(const Scene& scene, const ReflectionOperator& fine, const ReflectionOperator* coarse,
                               const std::vector<std::size_t>& grid_indices, const std::vector<int>& group_of_aperture,
                               std::size_t groups, const std::vector<HourLight>& hours, double ground_reflectance);

// The same for the hours of an annual sky: the Perez luminance (clamps included) of each hour with
// a sky, its sun and E_h = E_dh + E_dn sin(altitude).
ReflectedGrids reflected_hours(const Scene& scene, const ReflectionOperator& fine, const ReflectionOperator* coarse,
                               const std::vector<std::size_t>& grid_indices, const std::vector<int>& group_of_aperture,
                               std::size_t groups, const AnnualSky& sky, double ground_reflectance);

// The operator's grids in order, in consecutive batches whose ReflectedHours over `hours` hours
// take at most `max_bytes` together (a grid larger than that alone): each batch is one call of
// reflected_light, so that a model of many small grids (a room each) does its per-node work once
// while the memory held stays bounded.
// What the CLI lets a batch hold: a gigabyte, about the hourly arrays of 6,000 sensors with one
// window group (the grid of one large open-plan floor), beyond what one grid alone needed before.
inline constexpr std::size_t kReflectedBatchBytes = std::size_t(1) << 30;
std::vector<std::vector<std::size_t>> reflected_batches(const ReflectionOperator& op, std::size_t hours, std::size_t groups,
                                                        std::size_t max_bytes);

}  // namespace daylit
