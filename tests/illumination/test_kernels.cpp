// Kernels of illumination/ against closed forms and against long-double quadrature over area.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "illumination/moments.hpp"
#include "illumination/solid_angle.hpp"
#include "reference_quadrature.hpp"
#include "test_support.hpp"

using namespace daylit;
using daylit::test::LVec3;

namespace {

constexpr double pi = std::numbers::pi;

// Directions from p to the corners of a polygon, oriented positively.
SphericalRegion region_of(const std::vector<Vec3>& corners, const Vec3& p = {}) {
  DirectionLoop loop;
  for (const Vec3& c : corners) loop.push_back(c - p);
  if (solid_angle(loop) < 0) std::reverse(loop.begin(), loop.end());
  return {{loop}};
}

using daylit::test::relative_error;

// Howell's configuration factors (SKY/DESIGN §7), evaluated in long double.
long double parallel_rectangle_factor(long double a, long double b, long double c) {
  const long double A = a / c, B = b / c;
  const long double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * std::numbers::pi_v<long double>);
}
long double perpendicular_rectangle_factor(long double a, long double b, long double c) {
  const long double s = std::sqrt(b * b + c * c);
  return (std::atan(a / b) - (b / s) * std::atan(a / s)) / (2 * std::numbers::pi_v<long double>);
}

Vec3 rotate(const Vec3& v) {
  // A fixed rotation with no special axis: R = Rz(0.7) Ry(−1.1) Rx(0.3).
  auto rx = [](Vec3 a, double t) { return Vec3{a.x, std::cos(t) * a.y - std::sin(t) * a.z, std::sin(t) * a.y + std::cos(t) * a.z}; };
  auto ry = [](Vec3 a, double t) { return Vec3{std::cos(t) * a.x + std::sin(t) * a.z, a.y, -std::sin(t) * a.x + std::cos(t) * a.z}; };
  auto rz = [](Vec3 a, double t) { return Vec3{std::cos(t) * a.x - std::sin(t) * a.y, std::sin(t) * a.x + std::cos(t) * a.y, a.z}; };
  return rz(ry(rx(v, 0.3), -1.1), 0.7);
}

// The solid angle of a positively oriented loop by Gauss–Bonnet, 2π − Σ turning angles, in long
// double: the turning angle at a vertex comes from the normals of its own two arcs, so no
// diagonal enters (an independent formula from the fan's; accurate for loops of O(1) size whose
// arcs stay well short of π).
long double gauss_bonnet_solid_angle(const DirectionLoop& loop) {
  const auto cross = [](const LVec3& a, const LVec3& b) {
    return LVec3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  };
  const auto dot = [](const LVec3& a, const LVec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
  const auto unit = [&](const Vec3& v) {
    const LVec3 l{v.x, v.y, v.z};
    const long double n = std::sqrt(dot(l, l));
    return LVec3{l.x / n, l.y / n, l.z / n};
  };
  const std::size_t m = loop.size();
  long double turning = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const LVec3 before = unit(loop[(i + m - 1) % m]), here = unit(loop[i]), after = unit(loop[(i + 1) % m]);
    const LVec3 n_in = cross(before, here), n_out = cross(here, after);
    turning += std::atan2(dot(cross(n_in, n_out), here), dot(n_in, n_out));
  }
  return 2 * std::numbers::pi_v<long double> - turning;
}

}  // namespace

