// Arvo 1995 §6 (glossy.hpp): directional luminaires, glossy reflection and transmission, and the
// normalisation N(w, v, n), against long-double quadrature that shares no formula with them.
//
// Tolerances: the kernels are accurate to ~1e-13 (moments.hpp); the quadratures below converge to
// below 1e-15 on these smooth integrands (checked by doubling their points), so 1e-12 relative
// leaves room only for the kernels' rounding.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/error.hpp"
#include "illumination/glossy.hpp"
#include "illumination/moments.hpp"
#include "reference_quadrature.hpp"

using namespace daylit;
using daylit::test::LVec3;

namespace {

constexpr long double pi_l = std::numbers::pi_v<long double>;
long double ldot(const Vec3& a, const LVec3& u) { return a.x * u.x + a.y * u.y + a.z * u.z; }

// N(w, v, n) by quadrature in coordinates adapted to the lune: with v = z, w = (sin α, 0, cos α)
// and u = cos β (cos ψ z + sin ψ x) + sin β y (dσ = cos β dβ dψ), the lune is the rectangle
// ψ ∈ [α − π/2, π/2], β ∈ [−π/2, π/2], and the integrand cos^{n+2} β · cos^n(ψ − α) cos ψ
// separates into two smooth 1-D integrals, each by 4 × 64-point Gauss–Legendre.
long double lune_quadrature(long double alpha, int n) {
  std::vector<long double> x, wt;
  test::gauss_legendre(64, x, wt);
  auto integrate = [&](long double a, long double b, auto f) {
    long double sum = 0;
    for (int p = 0; p < 4; ++p)
      for (int i = 0; i < 64; ++i) sum += wt[i] * f(a + (p + 0.5L * (x[i] + 1)) * (b - a) / 4);
    return sum * (b - a) / 8;
  };
  const long double polar = integrate(-pi_l / 2, pi_l / 2, [&](long double beta) { return std::pow(std::cos(beta), (long double)n + 2); });
  const long double azimuth = integrate(alpha - pi_l / 2, pi_l / 2, [&](long double psi) {
    return std::pow(std::cos(psi - alpha), (long double)n) * std::cos(psi);
  });
  return polar * azimuth;
}

}  // namespace

TEST_CASE("N(w, v, n) matches quadrature over the lune and Arvo's special cases") {
  for (double alpha : {0.0, 0.3, 1.2, 1.5707963267948966, 2.0, 2.9})
    for (int n : {0, 1, 2, 5, 30, 200}) {
      const Vec3 w{std::sin(alpha), 0, std::cos(alpha)}, v{0, 0, 1};
      const long double reference = lune_quadrature(alpha, n);
      INFO("alpha = " << alpha << ", n = " << n);
      // For w·v < 0 the lune is thin and the recurrence's terms alternate: 1e-12 absolute of the
      // hemisphere's scale 2π/(n + 2) as well.
      CHECK(std::abs(phong_normalisation(w, v, n) - reference) <= 1e-12 * std::abs(reference) + 1e-13 / (n + 2));
    }
  for (int n : {0, 1, 7, 1000}) CHECK(phong_normalisation({0, 0, 1}, {0, 0, 1}, n) == Approx(2 * std::numbers::pi / (n + 2)).epsilon(1e-14));
}

TEST_CASE("a Phong luminaire's irradiance matches quadrature and reduces to Lambert at n = 0") {
  // A 2 × 1.5 panel 2 m above the receiver, emitting about an axis tilted 20° from straight down.
  const std::vector<Vec3> panel{{-1, -0.5, 2}, {1, -0.5, 2}, {1, 1, 2}, {-1, 1, 2}};
  const auto region = directions_through(panel, {});
  const Vec3 axis = normalized(Vec3{0.34, 0, -0.94}), normal{0, 0, 1};
  for (int n : {0, 1, 10, 100}) {
    const long double reference = test::integrate_directions({0, 0, 0}, {-1, -0.5, 2}, {2, 0, 0}, {0, 1.5, 0}, [&](const LVec3& u) {
      return std::pow(std::max(-ldot(axis, u), 0.0L), (long double)n) * ldot(normal, u);
    });
    INFO("n = " << n);
    CHECK(phong_luminaire_irradiance(region, axis, n, normal, 1.0) == Approx(double(reference)).epsilon(1e-12));
  }
  CHECK(phong_luminaire_irradiance(region, axis, 0, normal, 2.5) == Approx(2.5 * lambert(region, normal)).epsilon(1e-14));
}

TEST_CASE("glossy reflection of a window matches quadrature, c beyond the energy bound is refused") {
  // A floor point with normal z sees a window in the wall y = 3; the viewer looks down at 40°.
  const std::vector<Vec3> window{{-1, 3, 1}, {1, 3, 1}, {1, 3, 2.5}, {-1, 3, 2.5}};
  const auto region = directions_through(window, {});
  const Vec3 normal{0, 0, 1}, to_viewer = normalized(Vec3{0, -0.77, 0.64});
  const Vec3 mirror = 2 * dot(normal, to_viewer) * normal - to_viewer;
  for (int n : {1, 10, 300}) {
    const double c = max_glossy_coefficient(n);
    const long double reference = test::integrate_directions({0, 0, 0}, {-1, 3, 1}, {2, 0, 0}, {0, 0, 1.5}, [&](const LVec3& u) {
      return c * std::pow(std::max(ldot(mirror, u), 0.0L), (long double)n) * ldot(normal, u);
    });
    INFO("n = " << n);
    CHECK(glossy_reflected_radiance(region, normal, to_viewer, n, c, 1.0) == Approx(double(reference)).epsilon(1e-12));
  }
  CHECK_THROWS_AS(glossy_reflected_radiance(region, normal, to_viewer, 10, 1.01 * max_glossy_coefficient(10), 1.0), Error);
  // At the energy bound a white sky hemisphere (a huge luminaire) reflects at most its radiance.
  const auto sky = directions_through({{-1e4, -1e4, 1}, {1e4, -1e4, 1}, {1e4, 1e4, 1}, {-1e4, 1e4, 1}}, {});
  CHECK(glossy_reflected_radiance(sky, normal, normal, 50, max_glossy_coefficient(50), 1.0) == Approx(1.0).epsilon(1e-6));
}

TEST_CASE("glossy transmission through frosted glass matches quadrature") {
  // A viewer below a frosted skylight (normal −z, facing the viewer) looks up through it at a
  // bright panel above.
  const std::vector<Vec3> panel{{-2, -1, 3}, {2, -1, 3}, {2, 2, 3}, {-2, 2, 3}};
  const auto region = directions_through(panel, {});
  const Vec3 normal{0, 0, -1}, to_viewer = normalized(Vec3{0.2, -0.1, -1});
  const Vec3 w = -1.0 * to_viewer;
  for (int n : {2, 65}) {
    const double c = max_glossy_coefficient(n);
    const long double reference = test::integrate_directions({0, 0, 0}, {-2, -1, 3}, {4, 0, 0}, {0, 3, 0}, [&](const LVec3& u) {
      return c * std::pow(std::max(ldot(w, u), 0.0L), (long double)n) * u.z;
    });
    INFO("n = " << n);
    CHECK(glossy_transmitted_radiance(region, normal, to_viewer, n, c, 1.0) == Approx(double(reference)).epsilon(1e-12));
  }
}
