#pragma once
// Step 3 of the visibility routine (DESIGN.md §2), generic over the number type FT: clip the
// aperture piece to the receiver's hemisphere and horizon, clip each occluder piece to the view
// cone, project it centrally onto the aperture's plane, subtract the convex shadows piece by
// piece. Internal to geometry/visibility.cpp.
//
// FT = double is the float path. FT = Interval (CGAL's interval arithmetic) and FT = LazyExact
// (CGAL's lazy exact rationals) form the exact path, with two helps for sign decisions:
//  - Provenance. Every vertex knows the line its outgoing edge lies on (an aperture or occluder
//    edge between input vertices, the receiver's horizon or tangent plane, or a side plane of the
//    view cone) and, where it has one, the input vertex it is (or projects from). A vertex on the
//    line it is tested against has sign 0 by construction, and the sign of an input vertex
//    against a plane through input vertices and p is an exact predicate on input doubles. These
//    are precisely the degeneracies buildings are made of: shared vertices and edges, reveals,
//    coplanar walls, triangulated faces. Every shadow edge cut by the view cone lies on the
//    aperture's boundary and is skipped in the subtraction.
//  - Intervals. Every other sign is read off an interval; one that contains zero throws
//    CGAL::Uncertain_conversion_exception, and the caller redoes the pair in exact rationals.

#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Lazy_exact_nt.h>
#include <mpfr.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "geometry/convex_pieces.hpp"
#include "geometry/predicates.hpp"
#include "geometry/spherical_region.hpp"

namespace daylit::clipping {

using Interval = CGAL::Interval_nt<false>;
using LazyExact = CGAL::Lazy_exact_nt<CGAL::Gmpq>;
using predicates::sign_of;

inline int sign_of(const LazyExact& x) { return int(CGAL::sign(x)); }
inline int sign_of(const CGAL::Gmpq& x) { return int(CGAL::sign(x)); }
// Throws CGAL::Uncertain_conversion_exception when the interval contains zero but is not zero.
inline int sign_of(const Interval& x) { return int(CGAL::make_certain(CGAL::sign(x))); }

// ---------------------------------------------------------------------------------------------
// Rounding the result to double, once.

inline double round_to_double(double x, double = 0) { return x; }

// The midpoint of an interval that is narrow against `scale` (the magnitude of the vector the
// value is a component of: directions matter to the kernels relative to their length); a wider
// one throws, and the caller rebuilds that vertex in rationals. Accepted midpoints are within
// 2^-45 (2.8e-14) of `scale` of the exact value; the tests hold the results to the all-rational
// reference within 1e-12 (observed: 1.2e-13 on the office sample).
inline double round_to_double(const Interval& x, double scale) {
  const double lo = x.inf(), hi = x.sup();
  if (hi - lo <= 0x1p-44 * scale) return lo + 0.5 * (hi - lo);
  throw CGAL::Uncertain_conversion_exception("interval too wide to round");
}

// Within 2^-50 relative when the lazy interval is already that tight; otherwise the exact
// rational rounded to nearest through MPFR (CGAL::to_double may return an interval midpoint far
// from the value, and mpq_get_d truncates: DESIGN.md §7).
inline double round_rational(const CGAL::Gmpq& q) {
  mpfr_t r;
  mpfr_init2(r, 53);
  mpfr_set_q(r, q.mpq(), MPFR_RNDN);
  const double d = mpfr_get_d(r, MPFR_RNDN);
  mpfr_clear(r);
  return d;
}
inline double round_to_double(const LazyExact& x, double = 0) {
  const auto [lo, hi] = CGAL::to_interval(x);
  if (lo == hi) return lo;
  if ((lo > 0 || hi < 0) && hi - lo <= 0x1p-50 * std::min(std::abs(lo), std::abs(hi))) return lo + 0.5 * (hi - lo);
  return round_rational(x.exact());
}

// ---------------------------------------------------------------------------------------------
// Planes from the input, in any number type.

// The normal N of a convex piece's plane, from its base triple, and its offset h = N·(v0 − p)
// from the receiver p: the side p lies on is −sign(h).
template <class T>
void piece_plane(const ConvexPiece& c, const Vec3& p, std::array<T, 3>& N, T& h) {
  const auto& v = c.vertices;
  const Vec3 &o = v[0], &b = v[std::size_t(c.base_b)], &d = v[std::size_t(c.base_c)];
  const std::array<T, 3> e1{T(b.x) - T(o.x), T(b.y) - T(o.y), T(b.z) - T(o.z)};
  const std::array<T, 3> e2{T(d.x) - T(o.x), T(d.y) - T(o.y), T(d.z) - T(o.z)};
  N = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  h = N[0] * (T(o.x) - T(p.x)) + N[1] * (T(o.y) - T(p.y)) + N[2] * (T(o.z) - T(p.z));
}

// Normal of the plane through p that contains the segment ab: (a − p) × (b − a), equal to
// (a − p) × (b − p) but without its cancellation when the segment is short against its distance
// (DESIGN.md §7, edge terms): the products are |a − p|·|b − a| in size, not |a − p|·|b − p|.
template <class T>
std::array<T, 3> segment_plane_normal(const Vec3& a_in, const Vec3& b_in, const Vec3& p) {
  const std::array<T, 3> a{T(a_in.x) - T(p.x), T(a_in.y) - T(p.y), T(a_in.z) - T(p.z)};
  const std::array<T, 3> e{T(b_in.x) - T(a_in.x), T(b_in.y) - T(a_in.y), T(b_in.z) - T(a_in.z)};
  return {a[1] * e[2] - a[2] * e[1], a[2] * e[0] - a[0] * e[2], a[0] * e[1] - a[1] * e[0]};
}

// ---------------------------------------------------------------------------------------------
// Arcs nearly π long.

// A direction halfway along an arc nearly π long. Its ends are nearly opposite, so the great
// circle through their rounded directions turns by u/δ (δ their distance from antipodal), and
// when δ nears u not even the side of the sphere the arc takes is decided: a receiver within
// 1e-12 of an aperture's plane, inside its outline, sees the cut along its tangent plane run
// between nearly opposite directions, and its region came out 1.5e-3 sr short of 3.1416 in both
// exact modes (fuzz_visibility). The arc lies on the plane through p with normal M, and every
// direction along it meets the aperture's plane (normal N, offset h from p) ahead, h N·d > 0: it
// is part of the half circle {M·d = 0, h N·d > 0}, whose middle is sign(h)·((M·M)N − (N·M)M),
// and an arc longer than 154° of a half circle contains its middle. With that vertex the arc is
// two arcs of at most 116°, each as well conditioned as any. Built in rationals from the input
// doubles and rounded once (a rare path); nothing when p lies in the aperture's plane (h = 0: the
// region has no area) or M ∥ N (no such arc).
inline std::optional<Vec3> opposite_arc_midpoint(const std::array<CGAL::Gmpq, 3>& M, const std::array<CGAL::Gmpq, 3>& N,
                                                 const CGAL::Gmpq& h) {
  const int side = CGAL::sign(h);
  if (side == 0) return std::nullopt;
  const CGAL::Gmpq mm = M[0] * M[0] + M[1] * M[1] + M[2] * M[2], nm = N[0] * M[0] + N[1] * M[1] + N[2] * M[2];
  Vec3 d;
  double* out[3] = {&d.x, &d.y, &d.z};
  for (int k = 0; k < 3; ++k) *out[k] = side * round_rational(mm * N[k] - nm * M[k]);
  if (!(norm(d) > 0) || !is_finite(d)) return std::nullopt;
  return normalized(d);
}

// ---------------------------------------------------------------------------------------------
// Provenance.

// The line (or, in 3D, the plane through the receiver) an edge lies on. `aperture_plane` is where
// an occluder's plane meets the aperture's: the edge along which an occluder that crosses a
// luminaire's plane is cut (VisibilityOptions::occluders_beyond = false).
struct LineId {
  enum class Kind : std::uint8_t { unknown, segment, hemisphere, horizon, cone, aperture_plane };
  Kind kind = Kind::unknown;
  int index = -1;                              // cone: the aperture edge; aperture_plane: the blocker
  const Vec3* a = nullptr, *b = nullptr;       // segment: its input endpoints

