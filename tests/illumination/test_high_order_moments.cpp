// High orders and stiff geometry for the moments of moments.hpp (DESIGN.md §5, §7): Phong
// exponents up to 10,000 far off the axis, where eq. 11 alone loses every digit, against
// long-double quadrature over the polygon's area (tests/reference_quadrature.hpp), which shares no
// formula with the kernels.
//
// Tolerances. The axes here are exact unit vectors and the corners exact in double, so the
// reference integrates the very same input. What remains is the kernels' own rounding, a few ulp
// per term amplified by the condition of (w·u)^n itself: a relative change ε in u changes the
// integrand by n·tan δ·ε (δ the angle from w), about 1e-12 at n = 10,000 and δ = 20°; we allow
// 1e-11 there and 1e-13 to 1e-12 at lower orders. The quadrature is converged below 1e-15 (checked
// by doubling its panels while writing these tests).

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "illumination/moments.hpp"
#include "illumination/solid_angle.hpp"
#include "reference_quadrature.hpp"
#include "test_support.hpp"

using namespace daylit;
using daylit::test::LVec3;

namespace {

long double ldot(const Vec3& a, const LVec3& u) { return a.x * u.x + a.y * u.y + a.z * u.z; }

using daylit::test::relative_error;

// An axis-aligned rectangle in the plane z = height, seen from the origin.
struct Rectangle {
  double x0, x1, y0, y1, height = 1;

  SphericalRegion region() const {
    return directions_through({{x0, y0, height}, {x1, y0, height}, {x1, y1, height}, {x0, y1, height}}, {});
  }
  // ∫ g(u) dσ over the rectangle's directions; `panels` per side, 24 Gauss points each.
  long double integrate(const std::function<long double(const LVec3&)>& g, int panels) const {
    return test::integrate_directions({0, 0, 0}, {x0, y0, height}, {x1 - x0, 0, 0}, {0, y1 - y0, 0}, g, panels);
  }
};

const Vec3 z_axis{0, 0, 1};

}  // namespace

TEST_CASE("axial, double- and triple-axis moments stay accurate up to n = 10,000 far off the axis") {
  // The rectangle lies 11° to 31° from the axis: τ^n falls to 1e-53 at n = 10,000 while the terms
  // of eq. 11 stay O(1); the complementary form keeps the digits.
  const Rectangle rect{0.2, 0.6, -0.2, 0.2};
  const auto region = rect.region();
  const Vec3 a{0.3, -0.5, 0.2}, b{-0.2, 0.4, 0.9};
  for (int n : {0, 1, 2, 10, 100, 1000, 10000}) {
    const int panels = n >= 1000 ? 64 : 8;  // the integrand varies by e^{-n δ Δδ} across the rectangle
    const long double axial = rect.integrate([&](const LVec3& u) { return std::pow(u.z, (long double)n); }, panels);
    const long double dbl = rect.integrate([&](const LVec3& u) { return std::pow(u.z, (long double)n) * ldot(a, u); }, panels);
    const long double tri =
        rect.integrate([&](const LVec3& u) { return std::pow(u.z, (long double)n) * ldot(a, u) * ldot(b, u); }, panels);
    const double tolerance = n >= 1000 ? 1e-11 : 1e-13;
    INFO("n = " << n << ", axial moment " << double(axial));
    CHECK(relative_error(axial_moment(region, z_axis, n), axial) < tolerance);
    CHECK(relative_error(double_axis_moment(region, z_axis, a, n), dbl) < tolerance);
    CHECK(relative_error(triple_axis_moment(region, z_axis, a, b, n), tri) < tolerance);
    CHECK(triple_axis_moment_with_accuracy(region, z_axis, a, b, n).relative_error < 1e-12);
  }
}

