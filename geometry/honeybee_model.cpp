#include "geometry/honeybee_model.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>

#include "geometry/input_checks.hpp"
#include "geometry/json_input.hpp"
#include "geometry/text_scanner.hpp"

namespace daylit {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Honeybee's default modifiers and default modifier set.
//
// Source: honeybee-radiance (AGPL-3.0), honeybee_radiance/lib/modifiers.py and modifierset.py name
// the defaults (generic_wall_0.50, ...) and which slot of the set each fills; their values are
// those honeybee-radiance serialises for its default global modifier set, as in its test asset
// tests/assets/model/sample_radiance_properties.json (commit 20544a1, 2026-08-11): the glass
// transmissivities are Radiance's transmissivities for visible transmittances 0.88 and 0.64
// (0.9584154328610596 and 0.6975761815384331), the plastics have zero specularity and roughness,
// and air_boundary is a trans of reflectance 1 transmitting everything. Only facts (identifiers
// and numbers) are taken, no code.
struct DefaultModifier {
  const char* identifier;
  const char* type;
  std::vector<double> reals;
};

const std::vector<DefaultModifier>& default_modifiers() {
  static const std::vector<DefaultModifier> kDefaults = {
      {"generic_floor_0.20", "plastic", {0.2, 0.2, 0.2, 0, 0}},
      {"generic_wall_0.50", "plastic", {0.5, 0.5, 0.5, 0, 0}},
      {"generic_ceiling_0.80", "plastic", {0.8, 0.8, 0.8, 0, 0}},
      {"generic_opaque_door_0.50", "plastic", {0.5, 0.5, 0.5, 0, 0}},
      {"generic_interior_shade_0.50", "plastic", {0.5, 0.5, 0.5, 0, 0}},
      {"generic_exterior_shade_0.35", "plastic", {0.35, 0.35, 0.35, 0, 0}},
      {"generic_context_0.20", "plastic", {0.2, 0.2, 0.2, 0, 0}},
      {"generic_interior_window_vis_0.88", "glass", {0.9584154328610596, 0.9584154328610596, 0.9584154328610596}},
      {"generic_exterior_window_vis_0.64", "glass", {0.6975761815384331, 0.6975761815384331, 0.6975761815384331}},
      {"air_boundary", "trans", {1, 1, 1, 0, 0, 1, 1}},
  };
  return kDefaults;
}

// One modifier set, resolved to modifier identifiers (Honeybee's ModifierSet: a slot left null in
// an abridged set takes the default set's modifier).
struct ModifierSet {
  std::string wall_exterior = "generic_wall_0.50", wall_interior = "generic_wall_0.50";
  std::string floor_exterior = "generic_floor_0.20", floor_interior = "generic_floor_0.20";
  std::string roof_exterior = "generic_ceiling_0.80", roof_interior = "generic_ceiling_0.80";
  std::string window = "generic_exterior_window_vis_0.64", skylight = "generic_exterior_window_vis_0.64",
              operable = "generic_exterior_window_vis_0.64", aperture_interior = "generic_interior_window_vis_0.88";
  std::string door_exterior = "generic_opaque_door_0.50", door_interior = "generic_opaque_door_0.50",
              door_overhead = "generic_opaque_door_0.50", door_exterior_glass = "generic_exterior_window_vis_0.64",
              door_interior_glass = "generic_interior_window_vis_0.88";
  std::string shade_exterior = "generic_exterior_shade_0.35", shade_interior = "generic_interior_shade_0.50";
};

const char* const kContextModifier = "generic_context_0.20";  // detached orphaned shades

// ---------------------------------------------------------------------------------------------
// JSON access with messages that name the file and the JSON path.

class Reader {
 public:
  explicit Reader(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw Error(name_ + ": " + path + ": " + problem);
  }
  SourceLocation where(const std::string& path) const { return {name_ + " " + path, 0}; }
  const std::string& name() const { return name_; }

