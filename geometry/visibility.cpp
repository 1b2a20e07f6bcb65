// Exact visible regions (DESIGN.md §2), generic over the number type: the exact path runs the
// algorithm below on CGAL's lazy exact rationals (interval arithmetic first, GMP rationals only
// where an interval cannot decide), the float path runs the very same code on doubles.
//
// Per receiver p and convex aperture piece W:
//   1. cull occluder pieces: bounding boxes against the planes of the view cone in double with a
//      wide margin, then exact predicates on the input coordinates (filtered, so mostly doubles);
//   2. if none survives, clip W to the receiver's hemisphere and horizon in double: no exact work;
//   3. otherwise clip W, clip each survivor to the cone over W, project it centrally onto W's
//      plane, subtract the (convex) shadows from W piece by piece, and round the result once.
// Step 3 runs first in interval arithmetic: if every sign it decides is certain, its combinatorics
// are those of the exact computation and the output intervals enclose the exact coordinates (we
// accept them when narrower than 2^-45 relative). Any uncertain sign (a degenerate configuration:
// a shared edge, a coplanar face) aborts it, and the pair is redone in exact rationals. This is
// CGAL's filtering paradigm lifted from predicates to the whole algorithm.

#include "geometry/visibility.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Lazy_exact_nt.h>
#include <mpfr.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <type_traits>

#include "geometry/convex_pieces.hpp"

