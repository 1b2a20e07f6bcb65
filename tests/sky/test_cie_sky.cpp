// The CIE standard general skies (sky/cie_sky.hpp): normalisation, the whole-hemisphere
// illuminance against an independent quadrature in polar coordinates, and the fitted closed-form
// path against the adaptive-quadrature reference path over a window.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "illumination/cap_moment.hpp"
#include "illumination/moments.hpp"
#include "illumination/spherical_quadrature.hpp"
#include "reference_quadrature.hpp"
#include "sky/cie_sky.hpp"

using namespace daylit;

namespace {

constexpr double pi = std::numbers::pi;

// E_out/L_z = ∫∫ L(Z, A) cos Z sin Z dZ dA by Gauss–Legendre in the sun's polar coordinates
// (polar axis = the sun, so the indicatrix's kink at χ = 0 is the coordinate pole, where the
// integrand is smooth in (χ, ψ)); the horizon cuts the (χ, ψ) rectangle, so ψ-panels are many
// and the integrand is set to 0 below the horizon; the cut limits this rule to ~1e-7.
long double polar_quadrature(const CieSky& sky) {
  std::vector<long double> x, w;
  test::gauss_legendre(24, x, w);
  const Vec3 s = sky.sun;
  const Vec3 p = normalized(cross(s, Vec3{0, 0, 1}));
  const Vec3 q = cross(s, p);
  const int chi_panels = 24, psi_panels = 48;
  long double sum = 0;
  for (int a = 0; a < chi_panels; ++a)
    for (int i = 0; i < 24; ++i) {
      const long double chi = (a + 0.5L * (x[i] + 1)) * pi / chi_panels;
      long double inner = 0;
      for (int b = 0; b < psi_panels; ++b)
        for (int j = 0; j < 24; ++j) {
          const long double psi = (b + 0.5L * (x[j] + 1)) * 2 * pi / psi_panels;
          const Vec3 u = std::cos(double(chi)) * s + std::sin(double(chi)) * (std::cos(double(psi)) * p + std::sin(double(psi)) * q);
          if (u.z > 0) inner += w[j] * sky.relative_luminance(u) * u.z;
        }
      sum += w[i] * inner * std::sin(chi) * (pi / psi_panels) * (pi / (2 * chi_panels));
    }
  return sum;
}

}  // namespace

TEST_CASE("every CIE sky has L = L_z at the zenith, type 5 is uniform and type 1 is not the Moon–Spencer sky") {
  const Vec3 sun = sun_direction(35, 200);
  for (int type = 1; type <= 15; ++type) CHECK(CieSky(type, sun).relative_luminance({0, 0, 1}) == Approx(1).epsilon(1e-15));
  const CieSky uniform(5, sun);
  CHECK(uniform.relative_luminance(normalized(Vec3{0.3, -0.8, 0.2})) == Approx(1).epsilon(1e-15));
  // SKY.md: type 1's E_out/L_z lies about 0.25 % above 7π/9.
  const CieSky type1(1, sun);
  const double ratio = cie_sky_irradiance_quadrature(type1, sky_hemisphere(), {0, 0, 1}, 1e-12).value / (7 * pi / 9);
  CHECK(ratio > 1.002);
  CHECK(ratio < 1.003);
  CHECK_THROWS(CieSky(16, sun));
  CHECK_THROWS(CieSky(3, sun_direction(95, 0)));
}

TEST_CASE("E_out of each CIE sky: adaptive quadrature, the fit's closed forms and polar quadrature agree") {
  for (int type = 1; type <= 15; ++type)
    for (const Vec3 sun : {sun_direction(20, 150), sun_direction(70, 250)}) {
      const CieSky sky(type, sun);
      const double adaptive = cie_sky_irradiance_quadrature(sky, sky_hemisphere(), {0, 0, 1}, 1e-12).value;
      const long double polar = polar_quadrature(sky);
      const CieSkyFit fit = fit_cie_sky(sky);
      const double closed = cie_sky_irradiance(fit, sky.sun, sky_hemisphere(), {0, 0, 1});
      INFO("type " << type << ", sun zenith " << std::acos(sun.z) * 180 / pi << ": adaptive " << adaptive << ", polar "
                   << double(polar) << ", fit " << closed << " (max error " << fit.max_error << ")");
      // Two quadratures of different construction: 1e-6 covers the polar rule's horizon cut.
      CHECK(std::abs(adaptive - polar) <= 1e-6 * polar);
      // |L_fit − L| ≤ max_error pointwise, so |E_fit − E| ≤ max_error · π (plus the reference's 1e-12).
      CHECK(std::abs(closed - adaptive) <= fit.max_error * pi + 1e-12 * adaptive);
    }
}

