// Exact visible regions (DESIGN.md §2). The clipping is generic over the number type
// (shadow_clipping.hpp): the exact path runs it in interval arithmetic with exact predicates and
// provenance deciding what intervals cannot, the float path runs the same code on doubles, and the
// rational mode runs it on CGAL's lazy exact rationals throughout, as a reference.
//
// Per receiver p and convex aperture piece W:
//   1. cull occluder pieces: bounding boxes against the planes of the view cone in double with a
//      wide margin, then exact predicates on the input coordinates (filtered, so mostly doubles);
//   2. if none survives, clip W to the receiver's hemisphere and horizon on the directions
//      themselves (exact signs at the input vertices): no construction beyond that;
//   3. otherwise clip W, clip each survivor to the cone over W, project it centrally onto W's
//      plane, subtract the (convex) shadows from W piece by piece, and round the result once.
// Step 3 runs first in intervals: if every sign is certain (by the interval or by exact
// reasoning), its combinatorics are those of the exact computation and every output direction is
// rebuilt from its definition and certified to 2^-45 of its length (or rebuilt in rationals). A
// sign that nothing can decide aborts it, and the pair is redone in exact rationals: CGAL's
// filtering paradigm lifted from predicates to the whole algorithm.

#include "geometry/visibility.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <type_traits>

#include "geometry/box.hpp"
#include "geometry/convex_pieces.hpp"
#include "geometry/coplanar_panes.hpp"
#include "geometry/error.hpp"
#include "geometry/predicates.hpp"
#include "geometry/shadow_clipping.hpp"