  const json& member(const json& object, const std::string& path, const char* key) const {
    if (!object.is_object()) fail(path, "expected an object, found " + json_input::kind_of(object));
    const auto it = object.find(key);
    if (it == object.end()) fail(path, std::string("missing \"") + key + "\"");
    return *it;
  }
  // An optional member: null when absent.
  static const json& optional(const json& object, const char* key) {
    static const json kNull;
    if (!object.is_object()) return kNull;
    const auto it = object.find(key);
    return it == object.end() ? kNull : *it;
  }
  const json& array(const json& value, const std::string& path) const {
    if (!value.is_array()) fail(path, "expected an array, found " + json_input::kind_of(value));
    return value;
  }
  // An optional array member: empty when absent or null.
  const json& array_member(const json& object, const std::string& path, const char* key) const {
    static const json kEmpty = json::array();
    const json& v = optional(object, key);
    if (v.is_null()) return kEmpty;
    return array(v, path + "." + key);
  }
  std::string string(const json& value, const std::string& path) const {
    if (!value.is_string()) fail(path, "expected a string, found " + json_input::kind_of(value));
    return value.get<std::string>();
  }
  double number(const json& value, const std::string& path) const {
    if (!value.is_number()) fail(path, "expected a number, found " + json_input::kind_of(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(path, "the number is not finite");
    return x;
  }
  Vec3 point(const json& value, const std::string& path) const {
    if (!value.is_array() || value.size() != 3) fail(path, "expected a point [x, y, z]");
    Vec3 p{number(value[0], path + "[0]"), number(value[1], path + "[1]"), number(value[2], path + "[2]")};
    for (int i = 0; i < 3; ++i)
      if (!(std::abs(p[i]) <= kMaxCoordinate))
        fail(path, "coordinate beyond 1e12 in magnitude: move the model's origin nearer (or use larger units)");
    return p;
  }
  std::vector<Vec3> loop(const json& value, const std::string& path) const {
    array(value, path);
    std::vector<Vec3> v;
    for (std::size_t i = 0; i < value.size(); ++i) {
      const Vec3 p = point(value[i], path + "[" + std::to_string(i) + "]");
      if (v.empty() || !(v.back() == p)) v.push_back(p);
    }
    while (v.size() > 1 && v.front() == v.back()) v.pop_back();
    if (v.size() < 3) fail(path, "a polygon needs at least 3 distinct points");
    return v;
  }

 private:
  std::string name_;
};

std::string indexed(const std::string& path, const char* key, std::size_t i) {
  return (path.empty() ? std::string() : path + ".") + key + "[" + std::to_string(i) + "]";
}

// ---------------------------------------------------------------------------------------------
// Modifiers: HBJSON's modifier objects as Radiance materials (the reals in Radiance's order, as
// Honeybee's to_radiance writes them). Older HBJSON writes the type in lower case.

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

Material modifier_material(const Reader& r, const json& m, const std::string& path) {
  Material mat;
  mat.name = r.string(r.member(m, path, "identifier"), path + ".identifier");
  mat.where = r.where(path);
  const std::string type = lower(r.string(r.member(m, path, "type"), path + ".type"));
  const auto reals = [&](std::initializer_list<const char*> keys) {
    for (const char* k : keys) mat.reals.push_back(r.number(r.member(m, path, k), path + "." + k));
  };
  if (type == "plastic" || type == "metal") {
    mat.type = type;
    reals({"r_reflectance", "g_reflectance", "b_reflectance", "specularity", "roughness"});
  } else if (type == "glass") {
    mat.type = "glass";
    reals({"r_transmissivity", "g_transmissivity", "b_transmissivity"});
    if (const json& n = Reader::optional(m, "refraction_index"); !n.is_null())
      mat.reals.push_back(r.number(n, path + ".refraction_index"));
  } else if (type == "trans") {
    mat.type = "trans";
    reals({"r_reflectance", "g_reflectance", "b_reflectance", "specularity", "roughness", "transmitted_diff",
           "transmitted_spec"});
  } else if (type == "mirror") {
    mat.type = "mirror";
    reals({"r_reflectance", "g_reflectance", "b_reflectance"});
  } else if (type == "light") {
    mat.type = "light";
    reals({"r_emittance", "g_emittance", "b_emittance"});
  } else if (type == "glow") {
    mat.type = "glow";
    reals({"r_emittance", "g_emittance", "b_emittance", "max_radius"});
  } else if (type == "bsdf" || type == "absdf") {
    // The XML travels inside the HBJSON (bsdf_data); Honeybee's folder names it after the modifier.
    mat.type = type == "bsdf" ? "BSDF" : "aBSDF";
    mat.strings = {"0", mat.name + ".xml"};
  } else if (type == "void") {
    mat.type = "void";
  } else {
    r.fail(path + ".type", "modifier type " + printable(type) +
                               " is not read; daylit reads Plastic, Metal, Glass, Trans, Mirror, Light, Glow, BSDF, Void");
  }
  check_material(mat);  // the .rad reader's checks: counts and physical ranges
  return mat;
}

// ---------------------------------------------------------------------------------------------
// Punched polygons: a face with holes (its own and its sub-faces') as one polygon whose holes are
// cut by seams, the convention of Radiance and of the exact decomposition (convex_pieces), which
// cancels edges traversed both ways and fills by parity. Each hole is reached from the boundary's
// first vertex and left the same way. A hole vertex lying on a boundary edge (a door on the floor
// line, a window to the wall's edge) is inserted into that edge so that the shared stretch is
// traversed both ways and cancels, instead of leaving two overlapping edges.

bool on_segment(const Vec3& p, const Vec3& a, const Vec3& b, double tolerance) {
  const Vec3 ab = b - a;
  const double len2 = dot(ab, ab);
  if (!(len2 > 0)) return false;
  const double t = dot(p - a, ab) / len2;
  if (!(t > 0 && t < 1)) return false;
  return norm(p - (a + ab * t)) <= tolerance;
}

std::vector<Vec3> punched(std::vector<Vec3> boundary, std::vector<std::vector<Vec3>> holes) {
  if (holes.empty()) return boundary;
  const Vec3 n = newell_normal(boundary);
  double extent = 0;
  for (const Vec3& p : boundary) extent = std::max(extent, norm(p - boundary[0]));
  // 1e-9 of the extent: far above the rounding of coordinates written with ~15 digits, far below
  // any gap a model means.
  const double tolerance = 1e-9 * extent;
  for (auto& h : holes) {
    if (dot(newell_normal(h), n) > 0) std::reverse(h.begin(), h.end());
    std::vector<Vec3> split;
    for (std::size_t i = 0; i < boundary.size(); ++i) {
      const Vec3 a = boundary[i], b = boundary[(i + 1) % boundary.size()];
      split.push_back(a);
      std::vector<std::pair<double, Vec3>> inside;
      for (const Vec3& p : h)
        if (on_segment(p, a, b, tolerance)) inside.emplace_back(dot(p - a, b - a), p);
      std::sort(inside.begin(), inside.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (const auto& [t, p] : inside) split.push_back(p);
    }
    boundary = std::move(split);
  }
  std::vector<Vec3> v = boundary;
  for (const auto& h : holes) {
    v.push_back(boundary[0]);
    v.insert(v.end(), h.begin(), h.end());
    v.push_back(h[0]);
  }
  // The last seam returns to boundary[0] through the closing edge.
  return v;
}

// The holes of a polygon cut by seams (punched's inverse, for any bridging, as Honeybee's writer
// and ladybug-geometry make them): edges traversed both ways (the seams) cancel, and what is left
// is chained into closed loops; those turning against the whole polygon are its holes, returned
// turning as the polygon does. Coordinates are compared exactly: a seam repeats the same numbers.
// A polygon whose remaining edges do not close into loops has no holes found (none returned).
std::vector<std::vector<Vec3>> seam_holes(const std::vector<Vec3>& vertices) {
  const auto same = [](const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  struct Edge {
    Vec3 from, to;
    bool used = false;
  };
  std::vector<Edge> edges;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Vec3& a = vertices[i];
    const Vec3& b = vertices[(i + 1) % vertices.size()];
    if (!same(a, b)) edges.push_back({a, b});
  }
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size() && !edges[i].used; ++j)
      if (!edges[j].used && same(edges[i].from, edges[j].to) && same(edges[i].to, edges[j].from))
        edges[i].used = edges[j].used = true;
  std::vector<std::vector<Vec3>> loops;
  for (std::size_t start = 0; start < edges.size(); ++start) {
    if (edges[start].used) continue;
    std::vector<Vec3> loop;
    std::size_t at = start;
    while (true) {
      edges[at].used = true;
      loop.push_back(edges[at].from);
      if (same(edges[at].to, loop.front())) break;
      // The next edge from where this one ends, searched onward in the polygon's order.
      std::size_t next = edges.size();
      for (std::size_t k = 1; k < edges.size() && next == edges.size(); ++k) {
        const std::size_t c = (at + k) % edges.size();
        if (!edges[c].used && same(edges[c].from, edges[at].to)) next = c;
      }
      if (next == edges.size()) return {};
      at = next;
    }
    loops.push_back(std::move(loop));
  }
  if (loops.size() < 2) return {};
  const Vec3 n = newell_normal(vertices);
  std::vector<std::vector<Vec3>> holes;
  for (auto& loop : loops)
    if (dot(newell_normal(loop), n) < 0) {
      std::reverse(loop.begin(), loop.end());
      holes.push_back(std::move(loop));
    }
  return holes;
}

// Honeybee punches a face by the outer outline of each of its apertures and doors, so a hole in an
// aperture or door on the outside is open: Radiance sees the sky through it (an empty part of the
// polygon and of the wall). Each such hole becomes an opening of its own, a `void` polygon in an
// aperture file (transmittance 1), named "<name> hole <k>". Between two rooms a hole is nothing,
// which the punched polygon already is. Returns how many holes were opened.
std::size_t open_holes(const Polygon& opening, std::vector<std::vector<Vec3>> holes, RadContent& content) {
  for (std::size_t k = 0; k < holes.size(); ++k) {
    Polygon hole;
    hole.vertices = std::move(holes[k]);
    hole.name = opening.name + " hole " + std::to_string(k + 1);
    hole.material = "void";
    hole.where = opening.where;
    check_polygon(hole);
    content.polygons.push_back({std::move(hole), true});
  }
  return holes.size();
}

std::string open_holes_notice(const std::string& source, std::size_t holes, std::size_t openings) {
  return source + ": " + std::to_string(holes) + " holes in " + std::to_string(openings) +
         " apertures or doors taken as openings of transmittance 1 (Honeybee cuts the wall by the outer outline, so "
         "the sky is seen through them, as in Radiance)";
}

// ---------------------------------------------------------------------------------------------
// The model.

class HbjsonReader {
 public:
  HbjsonReader(const json& model, const std::string& name) : r_(name), model_(model) {}

  HoneybeeModel read() {
    const json& radiance = Reader::optional(Reader::optional(model_, "properties"), "radiance");
    const json& mods = r_.array_member(radiance, "properties.radiance", "modifiers");
    for (std::size_t i = 0; i < mods.size(); ++i) {
      const std::string path = indexed("properties.radiance", "modifiers", i);
      Material m = modifier_material(r_, mods[i], path);
      if (const json& inner = Reader::optional(mods[i], "modifier"); !inner.is_null()) ++with_inner_modifier_;
      modifiers_[m.name] = std::move(m);
    }
    const json& sets = r_.array_member(radiance, "properties.radiance", "modifier_sets");
    for (std::size_t i = 0; i < sets.size(); ++i) read_modifier_set(sets[i], indexed("properties.radiance", "modifier_sets", i));

    const json& rooms = r_.array_member(model_, "", "rooms");
    for (std::size_t i = 0; i < rooms.size(); ++i) read_room(rooms[i], indexed("", "rooms", i));
    const ModifierSet defaults;
    for (const char* key : {"orphaned_faces", "orphaned_apertures", "orphaned_doors", "orphaned_shades", "shade_meshes"}) {
      const json& list = r_.array_member(model_, "", key);
      for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string path = indexed("", key, i);
        const std::string k = key;
        if (k == "orphaned_faces") read_face(list[i], path, defaults);
        if (k == "orphaned_apertures") read_subface(list[i], path, defaults, "Wall", false);
        if (k == "orphaned_doors") read_subface(list[i], path, defaults, "Wall", true);
        if (k == "orphaned_shades") read_shade(list[i], path, nullptr);
        if (k == "shade_meshes") read_shade_mesh(list[i], path);
      }
    }
    read_grids(radiance);
    finish_notices();
    return std::move(out_);
  }

 private:
  void read_modifier_set(const json& s, const std::string& path) {
    ModifierSet set;
    const auto slot = [&](const char* subset, const char* key, std::string& target) {
      const json& v = Reader::optional(Reader::optional(s, subset), key);
      if (!v.is_null()) target = r_.string(v, path + "." + subset + "." + key);
    };
    slot("wall_set", "exterior_modifier", set.wall_exterior);
    slot("wall_set", "interior_modifier", set.wall_interior);
    slot("floor_set", "exterior_modifier", set.floor_exterior);
    slot("floor_set", "interior_modifier", set.floor_interior);
    slot("roof_ceiling_set", "exterior_modifier", set.roof_exterior);
    slot("roof_ceiling_set", "interior_modifier", set.roof_interior);
    slot("aperture_set", "window_modifier", set.window);
    slot("aperture_set", "skylight_modifier", set.skylight);
    slot("aperture_set", "operable_modifier", set.operable);
    slot("aperture_set", "interior_modifier", set.aperture_interior);
    slot("door_set", "exterior_modifier", set.door_exterior);
    slot("door_set", "interior_modifier", set.door_interior);
    slot("door_set", "overhead_modifier", set.door_overhead);
    slot("door_set", "exterior_glass_modifier", set.door_exterior_glass);
    slot("door_set", "interior_glass_modifier", set.door_interior_glass);
    slot("shade_set", "exterior_modifier", set.shade_exterior);
    slot("shade_set", "interior_modifier", set.shade_interior);
    sets_[r_.string(r_.member(s, path, "identifier"), path + ".identifier")] = set;
  }

  // The modifier an object names itself, if any (properties.radiance.modifier).
  std::optional<std::string> own_modifier(const json& object, const std::string& path) const {
    const json& v = Reader::optional(Reader::optional(Reader::optional(object, "properties"), "radiance"), "modifier");
    if (v.is_null()) return std::nullopt;
    return r_.string(v, path + ".properties.radiance.modifier");
  }

  // Makes sure `modifier` is defined in the content (from the model, else from Honeybee's
  // defaults) and returns it.
  const std::string& use(const std::string& modifier, const std::string& path) {
    if (out_.content.materials.count(modifier)) return modifier;
    if (const auto it = modifiers_.find(modifier); it != modifiers_.end()) {
      out_.content.materials[modifier] = it->second;
      return modifier;
    }
    for (const auto& d : default_modifiers())
      if (modifier == d.identifier) {
        out_.content.materials[modifier] = Material{modifier, d.type, {}, d.reals, {r_.name() + " (Honeybee's default)", 0}};
        return modifier;
      }
    r_.fail(path, "modifier " + printable(modifier) + " is neither in properties.radiance.modifiers nor one of Honeybee's defaults");
  }

  std::string boundary_condition(const json& object, const std::string& path) const {
    return r_.string(r_.member(r_.member(object, path, "boundary_condition"), path + ".boundary_condition", "type"),
                     path + ".boundary_condition.type");
  }

  std::string label(const json& object, const std::string& path) const {
    const json& id = Reader::optional(object, "identifier");
    return id.is_string() ? id.get<std::string>() : path;
  }

  void add_polygon(std::vector<Vec3> vertices, const json& object, const std::string& path, const std::string& modifier,
                   bool aperture_file, bool interior) {
    Polygon poly;
    poly.vertices = std::move(vertices);
    poly.name = label(object, path);
    poly.material = modifier;
    poly.where = r_.where(path);
    check_polygon(poly);
    RadContent::Entry entry{std::move(poly), aperture_file};
    entry.interior = interior;
    out_.content.polygons.push_back(std::move(entry));
  }

  void read_room(const json& room, const std::string& path) {
    ++out_.rooms;
    room_ = label(room, path);
    ModifierSet set;
    const json& set_id = Reader::optional(Reader::optional(Reader::optional(room, "properties"), "radiance"), "modifier_set");
    if (!set_id.is_null()) {
      const std::string id = r_.string(set_id, path + ".properties.radiance.modifier_set");
      const auto it = sets_.find(id);
      if (it == sets_.end()) r_.fail(path + ".properties.radiance.modifier_set", "modifier set " + printable(id) + " is not in properties.radiance.modifier_sets");
      set = it->second;
    }
    const json& faces = r_.array(r_.member(room, path, "faces"), path + ".faces");
    for (std::size_t i = 0; i < faces.size(); ++i) read_face(faces[i], indexed(path, "faces", i), set);
    room_.clear();
    for (const char* key : {"outdoor_shades", "indoor_shades"}) {
      const json& shades = r_.array_member(room, path, key);
      for (std::size_t i = 0; i < shades.size(); ++i)
        read_shade(shades[i], indexed(path, key, i), &set, std::string(key) == "indoor_shades");
    }
  }

  void read_face(const json& face, const std::string& path, const ModifierSet& set) {
    ++out_.faces;
    const std::string type = r_.string(r_.member(face, path, "face_type"), path + ".face_type");
    const std::string bc = boundary_condition(face, path);
    const bool outdoors = bc == "Outdoors";
    const json& geometry = r_.member(face, path, "geometry");
    const std::vector<Vec3> boundary = r_.loop(r_.member(geometry, path + ".geometry", "boundary"), path + ".geometry.boundary");
    std::vector<std::vector<Vec3>> holes = holes_of(geometry, path + ".geometry");
    if (!room_.empty()) out_.room_faces.push_back({room_, boundary});
    if (type == "Floor" && !room_.empty()) {
      out_.floors.push_back({room_, {boundary}});
      out_.floors.back().loops.insert(out_.floors.back().loops.end(), holes.begin(), holes.end());
    }
    for (const char* key : {"apertures", "doors"}) {
      const json& subs = r_.array_member(face, path, key);
      for (std::size_t i = 0; i < subs.size(); ++i) {
        const std::string sub_path = indexed(path, key, i);
        read_subface(subs[i], sub_path, set, type, std::string(key) == "doors");
        const json& g = r_.member(subs[i], sub_path, "geometry");
        holes.push_back(r_.loop(r_.member(g, sub_path + ".geometry", "boundary"), sub_path + ".geometry.boundary"));
      }
    }
    for (const char* key : {"outdoor_shades", "indoor_shades"}) {
      const json& shades = r_.array_member(face, path, key);
      for (std::size_t i = 0; i < shades.size(); ++i)
        read_shade(shades[i], indexed(path, key, i), &set, std::string(key) == "indoor_shades");
    }
    if (type == "AirBoundary") {
      ++air_boundaries_;
      return;
    }
    std::string modifier;
    if (const auto own = own_modifier(face, path)) modifier = *own;
    else if (type == "Wall") modifier = outdoors ? set.wall_exterior : set.wall_interior;
    else if (type == "Floor") modifier = outdoors ? set.floor_exterior : set.floor_interior;
    else if (type == "RoofCeiling") modifier = outdoors ? set.roof_exterior : set.roof_interior;
    else r_.fail(path + ".face_type", "face type " + printable(type) + " is not Wall, Floor, RoofCeiling or AirBoundary");
    add_polygon(punched(boundary, std::move(holes)), face, path, use(modifier, path), false, false);
  }

  // An aperture (door = false) or a door on a face of type `parent_type`.
  void read_subface(const json& sub, const std::string& path, const ModifierSet& set, const std::string& parent_type,
                    bool door) {
    ++(door ? out_.doors : out_.apertures);
    const std::string bc = boundary_condition(sub, path);
    if (bc != "Outdoors" && bc != "Surface")
      r_.fail(path + ".boundary_condition.type", "an aperture or door's boundary condition is Outdoors or Surface, not " + printable(bc));
    const bool outdoors = bc == "Outdoors";
    std::string modifier;
    const json& radiance = Reader::optional(Reader::optional(sub, "properties"), "radiance");
    const json* state = first_state(radiance);
    if (state) ++dynamic_;
    if (state && Reader::optional(*state, "modifier").is_string()) {
      // A dynamic group: its first state, the one Honeybee writes as the group's default (a state
      // without a modifier takes the aperture's own).
      modifier = (*state)["modifier"].get<std::string>();
    } else if (const auto own = own_modifier(sub, path)) {
      modifier = *own;
    } else if (door) {
      const bool glass = Reader::optional(sub, "is_glass").is_boolean() && sub["is_glass"].get<bool>();
      modifier = glass ? (outdoors ? set.door_exterior_glass : set.door_interior_glass)
                       : (!outdoors ? set.door_interior : parent_type == "Wall" ? set.door_exterior : set.door_overhead);
    } else {
      const bool operable = Reader::optional(sub, "is_operable").is_boolean() && sub["is_operable"].get<bool>();
      modifier = !outdoors ? set.aperture_interior : operable ? set.operable : parent_type == "Wall" ? set.window : set.skylight;
    }
    const json& g = r_.member(sub, path, "geometry");
    std::vector<Vec3> boundary = r_.loop(r_.member(g, path + ".geometry", "boundary"), path + ".geometry.boundary");
    std::vector<std::vector<Vec3>> holes = holes_of(g, path + ".geometry");
    std::vector<std::vector<Vec3>> open = holes;
    const Vec3 n = newell_normal(boundary);
    for (auto& h : open)
      if (dot(newell_normal(h), n) < 0) std::reverse(h.begin(), h.end());
    add_polygon(punched(std::move(boundary), std::move(holes)), sub, path, use(modifier, path), outdoors, !outdoors);
    if (outdoors && !open.empty()) {
      opened_holes_ += open_holes(out_.content.polygons.back().polygon, std::move(open), out_.content);
      ++with_open_holes_;
    }
    if (state) read_state_shades(*state, path + ".properties.radiance.states[0]");
    for (const char* key : {"outdoor_shades", "indoor_shades"}) {
      const json& shades = r_.array_member(sub, path, key);
      for (std::size_t i = 0; i < shades.size(); ++i)
        read_shade(shades[i], indexed(path, key, i), &set, std::string(key) == "indoor_shades");
    }
  }

  // A shade of a room, face or sub-face (`set` its room's modifier set), or orphaned (set null).
  void read_shade(const json& shade, const std::string& path, const ModifierSet* set, bool indoor = false) {
    ++out_.shades;
    std::string modifier;
    if (const auto own = own_modifier(shade, path)) modifier = *own;
    else if (set) modifier = indoor ? set->shade_interior : set->shade_exterior;
    else {
      const bool detached = Reader::optional(shade, "is_detached").is_boolean() && shade["is_detached"].get<bool>();
      modifier = detached ? kContextModifier : ModifierSet{}.shade_exterior;
    }
    // A dynamic shade group: its first state, as Honeybee's static octree includes it (`octree
    // from-folder`'s default --first-shade-state); a state without a modifier takes the shade's.
    const json* state = first_state(Reader::optional(Reader::optional(shade, "properties"), "radiance"));
    if (state) {
      ++dynamic_shades_;
      if (const json& m = Reader::optional(*state, "modifier"); !m.is_null())
        modifier = r_.string(m, path + ".properties.radiance.states[0].modifier");
    }
    add_polygon(punched_face(r_.member(shade, path, "geometry"), path + ".geometry"), shade, path, use(modifier, path), false, false);
    if (state) read_state_shades(*state, path + ".properties.radiance.states[0]");
  }

  // The first state of a dynamic group (an object's properties.radiance naming a
  // dynamic_group_identifier and listing states), else null.
  static const json* first_state(const json& radiance) {
    const json& states = Reader::optional(radiance, "states");
    if (Reader::optional(radiance, "dynamic_group_identifier").is_null() || !states.is_array() || states.empty()) return nullptr;
    return &states[0];
  }

  // The holes of a Face3D (`path` names it), as given.
  std::vector<std::vector<Vec3>> holes_of(const json& geometry, const std::string& path) const {
    std::vector<std::vector<Vec3>> holes;
    const json& own_holes = r_.array_member(geometry, path, "holes");
    for (std::size_t i = 0; i < own_holes.size(); ++i) holes.push_back(r_.loop(own_holes[i], indexed(path, "holes", i)));
    return holes;
  }

  // The boundary of a Face3D with its holes cut by seams.
  std::vector<Vec3> punched_face(const json& geometry, const std::string& path) {
    return punched(r_.loop(r_.member(geometry, path, "boundary"), path + ".boundary"), holes_of(geometry, path));
  }

  // The geometry a dynamic group's state adds (StateGeometry: Honeybee writes it into the state's
  // file), with its modifier, else Honeybee's generic exterior shade.
  void read_state_shades(const json& state, const std::string& path) {
    const json& shades = r_.array_member(state, path, "shades");
    for (std::size_t i = 0; i < shades.size(); ++i) {
      const std::string shade_path = indexed(path, "shades", i);
      const json& m = Reader::optional(shades[i], "modifier");
      const std::string modifier = m.is_null() ? ModifierSet{}.shade_exterior : r_.string(m, shade_path + ".modifier");
      add_polygon(punched_face(r_.member(shades[i], shade_path, "geometry"), shade_path + ".geometry"), shades[i], shade_path,
                  use(modifier, shade_path), false, false);
      ++state_shades_;
    }
  }

  // A ShadeMesh: one polygon per mesh face, as Honeybee writes them.
  void read_shade_mesh(const json& mesh, const std::string& path) {
    ++out_.shades;
    std::string modifier;
    if (const auto own = own_modifier(mesh, path)) modifier = *own;
    else {
      const bool detached = Reader::optional(mesh, "is_detached").is_boolean() && mesh["is_detached"].get<bool>();
      modifier = detached ? kContextModifier : ModifierSet{}.shade_exterior;
    }
    use(modifier, path);
    const std::string gpath = path + ".geometry";
    const json& geometry = r_.member(mesh, path, "geometry");
    const json& vertices = r_.array(r_.member(geometry, gpath, "vertices"), gpath + ".vertices");
    std::vector<Vec3> points;
    for (std::size_t i = 0; i < vertices.size(); ++i) points.push_back(r_.point(vertices[i], indexed(gpath, "vertices", i)));
    const json& faces = r_.array(r_.member(geometry, gpath, "faces"), gpath + ".faces");
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const std::string fpath = indexed(gpath, "faces", f);
      std::vector<Vec3> v;
      for (std::size_t k = 0; k < r_.array(faces[f], fpath).size(); ++k) {
        const json& index = faces[f][k];
        if (!index.is_number_unsigned() || index.get<std::size_t>() >= points.size())
          r_.fail(fpath, "a vertex index of the mesh is not an integer from 0 to " + std::to_string(points.size() - 1));
        v.push_back(points[index.get<std::size_t>()]);
      }
      json named = json::object();
      named["identifier"] = label(mesh, path) + "_" + std::to_string(f);
      add_polygon(std::move(v), named, fpath, modifier, false, false);
    }
  }

