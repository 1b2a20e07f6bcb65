#include "sky/cie_sky.hpp"

#include "sky/adaptive_quadrature.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <gsl/gsl_errno.h>

#include <algorithm>
#include <memory>

#include "geometry/error.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "illumination/least_squares.hpp"
#include "illumination/moments.hpp"
#include "sky/sky_quadrature.hpp"

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

double CieSky::max_relative_luminance() const {
  double m = relative_luminance(sun);
  for (const Vec3& u : hemisphere_directions(40000)) m = std::max(m, relative_luminance(u));
  return m;
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
                                            double tolerance, const std::function<double(const Vec3&)>& transmittance) {
  const QuadratureResult q = sky_irradiance_quadrature([&](const Vec3& u) { return sky.relative_luminance(u); },
                                                       sky.sun, region, n, tolerance, transmittance);
  return {q.value, q.error_estimate, q.evaluations};
}

namespace {

// The θ ∈ [0, σ] along the meridian u(θ) = cos θ L + sin θ e where c·u ≥ 0 for every c given:
// c·u = A cos θ + B sin θ vanishes at θ = atan2(A, −B) + kπ, so within [0, σ] (σ ≤ π) each
// constraint changes sign at most twice; the pieces between the crossings are tested at their
// midpoints. Returns false when nothing is left.
bool meridian_interval(const Vec3& L, const Vec3& e, double sigma, const std::array<Vec3, 2>& constraints, double& lo,
                       double& hi) {
  std::vector<double> cuts{0, sigma};
  for (const Vec3& c : constraints) {
    const double A = dot(c, L), B = dot(c, e);
    const double root = std::atan2(A, -B);  // A cos θ + B sin θ = 0
    for (double t : {root - pi, root, root + pi, root + 2 * pi})
      if (t > 0 && t < sigma) cuts.push_back(t);
  }
  std::sort(cuts.begin(), cuts.end());
  lo = hi = 0;
  bool found = false;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double mid = 0.5 * (cuts[i] + cuts[i + 1]);
    const Vec3 u = std::cos(mid) * L + std::sin(mid) * e;
    if (std::all_of(constraints.begin(), constraints.end(), [&](const Vec3& c) { return dot(c, u) >= 0; })) {
      // Pieces that pass are contiguous (an intersection of arcs shorter than π on the meridian).
      if (!found) lo = cuts[i];
      hi = cuts[i + 1];
      found = true;
    }
  }
  return found && hi > lo;
}

}  // namespace

CieQuadrature cie_sky_irradiance_over_cap(const CieSky& sky, const Vec3& cap_axis, double half_angle, const Vec3& n,
                                          double tolerance) {
  static const bool handler_off = [] {
    gsl_set_error_handler_off();  // errors come back as status codes, never abort()
    return true;
  }();
  (void)handler_off;
  const Vec3 L = normalized(cap_axis);
  // An orthonormal frame (e1, e2) about L, from the axis L is least aligned with.
  const Vec3 helper = std::abs(L.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 e1 = normalized(cross(helper, L)), e2 = cross(L, e1);
  const std::array<Vec3, 2> constraints{Vec3{0, 0, 1}, n};
  const double sun_theta = std::atan2(norm(cross(sky.sun, L)), dot(sky.sun, L));
  const double sun_phi = std::atan2(dot(sky.sun, e2), dot(sky.sun, e1));
  long evaluations = 0;
  double inner_error = 0;
  int status = 0;
  Qagp outer, inner;
  auto integrand_phi = [&](double phi) {
    const Vec3 e = std::cos(phi) * e1 + std::sin(phi) * e2;
    double lo, hi;
    if (!meridian_interval(L, e, half_angle, constraints, lo, hi)) return 0.0;
    auto integrand_theta = [&](double theta) {
      ++evaluations;
      const Vec3 u = std::cos(theta) * L + std::sin(theta) * e;
      return std::sin(theta) * sky.relative_luminance(u) * std::max(0.0, dot(n, u));
    };
    std::vector<double> points{lo};
    // The sun's nearest approach on this meridian: where the indicatrix bends most.
    const double nearest = std::atan2(dot(sky.sun, e), dot(sky.sun, L));
    if (nearest > lo && nearest < hi) points.push_back(nearest);
    points.push_back(hi);
    const auto [value, error] = inner.integrate(integrand_theta, points, 0.1 * tolerance, 1e-300);
    inner_error += error;
    if (inner.status()) status = inner.status();
    return value;
  };
  std::vector<double> points{-pi};
  if (sun_theta > 1e-12 && sun_theta < half_angle && sun_phi > -pi && sun_phi < pi) points.push_back(sun_phi);
  points.push_back(pi);
  const auto [value, error] = outer.integrate(integrand_phi, points, tolerance, 1e-300);
  if (outer.status()) status = outer.status();
  if (status && !(error <= 10 * tolerance * std::abs(value)))
    throw Error(std::string("the cap's quadrature did not converge (GSL: ") + gsl_strerror(status) + ")");
  return {value, error, evaluations};
}

}  // namespace daylit