  static LineId segment(const Vec3& a, const Vec3& b) { return {Kind::segment, -1, &a, &b}; }
  static LineId cone(int e) { return {Kind::cone, e, nullptr, nullptr}; }
  static LineId aperture_plane(int blocker) { return {Kind::aperture_plane, blocker, nullptr, nullptr}; }
  static LineId named(Kind k) { return {k, -1, nullptr, nullptr}; }
};

// Whether two identities denote the same line. Segments are the same line when their endpoints
// are collinear (an exact predicate), so the shared edge of two occluder pieces (two triangles of
// one wall, two faces of a box) and collinear edges of different lengths (a ceiling tiled around
// openings) are recognised.
inline bool same_line(const LineId& x, const LineId& y) {
  if (x.kind != y.kind || x.kind == LineId::Kind::unknown) return false;
  // Two blockers' cuts are told apart even when the blockers are coplanar (two triangles of one
  // wall): the signs that identity would give are then exact zeros of planes_share_line and the
  // determinants, decided in multiprecision instead.
  if (x.kind == LineId::Kind::cone || x.kind == LineId::Kind::aperture_plane) return x.index == y.index;
  if (x.kind == LineId::Kind::segment) {
    if ((*x.a == *y.a && *x.b == *y.b) || (*x.a == *y.b && *x.b == *y.a)) return true;
    using predicates::point3;
    return CGAL::collinear(point3(*x.a), point3(*x.b), point3(*y.a)) &&
           CGAL::collinear(point3(*x.a), point3(*x.b), point3(*y.b));
  }
  return true;
}

// Whether two identities are the same record (not merely the same line, as same_line asks).
inline bool same_identity(const LineId& x, const LineId& y) {
  return x.kind == y.kind && x.index == y.index && x.a == y.a && x.b == y.b;
}

// The input vertex two segments share, if any: distinct lines through it meet there.
// The input vertex where two segments' lines meet, if it is an endpoint of either (a shared
// corner, or a T-junction such as a reveal edge ending on a long ceiling edge).
inline const Vec3* shared_endpoint(const LineId& x, const LineId& y) {
  if (x.kind != LineId::Kind::segment || y.kind != LineId::Kind::segment || same_line(x, y)) return nullptr;
  if (*x.a == *y.a || *x.a == *y.b) return x.a;
  if (*x.b == *y.a || *x.b == *y.b) return x.b;
  using predicates::point3;
  const auto on = [](const Vec3& v, const LineId& L) { return CGAL::collinear(point3(*L.a), point3(*L.b), point3(v)); };
  for (const Vec3* v : {x.a, x.b})
    if (on(*v, y)) return v;
  for (const Vec3* v : {y.a, y.b})
    if (on(*v, x)) return v;
  return nullptr;
}

template <class FT>
struct Vertex3 {
  FT c[3];
  const Vec3* input = nullptr;  // this vertex is an input vertex
  LineId out;                   // the line of the edge to the next vertex
  const FT& operator[](int i) const { return c[i]; }
  std::array<FT, 3> c3() const { return {c[0], c[1], c[2]}; }
};

// A sign found for the point where two lines meet, with the lines it was found for (a cut may
// give a vertex another line: keep_side); 0: not found yet.
struct MeetingSign {
  LineId in, out;
  std::int8_t sign = 0;
  // M_in × M_out in intervals (under upward rounding, as predicates::filtered_sign computes it).
  std::array<Interval, 3> direction{};
  bool holds_for(const LineId& a, const LineId& b) const { return sign != 0 && same_identity(in, a) && same_identity(out, b); }
};

template <class FT>
struct Vertex2 {
  FT u, v;                      // coordinates (x_i, x_j) in the aperture's plane, i = k+1, j = k+2
  const Vec3* at = nullptr;     // the input vertex this vertex is the central projection of
  bool in_plane = false;        // `at` lies in the aperture's plane: u, v are its exact coordinates
  LineId out;
  // Which point this is, within one clipping: copies of one vertex (the two halves of a cut share
  // the vertices on the cut) have the same id, distinct points distinct ids (0: not named).
  std::uint32_t id = 0;
  // ShadowClipper::line_side's exact path, for a vertex where two lines meet: the sign with which
  // the line through p along M_in × M_out meets the aperture's plane, an exact predicate of the
  // two lines alone, so it travels with the vertex's copies.
  mutable MeetingSign along;
};

template <class FT>
Vertex3<FT> interpolate(const Vertex3<FT>& a, const Vertex3<FT>& b, const FT& t, const LineId&) {
  return {{a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t}, nullptr, {}};
}
template <class FT>
Vertex2<FT> interpolate(const Vertex2<FT>& a, const Vertex2<FT>& b, const FT& t, const LineId& cut) {
  return {a.u + (b.u - a.u) * t, a.v + (b.v - a.v) * t, shared_endpoint(a.out, cut), false, {}, 0, {}};
}

template <class FT>
struct SignedValues {
  std::vector<FT> value;
  std::vector<int> sign;
  bool any_positive = false, any_negative = false;

  void push(FT v, int s) {
    // One allocation each for the polygons buildings are made of, not four (malloc and free were
    // 8 % of `daylit df` on the office).
    if (value.empty()) value.reserve(8), sign.reserve(8);
    any_positive |= s > 0;
    any_negative |= s < 0;
    value.push_back(std::move(v));
    sign.push_back(s);
  }
};

// One step of Sutherland–Hodgman on a convex polygon: the part where side·f ≥ 0. New vertices
// only where the sign strictly changes, so no duplicates arise; the edge that runs along the cut
// is given the identity `cut`. `refine(x, along, cut)` may replace the coordinates of a new
// vertex x, interpolated on an edge of line `along`, by ones built afresh from the two lines.
template <class V, class FT, class Refine>
std::vector<V> keep_side(const std::vector<V>& poly, const SignedValues<FT>& f, int side, const LineId& cut, const Refine& refine) {
  std::vector<V> out;
  out.reserve(poly.size() + 1);
  const auto& s = f.sign;
  const std::size_t m = poly.size();
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t j = (i + 1) % m;
    if (s[i] * side >= 0) {
      out.push_back(poly[i]);
      if (s[i] == 0 && s[j] * side < 0) out.back().out = cut;  // on the line, heading out
    }
    if (s[i] * s[j] < 0) {
      V x = interpolate(poly[i], poly[j], FT(f.value[i] / (f.value[i] - f.value[j])), cut);
      refine(x, poly[i].out, cut);
      x.out = s[i] * side > 0 ? cut : poly[i].out;  // exit point: along the cut; entry: along the old edge
      out.push_back(std::move(x));
    }
  }
  return out;
}
template <class V, class FT>
std::vector<V> keep_side(const std::vector<V>& poly, const SignedValues<FT>& f, int side, const LineId& cut) {
  return keep_side(poly, f, side, cut, [](V&, const LineId&, const LineId&) {});
}

// Reverses a loop, keeping each edge identity on its edge (which now starts at its other end).
template <class V>
void reverse_loop(std::vector<V>& loop) {
  const std::size_t m = loop.size();
  std::vector<LineId> ids;
  for (const V& x : loop) ids.push_back(x.out);
  std::reverse(loop.begin(), loop.end());
  for (std::size_t i = 0; i < m; ++i) loop[(2 * m - 2 - i) % m].out = ids[i];
}

// ---------------------------------------------------------------------------------------------

template <class FT, class Signs>
class ShadowClipper {
 public:
  // Symbolic reasoning belongs to the exact path; the float path decides everything in double.
  static constexpr bool kSymbolic = !std::is_same_v<FT, double>;

  // `horizon`: cut to the directions above p's horizontal plane as well (skies; not luminaires).
  // `beyond`: blockers beyond the piece's plane block too (skies); false cuts every blocker to p's
  // side of that plane first (luminaires: VisibilityOptions::occluders_beyond).
  // `skip_disjoint`: a shadow is not subtracted from a piece whose bounding box its own misses
  // (SubtractionOrder::front_to_back): the same set, another partition.
  ShadowClipper(const Vec3& p, const Vec3& n, const ConvexPiece& piece, int sh, bool horizon = true, bool beyond = true,
                bool skip_disjoint = false)
      : p_in_(p), n_in_(n), piece_(piece), sh_(sh), inside_(-sh), k_(piece.drop_axis), i_((k_ + 1) % 3),
        j_((k_ + 2) % 3), horizon_(horizon), beyond_(beyond), skip_disjoint_(skip_disjoint) {}

  // Blockers whose shadows were not built because their boxes missed every remaining piece.
  std::uint64_t skipped() const noexcept { return skipped_; }

  // Appends the visible part of the piece, as positively oriented loops, to `region`, and with
  // `sources` the source of each of their edges to region.edge_sources.
  void run(const std::vector<const ConvexPiece*>& blockers, SphericalRegion& region, bool sources = false) {
    std::vector<Vertex3<FT>> w;
    if (!prepare(w)) return;
    for (const auto& P : visible_pieces(blockers, w)) append_piece(P, region, sources);
  }

