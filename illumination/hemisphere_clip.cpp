#include "illumination/hemisphere_clip.hpp"

#include <vector>

namespace daylit {

void clip_to_hemisphere(const SphericalRegion& region, const Vec3& c, SphericalRegion& out) {
  thread_local std::vector<double> f;
  out.edge_sources.clear();  // new loops: no sources (spherical_region.hpp), as a fresh region
  std::size_t used = 0;      // loops of `out` written; the others keep their storage for reuse
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
    if (used == out.loops.size()) out.loops.emplace_back();
    DirectionLoop& kept = out.loops[used];
    if (!any_negative) {
      kept.assign(loop.begin(), loop.end());
      ++used;
      continue;
    }
    kept.clear();
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = (i + 1) % m;
      if (f[i] >= 0) kept.push_back(loop[i]);
      if ((f[i] > 0 && f[j] < 0) || (f[i] < 0 && f[j] > 0))
        kept.push_back(loop[i] + (f[i] / (f[i] - f[j])) * (loop[j] - loop[i]));
    }
    if (kept.size() >= 3) ++used;
  }
  out.loops.resize(used);
}

SphericalRegion clip_to_hemisphere(const SphericalRegion& region, const Vec3& c) {
  SphericalRegion out;
  clip_to_hemisphere(region, c, out);
  return out;
}

}  // namespace daylit