  void read_grids(const json& radiance) {
    const json& grids = r_.array_member(radiance, "properties.radiance", "sensor_grids");
    std::map<std::string, std::size_t> by_name;
    for (std::size_t g = 0; g < grids.size(); ++g) {
      const std::string path = indexed("properties.radiance", "sensor_grids", g);
      const std::string id = r_.string(r_.member(grids[g], path, "identifier"), path + ".identifier");
      const json& sensors = r_.array(r_.member(grids[g], path, "sensors"), path + ".sensors");
      if (sensors.empty()) r_.fail(path + ".sensors", "the sensor grid is empty");
      // Grids that share an identifier are one grid, as Honeybee writes them (one .pts file).
      auto [it, fresh] = by_name.try_emplace(id, out_.grids.size());
      if (fresh) {
        SensorGrid grid;
        grid.name = id;
        grid.path = r_.name() + " " + path;
        out_.grids.push_back(std::move(grid));
      } else {
        ++merged_grids_;
      }
      SensorGrid& grid = out_.grids[it->second];
      for (std::size_t s = 0; s < sensors.size(); ++s) {
        const std::string spath = path + ".sensors[" + std::to_string(s) + "]";
        const Vec3 p = r_.point(r_.member(sensors[s], spath, "pos"), spath + ".pos");
        const json& d = r_.member(sensors[s], spath, "dir");
        if (!d.is_array() || d.size() != 3) r_.fail(spath + ".dir", "expected a direction [dx, dy, dz]");
        const Vec3 dir{r_.number(d[0], spath + ".dir[0]"), r_.number(d[1], spath + ".dir[1]"), r_.number(d[2], spath + ".dir[2]")};
        const double length = norm(dir);
        if (!(length > 0) || !std::isfinite(length)) r_.fail(spath + ".dir", "sensor direction is zero");
        grid.sensors.push_back({p, dir / length});
      }
    }
  }

