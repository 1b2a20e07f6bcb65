// Irradiance from luminaires with polynomially varying exitance (Chen and Arvo 2000, §5) against
// high-order quadrature of the surface integral over the luminaire, in long double, on meshes
// graded towards the foot of the perpendicular (where the integrand peaks like h/(h² + ρ²)²).

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "geometry/error.hpp"
#include "illumination/glossy.hpp"
#include "illumination/glossy_linear.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "illumination/moments.hpp"
#include "illumination/polynomial_luminaire.hpp"
#include "tests/reference_quadrature.hpp"

using namespace daylit;

namespace {

constexpr long double kPi = 3.141592653589793238462643383279502884L;

long double power(long double x, int k) {
  long double r = 1;
  while (k-- > 0) r *= x;
  return r;
}

long double exitance_at(const ExitancePolynomial& M, long double x, long double y, long double z) {
  long double sum = 0;
  for (const ExitanceTerm& t : M) sum += t.coef * power(x, t.i) * power(y, t.j) * power(z, t.k);
  return sum;
}

// A luminaire rectangle: corner c0 and orthogonal edges e1, e2 (the reference needs them orthogonal).
struct Rectangle {
  Vec3 c0, e1, e2;
  std::vector<Vec3> polygon() const { return {c0, c0 + e1, c0 + e1 + e2, c0 + e2}; }
  Vec3 normal() const { return cross(e1, e2); }
};

// E = (1/π) ∫_rect M(x) (n·d)(w·d)/r⁴ dA, d = x − o, by tensor Gauss–Legendre (`order` points per
// panel) on panels graded towards the foot of the perpendicular from o: the integrand's only
// feature at the scale h (the distance to the plane). Positions are offsets (σ, τ) from the foot,
// and d = h w + σ u1 + τ u2: absolute coordinates would lose digits in d near the foot (1e-10
// relative at h = 1e-9). The part of the rectangle behind the receiver counts negative, as in the
// kernel (the tests that clip compare against sub-rectangles).
long double reference_irradiance(const Vec3& o, const Vec3& n, const Rectangle& rect, const ExitancePolynomial& M,
                                 int order = 12) {
  std::vector<long double> gx, gw;
  test::gauss_legendre(order, gx, gw);
  const long double L1 = norm(rect.e1), L2 = norm(rect.e2);
  const Vec3 u1 = rect.e1 / double(L1), u2 = rect.e2 / double(L2), w = normalized(rect.normal());
  const long double hs = dot(w, rect.c0 - o), h = std::abs(hs);  // o + hs w is the foot
  const long double f1 = dot(o - rect.c0, u1), f2 = dot(o - rect.c0, u2);  // the foot, in rectangle coordinates
  const auto b1 = test::graded_breakpoints(-f1, L1 - f1, 0, h), b2 = test::graded_breakpoints(-f2, L2 - f2, 0, h);
  long double sum = 0;
  for (std::size_t i = 0; i + 1 < b1.size(); ++i)
    for (std::size_t j = 0; j + 1 < b2.size(); ++j) {
      const long double s0 = b1[i], s1 = b1[i + 1], t0 = b2[j], t1 = b2[j + 1];
      for (int a = 0; a < order; ++a)
        for (int b = 0; b < order; ++b) {
          const long double s = (s0 + s1) / 2 + (s1 - s0) / 2 * gx[a], t = (t0 + t1) / 2 + (t1 - t0) / 2 * gx[b];
          const long double dx = hs * w.x + s * u1.x + t * u2.x, dy = hs * w.y + s * u1.y + t * u2.y,
                            dz = hs * w.z + s * u1.z + t * u2.z;
          const long double r2 = dx * dx + dy * dy + dz * dz;
          const long double cr = n.x * dx + n.y * dy + n.z * dz, cl = std::abs(w.x * dx + w.y * dy + w.z * dz);
          const long double m = exitance_at(M, o.x + dx, o.y + dy, o.z + dz);
          sum += gw[a] * gw[b] * (s1 - s0) * (t1 - t0) / 4 * m * cr * cl / (r2 * r2);
        }
    }
  return sum / kPi;
}

// A generic polynomial of total degree D in world coordinates (every monomial, varied
// coefficients of both signs, and a constant term).
ExitancePolynomial generic(int D) {
  ExitancePolynomial M{{1.0, 0, 0, 0}};
  for (int i = 0; i <= D; ++i)
    for (int j = 0; i + j <= D; ++j) M.push_back({(i + 2 * j) % 3 == 0 ? -0.3 / (1 + i) : 0.7 / (1 + j), i, j, D - i - j});
  return M;
}

LuminaireIrradiance kernel(const Vec3& o, const Vec3& n, const Rectangle& rect, const ExitancePolynomial& M) {
  return polynomial_luminaire_irradiance(directions_through(rect.polygon(), o), o, n, rect.c0, rect.normal(), M);
}

}  // namespace