namespace daylit {

namespace {

using predicates::ExactSigns;
using predicates::FloatSigns;
using clipping::Interval;
using clipping::LazyExact;

// ---------------------------------------------------------------------------------------------
// Unobstructed pairs: the aperture piece clipped to the receiver's tangent plane and horizon,
// nothing else. Both planes pass through p, so the clip runs on the directions d = v − p
// themselves, in double, with the signs at input vertices decided by Signs. No provenance, no
// allocation beyond the loop returned: the common case in real buildings must cost little.
// A new vertex x = a_i + t(a_j − a_i) is rounded from terms of the size of |a_i| + |a_j|: when
// the cut passes near p (the receiver almost on the line of an aperture edge), x is short and its
// direction uncertain. Such a vertex is accepted only when the bound on its error is within 2^-45
// of its length, as the certified path accepts its vertices; otherwise the function returns
// false and the caller clips in the general (certified) way. Found by fuzz_visibility: a receiver
// 1e-12 from an aperture's edge line, whose visible solid angle came out 5e-5 too small.
// Each edge's source follows Sutherland–Hodgman as keep_side does (shadow_clipping.hpp): id[i] is
// the edge leaving vertex i: k ≥ 0 the piece's edge from v[k], −1 the tangent plane, −2 the
// horizon. Its plane is what an arc nearly π long is split by; the region carries the sources
// only when asked for.

template <class Signs>
bool unobstructed_directions(const Vec3& p, const Vec3& n, const ConvexPiece& piece, int sh, const VisibilityOptions& options,
                             SphericalRegion& region) {
  constexpr std::size_t kMax = 64;
  const auto& v = piece.vertices;
  if (v.size() + 2 > kMax) return false;  // the general clipper takes such a piece
  std::array<Vec3, kMax> a, b;
  std::array<double, kMax> f;
  std::array<int, kMax> s, id, next_id;
  std::size_t m = v.size();
  for (std::size_t i = 0; i < m; ++i) {
    a[i] = v[i] - p;
    id[i] = int(i);
  }
  for (int plane = 0; plane < 2; ++plane) {
    if (plane == 1 && (!options.clip_to_horizon || (n.x == 0 && n.y == 0))) break;  // for an upward receiver the planes coincide
    bool any_positive = false, any_negative = false;
    for (std::size_t i = 0; i < m; ++i) {
      // Plane 0 (n·d ≥ 0) meets only input vertices: exact signs. Plane 1 (d_z ≥ 0): the sign of
      // a rounded difference is exact for input vertices, and as good as double for the others.
      f[i] = plane == 0 ? dot(n, a[i]) : a[i].z;
      s[i] = plane == 0 ? Signs::dot_diff(n, v[i], p) : predicates::sign_of(f[i]);
      any_positive |= s[i] > 0;
      any_negative |= s[i] < 0;
    }
    if (!any_positive) return true;
    if (!any_negative) continue;
    std::size_t k = 0;
    const int cut = plane == 0 ? -1 : -2;
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = (i + 1) % m;
      if (s[i] >= 0) {
        next_id[k] = s[i] == 0 && s[j] < 0 ? cut : id[i];  // on the cut, heading out: along it
        b[k++] = a[i];
      }
      if (s[i] * s[j] < 0) {
        const Vec3 x = a[i] + (f[i] / (f[i] - f[j])) * (a[j] - a[i]);
        // Rounding of t, of a_j − a_i, of the product and of the sum: 4 ulps of |a_i| + |a_j|;
        // plane 0 adds the rounding of f (3 ulps of |a|, n being unit), which moves x along the
        // edge by up to that over |f_i − f_j| times |a_j − a_i|.
        const double length = norm(a[i]) + norm(a[j]);
        const double slide = plane == 0 ? 3 * norm(a[j] - a[i]) / std::abs(f[i] - f[j]) : 0;
        if (!(0x1p-53 * length * (4 + slide) <= 0x1p-45 * norm(x))) return false;
        next_id[k] = s[i] > 0 ? cut : id[i];  // exit point: along the cut; entry: along the old edge
        b[k++] = x;
      }
    }
    a = b;
    id = next_id;
    m = k;
  }
  // An arc nearly π long (the receiver almost in the piece's plane: the cut along its tangent
  // plane; or almost on the line of one of its edges) gets a vertex at its middle, as the
  // certified clipper's do (clipping::opposite_arc_midpoint).
  using Q = CGAL::Gmpq;
  std::optional<std::pair<std::array<Q, 3>, Q>> plane;  // the piece's N and h, built at the first such arc
  for (std::size_t i = 0; i < m && m + 1 < kMax; ++i) {
    if (!nearly_opposite(a[i], a[(i + 1) % m])) continue;
    if (!plane) clipping::piece_plane(piece, p, plane.emplace().first, plane->second);
    const auto& [N, h] = *plane;
    std::array<Q, 3> M;
    if (id[i] >= 0) M = clipping::segment_plane_normal<Q>(v[std::size_t(id[i])], v[(std::size_t(id[i]) + 1) % v.size()], p);
    else if (id[i] == -1) M = {Q(n.x), Q(n.y), Q(n.z)};
    else M = {Q(0), Q(0), Q(1)};
    const auto middle = clipping::opposite_arc_midpoint(M, N, h);
    if (!middle) continue;
    for (std::size_t k = m; k > i + 1; --k) {
      a[k] = a[k - 1];
      id[k] = id[k - 1];
    }
    a[i + 1] = *middle;
    id[i + 1] = id[i];
    ++m;
    ++i;  // the two halves are well short of π
  }
  const bool track = options.edge_sources;
  DirectionLoop loop(a.begin(), a.begin() + m);
  if (sh > 0) std::reverse(loop.begin(), loop.end());
  region.loops.push_back(std::move(loop));
  if (track) {
    EdgeSourceLoop sources(m);
    for (std::size_t i = 0; i < m; ++i) {
      EdgeSource& e = sources[i];
      if (id[i] >= 0) {
        e = {EdgeSource::Kind::aperture, v[std::size_t(id[i])], v[(std::size_t(id[i]) + 1) % v.size()]};
      } else {
        e.kind = id[i] == -1 ? EdgeSource::Kind::receiver_plane : EdgeSource::Kind::horizon;
      }
    }
    // Reversing the loop keeps each edge's source on its edge, which now starts at its other end.
    if (sh > 0) {
      EdgeSourceLoop reversed(m);
      for (std::size_t i = 0; i < m; ++i) reversed[i] = sources[(2 * m - 2 - i) % m];
      sources = std::move(reversed);
    }
    region.edge_sources.push_back(std::move(sources));
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Culling hierarchy.

// A plane through the receiver, m·(x − p) ≥ 0 on the side that may matter, known in double only
// approximately; `scale` bounds |m| before cancellation so that the margin covers its rounding.
// A plane off the receiver (the aperture's own plane) is m·(x − p) + offset ≥ 0, offset = m·(q − p)
// rounded for a point q of it, and `distance` = |q − p| widens the margin to cover that rounding.
struct CullPlane {
  Vec3 m;
  double scale;
  double offset = 0, distance = 0;
};

// True if the box lies certainly on the negative side of the plane. The margin (1e-10 of the
// magnitudes involved) exceeds the rounding of m and of the evaluation by orders of magnitude, so
// nothing that might touch the cone is culled here; the exact predicates decide the rest.
// The box's centre and half-size as seen from the receiver, and their lengths, are the same for
// every plane of a cone: taken once per box, not once per plane.
// The margin's size is taken in the 1-norm (at most √3 times the 2-norm: a margin no tighter,
// and two square roots fewer per box, 7 % of the 665-polygon bench scene).
struct SeenBox {
  Vec3 c, h;
  double size;  // |c|₁ + |h|₁
  SeenBox(const Box& box, const Vec3& p)
      : c(box.center() - p), h(box.half()), size(std::abs(c.x) + std::abs(c.y) + std::abs(c.z) + h.x + h.y + h.z) {}
};
bool box_outside(const SeenBox& b, const CullPlane& plane) {
  const double reach =
      dot(plane.m, b.c) + std::abs(plane.m.x) * b.h.x + std::abs(plane.m.y) * b.h.y + std::abs(plane.m.z) * b.h.z;
  const double margin = 1e-10 * plane.scale * (b.size + plane.distance);
  return reach + plane.offset < -margin;
}
bool box_outside_any(const Box& box, const std::vector<CullPlane>& planes, const Vec3& p) {
  const SeenBox b(box, p);
  return std::any_of(planes.begin(), planes.end(), [&](const CullPlane& pl) { return box_outside(b, pl); });
}

struct BvhNode {
  Box box;
  int left = -1, right = -1;  // children, or -1 for a leaf
  int first = 0, count = 0;   // leaf: range in the ordered piece indices
};

// An occluder polygon as the union of its convex pieces, for the whole-piece cover test
// (VisibilityEngine::Impl::covers). `testable`: all its pieces lie exactly in the plane of the
// first (so that central projection from a receiver off that plane is one-to-one on it) and its
// boundary is short enough for the test to cost less than the clipping it may save.
struct OccluderPatch {
  std::vector<int> pieces;                       // indices in Impl::occluders
  std::vector<std::pair<Vec3, Vec3>> boundary;   // edges of its pieces that no other of its pieces has
  bool testable = false;
};

}  // namespace

// ---------------------------------------------------------------------------------------------

struct VisibilityEngine::Impl {
  GeometryMode mode;
  SubtractionOrder order_of_subtraction = SubtractionOrder::as_built;
  std::vector<ConvexPiece> occluders;
  std::size_t occluder_polygons = 0;  // Scene::occluders.size(): a pane's index past them is occluder_polygons + aperture
  std::vector<Box> occluder_boxes;
  std::vector<int> order;  // piece indices in BVH leaf order
  std::vector<BvhNode> nodes;
  std::vector<int> rank;   // rank[slot]: where the piece order[slot] comes in the traversal that
                           // fixes the order of subtraction (right child first, as built)
  std::vector<OccluderPatch> patches;  // by occluder polygon (ConvexPiece::source)
  std::vector<std::vector<ConvexPiece>> apertures;
  std::size_t aperture_pieces = 0;
  // AperturesAre::panes with more than one aperture: every aperture's pieces (source: the
  // aperture), which block the views through the others from beyond and filter them in front.
  bool panes = false;
  std::vector<ConvexPiece> pane_pieces;
  std::vector<Box> pane_boxes;
  std::vector<std::size_t> pane_first;  // per aperture, its first piece in pane_pieces (and one past the last)
  // A pane piece that crosses the plane of another aperture's piece w, cut by that plane (in
  // double: the cut's vertices are rounded, a stated approximation): its pieces on the side of
  // w's normal (N_W·(x − w0) ≥ 0) and on the other. Keyed by (w, pane piece index).
  struct Halves {
    std::vector<ConvexPiece> positive, negative;
  };
  std::map<std::pair<const ConvexPiece*, std::size_t>, Halves> pane_halves;
  // Panes in one plane that overlap (coplanar_panes.hpp): per aperture, the earlier ones whose
  // overlap with it is theirs, and the later ones that give it theirs.
  std::vector<std::vector<std::uint32_t>> overlaps_earlier, overlaps_later;
  static bool among(const std::vector<std::uint32_t>& list, std::size_t a) {
    return std::find(list.begin(), list.end(), std::uint32_t(a)) != list.end();
  }

