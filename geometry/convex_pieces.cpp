#include "geometry/convex_pieces.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <list>
#include <map>
#include <numbers>

namespace daylit {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = K::Point_2;
using Point3 = K::Point_3;

struct FaceInfo {
  int nesting_level = -1;
  bool inside() const { return nesting_level % 2 == 1; }
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K>;
using Fbb = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbb>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Constraints may touch at vertices (seams), never cross: a crossing is a self-intersection.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

int dominant_axis(const Vec3& n) {
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  return ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
}

Point2 drop(const Vec3& v, int k) { return {v[(k + 1) % 3], v[(k + 2) % 3]}; }
Point3 point3(const Vec3& v) { return {v.x, v.y, v.z}; }

// Base triple (0, b, c) of largest area, so that the plane it spans is well conditioned: of the
// pairs b < c with the largest |(v_b − v_0) × (v_c − v_0)| as computed, the first in (b, c) order.
// The pairs are visited farthest first, and a pair whose |v_b − v_0| |v_c − v_0| (its bound, with
// 1e-12 for the rounding of both sides) is below the best area found cannot be the answer, nor
// can any pair after it: a 361-gon's halves cut at other panes' planes (cut_crossing_panes) took
// O(n²) pairs each, 20 % of a run of Honeybee's tree-crown sample. Same answer as the search of
// all pairs (tests/geometry/test_visibility.cpp).
std::pair<int, int> base_triple(const std::vector<Vec3>& v) {
  const std::size_t m = v.size();
  std::vector<std::size_t> order(m - 1);
  std::vector<double> reach(m, 0.0);
  for (std::size_t i = 1; i < m; ++i) order[i - 1] = i, reach[i] = norm(v[i] - v[0]);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return reach[x] > reach[y]; });
  double best = -1;
  std::pair<std::size_t, std::size_t> bc{1, 2};
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (reach[order[i]] * reach[order[i]] * (1 + 1e-12) < best) break;
    for (std::size_t j = i + 1; j < order.size(); ++j) {
      if (reach[order[i]] * reach[order[j]] * (1 + 1e-12) < best) break;
      const std::size_t b = std::min(order[i], order[j]), c = std::max(order[i], order[j]);
      const double a = norm(cross(v[b] - v[0], v[c] - v[0]));
      if (a > best || (a == best && std::make_pair(b, c) < bc)) best = a, bc = {b, c};
    }
  }
  return {int(bc.first), int(bc.second)};
}

// Whether every vertex lies in one plane, exactly. Any triple of vertices not on one line spans
// that plane if there is one, so this takes one found in O(n) (the vertex farthest from v[0], then
// the one farthest from their line) rather than base_triple's O(n²) search, which the pieces
// keep for their own planes (make_piece): the halves of a 361-gon cut at every other pane's plane
// (cut_crossing_panes in visibility.cpp) took 42 % of a run of Honeybee's tree-crown sample in
// base_triple, most of it here, for halves that are planar only within rounding.
bool exactly_planar(const std::vector<Vec3>& v) {
  std::size_t b = 1, c = 2;
  double far = -1, wide = -1;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (const double d = dot(v[i] - v[0], v[i] - v[0]); d > far) far = d, b = i;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (const double a = norm(cross(v[b] - v[0], v[i] - v[0])); a > wide) wide = a, c = i;
  if (CGAL::collinear(point3(v[0]), point3(v[b]), point3(v[c]))) {
    const auto [bb, cc] = base_triple(v);  // the exhaustive search, where rounding misled the first
    b = std::size_t(bb), c = std::size_t(cc);
  }
  for (std::size_t i = 1; i < v.size(); ++i)
    if (CGAL::orientation(point3(v[0]), point3(v[b]), point3(v[c]), point3(v[i])) != CGAL::COPLANAR) return false;
  return true;
}

