#include "sky/context_buildings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "geometry/error.hpp"
#include "geometry/json_input.hpp"

namespace daylit {

namespace {

using nlohmann::json;

constexpr double kMaxDistanceM = 100e3;  // beyond it a footprint is taken for bad coordinates
constexpr double kMaxHeightM = 1000;     // the tallest building is 828 m: more is a unit mistake

struct Feature {
  std::string label;  // "file: feature 3 (id way/1)"

  [[noreturn]] void fail(const std::string& problem) const { throw Error(label + ": " + problem); }
};

std::string feature_label(const std::string& file, std::size_t index, const json& feature) {
  std::string label = file + ": feature " + std::to_string(index);
  const json* id = nullptr;
  if (const auto it = feature.find("id"); it != feature.end()) id = &*it;
  if (!id) {
    // Overpass turbo and osmtogeojson put the OSM id in the properties as "@id" ("way/1234").
    if (const auto p = feature.find("properties"); p != feature.end() && p->is_object())
      for (const char* key : {"@id", "id", "osm_id"})
        if (const auto it = p->find(key); it != p->end()) {
          id = &*it;
          break;
        }
  }
  if (id && id->is_string()) label += " (id " + id->get<std::string>() + ")";
  if (id && id->is_number()) label += " (id " + id->dump() + ")";
  return label;
}

// A length in metres: a number, or a string "12", "12.5 m", "12m" (OSM's tag values). Returns
// nullopt for anything else; other units are reported by the caller with the text.
std::optional<double> metres(const json& value) {
  if (value.is_number()) return value.get<double>();
  if (!value.is_string()) return std::nullopt;
  const std::string text = value.get<std::string>();
  std::size_t i = 0;
  const auto skip_space = [&] {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
  };
  const auto digits = [&] {
    const std::size_t start = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    return i - start;
  };
  skip_space();
  const std::size_t start = i;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t count = digits();
  if (i < text.size() && text[i] == '.') {
    ++i;
    count += digits();
  }
  if (count == 0) return std::nullopt;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return std::nullopt;
  }
  const std::string number = text.substr(start, i - start);
  skip_space();
  if (i < text.size() && text[i] == 'm') ++i;
  skip_space();
  if (i != text.size()) return std::nullopt;
  return std::strtod(number.c_str(), nullptr);
}

std::optional<double> length_property(const json& properties, const char* key, const Feature& f) {
  const auto it = properties.find(key);
  if (it == properties.end() || it->is_null()) return std::nullopt;
  const std::optional<double> m = metres(*it);
  if (!m)
    f.fail(fmt::format("property '{}' is {}; give metres as a number or a string such as \"12.5\" or \"12.5 m\"", key,
                       it->is_string() ? "\"" + it->get<std::string>() + "\"" : json_input::kind_of(*it)));
  if (!std::isfinite(*m)) f.fail(fmt::format("property '{}' is not finite", key));
  if (*m < 0) f.fail(fmt::format("property '{}' is negative ({} m)", key, *m));
  if (*m > kMaxHeightM) f.fail(fmt::format("property '{}' is {} m, more than {} m: is it in metres?", key, *m, kMaxHeightM));
  return m;
}

// ---------------------------------------------------------------------------------------------
// Plan geometry (model x, y). Validation only: the exact decisions are the visibility engine's.

double orient(const PlanPoint& a, const PlanPoint& b, const PlanPoint& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool same(const PlanPoint& a, const PlanPoint& b) { return a.x == b.x && a.y == b.y; }

// p collinear with segment ab: does it lie on the closed segment?
bool within(const PlanPoint& a, const PlanPoint& b, const PlanPoint& p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

// Do the closed segments ab and cd share a point?
bool segments_meet(const PlanPoint& a, const PlanPoint& b, const PlanPoint& c, const PlanPoint& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) || (o3 == 0 && within(c, d, a)) ||
         (o4 == 0 && within(c, d, b));
}

// Twice the signed area (positive: anticlockwise seen from above), relative to the first vertex.
double twice_area(const std::vector<PlanPoint>& ring) {
  double a = 0;
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) a += orient(ring[0], ring[i], ring[i + 1]);
  return a;
}

bool on_boundary(const std::vector<PlanPoint>& ring, const PlanPoint& p) {
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const PlanPoint& a = ring[i];
    const PlanPoint& b = ring[(i + 1) % ring.size()];
    if (orient(a, b, p) == 0 && within(a, b, p)) return true;
  }
  return false;
}

