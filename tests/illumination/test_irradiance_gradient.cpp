// The irradiance gradient (illumination/irradiance_gradient.hpp) against independent references:
// central finite differences of the exact irradiance (with a step-size study and Richardson
// extrapolation), and long-double Gauss–Legendre quadrature over the luminaire's area of the
// gradient of the integrand, which shares no formula with the boundary integrals under test.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include "geometry/visibility.hpp"
#include "materials/glass_transmittance.hpp"
#include "illumination/irradiance_gradient.hpp"
#include "illumination/moments.hpp"
#include "illumination/real_vector.hpp"
#include "reference_quadrature.hpp"
#include "simulation/grid_refinement.hpp"
#include "simulation/sky_component.hpp"
#include "test_scenes.hpp"

using namespace daylit;
using daylit::test::LVec3;

namespace {

constexpr double kPi = std::numbers::pi;

VisibilityOptions luminaire_options() {
  VisibilityOptions o;
  o.clip_to_horizon = false;
  o.edge_sources = true;
  return o;
}

// A luminaire (the scene's one aperture) of uniform exitance 1 behind the scene's occluders.
struct Luminaire {
  Scene scene;
  GeometryMode mode = GeometryMode::exact;

  double irradiance(const Vec3& p, const Vec3& n) const {
    const VisibilityEngine engine(scene, mode);
    VisibilityCounters counters;
    return lambert(engine.visible_region(p, n, 0, counters, luminaire_options()), n) / kPi;
  }
  IrradianceGradient gradient(const Vec3& p, const Vec3& n) const {
    const VisibilityEngine engine(scene, mode);
    VisibilityCounters counters;
    DirectionalRadiance L;
    L.alpha = 1 / kPi;
    return directional_irradiance_gradient(engine.visible_region(p, n, 0, counters, luminaire_options()), p, n, L);
  }
};

Luminaire luminaire(std::vector<Vec3> polygon, std::vector<std::vector<Vec3>> occluders = {}) {
  Luminaire l;
  l.scene.apertures.push_back({test::polygon(std::move(polygon), "luminaire"), 1.0});
  for (auto& o : occluders) l.scene.occluders.push_back(test::polygon(std::move(o), "occluder"));
  return l;
}

Vec3 unit(int axis) { return {axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0}; }

// Central difference of f along axis with step h, and Richardson's extrapolation of the steps h
// and h/2: (4 D(h/2) − D(h))/3 has truncation error O(h⁴) where D's is O(h²).
template <class F>
double central_difference(const F& f, const Vec3& p, int axis, double h) {
  return (f(p + h * unit(axis)) - f(p - h * unit(axis))) / (2 * h);
}
template <class F>
Vec3 richardson_gradient(const F& f, const Vec3& p, double h) {
  Vec3 g;
  double* c[3] = {&g.x, &g.y, &g.z};
  for (int a = 0; a < 3; ++a) *c[a] = (4 * central_difference(f, p, a, h / 2) - central_difference(f, p, a, h)) / 3;
  return g;
}

double relative_difference(const Vec3& a, const Vec3& b) { return norm(a - b) / norm(b); }

// ∇_p of ∫ M(x) cosθ_r cosθ_l /(π r²) dA over an unoccluded parallelogram wholly in front of the
// receiver, by differentiating the integrand (M does not depend on p in the area parametrisation):
// with d = x − p, q = ν·(p − x) > 0 (ν the unit normal facing p), K = (n·d) q /(π r⁴) and
// ∇_p K = [(n·d) ν − q n]/(π r⁴) + 4 (n·d) q d /(π r⁶). M is 1 unless given.
Vec3 quadrature_gradient(const Vec3& p, const Vec3& n, const Vec3& origin, const Vec3& e1, const Vec3& e2, int panels = 8,
                         const std::function<long double(const LVec3&)>& M = {}) {
  Vec3 nu = normalized(cross(e1, e2));
  if (dot(nu, p - origin) < 0) nu = -1.0 * nu;
  Vec3 g;
  double* c[3] = {&g.x, &g.y, &g.z};
  for (int a = 0; a < 3; ++a) {
    *c[a] = double(test::integrate_parallelogram(
        test::lvec(origin), test::lvec(e1), test::lvec(e2),
        [&](const LVec3& x) {
          const long double d[3] = {x.x - p.x, x.y - p.y, x.z - p.z};
          const long double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
          const long double nd = n.x * d[0] + n.y * d[1] + n.z * d[2];
          const long double q = -(nu.x * d[0] + nu.y * d[1] + nu.z * d[2]);
          return (M ? M(x) : 1.0L) * ((nd * nu[a] - q * n[a]) / (r2 * r2) + 4 * nd * q * d[a] / (r2 * r2 * r2)) /
                 std::numbers::pi_v<long double>;
        },
        panels, 24));
  }
  return g;
}

}  // namespace

