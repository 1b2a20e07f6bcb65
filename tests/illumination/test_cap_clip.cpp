// The sun's disk cut by visible regions (illumination/cap_clip.hpp): whole, halved exactly at a
// shadow edge through its centre, cut at an offset against a 1-D quadrature in polar coordinates
// about the sun, through a frame with a hole, and against Snyder's I_hemi-sub for a tilted receiver.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "illumination/cap_clip.hpp"
#include "illumination/solid_angle.hpp"
#include "reference_quadrature.hpp"

using namespace daylit;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double sun_half_angle = 0.533 / 2 * pi / 180;  // SKY.md: the disk subtends 0.533°

// The region of directions through the rectangle x ∈ [x0, x1], y ∈ [y0, y1] of the plane z = 1.
SphericalRegion window(double x0, double x1, double y0, double y1) {
  return directions_through({{x0, y0, 1}, {x1, y0, 1}, {x1, y1, 1}, {x0, y1, 1}}, {});
}

// ∫ over the cap about s = z of (z·u) on the side x ≥ z·tan δ (a great circle at angular distance
// δ from the centre): ∫_0^ρ 2 φ_max(θ) cos θ sin θ dθ with cos φ_max = tan δ cot θ, in long
// double. φ_max is constant (0 or π) below θ = |δ| and grows like √(θ − |δ|) above it, so the
// second piece is integrated in v with θ = |δ| + (ρ − |δ|) v², which makes the integrand smooth.
long double offset_cut_reference(long double rho, long double delta) {
  std::vector<long double> x, w;
  test::gauss_legendre(64, x, w);
  auto integrand = [&](long double theta) {
    const long double c = std::clamp(std::tan(delta) / std::tan(theta), -1.0L, 1.0L);
    return 2 * std::acos(c) * std::cos(theta) * std::sin(theta);
  };
  const long double kink = std::min(std::abs(delta), rho);
  long double below = 0, above = 0;
  for (int panel = 0; panel < 8; ++panel)
    for (int i = 0; i < 64; ++i) {
      const long double t = (panel + 0.5L * (x[i] + 1)) / 8;  // in (0, 1)
      below += w[i] * integrand(kink * t) * kink / 16;
      const long double theta = kink + (rho - kink) * t * t;
      above += w[i] * integrand(theta) * 2 * (rho - kink) * t / 16;
    }
  return below + above;
}

}  // namespace

TEST_CASE("the sun's disk wholly inside or outside a window") {
  const Vec3 z{0, 0, 1};
  const double full = pi * std::sin(sun_half_angle) * std::sin(sun_half_angle);
  CHECK(cap_lambert(window(-1, 1, -1, 1), z, sun_half_angle, z) == Approx(full).epsilon(1e-13));
  CHECK(cap_lambert(window(0.5, 1, -1, 1), z, sun_half_angle, z) == 0);
  // A tilted receiver: the whole disk counts with n·s (Snyder's I_hemi-sub in its first branch).
  const Vec3 n = normalized(Vec3{0.6, 0, 0.8});
  CHECK(cap_lambert(window(-1, 1, -1, 1), z, sun_half_angle, n) == Approx(full * 0.8).epsilon(1e-12));
}

TEST_CASE("a shadow edge through the sun's centre leaves exactly half the disk") {
  const Vec3 z{0, 0, 1};
  const double full = pi * std::sin(sun_half_angle) * std::sin(sun_half_angle);
  // The window's edge x = 0 passes through the sun's direction: half by symmetry.
  CHECK(cap_lambert(window(0, 1, -1, 1), z, sun_half_angle, z) == Approx(full / 2).epsilon(1e-12));
  CHECK(cap_lambert(window(-1, 0, -1, 1), z, sun_half_angle, z) == Approx(full / 2).epsilon(1e-12));
  // ... and a corner at the centre leaves a quarter.
  CHECK(cap_lambert(window(0, 1, 0, 1), z, sun_half_angle, z) == Approx(full / 4).epsilon(1e-12));
}