TEST_CASE("a uniform exitance gives Lambert's formula over π, whichever side the plane normal faces") {
  const Rectangle rect{{-0.5, -0.7, 1.3}, {1.2, 0, 0.1}, {0, 1.1, 0.2}};
  const Vec3 o{0.3, -0.2, 0}, n = normalized(Vec3{0.1, 0.2, 1});
  const SphericalRegion region = directions_through(rect.polygon(), o);
  const double lambert_over_pi = lambert(region, n) / std::numbers::pi;
  const auto E = polynomial_luminaire_irradiance(region, o, n, rect.c0, rect.normal(), {{2.5, 0, 0, 0}});
  CHECK(E.value == Approx(2.5 * lambert_over_pi).epsilon(4e-15));  // both are sums of a few terms in double
  CHECK(E.relative_error < 1e-13);
  const auto F = polynomial_luminaire_irradiance(region, o, n, rect.c0, -1.0 * rect.normal(), {{2.5, 0, 0, 0}});
  CHECK(F.value == Approx(E.value).epsilon(4e-15));
}

TEST_CASE("linear, quadratic and higher-degree exitance match quadrature of the surface integral") {
  // Tolerance 2e-13 relative: the kernel's own estimate is kept below 1e-13 and the reference
  // (12-point tensor Gauss–Legendre per graded panel, long double) is good to ~1e-16 for these
  // polynomials of degree ≤ 6 times a smooth rational weight.
  struct Case {
    const char* name;
    Vec3 o, n;
    Rectangle rect;
  };
  const std::vector<Case> cases = {
      {"tilted receiver below a tilted luminaire", {0.3, -0.2, 0}, normalized(Vec3{0.1, 0.2, 1}),
       {{-0.5, -0.7, 1.3}, {1.2, 0, 0.1}, {0.02, 1.1, -0.24}}},
      {"vertical luminaire beside the receiver", {0, 0, 0}, normalized(Vec3{1, 0, 1}),
       {{2, -1, 0.1}, {0, 2, 0}, {0, 0, 1.5}}},
      {"luminaire far off the axis", {0, 0, 0}, {0, 0, 1}, {{5, 0.2, 1}, {1, 0, 0}, {0, 1, 0}}},
      {"foot of the perpendicular on a vertex (edges through w)", {0, 0, 0}, normalized(Vec3{0.3, 0, 1}),
       {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}},
  };
  for (const auto& c : cases)
    for (int D = 1; D <= 6; ++D) {
      const ExitancePolynomial M = generic(D);
      const auto E = kernel(c.o, c.n, c.rect, M);
      const long double ref = reference_irradiance(c.o, c.n, c.rect, M);
      INFO(c.name << ", degree " << D << ": " << E.value << " vs " << double(ref) << ", estimate " << E.relative_error);
      CHECK(E.relative_error < 1e-13);
      CHECK(std::abs(E.value - ref) <= 2e-13 * std::abs(ref));
    }
}