TEST_CASE("the gradient of a uniform luminaire matches quadrature of the differentiated integrand") {
  // A 1 × 0.6 rectangle at z = 2 and a tilted one, seen by receivers facing up and sideways.
  const Vec3 o{-0.3, 0.2, 2}, e1{1, 0, 0}, e2{0, 0.6, 0};
  const Luminaire flat = luminaire({o, o + e1, o + e1 + e2, o + e2});
  const Vec3 t{0.5, -1, 1.5}, f1{0.8, 0.3, 0}, f2{0, 0.4, 0.7};
  const Luminaire tilted = luminaire({t, t + f1, t + f1 + f2, t + f2});
  for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{2, -1, 0.5}, Vec3{0.1, 0.4, 1.7}}) {
    const Vec3 n = normalized(Vec3{0.1, -0.2, 1});
    const IrradianceGradient g = flat.gradient(p, n);
    const Vec3 reference = quadrature_gradient(p, n, o, e1, e2);
    INFO("p = " << p.x << " " << p.y << " " << p.z << ": " << g.value.x << " " << g.value.y << " " << g.value.z
                << " reference " << reference.x << " " << reference.y << " " << reference.z);
    // Quadrature of a smooth integrand (8×8 panels of 24² points, long double): ~1e-15; the
    // kernel's own estimate is 1e-13.
    CHECK(relative_difference(g.value, reference) < 1e-12);
    CHECK(g.relative_error < 1e-13);
  }
  for (const Vec3 p : {Vec3{0.9, 0.2, 0.1}, Vec3{-1, -2, 0.4}}) {
    const Vec3 n = normalized(Vec3{0.3, 0.1, 1});
    const Vec3 reference = quadrature_gradient(p, n, t, f1, f2);
    CHECK(relative_difference(tilted.gradient(p, n).value, reference) < 1e-12);
  }
}

TEST_CASE("the gradient behind an occluder matches central differences of the exact irradiance") {
  // DESIGN.md §7: an occluder edge's line is not in the luminaire's plane; the gradient must turn
  // the shadow's edges about the occluder's own edges. Luminaire 2 × 2 at z = 3, a plate at z = 1.5
  // hiding part of it, an oblique strip at z ≈ 2.2 crossing it.
  const Luminaire lum = luminaire({{-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}},
                                  {{{-0.2, -0.1, 1.5}, {0.6, -0.3, 1.5}, {0.7, 0.5, 1.5}, {-0.1, 0.6, 1.5}},
                                   {{-1.5, 0.8, 2.1}, {1.4, -0.2, 2.3}, {1.5, 0.1, 2.3}, {-1.4, 1.1, 2.1}}});
  // The receiver facing up, and tilted so that its tangent plane cuts the luminaire (those edges
  // stay put).
  for (const Vec3 n : {Vec3{0, 0, 1}, normalized(Vec3{1, 0, 0.3})}) {
    for (const Vec3 p : {Vec3{0.05, 0.1, 0}, Vec3{-0.4, 0.3, 0.2}, Vec3{0.6, -0.5, 0.7}}) {
      const auto E = [&](const Vec3& q) { return lum.irradiance(q, n); };
      const IrradianceGradient g = lum.gradient(p, n);
      // Step-size study: the central difference's error falls as h² (truncation) until rounding,
      // u·E/h, takes over; Richardson's extrapolation removes the h² term.
      std::printf("n = (%.3g, %.3g, %.3g), p = (%g, %g, %g): gradient (%.15g, %.15g, %.15g)\n", n.x, n.y, n.z, p.x, p.y, p.z,
                  g.value.x, g.value.y, g.value.z);
      for (const double h : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
        Vec3 fd;
        double* c[3] = {&fd.x, &fd.y, &fd.z};
        for (int a = 0; a < 3; ++a) *c[a] = central_difference(E, p, a, h);
        std::printf("  h = %.0e: |central − gradient|/|gradient| = %.3g, Richardson %.3g\n", h,
                    relative_difference(fd, g.value), relative_difference(richardson_gradient(E, p, h), g.value));
      }
      // At h = 1e-3: truncation ~ (h/2)⁴ E^(5) ≈ 1e-13, rounding ~ u E/h ≈ 1e-13, relative to a
      // gradient of size ~E.
      CHECK(relative_difference(richardson_gradient(E, p, 1e-3), g.value) < 1e-9);
    }
  }
}