  // As run, where the blockers with pane[b] ≥ 0 transmit: their shadows split the pieces instead
  // of removing them, and every piece is appended to the region of its tag, the bits pane[b] of
  // the transmitting blockers whose shadows it lies in (tag 0: seen through none).
  void run_tagged(const std::vector<const ConvexPiece*>& blockers, const std::vector<int>& pane,
                  std::vector<std::pair<std::uint64_t, SphericalRegion>>& regions, bool sources = false) {
    std::vector<Vertex3<FT>> w;
    if (!prepare(w)) return;
    std::vector<std::uint64_t> tags;
    const auto pieces = visible_pieces(blockers, w, &pane, &tags);
    for (std::size_t q = 0; q < pieces.size(); ++q) {
      auto it = std::find_if(regions.begin(), regions.end(), [&](const auto& r) { return r.first == tags[q]; });
      if (it == regions.end()) it = regions.insert(regions.end(), {tags[q], SphericalRegion{}});
      append_piece(pieces[q], it->second, sources);
    }
  }

  // Whether the blockers leave nothing of the piece, without building any direction. Exact on the
  // exact path (every sign is the exact sign): then any superset of the blockers, in any order,
  // leaves nothing either.
  bool hides_all(const std::vector<const ConvexPiece*>& blockers) {
    std::vector<Vertex3<FT>> w;
    return !prepare(w) || visible_pieces(blockers, w).empty();
  }

 private:
  using V3 = Vertex3<FT>;
  using V2 = Vertex2<FT>;

  // The piece relative to p, clipped to the receiver's hemisphere and horizon; false if nothing
  // is left.
  bool prepare(std::vector<Vertex3<FT>>& w) {
    const auto& wv = piece_.vertices;
    for (std::size_t e = 0; e < wv.size(); ++e) {
      const Vec r = relative(wv[e]);
      w.push_back({{r[0], r[1], r[2]}, &wv[e], LineId::segment(wv[e], wv[(e + 1) % wv.size()])});
    }
    w0_ = w[0];
    N_ = cross(sub(w[piece_.base_b], w0_), sub(w[piece_.base_c], w0_));
    // The float path lifts its vertices by dividing by N_k. A sliver (a triangle of a polygon
    // warped within tolerance, 1e-13 of area) can have that component 0 in doubles: seen edge-on
    // in its projection, it covers nothing there, and its lifted vertices were infinite (found by
    // fuzz_visibility: a NaN solid angle in float mode). The exact paths build their directions
    // from the input and never divide by it.
    if constexpr (!kSymbolic)
      if (N_[k_] == 0) return false;
    if (!clip_to_receiver(w)) return false;
    for (const auto& x : w) cone_lines_.push_back(x.out);
    return true;
  }

  // The clipped piece minus the blockers' shadows, subtracted in the order given, as convex pieces
  // in the aperture's plane. Each shadow is built only when it is subtracted, so that nothing is
  // built once the piece is all hidden. The shadows and their order are those of building them
  // all first, so the result is the same; only an uncertain sign in a shadow that is never built
  // no longer sends an empty region to the rationals (whose answer is the same empty region).
  // With `pane` (one entry per blocker), the blockers with pane[b] ≥ 0 split the pieces into the
  // parts outside and inside their shadows, and `tags` gets each piece's bits (see run_tagged).
  // Their shadows are built as the others' are, so the inside parts are certified alike.
  std::vector<std::vector<Vertex2<FT>>> visible_pieces(const std::vector<const ConvexPiece*>& blockers,
                                                       const std::vector<Vertex3<FT>>& w,
                                                       const std::vector<int>* pane = nullptr,
                                                       std::vector<std::uint64_t>* tags = nullptr) {
    blockers_ = &blockers;
    std::vector<std::vector<Vertex2<FT>>> pieces(1);
    std::vector<std::uint64_t> tag(1, 0);
    for (const auto& x : w) pieces[0].push_back({x[i_], x[j_], x.input, x.input != nullptr, x.out, ++next_id_, {}});
    // Front to back, the pieces are merged whenever they have doubled since the last merge, and
    // once at the end: each merge costs a pass over every edge, so it is amortised over as many
    // pieces as it found (a 361-gon's shadow leaves about as many pieces as it has vertices,
    // none of which merge).
    std::size_t after_merge = 1;
    for (std::size_t b = 0; b < blockers.size(); ++b) {
      const int bit = pane ? (*pane)[b] : -1;
      std::optional<Box2> box;
      if (skip_disjoint_ || bit >= 0) {
        box = projected_box(*blockers[b]);
        if (box && std::none_of(pieces.begin(), pieces.end(), [&](const auto& P) { return box->meets(box_of(P)); })) {
          if (bit < 0) ++skipped_;
          continue;
        }
      }
      const std::optional<Shadow> shadow = shadow_of(*blockers[b], int(b), w);
      if (!shadow) continue;
      std::vector<std::vector<Vertex2<FT>>> next;
      std::vector<std::uint64_t> next_tag;
      for (std::size_t q = 0; q < pieces.size(); ++q) {
        auto& P = pieces[q];
        std::vector<V2> inside;
        if (box && !box->meets(box_of(P)))
          next.push_back(std::move(P));
        else
          subtract(P, *shadow, next, bit >= 0 ? &inside : nullptr);
        next_tag.resize(next.size(), tag[q]);
        if (inside.size() >= 3) {
          next.push_back(std::move(inside));
          next_tag.push_back(tag[q] | (std::uint64_t(1) << bit));
        }
      }
      pieces = std::move(next);
      tag = std::move(next_tag);
      if (pieces.empty()) break;
      if (skip_disjoint_ && pieces.size() >= 2 * after_merge) {
        merge_pieces(pieces, tag);
        after_merge = pieces.size();
      }
    }
    if (skip_disjoint_ && pieces.size() > after_merge) merge_pieces(pieces, tag);
    if (tags) *tags = std::move(tag);
    return pieces;
  }

  // A box in the aperture's plane's coordinates (u, v) relative to p.
  struct Box2 {
    double u0 = HUGE_VAL, u1 = -HUGE_VAL, v0 = HUGE_VAL, v1 = -HUGE_VAL;
    bool meets(const Box2& o) const { return u0 <= o.u1 && o.u0 <= u1 && v0 <= o.v1 && o.v0 <= v1; }
  };
  // Encloses the piece: each coordinate's interval (exact bounds of the number it carries).
  static Box2 box_of(const std::vector<V2>& P) {
    Box2 b;
    for (const V2& x : P) {
      const auto [ul, uh] = CGAL::to_interval(x.u);
      const auto [vl, vh] = CGAL::to_interval(x.v);
      b.u0 = std::min(b.u0, ul), b.u1 = std::max(b.u1, uh), b.v0 = std::min(b.v0, vl), b.v1 = std::max(b.v1, vh);
    }
    return b;
  }
  // Encloses the central projection of the whole blocker onto the aperture's plane (so that of its
  // part in the cone), in double widened by 1e-8 of its reach from p. With N·d and h at least 1e-6
  // of |N||d| and |N||w0 − p| (else nothing: p nearly in the aperture's plane, or a vertex not
  // certainly in front of p, where the projection is unbounded), t = h/(N·d) is within 2e-9
  // relative of its value, and u, v within that of the reach: the margin covers it five times.
  std::optional<Box2> projected_box(const ConvexPiece& blocker) const {
    const auto& wv = piece_.vertices;
    const Vec3 N = daylit::cross(wv[piece_.base_b] - wv[0], wv[piece_.base_c] - wv[0]);
    const double h = daylit::dot(N, wv[0] - p_in_);
    if (std::abs(h) < 1e-6 * norm(N) * norm(wv[0] - p_in_)) return std::nullopt;  // p nearly in the plane: t uncertain
    Box2 b;
    double reach = 0;
    for (const Vec3& v : blocker.vertices) {
      const Vec3 d = v - p_in_;
      const double along = daylit::dot(N, d);
      if (!(along * h > 0) || std::abs(along) < 1e-6 * norm(N) * norm(d)) return std::nullopt;
      const double t = h / along, u = d[i_] * t, vv = d[j_] * t;
      b.u0 = std::min(b.u0, u), b.u1 = std::max(b.u1, u), b.v0 = std::min(b.v0, vv), b.v1 = std::max(b.v1, vv);
      reach = std::max({reach, std::abs(u), std::abs(vv)});
    }
    const double margin = 1e-8 * reach;
    b.u0 -= margin, b.u1 += margin, b.v0 -= margin, b.v1 += margin;
    return b;
  }
  // A shadow, counter-clockwise; `reversed` when its edges run against the direction of the
  // occluder edges they lie on (the projection reversed the occluder's orientation).
  struct Shadow {
    std::vector<V2> loop;
    bool reversed;
  };
  using Vec = std::array<FT, 3>;