  void finish_notices() {
    auto& n = out_.content.notices;
    n.push_back(r_.name() + ": " + std::to_string(out_.rooms) + " rooms, " + std::to_string(out_.faces) + " faces, " +
                std::to_string(out_.apertures) + " apertures, " + std::to_string(out_.doors) + " doors, " +
                std::to_string(out_.shades) + " shades, " + std::to_string(out_.grids.size()) + " sensor grids");
    if (air_boundaries_)
      n.push_back(r_.name() + ": " + std::to_string(air_boundaries_) + " air boundaries left out (they let all light through; Honeybee writes no geometry for them)");
    if (dynamic_)
      n.push_back(r_.name() + ": " + std::to_string(dynamic_) + " apertures of dynamic groups taken in their first state (the default Honeybee writes); the other states are left out");
    if (dynamic_shades_)
      n.push_back(r_.name() + ": " + std::to_string(dynamic_shades_) + " shades of dynamic groups taken in their first state (as Honeybee's static octree includes them); the other states are left out");
    if (state_shades_)
      n.push_back(r_.name() + ": " + std::to_string(state_shades_) + " shades that the first states of dynamic groups add");
    if (opened_holes_) n.push_back(open_holes_notice(r_.name(), opened_holes_, with_open_holes_));
    if (merged_grids_)
      n.push_back(r_.name() + ": " + std::to_string(merged_grids_) + " sensor grids share an identifier with an earlier one and are merged into it, as Honeybee does");
    if (with_inner_modifier_)
      n.push_back(r_.name() + ": " + std::to_string(with_inner_modifier_) + " modifiers are modified by a pattern or texture, which is left out");
  }