namespace daylit {

namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using LazyExact = CGAL::Lazy_exact_nt<CGAL::Gmpq>;

Epick::Point_3 point3(const Vec3& v) { return {v.x, v.y, v.z}; }

// ---------------------------------------------------------------------------------------------
// Signs of the culling predicates.

// Interval arithmetic first; exact rationals only when the interval contains zero. This is the
// filter of CGAL's Filtered_predicate, written out for expressions that are not kernel predicates.
template <class Expr>
int filtered_sign(const Expr& expr) {
  {
    CGAL::Protect_FPU_rounding<true> guard;
    const CGAL::Interval_nt<false> r = expr(CGAL::Interval_nt<false>(0));
    if (r.inf() > 0) return 1;
    if (r.sup() < 0) return -1;
    if (r.inf() == 0 && r.sup() == 0) return 0;
  }
  return int(CGAL::sign(expr(CGAL::Gmpq(0))));
}

template <class T>
T dot_diff(const Vec3& n, const Vec3& v, const Vec3& p) {
  return T(n.x) * (T(v.x) - T(p.x)) + T(n.y) * (T(v.y) - T(p.y)) + T(n.z) * (T(v.z) - T(p.z));
}

// ((a − o) × (b − o)) · (v − p)
template <class T>
T normal_dot_diff(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& v, const Vec3& p) {
  const T ax = T(a.x) - T(o.x), ay = T(a.y) - T(o.y), az = T(a.z) - T(o.z);
  const T bx = T(b.x) - T(o.x), by = T(b.y) - T(o.y), bz = T(b.z) - T(o.z);
  return (ay * bz - az * by) * (T(v.x) - T(p.x)) + (az * bx - ax * bz) * (T(v.y) - T(p.y)) +
         (ax * by - ay * bx) * (T(v.z) - T(p.z));
}

struct ExactSigns {
  static int orient3(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    return int(CGAL::orientation(point3(p), point3(a), point3(b), point3(c)));
  }
  static int dot_diff(const Vec3& n, const Vec3& v, const Vec3& p) {
    return filtered_sign([&](auto zero) { return daylit::dot_diff<decltype(zero)>(n, v, p); });
  }
  static int normal_dot_diff(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& v, const Vec3& p) {
    return filtered_sign([&](auto zero) { return daylit::normal_dot_diff<decltype(zero)>(o, a, b, v, p); });
  }
};

using Interval = CGAL::Interval_nt<false>;

int sign_of(double x) { return (x > 0) - (x < 0); }
int sign_of(const LazyExact& x) { return int(CGAL::sign(x)); }
// Throws CGAL::Uncertain_conversion_exception when the interval contains zero but is not zero.
int sign_of(const Interval& x) { return int(CGAL::make_certain(CGAL::sign(x))); }

struct FloatSigns {
  static int orient3(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    return sign_of(dot(cross(a - p, b - p), c - p));
  }
  static int dot_diff(const Vec3& n, const Vec3& v, const Vec3& p) { return sign_of(daylit::dot_diff<double>(n, v, p)); }
  static int normal_dot_diff(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& v, const Vec3& p) {
    return sign_of(daylit::normal_dot_diff<double>(o, a, b, v, p));
  }
};

// ---------------------------------------------------------------------------------------------
// Rounding the exact result to double, once.

// Faithful to within 2^-50 relative when the lazy interval is already that tight; otherwise the
// exact rational is rounded to nearest through MPFR (CGAL::to_double may return an interval
// midpoint far from the value, and mpq_get_d truncates: DESIGN.md §7).
double round_to_double(const LazyExact& x) {
  const auto [lo, hi] = CGAL::to_interval(x);
  if (lo == hi) return lo;
  if ((lo > 0 || hi < 0) && hi - lo <= 0x1p-50 * std::min(std::abs(lo), std::abs(hi))) return lo + 0.5 * (hi - lo);
  const CGAL::Gmpq& q = x.exact();
  mpfr_t r;
  mpfr_init2(r, 53);
  mpfr_set_q(r, q.mpq(), MPFR_RNDN);
  const double d = mpfr_get_d(r, MPFR_RNDN);
  mpfr_clear(r);
  return d;
}
double round_to_double(double x) { return x; }
// The midpoint of a narrow interval; a wide one sends the pair to exact arithmetic.
double round_to_double(const Interval& x) {
  const double lo = x.inf(), hi = x.sup();
  if (lo == hi) return lo;
  if ((lo > 0 || hi < 0) && hi - lo <= 0x1p-45 * std::min(std::abs(lo), std::abs(hi))) return lo + 0.5 * (hi - lo);
  throw CGAL::Uncertain_conversion_exception("interval too wide to round");
}

// ---------------------------------------------------------------------------------------------
// Small point types over a number type FT.

// Points remember whether they are input coordinates (`input` points at the input vertex). The
// sign of an affine function at an input point, against a plane or line through input points, is
// an exact predicate on input doubles (CGAL's filtered orientation), so the shared vertices and
// edges that architectural models are made of (reveals, coplanar walls) never need rationals.
//
// Points also carry `cone_edge`: the edge from this vertex to the next lies on side plane number
// cone_edge of the view cone (−1: not known to). Clipping to the cone creates such edges in every
// shadow, and they lie exactly on the aperture's boundary, so the subtraction may skip them: no
// sign needs deciding there.
template <class FT>
struct P3 {
  FT c[3];
  const Vec3* input = nullptr;
  int cone_edge = -1;
  const FT& operator[](int i) const { return c[i]; }
};
template <class FT>
struct P2 {
  FT u, v;
  const Vec3* input = nullptr;  // the point is this input vertex with the drop axis removed
  int cone_edge = -1;
};

template <class FT>
P3<FT> to_p3(const Vec3& v) {
  return {{FT(v.x), FT(v.y), FT(v.z)}, nullptr};
}
template <class FT>
P3<FT> input_p3(const Vec3& v) {
  return {{FT(v.x), FT(v.y), FT(v.z)}, &v};
}
template <class FT>
P3<FT> operator-(const P3<FT>& a, const P3<FT>& b) {
  return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}};
}
template <class FT>
FT dot(const P3<FT>& a, const P3<FT>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <class FT>
P3<FT> cross(const P3<FT>& a, const P3<FT>& b) {
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}, nullptr};
}
template <class FT>
P3<FT> lerp(const P3<FT>& a, const P3<FT>& b, const FT& t) {
  return {{a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t}, nullptr, a.cone_edge};
}
template <class FT>
P2<FT> lerp(const P2<FT>& a, const P2<FT>& b, const FT& t) {
  return {a.u + (b.u - a.u) * t, a.v + (b.v - a.v) * t, nullptr, a.cone_edge};
}

// One step of Sutherland–Hodgman on a convex polygon: the part where side·f ≥ 0, given the values
// f of an affine function at the vertices. New vertices only where the sign strictly changes, so
// no duplicates arise. The edge that runs along the cutting line is tagged `cut_tag`.
template <class Pt, class FT>
std::vector<Pt> keep_side(const std::vector<Pt>& poly, const std::vector<FT>& f, const std::vector<int>& s, int side,
                          int cut_tag = -1) {
  std::vector<Pt> out;
  out.reserve(poly.size() + 1);
  const std::size_t m = poly.size();
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t j = (i + 1) % m;
    if (s[i] * side >= 0) {
      out.push_back(poly[i]);
      // On the line, heading out: the next kept point is the entry point, along the line.
      if (s[i] == 0 && s[j] * side < 0) out.back().cone_edge = cut_tag;
    }
    if (s[i] * s[j] < 0) {
      out.push_back(lerp(poly[i], poly[j], FT(f[i] / (f[i] - f[j]))));
      if (s[i] * side > 0) out.back().cone_edge = cut_tag;  // exit point: the edge to the entry point
    }
  }
  return out;
}

