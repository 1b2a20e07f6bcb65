// The sky component through exact visible regions, against long-double quadrature over the window
// area (unobstructed, behind the horizon, and with occluders whose shadows are known exactly), and
// against the closed forms of SKY.md for vertical receivers.

#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

#include "reference_quadrature.hpp"
#include "test_scenes.hpp"
#include "materials/glass_transmittance.hpp"
#include "simulation/sky_component.hpp"
#include "test_support.hpp"

using namespace daylit;
using daylit::test::LVec3;

namespace {

constexpr long double kEout = 7 * std::numbers::pi_v<long double> / 9;

using test::polygon;

double sc_percent(const Scene& scene, const Vec3& p, const Vec3& n, GeometryMode mode = GeometryMode::exact) {
  const VisibilityEngine engine(scene, mode);
  VisibilityCounters counters;
  return sky_component_percent(engine, scene, {p, normalized(n)}, SkyModel::cie_overcast, counters);
}

// Overcast sky component (percent) through the rectangle origin + s e1 + t e2, by quadrature.
long double reference_sc(const Vec3& p, const Vec3& n, const LVec3& origin, const LVec3& e1, const LVec3& e2) {
  const Vec3 un = normalized(n);
  const long double E = test::integrate_directions(test::lvec(p), origin, e1, e2, [&](const LVec3& u) {
    const long double cosine = un.x * u.x + un.y * u.y + un.z * u.z;
    return (1 + 2 * u.z) / 3 * cosine;
  });
  return 100 * E / kEout;
}

using daylit::test::relative_error;

}  // namespace

TEST_CASE("overcast sky component through an unobstructed window matches quadrature to 1e-10") {
  Scene scene;
  scene.apertures.push_back({polygon({{0, 2, 1}, {2, 2, 1}, {2, 2, 2.2}, {0, 2, 2.2}}), 1.0});
  struct Case {
    Vec3 p, n;
  };
  for (const Case c : {Case{{0.7, -1.5, 0.85}, {0, 0, 1}}, Case{{3.5, 0.5, 0.2}, {0, 0, 1}}, Case{{1, -4, 0.9}, {0.3, 1, 0.4}},
                       Case{{-2, 1.9, 0.85}, {0, 0, 1}}}) {
    const double value = sc_percent(scene, c.p, c.n);
    const long double ref = reference_sc(c.p, c.n, {0, 2, 1}, {2, 0, 0}, {0, 0, 1.2});
    INFO("sensor " << c.p.x << "," << c.p.y << "," << c.p.z << " value " << value << " reference " << double(ref));
    CHECK(relative_error(value, ref) < 1e-10);
  }
}

TEST_CASE("the part of a window below the sensor's horizon does not count") {
  Scene scene;
  scene.apertures.push_back({polygon({{0, 2, 0.3}, {2, 2, 0.3}, {2, 2, 2.2}, {0, 2, 2.2}}), 1.0});
  const Vec3 p{0.6, -1, 0.85};
  const double value = sc_percent(scene, p, {0, 0, 1});
  // Only z ∈ [0.85, 2.2] is sky.
  const long double ref = reference_sc(p, {0, 0, 1}, {0, 2, 0.85}, {2, 0, 0}, {0, 0, 1.35});
  CHECK(relative_error(value, ref) < 1e-10);
}

