#include "simulation/model_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "geometry/coplanar_panes.hpp"
#include "geometry/honeybee_model.hpp"
#include "geometry/obj_material_map.hpp"
#include "geometry/ray_crossing.hpp"
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

// Sensors that see the sky directly, not through an aperture: a ray from the sensor, into its
// hemisphere and above the horizon, meets no polygon (occluder or aperture). Tried first along
// n + z and n + 3z (a façade sensor in a courtyard sees the sky steeply), then along 17 fixed
// directions (the zenith; 8 azimuths at about 45° and 8 at about 10° elevation: past a balcony, a
// canopy or a deep reveal), stopping at the first that escapes. A ray may slip between two
// polygons through their shared edge (a room's corner seen at 45° from a sensor on a 0.1 m grid):
// so the fixed directions are off the round angles, and a ray counts only where a second one,
// turned by 1e-3 rad, escapes too (an opening narrower than that is not found). Tested on at
// most 4,096 sensors per grid, evenly through it (floating point: it decides which grids get the
// exact direct view, never a result). Returns {found, tested}.
std::pair<std::size_t, std::size_t> open_to_sky(const SensorGrid& grid, RayBlockers& surfaces) {
  static const std::vector<Vec3> fixed = [] {
    std::vector<Vec3> d{normalized(Vec3{0.0123, 0.0171, 1})};
    for (const double elevation : {44.3, 10.7})
      for (int k = 0; k < 8; ++k) {
        const double e = elevation * std::numbers::pi / 180, a = (k + 0.137) * std::numbers::pi / 4;
        d.push_back({std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)});
      }
    return d;
  }();
  // The ray starts a hair (1e-7 of the coordinates' size) off the sensor: a sensor lying on a
  // polygon (a table top) is not hidden by it, as in the exact engine.
  const auto escapes = [&](const Vec3& sensor, const Vec3& direction) {
    const double size = std::max({1.0, std::abs(sensor.x), std::abs(sensor.y), std::abs(sensor.z)});
    const Vec3 origin = sensor + 1e-7 * size * direction;
    const Vec3 side = normalized(std::abs(direction.z) < 0.9 ? cross(direction, Vec3{0, 0, 1}) : cross(direction, Vec3{1, 0, 0}));
    return !surfaces.blocked(origin, direction) &&
           !surfaces.blocked(origin, normalized(direction + 1e-3 * side + 1e-3 * cross(direction, side)));
  };
  const std::size_t n = grid.sensors.size(), tested = std::min<std::size_t>(n, 4096);
  std::size_t found = 0;
  for (std::size_t k = 0; k < tested; ++k) {
    const Sensor& s = grid.sensors[k * n / tested];
    std::vector<Vec3> rays{s.normal + Vec3{0, 0, 1}, s.normal + Vec3{0, 0, 3}};
    rays.insert(rays.end(), fixed.begin(), fixed.end());
    for (const Vec3& up : rays) {
      if (dot(up, s.normal) <= 1e-3 * norm(up) * norm(s.normal) || up.z <= 1e-3 * norm(up)) continue;  // below its or the sky's horizon
      if (escapes(s.position, normalized(up))) {
        ++found;
        break;
      }
    }
  }
  return {found, tested};
}

