// Monte Carlo moments (illumination/monte_carlo.hpp): the winding number against a planar
// point-in-polygon test, the estimators against the closed forms of moments.hpp, and their
// standard errors against the spread actually observed over seeds.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "illumination/moments.hpp"
#include "illumination/monte_carlo.hpp"
#include "illumination/xoshiro256.hpp"

using namespace daylit;

namespace {

struct Point2 {
  double s, t;
};

// A planar polygon given in 2D coordinates (s, t) of the plane centre + s·e1 + t·e2.
struct PlanarPolygon {
  Vec3 centre, e1, e2;
  std::vector<Point2> outer;
  std::vector<Point2> hole;  // optional, inside outer

  Vec3 lift(const Point2& p) const { return centre + p.s * e1 + p.t * e2; }
};

// Even–odd crossing test in the plane (Shimrat's algorithm 112).
bool inside_2d(const std::vector<Point2>& poly, const Point2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Point2 &a = poly[i], &b = poly[j];
    if ((a.t > p.t) != (b.t > p.t) && p.s < (b.s - a.s) * (p.t - a.t) / (b.t - a.t) + a.s) in = !in;
  }
  return in;
}

// The region of directions from `origin` through the polygon (outer boundary positive, the hole
// as a second loop of opposite orientation).
SphericalRegion region_of(const PlanarPolygon& poly, const Vec3& origin) {
  std::vector<Vec3> outer, hole;
  for (const Point2& p : poly.outer) outer.push_back(poly.lift(p));
  SphericalRegion region = directions_through(outer, origin);
  if (!poly.hole.empty()) {
    for (const Point2& p : poly.hole) hole.push_back(poly.lift(p));
    SphericalRegion h = directions_through(hole, origin);
    std::reverse(h.loops[0].begin(), h.loops[0].end());
    region.loops.push_back(h.loops[0]);
  }
  return region;
}

// Does the ray from origin along u hit the polygon (minus its hole)?
bool ray_hits(const PlanarPolygon& poly, const Vec3& origin, const Vec3& u) {
  const Vec3 normal = cross(poly.e1, poly.e2);
  const double along = dot(normal, u);
  if (along == 0) return false;
  const double t = dot(normal, poly.centre - origin) / along;
  if (!(t > 0)) return false;
  const Vec3 x = origin + t * u - poly.centre;
  const Point2 p{dot(x, poly.e1) / dot(poly.e1, poly.e1), dot(x, poly.e2) / dot(poly.e2, poly.e2)};
  return inside_2d(poly.outer, p) && !(poly.hole.size() >= 3 && inside_2d(poly.hole, p));
}

