#include "geometry/ray_crossing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace daylit {

namespace {

// Whether q, in the polygon's plane, lies inside it: the crossing-number test on the projection
// that drops the normal's largest coordinate.
bool inside(const std::vector<Vec3>& v, const Vec3& n, const Vec3& q) {
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  const int drop = ax >= ay && ax >= az ? 0 : ay >= az ? 1 : 2;
  const int u = drop == 0 ? 1 : 0, w = drop == 2 ? 1 : 2;
  bool in = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    const double ui = v[i][u], wi = v[i][w], uj = v[j][u], wj = v[j][w];
    if ((wi > q[w]) != (wj > q[w]) && q[u] < ui + (q[w] - wi) * (uj - ui) / (wj - wi)) in = !in;
  }
  return in;
}

// Where the ray crosses the polygon (n its Newell normal), if at 0 < t < limit: t, else infinity.
double crossing(const Polygon& p, const Vec3& n, const Vec3& origin, const Vec3& direction, double limit) {
  const double along = dot(n, direction);
  // A ray in the polygon's plane (to rounding) meets it only along an edge.
  if (!(std::abs(along) > 1e-12 * norm(n) * norm(direction))) return std::numeric_limits<double>::infinity();
  const double t = dot(n, p.vertices[0] - origin) / along;
  if (!(t > 0 && t < limit) || !inside(p.vertices, n, origin + t * direction)) return std::numeric_limits<double>::infinity();
  return t;
}

}  // namespace

double nearest_crossing(const std::vector<Polygon>& polygons, const Vec3& origin, const Vec3& direction) {
  double best = std::numeric_limits<double>::infinity();
  for (const Polygon& p : polygons) {
    if (p.vertices.size() < 3) continue;
    best = std::min(best, crossing(p, newell_normal(p.vertices), origin, direction, best));
  }
  return best;
}

std::size_t crossing_count(const std::vector<Polygon>& polygons, const Vec3& origin, const Vec3& direction) {
  std::size_t count = 0;
  for (const Polygon& p : polygons)
    if (p.vertices.size() >= 3 &&
        std::isfinite(crossing(p, newell_normal(p.vertices), origin, direction, std::numeric_limits<double>::infinity())))
      ++count;
  return count;
}

RayBlockers::RayBlockers(const std::vector<Polygon>& polygons) {
  for (const Polygon& p : polygons)
    if (p.vertices.size() >= 3) planes_.push_back({&p, newell_normal(p.vertices)});
}

bool RayBlockers::blocked(const Vec3& origin, const Vec3& direction) {
  const double far = std::numeric_limits<double>::infinity();
  const auto hits = [&](std::size_t i) {
    return std::isfinite(crossing(*planes_[i].polygon, planes_[i].normal, origin, direction, far));
  };
  for (std::size_t k = 0; k < recent_count_; ++k)
    if (hits(recent_[k])) {
      std::rotate(recent_.begin(), recent_.begin() + std::ptrdiff_t(k), recent_.begin() + std::ptrdiff_t(k) + 1);
      return true;
    }
  for (std::size_t i = 0; i < planes_.size(); ++i)
    if (hits(i)) {
      // The newest blocker first; the oldest of a full list drops out.
      recent_count_ = std::min(recent_count_ + 1, recent_.size());
      std::rotate(recent_.begin(), recent_.begin() + std::ptrdiff_t(recent_count_) - 1,
                  recent_.begin() + std::ptrdiff_t(recent_count_));
      recent_[0] = i;
      return true;
    }
  return false;
}

}  // namespace daylit
