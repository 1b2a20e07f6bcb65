#include "illumination/glossy.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "geometry/error.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "illumination/moments.hpp"

namespace daylit {

namespace {

constexpr double pi = std::numbers::pi;

void check_coefficient(double coefficient, int n) {
  if (!(coefficient >= 0) || coefficient > max_glossy_coefficient(n) * (1 + 1e-15))
    throw Error("glossy coefficient " + std::to_string(coefficient) + " exceeds the energy bound (n + 2)/(2π) = " +
                std::to_string(max_glossy_coefficient(n)) + " for n = " + std::to_string(n));
}

// ∫ (w·u)^n (v·u) dσ over the part of the region where both factors are non-negative.
double positive_lobe_moment(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n) {
  const SphericalRegion cut = clip_to_hemisphere(clip_to_hemisphere(region, v), w);
  return cut.empty() ? 0.0 : double_axis_moment(cut, w, v, n);
}

}  // namespace

double phong_normalisation(const Vec3& w, const Vec3& v, int n) {
  const double d = std::clamp(dot(w, v), -1.0, 1.0);
  const double c = norm(cross(w, v));
  const double tau1 = 0.5 * pi * (1 + d);  // τ^1 = (π + d W_0)/2
  if (n == 0) return tau1;                  // eq. 14 at n = 0: both edges count, 2N = π + d π
  // τ^{n−1} of the lune about w, stepping k by 2 from τ^0 or τ^1 with cw = c^{k−1} W_{k−1}.
  const int last = n - 1;
  double tau = last % 2 == 0 ? 2 * (pi - std::acos(d)) : tau1;
  int k = last % 2 == 0 ? 2 : 3;
  double cw = last % 2 == 0 ? 2 * c : c * c * pi / 2;  // c W_1 or c² W_2
  for (; k <= last; k += 2) {
    tau = ((k - 1) * tau + d * cw) / (k + 1);
    cw *= c * c * double(k) / (k + 1);  // W_{j+2} = W_j (j + 1)/(j + 2) with j = k − 1
  }
  // c^n W_n.
  double top = n % 2 == 0 ? pi : 2.0;
  for (int j = n % 2 == 0 ? 2 : 3; j <= n; j += 2) top *= double(j - 1) / j;
  top *= std::pow(c, n);
  return (n * d * tau + top) / (n + 2);
}

double max_glossy_coefficient(int n) { return (n + 2) / (2 * pi); }

double phong_luminaire_irradiance(const SphericalRegion& luminaire, const Vec3& luminaire_axis, int n,
                                  const Vec3& receiver_normal, double peak_radiance) {
  return peak_radiance * positive_lobe_moment(luminaire, -1.0 * luminaire_axis, receiver_normal, n);
}

double glossy_reflected_radiance(const SphericalRegion& luminaire, const Vec3& normal, const Vec3& to_viewer, int n,
                                 double coefficient, double radiance) {
  check_coefficient(coefficient, n);
  const Vec3 mirror = 2 * dot(normal, to_viewer) * normal - to_viewer;
  return radiance * coefficient * positive_lobe_moment(luminaire, mirror, normal, n);
}

double glossy_transmitted_radiance(const SphericalRegion& luminaire, const Vec3& normal, const Vec3& to_viewer, int n,
                                   double coefficient, double radiance) {
  check_coefficient(coefficient, n);
  return radiance * coefficient * positive_lobe_moment(luminaire, -1.0 * to_viewer, -1.0 * normal, n);
}

}  // namespace daylit