TEST_CASE("the sky component's gradient matches central differences through a window with an overhang") {
  Scene scene;
  scene.apertures.push_back({test::polygon({{0, 0, 1}, {2, 0, 1}, {2, 0, 2}, {0, 0, 2}}, "window"), 1.0});
  scene.occluders.push_back(test::polygon({{-0.5, 0, 2.1}, {2.5, 0, 2.1}, {2.5, -0.8, 2.1}, {-0.5, -0.8, 2.1}}, "overhang"));
  scene.occluders.push_back(test::polygon({{-3, -6, 0}, {5, -6, 0}, {5, -6, 4}, {-3, -6, 4}}, "building opposite"));
  // A glazed rooflight: clear glass (Radiance's model fitted by a degree-12 polynomial in the
  // cosine of incidence), whose sky component is a sum of moments up to order 14.
  Aperture rooflight{test::polygon({{0.2, 0.5, 3}, {1.4, 0.5, 3}, {1.4, 1.7, 3}, {0.2, 1.7, 3}}, "rooflight"), 0.88};
  rooflight.angular_transmittance = fit_glass_transmittance({{0.96, 0.96, 0.96}}).coefficients;
  scene.apertures.push_back(rooflight);
  for (const SkyModel sky : {SkyModel::cie_overcast, SkyModel::uniform})
    for (const GeometryMode mode : {GeometryMode::exact, GeometryMode::floating, GeometryMode::rational}) {
      const VisibilityEngine engine(scene, mode);
      for (const Vec3 p : {Vec3{0.7, 1.3, 0.85}, Vec3{1.6, 0.4, 1.2}, Vec3{-0.5, 2.5, 0.3}}) {
        const Sensor sensor{p, {0, 0, 1}};
        VisibilityCounters counters;
        const SkyComponentPoint point = sky_component_with_gradient(engine, scene, sensor, sky, counters);
        CHECK(point.percent == sky_component_percent(engine, scene, sensor, sky, counters));
        const auto sc = [&](const Vec3& q) { return sky_component_percent(engine, scene, {q, {0, 0, 1}}, sky, counters); };
        const Vec3 fd = richardson_gradient(sc, p, 1e-3);
        INFO("p = " << p.x << " " << p.y << " " << p.z << " gradient " << point.gradient.x << " " << point.gradient.y << " "
                    << point.gradient.z << " differences " << fd.x << " " << fd.y << " " << fd.z);
        // The differences are good to ~1e-12 (see the luminaire's step study); the gradient is
        // computed to 1e-7 (sky_component.hpp: the glazing polynomial's coefficients cost five
        // digits in double, and 1e-7 keeps it there).
        std::printf("sky %d, geometry %d, p = (%g, %g, %g): |gradient − Richardson(h = 1e-3)|/|gradient| = %.2g\n", int(sky),
                    int(mode), p.x, p.y, p.z, relative_difference(point.gradient, fd));
        CHECK(relative_difference(point.gradient, fd) < 1e-7);
      }
    }
}

namespace {

// A luminaire of polynomial exitance: E and ∇E from polynomial_luminaire_gradient.
struct PolynomialLuminaire {
  Luminaire geometry;
  ExitancePolynomial M;