  void cut_crossing_panes() {
    for (const auto& pieces : apertures)
      for (const ConvexPiece& w : pieces) {
        const auto& wv = w.vertices;
        const Vec3 normal = cross(wv[w.base_b] - wv[0], wv[w.base_c] - wv[0]);
        for (std::size_t i = 0; i < pane_pieces.size(); ++i) {
          const ConvexPiece& q = pane_pieces[i];
          if (q.source == w.source) continue;
          std::vector<int> side;
          for (const Vec3& v : q.vertices) side.push_back(ExactSigns::normal_dot_diff(wv[0], wv[w.base_b], wv[w.base_c], v, wv[0]));
          if (std::none_of(side.begin(), side.end(), [](int x) { return x > 0; }) ||
              std::none_of(side.begin(), side.end(), [](int x) { return x < 0; }))
            continue;
          Polygon plus, minus;
          const std::size_t m = q.vertices.size();
          for (std::size_t k = 0; k < m; ++k) {
            const Vec3& a = q.vertices[k];
            const Vec3& b = q.vertices[(k + 1) % m];
            if (side[k] >= 0) plus.vertices.push_back(a);
            if (side[k] <= 0) minus.vertices.push_back(a);
            const int sb = side[(k + 1) % m];
            if (side[k] * sb < 0) {
              const double da = dot(normal, a - wv[0]), db = dot(normal, b - wv[0]);
              const Vec3 x = a + (da / (da - db)) * (b - a);
              plus.vertices.push_back(x);
              minus.vertices.push_back(x);
            }
          }
          // A half of (nearly) no area (the pane touches the plane along an edge, beyond rounding)
          // casts no shadow worth the name and is dropped.
          const auto pieces_of = [&](const Polygon& half) {
            std::vector<ConvexPiece> out;
            if (half.vertices.size() < 3) return out;
            Box b;
            for (const Vec3& v : half.vertices) b.add(v);
            const Vec3 extent = b.hi - b.lo;
            if (!(norm(newell_normal(half.vertices)) > 1e-12 * dot(extent, extent))) return out;
            try {
              out = convex_pieces(half, q.source);
            } catch (const Error&) {
              out.clear();  // rounding made the sliver degenerate: nothing to cast
            }
            return out;
          };
          Halves h;
          h.positive = pieces_of(plus);
          h.negative = pieces_of(minus);
          pane_halves.emplace(std::make_pair(&w, i), std::move(h));
        }
      }
  }

  // The rank of every slot in the depth-first order that visits the right child first: the order
  // in which collect() once visited the survivors, and in which their shadows are still
  // subtracted (the partition into loops, and so every kernel sum, depends on it).
  void rank_slots() {
    rank.assign(order.size(), 0);
    int next = 0;
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const BvhNode& node = nodes[stack.back()];
      stack.pop_back();
      if (node.left >= 0) {
        stack.push_back(node.left);
        stack.push_back(node.right);
        continue;
      }
      for (int i = node.first; i < node.first + node.count; ++i) rank[i] = next++;
    }
  }