TEST_CASE("receivers close to the luminaire's plane: h = 1e-3, 1e-6, 1e-9 under and beside it") {
  // The integrand concentrates in a disc of radius ~h around the foot, and w·u → 0 over the rest
  // of the luminaire: every rational moment is stiff. The graded reference resolves both.
  const Rectangle rect{{-0.5, -0.7, 1}, {1.2, 0, 0}, {0, 1.1, 0}};
  for (const double h : {1e-3, 1e-6, 1e-9})
    for (const Vec3& foot : {Vec3{0.3, -0.2, 1}, Vec3{1.5, 0.1, 1}}) {
      const Vec3 o = foot - Vec3{0, 0, h}, n = normalized(Vec3{0.2, 0.1, 1});
      for (int D : {0, 1, 2, 3}) {
        const ExitancePolynomial M = generic(D);
        const auto E = kernel(o, n, rect, M);
        const long double ref = reference_irradiance(o, n, rect, M);
        INFO("h " << h << " foot x " << foot.x << " degree " << D << ": " << E.value << " vs " << double(ref)
                  << ", estimate " << E.relative_error);
        CHECK(std::abs(E.value - ref) <= 1e-12 * std::abs(ref));
      }
    }
}

TEST_CASE("exitance that vanishes on an edge of the luminaire, and a receiver in the plane") {
  const Rectangle rect{{1, -0.5, 2}, {1.5, 0, 0}, {0, 1, 0}};
  const Vec3 o{0, 0, 0}, n{0, 0, 1};
  // M = x − 1 vanishes along the edge x = 1 and grows linearly across; (x − 1)² quadratically.
  for (const ExitancePolynomial& M : {ExitancePolynomial{{1, 1, 0, 0}, {-1, 0, 0, 0}},
                                      ExitancePolynomial{{1, 2, 0, 0}, {-2, 1, 0, 0}, {1, 0, 0, 0}}}) {
    const auto E = kernel(o, n, rect, M);
    const long double ref = reference_irradiance(o, n, rect, M);
    CHECK(std::abs(E.value - ref) <= 2e-13 * std::abs(ref));
  }
  // The origin in the luminaire's plane sees it edge-on: nothing arrives.
  const Vec3 in_plane{0, 0, 2};
  CHECK(polynomial_luminaire_irradiance({{{Vec3{1, 0, 0}, Vec3{2, 0, 0}, Vec3{2, 1, 0}}}}, in_plane, n, rect.c0,
                                        rect.normal(), {{1, 1, 0, 0}})
            .value == 0);
}

TEST_CASE("tiny luminaires far away and huge luminaires close by") {
  const Vec3 o{0, 0, 0}, n = normalized(Vec3{0.1, -0.2, 1});
  const ExitancePolynomial M = generic(2);
  // 1e-3 wide at distance 100 (σ ~ 1e-10): the edge terms cancel to 1e-8 of their size, which
  // sends the sums to __float128.
  const Rectangle tiny{{0.1, 0.2, 100}, {1e-3, 0, 0}, {0, 1e-3, 0}};
  const auto Et = kernel(o, n, tiny, M);
  const long double rt = reference_irradiance(o, n, tiny, M);
  CHECK(std::abs(Et.value - rt) <= 1e-12 * std::abs(rt));
  // 1e4 wide at distance 1.
  const Rectangle huge{{-4000, -6000, 1}, {1e4, 0, 0}, {0, 1e4, 0}};
  const ExitancePolynomial M1{{1, 0, 0, 0}, {1e-4, 1, 0, 0}, {-2e-4, 0, 1, 0}};
  const auto Eh = kernel(o, n, huge, M1);
  const long double rh = reference_irradiance(o, n, huge, M1);
  CHECK(std::abs(Eh.value - rh) <= 1e-12 * std::abs(rh));
}