// Even–odd rule (crossing number), for a point not on the ring.
bool inside_ring(const std::vector<PlanPoint>& ring, const PlanPoint& p) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const PlanPoint& a = ring[i];
    const PlanPoint& b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) in = !in;
  }
  return in;
}

// Inside the footprint (outline minus holes) or on its boundary.
bool in_footprint(const ContextBuilding& b, const PlanPoint& p) {
  for (const Footprint& part : b.parts) {
    bool boundary = false;
    for (const auto& ring : part.rings) boundary = boundary || on_boundary(ring, p);
    if (boundary) return true;
    if (!inside_ring(part.rings[0], p)) continue;
    bool in_hole = false;
    for (std::size_t h = 1; h < part.rings.size() && !in_hole; ++h) in_hole = inside_ring(part.rings[h], p);
    if (!in_hole) return true;
  }
  return false;
}

std::string ring_name(std::size_t polygon, std::size_t ring, bool multi) {
  const std::string r = ring == 0 ? "outline" : "hole " + std::to_string(ring);
  return multi ? fmt::format("polygon {} {}", polygon, r) : r;
}

// Checks a polygon's rings (outline first) and turns them: outline anticlockwise, holes clockwise.
void validate_and_orient(Footprint& part, std::size_t polygon, bool multi, const Feature& f) {
  auto& rings = part.rings;
  for (std::size_t r = 0; r < rings.size(); ++r) {
    const double a = twice_area(rings[r]);
    if (a == 0) f.fail(ring_name(polygon, r, multi) + " encloses no area");
    if ((r == 0) != (a > 0)) std::reverse(rings[r].begin(), rings[r].end());
  }
  struct Edge {
    std::size_t ring, index;
  };
  std::vector<Edge> edges;
  for (std::size_t r = 0; r < rings.size(); ++r)
    for (std::size_t i = 0; i < rings[r].size(); ++i) edges.push_back({r, i});
  const auto point = [&](const Edge& e, std::size_t k) -> const PlanPoint& {
    return rings[e.ring][(e.index + k) % rings[e.ring].size()];
  };
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Edge& E = edges[e];
    const std::size_t n = rings[E.ring].size();
    // A spike: the next edge runs back along this one.
    const PlanPoint &a = point(E, 0), &b = point(E, 1), &c = point(E, 2);
    if (orient(a, b, c) == 0 && (b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y) < 0)
      f.fail(fmt::format("{} doubles back on itself at vertex {}", ring_name(polygon, E.ring, multi), (E.index + 1) % n));
    for (std::size_t g = e + 1; g < edges.size(); ++g) {
      const Edge& G = edges[g];
      if (G.ring == E.ring && ((E.index + 1) % n == G.index || (G.index + 1) % n == E.index)) continue;  // adjacent
      const PlanPoint &p = point(G, 0), &q = point(G, 1);
      if (!segments_meet(a, b, p, q)) continue;
      if (G.ring != E.ring) {
        // Rings may share a vertex (and nothing more).
        const bool shared = same(a, p) || same(a, q) || same(b, p) || same(b, q);
        const bool overlap = orient(a, b, p) == 0 && orient(a, b, q) == 0;
        if (shared && !overlap) continue;
        f.fail(fmt::format("{} and {} cross or touch (edges {} and {})", ring_name(polygon, E.ring, multi),
                           ring_name(polygon, G.ring, multi), E.index, G.index));
      }
      f.fail(fmt::format("{} intersects itself (edges {} and {})", ring_name(polygon, E.ring, multi), E.index, G.index));
    }
  }
  // Holes inside the outline and outside each other: the rings do not cross, so one vertex off
  // the other ring's boundary decides.
  const auto inside_of = [&](std::size_t r, std::size_t s) {
    for (const PlanPoint& p : rings[r])
      if (!on_boundary(rings[s], p)) return inside_ring(rings[s], p);
    return true;  // every vertex on the other ring: the same ring traced again
  };
  for (std::size_t h = 1; h < rings.size(); ++h) {
    if (!inside_of(h, 0)) f.fail(ring_name(polygon, h, multi) + " lies outside the outline");
    for (std::size_t k = 1; k < rings.size(); ++k)
      if (k != h && inside_of(h, k))
        f.fail(ring_name(polygon, h, multi) + " lies inside " + ring_name(polygon, k, multi));
  }
}