  // Groups the pieces by polygon and finds each polygon's boundary: an edge (unordered pair of
  // input vertices) that only one of its pieces has. The pieces of a triangulation share their
  // inner edges vertex for vertex; an inner edge taken for a boundary edge only makes the test
  // stricter.
  void build_patches(std::size_t polygons) {
    constexpr std::size_t kMaxBoundary = 64;
    patches.assign(polygons, {});
    for (std::size_t i = 0; i < occluders.size(); ++i) patches[occluders[i].source].pieces.push_back(int(i));
    const auto less = [](const Vec3& a, const Vec3& b) {
      return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z);
    };
    for (OccluderPatch& patch : patches) {
      if (patch.pieces.empty()) continue;
      const ConvexPiece& first = occluders[patch.pieces[0]];
      const auto& fv = first.vertices;
      bool planar = true;
      std::vector<std::pair<Vec3, Vec3>> edges;
      for (const int i : patch.pieces) {
        const auto& v = occluders[i].vertices;
        for (std::size_t e = 0; e < v.size(); ++e) {
          planar &= ExactSigns::orient3(fv[0], fv[first.base_b], fv[first.base_c], v[e]) == 0;
          Vec3 a = v[e], b = v[(e + 1) % v.size()];
          if (less(b, a)) std::swap(a, b);
          edges.emplace_back(a, b);
        }
      }
      if (!planar) continue;
      const auto pair_less = [&](const std::pair<Vec3, Vec3>& x, const std::pair<Vec3, Vec3>& y) {
        return less(x.first, y.first) || (x.first == y.first && less(x.second, y.second));
      };
      std::sort(edges.begin(), edges.end(), pair_less);
      for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        if (j - i == 1) patch.boundary.push_back(edges[i]);
        i = j;
      }
      patch.testable = patch.boundary.size() <= kMaxBoundary;
    }
  }

  // Whether polygon `patch` hides all of aperture piece w from p, by exact predicates on the input;
  // false when it does not or when the test cannot tell. With Π the polygon's plane and p off it:
  // if every vertex of w lies strictly beyond Π seen from p (with the occluders beyond: the rays
  // p→w reach Π at t > 0; without: the segments (p, w) cross it), the rays through w meet Π in a
  // convex polygon Q, and central projection maps the polygon's pieces one-to-one onto Π's
  // points. Q lies in the union of the pieces iff no boundary edge of the polygon meets the
  // interior of Q and one interior point of Q lies in a piece (the interior of Q is connected).
  // An edge (a, b) of Π misses the interior of Q iff a line separates them (2-D separating axes:
  // the lines of Q's edges, planes through p and w's edges, or the edge's own line, the plane
  // through p, a, b). The interior point is the ray through g = (w0 + w_b + w_c)/3, inside the
  // base triangle of w. Then the exact subtraction leaves nothing of the piece whatever the other
  // blockers and their order: the region is empty, the result of today's computation exactly
  // (every sign there is the exact sign; a partition of an empty set has no loops).
  template <class Signs>
  bool covers(const OccluderPatch& patch, const Vec3& p, const ConvexPiece& w, int sh, bool beyond) const {
    const ConvexPiece& first = occluders[patch.pieces[0]];
    const auto& fv = first.vertices;
    const Vec3 &o0 = fv[0], &ob = fv[first.base_b], &oc = fv[first.base_c];
    const int sp = Signs::orient3(o0, ob, oc, p);
    if (sp == 0) return false;
    const auto& wv = w.vertices;
    for (const Vec3& v : wv)
      if (Signs::normal_dot_diff(o0, ob, oc, v, beyond ? p : o0) != -sp) return false;
    const int inside = -sh;
    for (const auto& [a, b] : patch.boundary) {
      int lo = 1, hi = -1;
      for (const Vec3& v : wv) {
        const int s = Signs::orient3(p, a, b, v);
        lo = std::min(lo, s), hi = std::max(hi, s);
      }
      if (lo >= 0 || hi <= 0) continue;  // w on one side of the edge's line
      bool separated = false;
      for (std::size_t e = 0; e < wv.size() && !separated; ++e) {
        const Vec3 &c = wv[e], &d = wv[(e + 1) % wv.size()];
        separated = inside * Signs::orient3(p, c, d, a) <= 0 && inside * Signs::orient3(p, c, d, b) <= 0;
      }
      if (!separated) return false;
    }
    const Vec3 &w0 = wv[0], &wb = wv[w.base_b], &wc = wv[w.base_c];
    // sign det[a − p, b − p, g − p], times 3: exact on the input.
    const auto orient_g = [&](const Vec3& a, const Vec3& b) {
      return predicates::filtered_sign([&](auto zero) {
        using T = decltype(zero);
        const T ax = T(a.x) - T(p.x), ay = T(a.y) - T(p.y), az = T(a.z) - T(p.z);
        const T bx = T(b.x) - T(p.x), by = T(b.y) - T(p.y), bz = T(b.z) - T(p.z);
        const T gx = T(w0.x) + T(wb.x) + T(wc.x) - (T(p.x) + T(p.x) + T(p.x));
        const T gy = T(w0.y) + T(wb.y) + T(wc.y) - (T(p.y) + T(p.y) + T(p.y));
        const T gz = T(w0.z) + T(wb.z) + T(wc.z) - (T(p.z) + T(p.z) + T(p.z));
        return gx * (ay * bz - az * by) + gy * (az * bx - ax * bz) + gz * (ax * by - ay * bx);
      });
    };
    for (const int i : patch.pieces) {
      const auto& v = occluders[i].vertices;
      // The pieces share the plane and the orientation (one drop axis per polygon): inside the
      // cone over a piece, −sp · orient3(p, a, b, x) ≥ 0 on each edge (a, b).
      bool in = true;
      for (std::size_t e = 0; e < v.size() && in; ++e) in = -sp * orient_g(v[e], v[(e + 1) % v.size()]) >= 0;
      if (in) return true;
    }
    return false;
  }

  int build(int first, int count) {
    BvhNode node;
    for (int i = first; i < first + count; ++i) node.box.add(occluder_boxes[order[i]]);
    const int index = int(nodes.size());
    nodes.push_back(node);
    if (count <= 4) {
      nodes[index].first = first;
      nodes[index].count = count;
      return index;
    }
    const Vec3 extent = node.box.hi - node.box.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const int mid = first + count / 2;
    std::nth_element(order.begin() + first, order.begin() + mid, order.begin() + first + count, [&](int a, int b) {
      return occluder_boxes[a].center()[axis] < occluder_boxes[b].center()[axis];
    });
    const int left = build(first, mid - first);
    const int right = build(mid, first + count - mid);
    nodes[index].left = left;
    nodes[index].right = right;
    return index;
  }

  template <class Signs>
  bool survives(const ConvexPiece& o, const Vec3& p, const Vec3& n, const ConvexPiece& w, int sh, bool horizon,
                bool beyond) const {
    const auto& ov = o.vertices;
    const auto& wv = w.vertices;
    const auto all = [&](auto&& pred) { return std::all_of(ov.begin(), ov.end(), pred); };
    // A luminaire's occluders must lie between it and the receiver: a piece with no vertex strictly
    // on p's side of the aperture's plane (sh = sign N_W·(p − w0)) hides nothing. Tested first:
    // seen from a surface of a model, the rest of the building behind that surface is all of this
    // kind, and the box test in collect() lets through only the pieces that touch the plane.
    if (!beyond && all([&](const Vec3& v) { return sh * Signs::normal_dot_diff(wv[0], wv[w.base_b], wv[w.base_c], v, wv[0]) <= 0; }))
      return false;
    if (horizon && all([&](const Vec3& v) { return v.z <= p.z; })) return false;
    if (all([&](const Vec3& v) { return Signs::dot_diff(n, v, p) <= 0; })) return false;
    // Points of the cone have N·(x − p) of the sign of −h.
    if (all([&](const Vec3& v) { return -sh * Signs::normal_dot_diff(wv[0], wv[w.base_b], wv[w.base_c], v, p) <= 0; }))
      return false;
    const int inside = -sh;
    for (std::size_t e = 0; e < wv.size(); ++e) {
      const Vec3& a = wv[e];
      const Vec3& b = wv[(e + 1) % wv.size()];
      if (all([&](const Vec3& v) { return inside * Signs::orient3(p, a, b, v) <= 0; })) return false;
    }
    // Rays p + t(w − p), t > 0, never reach the occluder's plane from p's side when each moves
    // away from it or parallel to it: sign(N_o·(w − p)) is that of N_o·(p − o0) or zero. (The
    // rays go on beyond the aperture, so the aperture lying on p's side is not enough.) A plane
    // through p itself casts a shadow of zero area. Without the occluders beyond, the segments
    // (p, w) are what must cross it: the aperture on p's side of the plane, or on it, is enough.
    const Vec3 &o0 = ov[0], &ob = ov[o.base_b], &oc = ov[o.base_c];
    const int sp = Signs::orient3(o0, ob, oc, p);
    if (sp == 0) return false;
    const Vec3& from = beyond ? p : o0;
    return !std::all_of(wv.begin(), wv.end(), [&](const Vec3& v) { return sp * Signs::normal_dot_diff(o0, ob, oc, v, from) >= 0; });
  }

  // Planes of the cone over w from p, m·(x − p) ≥ 0 inside, in double for the box tests.
  static std::vector<CullPlane> cone_planes(const Vec3& p, const Vec3& n, const ConvexPiece& w, int sh,
                                            const VisibilityOptions& options) {
    std::vector<CullPlane> planes;
    const auto& wv = w.vertices;
    const Vec3 eb = wv[w.base_b] - wv[0], ec = wv[w.base_c] - wv[0];
    // Without the occluders beyond: p's side of the aperture's plane, sh·N_W·(x − w0) ≥ 0, first,
    // so that whole BVH subtrees behind the luminaire's surface are dropped at once.
    if (!options.occluders_beyond) {
      const Vec3 m = double(sh) * cross(eb, ec);
      planes.push_back({m, norm(eb) * norm(ec), dot(m, p - wv[0]), norm(p - wv[0])});
    }
    planes.push_back({n, 1});
    if (options.clip_to_horizon) planes.push_back({{0, 0, 1}, 1});
    planes.push_back({double(-sh) * cross(eb, ec), norm(eb) * norm(ec)});
    for (std::size_t e = 0; e < wv.size(); ++e) {
      const Vec3 a = wv[e] - p, b = wv[(e + 1) % wv.size()] - p;
      planes.push_back({double(-sh) * cross(a, b), norm(a) * norm(b)});
    }
    return planes;
  }

  // The other apertures' pieces that may meet the view through w from p (the same culling as
  // occluders'): those on p's side of w's plane are appended to `blockers` as transmitting,
  // pane[b] the bit of their aperture in `front`; those beyond it are only counted (panes_beyond):
  // the view through w is not cut at them, and the sky past them, which w's view counts, is taken
  // back by their own views (PaneView::last), where w is in front. A piece that crosses w's plane
  // (counted: panes_crossing) is taken as its two halves cut at that plane (cut_crossing_panes):
  // the half on p's side transmits.
  template <class Signs>
  void collect_panes(const Vec3& p, const Vec3& n, const ConvexPiece& w, int sh, const VisibilityOptions& options,
                     std::vector<const ConvexPiece*>& blockers, std::vector<int>& pane, std::vector<std::uint32_t>& front,
                     VisibilityCounters& counters) const {
    const std::vector<CullPlane> planes = cone_planes(p, n, w, sh, options);
    const auto& wv = w.vertices;
    std::vector<const ConvexPiece*> beyond_w, in_front;
    for (std::size_t i = 0; i < pane_pieces.size(); ++i) {
      const ConvexPiece& q = pane_pieces[i];
      if (q.source == w.source) continue;
      // The pane the receiver lies on (a radiosity node on a glass partition) is in front of
      // nothing it sees: to roundoff the receiver is on either side of it, and on the far side
      // every direction would pass it (measured: the sky through a skylight, seen from the
      // nodes of a glass partition, counted under the partition's T as well at about half of them).
      if (options.receiver_occluder == occluder_polygons + q.source) continue;
      // A later pane in w's plane that overlaps it gives w the overlap, and is not in front of it.
      if (among(overlaps_later[w.source], q.source)) continue;
      if (box_outside_any(pane_boxes[i], planes, p)) continue;
      if (!survives<Signs>(q, p, n, w, sh, options.clip_to_horizon, options.occluders_beyond)) continue;
      // An earlier one keeps the overlap: w's view passes none of it (exact clipping, as of a
      // wall in the aperture's plane).
      if (among(overlaps_earlier[w.source], q.source)) {
        blockers.push_back(&q);
        continue;
      }
      bool near_side = false, far_side = false;
      for (const Vec3& v : q.vertices) {
        const int side = sh * Signs::normal_dot_diff(wv[0], wv[w.base_b], wv[w.base_c], v, wv[0]);
        near_side |= side > 0;
        far_side |= side < 0;
      }
      if (!near_side && !far_side) continue;  // in w's plane: it meets the view only on w's boundary
      if (!near_side) {
        beyond_w.push_back(&q);
        continue;
      }
      if (!far_side) {
        in_front.push_back(&q);
        continue;
      }
      // Crossing w's plane: its part on p's side transmits, its part beyond blocks.
      ++counters.panes_crossing;
      const auto found = pane_halves.find({&w, i});
      if (found == pane_halves.end()) {  // the float path's signs said crossing where the exact ones do not
        in_front.push_back(&q);
        continue;
      }
      const Halves& h = found->second;
      const bool p_positive = sh > 0;
      for (const ConvexPiece& half : p_positive ? h.positive : h.negative) in_front.push_back(&half);
      for (const ConvexPiece& half : p_positive ? h.negative : h.positive) beyond_w.push_back(&half);
    }
    counters.panes_beyond += beyond_w.size();
    if (in_front.empty()) return;
    pane.assign(blockers.size(), -1);
    for (const ConvexPiece* q : in_front) {
      auto it = std::find(front.begin(), front.end(), std::uint32_t(q->source));
      if (it == front.end()) {
        if (front.size() == 64)
          throw Error("more than 64 other apertures' panes lie in front of one aperture seen from (" + std::to_string(p.x) +
                      ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")");
        it = front.insert(front.end(), std::uint32_t(q->source));
      }
      blockers.push_back(q);
      pane.push_back(int(it - front.begin()));
    }
    counters.panes_in_front += in_front.size();
  }

  // Of the panes `through` (in front of aperture piece w from p, all crossed by the directions of
  // one region), the one nearest w: every other lies on p's side of its plane. Exact signs of
  // the panes' vertices; for panes that cross each other's planes (cut only against apertures'
  // planes, not each other's) the one with the fewest others behind it.
  template <class Signs>
  std::uint32_t last_pane(const Vec3& p, const std::vector<std::uint32_t>& through) const {
    if (through.size() == 1) return through[0];
    std::uint32_t best = through[0];
    int best_in_front = -1;
    for (std::uint32_t b : through) {
      const ConvexPiece& plane = pane_pieces[pane_first[b]];
      const auto& bv = plane.vertices;
      const int sp = Signs::normal_dot_diff(bv[0], bv[plane.base_b], bv[plane.base_c], p, bv[0]);
      int in_front = 0;
      for (std::uint32_t c : through) {
        if (c == b) continue;
        bool near = true;
        for (std::size_t k = pane_first[c]; k < pane_first[c + 1] && near; ++k)
          for (const Vec3& v : pane_pieces[k].vertices)
            if (sp * Signs::normal_dot_diff(bv[0], bv[plane.base_b], bv[plane.base_c], v, bv[0]) < 0) {
              near = false;
              break;
            }
        in_front += near;
      }
      if (in_front > best_in_front) best = b, best_in_front = in_front;
    }
    return best;
  }

  // The occluder pieces that may hide part of w from p, in the order of subtraction: as built
  // (rank), or front to back (by their boxes' distance from p, ties by rank: one sort, where a
  // sort by rank and then a stable one by distance, which gives the same order, cost twice). The
  // hierarchy is walked nearest box first, so that what is near the receiver (its own room's walls)
  // comes first; in the exact modes each of the first kCoverTries polygons met is tested for
  // hiding all of w (covers), and the walk stops when one does: returns true, and `out` is then
  // to be ignored. `nearest`: the first kNearest survivors met, for the trial in evaluate(). The
  // float path never stops (its subtraction rounds, and may leave slivers that
  // it must report as the same code always has).
  template <class Signs>
  bool collect(const Vec3& p, const Vec3& n, const ConvexPiece& w, int sh, const VisibilityOptions& options,
               std::vector<const ConvexPiece*>& out, std::vector<const ConvexPiece*>& nearest, VisibilityCounters& counters) const {
    if (nodes.empty()) return false;
    constexpr int kCoverTries = 6;
    constexpr std::size_t kNearest = 12;
    const bool try_cover = mode != GeometryMode::floating;
    const bool horizon = options.clip_to_horizon, beyond = options.occluders_beyond;
    const std::vector<CullPlane> planes = cone_planes(p, n, w, sh, options);
    struct Found {
      double distance2;  // of the piece's box from p (front to back), else 0
      int rank;
      const ConvexPiece* piece;
    };
    const bool front_to_back = order_of_subtraction == SubtractionOrder::front_to_back;
    std::vector<Found> found;
    std::size_t tried[kCoverTries];
    int tries = 0;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const BvhNode& node = nodes[stack[--top]];
      const bool outside = box_outside_any(node.box, planes, p);
      if (outside) {
        counters.occluders_box_culled += node.left < 0 ? node.count : 1;
        continue;
      }
      if (node.left >= 0) {
        const bool left_first = nodes[node.left].box.distance2(p) <= nodes[node.right].box.distance2(p);
        stack[top++] = left_first ? node.right : node.left;
        stack[top++] = left_first ? node.left : node.right;
        continue;
      }
      for (int i = node.first; i < node.first + node.count; ++i) {
        const ConvexPiece& o = occluders[order[i]];
        if (o.source == options.excluded_occluder || o.source == options.receiver_occluder) continue;
        if (box_outside_any(occluder_boxes[order[i]], planes, p)) {
          ++counters.occluders_box_culled;
          continue;
        }
        ++counters.occluders_tested;
        if (!survives<Signs>(o, p, n, w, sh, horizon, beyond)) continue;
        found.push_back({front_to_back ? occluder_boxes[order[i]].distance2(p) : 0.0, rank[i], &o});
        if (nearest.size() < kNearest) nearest.push_back(&o);
        if (!try_cover || tries == kCoverTries || std::find(tried, tried + tries, o.source) != tried + tries) continue;
        tried[tries++] = o.source;
        const OccluderPatch& patch = patches[o.source];
        if (patch.testable && covers<Signs>(patch, p, w, sh, beyond)) return true;
      }
    }
    std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
      return a.distance2 < b.distance2 || (a.distance2 == b.distance2 && a.rank < b.rank);
    });
    for (const Found& f : found) out.push_back(f.piece);
    return false;
  }

  // The trial that finds a piece hidden by several polygons together (the corner of a room, where
  // the rays to another room's window leave through two walls): the nearest survivors alone,
  // subtracted in the order met. Where they leave nothing the region is empty whatever the others
  // (the subtraction is exact in these modes), and their clipping is all the pair costs; where they
  // leave something, the pair is clipped as before, in the order of subtraction, and the trial
  // was wasted: tried only when it clips at most half of the survivors. In the exact mode in
  // intervals first, then, if a sign is uncertain, in rationals, so that both exact modes decide
  // alike.
  template <class Signs>
  bool nearest_hide_all(const Vec3& p, const Vec3& n, const ConvexPiece& w, int sh, const VisibilityOptions& options,
                        const std::vector<const ConvexPiece*>& nearest) const {
    // First what costs no construction: the ray through each vertex of w must meet one of them
    // (in the closed cone over a piece, and reaching its plane as covers() asks). Where one does
    // not (the own window, whose top corners see sky), the trial is not made. A vertex that the
    // receiver's planes cut away may decline a trial that would succeed: nothing is lost but time.
    const auto& wv = w.vertices;
    const bool beyond = options.occluders_beyond;
    for (const Vec3& v : wv) {
      const bool hit = std::any_of(nearest.begin(), nearest.end(), [&](const ConvexPiece* o) {
        const auto& ov = o->vertices;
        const int sp = Signs::orient3(ov[0], ov[o->base_b], ov[o->base_c], p);
        if (sp == 0 || Signs::normal_dot_diff(ov[0], ov[o->base_b], ov[o->base_c], v, beyond ? p : ov[0]) != -sp) return false;
        for (std::size_t e = 0; e < ov.size(); ++e)
          if (-sp * Signs::orient3(p, ov[e], ov[(e + 1) % ov.size()], v) < 0) return false;
        return true;
      });
      if (!hit) return false;
    }
    if (mode == GeometryMode::exact) {
      try {
        CGAL::Protect_FPU_rounding<true> upward;
        return clipping::ShadowClipper<Interval, Signs>(p, n, w, sh, options.clip_to_horizon, options.occluders_beyond).hides_all(nearest);
      } catch (const CGAL::Uncertain_conversion_exception&) {
      }
    }
    return clipping::ShadowClipper<LazyExact, Signs>(p, n, w, sh, options.clip_to_horizon, options.occluders_beyond).hides_all(nearest);
  }

  template <class Signs, class FT>
  void evaluate(const Vec3& p, const Vec3& n, const ConvexPiece& w, const VisibilityOptions& options, ApertureView& view,
                VisibilityCounters& counters) const {
    SphericalRegion& region = view.region;
    ++counters.pairs;
    const auto& wv = w.vertices;
    const int sh = Signs::normal_dot_diff(wv[0], wv[w.base_b], wv[w.base_c], p, wv[0]);
    if (sh == 0) {
      ++counters.pairs_not_facing;
      return;
    }
    // Whole piece behind the receiver or below its horizon: nothing to do. A receiver facing
    // straight down (n = −z exactly) with the horizon cut sees only the horizon itself, a set of
    // zero measure: clipping to the two opposite planes in turn would leave a degenerate loop on
    // the horizon whose kernels need not vanish (a vertical window gave 0.5 % DF).
    const bool facing_down = options.clip_to_horizon && n.x == 0 && n.y == 0 && n.z < 0;
    const bool below = facing_down || (options.clip_to_horizon &&
                                       std::all_of(wv.begin(), wv.end(), [&](const Vec3& v) { return v.z <= p.z; }));
    const bool behind = std::all_of(wv.begin(), wv.end(), [&](const Vec3& v) { return Signs::dot_diff(n, v, p) <= 0; });
    if (below || behind) {
      ++counters.pairs_not_facing;
      return;
    }
    std::vector<const ConvexPiece*> blockers, nearest;
    if (collect<Signs>(p, n, w, sh, options, blockers, nearest, counters) ||
        (mode != GeometryMode::floating && blockers.size() > 2 * nearest.size() && nearest_hide_all<Signs>(p, n, w, sh, options, nearest))) {
      ++counters.pairs_covered;
      return;
    }
    const bool reference = mode == GeometryMode::rational;
    const bool front_to_back = order_of_subtraction == SubtractionOrder::front_to_back;
    std::vector<int> pane;              // per blocker, with other apertures' panes among them
    std::vector<std::uint32_t> front;   // the apertures whose panes lie in front, by bit
    if (panes) collect_panes<Signs>(p, n, w, sh, options, blockers, pane, front, counters);
    // The unobstructed shortcut; where it declines (a large piece, or a vertex it cannot round
    // within 2^-45), the general clipper below, certified in the exact mode.
    const bool shortcut = blockers.empty() && !reference && unobstructed_directions<Signs>(p, n, w, sh, options, region);
    if (shortcut) {
      ++counters.pairs_unobstructed;
      return;
    }
    blockers.empty() ? ++counters.pairs_unobstructed : ++counters.pairs_clipped;
    counters.occluders_clipped += blockers.size();
    // Into `out` (tag 0: the region) and `tagged` (other tags: seen through panes in front).
    const auto clip = [&](auto number, SphericalRegion& out, std::vector<std::pair<std::uint64_t, SphericalRegion>>& tagged) {
      clipping::ShadowClipper<decltype(number), Signs> clipper(p, n, w, sh, options.clip_to_horizon, options.occluders_beyond, front_to_back);
      if (pane.empty()) {
        clipper.run(blockers, out, options.edge_sources);
      } else {
        clipper.run_tagged(blockers, pane, tagged, options.edge_sources);
        for (auto it = tagged.begin(); it != tagged.end(); ++it)
          if (it->first == 0) {
            for (auto& loop : it->second.loops) out.loops.push_back(std::move(loop));
            for (auto& sources : it->second.edge_sources) out.edge_sources.push_back(std::move(sources));
            tagged.erase(it);
            break;
          }
      }
      counters.occluders_skipped += clipper.skipped();
    };
    std::vector<std::pair<std::uint64_t, SphericalRegion>> tagged;
    if constexpr (std::is_same_v<FT, double>) {
      clip(0.0, region, tagged);
    } else {
      SphericalRegion certified;
      bool certain = !reference;
      if (certain) {
        try {
          CGAL::Protect_FPU_rounding<true> upward;
          clip(Interval(0), certified, tagged);
        } catch (const CGAL::Uncertain_conversion_exception&) {
          certain = false;
          tagged.clear();
        }
      }
      if (certain) {
        for (auto& loop : certified.loops) region.loops.push_back(std::move(loop));
        for (auto& sources : certified.edge_sources) region.edge_sources.push_back(std::move(sources));
      } else {
        ++counters.pairs_rational;
        clip(FT(0), region, tagged);
      }
    }
    for (auto& [tag, part] : tagged) {
      std::vector<std::uint32_t> through;
      for (std::size_t bit = 0; bit < front.size(); ++bit)
        if (tag >> bit & 1) through.push_back(front[bit]);
      // A direction through two panes in one plane crosses the plane once, in their overlap: the
      // earlier pane's alone.
      const std::vector<std::uint32_t> crossed = through;
      std::erase_if(through, [&](std::uint32_t t) {
        return std::any_of(crossed.begin(), crossed.end(), [&](std::uint32_t e) { return among(overlaps_later[e], t); });
      });
      std::sort(through.begin(), through.end());
      const std::uint32_t last = last_pane<Signs>(p, through);
      add_behind(view, std::move(through), std::move(part), last);
    }
  }

  static void add_behind(ApertureView& view, std::vector<std::uint32_t> through, SphericalRegion part, std::uint32_t last) {
    auto it = std::find_if(view.behind.begin(), view.behind.end(), [&](const PaneView& b) { return b.panes == through; });
    if (it == view.behind.end()) {
      view.behind.push_back({std::move(part), std::move(through), last});
      return;
    }
    for (auto& loop : part.loops) it->region.loops.push_back(std::move(loop));
    for (auto& sources : part.edge_sources) it->region.edge_sources.push_back(std::move(sources));
  }
};