TEST_CASE("the part of a luminaire in front of the receiver, and a luminaire with a hole, add up") {
  // The receiver's plane x = 0.2 (normal +x, receiver at the origin tilted) cuts the luminaire
  // along x = 0.2: clipping to the hemisphere must give the integral over [0.2, 1] × [..].
  const Vec3 o{0.2, 0, 0}, n{1, 0, 0};
  const Rectangle rect{{-0.6, -0.5, 1}, {1.6, 0, 0}, {0, 1.2, 0}};
  const ExitancePolynomial M = generic(2);
  const SphericalRegion clipped = clip_to_hemisphere(directions_through(rect.polygon(), o), n);
  const auto E = polynomial_luminaire_irradiance(clipped, o, n, rect.c0, rect.normal(), M);
  const Rectangle front{{0.2, -0.5, 1}, {0.8, 0, 0}, {0, 1.2, 0}};
  const long double ref = reference_irradiance(o, n, front, M);
  CHECK(std::abs(E.value - ref) <= 2e-13 * std::abs(ref));
  // A hole: the outer loop and the hole's loop reversed; the reference subtracts.
  const Vec3 o2{0.1, 0.1, 0}, n2 = normalized(Vec3{0, 0.3, 1});
  const Rectangle outer{{-1, -1, 1.5}, {2, 0, 0}, {0, 2, 0}}, hole{{-0.2, -0.3, 1.5}, {0.5, 0, 0}, {0, 0.4, 0}};
  SphericalRegion region = directions_through(outer.polygon(), o2);
  DirectionLoop inner = directions_through(hole.polygon(), o2).loops.at(0);
  std::reverse(inner.begin(), inner.end());
  region.loops.push_back(inner);
  const auto Eh = polynomial_luminaire_irradiance(region, o2, n2, outer.c0, outer.normal(), M);
  const long double rh = reference_irradiance(o2, n2, outer, M) - reference_irradiance(o2, n2, hole, M);
  CHECK(std::abs(Eh.value - rh) <= 2e-13 * std::abs(rh));
}

TEST_CASE("the irradiance does not depend on the world frame: a rotated and moved scene gives the same") {
  const Rectangle rect{{-0.5, -0.7, 1.3}, {1.2, 0, 0.1}, {0, 1.1, 0.2}};
  const Vec3 o{0.3, -0.2, 0}, n = normalized(Vec3{0.1, 0.2, 1});
  const ExitancePolynomial M{{1, 0, 0, 0}, {0.5, 1, 0, 0}, {0.25, 0, 2, 0}};
  // Rotation by 90° about z and a shift by t: x' = (−y, x, z) + t. The exitance in the new frame
  // is M(R⁻¹(x' − t)): with t = (3, −2, 1), x = y' + 2, y = −(x' − 3) = 3 − x', z = z' − 1.
  const Vec3 t{3, -2, 1};
  auto move = [&](const Vec3& v) { return Vec3{-v.y, v.x, v.z} + t; };
  auto turn = [&](const Vec3& v) { return Vec3{-v.y, v.x, v.z}; };
  const Rectangle moved{move(rect.c0), turn(rect.e1), turn(rect.e2)};
  // M' = 1 + 0.5 (y' + 2) + 0.25 (3 − x')² = 1 + 0.5 y' + 1 + 0.25 (9 − 6 x' + x'²).
  const ExitancePolynomial M2{{2 + 2.25, 0, 0, 0}, {0.5, 0, 1, 0}, {-1.5, 1, 0, 0}, {0.25, 2, 0, 0}};
  const auto E1 = kernel(o, n, rect, M), E2 = kernel(move(o), turn(n), moved, M2);
  CHECK(E2.value == Approx(E1.value).epsilon(1e-13));
}

TEST_CASE("bad luminaire input is refused with daylit::Error") {
  const Rectangle rect{{-0.5, -0.5, 1}, {1, 0, 0}, {0, 1, 0}};
  const Vec3 o{0, 0, 0}, n{0, 0, 1};
  const SphericalRegion region = directions_through(rect.polygon(), o);
  CHECK_THROWS_AS(polynomial_luminaire_irradiance(region, o, n, rect.c0, rect.normal(), {{1, 17, 0, 0}}), Error);
  CHECK_THROWS_AS(polynomial_luminaire_irradiance(region, o, n, rect.c0, rect.normal(), {{1, -1, 0, 0}}), Error);
  CHECK_THROWS_AS(polynomial_luminaire_irradiance(region, o, n, rect.c0, Vec3{0, 0, 0}, {{1, 0, 0, 0}}), Error);
  CHECK_THROWS_AS(polynomial_luminaire_irradiance(region, o, n, rect.c0, rect.normal(), {{NAN, 0, 0, 0}}), Error);
  // A region that is not the luminaire's (directions pointing away from its plane).
  const SphericalRegion behind = directions_through(rect.polygon(), Vec3{0, 0, 2});
  CHECK_THROWS_AS(polynomial_luminaire_irradiance(behind, o, n, rect.c0, rect.normal(), {{1, 0, 0, 0}}), Error);
}