  LuminaireGradient at(const Vec3& p, const Vec3& n) const {
    const VisibilityEngine engine(geometry.scene, geometry.mode);
    VisibilityCounters counters;
    const auto& v = geometry.scene.apertures[0].polygon.vertices;
    return polynomial_luminaire_gradient(engine.visible_region(p, n, 0, counters, luminaire_options()), p, n, v[0],
                                         newell_normal(v), M);
  }
};

double evaluate(const ExitancePolynomial& M, const LVec3& x) {
  long double sum = 0;
  for (const ExitanceTerm& t : M) sum += t.coef * std::pow(x.x, t.i) * std::pow(x.y, t.j) * std::pow(x.z, t.k);
  return double(sum);
}

// The same with the exitance polynomial M.
Vec3 quadrature_gradient(const ExitancePolynomial& M, const Vec3& p, const Vec3& n, const Vec3& origin, const Vec3& e1,
                         const Vec3& e2) {
  return quadrature_gradient(p, n, origin, e1, e2, 8, [&](const LVec3& x) { return evaluate(M, x); });
}

}  // namespace

TEST_CASE("the gradient of a linear or quadratic luminaire matches quadrature of the differentiated integrand") {
  const Vec3 o{-0.3, 0.2, 2}, e1{1, 0, 0}, e2{0, 0.6, 0};
  const ExitancePolynomial linear{{1, 0, 0, 0}, {0.7, 1, 0, 0}, {-0.4, 0, 1, 0}};
  const ExitancePolynomial quadratic{{2, 0, 0, 0}, {0.3, 2, 0, 0}, {-0.5, 1, 1, 0}, {0.8, 0, 2, 0}, {0.2, 0, 0, 1}};
  for (const ExitancePolynomial& M : {linear, quadratic}) {
    const PolynomialLuminaire lum{luminaire({o, o + e1, o + e1 + e2, o + e2}), M};
    for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{2, -1, 0.5}, Vec3{0.1, 0.4, 1.7}}) {
      const Vec3 n = normalized(Vec3{0.1, -0.2, 1});
      const LuminaireGradient g = lum.at(p, n);
      const Vec3 reference = quadrature_gradient(M, p, n, o, e1, e2);
      INFO("p = " << p.x << " " << p.y << " " << p.z << ": " << g.gradient.x << " " << g.gradient.y << " " << g.gradient.z
                  << " reference " << reference.x << " " << reference.y << " " << reference.z);
      // Quadrature ~1e-15 (smooth integrand); the kernel's stated bound is 1e-13.
      CHECK(relative_difference(g.gradient, reference) < 1e-12);
      CHECK(g.relative_error < 1e-10);
    }
  }
}

TEST_CASE("the gradient of a linear luminaire behind occluders matches central differences of its exact irradiance") {
  PolynomialLuminaire lum{luminaire({{-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}},
                                    {{{-0.2, -0.1, 1.5}, {0.6, -0.3, 1.5}, {0.7, 0.5, 1.5}, {-0.1, 0.6, 1.5}},
                                     {{-1.5, 0.8, 2.1}, {1.4, -0.2, 2.3}, {1.5, 0.1, 2.3}, {-1.4, 1.1, 2.1}}}),
                          {{1, 0, 0, 0}, {0.5, 1, 0, 0}, {0.3, 0, 1, 0}, {-0.2, 1, 1, 0}}};
  const Vec3 n = normalized(Vec3{0.2, 0, 1});
  const auto E = [&](const Vec3& p) { return lum.at(p, n).value; };
  for (const Vec3 p : {Vec3{0.05, 0.1, 0}, Vec3{-0.4, 0.3, 0.2}, Vec3{0.6, -0.5, 0.7}}) {
    const LuminaireGradient g = lum.at(p, n);
    const Vec3 fd = richardson_gradient(E, p, 1e-3);
    INFO("p = " << p.x << " " << p.y << " " << p.z << ": " << g.gradient.x << " " << g.gradient.y << " " << g.gradient.z
                << " differences " << fd.x << " " << fd.y << " " << fd.z);
    CHECK(relative_difference(g.gradient, fd) < 1e-9);
  }
}

