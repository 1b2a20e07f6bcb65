// Visibility of a luminaire (VisibilityOptions::occluders_beyond = false): the directions from
// the receiver to points x of the luminaire whose open segment (p, x) meets no occluder. What lies
// beyond the luminaire's plane, or touches it from there, cannot hide it; what crosses the plane
// hides with its part in front only. The radiosity configurations (DESIGN.md §4: every surface a
// luminaire and an occluder, receivers on surfaces, surfaces meeting along edges) are checked
// against closed forms; the exact mode against the all-rational reference on each of them and on
// seeded random scenes; the float mode's answers are printed (run with -s).

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "geometry/visibility.hpp"
#include "illumination/moments.hpp"
#include "illumination/solid_angle.hpp"
#include "illumination/xoshiro256.hpp"
#include "test_scenes.hpp"

using namespace daylit;
using test::polygon;

namespace {

// Closed forms for the rectangle [x0, x1] × [y0, y1] of a plane at distance d from the receiver,
// in coordinates of that plane with the foot of the perpendicular at the origin. The rectangle
// [0, a] × [0, b] with a corner at the foot subtends asin(ab / √((a² + d²)(b² + d²))), a quarter of
// the centred rectangle's 4·asin(ab / √((a² + 4d²)(b² + 4d²))), and its Lambert integral ∫ cos θ dω
// (receiver facing the plane) is π times the view factor from a point to a parallel rectangle
// with its normal through a corner, ½ [A atan(B/√(1+A²))/√(1+A²) + B atan(A/√(1+B²))/√(1+B²)],
// A = a/d, B = b/d. Both are odd in a and in b, so any rectangle is a signed sum of four corners
// (regions split into rectangles add).
double corner_solid_angle(double a, double b, double d) { return std::asin(a * b / std::sqrt((a * a + d * d) * (b * b + d * d))); }
double corner_lambert(double a, double b, double d) {
  const double A = a / d, B = b / d, sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return 0.5 * (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb));
}
template <class F>
double rectangle(F corner, double x0, double x1, double y0, double y1, double d) {
  return corner(x1, y1, d) - corner(x0, y1, d) - corner(x1, y0, d) + corner(x0, y0, d);
}
double rectangle_solid_angle(double x0, double x1, double y0, double y1, double d) {
  return rectangle(corner_solid_angle, x0, x1, y0, y1, d);
}
double rectangle_lambert(double x0, double x1, double y0, double y1, double d) { return rectangle(corner_lambert, x0, x1, y0, y1, d); }

VisibilityOptions luminaire_options(bool beyond, std::size_t excluded = VisibilityOptions::kNoOccluder, bool sources = false) {
  VisibilityOptions options;
  options.clip_to_horizon = false;
  options.occluders_beyond = beyond;
  options.excluded_occluder = excluded;
  options.edge_sources = sources;
  return options;
}

struct Seen {
  double solid_angle, lambert;
};

Seen seen(const Scene& scene, GeometryMode mode, const Vec3& p, const Vec3& n, const VisibilityOptions& options,
          VisibilityCounters* counters_out = nullptr) {
  const VisibilityEngine engine(scene, mode);
  VisibilityCounters counters;
  const SphericalRegion region = engine.visible_region(p, n, 0, counters, options);
  if (counters_out) *counters_out = counters;
  return {solid_angle(region), lambert(region, n)};
}

// The region in the exact mode, checked against the rational reference to the certification
// bound: every direction within 2^-45 (2.8e-14) of its length of the exact one, so the solid angle
// and Lambert integral within a few 1e-14 of the luminaire's (4e-14 here; observed below 1e-15 on
// these scenes). The float mode's answer is printed.
Seen seen_exactly(const char* what, const Scene& scene, const Vec3& p, const Vec3& n, const VisibilityOptions& options) {
  const Seen exact = seen(scene, GeometryMode::exact, p, n, options), rational = seen(scene, GeometryMode::rational, p, n, options),
             floating = seen(scene, GeometryMode::floating, p, n, options);
  INFO(what << ": exact " << exact.solid_angle << " rational " << rational.solid_angle);
  const double whole = std::max(std::abs(rational.solid_angle), 1e-3);
  CHECK(std::abs(exact.solid_angle - rational.solid_angle) <= 4e-14 * whole);
  CHECK(std::abs(exact.lambert - rational.lambert) <= 4e-14 * whole);
  std::printf("%-60s exact %.17g  float %.17g  |float-exact| %.3g sr\n", what, exact.solid_angle, floating.solid_angle,
              std::abs(floating.solid_angle - exact.solid_angle));
  return exact;
}

