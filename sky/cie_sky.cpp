#include "sky/cie_sky.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "geometry/error.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "illumination/least_squares.hpp"
#include "illumination/moments.hpp"
#include "illumination/spherical_quadrature.hpp"

namespace daylit {

namespace {

constexpr double pi = std::numbers::pi;

// ISO 15469:2004, Table 1: a, b (gradation), c, d, e (indicatrix) of types 1..15.
constexpr double kParameters[15][5] = {
    {4, -0.7, 0, -1, 0},        {4, -0.7, 2, -1.5, 0.15},    {1.1, -0.8, 0, -1, 0},      {1.1, -0.8, 2, -1.5, 0.15},
    {0, -1, 0, -1, 0},          {0, -1, 2, -1.5, 0.15},      {0, -1, 5, -2.5, 0.3},      {0, -1, 10, -3, 0.45},
    {-1, -0.55, 2, -1.5, 0.15}, {-1, -0.55, 5, -2.5, 0.3},   {-1, -0.55, 10, -3, 0.45},  {-1, -0.32, 10, -3, 0.45},
    {-1, -0.32, 16, -3, 0.3},   {-1, -0.15, 16, -3, 0.3},    {-1, -0.15, 24, -2.8, 0.15},
};

constexpr int kZenithDegree = 10, kSunDegree = 10;
constexpr int kLobes[] = {16, 32, 64, 128, 256, 512, 1024};

// Directions spread evenly over the upper hemisphere (a Fibonacci lattice, equal solid angles).
std::vector<Vec3> hemisphere_directions(int count) {
  std::vector<Vec3> u(count);
  const double golden = pi * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1 - (i + 0.5) / count;
    const double r = std::sqrt(1 - z * z);
    u[i] = {r * std::cos(golden * i), r * std::sin(golden * i), z};
  }
  return u;
}

// The fit's basis functions at u, in the order of CieSkyFit's coefficient lists.
std::vector<long double> basis(const Vec3& u, const Vec3& s) {
  const long double z = u.z, t = dot(s, u);
  std::vector<long double> row;
  long double zi = 1;
  for (int i = 0; i <= kZenithDegree; ++i, zi *= z) row.push_back(zi);
  zi = 1;
  for (int i = 0; i <= kZenithDegree; ++i, zi *= z) row.push_back(zi * t);
  long double tj = t * t;
  for (int j = 2; j <= kSunDegree; ++j, tj *= t) row.push_back(tj);
  tj = t * t;
  for (int j = 2; j <= kSunDegree; ++j, tj *= t) row.push_back(tj * z);
  for (int n : kLobes) row.push_back(std::pow(t, (long double)n));
  return row;
}

double evaluate(const CieSkyFit& fit, const Vec3& u, const Vec3& s) {
  const double z = u.z, t = dot(s, u);
  double sum = 0, zi = 1;
  for (std::size_t i = 0; i < fit.zenith_powers.size(); ++i, zi *= z)
    sum += (fit.zenith_powers[i] + fit.zenith_powers_times_sun[i] * t) * zi;
  double tj = 1;
  for (std::size_t j = 0; j < fit.sun_powers.size(); ++j, tj *= t)
    sum += (fit.sun_powers[j] + fit.sun_powers_times_zenith[j] * z) * tj;
  for (std::size_t k = 0; k < fit.lobe_exponents.size(); ++k) sum += fit.lobe_weights[k] * std::pow(t, fit.lobe_exponents[k]);
  return sum;
}

}  // namespace

CieSky::CieSky(int type_, const Vec3& sun_) : type(type_), sun(normalized(sun_)) {
  if (type < 1 || type > 15) throw Error("CIE sky type " + std::to_string(type) + " is not one of 1..15");
  if (!(sun.z > 0)) throw Error("the sun is below the horizon (zenith angle ≥ 90°): the CIE general skies need it above");
  const double* p = kParameters[type - 1];
  a = p[0], b = p[1], c = p[2], d = p[3], e = p[4];
}

double CieSky::relative_luminance(const Vec3& u) const {
  if (!(u.z > 0)) return 0;
  auto gradation = [&](double cos_z) { return 1 + a * std::exp(b / cos_z); };
  auto indicatrix = [&](double chi) { return 1 + c * (std::exp(d * chi) - std::exp(d * pi / 2)) + e * std::cos(chi) * std::cos(chi); };
  // χ = atan2(|s × u|, s·u): full precision near the sun, where acos loses half the digits.
  const double chi = std::atan2(norm(cross(sun, u)), dot(sun, u));
  const double zenith_of_sun = std::atan2(std::hypot(sun.x, sun.y), sun.z);
  return gradation(u.z) * indicatrix(chi) / (gradation(1.0) * indicatrix(zenith_of_sun));
}

Vec3 sun_direction(double zenith_deg, double azimuth_deg) {
  const double z = zenith_deg * pi / 180, a = azimuth_deg * pi / 180;
  return {std::sin(z) * std::sin(a), std::sin(z) * std::cos(a), std::cos(z)};
}

