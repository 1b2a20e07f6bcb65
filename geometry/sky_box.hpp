#pragma once
// The sky and far ground seen directly, not through an aperture, as a scene for the visibility
// engine: the six inward faces of a box around the model are its apertures (open, transmittance
// 1), every opaque polygon and every aperture's pane its occluders. A direction from a point inside
// the box that meets no polygon leaves the box through exactly one face (or an edge between two),
// so the regions of the six faces are disjoint and together are every direction by which the point
// sees past the model: what a sensor outdoors, in a courtyard or on a façade sees of the sky above
// the horizon and of the far ground below it. A direction through an aperture's pane is hidden
// here: the sky seen through apertures is theirs to count, so nothing is counted twice.

#include <memory>
#include <vector>

#include "geometry/box.hpp"
#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"

namespace daylit {

// Occluders: scene.occluders, then each aperture's polygon (a pane's index is occluders +
// aperture, as the reflected components list the reflecting surfaces). Apertures: the six faces,
// at least 2·(longest side) + 1 model units (in unequal ratios along x, y, z) beyond the box of `around` (the receivers: sensors, mesh nodes)
// and every vertex of the scene, so that every receiver is well inside it.
Scene sky_box_scene(const Scene& scene, Box around);

// The box's scene and its engine (apertures independent) around every sensor of `grids`, for the
// grids that see the sky directly (SensorGrid::sees_sky_directly). The engine's regions are
// indexed by the scene's apertures, the box's faces (open: transmittance 1).
struct DirectSky {
  DirectSky(const Scene& model, const Box& around, GeometryMode mode, SubtractionOrder order);
  const Scene scene;
  const VisibilityEngine engine;
};
// nullptr where no grid sees the sky directly, so that a model seen only through its apertures
// builds nothing.
std::unique_ptr<DirectSky> direct_sky(const Scene& scene, const std::vector<SensorGrid>& grids, GeometryMode mode,
                                      SubtractionOrder order);

}  // namespace daylit