template <class FT>
struct Signed {
  std::vector<FT> value;
  std::vector<int> sign;
  bool any_positive = false, any_negative = false;

  // `exact_sign`, when the caller could decide the sign by an exact predicate, overrides the
  // sign of the value (an interval may straddle zero where the true value is zero or tiny).
  void push(FT v, std::optional<int> exact_sign = std::nullopt) {
    const int s = exact_sign ? *exact_sign : sign_of(v);
    any_positive |= s > 0;
    any_negative |= s < 0;
    value.push_back(std::move(v));
    sign.push_back(s);
  }
};

Epick::Point_2 drop(const Vec3& v, int k) { return {v[(k + 1) % 3], v[(k + 2) % 3]}; }

// Reverses a loop, keeping each edge tag on its edge (which now starts at the other end).
template <class Pt>
void reverse_loop(std::vector<Pt>& loop) {
  std::vector<int> tags;
  for (const Pt& x : loop) tags.push_back(x.cone_edge);
  const std::size_t m = loop.size();
  std::reverse(loop.begin(), loop.end());
  // Old edge i → i+1 becomes new edge (m−1−(i+1)) → (m−1−i).
  for (std::size_t i = 0; i < m; ++i) loop[(2 * m - 2 - i) % m].cone_edge = tags[i];
}

// P − C for convex P and C (both counter-clockwise, in the coordinates that drop axis k),
// appended to `out` as convex pieces.
template <class FT>
void subtract_convex(const std::vector<P2<FT>>& P, const std::vector<P2<FT>>& C, int k,
                     std::vector<std::vector<P2<FT>>>& out) {
  std::vector<P2<FT>> rest = P;
  for (std::size_t e = 0; e < C.size(); ++e) {
    const P2<FT>& a = C[e];
    const P2<FT>& b = C[(e + 1) % C.size()];
    if (a.cone_edge >= 0) continue;  // on the aperture's boundary: all of P is inside
    const FT du = b.u - a.u, dv = b.v - a.v;
    Signed<FT> side;  // > 0: inside C's half-plane
    for (const auto& x : rest) {
      std::optional<int> exact;
      if (a.input && b.input && x.input)
        exact = int(CGAL::orientation(drop(*a.input, k), drop(*b.input, k), drop(*x.input, k)));
      side.push(du * (x.v - a.v) - dv * (x.u - a.u), exact);
    }
    if (!side.any_negative) continue;
    if (!side.any_positive) {
      out.push_back(std::move(rest));
      return;
    }
    out.push_back(keep_side(rest, side.value, side.sign, -1));
    rest = keep_side(rest, side.value, side.sign, +1);
  }
  // What remains lies inside C: in shadow.
}

// ---------------------------------------------------------------------------------------------
// Culling hierarchy.

struct Box {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void add(const Vec3& v) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  void add(const Box& b) {
    add(b.lo);
    add(b.hi);
  }
  Vec3 center() const { return 0.5 * (lo + hi); }
  Vec3 half() const { return 0.5 * (hi - lo); }
};

// A plane through the receiver, m·(x − p) ≥ 0 on the side that may matter, known in double only
// approximately; `scale` bounds |m| before cancellation so that the margin covers its rounding.
struct CullPlane {
  Vec3 m;
  double scale;
};

// True if the box lies certainly on the negative side of the plane. The margin (1e-10 of the
// magnitudes involved) exceeds the rounding of m and of the evaluation by orders of magnitude, so
// nothing that might touch the cone is culled here; the exact predicates decide the rest.
bool box_outside(const Box& box, const CullPlane& plane, const Vec3& p) {
  const Vec3 c = box.center() - p, h = box.half();
  const double reach = dot(plane.m, c) + std::abs(plane.m.x) * h.x + std::abs(plane.m.y) * h.y + std::abs(plane.m.z) * h.z;
  const double margin = 1e-10 * plane.scale * (norm(c) + norm(h));
  return reach < -margin;
}

