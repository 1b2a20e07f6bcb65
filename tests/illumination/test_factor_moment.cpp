// Factor-pattern moments of polygon regions, with and without a clip hemisphere, against
// long-double quadrature over the polygon's area.

#include <catch2/catch.hpp>

#include <cmath>

#include "geometry/error.hpp"
#include "illumination/factor_moment.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "reference_quadrature.hpp"

using namespace daylit;
using daylit::test::LVec3;

namespace {

long double ldot(const Vec3& a, const LVec3& u) { return a.x * u.x + a.y * u.y + a.z * u.z; }

}  // namespace

TEST_CASE("directions through a polygon are positive whatever the vertex order") {
  const std::vector<Vec3> square{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::vector<Vec3> reversed(square.rbegin(), square.rend());
  const double a = factor_moment(directions_through(square, {}), {}).value;
  const double b = factor_moment(directions_through(reversed, {}), {}).value;
  CHECK(a == Approx(3.14159265358979323846 / 6).epsilon(1e-15));
  CHECK(a == b);
  CHECK(directions_through(square, {5, 5, 1}).empty());  // origin in the polygon's plane
}

TEST_CASE("factor patterns (n), (n,1) and (n,1,1) with non-unit axes agree with quadrature") {
  const std::vector<Vec3> quad{{-0.5, 1.5, 0.2}, {1.2, 1.5, 0.2}, {1.2, 1.5, 1.9}, {-0.5, 1.5, 1.9}};
  const Vec3 origin{0.1, -0.3, 0.4};
  const auto region = directions_through(quad, origin);
  const Vec3 a{0.4, 1.8, 0.6}, b{-0.3, 0.2, 2.0}, c{1.1, -0.4, 0.3};
  const LVec3 o{-0.5, 1.5, 0.2}, e1{1.7, 0, 0}, e2{0, 0, 1.7};
  for (int n : {0, 1, 2, 5, 8}) {
    const long double ref_n = test::integrate_directions(test::lvec(origin), o, e1, e2,
                                                         [&](const LVec3& u) { return std::pow(ldot(a, u), (long double)n); });
    const long double ref_n1 = test::integrate_directions(test::lvec(origin), o, e1, e2, [&](const LVec3& u) {
      return std::pow(ldot(a, u), (long double)n) * ldot(b, u);
    });
    const long double ref_n11 = test::integrate_directions(test::lvec(origin), o, e1, e2, [&](const LVec3& u) {
      return std::pow(ldot(a, u), (long double)n) * ldot(b, u) * ldot(c, u);
    });
    INFO("n = " << n);
    CHECK(factor_moment(region, {{a, n}}).value == Approx(double(ref_n)).epsilon(1e-12));
    // Either order of the factors.
    CHECK(factor_moment(region, {{b, 1}, {a, n}}).value == Approx(double(ref_n1)).epsilon(1e-12));
    CHECK(factor_moment(region, {{b, 1}, {c, 1}, {a, n}}).value == Approx(double(ref_n11)).epsilon(1e-12));
  }
}

TEST_CASE("a clip hemisphere keeps exactly the part of the region in front of it") {
  // Square z = 1, x, y ∈ [−1, 1] seen from the origin, clipped to x ≥ 0.3 z: the part with x ≥ 0.3.
  const std::vector<Vec3> square{{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  const auto region = clip_to_hemisphere(directions_through(square, {}), {1, 0, -0.3});
  const Vec3 z{0, 0, 1};
  const long double ref = test::integrate_directions({0, 0, 0}, {0.3L, -1, 1}, {0.7L, 0, 0}, {0, 2, 0},
                                                     [&](const LVec3& u) { return ldot(z, u); });
  CHECK(factor_moment(region, {{z, 1}}).value == Approx(double(ref)).epsilon(1e-12));
  CHECK(clip_to_hemisphere(directions_through(square, {}), {0, 0, -1}).empty());
}

TEST_CASE("unsupported factor patterns are refused by name") {
  const auto region = directions_through({{0, 0, 1}, {1, 0, 1}, {1, 1, 1}}, {});
  CHECK_THROWS_WITH(factor_moment(region, {{{1, 0, 0}, 2}, {{0, 1, 0}, 1}, {{0, 0, 1}, 1}, {{1, 1, 0}, 1}}),
                    Catch::Contains("(2,1,1,1)"));
  CHECK_THROWS_WITH(factor_moment(region, {{{1, 0, 0}, 2}, {{0, 1, 0}, 2}}), Catch::Contains("(2,2)"));
  CHECK_THROWS_AS(factor_moment(region, {{{0, 0, 0}, 1}}), Error);
}