TEST_CASE("a polynomial exitance that is constant gives the uniform luminaire's gradient") {
  // The constant written with a zero linear term takes the quadrature path of the boundary term
  // and the interior term; the uniform path is the closed form. And M = 1 + εx tends to it.
  const Luminaire geometry = luminaire({{-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}},
                                       {{{-0.2, -0.1, 1.5}, {0.6, -0.3, 1.5}, {0.7, 0.5, 1.5}, {-0.1, 0.6, 1.5}}});
  const Vec3 p{0.3, -0.2, 0.4}, n = normalized(Vec3{0.1, 0.3, 1});
  const Vec3 uniform = geometry.gradient(p, n).value;
  const LuminaireGradient constant = PolynomialLuminaire{geometry, {{1, 0, 0, 0}, {0, 1, 0, 0}}}.at(p, n);
  CHECK(relative_difference(constant.gradient, uniform) < 1e-13);
  CHECK(constant.value == Approx(geometry.irradiance(p, n)).epsilon(1e-14));
  for (const double eps : {1e-2, 1e-4, 1e-6}) {
    const LuminaireGradient g = PolynomialLuminaire{geometry, {{1, 0, 0, 0}, {eps, 1, 0, 0}}}.at(p, n);
    // The change is linear in ε, of the size of ε times the gradient's scale.
    CHECK(relative_difference(g.gradient, uniform) < 3 * eps);
    CHECK(relative_difference(g.gradient, uniform) > 0.01 * eps);
  }
}

TEST_CASE("stiff: receivers close to the luminaire's plane keep their gradient") {
  // Luminaire z = 3, x, y ∈ [−1, 1]. Receivers at distance D below its plane: beside it (facing it
  // obliquely, where n·u and ν·u are both small over much of the region) and under it. E changes on
  // the scale D there, so the differences take steps h = D/100: Richardson's truncation error is
  // then ~(h/D)⁴ ≈ 1e-8 and rounding u·D/h ≈ 1e-14, relative to |∇E| ~ E/D.
  // Under the luminaire, facing it, E ≈ 1 while |∇E| = O(D): differences of E in double would
  // lose everything to rounding (u·E/h), so the reference there is Howell's closed form for the
  // four rectangles about the foot point (DESIGN.md §7), differenced in __float128.
  const Luminaire lum = luminaire({{-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}});
  const PolynomialLuminaire linear{lum, {{1, 0, 0, 0}, {0.4, 1, 0, 0}, {0.3, 0, 1, 0}}};
  using Q = real::quad;
  const auto howell = [](Q a, Q b, Q c) {
    const Q A = a / c, B = b / c, sa = sqrtq(1 + A * A), sb = sqrtq(1 + B * B);
    return (A / sa * atanq(B / sa) + B / sb * atanq(A / sb)) / (2 * acosq(Q(-1)));
  };
  const auto howell_E = [&](Q x, Q y, Q z) {
    return howell(1 - x, 1 - y, 3 - z) + howell(1 + x, 1 - y, 3 - z) + howell(1 - x, 1 + y, 3 - z) + howell(1 + x, 1 + y, 3 - z);
  };
  for (const double D : {1e-2, 1e-4, 1e-6}) {
    for (const auto& [p, n] : {std::pair{Vec3{1.3, 0.2, 3 - D}, normalized(Vec3{-1, 0, 0.1})},
                               std::pair{Vec3{0.3, 0.2, 3 - D}, Vec3{0, 0, 1}}}) {
      INFO("D = " << D << ", p = " << p.x << " " << p.y << " " << p.z);
      const auto E = [&](const Vec3& q) { return lum.irradiance(q, n); };
      const IrradianceGradient g = lum.gradient(p, n);
      if (n.z == 1) {
        // Central differences in __float128 with steps D/100: rounding 1e-34/h, truncation
        // (h/1)² since E varies on the scale of the distance to the edges under the luminaire.
        const Q h = Q(D) / 100;
        const Q gx = (howell_E(p.x + h, p.y, p.z) - howell_E(p.x - h, p.y, p.z)) / (2 * h);
        const Q gy = (howell_E(p.x, p.y + h, p.z) - howell_E(p.x, p.y - h, p.z)) / (2 * h);
        const Q gz = (howell_E(p.x, p.y, p.z + h) - howell_E(p.x, p.y, p.z - h)) / (2 * h);
        INFO("gradient " << g.value.x << " " << g.value.y << " " << g.value.z << ", Howell " << double(gx) << " " << double(gy)
                         << " " << double(gz));
        CHECK(relative_difference(g.value, {double(gx), double(gy), double(gz)}) < 1e-6);
      } else {
        CHECK(relative_difference(g.value, richardson_gradient(E, p, D / 100)) < 1e-6);
      }
      CHECK(g.relative_error < 1e-13);
      const auto El = [&](const Vec3& q) { return linear.at(q, n).value; };
      const LuminaireGradient gl = linear.at(p, n);
      INFO("linear: " << gl.gradient.x << " " << gl.gradient.y << " " << gl.gradient.z << ", error " << gl.relative_error);
      CHECK(relative_difference(gl.gradient, richardson_gradient(El, p, D / 100)) < 1e-6);
    }
  }
}

