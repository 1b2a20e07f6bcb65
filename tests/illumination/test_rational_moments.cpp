// Rational moments ∫_A P(u)/(w·u)^q dσ (Chen and Arvo) against long-double quadrature of the
// same integrals over the luminaire's surface (tests/reference_quadrature.hpp: it shares no code
// or formula with the kernels), and against each other where two routes exist.

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <vector>

#include "geometry/error.hpp"
#include "illumination/rational_moments.hpp"
#include "tests/reference_quadrature.hpp"

using namespace daylit;
using test::LVec3;

namespace {

long double dotl(const Vec3& a, const LVec3& u) { return a.x * u.x + a.y * u.y + a.z * u.z; }

struct Scene {
  Vec3 p;           // receiver
  Vec3 c0, e1, e2;  // parallelogram
  SphericalRegion region() const { return directions_through({c0, c0 + e1, c0 + e1 + e2, c0 + e2}, p); }
  long double integrate(const std::function<long double(const LVec3&)>& g, int panels = 8) const {
    return test::integrate_directions({p.x, p.y, p.z}, {c0.x, c0.y, c0.z}, {e1.x, e1.y, e1.z}, {e2.x, e2.y, e2.z}, g,
                                      panels, 24);
  }
  // The same on panels graded towards (s, t) with widths (scale_s, scale_t), in fractions of the
  // edges (reference_quadrature.hpp): for integrands with a feature narrower than a panel.
  long double integrate_graded(const std::function<long double(const LVec3&)>& g, long double s, long double t,
                               long double scale_s, long double scale_t) const {
    const Vec3 m = normalized(cross(e1, e2));
    return test::integrate_parallelogram_graded(
        {c0.x, c0.y, c0.z}, {e1.x, e1.y, e1.z}, {e2.x, e2.y, e2.z},
        [&](const LVec3& x) {
          const LVec3 d{x.x - p.x, x.y - p.y, x.z - p.z};
          const long double r = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
          return g({d.x / r, d.y / r, d.z / r}) * std::abs(m.x * d.x + m.y * d.y + m.z * d.z) / (r * r * r);
        },
        s, t, scale_s, scale_t);
  }
};

const Scene kGeneral{{0.3, -0.2, 0}, {-0.5, -0.7, 1.3}, {1.2, 0, 0.1}, {0, 1.1, 0.2}};
const Vec3 kW = normalized(Vec3{0.2, 0.1, 1});
const Vec3 kV{0.3, 0.4, 0.8}, kA{1, -0.5, 0.2}, kB{-0.3, 0.7, 0.5};

// |got − ref| ≤ tol·|ref| with the values in the message.
void check_close(double got, long double ref, double tol) {
  INFO(got << " vs " << double(ref) << " (relative " << double((got - ref) / ref) << ")");
  CHECK(std::abs(got - ref) <= tol * std::abs(ref));
}

}  // namespace

TEST_CASE("τ^{0:1} = ∫ dσ/(w·u) through Cl2 matches quadrature, for w of any length") {
  // 3e-14: the Cl2 brackets (GSL, ≤ 8 ulp of their O(1) terms) summed over 8 brackets.
  const long double ref = kGeneral.integrate([](const LVec3& u) { return 1 / dotl(kW, u); });
  check_close(rational_base_moment(kGeneral.region(), kW).value, ref, 3e-14);
  check_close(rational_base_moment(kGeneral.region(), 3.0 * kW).value, ref / 3, 3e-14);
}

TEST_CASE("τ^{n:1}, τ^{n,1:1} and τ^{n,1,1:1} (eqs. 11–13) match quadrature for n up to 200") {
  const SphericalRegion region = kGeneral.region();
  for (const int n : {0, 1, 2, 3, 5, 10, 30, 100, 200}) {
    auto vn = [n](const LVec3& u) { return std::pow(dotl(kV, u), (long double)n); };
    const long double r1 = kGeneral.integrate([&](const LVec3& u) { return vn(u) / dotl(kW, u); });
    const long double r2 = kGeneral.integrate([&](const LVec3& u) { return vn(u) * dotl(kA, u) / dotl(kW, u); });
    const long double r3 =
        kGeneral.integrate([&](const LVec3& u) { return vn(u) * dotl(kA, u) * dotl(kB, u) / dotl(kW, u); });
    INFO("n = " << n);
    // 1e-13: each result's estimate is held below 1e-13 by escalation, and the reference
    // (8 × 8 panels of 24² points, long double) resolves (v·u)^200's lobe (width ~0.1 here).
    const auto m1 = rational_moment_n(region, kV, n, kW), m2 = rational_moment_n1(region, kV, n, kA, kW),
               m3 = rational_moment_n11(region, kV, n, kA, kB, kW);
    check_close(m1.value, r1, 1e-13);
    check_close(m2.value, r2, 1e-13);
    check_close(m3.value, r3, 1e-13);
    CHECK(m3.relative_error < 1e-13);
  }
}