// Convex in the 2D projection: all turns of one sign (collinear ones allowed) and one winding,
// no turn back along the same line and no vertex visited twice. (A spike out and back along an
// edge, A B C A D, has neither kind of wrong turn: fuzz_visibility found it kept whole, and its
// visible solid angle negative. The triangulation cancels such seams.)
bool convex_in_projection(const std::vector<Vec3>& v, int k) {
  const std::size_t m = v.size();
  int sign = 0;
  double turning = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const Point2 a = drop(v[i], k), b = drop(v[(i + 1) % m], k), c = drop(v[(i + 2) % m], k);
    const int o = int(CGAL::orientation(a, b, c));
    const double e1x = b.x() - a.x(), e1y = b.y() - a.y(), e2x = c.x() - b.x(), e2y = c.y() - b.y();
    // For collinear a, b, c both products have the sign of the exact dot product: so has the sum.
    if (o == 0 && e1x * e2x + e1y * e2y < 0) return false;
    if (o != 0) {
      if (sign != 0 && o != sign) return false;
      sign = o;
    }
    // The turn's sign is the exact orientation's: at a turn back by nearly π the rounded cross
    // product may have the other sign, and ±π then cancel where they add (a sliver doubling back
    // twice along itself, 7e6 m long, summed to 2π and was kept whole, crossing itself; its
    // visible solid angle came out negative: fuzz_visibility).
    if (o != 0) turning += o * std::atan2(std::abs(e1x * e2y - e1y * e2x), e1x * e2x + e1y * e2y);
  }
  if (sign == 0 || !(std::abs(std::abs(turning) - 2 * std::numbers::pi) < 1.0)) return false;
  std::vector<std::pair<double, double>> points;
  for (const Vec3& p : v) points.emplace_back(drop(p, k).x(), drop(p, k).y());
  std::sort(points.begin(), points.end());
  return std::adjacent_find(points.begin(), points.end()) == points.end();
}

ConvexPiece make_piece(std::vector<Vec3> vertices, int k, std::size_t source) {
  ConvexPiece piece;
  const auto [b, c] = base_triple(vertices);
  if (CGAL::orientation(drop(vertices[0], k), drop(vertices[b], k), drop(vertices[c], k)) == CGAL::CLOCKWISE) {
    std::reverse(vertices.begin() + 1, vertices.end());
    piece.base_b = int(vertices.size()) - c;
    piece.base_c = int(vertices.size()) - b;
  } else {
    piece.base_b = b;
    piece.base_c = c;
  }
  piece.vertices = std::move(vertices);
  piece.drop_axis = k;
  piece.source = source;
  return piece;
}

void mark_domains(Cdt& cdt, Cdt::Face_handle start, int level, std::list<Cdt::Edge>& border) {
  if (start->info().nesting_level != -1) return;
  std::list<Cdt::Face_handle> queue{start};
  while (!queue.empty()) {
    const Cdt::Face_handle fh = queue.front();
    queue.pop_front();
    if (fh->info().nesting_level != -1) continue;
    fh->info().nesting_level = level;
    for (int i = 0; i < 3; ++i) {
      const Cdt::Face_handle n = fh->neighbor(i);
      if (n->info().nesting_level != -1) continue;
      if (cdt.is_constrained(Cdt::Edge(fh, i)))
        border.emplace_back(fh, i);
      else
        queue.push_back(n);
    }
  }
}

