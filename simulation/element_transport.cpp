#include "simulation/element_transport.hpp"

#include <algorithm>
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

// c_k of an element from its Lambert term l0 and the pair t1, t2 (the header's formula).
std::array<double, 3> coefficients_from(const RadiosityElement& element, const Vec3& x, double h, const Vec3& e1,
                                        const Vec3& e2, double l0, double t1, double t2) {
  std::array<double, 3> c{};
  for (int k = 0; k < 3; ++k) {
    const Vec3 g = element.basis_gradient(k);
    c[std::size_t(k)] = (element.basis(k, x) * l0 + h * (dot(g, e1) * t1 + dot(g, e2) * t2)) / std::numbers::pi;
  }
  return c;
}

// The accuracy the moments need against the element's irradiance (element_irradiance_coefficients).
double moment_tolerance(const RadiosityElement& element, double l0, double h) {
  return std::max(kTransportTolerance * std::abs(l0), 1e-13) * std::sqrt(element.area) / h;
}

// How much of Lambert's term l0 reaches the coefficients: c_k = (φ_k(x) l0 + …)/π, so an error δ
// in l0 costs |φ_k(x)|δ/π in c_k, and φ_k, linear, grows beyond the element as the distance over
// its size. Lambert's term is held to what the moments are held to (moment_tolerance: the error
// of c_k at most 1e-9 of l0, never below 1e-13), relative and absolute. Asked for 1e-13 relative
// instead, the Stokes sum of a small or grazing element (κ ≈ 3·distance/(size·cos), its edges'
// terms first order in the size and the result second order) went on to long double in 3.5 of
// 5.7 million calls on the office sample.
struct LambertTarget {
  double relative, absolute;
};
LambertTarget lambert_target(const RadiosityElement& element, const Vec3& x) {
  double reach = 1;
  for (int k = 0; k < 3; ++k) reach = std::max(reach, std::abs(element.basis(k, x)));
  return {kTransportTolerance * std::numbers::pi / reach, 1e-13 * std::numbers::pi / reach};
}

}  // namespace

void element_region(const SphericalRegion& surface_region, bool unobstructed, const RadiosityElement& element,
                    const Vec3& x, const Vec3& n, SphericalRegion& out) {
  if (unobstructed) {
    SphericalRegion own = directions_through({element.vertices.begin(), element.vertices.end()}, x);
    if (!own.empty() && crosses_plane(own, n))
      clip_to_hemisphere(own, n, out);
    else
      out = std::move(own);
    return;
  }
  // The element's cone: the planes through x and its edges, oriented so that the cone is on
  // their positive side (a·(b×c) > 0 for the directions a, b, c of a positively turned triangle).
  Vec3 a = element.vertices[0] - x, b = element.vertices[1] - x, c = element.vertices[2] - x;
  const double turn = dot(a, cross(b, c));
  out.loops.clear();
  out.edge_sources.clear();
  if (turn == 0) return;
  if (turn < 0) std::swap(b, c);
  thread_local SphericalRegion first, second;
  clip_to_hemisphere(surface_region, cross(a, b), first);
  if (first.empty()) return;
  clip_to_hemisphere(first, cross(b, c), second);
  if (second.empty()) return;
  clip_to_hemisphere(second, cross(c, a), out);
}

SphericalRegion element_region(const SphericalRegion& surface_region, bool unobstructed,
                               const RadiosityElement& element, const Vec3& x, const Vec3& n) {
  SphericalRegion out;
  element_region(surface_region, unobstructed, element, x, n, out);
  return out;
}

std::array<double, 3> element_irradiance_coefficients(const SphericalRegion& part, const RadiosityElement& element,
                                                      const Vec3& x, const Vec3& n) {
  std::array<double, 3> c{0, 0, 0};
  if (part.empty() || element.sliver) return c;
  const double side = dot(element.normal, element.vertices[0] - x);
  const Vec3 w = side > 0 ? element.normal : -1.0 * element.normal;
  const double h = std::abs(side);
  // A receiver within 1e-12 of the element's size from its plane (a node of a coplanar surface,
  // off the plane by roundoff) sees it at grazing incidence: the coefficients are O(h/size) of
  // the element's exitance, below 1e-12, and the region's directions may touch w·u = 0, where
  // the rational moments diverge. Left out, as 0.
  if (h <= 1e-12 * std::sqrt(element.area)) return c;
  Vec3 e1, e2;
  orthonormal_basis(w, e1, e2);
  const LambertTarget target = lambert_target(element, x);
  const double l0 = lambert_with_accuracy(part, n, target.relative, target.absolute).value;
  if (l0 == 0) return c;
  // The moments need to be accurate against the element's irradiance, not against themselves
  // (they vanish where the region is symmetric about e_i). An error δ in either costs
  // h|∇φ_k|δ/π ≈ (h/size)δ in c_k, so δ ≤ tol·size/h with tol = 1e-9 of Lambert's term, and
  // never below 1e-13 absolute (a coefficient of a form factor ≤ 1: slivers the cone clips leave
  // along element edges have l0 ~ 1e-20, and their digits are nobody's). The representation of
  // the exitance on the elements costs 1e-6 and more (the error estimate says how much), so
  // digits beyond that are not worth the long double and __float128 passes (10 to 100 times the
  // double one).
  const auto t = linear_exitance_moments(part, w, e1, e2, n, moment_tolerance(element, l0, h));
  return coefficients_from(element, x, h, e1, e2, l0, t[0].value, t[1].value);
}

