#include "simulation/model_inputs.hpp"

#include "geometry/honeybee_model.hpp"
#include "geometry/obj_material_map.hpp"
#include "materials/obj_materials.hpp"
#include "materials/scene_materials.hpp"
#include "geometry/error.hpp"

namespace daylit {

namespace {

// True when every aperture lies wholly behind (or in) the plane of every sensor: no sky reaches
// the grid directly. Stops at the first sensor that faces an aperture, so a usual grid costs one
// sensor's pass over the apertures' vertices.
bool faces_no_aperture(const SensorGrid& grid, const Scene& scene) {
  for (const Sensor& s : grid.sensors)
    for (const Aperture& a : scene.apertures)
      for (const Vec3& v : a.polygon.vertices)
        if (dot(v - s.position, s.normal) > 0) return false;
  return true;
}

}  // namespace

ModelInputs load_model(const ModelFiles& files, SkyModel sky, const std::optional<SunBeam>& sun) {
  if (!files.context.empty() && files.site.empty())
    throw Error("--context needs --site: the site places the footprints' longitudes and latitudes in the model");
  const bool obj = !files.model.empty() && is_obj_path(files.model);
  if (!files.obj_materials.empty() && !obj)
    throw Error("--obj-materials " + files.obj_materials + " applies to an OBJ model (--model ending in .obj)");
  ModelInputs in;
  RadContent content;
  if (obj) {
    const ObjModel model = read_obj_model(files.model, files.obj);
    if (files.obj_materials.empty()) {
      content = obj_rad_content(model);
    } else {
      const ObjMaterialMap map = read_obj_material_map(files.obj_materials);
      content = obj_rad_content(model, &map);
    }
  } else if (!files.model.empty()) {
    HoneybeeModel model = read_honeybee_model(files.model);
    content = std::move(model.content);
    if (files.grid_files.empty()) in.grids = std::move(model.grids);
    else if (!model.grids.empty()) content.notices.push_back(files.model + ": its sensor grids are left out: --grid was given");
  }
  for (const auto& f : files.scene_files) read_rad_file(f, false, content);
  for (const auto& f : files.aperture_files) read_rad_file(f, true, content);
  in.scene = assemble_scene(content, SceneOptions{files.bsdf_transmittance});
  if (in.scene.apertures.empty() && obj)
    throw Error(files.model + ": no face is an aperture: give the windows' materials or groups the role aperture or "
                "glass in --obj-materials (or list their groups in its aperture_groups), or make their .mtl materials "
                "transparent (d < 1); --apertures files add openings too");
  if (in.scene.apertures.size() == in.scene.interior_apertures)
    throw Error("no apertures open to the sky" +
                (in.scene.interior_apertures ? " (" + std::to_string(in.scene.interior_apertures) + " interior windows between rooms)"
                                             : std::string()) +
                ": give sky openings with --apertures, glass polygons in the scene, or a --model with apertures");
  for (const auto& f : files.grid_files) in.grids.push_back(read_sensor_grid(f));
  if (in.grids.empty())
    throw Error(files.model.empty() ? "no sensor grids: give --grid (or --model with sensor grids)"
                : obj ? files.model + ": an OBJ model carries no sensor grids: give --grid (daylit grid --model " +
                            files.model + " lays them on its floors)"
                      : files.model + ": the model has no sensor grids: give --grid");
  for (const auto& grid : in.grids)
    if (faces_no_aperture(grid, in.scene))
      in.scene.notices.push_back(grid.path + ": every sensor of grid '" + grid.name + "' faces away from every aperture "
                                 "(each aperture lies behind each sensor's plane): its sky components are 0 (only reflected light can reach it). A grid on a "
                                 "facade facing out, or reversed directions?");
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