// Closed forms against the exact answer: directions certified to 2^-45 of their length and the
// kernels' own rounding (a few ulp per edge term) leave well under 1e-13 relative.
constexpr double kClosedForm = 1e-13;

// A unit square 1 above the receiver at the origin, facing it.
Polygon unit_square_at(double z) { return polygon({{-0.5, -0.5, z}, {0.5, -0.5, z}, {0.5, 0.5, z}, {-0.5, 0.5, z}}); }

}  // namespace

TEST_CASE("an occluder wholly beyond a luminaire does not hide it, with occluders beyond it does") {
  // The luminaire is a surface of the model and so also an occluder, not excluded: touching its
  // own plane, it lies "not between" and hides nothing. A ceiling above it (beyond, seen from the
  // receiver) covers the whole view.
  Scene scene;
  scene.occluders.push_back(unit_square_at(1));
  scene.occluders.push_back(polygon({{-9, -9, 2}, {9, -9, 2}, {9, 9, 2}, {-9, 9, 2}}, "ceiling beyond"));
  scene.apertures.push_back({scene.occluders[0], 1.0});
  const Vec3 p{0, 0, 0}, n{0, 0, 1};
  const Seen luminaire = seen_exactly("beyond: luminaire alone", scene, p, n, luminaire_options(false));
  CHECK(luminaire.solid_angle == Approx(4 * std::asin(1.0 / 5)).epsilon(kClosedForm));
  CHECK(luminaire.lambert == Approx(rectangle_lambert(-0.5, 0.5, -0.5, 0.5, 1)).epsilon(kClosedForm));
  // Both occluders are culled before any clipping: the pair is unobstructed.
  VisibilityCounters counters;
  seen(scene, GeometryMode::exact, p, n, luminaire_options(false), &counters);
  CHECK(counters.pairs_unobstructed == 1);
  CHECK(counters.occluders_clipped == 0);
  // The default (a sky through a window) lets the ceiling hide it, and the surface itself too.
  CHECK(seen(scene, GeometryMode::exact, p, n, luminaire_options(true, 0)).solid_angle == 0);
  CHECK(seen(scene, GeometryMode::exact, p, n, luminaire_options(true)).solid_angle == 0);
  // A square in front, half over the luminaire's view, still hides its half.
  scene.occluders.push_back(polygon({{0, -1, 0.5}, {1, -1, 0.5}, {1, 1, 0.5}, {0, 1, 0.5}}, "in front"));
  const Seen half = seen_exactly("beyond: half hidden by a square in front", scene, p, n, luminaire_options(false));
  CHECK(half.solid_angle == Approx(2 * std::asin(1.0 / 5)).epsilon(kClosedForm));
  CHECK(half.lambert == Approx(rectangle_lambert(-0.5, 0, -0.5, 0.5, 1)).epsilon(kClosedForm));
}

