#include "simulation/element_transport.hpp"

#include <cmath>
#include <numbers>

#include "illumination/hemisphere_clip.hpp"
#include "illumination/moments.hpp"
#include "illumination/orthonormal_basis.hpp"
#include "illumination/rational_moments.hpp"

namespace daylit {

namespace {

constexpr double kTransportTolerance = 1e-9;

bool crosses_plane(const SphericalRegion& region, const Vec3& n) {
  for (const auto& loop : region.loops)
    for (const Vec3& u : loop)
      if (dot(u, n) < 0) return true;
  return false;
}

}  // namespace

SphericalRegion element_region(const SphericalRegion& surface_region, bool unobstructed,
                               const RadiosityElement& element, const Vec3& x, const Vec3& n) {
  if (unobstructed) {
    SphericalRegion own = directions_through({element.vertices.begin(), element.vertices.end()}, x);
    if (own.empty()) return own;
    return crosses_plane(own, n) ? clip_to_hemisphere(own, n) : own;
  }
  // The element's cone: the planes through x and its edges, oriented so that the cone is on
  // their positive side (a·(b×c) > 0 for the directions a, b, c of a positively turned triangle).
  Vec3 a = element.vertices[0] - x, b = element.vertices[1] - x, c = element.vertices[2] - x;
  const double turn = dot(a, cross(b, c));
  if (turn == 0) return {};
  if (turn < 0) std::swap(b, c);
  SphericalRegion r = clip_to_hemisphere(surface_region, cross(a, b));
  if (!r.empty()) r = clip_to_hemisphere(r, cross(b, c));
  if (!r.empty()) r = clip_to_hemisphere(r, cross(c, a));
  return r;
}

std::array<double, 3> element_irradiance_coefficients(const SphericalRegion& part, const RadiosityElement& element,
                                                      const Vec3& x, const Vec3& n) {
  std::array<double, 3> c{0, 0, 0};
  if (part.empty()) return c;
  const double side = dot(element.normal, element.vertices[0] - x);
  if (side == 0) return c;
  const Vec3 w = side > 0 ? element.normal : -1.0 * element.normal;
  const double h = std::abs(side);
  Vec3 e1, e2;
  orthonormal_basis(w, e1, e2);
  const double l0 = lambert(part, n);
  if (l0 == 0) return c;
  // The moments need to be accurate against the element's irradiance, not against themselves
  // (they vanish where the region is symmetric about e_i). An error δ in either costs
  // h|∇φ_k|δ/π ≈ (h/size)δ in c_k, so δ ≤ tol·size/h with tol = 1e-9 of Lambert's term, and
  // never below 1e-13 absolute (a coefficient of a form factor ≤ 1: slivers the cone clips leave
  // along element edges have l0 ~ 1e-20, and their digits are nobody's). The representation of
  // the exitance on the elements costs 1e-6 and more (the error estimate says how much), so
  // digits beyond that are not worth the long double and __float128 passes (10 to 100 times the
  // double one).
  const double size = std::sqrt(element.area);
  const double tol = std::max(kTransportTolerance * std::abs(l0), 1e-13) * size / h;
  const auto t = linear_exitance_moments(part, w, e1, e2, n, tol);
  const double t1 = t[0].value, t2 = t[1].value;
  for (int k = 0; k < 3; ++k) {
    const Vec3 g = element.basis_gradient(k);
    c[k] = (element.basis(k, x) * l0 + h * (dot(g, e1) * t1 + dot(g, e2) * t2)) / std::numbers::pi;
  }
  return c;
}

std::array<double, 3> element_irradiance_coefficients(const SphericalRegion& surface_region, bool unobstructed,
                                                      const RadiosityElement& element, const Vec3& x, const Vec3& n) {
  return element_irradiance_coefficients(element_region(surface_region, unobstructed, element, x, n), element, x, n);
}

}  // namespace daylit
