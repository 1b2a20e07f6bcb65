#include "geometry/plan_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace daylit {

namespace {

// The section of one planar polygon by z = height. A vertex counts as above when z > height, so
// that each crossing edge has one end on each side (half-open, as in a point-in-polygon test) and
// a vertex on the plane is not counted twice; the crossings, sorted along the line of the section
// (the polygon's plane meets z = height in a line), pair up into the parts inside the polygon.
void cut(const Polygon& polygon, double height, std::vector<PlanSegment>& out) {
  const auto& v = polygon.vertices;
  const Vec3 n = newell_normal(v);
  // The line's direction: horizontal and in the polygon's plane. A horizontal polygon has none.
  const Vec3 along{-n.y, n.x, 0};
  const double length = std::hypot(along.x, along.y);
  if (!(length > 1e-12 * (std::abs(n.x) + std::abs(n.y) + std::abs(n.z)))) return;
  std::vector<std::pair<double, Vec3>> crossings;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3& a = v[i];
    const Vec3& b = v[(i + 1) % v.size()];
    if ((a.z > height) == (b.z > height)) continue;
    const double t = (height - a.z) / (b.z - a.z);
    const Vec3 p{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), height};
    crossings.emplace_back((p.x * along.x + p.y * along.y) / length, p);
  }
  std::sort(crossings.begin(), crossings.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i + 1 < crossings.size(); i += 2)
    out.push_back({crossings[i].second.x, crossings[i].second.y, crossings[i + 1].second.x, crossings[i + 1].second.y});
}

double segment_distance(const PlanSegment& s, double x, double y) noexcept {
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  const double length2 = dx * dx + dy * dy;
  const double t = length2 > 0 ? std::clamp(((x - s.x0) * dx + (y - s.y0) * dy) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(x - (s.x0 + t * dx), y - (s.y0 + t * dy));
}

}  // namespace

PlanDrawing plan_drawing(const Scene& scene, double height) {
  PlanDrawing drawing;
  for (const Polygon& p : scene.occluders) cut(p, height, drawing.walls);
  for (const Aperture& a : scene.apertures) {
    const auto& v = a.polygon.vertices;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Vec3& p = v[i];
      const Vec3& q = v[(i + 1) % v.size()];
      const double extent = std::max(std::abs(p.x) + std::abs(p.y), std::abs(q.x) + std::abs(q.y));
      if (std::hypot(q.x - p.x, q.y - p.y) > 1e-12 * std::max(extent, 1.0)) drawing.apertures.push_back({p.x, p.y, q.x, q.y});
    }
  }
  return drawing;
}

double plan_height(const SensorGrid& grid) {
  std::vector<double> z;
  for (const Sensor& s : grid.sensors) z.push_back(s.position.z);
  if (z.empty()) return 0;
  std::nth_element(z.begin(), z.begin() + std::ptrdiff_t(z.size() / 2), z.end());
  return z[z.size() / 2];
}

double plan_distance(const std::vector<PlanSegment>& segments, double x, double y) noexcept {
  double d = std::numeric_limits<double>::infinity();
  for (const PlanSegment& s : segments) d = std::min(d, segment_distance(s, x, y));
  return d;
}

}  // namespace daylit