TEST_CASE("stiff: occluder edges that graze the luminaire's edges and corners") {
  // Seen from p = (0, 0, 0), a plate at z = 1.5 whose edge projects onto the luminaire (z = 3,
  // x, y ∈ [−1, 1]) at 1e-6 inside its edge x = 1 (a sliver of the luminaire stays visible), or
  // obliquely through a point 1e-6 from its corner (1, 1). The sliver's area changes at O(1)
  // while it is 1e-6 wide: the gradient is dominated by it. Steps h = 1e-8 keep the sliver's shape
  // (truncation (h/1e-6)² ≈ 1e-4 of the sliver's second-order change, itself 1e-6 of the whole).
  const double s = 1e-6;
  const Vec3 p{0, 0, 0}, n{0, 0, 1};
  const std::vector<Vec3> square{{-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}};
  const Luminaire parallel = luminaire(square, {{{-2, -2, 1.5}, {0.5 - s / 2, -2, 1.5}, {0.5 - s / 2, 2, 1.5}, {-2, 2, 1.5}}});
  // The oblique edge through (1 − s, 1, 3)/2 and (1, 1 − s... ) at half the distance: it cuts a
  // triangle of legs ~s·2 off the corner.
  const Luminaire corner = luminaire(square, {{{-2, -2, 1.5}, {0.5 + 0.25, -2, 1.5}, {0.5 - s / 2 - 0.25 * (1 - s) / 1.5, 2, 1.5}, {-2, 2, 1.5}}});
  for (const Luminaire* lum : {&parallel, &corner}) {
    const auto E = [&](const Vec3& q) { return lum->irradiance(q, n); };
    const IrradianceGradient g = lum->gradient(p, n);
    Vec3 fd;
    double* c[3] = {&fd.x, &fd.y, &fd.z};
    for (int a = 0; a < 3; ++a) *c[a] = central_difference(E, p, a, 1e-8);
    INFO("E = " << E(p) << ", gradient " << g.value.x << " " << g.value.y << " " << g.value.z << ", differences " << fd.x << " "
                << fd.y << " " << fd.z);
    CHECK(E(p) > 0);
    CHECK(relative_difference(g.value, fd) < 1e-6);
  }
}

TEST_CASE("treating occluder edges as if they lay in the luminaire's plane gives a wrong gradient") {
  // DESIGN.md §7: the test above would catch the mistake. Replacing each occluder edge's line by
  // the line where its shadow falls on the luminaire's plane changes the gradient by O(1).
  const Luminaire lum = luminaire({{-1, -1, 3}, {1, -1, 3}, {1, 1, 3}, {-1, 1, 3}},
                                  {{{-0.2, -0.1, 1.5}, {0.6, -0.3, 1.5}, {0.7, 0.5, 1.5}, {-0.1, 0.6, 1.5}}});
  const Vec3 p{0.05, 0.1, 0}, n{0, 0, 1};
  const VisibilityEngine engine(lum.scene, GeometryMode::exact);
  VisibilityCounters counters;
  SphericalRegion region = engine.visible_region(p, n, 0, counters, luminaire_options());
  DirectionalRadiance L;
  L.alpha = 1 / kPi;
  const Vec3 right = directional_irradiance_gradient(region, p, n, L).value;
  const auto on_plane = [&](const Vec3& u) { return p + (3 - p.z) / u.z * u; };
  for (std::size_t l = 0; l < region.loops.size(); ++l)
    for (std::size_t i = 0; i < region.loops[l].size(); ++i)
      if (region.edge_sources[l][i].kind == EdgeSource::Kind::occluder)
        region.edge_sources[l][i] = {EdgeSource::Kind::occluder, on_plane(region.loops[l][i]),
                                     on_plane(region.loops[l][(i + 1) % region.loops[l].size()])};
  const Vec3 wrong = directional_irradiance_gradient(region, p, n, L).value;
  std::printf("occluder edges in the luminaire's plane: gradient (%.6g, %.6g, %.6g) instead of (%.6g, %.6g, %.6g)\n", wrong.x,
              wrong.y, wrong.z, right.x, right.y, right.z);
  CHECK(relative_difference(wrong, right) > 0.3);
}