struct Placer {
  const Site& site;
  const Feature& f;

  PlanPoint place(const json& position, const std::string& where) const {
    if (!position.is_array() || position.size() < 2 || position.size() > 3)
      f.fail(where + ": a position must be [longitude, latitude] or [longitude, latitude, altitude], not " +
             position.dump());
    for (const auto& c : position)
      if (!c.is_number()) f.fail(where + ": coordinate " + c.dump() + " is not a number");
    const double lon = position[0].get<double>(), lat = position[1].get<double>();
    if (!(lon >= -180 && lon <= 180) || !(lat >= -90 && lat <= 90))
      f.fail(fmt::format("{}: [{}, {}] is not [longitude, latitude] in degrees (RFC 7946; a projected file must be "
                         "converted to WGS84 first)",
                         where, lon, lat));
    const Vec3 m = site.model_from_wgs84(lat, lon, site.origin().height_m);
    const double distance = std::hypot(m.x, m.y);
    if (!(distance <= kMaxDistanceM))
      f.fail(fmt::format("{}: [{}, {}] is {:.0f} km from the site's origin, more than {:.0f} km (longitude and latitude "
                         "swapped? GeoJSON gives longitude first)",
                         where, lon, lat, distance / 1000, kMaxDistanceM / 1000));
    return {m.x, m.y};
  }

  std::vector<PlanPoint> ring(const json& positions, const std::string& where) const {
    if (!positions.is_array()) f.fail(where + ": a ring must be an array of positions, not " + json_input::kind_of(positions));
    if (positions.size() < 4)
      f.fail(fmt::format("{} has {} positions; a ring needs at least 4 (3 distinct vertices, then the first again)", where,
                         positions.size()));
    std::vector<PlanPoint> out;
    std::vector<std::array<double, 2>> raw;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const PlanPoint p = place(positions[i], fmt::format("{} position {}", where, i));
      const std::array<double, 2> lonlat{positions[i][0].get<double>(), positions[i][1].get<double>()};
      if (i + 1 == positions.size()) {
        if (lonlat != raw.front()) f.fail(where + " is not closed: its last position differs from its first");
        break;
      }
      if (!raw.empty() && lonlat == raw.back()) continue;  // repeated vertex (OSM exports have some)
      raw.push_back(lonlat);
      out.push_back(p);
    }
    while (raw.size() > 1 && raw.back() == raw.front()) raw.pop_back(), out.pop_back();
    std::vector<std::array<double, 2>> distinct = raw;
    std::sort(distinct.begin(), distinct.end());
    if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() < 3)
      f.fail(where + " has fewer than 3 distinct vertices");
    return out;
  }
};

