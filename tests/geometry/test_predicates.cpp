// The signs the culling decides on input coordinates (geometry/predicates.hpp) against the same
// polynomials evaluated in rationals: each static filter may answer only when it is right, on
// inputs far from and right at degeneracy, near the origin and 5.4e6 m from it.

#include <catch2/catch.hpp>

#include <CGAL/Gmpq.h>

#include <array>

#include "geometry/predicates.hpp"
#include "illumination/xoshiro256.hpp"

using namespace daylit;
using Q = CGAL::Gmpq;

namespace {

std::array<Q, 3> q(const Vec3& v) { return {Q(v.x), Q(v.y), Q(v.z)}; }
std::array<Q, 3> minus(const std::array<Q, 3>& a, const std::array<Q, 3>& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Q dot(const std::array<Q, 3>& a, const std::array<Q, 3>& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
std::array<Q, 3> cross(const std::array<Q, 3>& a, const std::array<Q, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
int sign(const Q& x) { return int(CGAL::sign(x)); }

// A point of one of four kinds: anywhere in a 20 m cube; on the plane of (a, b, c) as rounded
// from its parametric form (within an ulp or so of it); that point moved by 1e-15 to 1e-9 m;
// or on a 0.25 m grid of two floors, where planes are shared exactly.
struct PointMaker {
  Xoshiro256 rng{20261206};
  double offset = 0;
  Vec3 anywhere() { return {offset + rng.uniform(-10, 10), offset + rng.uniform(-10, 10), rng.uniform(-10, 10)}; }
  Vec3 on_grid() {
    return {offset + 0.25 * double(rng.uniform_int(-8, 8)), offset + 0.25 * double(rng.uniform_int(-8, 8)),
            0.25 * double(rng.uniform_int(0, 1))};  // two floors: often all four points on one
  }
  Vec3 near_plane(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double s = rng.uniform(-2, 2), t = rng.uniform(-2, 2);
    Vec3 x = a + s * (b - a) + t * (c - a);
    if (rng.uniform(0, 1) < 0.5) x.z += std::pow(10.0, rng.uniform(-15, -9)) * (rng.uniform(0, 1) < 0.5 ? -1 : 1);
    return x;
  }
};

}  // namespace

TEST_CASE("the culling's predicates give the exact sign, near degeneracy and 5.4e6 m away too") {
  for (const double offset : {0.0, 5.4e6}) {
    PointMaker make;
    make.offset = offset;
    int zeros = 0, decided = 0;
    for (int trial = 0; trial < 30000; ++trial) {
      const bool grid = trial % 3 == 0;
      const Vec3 p = grid ? make.on_grid() : make.anywhere(), a = grid ? make.on_grid() : make.anywhere(),
                 b = grid ? make.on_grid() : make.anywhere();
      const Vec3 c = grid ? make.on_grid() : trial % 3 == 1 ? make.near_plane(p, a, b) : make.anywhere();
      const Vec3 n = trial % 2 ? Vec3{0, 0, 1} : Vec3{make.rng.uniform(-1, 1), make.rng.uniform(-1, 1), make.rng.uniform(-1, 1)};
      const auto P = q(p), A = q(a), B = q(b), C = q(c);
      const int orient = sign(dot(cross(minus(A, P), minus(B, P)), minus(C, P)));
      const int along = sign(dot(q(n), minus(C, P)));
      const int normal = sign(dot(cross(minus(A, P), minus(B, P)), minus(C, A)));
      INFO("offset " << offset << ", trial " << trial);
      REQUIRE(predicates::ExactSigns::orient3(p, a, b, c) == orient);
      REQUIRE(predicates::ExactSigns::dot_diff(n, c, p) == along);
      REQUIRE(predicates::ExactSigns::normal_dot_diff(p, a, b, c, a) == normal);
      zeros += orient == 0;
      decided += orient != 0;
    }
    // The inputs reach the degenerate cases the filters must not decide (grid points share planes).
    CHECK(zeros > 1000);
    CHECK(decided > 10000);
  }
}
