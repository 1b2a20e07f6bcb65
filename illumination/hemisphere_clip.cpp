#include "illumination/hemisphere_clip.hpp"

#include <vector>

namespace daylit {

SphericalRegion clip_to_hemisphere(const SphericalRegion& region, const Vec3& c) {
  SphericalRegion out;
  std::vector<double> f;
  for (const auto& loop : region.loops) {
    const std::size_t m = loop.size();
    f.resize(m);
    bool any_positive = false, any_negative = false;
    for (std::size_t i = 0; i < m; ++i) {
      f[i] = dot(c, loop[i]);
      any_positive |= f[i] > 0;
      any_negative |= f[i] < 0;
    }
    if (!any_positive) continue;
    if (!any_negative) {
      out.loops.push_back(loop);
      continue;
    }
    DirectionLoop kept;
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = (i + 1) % m;
      if (f[i] >= 0) kept.push_back(loop[i]);
      if ((f[i] > 0 && f[j] < 0) || (f[i] < 0 && f[j] > 0))
        kept.push_back(loop[i] + (f[i] / (f[i] - f[j])) * (loop[j] - loop[i]));
    }
    if (kept.size() >= 3) out.loops.push_back(std::move(kept));
  }
  return out;
}

}  // namespace daylit