void unobstructed_surface_coefficients(const RadiosityMesh& mesh, std::size_t surface, const Vec3& x, const Vec3& n,
                                       std::vector<std::array<double, 3>>& out) {
  const RadiositySurface& surf = mesh.surfaces[surface];
  out.assign(surf.elements.size(), {0.0, 0.0, 0.0});
  if (surf.elements.empty()) return;
  // The side of the surface's plane that x is on fixes w and the basis for every element.
  const double facing = dot(surf.normal, surf.point - x);
  if (facing == 0) return;
  const Vec3 w = facing > 0 ? surf.normal : -1.0 * surf.normal;
  Vec3 e1, e2;
  orthonormal_basis(w, e1, e2);
  // The edges' terms, computed on first use.
  thread_local std::vector<std::array<real::Tracked<double>, 3>> terms;
  thread_local std::vector<char> known;
  const std::size_t edges = surf.edge_end - surf.edge_begin;
  terms.resize(edges);
  known.assign(edges, 0);
  constexpr double u = 0x1p-53;
  for (std::size_t i = 0; i < surf.elements.size(); ++i) {
    const std::size_t e = surf.elements[i];
    const RadiosityElement& el = mesh.elements[e];
    const double side = dot(el.normal, el.vertices[0] - x);
    bool separate = side == 0 || (side > 0) != (facing > 0) || el.sliver;
    for (const Vec3& v : el.vertices) separate = separate || dot(n, v - x) < 0;
    std::array<real::Tracked<double>, 3> sum{};
    if (!separate) {
      // directions_through runs the loop the vertices' way where side = normal·(v0 − x) > 0 and
      // the other way where side < 0: each edge's canonical terms, signed.
      for (int k = 0; k < 3; ++k) {
        const ElementEdge& ee = mesh.element_edges[e][std::size_t(k)];
        const std::size_t local = ee.id - surf.edge_begin;
        if (!known[local]) {
          const MeshEdge& me = mesh.edges[ee.id];
          terms[local] = linear_element_edge_terms(me.from - x, me.to - x, w, e1, e2, n);
          known[local] = 1;
        }
        const bool negate = ee.reversed != (side < 0);
        for (int j = 0; j < 3; ++j) {
          const real::Tracked<double>& t = terms[local][std::size_t(j)];
          sum[std::size_t(j)].add(negate ? -t.value : t.value, t.magnitude);
        }
      }
      // escalate_tracked's tests in double: (10 + order)·u·magnitude against the relative target
      // or the absolute one (lambert_target, moment_tolerance).
      const double l0 = sum[0].value, h = std::abs(side);
      const double tol = moment_tolerance(el, l0, h);
      const LambertTarget target = lambert_target(el, x);
      const double l0_err = 11 * u * sum[0].magnitude;
      const bool l0_ok = l0_err <= target.relative * std::abs(l0) || l0_err <= target.absolute;
      const auto pair_ok = [&](const real::Tracked<double>& t) {
        const double err = 12 * u * t.magnitude;
        return err <= 1e-13 * std::abs(t.value) || err <= tol;
      };
      separate = l0 == 0 || !l0_ok || !pair_ok(sum[1]) || !pair_ok(sum[2]);
      if (!separate) out[i] = coefficients_from(el, x, h, e1, e2, l0, sum[1].value, sum[2].value);
    }
    if (separate) out[i] = element_irradiance_coefficients(SphericalRegion{}, true, el, x, n);
  }
}

std::array<double, 3> element_irradiance_coefficients(const SphericalRegion& surface_region, bool unobstructed,
                                                      const RadiosityElement& element, const Vec3& x, const Vec3& n) {
  thread_local SphericalRegion part;
  element_region(surface_region, unobstructed, element, x, n, part);
  return element_irradiance_coefficients(part, element, x, n);
}

}  // namespace daylit
