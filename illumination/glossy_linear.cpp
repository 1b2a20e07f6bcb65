#include "illumination/glossy_linear.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "geometry/error.hpp"
#include "illumination/glossy.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "illumination/rational_moments.hpp"

namespace daylit {

namespace {

void check_coefficient(double coefficient, int n) {
  if (n < 0) throw Error("the Phong exponent must be ≥ 0");
  if (!(coefficient >= 0) || coefficient > max_glossy_coefficient(n) * (1 + 1e-15))
    throw Error("glossy coefficient " + std::to_string(coefficient) + " exceeds the energy bound (n + 2)/(2π) = " +
                std::to_string(max_glossy_coefficient(n)) + " for n = " + std::to_string(n));
}

// (c/π) τ^{n,1,1;1}(A ∩ {lobe·u ≥ 0} ∩ {cosine·u ≥ 0}, lobe, cosine, a; w) for the luminaire.
double lobe_radiance(const SphericalRegion& luminaire, const Vec3& origin, const Vec3& lobe, const Vec3& cosine, int n,
                     double coefficient, const Vec3& plane_point, const Vec3& plane_normal, const LinearExitance& M) {
  if (!is_finite(origin) || !is_finite(plane_point) || !is_finite(plane_normal) || !is_finite(M.gradient) ||
      !std::isfinite(M.constant) || !(norm(plane_normal) > 0))
    throw Error("linear luminaire: the origin, plane and exitance must be finite and the plane normal non-zero");
  const Vec3 N = normalized(plane_normal);
  const double side = dot(N, plane_point - origin);
  if (side == 0) return 0;  // the point lies in the luminaire's plane: it sees the luminaire edge-on
  const Vec3 w = side > 0 ? N : -1.0 * N;
  const double h = std::abs(side);
  const SphericalRegion cut = clip_to_hemisphere(clip_to_hemisphere(luminaire, cosine), lobe);
  if (cut.empty()) return 0;
  // Eq. 2: M(o + h u/(w·u)) = (a·u)/(w·u), a = M(o) w + h g.
  const Vec3 a = (M.constant + dot(M.gradient, origin)) * w + h * M.gradient;
  const Vec3 t = linear_luminaire_glossy_tensor(cut, lobe, n, cosine, w);
  return coefficient / std::numbers::pi * dot(a, t);
}

}  // namespace

Vec3 linear_luminaire_glossy_tensor(const SphericalRegion& region, const Vec3& v, int n, const Vec3& b, const Vec3& w) {
  if (region.empty()) return {};
  double t[3];
  for (int i = 0; i < 3; ++i) {
    const Vec3 e{double(i == 0), double(i == 1), double(i == 2)};
    const RationalMoment m = rational_moment_n11(region, v, n, b, e, w);
    t[i] = m.value;
  }
  return {t[0], t[1], t[2]};
}

double glossy_reflected_radiance_linear(const SphericalRegion& luminaire, const Vec3& origin, const Vec3& normal,
                                        const Vec3& to_viewer, int n, double coefficient, const Vec3& plane_point,
                                        const Vec3& plane_normal, const LinearExitance& exitance) {
  check_coefficient(coefficient, n);
  const Vec3 mirror = 2 * dot(normal, to_viewer) * normal - to_viewer;
  return lobe_radiance(luminaire, origin, mirror, normal, n, coefficient, plane_point, plane_normal, exitance);
}

double glossy_transmitted_radiance_linear(const SphericalRegion& luminaire, const Vec3& origin, const Vec3& normal,
                                          const Vec3& to_viewer, int n, double coefficient, const Vec3& plane_point,
                                          const Vec3& plane_normal, const LinearExitance& exitance) {
  check_coefficient(coefficient, n);
  return lobe_radiance(luminaire, origin, -1.0 * to_viewer, -1.0 * normal, n, coefficient, plane_point, plane_normal,
                       exitance);
}

}  // namespace daylit
