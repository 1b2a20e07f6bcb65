#pragma once
// Radiance's transform arguments (xform(1): -t, -rx, -ry, -rz, -s, -mx, -my, -mz), as a `mesh` or
// `instance` primitive carries them after its file name, applied left to right as xform applies
// them. Rotations by a multiple of 90 degrees use exact cosines and sines (0, ±1), so an
// axis-aligned model stays on the doubles it was written with; other angles take std::cos and
// std::sin of the angle in radians (one rounding each).

#include <array>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/vec3.hpp"

namespace daylit {

struct RadTransform {
  // p ↦ m·p + t, rows of m.
  std::array<Vec3, 3> m{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  Vec3 t;
  bool mirrors = false;  // an odd number of -mx/-my/-mz: polygons' vertex order is reversed to keep
                         // their normals the mirrored ones, as xform does

  Vec3 apply(const Vec3& p) const noexcept { return {dot(m[0], p) + t.x, dot(m[1], p) + t.y, dot(m[2], p) + t.z}; }
};

// Parses `args` (the words after the file name). Throws daylit::Error at `where` for an option
// daylit does not apply (-i, -a: arrays of copies), a missing or bad number, or a scale ≤ 0.
RadTransform parse_rad_transform(const std::vector<std::string>& args, const SourceLocation& where);

}  // namespace daylit
