#pragma once
// Radiance's curved surface primitives (sphere, ring, cylinder, tube, cone, cup) as polygons, for
// the exact visibility, which works on polygons. Each is cut into planar facets whose vertices lie
// on the true surface (an inscribed polyhedron), with n segments around every circle chosen so that
// the chord's sagitta r (1 − cos(π/n)) is at most `relative_deviation` · r: every point of the
// facets lies within that distance of the true surface (and inside its convex hull), and every
// point of the surface within it of a facet. Orientation as Radiance's: outward normals for
// sphere (inward for a negative radius), cylinder and cone; inward for tube and cup; a ring's
// along its given normal.

#include <string>
#include <string_view>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/polygon.hpp"

namespace daylit {

inline constexpr double kTessellationRelativeDeviation = 0.01;

bool is_curved_primitive(std::string_view type) noexcept;

struct Tessellation {
  std::vector<Polygon> facets;
  double max_deviation = 0;  // the largest sagitta used, model units
  int segments = 0;          // around the primitive's largest circle
};

// The facets of primitive `type` named `name` with `modifier` and the primitive's real arguments
// (Radiance's reference manual: sphere: centre, radius; ring: centre, normal, inner and outer
// radius; cylinder and tube: two end centres, radius; cone and cup: two end centres and radii).
// Throws daylit::Error naming `where` for a wrong number of arguments, a radius that is zero (or
// negative where Radiance does not allow it), coincident ends or a zero normal.
Tessellation tessellate_primitive(std::string_view type, const std::string& name, const std::string& modifier,
                                  const std::vector<double>& reals, const SourceLocation& where,
                                  double relative_deviation = kTessellationRelativeDeviation);

}  // namespace daylit