std::vector<ConvexPiece> triangulate(const Polygon& polygon, int k, std::size_t source) {
  const auto& v = polygon.vertices;
  const std::size_t m = v.size();
  // Edges traversed in both directions are seams: they bound nothing and cancel.
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  std::map<std::pair<double, double>, std::size_t> index_of;  // projected point → first vertex
  std::vector<std::size_t> id(m);
  for (std::size_t i = 0; i < m; ++i) {
    const Point2 p = drop(v[i], k);
    id[i] = index_of.try_emplace({p.x(), p.y()}, i).first->second;
  }
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t a = id[i], b = id[(i + 1) % m];
    if (a == b) continue;
    auto reverse = directed.find({b, a});
    if (reverse != directed.end() && reverse->second > 0)
      --reverse->second;
    else
      ++directed[{a, b}];
  }
  Cdt cdt;
  std::map<std::size_t, Cdt::Vertex_handle> handle;
  for (const auto& [p, i] : index_of) {
    auto vh = cdt.insert(Point2(p.first, p.second));
    vh->info() = i;
    handle[i] = vh;
  }
  try {
    for (const auto& [edge, count] : directed)
      if (count > 0) cdt.insert_constraint(handle[edge.first], handle[edge.second]);
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    throw input_error(polygon.where, "polygon '" + polygon.name + "' intersects itself");
  }
  // Every vertex on one line in the projection: a polygon of no area in exact arithmetic whose
  // double normal, all rounding, passed the readers' zero-area test (found by fuzz_visibility: a
  // triangle in x = −1.0000000000001137 with collinear (y, z)). The triangulation is then a
  // segment, with no faces to walk.
  if (cdt.dimension() < 2) throw input_error(polygon.where, "polygon '" + polygon.name + "' encloses no area");
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info().nesting_level = -1;
  std::list<Cdt::Edge> border;
  mark_domains(cdt, cdt.infinite_face(), 0, border);
  while (!border.empty()) {
    const Cdt::Edge e = border.front();
    border.pop_front();
    const Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting_level == -1) mark_domains(cdt, n, e.first->info().nesting_level + 1, border);
  }
  std::vector<ConvexPiece> pieces;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->info().inside()) continue;
    pieces.push_back(make_piece({v[f->vertex(0)->info()], v[f->vertex(1)->info()], v[f->vertex(2)->info()]}, k, source));
  }
  if (pieces.empty()) throw input_error(polygon.where, "polygon '" + polygon.name + "' encloses no area");
  return pieces;
}

// A convex polygon that is planar only within tolerance, as triangles of its input vertices: the
// chain v[lo..hi] closed by the chord (hi, lo) is cut by the triangle (lo, mid, hi) at its middle
// vertex and its two halves cut again. The triangles are compact near the rim, where most of
// them are, unlike a fan from one vertex, whose n − 2 slivers each reach across the polygon:
// every view and every culling box of a many-sided disc (a tree crown drawn as a 361-gon) then
// meets a few of them, not all. A triangle of collinear vertices (in the projection) means the
// whole chain is straight: nothing to cover.
void split_convex(const std::vector<Vec3>& v, std::size_t lo, std::size_t hi, int k, std::size_t source,
                  std::vector<ConvexPiece>& pieces) {
  if (hi < lo + 2) return;
  const std::size_t mid = lo + (hi - lo) / 2;
  if (CGAL::orientation(drop(v[lo], k), drop(v[mid], k), drop(v[hi], k)) == CGAL::COLLINEAR) return;
  pieces.push_back(make_piece({v[lo], v[mid], v[hi]}, k, source));
  split_convex(v, lo, mid, k, source, pieces);
  split_convex(v, mid, hi, k, source, pieces);
}

}  // namespace

bool exactly_zero_area(const std::vector<Vec3>& v) {
  using Q = CGAL::Gmpq;
  if (v.size() < 3) return true;
  const Q ox(v[0].x), oy(v[0].y), oz(v[0].z);
  Q n[3] = {0, 0, 0};
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    const Q ax = Q(v[i].x) - ox, ay = Q(v[i].y) - oy, az = Q(v[i].z) - oz;
    const Q bx = Q(v[i + 1].x) - ox, by = Q(v[i + 1].y) - oy, bz = Q(v[i + 1].z) - oz;
    n[0] += ay * bz - az * by;
    n[1] += az * bx - ax * bz;
    n[2] += ax * by - ay * bx;
  }
  return CGAL::sign(n[0]) == CGAL::ZERO && CGAL::sign(n[1]) == CGAL::ZERO && CGAL::sign(n[2]) == CGAL::ZERO;
}

std::vector<ConvexPiece> convex_pieces(const Polygon& polygon, std::size_t source) {
  const auto& v = polygon.vertices;
  const Vec3 normal = newell_normal(v);
  if (!(norm(normal) > 0)) throw input_error(polygon.where, "polygon '" + polygon.name + "' has zero area");
  const int k = dominant_axis(normal);
  if (convex_in_projection(v, k)) {
    if (exactly_planar(v)) return {make_piece(v, k, source)};
    std::vector<ConvexPiece> pieces;
    split_convex(v, 0, v.size() - 1, k, source, pieces);
    return pieces;
  }
  return triangulate(polygon, k, source);
}

}  // namespace daylit