TEST_CASE("solid angle of an octant is pi/2 and changes sign with orientation") {
  const DirectionLoop octant{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  CHECK(solid_angle(octant) == Approx(pi / 2).epsilon(1e-15));
  const DirectionLoop reversed{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  CHECK(solid_angle(reversed) == Approx(-pi / 2).epsilon(1e-15));
}

TEST_CASE("solid angle of a centred rectangle matches the closed form from near to 1e6 away") {
  // Ω = 4 asin(ab / sqrt((a² + 4d²)(b² + 4d²))) for an a × b rectangle centred on the axis at d.
  for (double d : {1e-3, 0.5, 1.0, 1e3, 1e6}) {
    const double a = 2, b = 1;
    const auto region = region_of({{-a / 2, -b / 2, d}, {a / 2, -b / 2, d}, {a / 2, b / 2, d}, {-a / 2, b / 2, d}});
    // The sums under the root in long double: at d = 1e-3 the argument of asin is 1 − 2.5e-6,
    // where asin amplifies its error 450-fold, and a + 4d² rounded in double had put the
    // reference itself 2.7e-14 off.
    const long double la = a, lb = b, ld = d;
    const long double ref = 4 * std::asin(la * lb / std::sqrt((la * la + 4 * ld * ld) * (lb * lb + 4 * ld * ld)));
    INFO("distance " << d);
    // Van Oosterom–Strackee with the difference form: a few ulps even at 1e6 (DESIGN.md §7), and at
    // 1e-3, where opposite corners lie 1.8e-3 from antipodal and the fan is drawn from inside
    // (from a corner it was 1.9e-14 off).
    CHECK(relative_error(solid_angle(region), double(ref)) < 1e-15);
  }
}

TEST_CASE("Lambert's formula gives the configuration factor of a parallel rectangle to 1e-12") {
  // F = E/(πL): ∫(n·u)dσ = π F for an element at the origin with normal +z.
  struct Case {
    double a, b, c;
  };
  for (const Case k : {Case{1, 1, 1}, Case{3, 0.5, 2}, Case{1e-4, 2e-4, 1}, Case{1, 1, 1e4}, Case{1e3, 1e3, 1e-2}}) {
    const auto region = region_of({{0, 0, k.c}, {k.a, 0, k.c}, {k.a, k.b, k.c}, {0, k.b, k.c}});
    const double ref = double(std::numbers::pi_v<long double> * parallel_rectangle_factor(k.a, k.b, k.c));
    INFO("a=" << k.a << " b=" << k.b << " c=" << k.c);
    CHECK(relative_error(lambert(region, {0, 0, 1}), ref) < 1e-12);
  }
}

TEST_CASE("Lambert's formula gives the configuration factor of a perpendicular rectangle to 1e-12") {
  // The rectangle starts in the receiver's plane (n·u = 0 along one edge): a stiff case.
  struct Case {
    double a, b, c;
  };
  for (const Case k : {Case{1, 1, 1}, Case{2, 0.5, 3}, Case{1, 2, 1e-2}, Case{1e-3, 1, 1e-3}, Case{50, 1, 50}}) {
    const auto region = region_of({{0, k.b, 0}, {k.a, k.b, 0}, {k.a, k.b, k.c}, {0, k.b, k.c}});
    const double ref = double(std::numbers::pi_v<long double> * perpendicular_rectangle_factor(k.a, k.b, k.c));
    INFO("a=" << k.a << " b=" << k.b << " c=" << k.c);
    // The reference itself cancels like c²; in long double it keeps > 12 digits for c ≥ 1e-3.
    CHECK(relative_error(lambert(region, {0, 0, 1}), ref) < 1e-12);
  }
}

TEST_CASE("axial and double-axis moments agree with quadrature over the area") {
  const Vec3 p{0.3, -0.2, 0.1};
  const std::vector<Vec3> corners{{-1, 2, 0.5}, {1.5, 2, 0.5}, {1.5, 2, 2}, {-1, 2, 2}};
  const auto region = region_of(corners, p);
  const Vec3 w = normalized(Vec3{0.2, 0.9, 0.4});
  const Vec3 v = normalized(Vec3{-0.3, 0.2, 1.0});
  const auto tau = axial_moments(region, w, 8);
  const LVec3 lp = test::lvec(p), o = test::lvec(corners[0]), e1{2.5, 0, 0}, e2{0, 0, 1.5};
  for (int n = 0; n <= 8; ++n) {
    const long double ref = test::integrate_directions(lp, o, e1, e2, [&](const LVec3& u) {
      return std::pow(w.x * u.x + w.y * u.y + w.z * u.z, (long double)n);
    });
    INFO("axial moment order " << n);
    CHECK(relative_error(tau[n], double(ref)) < 1e-12);
    const long double ref2 = test::integrate_directions(lp, o, e1, e2, [&](const LVec3& u) {
      return std::pow(w.x * u.x + w.y * u.y + w.z * u.z, (long double)n) * (v.x * u.x + v.y * u.y + v.z * u.z);
    });
    INFO("double-axis moment order " << n);
    CHECK(relative_error(double_axis_moment(region, w, v, n), double(ref2)) < 1e-12);
  }
}

TEST_CASE("double-axis moment reduces to the axial moment when v = w and to Lambert when n = 0") {
  const auto region = region_of({{-1, 1, 0.2}, {2, 1, 0.2}, {2, 1.5, 3}, {-1, 1.2, 3}});
  const Vec3 w = normalized(Vec3{0.1, 1, 0.5});
  const auto tau = axial_moments(region, w, 6);
  for (int n = 0; n <= 5; ++n) CHECK(relative_error(double_axis_moment(region, w, w, n), tau[n + 1]) < 1e-14);
  const Vec3 v{0, 0, 1};
  CHECK(relative_error(double_axis_moment(region, w, v, 0), lambert(region, v)) < 1e-15);
}

TEST_CASE("moments are invariant under rotation, vertex order and splitting of the region") {
  const std::vector<Vec3> corners{{-1, 2, 0.5}, {1.5, 2.5, 0.5}, {1.5, 2.5, 2}, {-1, 2, 2}};
  const auto region = region_of(corners);
  const Vec3 w = normalized(Vec3{0.2, 0.9, 0.4}), v{0, 0, 1};
  const double value = double_axis_moment(region, w, v, 3);

  std::vector<Vec3> rotated;
  for (const Vec3& c : corners) rotated.push_back(rotate(c));
  CHECK(relative_error(double_axis_moment(region_of(rotated), rotate(w), rotate(v), 3), value) < 1e-13);

  auto shifted = region;
  std::rotate(shifted.loops[0].begin(), shifted.loops[0].begin() + 1, shifted.loops[0].end());
  CHECK(relative_error(double_axis_moment(shifted, w, v, 3), value) < 1e-14);

  // Split along the segment between the midpoints of two opposite edges.
  const Vec3 m1 = 0.5 * (corners[0] + corners[1]), m2 = 0.5 * (corners[2] + corners[3]);
  SphericalRegion halves = region_of({corners[0], m1, m2, corners[3]});
  halves.loops.push_back(region_of({m1, corners[1], corners[2], m2}).loops[0]);
  CHECK(relative_error(double_axis_moment(halves, w, v, 3), value) < 1e-14);
}

TEST_CASE("a tiny luminaire far away tends to the point-source limit") {
  // A 1 mm square 1 km straight above: ∫(n·u)dσ → A/d² with relative correction O((s/d)²) ~ 1e-12.
  const double s = 1e-3, d = 1e3;
  const auto region = region_of({{-s / 2, -s / 2, d}, {s / 2, -s / 2, d}, {s / 2, s / 2, d}, {-s / 2, s / 2, d}});
  CHECK(relative_error(lambert(region, {0, 0, 1}), s * s / (d * d)) < 1e-11);
  CHECK(relative_error(solid_angle(region), s * s / (d * d)) < 1e-11);
}

TEST_CASE("solid angle: a loop with two nearly opposite vertices is not lost in its fan's diagonal") {
  // The region fuzz_visibility found: a receiver 1e-6 from the plane of an aperture 5.4e6 m from
  // the origin sees a convex loop whose first vertex lies 5e-7 rad from the opposite of the third
  // and fourth. The fan from the first vertex summed a triangle whose denominator cancels to
  // O(δ²): 1.2291 sr, 1.5e-3 off. Reference: the same fan in 50-digit arithmetic (mpmath, from
  // every apex alike) on these doubles, 1.230958876456394464. What is left is the conditioning of
  // the loop's own edge between the opposite vertices: the triangle holding them sums O(1) terms
  // to O(δ), a few times ε/δ ≈ 2e-10 relative (measured 7e-10 and 1.2e-10 for the two starts);
  // held to 5e-9, six orders below the fan's former error.
  const DirectionLoop loop = {{-1.7999969902632267, -1.7999958464138306, 6.8787470164239957e-07},
                              {3, 3, 2.9999980926518228},
                              {1.5000021453009258, 1.500001192092725, 0},
                              {3.1716835525398117e-06, 3.1716827490901976e-06, 0}};
  CHECK(relative_error(solid_angle(loop), 1.230958876456394464) < 5e-9);
  // Rotating the loop's start changes nothing beyond that.
  const DirectionLoop rotated = {loop[2], loop[3], loop[0], loop[1]};
  CHECK(relative_error(solid_angle(rotated), 1.230958876456394464) < 5e-9);
}

TEST_CASE("solid angle: a fan is drawn from a vertex or a direction with no nearly opposite diagonal") {
  SECTION("Gauss-Bonnet, the reference below, gives an octant and a centred square") {
    CHECK(relative_error(gauss_bonnet_solid_angle({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}), std::numbers::pi_v<long double> / 2) < 1e-17);
    CHECK(relative_error(gauss_bonnet_solid_angle({{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}), 2 * std::numbers::pi_v<long double> / 3) < 1e-17);
  }
  SECTION("a lune whose tips lie 1e-12 from opposite, the fuzz finding of CI's seed-1 run") {
    // A receiver within 1e-12 of the plane x = y of an aperture 5.4e6 m from the origin, in the
    // plane z = 0 of an occluder, facing up: its region is the lune between z = 0 and x = y. The
    // fan from the first vertex had the diagonal to the third, 1e-12 from π, and gave 3.1409051 sr
    // for the exact mode's loop and 3.1415563 for the rational mode's, whose vertices differ only
    // in the last bit and the sign of a zero. Every arc of the loop is ≤ 154°, so Gauss–Bonnet is
    // accurate to ~1e-18 here; the fan's two terms are held to 1e-15 (a few ulps each).
    const DirectionLoop exact_mode = {{-1.7999980908560265, -1.7999969470063679, 4.3655713253267835e-12},
                                      {3, 3, 2.9999980926518228},
                                      {1.5000021453009258, 1.5000011920927248, 0},
                                      {6.060330983768843e-13, 1.8180992951306528e-12, 0}};
    const DirectionLoop rational_mode = {{-1.7999980908560262, -1.7999969470063677, 4.3655713253267835e-12},
                                         {3, 3, 2.9999980926518228},
                                         {1.5000021453009258, 1.500001192092725, -0.0},
                                         {6.060330983768842e-13, 1.8180992951306528e-12, -0.0}};
    for (const DirectionLoop& loop : {exact_mode, rational_mode}) {
      const long double reference = gauss_bonnet_solid_angle(loop);
      for (std::size_t start = 0; start < loop.size(); ++start) {
        DirectionLoop rotated(loop.begin() + start, loop.end());
        rotated.insert(rotated.end(), loop.begin(), loop.begin() + start);
        CHECK(relative_error(solid_angle(rotated), reference) < 1e-15);
      }
    }
  }
  SECTION("lunes between exactly opposite tips, up to a near hemisphere, whatever their lengths") {
    // Tips ±x, the arcs through (0, 1, 0) and (0, cos α, sin α): a lune of dihedral angle α,
    // solid angle 2α exactly. Every fan from a tip has a diagonal exactly π long (0/0 in its
    // triangle); near α = π the middle vertices are nearly opposite too, so no vertex will do
    // and the fan is drawn from a direction inside (the pole of the lune, 90° from every vertex).
    // Four terms of at most 2π each, each within a few ulps: 1e-14 relative.
    const double lengths[4] = {2e-12, 3, 1.5, 7};
    for (double alpha : {0.3, pi / 2, 2.5, pi - 1e-3, pi - 1e-6, pi - 1e-9}) {
      const Vec3 corners[4] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, std::cos(alpha), std::sin(alpha)}};
      for (std::size_t start = 0; start < 4; ++start) {
        DirectionLoop loop, reversed;
        for (std::size_t i = 0; i < 4; ++i) loop.push_back(lengths[i] * corners[(start + i) % 4]);
        reversed.assign(loop.rbegin(), loop.rend());
        INFO("alpha " << alpha << ", start " << start);
        CHECK(relative_error(solid_angle(loop), 2 * alpha) < 1e-14);
        CHECK(relative_error(solid_angle(reversed), -2 * alpha) < 1e-14);
      }
    }
  }
}