  static Vec to3(const Vec3& v) { return {FT(v.x), FT(v.y), FT(v.z)}; }
  // Coordinates relative to the receiver: all constructions happen in this frame, so that a model
  // placed at georeferenced coordinates (1e6 m from its origin) keeps its digits. In intervals the
  // difference of two doubles is enclosed to an ulp of itself; in rationals it is exact.
  Vec relative(const Vec3& v) const { return {FT(v.x) - FT(p_in_.x), FT(v.y) - FT(p_in_.y), FT(v.z) - FT(p_in_.z)}; }
  static Vec sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
  static FT dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  static Vec cross(const Vec& a, const Vec& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  }

  // The receiver's tangent plane and horizon; false if nothing is left.
  bool clip_to_receiver(std::vector<V3>& w) const {
    const Vec n = to3(n_in_);
    SignedValues<FT> front;
    for (const V3& x : w) {
      FT value = dot(n, x.c3());
      const int s = kSymbolic && x.input ? Signs::dot_diff(n_in_, *x.input, p_in_) : sign_of(value);
      front.push(std::move(value), s);
    }
    if (!front.any_positive) return false;
    if (front.any_negative) w = keep_side(w, front, +1, LineId::named(LineId::Kind::hemisphere));
    // For an upward receiver the two planes coincide.
    if (!horizon_ || (n_in_.x == 0 && n_in_.y == 0)) return true;
    SignedValues<FT> above;
    for (const V3& x : w) {
      FT value = x[2];
      const int s = kSymbolic && x.input ? sign_of(x.input->z - p_in_.z) : sign_of(value);
      above.push(std::move(value), s);
    }
    if (!above.any_positive) return false;
    if (above.any_negative) w = keep_side(w, above, +1, LineId::named(LineId::Kind::horizon));
    return true;
  }

  // The sign of `value`, with `symbolic` (exact reasoning on the input: a sign, or nothing) as
  // the help. Intervals ask for help only when they cannot decide, lazy rationals before they
  // would evaluate exactly; the float path never does. Throws when intervals cannot decide alone.
  template <class Symbolic>
  static int decide(const FT& value, const Symbolic& symbolic) {
    if constexpr (std::is_same_v<FT, double>) {
      return sign_of(value);
    } else if constexpr (std::is_same_v<FT, Interval>) {
      const auto s = CGAL::sign(value);
      if (CGAL::is_certain(s)) return int(CGAL::get_certain(s));
      if (const std::optional<int> exact = symbolic()) return *exact;
      throw CGAL::Uncertain_conversion_exception("uncertain sign");
    } else {
      if (const std::optional<int> exact = symbolic()) {
#ifdef DAYLIT_CHECK_SYMBOLIC
        // Fuzz builds (fuzz/instrument.cmake): every exact shortcut must give the sign of the
        // value it stands for, which the rationals know.
        if (sign_of(value) != *exact) {
          std::fprintf(stderr, "daylit: symbolic sign %d, exact sign %d\n", *exact, sign_of(value));
          std::abort();
        }
#endif
        return *exact;
      }
      return sign_of(value);
    }
  }

  // Normal of the plane through p that contains line L, from the input doubles in number type T
  // (a segment's by segment_plane_normal). With the longer form of a segment's, the meeting points of a 128-gon canopy's edges
  // with other lines came out of intervals up to twice 2^-44 of their length and were rebuilt in
  // rationals, at 80 % of the pair's cost (exact 13 times slower than float; now 0.9).
  template <class T>
  std::array<T, 3> plane_normal(const LineId& L) const {
    switch (L.kind) {
      case LineId::Kind::segment: return segment_plane_normal<T>(*L.a, *L.b, p_in_);
      case LineId::Kind::hemisphere: return {T(n_in_.x), T(n_in_.y), T(n_in_.z)};
      case LineId::Kind::horizon: return {T(0), T(0), T(1)};
      case LineId::Kind::aperture_plane: return cut_plane_normal<T>(*(*blockers_)[std::size_t(L.index)]);
      default: return plane_normal<T>(cone_lines_[L.index]);
    }
  }

  // Normal of the plane through p that holds the line where the blocker's plane meets the
  // aperture's. With N_o, N_W their normals and h_o = N_o·(o0 − p), h_W = N_W·(w0 − p) their
  // offsets from p, every point x of both planes has h_W N_o·(x − p) − h_o N_W·(x − p) = 0, and so
  // has p: that is the plane. Oriented as plane_normal orients a segment, (q − p) × e with q on the
  // line and e the way the cut edge runs around the clipped blocker: counter-clockwise about N_o
  // with the kept side, sh·N_W·(x − w0) ≥ 0, on its left, so e = sh N_W × N_o and
  // M = sh (h_o N_W − h_W N_o), of degree 5 in the input.
  template <class T>
  std::array<T, 3> cut_plane_normal(const ConvexPiece& blocker) const {
    std::array<T, 3> No, Nw;
    T ho, hw;
    piece_plane(blocker, p_in_, No, ho);
    piece_plane(piece_, p_in_, Nw, hw);
    const T s{double(sh_)};
    return {s * (ho * Nw[0] - hw * No[0]), s * (ho * Nw[1] - hw * No[1]), s * (ho * Nw[2] - hw * No[2])};
  }

  // Whether the planes through p of three lines share a line (det[M_A, M_B, M_C] = 0, exactly):
  // then a vertex where lines A and B meet lies on (the projection of) line C.
  bool planes_share_line(const LineId& A, const LineId& B, const LineId& C) const {
    for (const LineId* L : {&A, &B, &C})
      if (L->kind == LineId::Kind::unknown) return false;
    return predicates::filtered_sign([&](auto zero) {
             using T = decltype(zero);
             const auto a = plane_normal<T>(A), b = plane_normal<T>(B), c = plane_normal<T>(C);
             return a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
           }) == 0;
  }