TEST_CASE("the lobe inside the region: n = 10,000 gives 2π/(n+1)") {
  // The axis pierces the rectangle 0.1 rad from its nearest edge: τ^n = 2π/(n + 1) to within
  // cos^n(0.1) ≈ e^{-n·0.01/2} ≈ 2e-22 relative, a closed form independent of any quadrature.
  const Rectangle rect{-0.1, 0.3, -0.2, 0.2};
  for (int n : {10000, 20000}) {
    CHECK(relative_error(axial_moment(rect.region(), z_axis, n), 2 * std::numbers::pi_v<long double> / (n + 1)) < 1e-13);
  }
  // ... and −w in the region: odd orders count it negative, even ones positive.
  const Rectangle below{-0.1, 0.3, -0.2, 0.2, -1};
  CHECK(relative_error(axial_moment(below.region(), z_axis, 10001), -2 * std::numbers::pi_v<long double> / 10002) < 1e-13);
  CHECK(relative_error(axial_moment(below.region(), z_axis, 10000), 2 * std::numbers::pi_v<long double> / 10001) < 1e-13);
}

TEST_CASE("a luminaire of 1e-4 rad with 1e-4 rad edges keeps its digits at every order") {
  // Short arcs: the endpoint differences of eq. 19 are formed from the chord, not by subtraction.
  const Rectangle tiny{0.5, 0.5001, 0.1, 0.1001};
  const auto region = tiny.region();
  const Vec3 a{0.3, -0.5, 0.2};
  for (int n : {1, 10, 100, 1000}) {
    const long double axial = tiny.integrate([&](const LVec3& u) { return std::pow(u.z, (long double)n); }, 2);
    const long double dbl = tiny.integrate([&](const LVec3& u) { return std::pow(u.z, (long double)n) * ldot(a, u); }, 2);
    INFO("n = " << n << ": errors " << relative_error(axial_moment(region, z_axis, n), axial) << ", "
                << relative_error(double_axis_moment(region, z_axis, a, n), dbl));
    CHECK(relative_error(axial_moment(region, z_axis, n), axial) < 1e-12);
    CHECK(relative_error(double_axis_moment(region, z_axis, a, n), dbl) < 1e-12);
  }
}

TEST_CASE("an edge whose great circle passes through the axis, and an axis on a vertex") {
  // w = z lies in the plane of the edge x = 0 (c = 1 on that edge) and, in the second region, is a
  // vertex: the forward form is well conditioned there and must be the one used.
  const Rectangle touching{0, 0.4, 0.1, 0.5};
  const Rectangle cornered{0, 0.4, 0, 0.5};
  for (const Rectangle& rect : {touching, cornered})
    for (int n : {1, 7, 100, 2000}) {
      const long double axial = rect.integrate([&](const LVec3& u) { return std::pow(u.z, (long double)n); }, 48);
      INFO("n = " << n << ", y0 = " << rect.y0);
      CHECK(relative_error(axial_moment(rect.region(), z_axis, n), axial) < 1e-11);
    }
}

TEST_CASE("special cases: n = 0 is the solid angle, v = w reduces the double-axis moment, a = b = w the triple") {
  const auto region = Rectangle{0.2, 0.9, -0.3, 0.4}.region();
  const Vec3 w = normalized(Vec3{0.3, 0.1, 1}), v{0.2, -0.7, 0.4};
  CHECK(axial_moment(region, w, 0) == Approx(solid_angle(region)).epsilon(1e-15));
  for (int n : {0, 1, 5, 300}) {
    const double next = axial_moment(region, w, n + 1), after = axial_moment(region, w, n + 2);
    CHECK(double_axis_moment(region, w, w, n) == Approx(next).epsilon(1e-13));
    CHECK(triple_axis_moment(region, w, w, w, n) == Approx(after).epsilon(1e-13));
    CHECK(triple_axis_moment(region, w, v, w, n) == Approx(double_axis_moment(region, w, v, n + 1)).epsilon(1e-13));
  }
  // Eq. 11's all-orders pass and the single-order form agree where eq. 11 does not cancel.
  const auto tau = axial_moments(region, w, 12);
  for (int n = 0; n <= 12; ++n) CHECK(axial_moment(region, w, n) == Approx(tau[n]).epsilon(1e-14));
}