CieSkyFit fit_cie_sky(const CieSky& sky) {
  const std::vector<Vec3> samples = hemisphere_directions(8000);
  std::vector<long double> A, b;
  std::size_t cols = 0;
  for (const Vec3& u : samples) {
    const auto row = basis(u, sky.sun);
    cols = row.size();
    A.insert(A.end(), row.begin(), row.end());
    b.push_back(sky.relative_luminance(u));
  }
  const std::vector<long double> x = least_squares(std::move(A), std::move(b), samples.size(), cols);
  CieSkyFit fit;
  std::size_t k = 0;
  for (int i = 0; i <= kZenithDegree; ++i) fit.zenith_powers.push_back(double(x[k++]));
  for (int i = 0; i <= kZenithDegree; ++i) fit.zenith_powers_times_sun.push_back(double(x[k++]));
  fit.sun_powers.assign(2, 0.0);
  for (int j = 2; j <= kSunDegree; ++j) fit.sun_powers.push_back(double(x[k++]));
  fit.sun_powers_times_zenith.assign(2, 0.0);
  for (int j = 2; j <= kSunDegree; ++j) fit.sun_powers_times_zenith.push_back(double(x[k++]));
  for (int n : kLobes) {
    fit.lobe_exponents.push_back(n);
    fit.lobe_weights.push_back(double(x[k++]));
  }
  // The fit's error on a denser lattice and around the sun.
  std::vector<Vec3> checks = hemisphere_directions(40000);
  for (double ring : {1e-3, 3e-3, 1e-2, 3e-2, 0.1})
    for (int i = 0; i < 32; ++i) {
      const Vec3 p = normalized(cross(sky.sun, std::abs(sky.sun.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0}));
      const Vec3 q = cross(sky.sun, p);
      const double phi = 2 * pi * i / 32;
      const Vec3 u = normalized(std::cos(ring) * sky.sun + std::sin(ring) * (std::cos(phi) * p + std::sin(phi) * q));
      if (u.z > 0) checks.push_back(u);
    }
  checks.push_back(sky.sun);
  double sum2 = 0;
  for (const Vec3& u : checks) {
    const double error = std::abs(evaluate(fit, u, sky.sun) - sky.relative_luminance(u));
    fit.max_error = std::max(fit.max_error, error);
    sum2 += error * error;
  }
  fit.rms_error = std::sqrt(sum2 / checks.size());
  return fit;
}

double cie_sky_irradiance(const CieSkyFit& fit, const Vec3& sun, const SphericalRegion& region, const Vec3& n) {
  if (region.empty()) return 0;
  const Vec3 zenith{0, 0, 1};
  // Σ p_i ∫ z^i (n·u) + Σ q_i ∫ z^i (s·u)(n·u) and Σ r_j ∫ t^j (n·u) + Σ w_j ∫ t^j (z·u)(n·u):
  // polynomial_cosine_moments about the zenith and about the sun.
  double sum = polynomial_cosine_moments(region, zenith, n, sun, fit.zenith_powers).cosine +
               polynomial_cosine_moments(region, zenith, n, sun, fit.zenith_powers_times_sun).cosine_linear +
               polynomial_cosine_moments(region, sun, n, zenith, fit.sun_powers).cosine +
               polynomial_cosine_moments(region, sun, n, zenith, fit.sun_powers_times_zenith).cosine_linear;
  for (std::size_t k = 0; k < fit.lobe_exponents.size(); ++k)
    sum += fit.lobe_weights[k] * double_axis_moment(region, sun, n, fit.lobe_exponents[k]);
  return sum;
}

SphericalRegion above_horizon_and_in_front(const SphericalRegion& region, const Vec3& n) {
  return clip_to_hemisphere(clip_to_hemisphere(region, {0, 0, 1}), n);
}

SphericalRegion sky_hemisphere() {
  // Four octants from the zenith: one loop on the horizon alone would be a great circle, whose
  // fan triangles (for the solid angle and the quadrature) all degenerate.
  const Vec3 z{0, 0, 1}, h[4] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  SphericalRegion region;
  for (int i = 0; i < 4; ++i) region.loops.push_back({z, h[i], h[(i + 1) % 4]});
  return region;
}

CieQuadrature cie_sky_irradiance_quadrature(const CieSky& sky, const SphericalRegion& region, const Vec3& n,
                                            double tolerance) {
  // Fan triangles, each split at the sun when it holds it, so that the indicatrix's kink sits on
  // a vertex, where the cubature's refinement converges fastest.
  SphericalRegion triangles;
  for (const DirectionLoop& loop : region.loops)
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
      const Vec3 a = loop[0], b = loop[i], c = loop[i + 1];
      const double orientation = dot(a, cross(b, c));
      const Vec3& s = sky.sun;
      const bool holds_sun = orientation != 0 && dot(s, cross(a, b)) * orientation > 0 &&
                             dot(s, cross(b, c)) * orientation > 0 && dot(s, cross(c, a)) * orientation > 0;
      if (holds_sun) {
        const Vec3 sun_point = (dot(a, a) > 0 ? norm(a) : 1.0) * s;
        triangles.loops.push_back({sun_point, b, c});
        triangles.loops.push_back({a, sun_point, c});
        triangles.loops.push_back({a, b, sun_point});
      } else {
        triangles.loops.push_back({a, b, c});
      }
    }
  const QuadratureResult q = integrate_over_region(
      triangles, [&](const Vec3& u) { return sky.relative_luminance(u) * std::max(0.0, dot(n, u)); }, tolerance);
  return {q.value, q.error_estimate, q.evaluations};
}

}  // namespace daylit