  Reader r_;
  const json& model_;
  HoneybeeModel out_;
  std::map<std::string, Material> modifiers_;
  std::map<std::string, ModifierSet> sets_;
  std::string room_;  // the room whose faces are being read
  long air_boundaries_ = 0, dynamic_ = 0, dynamic_shades_ = 0, state_shades_ = 0, merged_grids_ = 0, with_inner_modifier_ = 0;
  std::size_t opened_holes_ = 0, with_open_holes_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Honeybee Radiance folders.

std::vector<fs::path> files_matching(const fs::path& dir, const std::string& extension) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == extension) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Honeybee writes a window between two rooms once per room, and its translator moves one face of
// each pair shared by two rooms 2 × tolerance into its room, the window with it: a folder holds two
// glass polygons of one outline facing opposite ways, that far apart. Both are marked interior,
// so that assemble_scene takes them as one pane between rooms (without, light through them was
// counted with T² instead of T).
void mark_interior_copies(RadContent& content) {
  std::vector<RadContent::Entry*> glass;
  for (RadContent::Entry& e : content.polygons) {
    const auto it = content.materials.find(e.polygon.material);
    if (it != content.materials.end() && it->second.type == "glass") glass.push_back(&e);
  }
  for (std::size_t i = 0; i < glass.size(); ++i)
    for (std::size_t j = i + 1; j < glass.size(); ++j)
      if (same_outline(glass[i]->polygon, glass[j]->polygon, RadContent::kInteriorCopyGap))
        glass[i]->interior = glass[j]->interior = true;
}

// The first (default) state of each group in `dir`/states.json, read as aperture files or scene
// files, each said in a notice.
void read_first_states(const fs::path& dir, bool aperture_files, const std::string& what, RadContent& content) {
  const fs::path states = dir / "states.json";
  if (!fs::exists(states)) return;
  const json groups = json_input::read_file(states.string());
  const Reader r(states.string());
  if (!groups.is_object()) r.fail("(top)", "expected an object of " + what + "s");
  for (const auto& [group, list] : groups.items()) {
    if (!list.is_array() || list.empty()) r.fail(group, "expected an array of states");
    const std::string file = r.string(r.member(list[0], group + "[0]", "default"), group + "[0].default");
    read_rad_file((dir / file).lexically_normal().string(), aperture_files, content);
    content.notices.push_back(states.string() + ": " + what + " " + printable(group) +
                              " taken in its first state (the default); the other states are left out");
  }
}

HoneybeeModel read_folder(const fs::path& given) {
  const fs::path root = fs::is_directory(given / "model") ? given / "model" : given;
  if (!fs::is_directory(root / "scene") && !fs::is_directory(root / "aperture"))
    throw Error(given.string() + ": not a Honeybee Radiance folder (no model/scene or model/aperture folder) and not an HBJSON file");
  HoneybeeModel out;
  // Modifiers (.mat) before the geometry that uses them; .blk files are for other simulations.
  for (const char* sub : {"scene", "aperture"}) {
    const bool apertures = std::string(sub) == "aperture";
    for (const auto& f : files_matching(root / sub, ".mat")) read_rad_file(f.string(), apertures, out.content);
    for (const auto& f : files_matching(root / sub, ".rad")) read_rad_file(f.string(), apertures, out.content);
  }
  read_first_states(root / "aperture_group", true, "aperture group", out.content);
  // Dynamic shade groups in their first state, as Honeybee's static octree includes them (`octree
  // from-folder`'s default --first-shade-state), outdoor and indoor.
  read_first_states(root / "scene_dynamic", false, "shade group", out.content);
  read_first_states(root / "scene_dynamic" / "indoor", false, "shade group", out.content);
  // Holes cut in apertures and doors (their seams) are open: see open_holes.
  std::size_t holes = 0, openings = 0;
  for (std::size_t i = 0, n = out.content.polygons.size(); i < n; ++i) {
    if (!out.content.polygons[i].from_aperture_file) continue;
    std::vector<std::vector<Vec3>> found = seam_holes(out.content.polygons[i].polygon.vertices);
    if (found.empty()) continue;
    const Polygon opening = out.content.polygons[i].polygon;  // copied: open_holes appends to the same vector
    holes += open_holes(opening, std::move(found), out.content);
    ++openings;
  }
  if (holes) out.content.notices.push_back(open_holes_notice(root.string(), holes, openings));
  mark_interior_copies(out.content);
  const fs::path grid_dir = root / "grid";
  std::vector<fs::path> grids;
  if (const fs::path info = grid_dir / "_info.json"; fs::exists(info)) {
    const json list = json_input::read_file(info.string());
    const Reader r(info.string());
    r.array(list, "(top)");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string path = "[" + std::to_string(i) + "]";
      const json& id = Reader::optional(list[i], "full_id").is_string() ? list[i]["full_id"] : r.member(list[i], path, "identifier");
      grids.push_back(grid_dir / (r.string(id, path + ".full_id") + ".pts"));
    }
  } else {
    grids = files_matching(grid_dir, ".pts");
  }
  for (const auto& g : grids) {
    out.grids.push_back(read_sensor_grid(g.string()));
    out.grids.back().name = g.stem().string();
  }
  return out;
}

}  // namespace

HoneybeeModel parse_hbjson(const std::string& text, const std::string& name) {
  const json model = json_input::parse(text, name);
  if (!model.is_object() || !Reader::optional(model, "type").is_string() || model["type"] != "Model")
    throw Error(name + ": not an HBJSON model (its top level is not an object with \"type\": \"Model\")");
  return HbjsonReader(model, name).read();
}

HoneybeeModel read_honeybee_model(const std::string& path) {
  if (fs::is_directory(path)) return read_folder(path);
  return parse_hbjson(read_text_file(path), path);
}

}  // namespace daylit