TEST_CASE("an edge at an offset from the centre cuts a segment that matches quadrature") {
  const Vec3 z{0, 0, 1};
  for (double rho : {sun_half_angle, 0.2})
    for (double fraction : {-0.9, -0.3, 0.1, 0.7, 0.99}) {
      const double delta = fraction * rho;
      // Window x ≥ tan δ at z = 1: its edge is the great circle at angular distance δ from z.
      const double value = cap_lambert(window(std::tan(delta), 10, -10, 10), z, rho, z);
      const long double reference = offset_cut_reference(rho, delta);
      INFO("rho " << rho << ", delta " << delta);
      CHECK(value == Approx(double(reference)).epsilon(1e-11));
    }
}

TEST_CASE("a frame with a hole: the winding number weights the disk's circle") {
  // The disk sits in the hole of a frame (outer loop positive, hole reversed): nothing is seen; a
  // hole that only covers half the disk leaves the other half.
  const Vec3 z{0, 0, 1};
  const double full = pi * std::sin(sun_half_angle) * std::sin(sun_half_angle);
  SphericalRegion frame = window(-1, 1, -1, 1);
  DirectionLoop hole = window(-0.1, 0.1, -0.1, 0.1).loops[0];
  std::reverse(hole.begin(), hole.end());
  frame.loops.push_back(hole);
  CHECK(std::abs(cap_lambert(frame, z, sun_half_angle, z)) < 1e-18);
  SphericalRegion half_hole = window(-1, 1, -1, 1);
  DirectionLoop edge_hole = window(0, 0.1, -0.1, 0.1).loops[0];
  std::reverse(edge_hole.begin(), edge_hole.end());
  half_hole.loops.push_back(edge_hole);
  CHECK(cap_lambert(half_hole, z, sun_half_angle, z) == Approx(full / 2).epsilon(1e-12));
}

TEST_CASE("a disk clear of every edge: inside or outside a non-convex loop, two pieces, a loop given twice") {
  // No edge's great circle comes within ρ of the sun here, so the winding number about the sun
  // decides alone (the path without arcs); where an edge's circle does, the general path.
  const Vec3 z{0, 0, 1};
  const double full = pi * std::sin(sun_half_angle) * std::sin(sun_half_angle);
  // An L: [−1, 1] × [−1, 0] and [−1, 0] × [0, 1] as one loop, seen from the sensor at the origin.
  const auto l_shape = [](double dx, double dy) {
    return directions_through({{-1 - dx, -1 - dy, 1},
                               {1 - dx, -1 - dy, 1},
                               {1 - dx, -dy, 1},
                               {-dx, -dy, 1},
                               {-dx, 1 - dy, 1},
                               {-1 - dx, 1 - dy, 1}},
                              {});
  };
  // Shifted by −(dx, dy), the sun (on the axis) lies in the notch, the corner square, the upper arm.
  CHECK(cap_lambert(l_shape(0.5, 0.5), z, sun_half_angle, z) == 0);
  CHECK(cap_lambert(l_shape(-0.5, -0.5), z, sun_half_angle, z) == Approx(full).epsilon(1e-13));
  CHECK(cap_lambert(l_shape(-0.5, 0.5), z, sun_half_angle, z) == Approx(full).epsilon(1e-13));
  // Two pieces side by side, the sun in the second; the same loop twice counts twice.
  SphericalRegion pieces = window(-1, -0.2, -1, 1);
  pieces.loops.push_back(window(-0.2, 1, -1, 1).loops[0]);
  CHECK(cap_lambert(pieces, z, sun_half_angle, z) == Approx(full).epsilon(1e-13));
  SphericalRegion twice = window(-1, 1, -1, 1);
  twice.loops.push_back(twice.loops[0]);
  CHECK(cap_lambert(twice, z, sun_half_angle, z) == Approx(2 * full).epsilon(1e-13));
  // A tilted sun and receiver, the window far from the zenith.
  const Vec3 s = normalized(Vec3{1, 0.3, 1});
  const Vec3 n = normalized(Vec3{0.2, 0.1, 1});
  CHECK(cap_lambert(window(0.5, 1.5, -0.5, 1), s, sun_half_angle, n) == Approx(full * dot(n, s)).epsilon(1e-13));
  CHECK(cap_lambert(window(1.2, 1.5, -0.5, 1), s, sun_half_angle, n) == 0);
}