TEST_CASE("an occluder crossing the luminaire's plane hides exactly the part in front of it") {
  // Luminaire [−1, 1]² at z = 1, receivers below it facing up; a wall x = c, |y| ≤ 8, from z = 0.5
  // to 1.5 crosses its plane. Seen from p, its part in front (z ≤ 1) covers the strip between
  // x − p_x = c' and c'/0.5 (c' = c − p_x) of the luminaire, over its whole depth; the part beyond
  // would add c'/1.5 to c'. Visible: the luminaire less the strip, two rectangles that add.
  Scene scene;
  scene.occluders.push_back(polygon({{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}, "luminaire"));
  scene.occluders.push_back(polygon({{0.25, -8, 0.5}, {0.25, 8, 0.5}, {0.25, 8, 1.5}, {0.25, -8, 1.5}}, "crossing wall"));
  scene.apertures.push_back({scene.occluders[0], 1.0});
  for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{0.125, 0.3, 0.25}, Vec3{0.7, -0.4, 0}}) {
    const double d = 1 - p.z, c = 0.25 - p.x, x0 = -1 - p.x, x1 = 1 - p.x, y0 = -1 - p.y, y1 = 1 - p.y;
    // The wall's edges at z = 0.5 and 1.5, projected from p onto z = 1.
    const double near = c * d / (0.5 - p.z), far = c * d / (1.5 - p.z);
    const auto visible = [&](double lo, double hi, auto rect) {
      lo = std::max(lo, x0), hi = std::min(hi, x1);
      return rect(x0, lo, y0, y1, d) + rect(hi, x1, y0, y1, d);
    };
    INFO("receiver " << p.x << " " << p.y << " " << p.z);
    const Seen front = seen_exactly("crossing: in front only", scene, p, {0, 0, 1}, luminaire_options(false));
    CHECK(front.solid_angle == Approx(visible(std::min(c, near), std::max(c, near), rectangle_solid_angle)).epsilon(kClosedForm));
    CHECK(front.lambert == Approx(visible(std::min(c, near), std::max(c, near), rectangle_lambert)).epsilon(kClosedForm));
    const Seen sky = seen_exactly("crossing: default, beyond too", scene, p, {0, 0, 1}, luminaire_options(true, 0));
    CHECK(sky.solid_angle == Approx(visible(std::min(far, near), std::max(far, near), rectangle_solid_angle)).epsilon(kClosedForm));
    CHECK(sky.lambert == Approx(visible(std::min(far, near), std::max(far, near), rectangle_lambert)).epsilon(kClosedForm));
  }
}

namespace {

// A room [0, 4]² × [0, 3] whose surfaces are all occluders: the floor (index 0, reaching out under
// the wall to x = −3, so that it crosses the wall's plane), the walls x = 0 (1), x = 4, y = 0,
// y = 4 and the ceiling; beyond the wall x = 0 a neighbour's facade at x = −2, and under the floor a
// basement slab at z = −0.5, both covering every view through the surfaces they are behind.
Scene room() {
  Scene s;
  s.occluders.push_back(polygon({{-3, 0, 0}, {4, 0, 0}, {4, 4, 0}, {-3, 4, 0}}, "floor"));
  s.occluders.push_back(polygon({{0, 0, 0}, {0, 4, 0}, {0, 4, 3}, {0, 0, 3}}, "wall x=0"));
  s.occluders.push_back(polygon({{4, 0, 0}, {4, 0, 3}, {4, 4, 3}, {4, 4, 0}}, "wall x=4"));
  s.occluders.push_back(polygon({{0, 0, 0}, {0, 0, 3}, {4, 0, 3}, {4, 0, 0}}, "wall y=0"));
  s.occluders.push_back(polygon({{0, 4, 0}, {4, 4, 0}, {4, 4, 3}, {0, 4, 3}}, "wall y=4"));
  s.occluders.push_back(polygon({{0, 0, 3}, {4, 0, 3}, {4, 4, 3}, {0, 4, 3}}, "ceiling"));
  s.occluders.push_back(polygon({{-2, -50, -50}, {-2, 50, -50}, {-2, 50, 50}, {-2, -50, 50}}, "facade beyond x=0"));
  s.occluders.push_back(polygon({{-50, -50, -0.5}, {50, -50, -0.5}, {50, 50, -0.5}, {-50, 50, -0.5}}, "basement slab"));
  return s;
}

}  // namespace

