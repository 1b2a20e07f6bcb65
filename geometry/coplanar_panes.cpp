#include "geometry/coplanar_panes.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/box.hpp"

namespace daylit {

namespace {

Box box_of(const std::vector<ConvexPiece>& pieces) {
  Box b;
  for (const ConvexPiece& p : pieces)
    for (const Vec3& v : p.vertices) b.add(v);
  return b;
}

double joint_extent(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  Box box;
  for (const Vec3& v : a) box.add(v);
  for (const Vec3& v : b) box.add(v);
  return norm(box.hi - box.lo);
}

bool meet(const Box& x, const Box& y, double margin) {
  return x.lo.x <= y.hi.x + margin && y.lo.x <= x.hi.x + margin && x.lo.y <= y.hi.y + margin &&
         y.lo.y <= x.hi.y + margin && x.lo.z <= y.hi.z + margin && y.lo.z <= x.hi.z + margin;
}

// The normal (v_b − v_0) × (v_c − v_0) of a piece: its vertices wind counter-clockwise about it.
Vec3 winding_normal(const ConvexPiece& p) {
  const auto& v = p.vertices;
  return cross(v[p.base_b] - v[0], v[p.base_c] - v[0]);
}

constexpr double kCoplanar = 1e-9;

}  // namespace

bool coplanar_pieces(const ConvexPiece& a, const ConvexPiece& b) {
  const double tolerance = kCoplanar * joint_extent(a.vertices, b.vertices);
  const auto within = [&](const ConvexPiece& plane, const ConvexPiece& other) {
    const Vec3 n = winding_normal(plane);
    const double length = norm(n);
    if (!(length > 0)) return false;
    return std::all_of(other.vertices.begin(), other.vertices.end(), [&](const Vec3& v) {
      return std::abs(dot(n, v - plane.vertices[0])) <= tolerance * length;
    });
  };
  return within(a, b) && within(b, a);
}

namespace {

// The part of q inside w (q cut at the lines of w's edges in turn), or nothing when it has no area
// beyond the rounding of the cut's vertices at the pieces' scale.
std::vector<Vec3> part_inside(const ConvexPiece& q, const ConvexPiece& w) {
  const double extent = joint_extent(q.vertices, w.vertices);
  const Vec3 n = winding_normal(w);
  const auto& wv = w.vertices;
  std::vector<Vec3> inside = q.vertices;
  for (std::size_t k = 0; k < wv.size(); ++k) {
    const Vec3& a = wv[k];
    const Vec3 m = cross(wv[(k + 1) % wv.size()] - a, n);  // in w's plane, away from w
    std::vector<double> s;
    for (const Vec3& v : inside) s.push_back(dot(m, v - a));
    std::vector<Vec3> next;
    for (std::size_t i = 0; i < inside.size(); ++i) {
      const std::size_t j = (i + 1) % inside.size();
      if (s[i] <= 0) next.push_back(inside[i]);
      if ((s[i] < 0 && s[j] > 0) || (s[i] > 0 && s[j] < 0))
        next.push_back(inside[i] + (s[i] / (s[i] - s[j])) * (inside[j] - inside[i]));
    }
    // q lies outside this edge's line, or touches it
    if (next.size() < 3 || !(norm(newell_normal(next)) > 1e-12 * extent * extent)) return {};
    inside = std::move(next);
  }
  return inside;
}

double area_of(const std::vector<Vec3>& v) { return 0.5 * norm(newell_normal(v)); }

}  // namespace

bool overlap_in_plane(const ConvexPiece& q, const ConvexPiece& w) { return !part_inside(q, w).empty(); }

std::vector<std::pair<std::size_t, std::size_t>> overlapping_coplanar_panes(const std::vector<std::vector<ConvexPiece>>& panes) {
  std::vector<Box> boxes;
  for (const auto& pieces : panes) boxes.push_back(box_of(pieces));
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < panes.size(); ++i)
    for (std::size_t j = i + 1; j < panes.size(); ++j) {
      if (panes[i].empty() || panes[j].empty()) continue;
      const double margin = kCoplanar * norm(boxes[i].hi - boxes[i].lo) + kCoplanar * norm(boxes[j].hi - boxes[j].lo);
      if (!meet(boxes[i], boxes[j], margin)) continue;
      // Every piece of each in the plane of every piece of the other: then a direction that
      // crosses both panes crosses that plane once, in their overlap, whichever pieces it meets.
      const bool one_plane = std::all_of(panes[j].begin(), panes[j].end(), [&](const ConvexPiece& q) {
        return std::all_of(panes[i].begin(), panes[i].end(), [&](const ConvexPiece& w) { return coplanar_pieces(q, w); });
      });
      if (!one_plane) continue;
      const bool overlap = std::any_of(panes[j].begin(), panes[j].end(), [&](const ConvexPiece& q) {
        return std::any_of(panes[i].begin(), panes[i].end(), [&](const ConvexPiece& w) { return overlap_in_plane(q, w); });
      });
      if (overlap) pairs.emplace_back(i, j);
    }
  return pairs;
}

std::vector<CoplanarOverlap> coplanar_overlaps(const std::vector<Polygon>& polygons) {
  std::vector<std::vector<ConvexPiece>> pieces(polygons.size());
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    try {
      pieces[i] = convex_pieces(polygons[i], i);
    } catch (const Error&) {
      // a polygon the engine refuses is reported there
    }
  }
  std::vector<CoplanarOverlap> out;
  for (const auto& [earlier, later] : overlapping_coplanar_panes(pieces)) {
    // The pieces of a pane do not overlap each other: the overlaps of piece pairs add up.
    double common = 0, whole = 0;
    for (const ConvexPiece& q : pieces[later]) {
      whole += area_of(q.vertices);
      for (const ConvexPiece& w : pieces[earlier]) common += area_of(part_inside(q, w));
    }
    out.push_back({earlier, later, whole > 0 ? std::min(1.0, common / whole) : 0.0});
  }
  return out;
}

}  // namespace daylit