TEST_CASE("the semi-analytic path converges to the exact one and its estimate bounds its error") {
  const SphericalRegion region = kGeneral.region();
  for (const int n : {5, 50, 300}) {
    const double exact = rational_moment_n11(region, kV, n, kA, kB, kW).value;
    double previous_error = HUGE_VAL;
    for (const int points : {4, 8, 16, 32, 64}) {
      const auto semi = rational_moment_n11(region, kV, n, kA, kB, kW, {RationalMethod::semi_analytic, points});
      const double error = std::abs(semi.value - exact) / std::abs(exact);
      INFO("n " << n << " points " << points << " error " << error << " estimate " << semi.relative_error);
      CHECK(error <= semi.relative_error + 1e-14);
      CHECK(error <= std::max(previous_error, 1e-14));
      previous_error = error;
    }
    CHECK(previous_error < 1e-12);  // 64 nodes resolve even n = 300 on edges this long
  }
}

TEST_CASE("general numerators with q = 1 and 2 (frame recurrences) match quadrature and eqs. 11–13") {
  const SphericalRegion region = kGeneral.region();
  for (const int n : {0, 1, 2, 4, 8}) {
    for (const int q : {0, 1, 2, 3}) {
      const long double ref = kGeneral.integrate([&](const LVec3& u) {
        return std::pow(dotl(kV, u), (long double)n) * dotl(kA, u) * dotl(kB, u) / std::pow(dotl(kW, u), (long double)q);
      });
      const auto m = rational_moment(region, {{kV, n}, {kA, 1}, {kB, 1}}, kW, q);
      INFO("n " << n << " q " << q);
      check_close(m.value, ref, 1e-13);
    }
    // Two routes to τ^{n,1,1;1}: Theorem 3 in w's frame and the linearly-varying paper's eq. 13.
    CHECK(rational_moment(region, {{kV, n}, {kA, 1}, {kB, 1}}, kW, 1).value ==
          Approx(rational_moment_n11(region, kV, n, kA, kB, kW).value).epsilon(1e-13));
  }
  // Mixed patterns of higher degree: (3, 2, 2) over (w·u)², and the denominator's length.
  const long double ref = kGeneral.integrate([&](const LVec3& u) {
    return std::pow(dotl(kV, u), 3.0L) * std::pow(dotl(kA, u), 2.0L) * std::pow(dotl(kB, u), 2.0L) /
           std::pow(dotl(kW, u), 2.0L);
  });
  check_close(rational_moment(region, {{kV, 3}, {kA, 2}, {kB, 2}}, 2.0 * kW, 2).value, ref / 4, 1e-13);
}

