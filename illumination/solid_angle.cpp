#include "illumination/solid_angle.hpp"

namespace daylit {

double solid_angle(const DirectionLoop& loop) noexcept {
  double sum = 0;
  for_each_solid_angle_term<double>(loop, [&](double term) { sum += term; });
  return sum;
}

double solid_angle(const SphericalRegion& region) noexcept {
  double sum = 0;
  for (const auto& loop : region.loops) sum += solid_angle(loop);
  return sum;
}

}  // namespace daylit