// Uniform on the sphere (Archimedes: z uniform in [−1, 1]), from Xoshiro256, so that the
// directions are the same on every platform (std::normal_distribution's are not).
Vec3 random_direction(Xoshiro256& rng) {
  const double z = rng.uniform(-1, 1), phi = rng.uniform(0, 2 * std::numbers::pi);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// An L-shaped (non-convex) window in the vertical plane y = 3, seen from a desk point.
PlanarPolygon l_shaped_window() {
  return {{0, 3, 1.5}, {1, 0, 0}, {0, 0, 1}, {{-1.2, -0.6}, {1.2, -0.6}, {1.2, 0.0}, {0.1, 0.0}, {0.1, 0.6}, {-1.2, 0.6}}, {}};
}

// A tilted square rooflight with a square hole, its vertices in clockwise order.
PlanarPolygon rooflight_with_hole() {
  const Vec3 e1 = normalized(Vec3{1, 0, 0.3}), e2 = normalized(cross(Vec3{-0.3, 0.2, 1}, e1));
  return {{0.4, -0.2, 2.5}, e1, e2, {{-1, -1}, {-1, 1}, {1, 1}, {1, -1}}, {{-0.3, -0.4}, {0.5, -0.4}, {0.5, 0.2}, {-0.3, 0.2}}};
}

double exact_moment(const SphericalRegion& region, const MomentIntegrand& f) {
  return f.v ? double_axis_moment(region, f.w, *f.v, f.n) : axial_moments(region, f.w, f.n)[std::size_t(f.n)];
}

struct Case {
  const char* name;
  SphericalRegion region;
  MomentIntegrand f;
  // Relative standard error the lobe sampler must reach at N = 4096: larger where the lobe puts
  // most samples outside the region; 0 where it almost never hits it (no check of its accuracy or
  // its standard error, which is 0 when no sample hits: only of its bias).
  double lobe_accuracy = 0.05;
};

std::vector<Case> cases() {
  const Vec3 desk{0.3, 0.2, 0.8}, up{0, 0, 1};
  const SphericalRegion window = region_of(l_shaped_window(), desk);
  const SphericalRegion rooflight = region_of(rooflight_with_hole(), {0, 0, 0.8});
  // A window reaching below the receiver's horizon: the lobe around the zenith is sampled on
  // both sides of the plane w·u = 0.
  const SphericalRegion low = region_of({{0, 2, 0}, {1, 0, 0}, {0, 0, 1}, {{-1, -0.3}, {1, -0.3}, {1, 0.7}, {-1, 0.7}}, {}}, {0, 0, 0});
  return {
      {"L-shaped window, Lambert", window, {up, 1, std::nullopt}, 0.15},
      {"L-shaped window, overcast term (z·u)(n·u)", window, {up, 1, normalized(Vec3{0, 1, 1})}, 0.15},
      {"L-shaped window, Phong n = 10 double-axis", window, {normalized(Vec3{0.2, 1, 0.4}), 10, up}},
      // The region lies wholly where w·u < 0: the lobe is sampled on that side, with the odd power's sign.
      {"L-shaped window, lobe axis pointing away, n = 5", window, {normalized(Vec3{-0.2, -1, -0.4}), 5, up}},
      {"rooflight with a hole, n = 2 about a tilted axis", rooflight, {normalized(Vec3{0.3, -0.2, 1}), 2, std::nullopt}},
      {"rooflight with a hole, Phong n = 100 off-axis", rooflight, {normalized(Vec3{0.15, 0, 1}), 100, up}},
      {"window across the horizon, odd power n = 3", low, {up, 3, std::nullopt}, 0},
      {"window across the horizon, n = 4 with v", low, {Vec3{0, 2, 1}, 4, Vec3{0, 1, 0}}},
  };
}

}  // namespace

TEST_CASE("winding number agrees with a planar point-in-polygon test on every direction") {
  Xoshiro256 rng(7);
  struct Setup {
    PlanarPolygon poly;
    Vec3 origin;
  };
  for (const Setup& s : {Setup{l_shaped_window(), {0.3, 0.2, 0.8}}, Setup{l_shaped_window(), {-2, 0.5, 2.9}},
                         Setup{rooflight_with_hole(), {0, 0, 0.8}}, Setup{rooflight_with_hole(), {3, -1, 1.5}}}) {
    const SphericalRegion region = region_of(s.poly, s.origin);
    const RegionWinding winding(region);
    const SphericalCap& cap = winding.bounding_cap();
    int inside = 0, mismatches = 0;
    for (int i = 0; i < 20000; ++i) {
      // Half the directions uniform on the sphere, half in the bounding cap, where it matters.
      Vec3 u = random_direction(rng);
      if (i % 2 == 1) u = normalized(cap.axis + (std::sqrt(cap.height) * 1.5) * u);
      const int k = winding.winding(u);
      const bool hit = ray_hits(s.poly, s.origin, u);
      inside += hit;
      if (k != (hit ? 1 : 0)) ++mismatches;
    }
    CHECK(mismatches == 0);
    CHECK(inside > 1000);
  }
}