  // Sign of x against side plane e of the cone (through p and edge e of w, positive inside).
  int cone_side(const ConvexPiece& blocker, const V3& x, const LineId& x_in, const LineId& edge, int e,
                const FT& value) const {
    return decide(value, [&]() -> std::optional<int> {
      const LineId cone = LineId::cone(e);
      if (same_line(x.out, cone) || same_line(x_in, cone)) return 0;
      if (x.input) {
        switch (edge.kind) {
          case LineId::Kind::segment: return inside_ * Signs::orient3(p_in_, *edge.a, *edge.b, *x.input);
          case LineId::Kind::horizon: return sign_of(x.input->z - p_in_.z);
          case LineId::Kind::hemisphere: return Signs::dot_diff(n_in_, *x.input, p_in_);
          default: return std::nullopt;
        }
      }
      if (!same_line(x_in, x.out) && planes_share_line(x_in, x.out, cone)) return 0;
      // x where an occluder edge A meets cone plane B: x − p = (a − p) + s (b − a) with
      // M_B·(x − p) = 0, so by the Binet–Cauchy identity M_E·(x − p) = det[M_E, M_B, M_A] / (M_B·(b − a)),
      // a sign decided exactly on the input (M_E oriented positive inside, M_A = (a − p) × (b − p)).
      // The same holds for B the blocker's cut along the aperture's plane (a plane through p too).
      const LineId* A = x_in.kind == LineId::Kind::segment ? &x_in : (x.out.kind == LineId::Kind::segment ? &x.out : nullptr);
      const auto plane_through_p = [](const LineId& L) { return L.kind == LineId::Kind::cone || L.kind == LineId::Kind::aperture_plane; };
      const LineId* B = plane_through_p(x_in) ? &x_in : (plane_through_p(x.out) ? &x.out : nullptr);
      if (A && B && !(B->kind == LineId::Kind::cone && B->index == e)) {
        const int det = predicates::filtered_sign([&](auto zero) {
          using T = decltype(zero);
          auto E = plane_normal<T>(edge);
          if (edge.kind == LineId::Kind::segment && inside_ < 0) E = {-E[0], -E[1], -E[2]};
          const auto b = plane_normal<T>(*B), a = plane_normal<T>(*A);
          return E[0] * (b[1] * a[2] - b[2] * a[1]) + E[1] * (b[2] * a[0] - b[0] * a[2]) + E[2] * (b[0] * a[1] - b[1] * a[0]);
        });
        const int along = predicates::filtered_sign([&](auto zero) {
          using T = decltype(zero);
          const auto b = plane_normal<T>(*B);
          return b[0] * (T(A->b->x) - T(A->a->x)) + b[1] * (T(A->b->y) - T(A->a->y)) + b[2] * (T(A->b->z) - T(A->a->z));
        });
        if (along != 0) return det * along;
      }
      // Any other x where two lines meet (two of the cone's sides, a side and the cut along the
      // aperture's plane: the corner of a luminaire that a wall of the next room touches) lies on
      // the line through p along d = M_in × M_out, and on the blocker's plane N_o·(x − o0) = 0:
      // x − p = λ d with λ = N_o·(o0 − p) / (N_o·d), so M_E·(x − p) = λ det[M_E, M_in, M_out], a
      // sign decided exactly on the input. (N_o·d = 0: the line misses the plane, x is not there.)
      if (x_in.kind == LineId::Kind::unknown || x.out.kind == LineId::Kind::unknown || same_line(x_in, x.out))
        return std::nullopt;
      const auto& ov = blocker.vertices;
      const Vec3 &o0 = ov[0], &ob = ov[blocker.base_b], &oc = ov[blocker.base_c];
      const int toward = predicates::filtered_sign([&](auto zero) {
        using T = decltype(zero);
        const auto a = plane_normal<T>(x_in), b = plane_normal<T>(x.out);
        const T ux = T(ob.x) - T(o0.x), uy = T(ob.y) - T(o0.y), uz = T(ob.z) - T(o0.z);
        const T vx = T(oc.x) - T(o0.x), vy = T(oc.y) - T(o0.y), vz = T(oc.z) - T(o0.z);
        return (uy * vz - uz * vy) * (a[1] * b[2] - a[2] * b[1]) + (uz * vx - ux * vz) * (a[2] * b[0] - a[0] * b[2]) +
               (ux * vy - uy * vx) * (a[0] * b[1] - a[1] * b[0]);
      });
      if (toward == 0) return std::nullopt;
      const int det = predicates::filtered_sign([&](auto zero) {
        using T = decltype(zero);
        auto E = plane_normal<T>(edge);
        if (edge.kind == LineId::Kind::segment && inside_ < 0) E = {-E[0], -E[1], -E[2]};
        const auto a = plane_normal<T>(x_in), b = plane_normal<T>(x.out);
        return E[0] * (a[1] * b[2] - a[2] * b[1]) + E[1] * (a[2] * b[0] - a[0] * b[2]) + E[2] * (a[0] * b[1] - a[1] * b[0]);
      });
      // sign λ = sign N_o·(o0 − p) · toward, and orient3(o0, o_b, o_c, p) = sign N_o·(p − o0).
      return -Signs::orient3(o0, ob, oc, p_in_) * toward * det;
    });
  }

  // Intervals only: the coordinates of x, a vertex of `blocker` clipped to the cone where the
  // line `along` meets the plane of `cut`, built afresh from the input as the point of the
  // blocker's plane on the line M_along × M_cut through p (as direction_from_input does for the
  // aperture's plane). Interpolating from the endpoints of the edge instead chains every cut to
  // the ones before: an edge along cone plane e cut by the nearly parallel plane e + 1 of a fine
  // polygon (exterior angle 2π/k) widens the interval by about k/2π, and the vertex after it by
  // as much again, so a 48-gon's cone left every occluder that covers it uncertain and sent all
  // its pairs to rationals. Rebuilt, a vertex's interval is a few ulps over sin(angle between the
  // planes) whatever the cuts before it. Left as interpolated where the line misses the plane in
  // certainty (the rationals then decide, as before).
  void rebuild_on(const ConvexPiece& blocker, V3& x, const LineId& along, const LineId& cut) const {
    if constexpr (std::is_same_v<FT, Interval>) {
      if (along.kind == LineId::Kind::unknown || cut.kind == LineId::Kind::unknown || same_line(along, cut)) return;
      const auto a = plane_normal<Interval>(along), b = plane_normal<Interval>(cut);
      const Vec d = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
      const auto& ov = blocker.vertices;
      const Vec o = relative(ov[0]), ob = relative(ov[blocker.base_b]), oc = relative(ov[blocker.base_c]);
      const Vec N = cross({ob[0] - o[0], ob[1] - o[1], ob[2] - o[2]}, {oc[0] - o[0], oc[1] - o[1], oc[2] - o[2]});
      const Interval meet = dot(N, d);
      if (!(meet.inf() > 0 || meet.sup() < 0)) return;
      const Interval t = dot(N, o) / meet;
      for (int c = 0; c < 3; ++c) {
#ifdef DAYLIT_CHECK_SYMBOLIC
        // Both intervals hold the exact vertex if the lines are right (fuzz builds check it).
        if (!x.c[c].do_overlap(d[c] * t)) {
          std::fprintf(stderr, "daylit: rebuilt vertex off its interpolated interval\n");
          std::abort();
        }
#endif
        x.c[c] = d[c] * t;
      }
    } else {
      (void)blocker, (void)x, (void)along, (void)cut;
    }
  }

  // The blocker (number `index` of run()'s blockers) clipped to the cone over w and projected onto
  // the aperture's plane, counter-clockwise; nothing if it has no area there.
  std::optional<Shadow> shadow_of(const ConvexPiece& blocker, int index, const std::vector<V3>& w) const {
    const auto& ov = blocker.vertices;
    const auto& wv = piece_.vertices;
    if (Signs::orient3(ov[0], ov[blocker.base_b], ov[blocker.base_c], p_in_) == 0) return std::nullopt;  // edge-on
    std::vector<V3> o;
    for (std::size_t i = 0; i < ov.size(); ++i) {
      const Vec r = relative(ov[i]);
      o.push_back({{r[0], r[1], r[2]}, &ov[i], LineId::segment(ov[i], ov[(i + 1) % ov.size()])});
    }
    const auto rebuild = [&](V3& x, const LineId& along, const LineId& cut) { rebuild_on(blocker, x, along, cut); };
    // A luminaire is hidden only by what lies between it and the receiver: the blocker's part on
    // p's side of the aperture's plane, sh·N_W·(x − w0) ≥ 0, clipped before the cone so that every
    // sign here is an exact predicate on an input vertex. The new vertices lie on the line
    // aperture_plane(index), rebuilt from it (rebuild_on) as those on the cone's planes are, and
    // the cone's clips decide their signs by the same Binet–Cauchy identity (cone_side).
    if (!beyond_) {
      const FT side{double(sh_)};
      SignedValues<FT> f;
      for (const V3& x : o) {
        // The float path too takes the sign from the input (FloatSigns: in double), as survives()
        // culled by it: a vertex on the plane then stays on it rather than a rounding off it.
        FT value = side * dot(N_, sub(x, w0_));
        f.push(std::move(value), sh_ * Signs::normal_dot_diff(wv[0], wv[piece_.base_b], wv[piece_.base_c], *x.input, wv[0]));
      }
      if (!f.any_positive) return std::nullopt;
      if (f.any_negative) o = keep_side(o, f, +1, LineId::aperture_plane(index), rebuild);
    }
    for (std::size_t e = 0; e < w.size(); ++e) {
      Vec m = cross(w[e].c3(), w[(e + 1) % w.size()].c3());
      if (inside_ < 0) m = {-m[0], -m[1], -m[2]};
      SignedValues<FT> f;
      for (std::size_t q = 0; q < o.size(); ++q) {
        FT value = dot(m, o[q].c3());
        const int s = cone_side(blocker, o[q], o[(q + o.size() - 1) % o.size()].out, w[e].out, int(e), value);
        f.push(std::move(value), s);
      }
      if (!f.any_positive) return std::nullopt;
      if (f.any_negative) o = keep_side(o, f, +1, LineId::cone(int(e)), rebuild);
    }
    const FT minus_h = dot(N_, w0_.c3());
    std::vector<V2> shadow;
    for (std::size_t q = 0; q < o.size(); ++q) {
      const V3& x = o[q];
      // An input vertex in the aperture's plane is its own projection.
      if (x.input && Signs::orient3(wv[0], wv[piece_.base_b], wv[piece_.base_c], *x.input) == 0) {
        shadow.push_back({x[i_], x[j_], x.input, true, x.out, 0, {}});
        continue;
      }
      // So is a vertex of the cut along it (t = 1 exactly, and no wider interval for dividing by it).
      if (x.out.kind == LineId::Kind::aperture_plane || o[(q + o.size() - 1) % o.size()].out.kind == LineId::Kind::aperture_plane) {
        shadow.push_back({x[i_], x[j_], nullptr, false, x.out, 0, {}});
        continue;
      }
      const FT t = minus_h / dot(N_, x.c3());
      shadow.push_back({x[i_] * t, x[j_] * t, x.input, false, x.out, 0, {}});
    }
    // Orientation of the shadow, from an exact predicate rather than its area: with A', B', C' the
    // projections of A, B, C, det[A'−p, B'−p, C'−p] = t_A t_B t_C det[A−p, B−p, C−p], t > 0 in the
    // cone, which gives sign(orientation in the aperture's plane) = sh · orient3(o0, o_b, o_c, p).
    // Clipping kept the occluder's vertex order; positive area is guaranteed by the clip's signs.
    const int orientation = sh_ * Signs::orient3(ov[0], ov[blocker.base_b], ov[blocker.base_c], p_in_);
    if (orientation < 0) reverse_loop(shadow);
    return Shadow{std::move(shadow), orientation < 0};
  }