TEST_CASE("grid refinement finds each sensor's cell and estimates the midpoint error of a quadratic DF exactly") {
  // A 6 × 5 horizontal grid of spacing 0.1 (with a vertical sensor aside, alone in its plane) and
  // DF = a x² + b y² + c xy: the midpoint rule's error over a cell is (w²/24)(2a + 2b) everywhere,
  // and the gradients' differences give it exactly, centrally inside and one-sided at the border.
  SensorGrid grid;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 6; ++i) grid.sensors.push_back({{0.05 + 0.1 * i, 0.05 + 0.1 * j, 0.85}, {0, 0, 1}});
  grid.sensors.push_back({{3, 3, 1.5}, {1, 0, 0}});
  const double a = 2, b = -0.5, c = 0.7;
  std::vector<Vec3> gradient;
  for (const Sensor& s : grid.sensors)
    gradient.push_back({2 * a * s.position.x + c * s.position.y, 2 * b * s.position.y + c * s.position.x, 0});
  const std::vector<SensorCell> cells = infer_cells(grid);
  const std::vector<double> errors = cell_mean_errors(cells, gradient);
  for (std::size_t k = 0; k < 30; ++k) {
    INFO("sensor " << k);
    CHECK(cells[k].width == Approx(0.1).epsilon(1e-12));
    const int i = int(k % 6), j = int(k / 6);
    CHECK((cells[k].neighbour[0] >= 0) == (i < 5));
    CHECK((cells[k].neighbour[1] >= 0) == (i > 0));
    CHECK((cells[k].neighbour[2] >= 0) == (j < 4));
    CHECK((cells[k].neighbour[3] >= 0) == (j > 0));
    CHECK(errors[k] == Approx(0.01 / 24 * (2 * a + 2 * b)).epsilon(1e-10));
  }
  CHECK(cells[30].width == 0);
  CHECK(errors[30] == 0);
}

TEST_CASE("stiff: a receiver 1e-10 above a linear luminaire, facing it, sees the exitance's own gradient") {
  // As D → 0 over the luminaire's interior, E → M(foot point) and ∇E → the in-plane gradient of M,
  // with corrections O(D/distance to the edges). Once took minutes: the adaptive quadrature of the
  // boundary term now has a budget per arc.
  const PolynomialLuminaire lum{luminaire({{0, 0, 1.5}, {1, 0, 1.5}, {1, 2, 1.5}, {0, 2, 1.5}}), {{1, 1, 0, 0}, {-0.5, 0, 1, 0}}};
  for (const double D : {1e-4, 1e-7, 1e-10}) {
    const LuminaireGradient g = lum.at({0.3, 0.4, 1.5 + D}, {0, 0, -1});
    INFO("D = " << D << ": E = " << g.value << ", gradient " << g.gradient.x << " " << g.gradient.y << " " << g.gradient.z
                << ", estimated error " << g.relative_error);
    CHECK(std::abs(g.value - (0.3 - 0.5 * 0.4)) < 10 * D);
    CHECK(relative_difference(g.gradient, {1, -0.5, 0}) < 10 * D);
    CHECK(g.relative_error < 1e-10);
  }
}

