#include "sky/sky_quadrature.hpp"

#include <algorithm>

namespace daylit {

SphericalRegion split_at_sun(const SphericalRegion& region, const Vec3& s) {
  SphericalRegion triangles;
  for (const DirectionLoop& loop : region.loops)
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
      const Vec3 a = loop[0], b = loop[i], c = loop[i + 1];
      const double orientation = dot(a, cross(b, c));
      const bool holds_sun = orientation != 0 && dot(s, cross(a, b)) * orientation > 0 &&
                             dot(s, cross(b, c)) * orientation > 0 && dot(s, cross(c, a)) * orientation > 0;
      if (holds_sun) {
        const Vec3 sun_point = (dot(a, a) > 0 ? norm(a) : 1.0) * s;
        triangles.loops.push_back({sun_point, b, c});
        triangles.loops.push_back({a, sun_point, c});
        triangles.loops.push_back({a, b, sun_point});
      } else {
        triangles.loops.push_back({a, b, c});
      }
    }
  return triangles;
}

QuadratureResult sky_irradiance_quadrature(const std::function<double(const Vec3&)>& luminance, const Vec3& s,
                                           const SphericalRegion& region, const Vec3& n, double tolerance,
                                           const std::function<double(const Vec3&)>& transmittance) {
  return integrate_over_region(
      split_at_sun(region, s),
      [&](const Vec3& u) {
        const double l = luminance(u) * std::max(0.0, dot(n, u));
        return transmittance ? l * transmittance(u) : l;
      },
      tolerance);
}

}  // namespace daylit