TEST_CASE("moments are additive over a split region at high order") {
  const Rectangle whole{0.2, 0.6, -0.2, 0.2}, left{0.2, 0.35, -0.2, 0.2}, right{0.35, 0.6, -0.2, 0.2};
  const Vec3 v{0.1, 0.2, 0.9};
  for (int n : {50, 3000}) {
    CHECK(axial_moment(whole.region(), z_axis, n) ==
          Approx(axial_moment(left.region(), z_axis, n) + axial_moment(right.region(), z_axis, n)).epsilon(1e-12));
    CHECK(double_axis_moment(whole.region(), z_axis, v, n) ==
          Approx(double_axis_moment(left.region(), z_axis, v, n) + double_axis_moment(right.region(), z_axis, v, n))
              .epsilon(1e-12));
  }
}

TEST_CASE("early termination returns a bound that holds and does less work where the axis is far from the edges") {
  // A large luminaire centred on the lobe: every edge's plane is 45° from the axis (c = 0.71),
  // so the series of eq. 11 converges like 0.5^j and the order-200 moment needs far fewer than
  // its 100 terms per edge (Arvo's case for early termination).
  const Rectangle rect{-1, 1, -1, 1};
  const auto region = rect.region();
  const Vec3 w = z_axis, v = normalized(Vec3{0.3, 0, 1});
  const int n = 200;
  const double exact = axial_moment(region, w, n), exact_v = double_axis_moment(region, w, v, n);
  for (double tolerance : {1e-3, 1e-6, 1e-10, 1e-14}) {
    const TruncatedMoment t = axial_moment_truncated(region, w, n, tolerance);
    const TruncatedMoment tv = double_axis_moment_truncated(region, w, v, n, tolerance);
    INFO("tolerance " << tolerance);
    // The bound holds up to the rounding of the exact value itself (1e-14 relative).
    CHECK(std::abs(t.value - exact) <= t.error_bound + 1e-14 * std::abs(exact));
    CHECK(std::abs(tv.value - exact_v) <= tv.error_bound + 1e-14 * std::abs(exact_v));
    CHECK(t.error_bound <= 2 * tolerance * std::abs(exact) + 1e-14 * std::abs(exact));
    if (tolerance >= 1e-10) CHECK(t.terms < 4 * n / 2);
  }
  // Tolerance 0: every term, the value of eq. 11.
  CHECK(axial_moment_truncated(region, w, n, 0).value == Approx(exact).epsilon(1e-13));

  // Far off the axis eq. 11 cancels and so does its truncation; the bound still says so.
  const auto far = Rectangle{1, 2, -0.5, 0.5}.region();
  const TruncatedMoment t = axial_moment_truncated(far, w, n, 1e-6);
  CHECK(std::abs(t.value - axial_moment(far, w, n)) <= t.error_bound);
}

TEST_CASE("a non-convex luminaire with a hole at n = 500: the L-shape and the frame add up") {
  // An L-shaped polygon (one non-convex loop) and a frame (outer loop and a reversed inner loop)
  // against the sums and differences of rectangles they are made of.
  const Vec3 w = normalized(Vec3{0.1, 0.05, 1}), v{0.3, -0.2, 0.9};
  const int n = 500;
  const auto L = directions_through({{0.2, -0.2, 1}, {0.6, -0.2, 1}, {0.6, 0.0, 1}, {0.4, 0.0, 1}, {0.4, 0.2, 1}, {0.2, 0.2, 1}}, {});
  const double parts = axial_moment(Rectangle{0.2, 0.6, -0.2, 0.0}.region(), w, n) +
                       axial_moment(Rectangle{0.2, 0.4, 0.0, 0.2}.region(), w, n);
  CHECK(axial_moment(L, w, n) == Approx(parts).epsilon(1e-12));
  SphericalRegion frame = Rectangle{-0.3, 0.3, -0.3, 0.3}.region();
  DirectionLoop hole = Rectangle{-0.1, 0.1, -0.1, 0.1}.region().loops[0];
  std::reverse(hole.begin(), hole.end());
  frame.loops.push_back(hole);
  const double difference = double_axis_moment(Rectangle{-0.3, 0.3, -0.3, 0.3}.region(), w, v, n) -
                            double_axis_moment(Rectangle{-0.1, 0.1, -0.1, 0.1}.region(), w, v, n);
  CHECK(double_axis_moment(frame, w, v, n) == Approx(difference).epsilon(1e-12));
}