  // Sign of x against the line of shadow edge (a, b), identity L, positive inside the shadow.
  // Exactly, from the input: with M_L = (L.a − p) × (L.b − p), a point with x − p along
  // V − p (the projection of input vertex V) or along M1 × M2 (where the lines of its edges
  // meet) has orient2(a, b, x) = −sh · μ · sign(M_L · (x − p)), μ = −1 when the shadow's edge runs
  // against L.a → L.b; and x − p = −h (M1 × M2) / (N · (M1 × M2)) on the aperture's plane.
  // The same holds for L a blocker's cut along the aperture's plane, whose M_L cut_plane_normal
  // orients as the occluder's own edges are.
  int line_side(const V2& x, const LineId& x_in, const V2& a, const V2& b, const LineId& L, bool reversed,
                const FT& value) const {
    return decide(value, [&]() -> std::optional<int> {
      // The projection of an endpoint of L's segment lies in the plane through p and L (whichever
      // side of p the endpoint is): decided by identity before the collinearity tests below,
      // which a fan of triangles (every edge through its apex) would otherwise ask at every
      // vertex on the apex.
      if (x.at && L.kind == LineId::Kind::segment && (*x.at == *L.a || *x.at == *L.b)) return 0;
      if (same_line(x.out, L) || same_line(x_in, L)) return 0;
      if (a.in_plane && b.in_plane && x.in_plane) return Signs::orient2(*a.at, *b.at, *x.at, k_);
      if (L.kind != LineId::Kind::segment && L.kind != LineId::Kind::aperture_plane) return std::nullopt;
      const int mu = reversed ? -1 : 1;
      if (x.at) {
        // x − p = t (V − p), t = −h / (N·(V − p)): positive for the projection of a vertex of an
        // occluder clipped to the cone, but a meeting point of two lines through V
        // (shared_endpoint) projects a V that may lie behind p, with t < 0 (found by
        // fuzz_visibility: the rational reference then kept a piece below the horizon).
        const auto& pv = piece_.vertices;
        const int t_sign = -sh_ * Signs::normal_dot_diff(pv[0], pv[piece_.base_b], pv[piece_.base_c], *x.at, p_in_);
        if (t_sign == 0) return std::nullopt;
        if (L.kind == LineId::Kind::segment) return -sh_ * mu * t_sign * Signs::orient3(p_in_, *L.a, *L.b, *x.at);
        const Vec3& v = *x.at;
        return -sh_ * mu * t_sign * predicates::filtered_sign([&](auto zero) {
          using T = decltype(zero);
          const auto m = plane_normal<T>(L);
          return m[0] * (T(v.x) - T(p_in_.x)) + m[1] * (T(v.y) - T(p_in_.y)) + m[2] * (T(v.z) - T(p_in_.z));
        });
      }
      if (x_in.kind == LineId::Kind::unknown || x.out.kind == LineId::Kind::unknown || same_line(x_in, x.out))
        return std::nullopt;
      // M_in × M_out, and a direction's dot products with the aperture's normal (v_b − v_0) ×
      // (v_c − v_0) and with the line L's plane normal, in any number type: each predicate below is
      // one of these, its interval stage taking M_in × M_out from the vertex (the same operations
      // in the same order, so filtered_sign_given decides as filtered_sign would).
      const auto meeting_direction = [&](auto zero) {
        using T = decltype(zero);
        const auto m1 = plane_normal<T>(x_in), m2 = plane_normal<T>(x.out);
        return std::array<T, 3>{m1[1] * m2[2] - m1[2] * m2[1], m1[2] * m2[0] - m1[0] * m2[2], m1[0] * m2[1] - m1[1] * m2[0]};
      };
      const auto along_aperture_normal = [&](const auto& d) {
        using T = std::decay_t<decltype(d[0])>;
        const auto& wv = piece_.vertices;
        const T ax = T(wv[piece_.base_b].x) - T(wv[0].x), ay = T(wv[piece_.base_b].y) - T(wv[0].y), az = T(wv[piece_.base_b].z) - T(wv[0].z);
        const T bx = T(wv[piece_.base_c].x) - T(wv[0].x), by = T(wv[piece_.base_c].y) - T(wv[0].y), bz = T(wv[piece_.base_c].z) - T(wv[0].z);
        return (ay * bz - az * by) * d[0] + (az * bx - ax * bz) * d[1] + (ax * by - ay * bx) * d[2];
      };
      const auto along_line_normal = [&](const auto& d) {
        using T = std::decay_t<decltype(d[0])>;
        const auto l = plane_normal<T>(L);
        return l[0] * d[0] + l[1] * d[1] + l[2] * d[2];
      };
      // The same vertex meets every edge of a shadow and of the shadows after it: its sign is
      // found once (on a nearly planar 361-gon's triangles it was half of this routine's time).
      if (!x.along.holds_for(x_in, x.out)) {
        Interval r;
        {
          CGAL::Protect_FPU_rounding<true> guard;
          x.along.direction = meeting_direction(Interval(0));
          r = along_aperture_normal(x.along.direction);
        }
        x.along.sign = std::int8_t(predicates::filtered_sign_given(
            r, [&](auto zero) { return along_aperture_normal(meeting_direction(zero)); }));
        // 0 (the line misses the plane) is not kept: it is rare, and leaves the vertex undecided.
        x.along.in = x_in;
        x.along.out = x.out;
      }
      const int along = x.along.sign;
      if (along == 0) return std::nullopt;
      Interval r;
      {
        CGAL::Protect_FPU_rounding<true> guard;
        r = along_line_normal(x.along.direction);
      }
      return mu * along * predicates::filtered_sign_given(r, [&](auto zero) { return along_line_normal(meeting_direction(zero)); });
    });
  }

  // P − C for convex P and C (both counter-clockwise), appended to `out` as convex pieces.
  void subtract(const std::vector<V2>& P, const Shadow& shadow, std::vector<std::vector<V2>>& out,
                std::vector<V2>* inside = nullptr) const {
    const std::vector<V2>& C = shadow.loop;
    std::vector<V2> rest = P;
    for (std::size_t e = 0; e < C.size(); ++e) {
      const V2& a = C[e];
      const V2& b = C[(e + 1) % C.size()];
      // A cut by the view cone lies on the aperture's boundary: all of P is on its inner side.
      if (kSymbolic && a.out.kind == LineId::Kind::cone) continue;
      const FT du = b.u - a.u, dv = b.v - a.v;
      SignedValues<FT> side;
      for (std::size_t q = 0; q < rest.size(); ++q) {
        const V2& x = rest[q];
        FT value = du * (x.v - a.v) - dv * (x.u - a.u);
        const int s = line_side(x, rest[(q + rest.size() - 1) % rest.size()].out, a, b, a.out, shadow.reversed, value);
        side.push(std::move(value), s);
      }
      if (!side.any_negative) continue;
      if (!side.any_positive) {
        out.push_back(std::move(rest));
        return;
      }
      std::vector<V2> outside = keep_side(rest, side, -1, a.out);
      rest = keep_side(rest, side, +1, a.out);
      name_new_vertices(outside, rest);
      out.push_back(std::move(outside));
    }
    // What remains lies inside C: in shadow.
    if (inside) *inside = std::move(rest);
  }