TEST_CASE("the bounding cap contains the region and a region beyond a hemisphere is refused") {
  const SphericalRegion region = region_of(rooflight_with_hole(), {0, 0, 0.8});
  const RegionWinding winding(region);
  for (const auto& loop : region.loops)
    for (const Vec3& v : loop) CHECK(dot(normalized(v), winding.bounding_cap().axis) >= 1 - winding.bounding_cap().height);
  // A zigzag around the equator: no hemisphere holds its vertices.
  DirectionLoop zigzag;
  for (int k = 0; k < 6; ++k) zigzag.push_back({std::cos(k * 1.0471975511965976), std::sin(k * 1.0471975511965976), k % 2 ? 0.3 : -0.3});
  const SphericalRegion wide{{zigzag}};
  CHECK_THROWS(RegionWinding(wide));
}

TEST_CASE("Monte Carlo estimates agree with the exact moments within 5 standard errors") {
  for (const Case& c : cases()) {
    const double exact = exact_moment(c.region, c.f);
    for (std::uint64_t seed : {1, 2}) {
      const MonteCarloEstimate uniform = moment_uniform_stratified(c.region, c.f, 4096, seed);
      const MonteCarloEstimate lobe = moment_lobe_importance(c.region, c.f, 4096, seed);
      INFO(c.name << ", seed " << seed << ": exact " << exact << ", uniform " << uniform.value << " ± "
                  << uniform.standard_error << ", lobe " << lobe.value << " ± " << lobe.standard_error);
      CHECK(uniform.standard_error > 0);
      if (c.lobe_accuracy > 0) CHECK(lobe.standard_error > 0);
      CHECK(std::abs(uniform.value - exact) < 5 * uniform.standard_error);
      if (c.lobe_accuracy > 0 || lobe.standard_error > 0) CHECK(std::abs(lobe.value - exact) < 5 * lobe.standard_error);
      // Both are small against the moment itself: the estimators are not merely unbiased.
      CHECK(uniform.standard_error < 0.05 * std::abs(exact));
      if (c.lobe_accuracy > 0) CHECK(lobe.standard_error < c.lobe_accuracy * std::abs(exact));
    }
  }
}

TEST_CASE("Monte Carlo standard errors match the error observed over 20 seeds within a factor 2") {
  for (const Case& c : cases()) {
    const double exact = exact_moment(c.region, c.f);
    for (long samples : {64L, 1024L}) {
      double error2[2] = {0, 0}, se2[2] = {0, 0};
      for (std::uint64_t seed = 100; seed < 120; ++seed) {
        const MonteCarloEstimate e[2] = {moment_uniform_stratified(c.region, c.f, samples, seed),
                                         moment_lobe_importance(c.region, c.f, samples, seed)};
        for (int m = 0; m < 2; ++m) {
          error2[m] += (e[m].value - exact) * (e[m].value - exact);
          se2[m] += e[m].standard_error * e[m].standard_error;
        }
      }
      for (int m = 0; m < (c.lobe_accuracy > 0 ? 2 : 1); ++m) {
        const double ratio = std::sqrt(error2[m] / se2[m]);
        INFO(c.name << ", " << (m == 0 ? "uniform" : "lobe") << ", N = " << samples << ": RMS error / RMS SE = " << ratio);
        CHECK(ratio > 0.5);
        CHECK(ratio < 2.0);
      }
    }
  }
}

TEST_CASE("Monte Carlo estimates are deterministic for a seed and handle odd sample counts") {
  const Case c = cases()[2];
  const MonteCarloEstimate a = moment_uniform_stratified(c.region, c.f, 1001, 5);
  const MonteCarloEstimate b = moment_uniform_stratified(c.region, c.f, 1001, 5);
  CHECK(a.value == b.value);
  CHECK(a.standard_error == b.standard_error);
  CHECK(std::abs(a.value - exact_moment(c.region, c.f)) < 5 * a.standard_error);
  CHECK_THROWS(moment_lobe_importance(c.region, c.f, 1, 5));
}