TEST_CASE("glossy reflection of a linearly varying luminaire: the uniform limit is Arvo's, the linear case quadrature's") {
  const Rectangle rect{{-0.5, -0.4, 1}, {1, 0, 0}, {0, 0.9, 0}};
  const Vec3 o{0, 0, 0}, b{0, 0, 1}, e = normalized(Vec3{0.3, 0.1, 1});
  const SphericalRegion region = directions_through(rect.polygon(), o);
  for (const int n : {0, 1, 10, 50}) {
    const double c = max_glossy_coefficient(n) / 2;
    // Uniform exitance 2: radiance 2/π, Arvo's eq. 24 through double-axis moments (glossy.cpp).
    const double uniform = glossy_reflected_radiance_linear(region, o, b, e, n, c, rect.c0, rect.normal(), {2.0, {}});
    CHECK(uniform == Approx(glossy_reflected_radiance(region, b, e, n, c, 2 / std::numbers::pi)).epsilon(1e-13));
    // M = 2 + 0.5 x − 0.7 y against (c/π) ∫ (v·u)^n (b·u) M dσ over the luminaire (all of it lies
    // in both hemispheres here, so nothing is clipped); 1e-13 as for the moments themselves.
    const LinearExitance M{2.0, {0.5, -0.7, 0}};
    const Vec3 v = 2 * dot(b, e) * b - e;
    const long double ref = test::integrate_parallelogram(
        test::lvec(rect.c0), test::lvec(rect.e1), test::lvec(rect.e2), [&](const test::LVec3& x) {
          const long double r = std::sqrt(x.x * x.x + x.y * x.y + x.z * x.z);
          const long double vu = (v.x * x.x + v.y * x.y + v.z * x.z) / r, bu = x.z / r;
          return c / kPi * std::pow(vu, (long double)n) * bu * (2 + 0.5L * x.x - 0.7L * x.y) * (x.z / r) / (r * r);
        });
    const double got = glossy_reflected_radiance_linear(region, o, b, e, n, c, rect.c0, rect.normal(), M);
    INFO("n " << n << ": " << got << " vs " << double(ref));
    CHECK(std::abs(got - ref) <= 1e-13 * std::abs(ref));
  }
  CHECK_THROWS_AS(glossy_reflected_radiance_linear(region, o, b, e, 10, 1.0 + max_glossy_coefficient(10), rect.c0,
                                                   rect.normal(), {1, {}}),
                  Error);
}

TEST_CASE("glossy transmission of a linearly varying luminaire behind a frosted pane matches quadrature") {
  // The pane at the origin faces the viewer (+z); the luminaire lies behind it at z = −1.2.
  const Rectangle rect{{-0.6, -0.5, -1.2}, {1.1, 0, 0}, {0, 0.8, 0}};
  const Vec3 o{0, 0, 0}, b{0, 0, 1}, e = normalized(Vec3{0.1, 0.2, 1});
  const SphericalRegion region = directions_through(rect.polygon(), o);
  const LinearExitance M{1.0, {-0.3, 0.4, 0.2}};
  for (const int n : {2, 20}) {
    const double c = max_glossy_coefficient(n);
    const long double ref = test::integrate_parallelogram(
        test::lvec(rect.c0), test::lvec(rect.e1), test::lvec(rect.e2), [&](const test::LVec3& x) {
          const long double r = std::sqrt(x.x * x.x + x.y * x.y + x.z * x.z);
          const long double lobe = -(e.x * x.x + e.y * x.y + e.z * x.z) / r, cosine = -x.z / r;
          const long double m = 1 - 0.3L * x.x + 0.4L * x.y + 0.2L * x.z;
          return c / kPi * std::pow(lobe, (long double)n) * cosine * m * std::abs(x.z) / (r * r * r);
        });
    const double got = glossy_transmitted_radiance_linear(region, o, b, e, n, c, rect.c0, rect.normal(), M);
    INFO("n " << n << ": " << got << " vs " << double(ref));
    CHECK(std::abs(got - ref) <= 1e-13 * std::abs(ref));
  }
}