void extrude(ContextBuilding& b) {
  const std::string prefix = "f" + std::to_string(b.feature);
  const auto face = [&](std::vector<Vec3> vertices, std::string name) {
    Polygon p;
    p.vertices = std::move(vertices);
    p.name = std::move(name);
    p.material = "context";
    p.where = {b.label, 0};
    b.faces.push_back(std::move(p));
  };
  for (std::size_t k = 0; k < b.parts.size(); ++k) {
    const auto& rings = b.parts[k].rings;
    std::size_t wall = 0;
    for (const auto& ring : rings)
      for (std::size_t i = 0; i < ring.size(); ++i) {
        // Along the ring the solid lies to the left (anticlockwise outline, clockwise holes), so
        // (b − a) × z points out of it.
        const PlanPoint& a = ring[i];
        const PlanPoint& c = ring[(i + 1) % ring.size()];
        face({{a.x, a.y, b.base_z}, {c.x, c.y, b.base_z}, {c.x, c.y, b.top_z}, {a.x, a.y, b.top_z}},
             fmt::format("{}.p{}.wall{}", prefix, k, wall++));
      }
    // Roof: the outline, then each hole reached from the outline's first vertex by a seam
    // traversed once each way.
    std::vector<Vec3> roof;
    for (const PlanPoint& p : rings[0]) roof.push_back({p.x, p.y, b.top_z});
    for (std::size_t h = 1; h < rings.size(); ++h) {
      roof.push_back({rings[0][0].x, rings[0][0].y, b.top_z});
      for (const PlanPoint& p : rings[h]) roof.push_back({p.x, p.y, b.top_z});
      roof.push_back({rings[h][0].x, rings[h][0].y, b.top_z});
    }
    face(std::move(roof), fmt::format("{}.p{}.roof", prefix, k));
  }
}