TEST_CASE("surfaces meeting at a corner see each other whole, the receiver lying in an occluder's plane") {
  // The radiosity configuration: a node on the floor sees the wall that meets the floor along an
  // edge; a node on that wall sees the floor. Neither the surface the node lies on (its plane holds
  // the receiver), nor the luminaire itself (its own plane), nor the adjacent walls (touching it
  // along the corner edges), nor what lies beyond hides anything: every surface is an occluder and
  // none is excluded.
  {
    Scene scene = room();
    scene.apertures.push_back({scene.occluders[1], 1.0});
    const Vec3 p{2, 1, 0}, n{0, 0, 1};
    // The wall is 2 away; in its coordinates (y − 1, z) it spans [−1, 3] × [0, 3].
    const Seen wall = seen_exactly("corner: floor node sees the wall", scene, p, n, luminaire_options(false));
    CHECK(wall.solid_angle == Approx(rectangle_solid_angle(-1, 3, 0, 3, 2)).epsilon(kClosedForm));
    // The radiosity's query (reflected_components.cpp) excludes the luminaire, the one exclusion
    // there is, and leaves in the floor the receiver lies on: that floor, in the receiver's
    // tangent plane, hides nothing, so the region is the same whichever of the two is excluded.
    const Seen lum_excluded = seen_exactly("corner: wall excluded, floor node's floor kept", scene, p, n, luminaire_options(false, 1));
    const Seen own_excluded = seen_exactly("corner: floor node's floor excluded", scene, p, n, luminaire_options(false, 0));
    CHECK(lum_excluded.solid_angle == Approx(wall.solid_angle).epsilon(kClosedForm));
    CHECK(lum_excluded.lambert == Approx(wall.lambert).epsilon(kClosedForm));
    CHECK(own_excluded.solid_angle == Approx(wall.solid_angle).epsilon(kClosedForm));
    // With the occluders beyond (and the wall excluded) the facade hides it all.
    CHECK(seen(scene, GeometryMode::exact, p, n, luminaire_options(true, 1)).solid_angle == 0);
  }
  {
    Scene scene = room();
    scene.apertures.push_back({scene.occluders[0], 1.0});
    const Vec3 p{0, 2, 1.5}, n{1, 0, 0};
    // The floor beyond the wall's plane is behind the receiver: in coordinates (x, y − 2) the part
    // seen spans [0, 4] × [−2, 2], 1.5 below.
    const Seen floor = seen_exactly("corner: wall node sees the floor", scene, p, n, luminaire_options(false));
    CHECK(floor.solid_angle == Approx(rectangle_solid_angle(0, 4, -2, 2, 1.5)).epsilon(kClosedForm));
    // As above, the wall node's own wall (occluder 1) kept and the floor (the luminaire) excluded.
    const Seen lum_excluded = seen_exactly("corner: floor excluded, wall node's wall kept", scene, p, n, luminaire_options(false, 0));
    CHECK(lum_excluded.solid_angle == Approx(floor.solid_angle).epsilon(kClosedForm));
    CHECK(lum_excluded.lambert == Approx(floor.lambert).epsilon(kClosedForm));
    CHECK(seen(scene, GeometryMode::exact, p, n, luminaire_options(true, 0)).solid_angle == 0);
  }
}

TEST_CASE("a shelf meeting the luminaire along an edge hides its shadow from in front, nothing from behind") {
  // A shelf at z = 1, depth 0.5, along the whole wall x = 0: from the floor node (2, 1, 0), the
  // segment to the wall point (0, y, z) passes x ∈ [0, 0.5] at heights z·[3/4, 1], so the shelf in
  // front hides the strip z ∈ [1, 4/3] of the wall (its edge on the wall, and its outer edge
  // projected). The same shelf behind the wall hides nothing, and one through the wall hides what
  // the front one does.
  const Vec3 p{2, 1, 0}, n{0, 0, 1};
  const double strip_hidden = rectangle_solid_angle(-1, 3, 0, 1, 2) + rectangle_solid_angle(-1, 3, 4.0 / 3, 3, 2);
  const double whole = rectangle_solid_angle(-1, 3, 0, 3, 2);
  const struct {
    const char* name;
    double x0, x1, expected;
  } shelves[] = {{"shelf: in front, touching along an edge", 0, 0.5, strip_hidden},
                 {"shelf: behind, touching along an edge", -0.5, 0, whole},
                 {"shelf: through the wall", -0.5, 0.5, strip_hidden}};
  for (const auto& shelf : shelves) {
    Scene scene = room();
    scene.occluders.push_back(polygon({{shelf.x0, 0, 1}, {shelf.x1, 0, 1}, {shelf.x1, 4, 1}, {shelf.x0, 4, 1}}, "shelf"));
    scene.apertures.push_back({scene.occluders[1], 1.0});
    INFO(shelf.name);
    const Seen wall = seen_exactly(shelf.name, scene, p, n, luminaire_options(false));
    CHECK(wall.solid_angle == Approx(shelf.expected).epsilon(kClosedForm));
  }
}

