#include "geometry/ray_crossing.hpp"

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

}  // namespace

double nearest_crossing(const std::vector<Polygon>& polygons, const Vec3& origin, const Vec3& direction) {
  double best = std::numeric_limits<double>::infinity();
  for (const Polygon& p : polygons) {
    if (p.vertices.size() < 3) continue;
    const Vec3 n = newell_normal(p.vertices);
    const double along = dot(n, direction);
    // A ray in the polygon's plane (to rounding) meets it only along an edge.
    if (!(std::abs(along) > 1e-12 * norm(n) * norm(direction))) continue;
    const double t = dot(n, p.vertices[0] - origin) / along;
    if (!(t > 0 && t < best)) continue;
    if (inside(p.vertices, n, origin + t * direction)) best = t;
  }
  return best;
}

}  // namespace daylit