struct BvhNode {
  Box box;
  int left = -1, right = -1;  // children, or -1 for a leaf
  int first = 0, count = 0;   // leaf: range in the ordered piece indices
};

}  // namespace

// ---------------------------------------------------------------------------------------------

struct VisibilityEngine::Impl {
  GeometryMode mode;
  std::vector<ConvexPiece> occluders;
  std::vector<Box> occluder_boxes;
  std::vector<int> order;  // piece indices in BVH leaf order
  std::vector<BvhNode> nodes;
  std::vector<std::vector<ConvexPiece>> apertures;
  std::size_t aperture_pieces = 0;

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
  bool survives(const ConvexPiece& o, const Vec3& p, const Vec3& n, const ConvexPiece& w, int sh) const {
    const auto& ov = o.vertices;
    const auto& wv = w.vertices;
    const auto all = [&](auto&& pred) { return std::all_of(ov.begin(), ov.end(), pred); };
    if (all([&](const Vec3& v) { return v.z <= p.z; })) return false;
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
    // through p itself casts a shadow of zero area.
    const Vec3 &o0 = ov[0], &ob = ov[o.base_b], &oc = ov[o.base_c];
    const int sp = Signs::orient3(o0, ob, oc, p);
    if (sp == 0) return false;
    return !std::all_of(wv.begin(), wv.end(), [&](const Vec3& v) { return sp * Signs::normal_dot_diff(o0, ob, oc, v, p) >= 0; });
  }