TEST_CASE("without the occluders beyond, every edge still lies in the plane of its source line") {
  // Gradients need each edge's 3-D line (DESIGN.md §7). Where a crossing occluder is cut along the
  // luminaire's plane, that line is where the two planes meet: an occluder line with two points
  // of both planes. The sources are the same in the exact and rational modes.
  Scene scene;
  scene.occluders.push_back(polygon({{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}, "luminaire"));
  scene.occluders.push_back(polygon({{0.25, -0.5, 0.5}, {0.5, 0.5, 0.5}, {0.375, 0.5, 1.5}, {0.125, -0.5, 1.5}}, "tilted crossing"));
  scene.occluders.push_back(polygon({{-0.75, -2, 0.75}, {-0.25, -2, 0.75}, {-0.25, 0, 1.25}, {-0.75, 0, 1.25}}, "sloping crossing"));
  scene.apertures.push_back({scene.occluders[0], 1.0});
  const auto in_plane = [](const Vec3& v, const Polygon& poly) {
    const Vec3 m = normalized(newell_normal(poly.vertices));
    return std::abs(dot(m, v - poly.vertices[0])) <= 1e-15 * (norm(v) + 1);
  };
  const VisibilityEngine exact(scene, GeometryMode::exact), rational(scene, GeometryMode::rational);
  int cut_edges = 0;
  for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{0.3, -0.2, 0.1}, Vec3{-0.6, 0.4, 0.3}}) {
    VisibilityCounters counters;
    const SphericalRegion r = exact.visible_region(p, {0, 0, 1}, 0, counters, luminaire_options(false, 0, true));
    const SphericalRegion q = rational.visible_region(p, {0, 0, 1}, 0, counters, luminaire_options(false, 0, true));
    INFO("receiver " << p.x << " " << p.y << " " << p.z);
    CHECK(r.edge_sources == q.edge_sources);
    REQUIRE(r.has_edge_sources());
    for (std::size_t l = 0; l < r.loops.size(); ++l)
      for (std::size_t i = 0; i < r.loops[l].size(); ++i) {
        const EdgeSource& s = r.edge_sources[l][i];
        REQUIRE((s.kind == EdgeSource::Kind::aperture || s.kind == EdgeSource::Kind::occluder));
        const bool cut = s.kind == EdgeSource::Kind::occluder && in_plane(s.a, scene.occluders[0]) && in_plane(s.b, scene.occluders[0]);
        if (cut) {
          ++cut_edges;
          CHECK((in_plane(s.a, scene.occluders[1]) && in_plane(s.b, scene.occluders[1])) !=
                (in_plane(s.a, scene.occluders[2]) && in_plane(s.b, scene.occluders[2])));
        }
        // Directions rounded once from exact points, 2^-45 of their length.
        const Vec3 m = normalized(cross(s.a - p, s.b - s.a));
        CHECK(std::abs(dot(m, normalized(r.loops[l][i]))) < 1e-12);
        CHECK(std::abs(dot(m, normalized(r.loops[l][(i + 1) % r.loops[l].size()]))) < 1e-12);
      }
  }
  // Both occluders are cut, seen from every receiver.
  CHECK(cut_edges >= 6);
}