TEST_CASE("an overhang beyond the window casts the shadow similar triangles predict") {
  // Window y = 0, x ∈ [0, 2], z ∈ [1, 2]; sensor 2 m inside. A wide slab at z = 2.2 reaching 1 m
  // out hides everything above the line where the slab's outer edge projects:
  // z' = p_z + (2.2 − p_z) · 2/(2 + 1).
  Scene scene;
  scene.apertures.push_back({polygon({{0, 0, 1}, {2, 0, 1}, {2, 0, 2}, {0, 0, 2}}), 1.0});
  scene.occluders.push_back(polygon({{-50, 0, 2.2}, {52, 0, 2.2}, {52, -1, 2.2}, {-50, -1, 2.2}}, "overhang"));
  const Vec3 p{0.8, 2, 0.85};
  const long double z_cut = 0.85L + (2.2L - 0.85L) * 2 / 3;
  const long double ref = reference_sc(p, {0, 0, 1}, {0, 0, 1}, {2, 0, 0}, {0, 0, z_cut - 1});
  for (GeometryMode mode : {GeometryMode::exact, GeometryMode::floating}) {
    const double value = sc_percent(scene, p, {0, 0, 1}, mode);
    CHECK(relative_error(value, ref) < 1e-10);
  }
}

TEST_CASE("a pillar in front of the window subtracts its central projection exactly") {
  // Window y = 0, x ∈ [0, 3], z ∈ [1, 2.5]; sensor at y = 3. A pillar face at y = 1.5,
  // x ∈ [1, 1.4], z ∈ [0, 3]: seen from p it covers x' = p_x + (x − p_x)·2 on the window plane,
  // i.e. the full height of the window between x' = 0.5 and 1.3 when p_x = 1.5.
  Scene scene;
  scene.apertures.push_back({polygon({{0, 0, 1}, {3, 0, 1}, {3, 0, 2.5}, {0, 0, 2.5}}), 1.0});
  scene.occluders.push_back(polygon({{1, 1.5, 0}, {1.4, 1.5, 0}, {1.4, 1.5, 3.5}, {1, 1.5, 3.5}}, "pillar"));
  const Vec3 p{1.5, 3, 0.85};
  const long double left = reference_sc(p, {0, 0, 1}, {0, 0, 1}, {0.5, 0, 0}, {0, 0, 1.5});
  const long double right = reference_sc(p, {0, 0, 1}, {1.3, 0, 1}, {1.7, 0, 0}, {0, 0, 1.5});
  const double value = sc_percent(scene, p, {0, 0, 1});
  CHECK(relative_error(value, left + right) < 1e-10);
}

TEST_CASE("vertical sky component of an unobstructed vertical plane is (3π + 8)/(14π)") {
  // A 2e7-wide aperture 1 m in front of a receiver facing +y: it misses O(1/L) of the sky.
  const double L = 1e7;
  Scene scene;
  scene.apertures.push_back({polygon({{-L, 1, 10}, {L, 1, 10}, {L, 1, 10 + L}, {-L, 1, 10 + L}}), 1.0});
  const double value = sc_percent(scene, {0, 0, 10}, {0, 1, 0});
  const double pi = std::numbers::pi;
  CHECK(std::abs(value / 100 - (3 * pi + 8) / (14 * pi)) < 1e-6);
}

TEST_CASE("an infinitely long obstruction of profile angle 25° leaves BRE's 27.3 %") {
  const double L = 1e7, pi = std::numbers::pi, alpha = 25 * pi / 180;
  const double distance = 11, top = 10 + distance * std::tan(alpha);
  Scene scene;
  scene.apertures.push_back({polygon({{-L, 1, 10}, {L, 1, 10}, {L, 1, 10 + L}, {-L, 1, 10 + L}}), 1.0});
  scene.occluders.push_back(polygon({{-L, distance, 0}, {L, distance, 0}, {L, distance, top}, {-L, distance, top}}, "building"));
  const double expected = (3 * pi * (1 - std::sin(alpha)) + 8 * std::cos(alpha) * std::cos(alpha)) / (14 * pi);
  CHECK(std::abs(sc_percent(scene, {0, 0, 10}, {0, 1, 0}) / 100 - expected) < 1e-6);
  CHECK(expected == Approx(0.273).margin(5e-4));
}