ContextBuildings from_json(const json& doc, const std::string& name, const Site& site) {
  if (!doc.is_object()) throw Error(name + ": GeoJSON must be an object, not " + json_input::kind_of(doc));
  const auto type = doc.find("type");
  if (type == doc.end() || !type->is_string()) throw Error(name + ": GeoJSON object has no \"type\"");
  if (const auto crs = doc.find("crs"); crs != doc.end() && !crs->is_null()) {
    // GeoJSON 2008's "crs" member: allow only names of WGS84 longitude/latitude.
    const std::string text = crs->dump();
    if (text.find("CRS84") == std::string::npos && text.find("4326") == std::string::npos)
      throw Error(name + ": declares the coordinate system " + text +
                  "; daylit reads WGS84 longitude/latitude only (RFC 7946): convert the file first (e.g. ogr2ogr -t_srs "
                  "EPSG:4326)");
  }
  ContextBuildings out;
  out.path = name;
  std::vector<const json*> features;
  if (*type == "FeatureCollection") {
    const auto list = doc.find("features");
    if (list == doc.end() || !list->is_array()) throw Error(name + ": FeatureCollection has no \"features\" array");
    for (const auto& feature : *list) features.push_back(&feature);
  } else if (*type == "Feature") {
    features.push_back(&doc);
  } else {
    throw Error(name + ": GeoJSON of type \"" + type->get<std::string>() +
                "\"; expected a FeatureCollection (or a Feature) of building footprints with a \"height\" property");
  }
  out.features = features.size();
  std::vector<std::size_t> skipped;
  for (std::size_t i = 0; i < features.size(); ++i) {
    const json& feature = *features[i];
    if (!feature.is_object()) throw Error(fmt::format("{}: feature {}: must be an object, not {}", name, i, json_input::kind_of(feature)));
    const Feature f{feature_label(name, i, feature)};
    if (const auto t = feature.find("type"); t == feature.end() || *t != "Feature")
      f.fail("\"type\" must be \"Feature\"");
    const auto geometry = feature.find("geometry");
    if (geometry == feature.end() || geometry->is_null()) {
      skipped.push_back(i);
      continue;
    }
    if (!geometry->is_object()) f.fail("geometry must be an object, not " + json_input::kind_of(*geometry));
    const auto gtype = geometry->find("type");
    if (gtype == geometry->end() || !gtype->is_string()) f.fail("geometry has no \"type\"");
    const bool multi = *gtype == "MultiPolygon";
    if (!multi && *gtype != "Polygon") {
      skipped.push_back(i);
      continue;
    }
    const auto coordinates = geometry->find("coordinates");
    if (coordinates == geometry->end() || !coordinates->is_array()) f.fail("geometry has no \"coordinates\" array");

    json no_properties = json::object();
    const auto p = feature.find("properties");
    if (p != feature.end() && !p->is_null() && !p->is_object()) f.fail("\"properties\" must be an object");
    const json& properties = (p == feature.end() || p->is_null()) ? no_properties : *p;
    const std::optional<double> height = length_property(properties, "height", f);
    if (!height)
      f.fail("no \"height\" property: give the building's top in metres above the ground (OSM's building:levels is not "
             "used; multiply it by a storey height yourself)");
    const std::optional<double> min_height = length_property(properties, "min_height", f);
    const std::optional<double> base_prop = length_property(properties, "base", f);
    if (min_height && base_prop && *min_height != *base_prop)
      f.fail(fmt::format("\"min_height\" ({} m) and \"base\" ({} m) disagree", *min_height, *base_prop));
    const double base = min_height ? *min_height : (base_prop ? *base_prop : 0.0);
    if (!(*height > base))
      f.fail(fmt::format("\"height\" ({} m) must be above the bottom ({} m{})", *height, base,
                         min_height ? ", min_height" : (base_prop ? ", base" : "")));

    ContextBuilding b;
    b.feature = i;
    b.label = f.label;
    b.base_z = site.ground_z_m() + base;
    b.top_z = site.ground_z_m() + *height;
    const Placer placer{site, f};
    std::vector<const json*> polygons;
    if (multi)
      for (const auto& polygon : *coordinates) polygons.push_back(&polygon);
    else
      polygons.push_back(&*coordinates);
    if (polygons.empty()) f.fail("MultiPolygon has no polygons");
    for (std::size_t k = 0; k < polygons.size(); ++k) {
      const json& rings = *polygons[k];
      const std::string where = multi ? fmt::format("polygon {}", k) : "polygon";
      if (!rings.is_array() || rings.empty()) f.fail(where + " must be a non-empty array of rings");
      Footprint part;
      for (std::size_t r = 0; r < rings.size(); ++r) part.rings.push_back(placer.ring(rings[r], ring_name(k, r, multi)));
      validate_and_orient(part, k, multi, f);
      b.parts.push_back(std::move(part));
    }
    constexpr double inf = std::numeric_limits<double>::infinity();
    b.box_min = {inf, inf, b.base_z};
    b.box_max = {-inf, -inf, b.top_z};
    for (const auto& part : b.parts)
      for (const auto& ring : part.rings)
        for (const PlanPoint& q : ring) {
          b.box_min.x = std::min(b.box_min.x, q.x), b.box_min.y = std::min(b.box_min.y, q.y);
          b.box_max.x = std::max(b.box_max.x, q.x), b.box_max.y = std::max(b.box_max.y, q.y);
        }
    extrude(b);
    out.buildings.push_back(std::move(b));
  }
  out.skipped_features = skipped.size();
  if (!skipped.empty()) {
    std::string list;
    for (std::size_t k = 0; k < skipped.size() && k < 10; ++k) list += (k ? ", " : "") + std::to_string(skipped[k]);
    if (skipped.size() > 10) list += ", …";
    out.notices.push_back(fmt::format("{}: {} feature{} without a Polygon or MultiPolygon geometry skipped (feature{} {})",
                                      name, skipped.size(), skipped.size() == 1 ? "" : "s",
                                      skipped.size() == 1 ? "" : "s", list));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Placement and culling.

double distance_to_segment(const Vec3& c, const Vec3& a, const Vec3& b) {
  const Vec3 e = b - a;
  const double ee = dot(e, e);
  const double t = ee > 0 ? std::clamp(dot(c - a, e) / ee, 0.0, 1.0) : 0.0;
  return norm(c - (a + t * e));
}

// Distance from c to the nearest point of the planar polygon v (a lower bound when v is planar
// only within tolerance: the plane distance is reduced by the vertices' spread about the plane).
double distance_to_polygon(const Vec3& c, const std::vector<Vec3>& v) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) best = std::min(best, distance_to_segment(c, v[i], v[(i + 1) % v.size()]));
  const Vec3 nn = newell_normal(v);
  const double len = norm(nn);
  if (!(len > 0)) return best;
  const Vec3 n = nn / len;
  double spread = 0;
  for (const Vec3& p : v) spread = std::max(spread, std::abs(dot(n, p - v[0])));
  const double h = dot(n, c - v[0]);
  // Inside test in the plane, dropping the normal's dominant axis (seams cancel in the crossing count).
  const int k = std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z) ? 0 : (std::abs(n.y) >= std::abs(n.z) ? 1 : 2);
  std::vector<PlanPoint> plan;
  for (const Vec3& p : v) plan.push_back({p[(k + 1) % 3], p[(k + 2) % 3]});
  const Vec3 foot = c - h * n;
  if (inside_ring(plan, {foot[(k + 1) % 3], foot[(k + 2) % 3]})) best = std::min(best, std::max(0.0, std::abs(h) - spread));
  return best;
}