namespace {

// Seeded scenes: a luminaire triangle and occluder triangles around the segments from the receiver
// to it. xoshiro256 rather than the standard distributions, whose output differs between
// libraries. `grid`: coordinates on multiples of 1/4, so that occluders touch the luminaire's
// plane with vertices and edges and share its lines, as in models.
struct RandomScenes {
  Xoshiro256 rng{20261201};
  bool grid;
  double coordinate(double lo, double hi) {
    if (!grid) return lo + (hi - lo) * rng.uniform();
    const int steps = int(std::lround(4 * (hi - lo)));
    return lo + 0.25 * double(rng() % std::uint64_t(steps + 1));
  }
  Vec3 point(double lo, double hi) { return {coordinate(lo, hi), coordinate(lo, hi), coordinate(lo, hi)}; }
};

// N·(v − w0) of the luminaire's plane, in long double: the tests only use it far from zero.
long double side_of(const Polygon& w, const Vec3& v) {
  const Vec3 &a = w.vertices[0], &b = w.vertices[1], &c = w.vertices[2];
  const long double ux = (long double)b.x - a.x, uy = (long double)b.y - a.y, uz = (long double)b.z - a.z;
  const long double vx = (long double)c.x - a.x, vy = (long double)c.y - a.y, vz = (long double)c.z - a.z;
  return (uy * vz - uz * vy) * (v.x - a.x) + (uz * vx - ux * vz) * (v.y - a.y) + (ux * vy - uy * vx) * (v.z - a.z);
}

// The part of a triangle where side_of(w, ·) has the sign of `keep` (Sutherland–Hodgman in
// double): the reference clips occluders to the receiver's side before the default mode sees them.
std::optional<Polygon> clipped_to_side(const Polygon& o, const Polygon& w, long double keep) {
  std::vector<Vec3> out;
  const auto& v = o.vertices;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3 &a = v[i], &b = v[(i + 1) % v.size()];
    const long double fa = keep * side_of(w, a), fb = keep * side_of(w, b);
    if (fa >= 0) out.push_back(a);
    if ((fa > 0 && fb < 0) || (fa < 0 && fb > 0)) {
      const double t = double(fa / (fa - fb));
      out.push_back(a + t * (b - a));
    }
  }
  if (out.size() < 3) return std::nullopt;
  return polygon(out, o.name);
}

}  // namespace