TEST_CASE("stiff: tiny luminaires far away and a huge one near keep their gradient") {
  // Edge terms are O(θ/h) and the gradient O(θ²/h): a luminaire of angular size 1e-6 loses six
  // digits to cancellation in double, which the kernel detects and redoes in long double or
  // __float128 (its estimate must stay below 1e-13). References: quadrature of the differentiated
  // integrand (smooth over a tiny luminaire), and Richardson differences for the huge one.
  const Vec3 n = normalized(Vec3{0.2, 0.1, 1});
  for (const double distance : {10.0, 1e3, 1e5}) {
    // Dyadic sizes and integer positions, so that the vertices o + e are exact doubles and the
    // reference integrates the very polygon the kernel sees.
    const double s = 0x1p-10;
    const Vec3 o{0.3 * distance, -0.2 * distance, distance}, e1{s, 0, 0}, e2{0, 0.625 * s, 0.25 * s};
    const Luminaire tiny = luminaire({o, o + e1, o + e1 + e2, o + e2});
    const IrradianceGradient g = tiny.gradient({0, 0, 0}, n);
    const Vec3 reference = quadrature_gradient({0, 0, 0}, n, o, e1, e2, 1);
    INFO("distance " << distance << ": precision " << g.precision << ", estimated error " << g.relative_error);
    CHECK(relative_difference(g.value, reference) < 1e-12);
    CHECK(g.relative_error < 1e-13);
  }
  // 2000 × 2000 at height 1: E ≈ 1 for an upward receiver, the gradient small.
  const Luminaire huge = luminaire({{-900, -1100, 1}, {1100, -1100, 1}, {1100, 900, 1}, {-900, 900, 1}});
  const Vec3 p{0.2, -0.3, 0}, up{0, 0, 1};
  const auto E = [&](const Vec3& q) { return huge.irradiance(q, up); };
  const IrradianceGradient g = huge.gradient(p, up);
  INFO("huge: " << g.value.x << " " << g.value.y << " " << g.value.z);
  CHECK(relative_difference(g.value, richardson_gradient(E, p, 1e-2)) < 1e-5);
}

TEST_CASE("the sky component's gradient survives placing the model at georeferenced coordinates") {
  // The window with overhang rotated by 0.7 rad about z and moved 5.4e6 m: the gradient turns with
  // the model. Rounding the placed inputs moves the geometry by ~1e-9 m (an ulp of 5.4e6), which
  // may change the gradient by ~1e-9 relative; edge lines are formed from differences of input
  // doubles, exact at any offset.
  const double co = std::cos(0.7), si = std::sin(0.7);
  const auto turn = [&](const Vec3& v) { return Vec3{co * v.x - si * v.y, si * v.x + co * v.y, v.z}; };
  const auto place = [&](const Vec3& v) { return turn(v) + Vec3{512345.678, 5432109.876, 123.4}; };
  Scene local, placed;
  const std::vector<std::vector<Vec3>> occluders{{{-0.5, 0, 2.1}, {2.5, 0, 2.1}, {2.5, -0.8, 2.1}, {-0.5, -0.8, 2.1}},
                                                 {{-3, -6, 0}, {5, -6, 0}, {5, -6, 4}, {-3, -6, 4}}};
  const std::vector<Vec3> window{{0, 0, 1}, {2, 0, 1}, {2, 0, 2}, {0, 0, 2}};
  local.apertures.push_back({test::polygon(window), 1.0});
  std::vector<Vec3> w2;
  for (const Vec3& v : window) w2.push_back(place(v));
  placed.apertures.push_back({test::polygon(w2), 1.0});
  for (const auto& o : occluders) {
    local.occluders.push_back(test::polygon(o));
    std::vector<Vec3> o2;
    for (const Vec3& v : o) o2.push_back(place(v));
    placed.occluders.push_back(test::polygon(o2));
  }
  const VisibilityEngine engine_local(local, GeometryMode::exact), engine_placed(placed, GeometryMode::exact);
  for (const Vec3 p : {Vec3{0.7, 1.3, 0.85}, Vec3{1.6, 0.4, 1.2}}) {
    VisibilityCounters counters;
    const Vec3 g = sky_component_with_gradient(engine_local, local, {p, {0, 0, 1}}, SkyModel::cie_overcast, counters).gradient;
    const Vec3 gp = sky_component_with_gradient(engine_placed, placed, {place(p), {0, 0, 1}}, SkyModel::cie_overcast, counters).gradient;
    INFO("local " << g.x << " " << g.y << " " << g.z << ", placed and turned back " << gp.x << " " << gp.y << " " << gp.z);
    CHECK(relative_difference(gp, turn(g)) < 1e-7);
  }
}