TEST_CASE("transmittance scales the sky component and apertures add") {
  Scene one, two;
  const Polygon a = polygon({{0, 2, 1}, {1, 2, 1}, {1, 2, 2}, {0, 2, 2}});
  const Polygon b = polygon({{1, 2, 1}, {2, 2, 1}, {2, 2, 2}, {1, 2, 2}});
  const Polygon ab = polygon({{0, 2, 1}, {2, 2, 1}, {2, 2, 2}, {0, 2, 2}});
  one.apertures.push_back({ab, 0.7});
  two.apertures.push_back({a, 0.7});
  two.apertures.push_back({b, 0.7});
  const Vec3 p{0.4, -1, 0.85};
  Scene clear;
  clear.apertures.push_back({ab, 1.0});
  CHECK(sc_percent(one, p, {0, 0, 1}) == Approx(0.7 * sc_percent(clear, p, {0, 0, 1})).epsilon(1e-15));
  CHECK(sc_percent(two, p, {0, 0, 1}) == Approx(sc_percent(one, p, {0, 0, 1})).epsilon(1e-14));
}

TEST_CASE("results do not depend on the number of threads") {
  Scene scene;
  scene.apertures.push_back({polygon({{0, 0, 1}, {3, 0, 1}, {3, 0, 2.5}, {0, 0, 2.5}}), 1.0});
  scene.occluders.push_back(polygon({{1, 1.5, 0}, {1.4, 1.5, 0}, {1.4, 1.5, 3.5}, {1, 1.5, 3.5}}, "pillar"));
  SensorGrid grid;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 30; ++j) grid.sensors.push_back({{0.1 * i, 0.5 + 0.1 * j, 0.85}, {0, 0, 1}});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  std::vector<double> one, many;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = sky_component(engine, scene, grid, SkyModel::cie_overcast).sc_percent;
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 4);
    many = sky_component(engine, scene, grid, SkyModel::cie_overcast).sc_percent;
  }
  CHECK(one == many);
}

TEST_CASE("glazing: Radiance's angle-dependent glass integrated as moments about the pane's normal") {
  // A 2 × 1.2 window in the wall y = 2 of clear glass (transmissivity 0.96): the sky component
  // through its fitted polynomial T(μ) must equal quadrature of the same polynomial to the glazed
  // moments' target, 1e-9 (moments.cpp; measured 1.6e-14 to 3.6e-12 here), and quadrature of
  // Radiance's exact T(μ) to within the fit's
  // stated maximum error times the unglazed sky component (|T_fit − T| ≤ max_error pointwise).
  const GlassOptics clear{{0.96, 0.96, 0.96}, 1.52};
  const TransmittancePolynomial fit = fit_glass_transmittance(clear);
  CHECK(fit.max_error < 3e-3);
  CHECK(glass_transmittance(clear, 1.0) == Approx(0.8815).epsilon(1e-4));  // Radiance's documented 0.88 for 0.96
  Scene scene;
  Aperture window{polygon({{0, 2, 1}, {2, 2, 1}, {2, 2, 2.2}, {0, 2, 2.2}}), glass_transmittance(clear, 1.0)};
  window.angular_transmittance = fit.coefficients;
  window.angular_fit_error = fit.max_error;
  scene.apertures.push_back(window);
  auto polynomial = [&](long double mu) {
    long double t = 0;
    for (std::size_t k = fit.coefficients.size(); k-- > 0;) t = t * mu + fit.coefficients[k];
    return t;
  };
  for (const Vec3 p : {Vec3{0.7, -1.5, 0.85}, Vec3{3.5, 0.5, 0.2}, Vec3{-2, 1.9, 0.85}}) {
    const Vec3 n{0, 0, 1};
    auto reference = [&](const std::function<long double(long double)>& T) {
      return 100 * test::integrate_directions(test::lvec(p), {0, 2, 1}, {2, 0, 0}, {0, 0, 1.2}, [&](const LVec3& u) {
               return T(u.y) * (1 + 2 * u.z) / 3 * u.z;  // μ = |a·u| = u_y for the pane y = 2 seen from y < 2
             }) /
             kEout;
    };
    const double value = sc_percent(scene, p, n);
    const long double unglazed = reference_sc(p, n, {0, 2, 1}, {2, 0, 0}, {0, 0, 1.2});
    INFO("sensor " << p.x << "," << p.y << "," << p.z);
    const double error = relative_error(value, reference(polynomial));
    INFO("relative error against the polynomial's quadrature " << error);
    CHECK(error < 1e-9);
    CHECK(std::abs(value - reference([&](long double mu) { return glass_transmittance(clear, double(mu)); })) <=
          fit.max_error * unglazed);
    CHECK(value < 0.8815 * unglazed);  // oblique light loses more than at normal incidence
  }
}