struct ApertureView {
  const std::vector<Vec3>* vertices = nullptr;
  Vec3 n;             // unit normal
  double h_min = 0, h_max = 0;  // n·v over the vertices
  double z_min = 0;
  int sensor_side = 0;  // +1: every sensor has n·p > h_max; −1: every sensor n·p < h_min; 0: neither
  std::vector<Vec3> along_sun;  // with a sun: the vertices projected along its direction s
  double s_min = 0;             // min s·v over the vertices
};

// Whether the sphere (c, r) may meet the sun's beam through the aperture (place_context_buildings,
// rule (c) with a sun). The margin of 1e-9 of the distances covers the rounding of the projections.
bool meets_sun_beam(const Vec3& c, double r, const ApertureView& a, const SunBeam& sun) {
  const Vec3& s = sun.direction;
  double far = 0;  // D: the largest distance from c to an aperture vertex
  for (const Vec3& v : *a.vertices) far = std::max(far, norm(c - v));
  const double slack = 1e-9 * (far + r);
  if (dot(s, c) + r + slack < a.s_min) return false;  // wholly behind the aperture, seen from the sun
  const double reach = r + (far + r) * std::sin(sun.half_angle) + slack;
  return distance_to_polygon(c - dot(s, c) * s, a.along_sun) <= reach;
}

}  // namespace

ContextBuildings parse_context_buildings(const std::string& text, const std::string& name, const Site& site) {
  return from_json(json_input::parse(text, name), name, site);
}

ContextBuildings read_context_buildings(const std::string& path, const Site& site) {
  return from_json(json_input::read_file(path), path, site);
}

