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
    const long double ref = 4 * std::asin((long double)(a * b) / std::sqrt((long double)(a * a + 4 * d * d) * (b * b + 4 * d * d)));
    INFO("distance " << d);
    // Van Oosterom–Strackee with the difference form: a few ulps even at 1e6 (DESIGN.md §7).
    CHECK(relative_error(solid_angle(region), double(ref)) < 1e-14);
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
