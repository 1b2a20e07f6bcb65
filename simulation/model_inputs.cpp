#include "simulation/model_inputs.hpp"

#include "materials/scene_materials.hpp"
#include "geometry/error.hpp"

namespace daylit {

ModelInputs load_model(const ModelFiles& files, SkyModel sky, const std::optional<SunBeam>& sun) {
  if (!files.context.empty() && files.site.empty())
    throw Error("--context needs --site: the site places the footprints' longitudes and latitudes in the model");
  ModelInputs in;
  in.scene = load_scene(files.scene_files, files.aperture_files, SceneOptions{files.bsdf_transmittance});
  if (in.scene.apertures.empty())
    throw Error("no apertures: give sky openings with --apertures, or glass polygons in the scene");
  for (const auto& f : files.grid_files) in.grids.push_back(read_sensor_grid(f));
  if (!files.site.empty()) {
    in.site = read_site_file(files.site);
    in.scene.notices.push_back("site " + files.site + ": " + in.site->description());
  }
  if (!files.context.empty()) {
    const ContextBuildings buildings = read_context_buildings(files.context, *in.site);
    in.scene.notices.insert(in.scene.notices.end(), buildings.notices.begin(), buildings.notices.end());
    in.context = place_context_buildings(buildings, in.grids, sky, files.context_min_angle_deg, in.scene, sun);
    in.scene.notices.insert(in.scene.notices.end(), in.context->notices.begin(), in.context->notices.end());
  }
  return in;
}

}  // namespace daylit