ContextPlacement place_context_buildings(const ContextBuildings& context, const std::vector<SensorGrid>& grids,
                                         SkyModel sky, double min_angular_size_deg, Scene& scene,
                                         const std::optional<SunBeam>& sun) {
  if (!(min_angular_size_deg >= 0 && min_angular_size_deg < 180))
    throw Error(fmt::format("the context's minimum angular size must be in [0, 180) degrees, not {}", min_angular_size_deg));
  if (sun && !(std::abs(norm(sun->direction) - 1) < 1e-9 && sun->half_angle >= 0 && sun->half_angle < std::numbers::pi / 2))
    throw Error("the sun's beam needs a unit direction and a half-angle in [0, 90) degrees");
  constexpr double inf = std::numeric_limits<double>::infinity();
  ContextPlacement out;
  out.read = context.buildings.size();
  out.min_angular_size_deg = min_angular_size_deg;
  out.rule = fmt::format(
      "a building whose prism holds a sensor or an aperture vertex is the model's own and is left out; one whose box "
      "meets the box of the sensors and apertures is placed; any other is left out when, for every aperture, its top is "
      "no higher than the aperture's lowest vertex or the lowest sensor (below the horizon), or it lies on the sensors' "
      "side of the aperture's plane (behind), or its bounding sphere (radius r, centre at distance d from the aperture) "
      "subtends 2 asin(r/(d - 2r)) < {:g} deg (too small; the change this makes to the sky component is bounded by "
      "sc_change_bound_percent){}",
      min_angular_size_deg,
      sun ? " and its sphere misses the sun's beam through the aperture, the rays towards the sun's disk (so nothing "
            "left out shades the sun)"
          : "");
  out.sun_beam_kept = sun.has_value();

  // The model: sensors and apertures, and the box around them.
  Vec3 model_min{inf, inf, inf}, model_max{-inf, -inf, -inf};
  const auto grow = [&](const Vec3& p) {
    model_min = {std::min(model_min.x, p.x), std::min(model_min.y, p.y), std::min(model_min.z, p.z)};
    model_max = {std::max(model_max.x, p.x), std::max(model_max.y, p.y), std::max(model_max.z, p.z)};
  };
  double min_sensor_z = inf;
  // The lowest sensor of the grids that see the sky directly (SensorGrid::sees_sky_directly):
  // for them a building is hidden only below it (rules (a)-(c) reason about apertures).
  double direct_floor_z = inf;
  for (const auto& grid : grids)
    if (grid.sees_sky_directly)
      for (const auto& s : grid.sensors) direct_floor_z = std::min(direct_floor_z, s.position.z);
  for (const auto& grid : grids)
    for (const auto& s : grid.sensors) grow(s.position), min_sensor_z = std::min(min_sensor_z, s.position.z);
  std::vector<ApertureView> apertures;
  for (const auto& aperture : scene.apertures) {
    ApertureView a;
    a.vertices = &aperture.polygon.vertices;
    a.n = normalized(newell_normal(aperture.polygon.vertices));
    a.h_min = inf, a.h_max = -inf, a.z_min = inf;
    for (const Vec3& v : aperture.polygon.vertices) {
      grow(v);
      a.h_min = std::min(a.h_min, dot(a.n, v)), a.h_max = std::max(a.h_max, dot(a.n, v));
      a.z_min = std::min(a.z_min, v.z);
    }
    std::size_t front = 0, back = 0, total = 0;
    for (const auto& grid : grids)
      for (const auto& s : grid.sensors) {
        const double h = dot(a.n, s.position);
        front += h > a.h_max, back += h < a.h_min, ++total;
      }
    a.sensor_side = total > 0 && front == total ? 1 : (total > 0 && back == total ? -1 : 0);
    if (!is_finite(a.n)) a.sensor_side = 0;  // a degenerate aperture: the engine will reject it
    if (sun) {
      const Vec3& s = sun->direction;
      a.s_min = inf;
      for (const Vec3& v : aperture.polygon.vertices) {
        a.along_sun.push_back(v - dot(s, v) * s);
        a.s_min = std::min(a.s_min, dot(s, v));
      }
    }
    apertures.push_back(a);
  }
  const double floor_z = grids.empty() ? -inf : min_sensor_z;

  const auto inside_box = [](const Vec3& p, const ContextBuilding& b) {
    return p.x >= b.box_min.x && p.x <= b.box_max.x && p.y >= b.box_min.y && p.y <= b.box_max.y && p.z >= b.box_min.z &&
           p.z <= b.box_max.z;
  };
  const auto holds = [&](const ContextBuilding& b, const Vec3& p) { return inside_box(p, b) && in_footprint(b, {p.x, p.y}); };

  double solid_angle_sum = 0;
  for (const ContextBuilding& b : context.buildings) {
    // 1. The model's own building.
    const bool own =
        std::any_of(grids.begin(), grids.end(), [&](const SensorGrid& g) {
          return std::any_of(g.sensors.begin(), g.sensors.end(), [&](const Sensor& s) { return holds(b, s.position); });
        }) ||
        std::any_of(scene.apertures.begin(), scene.apertures.end(), [&](const Aperture& a) {
          return std::any_of(a.polygon.vertices.begin(), a.polygon.vertices.end(), [&](const Vec3& v) { return holds(b, v); });
        });
    if (own) {
      ++out.enclosing_model;
      out.notices.push_back(b.label + ": left out: its prism holds sensors or apertures of the model (the model's own "
                                      "building?)");
      continue;
    }
    // 2. Near the model: placed.
    const bool near = b.box_min.x <= model_max.x && model_min.x <= b.box_max.x && b.box_min.y <= model_max.y &&
                      model_min.y <= b.box_max.y && b.box_min.z <= model_max.z && model_min.z <= b.box_max.z;
    bool hidden = !near && !apertures.empty() && !(b.top_z > direct_floor_z);
    bool all_below = true, any_small = false, in_sun_beam = false;
    double building_solid_angle = 0;
    if (hidden) {
      const Vec3 centre = 0.5 * (b.box_min + b.box_max);
      const double radius = 0.5 * norm(b.box_max - b.box_min);
      std::array<Vec3, 8> corners;
      for (int c = 0; c < 8; ++c)
        corners[c] = {c & 1 ? b.box_max.x : b.box_min.x, c & 2 ? b.box_max.y : b.box_min.y, c & 4 ? b.box_max.z : b.box_min.z};
      for (const ApertureView& a : apertures) {
        if (b.top_z <= std::max(a.z_min, floor_z)) continue;  // (a) below the horizon
        all_below = false;
        if (a.sensor_side != 0 &&
            std::all_of(corners.begin(), corners.end(), [&](const Vec3& c) {
              return a.sensor_side > 0 ? dot(a.n, c) >= a.h_max : dot(a.n, c) <= a.h_min;
            }))
          continue;  // (b) behind the aperture
        const double d = distance_to_polygon(centre, *a.vertices);
        if (min_angular_size_deg > 0 && d - 2 * radius > 0) {
          const double alpha = std::asin(std::min(1.0, radius / (d - 2 * radius)));
          if (2 * alpha < min_angular_size_deg * std::numbers::pi / 180) {  // (c) too small
            if (sun && meets_sun_beam(centre, radius, a, *sun)) {
              in_sun_beam = true, hidden = false;
              break;
            }
            const double s = std::sin(alpha / 2);
            building_solid_angle += 4 * std::numbers::pi * s * s;  // 2π(1 − cos α)
            any_small = true;
            continue;
          }
        }
        hidden = false;
        break;
      }
    }
    if (!hidden) {
      ++out.placed;
      out.kept_in_sun_beam += in_sun_beam;
      out.faces += b.faces.size();
      scene.occluders.insert(scene.occluders.end(), b.faces.begin(), b.faces.end());
    } else if (any_small) {
      ++out.too_small;
      solid_angle_sum += building_solid_angle;
    } else if (all_below) {
      ++out.below_horizon;
    } else {
      ++out.behind_apertures;
    }
  }
  // L ≤ 1 in the units of unobstructed_horizontal_irradiance (L_z for the overcast sky), cosines
  // and transmittances ≤ 1.
  out.left_out_solid_angle_sr = solid_angle_sum;
  out.sc_change_bound_percent = 100 * solid_angle_sum / unobstructed_horizontal_irradiance(sky);
  out.notices.push_back(fmt::format(
      "{}: {} building{} read, {} placed ({} faces); left out: {} holding the model, {} below the horizon, {} behind "
      "the apertures, {} smaller than {:g}° (changing the sky component by at most {:.2g} %{}){}",
      context.path, out.read, out.read == 1 ? "" : "s", out.placed, out.faces, out.enclosing_model, out.below_horizon,
      out.behind_apertures, out.too_small, min_angular_size_deg, out.sc_change_bound_percent,
      sun ? ", and the sun's not at all" : "",
      out.kept_in_sun_beam > 0 ? fmt::format("; {} smaller ones kept because they lie in the sun's beam", out.kept_in_sun_beam)
                               : ""));
  return out;
}

}  // namespace daylit
