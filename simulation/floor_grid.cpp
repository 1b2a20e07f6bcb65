#include "simulation/floor_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "geometry/error.hpp"
#include "geometry/honeybee_model.hpp"
#include "geometry/obj_material_map.hpp"
#include "geometry/obj_model.hpp"
#include "geometry/rad_reader.hpp"
#include "geometry/ray_crossing.hpp"

namespace daylit {

namespace {

struct Edge {
  double ax, ay, bx, by;
};

double distance_to_segment(double px, double py, const Edge& e) {
  const double dx = e.bx - e.ax, dy = e.by - e.ay;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((px - e.ax) * dx + (py - e.ay) * dy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (e.ax + t * dx), py - (e.ay + t * dy));
}

}  // namespace

std::vector<Sensor> floor_grid(const std::vector<FloorOutline>& floors, const FloorGridOptions& options) {
  if (!(options.spacing > 0) || !std::isfinite(options.spacing)) throw Error("grid spacing must be positive");
  if (!(options.wall_offset >= 0) || !std::isfinite(options.wall_offset)) throw Error("wall offset must be 0 or more");
  std::vector<Sensor> sensors;
  for (const FloorOutline& floor : floors) {
    // Directed edges of all loops; a pair traversed both ways is a seam and bounds nothing.
    std::map<std::pair<std::pair<double, double>, std::pair<double, double>>, int> directed;
    double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin, extent = 0;
    for (const auto& loop : floor.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const Vec3 &a = loop[i], &b = loop[(i + 1) % loop.size()];
        zmin = std::min(zmin, a.z);
        zmax = std::max(zmax, a.z);
        extent = std::max(extent, norm(a - loop[0]));
        if (a.x == b.x && a.y == b.y) continue;
        const auto key = std::make_pair(std::make_pair(a.x, a.y), std::make_pair(b.x, b.y));
        const auto reverse = std::make_pair(key.second, key.first);
        if (auto it = directed.find(reverse); it != directed.end() && it->second > 0)
          --it->second;
        else
          ++directed[key];
      }
    if (!(zmax - zmin <= 1e-6 * extent))
      throw Error("a floor is not horizontal (its heights span " + std::to_string(zmax - zmin) +
                  "): grids are laid on horizontal floors");
    std::vector<Edge> edges;
    for (const auto& [key, count] : directed)
      for (int c = 0; c < count; ++c) edges.push_back({key.first.first, key.first.second, key.second.first, key.second.second});
    if (edges.empty()) continue;
    const auto inside = [&](double px, double py) {
      bool in = false;  // even-odd rule, half-open in y so that a vertex is counted once
      for (const Edge& e : edges)
        if ((e.ay > py) != (e.by > py) && px < e.ax + (py - e.ay) * (e.bx - e.ax) / (e.by - e.ay)) in = !in;
      if (!in) return false;
      for (const Edge& e : edges)
        if (distance_to_segment(px, py, e) < options.wall_offset) return false;
      return true;
    };
    // The inset region lies within the edges' bounding box shrunk by the offset.
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (const Edge& e : edges) {
      x0 = std::min({x0, e.ax, e.bx});
      x1 = std::max({x1, e.ax, e.bx});
      y0 = std::min({y0, e.ay, e.by});
      y1 = std::max({y1, e.ay, e.by});
    }
    x0 += options.wall_offset, y0 += options.wall_offset, x1 -= options.wall_offset, y1 -= options.wall_offset;
    if (!(x1 > x0) || !(y1 > y0)) continue;
    const auto nx = long(std::ceil((x1 - x0) / options.spacing)), ny = long(std::ceil((y1 - y0) / options.spacing));
    if (double(nx) * double(ny) > 1e8) throw Error("a floor would hold more than 1e8 sensors: give a larger spacing");
    const double z = 0.5 * (zmin + zmax) + options.height;
    for (long j = 0; j < ny; ++j)
      for (long i = 0; i < nx; ++i) {
        const double px = x0 + (double(i) + 0.5) * options.spacing, py = y0 + (double(j) + 0.5) * options.spacing;
        if (inside(px, py)) sensors.push_back({{px, py, z}, {0, 0, 1}});
      }
  }
  return sensors;
}

namespace {

// Facing up within 1°: cos 1° = 0.99985.
bool faces_up(const std::vector<Vec3>& v) {
  const Vec3 n = newell_normal(v);
  return n.z >= 0.99985 * norm(n);
}

// An OBJ model's floors: the faces a rule of the map marks "floor": true (a group rule before a
// material rule, as for roles), else, when no rule marks any, every horizontal face facing up,
// said in a notice (OBJ faces face whichever way their vertices turn: a room drawn as a closed
// solid has its floor facing down). One grid per group (else object) name.
std::vector<std::pair<std::string, std::vector<FloorOutline>>> obj_floors(const FloorSources& sources,
                                                                         std::vector<std::string>& notices) {
  const ObjModel model = read_obj_model(sources.model, sources.obj);
  std::optional<ObjMaterialMap> map;
  if (!sources.obj_materials.empty()) map = read_obj_material_map(sources.obj_materials);
  bool marked = false;
  if (map)
    for (const auto* rules : {&map->materials, &map->groups})
      for (const auto& r : *rules) marked |= r.floor;
  std::vector<std::pair<std::string, std::vector<FloorOutline>>> named;
  for (const ObjFace& f : model.faces) {
    bool floor;
    if (marked) {
      std::vector<std::string> names = f.groups;
      if (!f.object.empty()) names.push_back(f.object);
      const ObjSurfaceRule* r = match_rule(map->groups, names);
      if (!r && !f.polygon.material.empty()) r = match_rule(map->materials, {f.polygon.material});
      floor = r && r->floor;
    } else {
      floor = faces_up(f.polygon.vertices);
    }
    if (!floor) continue;
    const std::string name = f.groups.front() != "default" ? f.groups.front() : !f.object.empty() ? f.object : f.polygon.name;
    if (named.empty() || named.back().first != name) named.push_back({name, {}});
    named.back().second.push_back({{f.polygon.vertices}});
  }
  if (named.empty())
    throw Error(sources.model + (marked ? ": no face has a rule with \"floor\": true in " + sources.obj_materials
                                        : ": no face is horizontal and faces up; mark the floors with \"floor\": true "
                                          "in --obj-materials"));
  if (!marked)
    notices.push_back(sources.model + ": no rule of an --obj-materials map marks floors (\"floor\": true): took every "
                                      "horizontal face facing up");
  return named;
}

// Whether a room's faces enclose p: the parity of the faces crossed by a ray nearly straight up,
// the majority of three rays tilted apart (one through an edge two faces share, a roof's ridge
// above a lattice point, may count both or neither).
bool encloses(const std::vector<Polygon>& room, const Vec3& p) {
  static const Vec3 rays[3] = {{1.3e-4, 0.7e-4, 1}, {-0.9e-4, 1.1e-4, 1}, {0.5e-4, -1.7e-4, 1}};
  int odd = 0;
  for (const Vec3& d : rays) odd += crossing_count(room, p, d) % 2;
  return odd >= 2;
}

}  // namespace

std::vector<SensorGrid> floor_grids(const FloorSources& sources, const FloorGridOptions& options,
                                    std::vector<std::string>& notices) {
  std::vector<std::pair<std::string, std::vector<FloorOutline>>> named;  // in the model's order
  std::map<std::string, std::vector<Polygon>> room_faces;  // an HBJSON's rooms: their closed volumes
  if (!sources.model.empty() && is_obj_path(sources.model)) {
    named = obj_floors(sources, notices);
  } else if (!sources.model.empty()) {
    const HoneybeeModel model = read_honeybee_model(sources.model);
    for (const auto& f : model.room_faces) {
      Polygon p;
      p.vertices = f.boundary;
      room_faces[f.room].push_back(std::move(p));
    }
    for (const auto& f : model.floors) {
      if (named.empty() || named.back().first != f.room) named.push_back({f.room, {}});
      named.back().second.push_back({f.loops});
    }
    if (named.empty()) throw Error(sources.model + ": no room has a face of type Floor");
  }
  if (!sources.rad_files.empty()) {
    RadContent content;
    for (const auto& f : sources.rad_files) read_rad_file(f, false, content);
    for (const auto& e : content.polygons) {
      const Polygon& p = e.polygon;
      bool floor;
      if (!sources.floor_modifiers.empty()) {
        floor = std::find(sources.floor_modifiers.begin(), sources.floor_modifiers.end(), p.material) !=
                sources.floor_modifiers.end();
      } else {
        floor = faces_up(p.vertices);
      }
      if (floor) named.push_back({p.name, {FloorOutline{{p.vertices}}}});
    }
    if (named.empty())
      throw Error("no floor polygons in the .rad files (" +
                  std::string(sources.floor_modifiers.empty() ? "none is horizontal and faces up" : "none has the given modifiers") + ")");
  }
  std::vector<SensorGrid> grids;
  long empty = 0;
  std::string first_empty;
  for (const auto& [name, floors] : named) {
    SensorGrid grid;
    grid.name = name;
    grid.sensors = floor_grid(floors, options);
    // A room's sensors at its height above the floor may stand outside it: above a roof that slopes
    // down to the eaves (an attic), where they would see the sky directly. They are left out,
    // unless the room encloses none of them (its faces do not close: said, and kept).
    if (const auto faces = room_faces.find(name); faces != room_faces.end() && !grid.sensors.empty()) {
      std::vector<Sensor> inside;
      for (const Sensor& s : grid.sensors)
        if (encloses(faces->second, s.position)) inside.push_back(s);
      const std::size_t outside = grid.sensors.size() - inside.size();
      if (inside.empty()) {
        notices.push_back("room '" + name + "': its faces enclose none of its " + std::to_string(outside) +
                          " sensors (not a closed volume?): kept them all");
      } else if (outside > 0) {
        notices.push_back("room '" + name + "': " + std::to_string(outside) + " of its " +
                          std::to_string(grid.sensors.size()) + " sensors lie outside it (above a roof lower than " +
                          "the sensors' height, as at an attic's eaves): left out");
        grid.sensors = std::move(inside);
      }
    }
    if (grid.sensors.empty()) {
      if (empty++ == 0) first_empty = name;
      continue;
    }
    // Rooms split into several Floor faces, or .rad polygons sharing a name, are one grid.
    // (grid.name, not the structured binding: C++20 lets a lambda capture one, clang 14 does not.)
    auto same = std::find_if(grids.begin(), grids.end(), [&grid](const SensorGrid& g) { return g.name == grid.name; });
    if (same != grids.end()) same->sensors.insert(same->sensors.end(), grid.sensors.begin(), grid.sensors.end());
    else grids.push_back(std::move(grid));
  }
  if (empty)
    notices.push_back(std::to_string(empty) + " floor" + (empty > 1 ? "s" : "") + " ('" + first_empty +
                      "' first) too small for a sensor at this spacing and wall offset: no grid");
  if (grids.empty()) throw Error("no floor holds a sensor at this spacing and wall offset");
  return grids;
}

}  // namespace daylit