TEST_CASE("glass reflects what it does not transmit or absorb: Radiance's R(μ), and its value for diffuse light") {
  // Without absorption (transmissivity 1 in every channel) the pane's two Fresnel surfaces and the
  // light bouncing between them only split the light: R + T = 1 at every angle, to roundoff.
  for (const double n : {1.52, 1.4, 2.0}) {
    const GlassOptics lossless{{1.0, 1.0, 1.0}, n};
    for (int i = 0; i <= 100; ++i) {
      const double mu = i / 100.0;
      CHECK(std::abs(glass_reflectance(lossless, mu) + glass_transmittance(lossless, mu) - 1) < 1e-15);
    }
  }
  // At normal incidence r_s = r_p = r0 = ((n − 1)/(n + 1))², and the pane returns
  // r0 + (1 − r0)² r0 t²/(1 − r0² t²) (the geometric series of passes), written here that way.
  const GlassOptics clear{{0.96, 0.96, 0.96}, 1.52};
  const double r0 = std::pow(0.52 / 2.52, 2), t2 = 0.96 * 0.96;
  CHECK(glass_reflectance(clear, 1.0) == Approx(r0 + (1 - r0) * (1 - r0) * r0 * t2 / (1 - r0 * r0 * t2)).epsilon(1e-15));
  CHECK(glass_reflectance(clear, 0.0) == 1.0);  // grazing: everything is reflected
  // With absorption the pane keeps some: R + T < 1, the more so the more it absorbs.
  const GlassOptics tinted{{0.5, 0.6, 0.7}, 1.52};
  for (const double mu : {0.05, 0.3, 0.7, 1.0})
    CHECK(glass_reflectance(tinted, mu) + glass_transmittance(tinted, mu) < glass_reflectance(clear, mu) + glass_transmittance(clear, mu));
  // The diffuse reflectance 2 ∫ R μ dμ against composite Simpson on 2^16 intervals in long double
  // (an independent rule; R is smooth on [0, 1], so Simpson's h⁴ error is ~1e-19 here). 1e-13:
  // the two rules' sums of 64 and 65,537 terms each round to a few ulps of 0.15.
  for (const GlassOptics& g : {clear, tinted, GlassOptics{{0.9, 0.9, 0.9}, 1.4}}) {
    const int m = 1 << 16;
    long double simpson = 0;
    for (int i = 0; i <= m; ++i) {
      const long double mu = static_cast<long double>(i) / m;
      const long double w = (i == 0 || i == m) ? 1 : (i % 2 ? 4 : 2);
      simpson += w * 2 * mu * glass_reflectance(g, double(mu));
    }
    simpson /= 3.0L * m;
    CHECK(std::abs(glass_diffuse_reflectance(g) - double(simpson)) < 1e-13);
  }
  // Clear glass (88 % at normal incidence) reflects about 8 % of normal light and, since R rises
  // to 1 at grazing incidence, nearly twice that of diffuse light.
  CHECK(std::abs(glass_reflectance(clear, 1.0) - 0.08) < 0.002);
  INFO("diffuse reflectance of clear glass " << glass_diffuse_reflectance(clear));
  CHECK(glass_diffuse_reflectance(clear) > 1.5 * glass_reflectance(clear, 1.0));
  CHECK(glass_diffuse_reflectance(clear) < 2.0 * glass_reflectance(clear, 1.0));
}