// The first occluder that lies in an aperture's plane (normals parallel within 1e-9, every
// aperture vertex within 1e-6 of the aperture's extent of the occluder's plane) and holds the
// aperture's vertex mean inside it (even-odd, so a hole cut by seams does not count): a wall drawn
// whole with the window on it, which hides the window from every sensor. nullptr if none.
const Polygon* covering_occluder(const Scene& scene, const Aperture& aperture) {
  const auto& av = aperture.polygon.vertices;
  const Vec3 na = newell_normal(av);
  if (norm(na) == 0) return nullptr;
  const Vec3 u = normalized(na);
  Vec3 lo = av[0], hi = av[0], mean{};
  for (const Vec3& v : av) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
    mean += v;
  }
  mean = (1.0 / double(av.size())) * mean;
  const double tolerance = 1e-6 * norm(hi - lo);
  // The plane's coordinates: drop the normal's largest component.
  const int drop = std::abs(u.x) >= std::abs(u.y) && std::abs(u.x) >= std::abs(u.z) ? 0 : std::abs(u.y) >= std::abs(u.z) ? 1 : 2;
  const auto coordinates = [drop](const Vec3& v) {
    return drop == 0 ? std::pair{v.y, v.z} : drop == 1 ? std::pair{v.z, v.x} : std::pair{v.x, v.y};
  };
  for (const Polygon& o : scene.occluders) {
    const auto& ov = o.vertices;
    if (std::abs(dot(u, ov[0] - av[0])) > tolerance) continue;  // not in the aperture's plane: O(1) for most
    const Vec3 no = newell_normal(ov);
    if (norm(no) == 0 || std::abs(dot(normalized(no), u)) < 1 - 1e-9) continue;
    const Vec3 n = normalized(no);
    if (std::any_of(av.begin(), av.end(), [&](const Vec3& v) { return std::abs(dot(n, v - ov[0])) > tolerance; })) continue;
    const auto [px, py] = coordinates(mean);
    bool inside = false;
    for (std::size_t i = 0, j = ov.size() - 1; i < ov.size(); j = i++) {
      const auto [xi, yi] = coordinates(ov[i]);
      const auto [xj, yj] = coordinates(ov[j]);
      if ((yi > py) != (yj > py) && px < xi + (py - yi) * (xj - xi) / (yj - yi)) inside = !inside;
    }
    if (inside) return &o;
  }
  return nullptr;
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
  for (const auto& f : files.grid_files) in.grids.push_back(read_sensor_grid(f));
  if (in.grids.empty())
    throw Error(files.model.empty() ? "no sensor grids: give --grid (or --model with sensor grids)"
                : obj ? files.model + ": an OBJ model carries no sensor grids: give --grid (daylit grid --model " +
                            files.model + " lays them on its floors)"
                      : files.model + ": the model has no sensor grids: give --grid");
  std::size_t covered = 0;
  std::string first_covered;
  for (const Aperture& a : in.scene.apertures)
    if (const Polygon* wall = covering_occluder(in.scene, a); wall && covered++ == 0)
      first_covered = a.polygon.where.str() + ": aperture '" + a.polygon.name + "' lies in the plane of occluder '" +
                      wall->name + "' (" + wall->where.str() + ") and inside it";
  if (covered)
    in.scene.notices.push_back(first_covered + (covered > 1 ? " (and " + std::to_string(covered - 1) + " more apertures in walls alike)" : "") +
                               ": the occluder hides it from every sensor, so no sky comes through. Cut the window's "
                               "outline out of the wall (Radiance's seams), or leave the wall out there");
  if (in.scene.apertures.size() > 1) {
    std::vector<Polygon> panes;
    for (const Aperture& a : in.scene.apertures) panes.push_back(a.polygon);
    if (const auto overlaps = coplanar_overlaps(panes); !overlaps.empty()) {
      // A pane that lies all but a thousandth of its area inside an earlier one in its plane is
      // that pane drawn again: it reflects nothing, the earlier one reflecting for both (the part
      // outside, at most 1e-3 of its area, is left out of the reflected components).
      std::size_t silenced = 0, doubled = 0;
      double outside = 0;
      for (const CoplanarOverlap& o : overlaps) {
        Aperture& later = in.scene.apertures[o.later];
        if (!(later.reflectance > 0)) continue;
        if (o.later_share >= 1 - 1e-3) {
          later.reflectance = 0;
          ++silenced;
          outside = std::max(outside, 1 - o.later_share);
        } else {
          ++doubled;
        }
      }
      const Polygon& first = panes[overlaps[0].earlier];
      const Polygon& second = panes[overlaps[0].later];
      std::string notice = second.where.str() + ": pane '" + second.name + "' and pane '" + first.name + "' (" +
                           first.where.str() + ") lie in one plane and overlap" +
                           (overlaps.size() > 1 ? " (and " + std::to_string(overlaps.size() - 1) + " more pairs alike)" : "") +
                           ": a ray crosses both at one point, so where they overlap the light passes one pane, the first "
                           "listed, as in Radiance (whose ray meets the second at zero distance and passes it); a "
                           "double-sided shade drawn twice?";
      if (silenced > 0) {
        char share[32];
        std::snprintf(share, sizeof share, "%.2g", 100 * outside);
        notice += " In the reflected components " + std::to_string(silenced) +
                  (silenced == 1 ? " such pane lies within the first and reflects nothing"
                                 : " such panes lie within the first of their pair and reflect nothing") +
                  ", the first reflecting for both" +
                  (outside > 0 ? std::string(" (at most ") + share +
                                     " % of a pane's area lies outside the first: that part's reflection is left out)."
                               : std::string("."));
      }
      if (doubled > 0)
        notice += " In the reflected components the overlap of " + std::to_string(doubled) +
                  (doubled == 1 ? " pair" : " pairs") + " that overlap only in part reflects twice.";
      in.scene.notices.push_back(std::move(notice));
    }
  }
  std::vector<Polygon> surfaces = in.scene.occluders;
  for (const Aperture& a : in.scene.apertures) surfaces.push_back(a.polygon);
  RayBlockers blockers(surfaces);
  for (auto& grid : in.grids) {
    const auto [open, tested] = open_to_sky(grid, blockers);
    grid.sees_sky_directly = open > 0;
    if (open > 0)
      in.scene.notices.push_back(
          grid.path + ": " + std::to_string(open) + " of " +
          (tested == grid.sensors.size() ? "the " + std::to_string(tested) : std::to_string(tested) + " tested (of " + std::to_string(grid.sensors.size()) + ")") +
          " sensors of grid '" + grid.name + "' see the sky directly, not through an aperture (a ray from each into "
          "the sky meets no surface): outdoors, on a facade or in a model open to the sky. For this grid the sky "
          "and far ground seen past every surface are counted, exactly, besides what comes through the apertures "
          "(it costs a visibility query per face of a box around the model, per sensor).");
  }
  // Without an aperture open to the sky only a grid that sees the sky directly gets any (a street
  // of buildings without windows, for the sky seen on façades and the ground).
  const bool any_open = std::any_of(in.grids.begin(), in.grids.end(), [](const SensorGrid& g) { return g.sees_sky_directly; });
  if (in.scene.apertures.size() == in.scene.interior_apertures && !any_open)
    throw Error("no apertures open to the sky" +
                (in.scene.interior_apertures ? " (" + std::to_string(in.scene.interior_apertures) + " interior windows between rooms)"
                                             : std::string()) +
                ": give sky openings with --apertures, glass polygons in the scene, or a --model with apertures");
  for (const auto& grid : in.grids)
    if (!grid.sees_sky_directly && faces_no_aperture(grid, in.scene))
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