TEST_CASE("on seeded random scenes the luminaire's region is the default one when nothing lies beyond, and exact equals rational") {
  int compared = 0, crossing = 0, hidden = 0;
  double float_worst = 0;
  for (const bool grid : {false, true}) {
    RandomScenes random{Xoshiro256(grid ? 7 : 20261201), grid};
    for (int trial = 0; trial < 24; ++trial) {
      Scene scene;
      const Polygon w = polygon({random.point(-1, 1), random.point(-1, 1), random.point(-1, 1)}, "luminaire");
      if (std::abs(side_of(w, {0, 0, 0})) < 1e-3 || norm(newell_normal(w.vertices)) < 0.1) continue;
      // Receivers around the origin, on the origin's side of the luminaire's plane.
      const long double receiver_side = side_of(w, {0, 0, 0}) > 0 ? 1 : -1;
      Scene in_front, beyond_too;
      for (Scene* s : {&in_front, &beyond_too}) s->apertures.push_back({w, 1.0});
      for (int k = 0; k < 8; ++k) {
        // Centred on the segments from the receivers (about the origin) to the luminaire, from
        // 0.4 to 1.4 of their length: in front of the luminaire, across its plane, or beyond.
        const double u = random.coordinate(0, 1), v = random.coordinate(0, 1 - u), t = 0.4 + random.coordinate(0, 1);
        Vec3 c = t * ((1 - u - v) * w.vertices[0] + u * w.vertices[1] + v * w.vertices[2]);
        if (grid) c = {0.25 * std::round(4 * c.x), 0.25 * std::round(4 * c.y), 0.25 * std::round(4 * c.z)};
        Polygon o = polygon({c + random.point(-0.5, 0.5), c + random.point(-0.5, 0.5), c + random.point(-0.5, 0.5)}, "occluder");
        if (norm(newell_normal(o.vertices)) < 1e-3) continue;
        const bool all_in_front = std::all_of(o.vertices.begin(), o.vertices.end(), [&](const Vec3& v) { return receiver_side * side_of(w, v) > 1e-3; });
        if (all_in_front) in_front.occluders.push_back(o);
        beyond_too.occluders.push_back(o);
      }
      // The reference for the scene with occluders beyond: each clipped to the receiver's side
      // first, in double (vertices within an ulp of the exact cut: a shift of the shadow that
      // changes the solid angle by well under 1e-13), then seen with the default option.
      Scene reference;
      reference.apertures.push_back({w, 1.0});
      for (const Polygon& o : beyond_too.occluders)
        if (auto part = clipped_to_side(o, w, receiver_side)) reference.occluders.push_back(*part);
      const VisibilityEngine exact_front(in_front, GeometryMode::exact), rational_front(in_front, GeometryMode::rational);
      const VisibilityEngine exact_all(beyond_too, GeometryMode::exact), rational_all(beyond_too, GeometryMode::rational),
          float_all(beyond_too, GeometryMode::floating), exact_reference(reference, GeometryMode::exact);
      for (int s = 0; s < 6; ++s) {
        Vec3 p = random.point(-0.5, 0.5);
        if (receiver_side * side_of(w, p) < 1e-3) continue;
        const Vec3 n = normalized(random.point(-1, 1) + Vec3{0, 0, 0.01});
        INFO("grid " << grid << " trial " << trial << " receiver " << p.x << " " << p.y << " " << p.z);
        VisibilityCounters counters, beyond_counters;
        // Every other receiver with the horizon cut as well, which the new clip must not disturb.
        const auto omega = [&](const VisibilityEngine& e, bool beyond, VisibilityCounters& c) {
          VisibilityOptions options = luminaire_options(beyond);
          options.clip_to_horizon = s % 2 == 1;
          return solid_angle(e.visible_region(p, n, 0, c, options));
        };
        // Directions certified to 2^-45 of their length: a few 1e-14 of the luminaire's solid
        // angle, which bounds every region here.
        VisibilityCounters unobstructed;
        const double luminaire = omega(VisibilityEngine(Scene{{}, {{w, 1.0}}, {}, {}, {}}, GeometryMode::exact), true, unobstructed);
        const double bound = 4e-14 * std::max(luminaire, 1e-3);
        // Nothing beyond: both options give the same region.
        const double front_new = omega(exact_front, false, counters), front_old = omega(exact_front, true, counters);
        CHECK(std::abs(front_new - front_old) <= bound);
        CHECK(std::abs(front_new - omega(rational_front, false, counters)) <= bound);
        // Occluders anywhere: exact equals rational, and both equal the default mode on the
        // occluders clipped beforehand.
        const double all_new = omega(exact_all, false, beyond_counters);
        CHECK(std::abs(all_new - omega(rational_all, false, counters)) <= bound);
        CHECK(std::abs(all_new - omega(exact_reference, true, counters)) <= 1e-13 * std::max(luminaire, 1e-3));
        float_worst = std::max(float_worst, std::abs(omega(float_all, false, counters) - all_new) / std::max(luminaire, 1e-3));
        crossing += beyond_counters.occluders_clipped > 0 && beyond_too.occluders.size() > in_front.occluders.size();
        hidden += all_new < luminaire * (1 - 1e-9);
        ++compared;
      }
    }
  }
  std::printf("random luminaire scenes: %d receivers, %d with occluders clipped, %d partly hidden; float worst %.3g of the luminaire\n",
              compared, crossing, hidden, float_worst);
  // The scenes must exercise the new clip: many receivers, most partly hidden, many with crossing
  // occluders clipped.
  CHECK(compared > 150);
  CHECK(hidden > compared / 2);
  CHECK(crossing > compared / 3);
}
