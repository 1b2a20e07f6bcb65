#pragma once
// The user's map from an OBJ model's material and group names to what the surfaces are
// (--obj-materials, a small JSON file), read into plain rules; materials/obj_materials.hpp applies
// them. The format:
//
//   {"materials": {"Glass": {"role": "aperture", "transmittance": 0.7},
//                  "Glazing*": {"role": "glass", "transmittance": 0.64},
//                  "Wall": {"role": "opaque", "reflectance": 0.5},
//                  "Floor*": {"role": "opaque", "floor": true},
//                  "Tree": {"role": "ignore"}},
//    "groups": {"Shade_*": {"role": "opaque", "reflectance": 0.35}},
//    "aperture_groups": ["Window*"]}
//
// Keys are names or glob patterns (`*` any run of characters, `?` one character, case-sensitive).
// "materials" keys match usemtl names; "groups" keys and "aperture_groups" entries match a face's
// group names (`g`) and its object name (`o`); a group rule wins over a material rule. An exact
// name wins over patterns; two patterns that match the same name are an error (make them
// exclusive). Roles and their fields (every field optional unless said):
//   opaque    an occluder; "reflectance" in [0, 1) (else the .mtl's Kd); "floor": true marks the
//             floors `daylit grid` lays sensors on
//   aperture  a sky opening of constant "transmittance" in [0, 1] (else the .mtl's, else 1)
//   glass     a sky opening with Radiance's glass model (transmittance falling with the angle of
//             incidence): "transmittance" at normal incidence, or Radiance's "transmissivity"
//             (not both; else the .mtl's transmittance), "refractive_index" in [1, 100] (1.52)
//   ignore    left out of the model (furniture, people, trees drawn for show)
// "aperture_groups": [patterns] is the same as {"pattern": {"role": "aperture"}} in "groups".
// Unknown keys, roles and fields are errors naming the JSON path, so that a typo is not silently
// a default.

#include <optional>
#include <string>
#include <vector>

#include "geometry/error.hpp"

namespace daylit {

enum class ObjRole { opaque, aperture, glass, ignore };

struct ObjSurfaceRule {
  std::string pattern;
  ObjRole role = ObjRole::opaque;
  std::optional<double> reflectance, transmittance, transmissivity, refractive_index;
  bool floor = false;
  SourceLocation where;  // the map's file and the rule's JSON path ("map.json: materials.Glass")
  // Whether the rule gives every value its role needs, so that the .mtl is not needed.
  bool complete() const;
};

struct ObjMaterialMap {
  std::string path;
  std::vector<ObjSurfaceRule> materials, groups;
};

// Throws daylit::Error naming the file and the JSON path of bad content.
ObjMaterialMap read_obj_material_map(const std::string& path);
ObjMaterialMap parse_obj_material_map(const std::string& text, const std::string& name);

// True when `pattern` (with `*` and `?`) matches the whole of `name`. O(|pattern|·|name|).
bool glob_match(const std::string& pattern, const std::string& name);

// The rule among `rules` for a surface with these names: an exact name first, else the one
// pattern that matches; nullptr if none. Throws daylit::Error (naming the map) when two different
// rules match, exact or pattern alike, at the same level.
const ObjSurfaceRule* match_rule(const std::vector<ObjSurfaceRule>& rules, const std::vector<std::string>& names);

}  // namespace daylit