VisibilityEngine::VisibilityEngine(const Scene& scene, GeometryMode mode, SubtractionOrder order, AperturesAre apertures)
    : impl_(std::make_unique<Impl>()) {
  impl_->mode = mode;
  impl_->order_of_subtraction = order;
  impl_->occluder_polygons = scene.occluders.size();
  for (std::size_t s = 0; s < scene.occluders.size(); ++s)
    for (auto& piece : convex_pieces(scene.occluders[s], s)) impl_->occluders.push_back(std::move(piece));
  for (const ConvexPiece& o : impl_->occluders) {
    Box b;
    for (const Vec3& v : o.vertices) b.add(v);
    impl_->occluder_boxes.push_back(b);
  }
  impl_->order.resize(impl_->occluders.size());
  std::iota(impl_->order.begin(), impl_->order.end(), 0);
  if (!impl_->occluders.empty()) {
    impl_->build(0, int(impl_->occluders.size()));
    impl_->rank_slots();
  }
  impl_->build_patches(scene.occluders.size());
  for (std::size_t a = 0; a < scene.apertures.size(); ++a) {
    impl_->apertures.push_back(convex_pieces(scene.apertures[a].polygon, a));
    impl_->aperture_pieces += impl_->apertures.back().size();
  }
  impl_->panes = apertures == AperturesAre::panes && scene.apertures.size() > 1;
  if (impl_->panes) {
    impl_->overlaps_earlier.resize(scene.apertures.size());
    impl_->overlaps_later.resize(scene.apertures.size());
    for (const auto& [earlier, later] : overlapping_coplanar_panes(impl_->apertures)) {
      impl_->overlaps_earlier[later].push_back(std::uint32_t(earlier));
      impl_->overlaps_later[earlier].push_back(std::uint32_t(later));
    }
  }
  if (impl_->panes)
    for (const auto& pieces : impl_->apertures) {
      impl_->pane_first.push_back(impl_->pane_pieces.size());
      for (const ConvexPiece& q : pieces) {
        impl_->pane_pieces.push_back(q);
        Box b;
        for (const Vec3& v : q.vertices) b.add(v);
        impl_->pane_boxes.push_back(b);
      }
    }
  if (impl_->panes) {
    impl_->pane_first.push_back(impl_->pane_pieces.size());
    impl_->cut_crossing_panes();
  }
}

