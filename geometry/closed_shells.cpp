#include "geometry/closed_shells.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "geometry/box.hpp"
#include "geometry/convex_pieces.hpp"
#include "geometry/predicates.hpp"

namespace daylit {

namespace {

using predicates::Epick;
using predicates::point3;

// Coordinates as a key: −0 and +0 are one point.
using Key = std::array<double, 3>;
Key key_of(const Vec3& v) { return {v.x + 0.0, v.y + 0.0, v.z + 0.0}; }
using Piece = std::pair<Key, Key>;  // an edge piece, its ends in increasing order

// Cutting every edge at the vertices that lie on it tests each edge against the vertices in its
// box: beyond this many tests (a large model with long edges) no cycle is looked for, and every
// receiver goes the exact way.
constexpr std::size_t kMaxEdgeVertexTests = 50'000'000;

// Every polygon's edges cut at the vertices (of any polygon) that lie on them, exactly: after
// the cuts, two edges that overlap along a line share their pieces end to end. Empty lists where
// the cutting would cost more than kMaxEdgeVertexTests.
std::vector<std::vector<Piece>> edge_pieces(const std::vector<Polygon>& polygons) {
  std::vector<Vec3> vertices;
  for (const Polygon& p : polygons) vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
  std::sort(vertices.begin(), vertices.end(), [](const Vec3& a, const Vec3& b) { return key_of(a) < key_of(b); });
  vertices.erase(std::unique(vertices.begin(), vertices.end(), [](const Vec3& a, const Vec3& b) { return key_of(a) == key_of(b); }),
                 vertices.end());
  std::vector<std::vector<Piece>> out(polygons.size());
  std::size_t tests = 0;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    const std::vector<Vec3>& v = polygons[i].vertices;
    for (std::size_t k = 0; k < v.size(); ++k) {
      const Vec3 &a = v[k], &b = v[(k + 1) % v.size()];
      if (key_of(a) == key_of(b)) continue;
      std::vector<Vec3> on{a, b};
      const auto first = std::lower_bound(vertices.begin(), vertices.end(), std::min(a.x, b.x),
                                          [](const Vec3& p, double x) { return p.x + 0.0 < x + 0.0; });
      for (auto it = first; it != vertices.end() && it->x <= std::max(a.x, b.x); ++it) {
        if (++tests > kMaxEdgeVertexTests) return std::vector<std::vector<Piece>>(polygons.size());
        const Vec3& p = *it;
        if (p.y < std::min(a.y, b.y) || p.y > std::max(a.y, b.y) || p.z < std::min(a.z, b.z) || p.z > std::max(a.z, b.z))
          continue;
        if (key_of(p) == key_of(a) || key_of(p) == key_of(b)) continue;
        // Within the edge's box and collinear with it: strictly between its ends.
        if (CGAL::collinear(point3(a), point3(b), point3(p))) on.push_back(p);
      }
      // Along the edge's longest axis the collinear points are ordered by that coordinate, exactly.
      const Vec3 d = b - a;
      const int axis = std::abs(d.x) >= std::abs(d.y) && std::abs(d.x) >= std::abs(d.z) ? 0 : (std::abs(d.y) >= std::abs(d.z) ? 1 : 2);
      std::sort(on.begin(), on.end(), [axis](const Vec3& p, const Vec3& q) { return p[axis] < q[axis]; });
      for (std::size_t j = 0; j + 1 < on.size(); ++j) {
        const Key s = key_of(on[j]), t = key_of(on[j + 1]);
        out[i].push_back(s < t ? Piece{s, t} : Piece{t, s});
      }
    }
  }
  return out;
}

// The polygons that stay once those with an edge piece of odd count among the ones still kept
// are set aside, again until none is.
std::vector<bool> peel_to_cycle(const std::vector<std::vector<Piece>>& pieces) {
  std::vector<bool> kept(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) kept[i] = !pieces[i].empty();
  std::map<Piece, int> count;
  for (std::size_t i = 0; i < pieces.size(); ++i)
    for (const Piece& p : pieces[i]) ++count[p];
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (!kept[i]) continue;
      const bool open = std::any_of(pieces[i].begin(), pieces[i].end(), [&](const Piece& p) { return count[p] % 2 != 0; });
      if (!open) continue;
      kept[i] = false;
      changed = true;
      for (const Piece& p : pieces[i]) --count[p];
    }
  }
  return kept;
}

}  // namespace