TEST_CASE("Chen and Arvo's tensors M³ and M⁴ on the boundary (eqs. 65, 76) agree with quadrature and the frame recurrences") {
  const Vec3 c{0.4, 0.1, 0.9};
  const std::vector<std::pair<Scene, Vec3>> scenes = {
      {kGeneral, kW},
      {{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {0, 0, 1}},  // edges through w (c = 1)
      {{{0, 0, 0}, {1, -1, 0.05}, {2, 0, 0}, {0, 2, 0.5}}, {0, 0, 1}},  // grazing: w·u down to 0.02
  };
  for (const auto& [scene, w] : scenes) {
    const SphericalRegion region = scene.region();
    const long double r2 = scene.integrate([&](const LVec3& u) { return dotl(kA, u) * dotl(kB, u) / dotl(w, u); }, 16);
    const long double r3 = scene.integrate(
        [&](const LVec3& u) { return dotl(kA, u) * dotl(kB, u) * dotl(c, u) / std::pow(dotl(w, u), 2.0L); }, 16);
    const auto lin = linear_exitance_moment(region, w, kA, kB);
    const auto quad = quadratic_exitance_moment(region, w, kA, kB, c);
    check_close(lin.value, r2, 1e-13);
    check_close(quad.value, r3, 1e-13);
    // The two routes share only the edge integrals G(r, t) and Λ.
    CHECK(lin.value == Approx(rational_moment(region, {{kA, 1}, {kB, 1}}, w, 1).value).epsilon(1e-14));
    CHECK(quad.value == Approx(rational_moment(region, {{kA, 1}, {kB, 1}, {c, 1}}, w, 2).value).epsilon(1e-14));
  }
}

TEST_CASE("w nearly tangent to the region: w·u down to 1e-4 on a luminaire seen at grazing angles") {
  // A vertical luminaire at x ∈ [1, 3] whose bottom edge is 1e-4 above the receiver's horizon:
  // 1/(w·u) reaches 3e4 there.
  const Scene s{{0, 0, 0}, {1, -1, 1e-4}, {2, 0, 0}, {0, 2, 0.5}};
  const SphericalRegion region = s.region();
  const Vec3 w{0, 0, 1};
  // Graded towards the bottom edge t = 0, where z = 1e-4 + 0.5 t varies on the scale 2e-4 of t.
  const long double r0 = s.integrate_graded([&](const LVec3& u) { return 1 / dotl(w, u); }, 0.5, 0, 1, 2e-4);
  check_close(rational_base_moment(region, w).value, r0, 1e-12);
  const long double r1 =
      s.integrate_graded([&](const LVec3& u) { return dotl(kA, u) * dotl(kB, u) / dotl(w, u); }, 0.5, 0, 1, 2e-4);
  check_close(rational_moment_n11(region, kV, 0, kA, kB, w).value, r1, 1e-12);
  check_close(rational_moment(region, {{kA, 1}, {kB, 1}}, w, 1).value, r1, 1e-12);
}

TEST_CASE("edges through the axis (w·m = 0), tiny regions and huge ones") {
  const Vec3 w{0, 0, 1};
  // The foot of w on a vertex: two edges lie in planes through w (c = 1, Λ(1, β) of eq. 35).
  const Scene corner{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
  const long double rc = corner.integrate([&](const LVec3& u) { return dotl(kV, u) * dotl(kA, u) / dotl(w, u); });
  check_close(rational_moment_n1(corner.region(), kV, 1, kA, w).value, rc, 1e-13);
  // 1e-4 wide at distance 10: σ ~ 1e-10, edge terms cancel to 1e-6 of their size.
  const Scene tiny{{0, 0, 0}, {0.3, 0.2, 10}, {1e-4, 0, 0}, {0, 1e-4, 0}};
  const long double rt = tiny.integrate([&](const LVec3& u) { return 1 / dotl(w, u); }, 1);
  const auto mt = rational_base_moment(tiny.region(), w);
  check_close(mt.value, rt, 1e-12);
  CHECK(mt.relative_error < 1e-12);
  // 1e3 wide at distance 1.
  const Scene huge{{0, 0, 0}, {-400, -600, 1}, {1e3, 0, 0}, {0, 1e3, 0}};
  // Graded towards the foot of the perpendicular (s, t) = (0.4, 0.6), on the scale h/1e3.
  const long double rh =
      huge.integrate_graded([&](const LVec3& u) { return dotl(kA, u) * dotl(w, u); }, 0.4, 0.6, 1e-3, 1e-3);
  check_close(rational_moment(huge.region(), {{kA, 1}, {w, 2}}, w, 1).value, rh, 1e-11);
}

TEST_CASE("regions touching or crossing the denominator's plane are refused: the integral diverges") {
  const Scene crossing{{0, 0, 0}, {1, -1, -0.5}, {0, 2, 0}, {0, 0, 1}};
  CHECK_THROWS_AS(rational_base_moment(crossing.region(), Vec3{0, 0, 1}), Error);
  CHECK_THROWS_AS(rational_moment(crossing.region(), {{kA, 1}}, Vec3{0, 0, 1}, 2), Error);
  CHECK_THROWS_AS(rational_moment_n(crossing.region(), kV, 3, Vec3{0, 0, 1}), Error);
  CHECK_THROWS_AS(rational_moment(kGeneral.region(), {{kA, 13}}, kW, 1), Error);  // above the frame's degree
}