VisibilityEngine::~VisibilityEngine() = default;
VisibilityEngine::VisibilityEngine(VisibilityEngine&&) noexcept = default;
VisibilityEngine& VisibilityEngine::operator=(VisibilityEngine&&) noexcept = default;

std::size_t VisibilityEngine::aperture_count() const noexcept { return impl_->apertures.size(); }
std::size_t VisibilityEngine::occluder_piece_count() const noexcept { return impl_->occluders.size(); }
std::size_t VisibilityEngine::aperture_piece_count() const noexcept { return impl_->aperture_pieces; }
GeometryMode VisibilityEngine::mode() const noexcept { return impl_->mode; }
SubtractionOrder VisibilityEngine::order() const noexcept { return impl_->order_of_subtraction; }
bool VisibilityEngine::panes_interact() const noexcept { return impl_->panes; }

SphericalRegion VisibilityEngine::visible_region(const Vec3& p, const Vec3& n, std::size_t aperture,
                                                 VisibilityCounters& counters) const {
  return visible_region(p, n, aperture, counters, VisibilityOptions{});
}

SphericalRegion VisibilityEngine::visible_region(const Vec3& p, const Vec3& n, std::size_t aperture, VisibilityCounters& counters,
                                                 const VisibilityOptions& options) const {
  return aperture_view(p, n, aperture, counters, options).region;
}

ApertureView VisibilityEngine::aperture_view(const Vec3& p, const Vec3& n, std::size_t aperture, VisibilityCounters& counters,
                                             const VisibilityOptions& options) const {
  ApertureView view;
  for (const ConvexPiece& piece : impl_->apertures.at(aperture)) {
    ApertureView part;
    if (impl_->mode != GeometryMode::floating)
      impl_->evaluate<ExactSigns, LazyExact>(p, n, piece, options, part, counters);
    else
      impl_->evaluate<FloatSigns, double>(p, n, piece, options, part, counters);
    for (auto& loop : part.region.loops) view.region.loops.push_back(std::move(loop));
    for (auto& sources : part.region.edge_sources) view.region.edge_sources.push_back(std::move(sources));
    for (auto& b : part.behind) Impl::add_behind(view, std::move(b.panes), std::move(b.region), b.last);
  }
  return view;
}

}  // namespace daylit