  // The vertices a cut creates, named: keep_side makes one on each crossed edge, in edge order,
  // whichever side it keeps, so the k-th new vertex of one half is the k-th of the other.
  void name_new_vertices(std::vector<V2>& a, std::vector<V2>& b) const {
    std::size_t j = 0;
    for (V2& x : a) {
      if (x.id != 0) continue;
      while (j < b.size() && b[j].id != 0) ++j;
      x.id = ++next_id_;
      if (j < b.size()) b[j++].id = x.id;
    }
  }

  // The sign of a value where it is certain (intervals), else 0 meaning "unknown"; exact types
  // and double give their sign.
  static int certain_sign(const FT& value) {
    if constexpr (std::is_same_v<FT, Interval>) {
      const auto s = CGAL::sign(value);
      return CGAL::is_certain(s) ? int(CGAL::get_certain(s)) : 0;
    } else {
      return sign_of(value);
    }
  }

  // Whether the boundary turns left (strictly) at b on the way a → b → c, certainly.
  static bool turns_left(const V2& a, const V2& b, const V2& c) {
    return certain_sign((b.u - a.u) * (c.v - b.v) - (b.v - a.v) * (c.u - b.u)) > 0;
  }

  // Two pieces that share a whole edge, the same two vertices (by id) run in opposite senses,
  // whose union is convex, become one (SubtractionOrder::front_to_back only: the same set, fewer
  // pieces). Subtraction cuts each piece along the whole line of every shadow edge, so a shadow
  // that overlaps a piece in part leaves cuts running on across what stays visible; the shadows
  // of a wall fanned into triangles (a polygon planar only within tolerance) left 6,737 pieces
  // of one window's view in Honeybee's lab_building where the region needs few. The union is
  // convex where it turns left at both ends of the shared edge, by a certain sign of the
  // vertices' own coordinates, or runs straight on (the edges before and after lie on one line,
  // exactly: the vertex is dropped). Nothing is constructed: the merged piece's vertices are the
  // two pieces' own, each between the same two lines as before, so its certification is theirs;
  // an uncertain turn leaves the two pieces as they are.
  void merge_pieces(std::vector<std::vector<V2>>& pieces, std::vector<std::uint64_t>& tag) const {
    for (bool merged = true; merged;) {
      merged = false;
      // Every edge as (from, to) → (piece, index), sorted by key: one allocation per pass.
      const auto key = [](std::uint32_t from, std::uint32_t to) { return (std::uint64_t(from) << 32) | to; };
      struct Edge {
        std::uint64_t key;
        std::uint32_t piece, index;
        bool operator<(const Edge& o) const { return key < o.key; }
      };
      std::vector<Edge> edges;
      for (std::size_t q = 0; q < pieces.size(); ++q)
        for (std::size_t k = 0; k < pieces[q].size(); ++k)
          edges.push_back({key(pieces[q][k].id, pieces[q][(k + 1) % pieces[q].size()].id), std::uint32_t(q), std::uint32_t(k)});
      std::sort(edges.begin(), edges.end());
      std::vector<bool> gone(pieces.size(), false), changed(pieces.size(), false);
      for (std::size_t q = 0; q < pieces.size(); ++q) {
        if (gone[q] || changed[q]) continue;
        for (std::size_t k = 0; k < pieces[q].size(); ++k) {
          const auto& A = pieces[q];
          const std::size_t na = A.size();
          const V2& x1 = A[k];
          const V2& x2 = A[(k + 1) % na];
          if (x1.id == 0 || x2.id == 0) continue;
          const auto it = std::lower_bound(edges.begin(), edges.end(), Edge{key(x2.id, x1.id), 0, 0});
          if (it == edges.end() || it->key != key(x2.id, x1.id)) continue;
          const std::size_t r = it->piece, j = it->index;  // B's edge from x2 to x1 starts at B[j]
          if (r == q || gone[r] || changed[r] || tag[r] != tag[q]) continue;
          const auto& B = pieces[r];
          const std::size_t nb = B.size();
          const V2& a_prev = A[(k + na - 1) % na];  // A's edge into x1 leaves it
          const V2& a_next = A[(k + 2) % na];
          const V2& b_prev = B[(j + nb - 1) % nb];  // B's edge into x2 leaves it
          const V2& y1 = B[(j + 1) % nb];           // x1 in B: its edge out of x1
          const V2& b_next = B[(j + 2) % nb];
          // A certain left turn first (intervals); only where it is not certain, the exact test for
          // a straight junction.
          const bool left1 = turns_left(a_prev, x1, b_next), left2 = turns_left(b_prev, x2, a_next);
          const bool straight1 = !left1 && same_line(a_prev.out, y1.out);
          if (!left1 && !straight1) continue;
          const bool straight2 = !left2 && same_line(b_prev.out, x2.out);
          if (!left2 && !straight2) continue;
          std::vector<V2> u;
          u.reserve(na + nb - 2);
          if (!straight2) u.push_back(x2);
          for (std::size_t i = 2; i < na; ++i) u.push_back(A[(k + i) % na]);  // A from after x2 to before x1
          if (!straight1) {
            u.push_back(x1);
            u.back().out = y1.out;
          }
          for (std::size_t i = 2; i < nb; ++i) u.push_back(B[(j + i) % nb]);  // B from after x1 to before x2
          pieces[q] = std::move(u);
          gone[r] = true;
          changed[q] = true;
          merged = true;
          break;
        }
      }
      if (!merged) break;
      std::size_t kept = 0;
      for (std::size_t q = 0; q < pieces.size(); ++q)
        if (!gone[q]) {
          if (kept != q) pieces[kept] = std::move(pieces[q]), tag[kept] = tag[q];
          ++kept;
        }
      pieces.resize(kept);
      tag.resize(kept);
    }
  }

  // Direction d = X − p to a vertex X of a visible piece, built afresh in number type T from what
  // defines the vertex rather than from the chain of constructions that found it (whose intervals
  // widen): an input vertex in the aperture's plane, the projection of an input vertex, or the
  // meeting point of the lines of its two edges. With M1, M2 the normals of their planes through
  // p, d = (M1 × M2) · (−h) / (N · (M1 × M2)) puts d on the aperture's plane. Nothing if the vertex
  // is not known by its definition.
  template <class T>
  std::optional<std::array<T, 3>> direction_from_input(const V2& x, const LineId& in) const {
    const auto rel = [&](const Vec3& a) { return std::array<T, 3>{T(a.x) - T(p_in_.x), T(a.y) - T(p_in_.y), T(a.z) - T(p_in_.z)}; };
    if (x.in_plane) return rel(*x.at);
    std::array<T, 3> d;
    if (x.at) {
      d = rel(*x.at);
    } else {
      if (in.kind == LineId::Kind::unknown || x.out.kind == LineId::Kind::unknown || same_line(in, x.out)) return std::nullopt;
      const auto a = plane_normal<T>(in), b = plane_normal<T>(x.out);
      d = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    }
    const auto& wv = piece_.vertices;
    const auto e1 = rel(wv[piece_.base_b]), e2 = rel(wv[piece_.base_c]), o = rel(wv[0]);
    const std::array<T, 3> e1o{e1[0] - o[0], e1[1] - o[1], e1[2] - o[2]}, e2o{e2[0] - o[0], e2[1] - o[1], e2[2] - o[2]};
    const std::array<T, 3> N{e1o[1] * e2o[2] - e1o[2] * e2o[1], e1o[2] * e2o[0] - e1o[0] * e2o[2], e1o[0] * e2o[1] - e1o[1] * e2o[0]};
    const T along = N[0] * d[0] + N[1] * d[1] + N[2] * d[2];
    if constexpr (std::is_same_v<T, Interval>) {
      // N·d too small for its interval: two lines whose planes through p (nearly) coincide, the
      // feet of two walls standing on the floor a receiver lies on, to the rounding of its
      // coordinates. Exactly zero, the lines define no point; not quite, a point at a grazing
      // angle. Either way the vertex's constructed coordinates serve where they are narrow, and
      // otherwise directions() rebuilds this vertex alone in rationals (whose N·d is exact),
      // rather than the pair going to rationals: a house's node rows spent 83 % there.
      if (!CGAL::is_certain(CGAL::sign(along))) return std::nullopt;
    }
    // Planes that coincide define no point.
    if (sign_of(along) == 0) return std::nullopt;
    const T t = (N[0] * o[0] + N[1] * o[1] + N[2] * o[2]) / along;
    return std::array<T, 3>{d[0] * t, d[1] * t, d[2] * t};
  }