ClosedShells::ClosedShells(const std::vector<Polygon>& polygons) {
  const std::vector<bool> kept = peel_to_cycle(edge_pieces(polygons));
  Box box;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    if (!kept[i]) continue;
    ++shell_polygon_count_;
    for (const ConvexPiece& piece : convex_pieces(polygons[i], i)) {
      const std::vector<Vec3>& v = piece.vertices;
      for (std::size_t k = 1; k + 1 < v.size(); ++k) {
        triangles_.push_back({v[0], v[k], v[k + 1], i});
        for (const Vec3& p : {v[0], v[k], v[k + 1]}) box.add(p);
      }
    }
  }
  if (!box.empty()) reach_ = norm(box.hi - box.lo) + 1;
  centre_ = box.empty() ? Vec3{0, 0, 0} : 0.5 * (box.lo + box.hi);
}

bool ClosedShells::encloses(const Vec3& x, const Vec3& n, std::size_t own) const {
  if (triangles_.empty() || !std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) return false;
  // The test ray: of three fixed directions in no plane a building's faces are usually in, the
  // one nearest ±n, turned into n's hemisphere (|d·n| ≥ 1/√3 for one of three orthogonal ones).
  static const std::array<Vec3, 3> directions = [] {
    const Vec3 u = normalized(Vec3{0.3183098861837907, 0.2718281828459045, 0.9079809994790936});
    Vec3 v = normalized(cross(u, Vec3{1, 0, 0}));
    const Vec3 w = cross(u, v);
    return std::array<Vec3, 3>{u, v, w};
  }();
  Vec3 d = directions[0];
  for (const Vec3& c : directions)
    if (std::abs(dot(c, n)) > std::abs(dot(d, n))) d = c;
  if (dot(d, n) < 0) d = -1.0 * d;
  if (!(dot(d, n) > 0)) return false;
  // A segment from x to beyond every triangle stands for the ray (its direction is q − x exactly;
  // nearly d, which is all the choice of d asked for).
  const Vec3 q = x + 2 * (norm(x - centre_) + reach_) * d;
  if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return false;
  const Epick::Point_3 px = point3(x), pq = point3(q);
  std::size_t crossings = 0;
  for (const Triangle& t : triangles_) {
    if (t.polygon == own) continue;
    const Epick::Point_3 a = point3(t.a), b = point3(t.b), c = point3(t.c);
    const CGAL::Orientation ox = CGAL::orientation(a, b, c, px), oq = CGAL::orientation(a, b, c, pq);
    if (oq == CGAL::COPLANAR) return false;
    if (ox == CGAL::COPLANAR) {
      // x in the triangle's plane: the segment touches it at x only, which must be strictly outside.
      const bool outside = CGAL::coplanar_orientation(a, b, c, px) == CGAL::NEGATIVE ||
                           CGAL::coplanar_orientation(b, c, a, px) == CGAL::NEGATIVE ||
                           CGAL::coplanar_orientation(c, a, b, px) == CGAL::NEGATIVE;
      if (!outside) return false;
      continue;
    }
    if (ox == oq) continue;
    // The segment passes through the plane: through the triangle where the three edges turn the
    // same way about it, outside where two turn opposite ways, through an edge or vertex else.
    const CGAL::Orientation s[3] = {CGAL::orientation(px, pq, a, b), CGAL::orientation(px, pq, b, c),
                                    CGAL::orientation(px, pq, c, a)};
    const bool positive = s[0] == CGAL::POSITIVE || s[1] == CGAL::POSITIVE || s[2] == CGAL::POSITIVE;
    const bool negative = s[0] == CGAL::NEGATIVE || s[1] == CGAL::NEGATIVE || s[2] == CGAL::NEGATIVE;
    if (positive && negative) continue;
    if (s[0] == CGAL::COPLANAR || s[1] == CGAL::COPLANAR || s[2] == CGAL::COPLANAR) return false;
    ++crossings;
  }
  return crossings % 2 == 1;
}

}  // namespace daylit