  template <class Signs>
  void collect(const Vec3& p, const Vec3& n, const ConvexPiece& w, int sh, std::vector<const ConvexPiece*>& out,
               VisibilityCounters& counters) const {
    if (nodes.empty()) return;
    // Planes of the cone, m·(x − p) ≥ 0 inside, in double for the box tests.
    std::vector<CullPlane> planes;
    planes.push_back({n, 1});
    planes.push_back({{0, 0, 1}, 1});
    const auto& wv = w.vertices;
    const Vec3 eb = wv[w.base_b] - wv[0], ec = wv[w.base_c] - wv[0];
    planes.push_back({double(-sh) * cross(eb, ec), norm(eb) * norm(ec)});
    for (std::size_t e = 0; e < wv.size(); ++e) {
      const Vec3 a = wv[e] - p, b = wv[(e + 1) % wv.size()] - p;
      planes.push_back({double(-sh) * cross(a, b), norm(a) * norm(b)});
    }
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const BvhNode& node = nodes[stack[--top]];
      const bool outside = std::any_of(planes.begin(), planes.end(), [&](const CullPlane& pl) { return box_outside(node.box, pl, p); });
      if (outside) {
        counters.occluders_box_culled += node.left < 0 ? node.count : 1;
        continue;
      }
      if (node.left >= 0) {
        stack[top++] = node.left;
        stack[top++] = node.right;
        continue;
      }
      for (int i = node.first; i < node.first + node.count; ++i) {
        const ConvexPiece& o = occluders[order[i]];
        if (std::any_of(planes.begin(), planes.end(), [&](const CullPlane& pl) { return box_outside(occluder_boxes[order[i]], pl, p); })) {
          ++counters.occluders_box_culled;
          continue;
        }
        ++counters.occluders_tested;
        if (survives<Signs>(o, p, n, w, sh)) out.push_back(&o);
      }
    }
  }

  // Steps 2–3 of the file comment in number type FT; `Signs` decides predicates on input points.
  template <class FT, class Signs>
  static void clip_and_subtract(const Vec3& p_in, const Vec3& n_in, const ConvexPiece& piece, int sh,
                                const std::vector<const ConvexPiece*>& blockers, SphericalRegion& region) {
    using Pt = P3<FT>;
    const Pt p = to_p3<FT>(p_in);
    const Pt n = to_p3<FT>(n_in);
    const auto& wv = piece.vertices;
    std::vector<Pt> w;
    for (const Vec3& v : wv) w.push_back(input_p3<FT>(v));
    const Pt w0 = w[0];
    const Pt N = cross(w[piece.base_b] - w0, w[piece.base_c] - w0);

    // Receiver's hemisphere and horizon.
    for (int plane = 0; plane < 2; ++plane) {
      Signed<FT> f;
      for (const Pt& x : w) {
        std::optional<int> exact;
        if (x.input) exact = plane == 0 ? Signs::dot_diff(n_in, *x.input, p_in) : sign_of(x.input->z - p_in.z);
        f.push(plane == 0 ? dot(n, x - p) : FT(x[2] - p[2]), exact);
      }
      if (!f.any_positive) return;
      if (f.any_negative) w = keep_side(w, f.value, f.sign, +1);
    }

    // Shadows: survivors clipped to the cone over w, projected from p onto the aperture's plane.
    const int k = piece.drop_axis, i = (k + 1) % 3, j = (k + 2) % 3;
    const FT minus_h = dot(N, w0 - p);
    const int inside = -sh;
    std::vector<Pt> side_normals;
    for (std::size_t e = 0; e < w.size(); ++e) {
      const Pt m = cross(w[e] - p, w[(e + 1) % w.size()] - p);
      side_normals.push_back(inside < 0 ? Pt{{-m[0], -m[1], -m[2]}, nullptr} : m);
    }
    std::vector<std::vector<P2<FT>>> shadows;
    for (const ConvexPiece* blocker : blockers) {
      const auto& ov = blocker->vertices;
      if (Signs::orient3(ov[0], ov[blocker->base_b], ov[blocker->base_c], p_in) == 0) continue;  // edge-on
      std::vector<Pt> o;
      for (const Vec3& v : ov) o.push_back(input_p3<FT>(v));
      bool empty = false;
      for (std::size_t e = 0; e < side_normals.size() && !empty; ++e) {
        const Pt& a = w[e];
        const Pt& b = w[(e + 1) % w.size()];
        Signed<FT> f;
        for (const Pt& x : o) {
          std::optional<int> exact;
          if (a.input && b.input && x.input) exact = inside * Signs::orient3(p_in, *a.input, *b.input, *x.input);
          f.push(dot(side_normals[e], x - p), exact);
        }
        if (!f.any_positive) empty = true;
        else if (f.any_negative) o = keep_side(o, f.value, f.sign, +1, int(e));
      }
      if (empty) continue;
      std::vector<P2<FT>> shadow;
      for (const Pt& x : o) {
        // An input vertex in the aperture's plane is its own projection.
        if (x.input && Signs::orient3(wv[0], wv[piece.base_b], wv[piece.base_c], *x.input) == 0) {
          shadow.push_back({x[i], x[j], x.input, x.cone_edge});
          continue;
        }
        const Pt d = x - p;
        const FT t = minus_h / dot(N, d);
        shadow.push_back({p[i] + d[i] * t, p[j] + d[j] * t, nullptr, x.cone_edge});
      }
      FT area2(0);
      for (std::size_t a = 0; a < shadow.size(); ++a) {
        const auto& s0 = shadow[a];
        const auto& s1 = shadow[(a + 1) % shadow.size()];
        area2 += (s0.u - shadow[0].u) * (s1.v - shadow[0].v) - (s1.u - shadow[0].u) * (s0.v - shadow[0].v);
      }
      const int orientation = sign_of(area2);
      if (orientation == 0) continue;
      if (orientation < 0) reverse_loop(shadow);
      shadows.push_back(std::move(shadow));
    }

    std::vector<std::vector<P2<FT>>> pieces(1);
    for (const Pt& x : w) pieces[0].push_back({x[i], x[j], x.input});
    for (const auto& shadow : shadows) {
      std::vector<std::vector<P2<FT>>> next;
      for (const auto& P : pieces) subtract_convex(P, shadow, k, next);
      pieces = std::move(next);
      if (pieces.empty()) return;
    }

    // Lift to the aperture's plane, x_k = w0_k − (N_i (u − w0_i) + N_j (v − w0_j)) / N_k, and take
    // directions from p. A counter-clockwise piece is a positive loop when h < 0 (see survives()).
    for (const auto& P : pieces) {
      DirectionLoop loop;
      loop.reserve(P.size());
      for (const auto& x : P) {
        double d[3];
        if (x.input) {
          // Input vertices need no lifting; x − p rounds once.
          d[i] = round_to_double(FT(FT(x.input->operator[](i)) - p[i]));
          d[j] = round_to_double(FT(FT(x.input->operator[](j)) - p[j]));
          d[k] = round_to_double(FT(FT(x.input->operator[](k)) - p[k]));
        } else {
          const FT xk = w0[k] - (N[i] * (x.u - w0[i]) + N[j] * (x.v - w0[j])) / N[k];
          d[i] = round_to_double(FT(x.u - p[i]));
          d[j] = round_to_double(FT(x.v - p[j]));
          d[k] = round_to_double(FT(xk - p[k]));
        }
        loop.push_back({d[0], d[1], d[2]});
      }
      if (sh > 0) std::reverse(loop.begin(), loop.end());
      region.loops.push_back(std::move(loop));
    }
  }

  template <class Signs, class FT>
  void evaluate(const Vec3& p, const Vec3& n, const ConvexPiece& w, SphericalRegion& region, VisibilityCounters& counters) const {
    ++counters.pairs;
    const auto& wv = w.vertices;
    const int sh = Signs::normal_dot_diff(wv[0], wv[w.base_b], wv[w.base_c], p, wv[0]);
    if (sh == 0) {
      ++counters.pairs_not_facing;
      return;
    }
    // Whole piece behind the receiver or below its horizon: nothing to do.
    const bool below = std::all_of(wv.begin(), wv.end(), [&](const Vec3& v) { return v.z <= p.z; });
    const bool behind = std::all_of(wv.begin(), wv.end(), [&](const Vec3& v) { return Signs::dot_diff(n, v, p) <= 0; });
    if (below || behind) {
      ++counters.pairs_not_facing;
      return;
    }
    std::vector<const ConvexPiece*> blockers;
    collect<Signs>(p, n, w, sh, blockers, counters);
    if (blockers.empty()) {
      ++counters.pairs_unobstructed;
      clip_and_subtract<double, Signs>(p, n, w, sh, blockers, region);
    } else {
      ++counters.pairs_clipped;
      counters.occluders_clipped += blockers.size();
      if constexpr (std::is_same_v<FT, double>) {
        clip_and_subtract<double, Signs>(p, n, w, sh, blockers, region);
      } else {
        SphericalRegion certified;
        bool certain = true;
        try {
          CGAL::Protect_FPU_rounding<true> upward;
          clip_and_subtract<Interval, Signs>(p, n, w, sh, blockers, certified);
        } catch (const CGAL::Uncertain_conversion_exception&) {
          certain = false;
        }
        if (certain) {
          for (auto& loop : certified.loops) region.loops.push_back(std::move(loop));
        } else {
          ++counters.pairs_rational;
          clip_and_subtract<FT, Signs>(p, n, w, sh, blockers, region);
        }
      }
    }
  }
};

