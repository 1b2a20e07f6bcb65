#include "illumination/solid_angle.hpp"

#include <cmath>

namespace daylit {

double solid_angle(const DirectionLoop& loop) noexcept {
  if (loop.size() < 3) return 0;
  const Vec3& a = loop[0];
  const double la = norm(a);
  double sum = 0;
  for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
    const Vec3& b = loop[i];
    const Vec3& c = loop[i + 1];
    const double lb = norm(b), lc = norm(c);
    const double numerator = dot(a, cross(b - a, c - a));
    const double denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    sum += 2 * std::atan2(numerator, denominator);
  }
  return sum;
}

double solid_angle(const SphericalRegion& region) noexcept {
  double sum = 0;
  for (const auto& loop : region.loops) sum += solid_angle(loop);
  return sum;
}

}  // namespace daylit
