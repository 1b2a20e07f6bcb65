#include "geometry/obj_material_map.hpp"

#include <cmath>
#include <sstream>

#include "geometry/json_input.hpp"
#include "geometry/text_scanner.hpp"

namespace daylit {

namespace {

using nlohmann::json;

class MapReader {
 public:
  explicit MapReader(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw Error(name_ + (path.empty() ? "" : ": " + path) + ": " + problem);
  }

  ObjMaterialMap read(const json& root) {
    ObjMaterialMap map;
    map.path = name_;
    if (!root.is_object()) fail("", "expected a JSON object with \"materials\", \"groups\" or \"aperture_groups\", found " +
                                    json_input::kind_of(root));
    for (const auto& [key, value] : root.items()) {
      if (key == "materials" || key == "groups") {
        if (!value.is_object()) fail(key, "expected an object of names to rules, found " + json_input::kind_of(value));
        for (const auto& [pattern, rule] : value.items())
          (key == "materials" ? map.materials : map.groups).push_back(surface_rule(pattern, rule, key + "." + pattern));
      } else if (key == "aperture_groups") {
        if (!value.is_array()) fail(key, "expected an array of group names or patterns, found " + json_input::kind_of(value));
        for (std::size_t i = 0; i < value.size(); ++i) {
          const std::string path = key + "[" + std::to_string(i) + "]";
          if (!value[i].is_string()) fail(path, "expected a group name or pattern, found " + json_input::kind_of(value[i]));
          ObjSurfaceRule r;
          r.pattern = value[i].get<std::string>();
          r.role = ObjRole::aperture;
          r.where = {name_ + ": " + path, 0};
          map.groups.push_back(r);
        }
      } else {
        fail(key, "unknown key: the map has \"materials\", \"groups\" and \"aperture_groups\"");
      }
    }
    // A pattern both in "groups" and in "aperture_groups" (or twice in the latter): two rules
    // for the same surfaces.
    for (std::size_t i = 0; i < map.groups.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (map.groups[i].pattern == map.groups[j].pattern)
          throw Error(map.groups[i].where.str() + ": " + printable(map.groups[i].pattern) + " is also " +
                      map.groups[j].where.str().substr(name_.size() + 2) + ": give it once");
    return map;
  }

 private:
  ObjSurfaceRule surface_rule(const std::string& pattern, const json& rule, const std::string& path) const {
    if (pattern.empty()) fail(path, "an empty name matches nothing");
    if (!rule.is_object())
      fail(path, "expected an object such as {\"role\": \"opaque\", \"reflectance\": 0.5}, found " + json_input::kind_of(rule));
    ObjSurfaceRule r;
    r.pattern = pattern;
    r.where = {name_ + ": " + path, 0};
    const auto it = rule.find("role");
    if (it == rule.end()) fail(path, "missing \"role\" (opaque, aperture, glass or ignore)");
    if (!it->is_string()) fail(path + ".role", "expected a string, found " + json_input::kind_of(*it));
    const std::string role = it->get<std::string>();
    if (role == "opaque") r.role = ObjRole::opaque;
    else if (role == "aperture") r.role = ObjRole::aperture;
    else if (role == "glass") r.role = ObjRole::glass;
    else if (role == "ignore") r.role = ObjRole::ignore;
    else fail(path + ".role", "unknown role " + printable(role) + " (opaque, aperture, glass or ignore)");
    for (const auto& [key, value] : rule.items()) {
      if (key == "role") continue;
      const std::string at = path + "." + key;
      const auto allowed = [&](bool ok) {
        if (!ok) fail(at, "not a field of the role " + role + allowed_fields(r.role));
      };
      if (key == "reflectance") {
        allowed(r.role == ObjRole::opaque);
        r.reflectance = bounded(value, at, 0, 1, true);
      } else if (key == "transmittance") {
        allowed(r.role == ObjRole::aperture || r.role == ObjRole::glass);
        r.transmittance = bounded(value, at, 0, 1, false);
      } else if (key == "transmissivity") {
        allowed(r.role == ObjRole::glass);
        r.transmissivity = bounded(value, at, 0, 1, false);
      } else if (key == "refractive_index") {
        allowed(r.role == ObjRole::glass);
        r.refractive_index = bounded(value, at, 1, 100, false);
      } else if (key == "floor") {
        allowed(r.role == ObjRole::opaque);
        if (!value.is_boolean()) fail(at, "expected true or false, found " + json_input::kind_of(value));
        r.floor = value.get<bool>();
      } else {
        fail(at, "unknown field" + allowed_fields(r.role));
      }
    }
    if (r.transmittance && r.transmissivity) fail(path, "give transmittance or transmissivity, not both");
    return r;
  }

  static std::string allowed_fields(ObjRole role) {
    switch (role) {
      case ObjRole::opaque: return " (opaque takes reflectance and floor)";
      case ObjRole::aperture: return " (aperture takes transmittance)";
      case ObjRole::glass: return " (glass takes transmittance or transmissivity, and refractive_index)";
      case ObjRole::ignore: return " (ignore takes no field)";
    }
    return "";
  }

  // A number in [lo, hi] (or [lo, hi) when `open_above`).
  double bounded(const json& value, const std::string& path, double lo, double hi, bool open_above) const {
    if (!value.is_number()) fail(path, "expected a number, found " + json_input::kind_of(value));
    const double x = value.get<double>();
    if (!(x >= lo && (open_above ? x < hi : x <= hi))) {
      std::ostringstream msg;
      msg << x << " is outside [" << lo << ", " << hi << (open_above ? ")" : "]")
          << (open_above ? " (a surface reflecting all it receives makes the reflected components diverge)" : "");
      fail(path, msg.str());
    }
    return x;
  }

  std::string name_;
};

bool has_wildcard(const std::string& s) { return s.find_first_of("*?") != std::string::npos; }

}  // namespace

bool ObjSurfaceRule::complete() const {
  switch (role) {
    case ObjRole::opaque: return reflectance.has_value();
    case ObjRole::aperture:
    case ObjRole::glass: return transmittance || transmissivity;
    case ObjRole::ignore: return true;
  }
  return false;
}

ObjMaterialMap parse_obj_material_map(const std::string& text, const std::string& name) {
  return MapReader(name).read(json_input::parse(text, name));
}

ObjMaterialMap read_obj_material_map(const std::string& path) { return MapReader(path).read(json_input::read_file(path)); }

// Iterative matching with one backtrack point for the last `*` (the classic linear-space glob).
bool glob_match(const std::string& pattern, const std::string& name) {
  std::size_t p = 0, n = 0, star = std::string::npos, mark = 0;
  while (n < name.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == name[n])) {
      ++p;
      ++n;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = n;
    } else if (star != std::string::npos) {
      p = star + 1;
      n = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

const ObjSurfaceRule* match_rule(const std::vector<ObjSurfaceRule>& rules, const std::vector<std::string>& names) {
  const ObjSurfaceRule* exact = nullptr;
  const ObjSurfaceRule* glob = nullptr;
  std::string exact_name, glob_name;
  for (const auto& r : rules) {
    for (const auto& name : names) {
      if (!has_wildcard(r.pattern) && r.pattern == name) {
        if (exact && exact != &r)
          throw Error(r.where.str() + ": both " + printable(exact->pattern) + " and " + printable(r.pattern) +
                      " name one surface (of " + printable(exact_name) + " and " + printable(name) +
                      "): give it one rule");
        exact = &r;
        exact_name = name;
      } else if (has_wildcard(r.pattern) && glob_match(r.pattern, name)) {
        if (glob && glob != &r)
          throw Error(r.where.str() + ": the patterns " + printable(glob->pattern) + " and " + printable(r.pattern) +
                      " both match " + printable(glob_name == name ? name : glob_name + "' and '" + name) +
                      ": make them exclusive, or name it exactly");
        glob = &r;
        glob_name = name;
      }
    }
  }
  return exact ? exact : glob;
}

}  // namespace daylit