VisibilityEngine::VisibilityEngine(const Scene& scene, GeometryMode mode) : impl_(std::make_unique<Impl>()) {
  impl_->mode = mode;
  for (std::size_t s = 0; s < scene.occluders.size(); ++s)
    for (auto& piece : convex_pieces(scene.occluders[s], s)) impl_->occluders.push_back(std::move(piece));
  for (const ConvexPiece& o : impl_->occluders) {
    Box b;
    for (const Vec3& v : o.vertices) b.add(v);
    impl_->occluder_boxes.push_back(b);
  }
  impl_->order.resize(impl_->occluders.size());
  std::iota(impl_->order.begin(), impl_->order.end(), 0);
  if (!impl_->occluders.empty()) impl_->build(0, int(impl_->occluders.size()));
  for (std::size_t a = 0; a < scene.apertures.size(); ++a) {
    impl_->apertures.push_back(convex_pieces(scene.apertures[a].polygon, a));
    impl_->aperture_pieces += impl_->apertures.back().size();
  }
}

VisibilityEngine::~VisibilityEngine() = default;
VisibilityEngine::VisibilityEngine(VisibilityEngine&&) noexcept = default;
VisibilityEngine& VisibilityEngine::operator=(VisibilityEngine&&) noexcept = default;

std::size_t VisibilityEngine::aperture_count() const noexcept { return impl_->apertures.size(); }
std::size_t VisibilityEngine::occluder_piece_count() const noexcept { return impl_->occluders.size(); }
std::size_t VisibilityEngine::aperture_piece_count() const noexcept { return impl_->aperture_pieces; }
GeometryMode VisibilityEngine::mode() const noexcept { return impl_->mode; }

SphericalRegion VisibilityEngine::visible_region(const Vec3& p, const Vec3& n, std::size_t aperture,
                                                 VisibilityCounters& counters) const {
  SphericalRegion region;
  for (const ConvexPiece& piece : impl_->apertures.at(aperture)) {
    if (impl_->mode == GeometryMode::exact)
      impl_->evaluate<ExactSigns, LazyExact>(p, n, piece, region, counters);
    else
      impl_->evaluate<FloatSigns, double>(p, n, piece, region, counters);
  }
  return region;
}

}  // namespace daylit