  // The direction to a vertex in FT: from its definition on the exact path; on the float path,
  // and for a vertex without one, lifted from its constructed coordinates,
  // x_k = w0_k − (N_i (u − w0_i) + N_j (v − w0_j)) / N_k.
  Vec direction(const V2& x, const LineId& in) const {
    if constexpr (kSymbolic)
      if (auto d = direction_from_input<FT>(x, in)) return *d;
    if (x.in_plane) return relative(*x.at);
    Vec d;
    d[i_] = x.u;
    d[j_] = x.v;
    d[k_] = w0_[k_] - (N_[i_] * (x.u - w0_[i_]) + N_[j_] * (x.v - w0_[j_])) / N_[k_];
    return d;
  }

  // The 3-D line of each edge of a visible piece, edge q from P[q] to P[q + 1]: what gradients
  // need (DESIGN.md §7). A segment is the aperture's when its endpoints are the piece's own
  // vertices, else an occluder's; a cone line stands for the aperture edge it is on.
  EdgeSourceLoop edge_sources(const std::vector<V2>& P) const {
    const auto source = [&](LineId L) {
      if (L.kind == LineId::Kind::cone) L = cone_lines_[std::size_t(L.index)];
      switch (L.kind) {
        case LineId::Kind::segment: {
          const auto& wv = piece_.vertices;
          const bool own = L.a >= wv.data() && L.a < wv.data() + wv.size();
          return EdgeSource{own ? EdgeSource::Kind::aperture : EdgeSource::Kind::occluder, *L.a, *L.b};
        }
        case LineId::Kind::aperture_plane: {
          const auto [a, b] = cut_points(*(*blockers_)[std::size_t(L.index)]);
          return EdgeSource{EdgeSource::Kind::occluder, a, b};
        }
        case LineId::Kind::hemisphere: return EdgeSource{EdgeSource::Kind::receiver_plane};
        case LineId::Kind::horizon: return EdgeSource{EdgeSource::Kind::horizon};
        default: return EdgeSource{};
      }
    };
    EdgeSourceLoop out(P.size());
    for (std::size_t q = 0; q < P.size(); ++q) out[q] = source(P[q].out);
    return out;
  }

  // Two points of the line where the blocker's plane meets the aperture's, in model coordinates:
  // the line has no input points, so the two points where the blocker's boundary crosses the
  // plane (a convex piece that crosses it has two), in rationals from the input and rounded once,
  // whatever the mode, so that the sources agree across modes. A blocker edge on that line is
  // kept as a segment and never comes here.
  std::pair<Vec3, Vec3> cut_points(const ConvexPiece& blocker) const {
    using Q = CGAL::Gmpq;
    const auto& wv = piece_.vertices;
    const auto& ov = blocker.vertices;
    const auto q3 = [](const Vec3& v) { return std::array<Q, 3>{Q(v.x), Q(v.y), Q(v.z)}; };
    const auto w0 = q3(wv[0]), wb = q3(wv[piece_.base_b]), wc = q3(wv[piece_.base_c]);
    const std::array<Q, 3> e1{wb[0] - w0[0], wb[1] - w0[1], wb[2] - w0[2]}, e2{wc[0] - w0[0], wc[1] - w0[1], wc[2] - w0[2]};
    const std::array<Q, 3> N{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    std::vector<std::array<Q, 3>> v;
    std::vector<Q> f;
    for (const Vec3& x : ov) {
      v.push_back(q3(x));
      f.push_back(N[0] * (v.back()[0] - w0[0]) + N[1] * (v.back()[1] - w0[1]) + N[2] * (v.back()[2] - w0[2]));
    }
    std::vector<Vec3> points;
    const auto round = [](const std::array<Q, 3>& x) { return Vec3{round_rational(x[0]), round_rational(x[1]), round_rational(x[2])}; };
    for (std::size_t i = 0; i < v.size() && points.size() < 2; ++i) {
      const std::size_t j = (i + 1) % v.size();
      if (CGAL::sign(f[i]) == CGAL::ZERO) points.push_back(ov[i]);
      else if (CGAL::sign(f[i]) * CGAL::sign(f[j]) < 0) {
        const Q t = f[i] / (f[i] - f[j]);
        points.push_back(round({v[i][0] + (v[j][0] - v[i][0]) * t, v[i][1] + (v[j][1] - v[i][1]) * t, v[i][2] + (v[j][2] - v[i][2]) * t}));
      }
    }
    return {points.at(0), points.at(1)};
  }

  // Directions from p, rounded once, in the piece's order.
  DirectionLoop directions(const std::vector<V2>& P) const {
    DirectionLoop loop;
    loop.reserve(P.size());
    for (std::size_t q = 0; q < P.size(); ++q) {
      const LineId& in = P[(q + P.size() - 1) % P.size()].out;
      const auto d = direction(P[q], in);
      double scale = 0;
      for (const FT& c : d) scale = std::max(scale, std::abs(CGAL::to_double(c)));
      if constexpr (std::is_same_v<FT, Interval>) {
        try {
          loop.push_back({round_to_double(d[0], scale), round_to_double(d[1], scale), round_to_double(d[2], scale)});
        } catch (const CGAL::Uncertain_conversion_exception&) {
          // The vertex is certain, only its interval too wide: rebuild just it in rationals.
          const auto exact = direction_from_input<CGAL::Gmpq>(P[q], in);
          if (!exact) throw;
          loop.push_back({round_rational((*exact)[0]), round_rational((*exact)[1]), round_rational((*exact)[2])});
        }
        continue;
      }
      loop.push_back({round_to_double(d[0], scale), round_to_double(d[1], scale), round_to_double(d[2], scale)});
    }
    return loop;
  }

  // A visible piece appended to `region` as a positive loop (a counter-clockwise piece is one
  // when h < 0), with its edges' sources when asked for, and each arc nearly π long split at its
  // middle (opposite_arc_midpoint).
  void append_piece(const std::vector<V2>& P, SphericalRegion& region, bool sources) const {
    DirectionLoop loop = directions(P);
    EdgeSourceLoop edges;
    if (sources) edges = edge_sources(P);
    split_opposite_arcs(P, loop, sources ? &edges : nullptr);
    const std::size_t m = loop.size();
    if (sh_ > 0) {
      std::reverse(loop.begin(), loop.end());
      // Edge i of the reversed loop is edge m − 2 − i of the original.
      if (sources) {
        EdgeSourceLoop reversed(m);
        for (std::size_t i = 0; i < m; ++i) reversed[i] = edges[(2 * m - 2 - i) % m];
        edges = std::move(reversed);
      }
    }
    region.loops.push_back(std::move(loop));
    if (sources) region.edge_sources.push_back(std::move(edges));
  }

  // Inserts the middle of each arc nearly π long, its edge q's line P[q].out giving its plane;
  // both halves keep the edge's source.
  void split_opposite_arcs(const std::vector<V2>& P, DirectionLoop& loop, EdgeSourceLoop* sources) const {
    const std::size_t m = loop.size();
    bool any = false;
    for (std::size_t q = 0; q < m && !any; ++q)
      any = P[q].out.kind != LineId::Kind::unknown && nearly_opposite(loop[q], loop[(q + 1) % m]);
    if (!any) return;
    using Q = CGAL::Gmpq;
    std::array<Q, 3> N;
    Q h;
    piece_plane(piece_, p_in_, N, h);
    DirectionLoop split;
    EdgeSourceLoop split_sources;
    for (std::size_t q = 0; q < m; ++q) {
      split.push_back(loop[q]);
      if (sources) split_sources.push_back((*sources)[q]);
      if (P[q].out.kind == LineId::Kind::unknown || !nearly_opposite(loop[q], loop[(q + 1) % m])) continue;
      if (const auto middle = opposite_arc_midpoint(plane_normal<Q>(P[q].out), N, h)) {
        split.push_back(*middle);
        if (sources) split_sources.push_back((*sources)[q]);
      }
    }
    loop = std::move(split);
    if (sources) *sources = std::move(split_sources);
  }

  Vec3 p_in_, n_in_;
  const ConvexPiece& piece_;
  int sh_, inside_, k_, i_, j_;
  bool horizon_, beyond_;
  bool skip_disjoint_ = false;
  std::uint64_t skipped_ = 0;
  mutable std::uint32_t next_id_ = 0;  // the last vertex id given (Vertex2::id)
  V3 w0_;
  Vec N_;
  std::vector<LineId> cone_lines_;  // the line of each edge of the clipped aperture piece
  const std::vector<const ConvexPiece*>* blockers_ = nullptr;  // what LineId::aperture_plane indexes
};

}  // namespace daylit::clipping
