#pragma once
// What `daylit df` and `daylit illuminance` both read: the scene, its apertures, the sensor grids,
// and optionally the site and the context buildings placed around the model (the summary sections
// that describe them are report/model_reports.hpp).

#include <optional>
#include <string>
#include <vector>

#include "geometry/obj_model.hpp"
#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "sky/context_buildings.hpp"
#include "sky/site.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

struct ModelFiles {
  std::vector<std::string> scene_files, aperture_files, grid_files;
  // An HBJSON file or a Honeybee Radiance folder (geometry/honeybee_model.hpp): its scene, its
  // apertures and, unless grid_files are given, its sensor grids; or a Wavefront OBJ model (a path
  // ending in .obj: geometry/obj_model.hpp), read with `obj` and the map `obj_materials` (optional:
  // geometry/obj_material_map.hpp), which has no grids. The .rad files are added to it.
  std::string model;
  ObjOptions obj;
  std::string obj_materials;
  std::string site, context;
  double context_min_angle_deg = kDefaultContextMinAngularSizeDeg;
  std::optional<double> bsdf_transmittance;  // for BSDF apertures (materials/scene_materials.hpp)
};

struct ModelInputs {
  Scene scene;
  std::vector<SensorGrid> grids;
  std::optional<Site> site;
  std::optional<ContextPlacement> context;
};

// Reads everything and places the context buildings (their bound on what leaving some out changes
// is stated for `sky`; with a `sun`, every building that may shade its disk is kept). Throws
// daylit::Error naming the file and line of bad input.
ModelInputs load_model(const ModelFiles& files, SkyModel sky, const std::optional<SunBeam>& sun = std::nullopt);

}  // namespace daylit