TEST_CASE("over a window the fit's closed forms stay within the fit's bound of the quadrature reference") {
  const auto window = directions_through({{-1, 3, 0.9}, {1, 3, 0.9}, {1, 3, 2.4}, {-1, 3, 2.4}}, {0, 0, 0.85});
  const Vec3 up{0, 0, 1};
  for (int type : {1, 5, 8, 12, 15}) {
    const CieSky sky(type, sun_direction(40, 170));  // the sun behind the window, seen through it
    const CieSkyFit fit = fit_cie_sky(sky);
    const double reference = cie_sky_irradiance_quadrature(sky, window, up, 1e-12).value;
    const double closed = cie_sky_irradiance(fit, sky.sun, window, up);
    INFO("type " << type << ": fit " << closed << ", quadrature " << reference << ", fit max error " << fit.max_error);
    CHECK(std::abs(closed - reference) <= fit.max_error * lambert(window, up));
    if (type == 5) CHECK(closed == Approx(lambert(window, up)).epsilon(1e-13));  // the uniform sky is fitted exactly
  }
}

TEST_CASE("the adaptive cubature integrates polynomials over spherical polygons to 1e-12") {
  const auto region = directions_through({{0.2, -0.3, 1}, {0.9, -0.1, 1}, {0.7, 0.6, 1}, {0.4, 0.2, 1}, {0.1, 0.5, 1}}, {});
  const Vec3 w = normalized(Vec3{0.3, 0.1, 1}), n{0, 0.2, 1};
  for (int k : {0, 1, 5, 20}) {
    const QuadratureResult q = integrate_over_region(region, [&](const Vec3& u) { return std::pow(dot(w, u), k) * dot(n, u); }, 1e-13);
    CHECK(q.value == Approx(double_axis_moment(region, w, n, k)).epsilon(1e-12));
  }
}

TEST_CASE("over spherical caps the nested quadrature matches closed forms and the polygon cubature") {
  SECTION("the uniform sky (type 5) over a cap straddling the horizon: Snyder's clipped-cap moment") {
    // With n = z the receiver's plane is the horizon, so the region is C ∩ {z ≥ 0} and
    // E/L_z = ∫_{C∩H} z dΩ, Snyder's I(1) in closed form (cap_moment.hpp, 1e-15).
    const CieSky uniform(5, sun_direction(30, 180));
    for (const double tilt : {0.3, 1.2, 1.55, 1.6}) {
      const Vec3 axis{std::sin(tilt), 0, std::cos(tilt)};
      for (const double half_angle : {0.01, 0.4, 1.0}) {
        const double closed = cap_moment(axis, half_angle, Vec3{0, 0, 1}, {{Vec3{0, 0, 1}, 1}});
        const CieQuadrature q = cie_sky_irradiance_over_cap(uniform, axis, half_angle, {0, 0, 1}, 1e-12);
        INFO("tilt " << tilt << ", half-angle " << half_angle << ": " << q.value << " against " << closed);
        // The quadrature's target is 1e-12; the outer integrand has kinks where the horizon starts
        // to cut a meridian, which cost it a few more digits than smooth integrands would.
        CHECK(q.value == Approx(closed).epsilon(1e-10));
      }
    }
  }
  SECTION("the hemisphere in front of a tilted receiver, as a cap, against the fan cubature of the lune") {
    // The cap about n of half-angle π/2, cut by n·u ≥ 0 and the horizon, is the lune
    // above_horizon_and_in_front(hemisphere, n): a polygon region the fan cubature takes.
    for (const int type : {1, 7, 12, 15}) {
      const CieSky sky(type, sun_direction(40, 200));
      const Vec3 n = normalized(Vec3{0.3, -1, 0.6});
      const double cap = cie_sky_irradiance_over_cap(sky, n, pi / 2, n, 1e-12).value;
      const double lune = cie_sky_irradiance_quadrature(sky, above_horizon_and_in_front(sky_hemisphere(), n), n, 1e-12).value;
      INFO("type " << type);
      CHECK(cap == Approx(lune).epsilon(1e-9));
    }
  }
}
