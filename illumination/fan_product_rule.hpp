#pragma once
// A fixed product Gauss rule over a region bounded by great arcs: the nodes and weights with which
// Σ w_i g(u_i) approximates ∫_A g(u) dσ for a smooth g.
//
// Each loop is split into the fan of spherical triangles from its first vertex (signed, so that
// non-convex loops and holes add up, as in spherical_quadrature.hpp). A triangle ABC is the central
// projection of the planar triangle A + α(B − A) + β(C − A), dσ = det[A, B − A, C − A] / |p|³ dα dβ,
// and is integrated by the n × n Gauss–Legendre product collapsed onto the triangle at A (Duffy's
// map: α = x(1 − y), β = x y, dα dβ = x dx dy). The Jacobian 1/|p|³ is what limits such a rule: a
// triangle whose sides span angles near π has a chord plane that passes close to the centre, where
// 1/|p|³ grows without bound, and a fixed rule converges slowly there however smooth g is (measured,
// annual moments of a sensor 0.25 m from the room sample's 2 × 1.5 m window, fan triangles of about
// 150°: orders 20 and 28 differed by 26 % of the Lambert weight; split to sides of 0.7 rad, by
// 8e-15). So each triangle is first split at its arcs' midpoints
// (four spherical triangles that tile it exactly) until no side exceeds `max_side`: with sides of
// angle s, |p| ≥ cos(s/√3) over the planar triangle, and the Jacobian varies by less than a factor
// cos(s/√3)^−3 (1.7 for s = 1 rad). Used by the annual moments and circumsolar rules
// (annual_coefficients.hpp, annual.hpp) and the reflection operator's hat functions
// (annual_reflections.hpp), each with its own `max_side`.

#include <cmath>
#include <cstddef>

#include "geometry/spherical_region.hpp"
#include "illumination/gauss_legendre.hpp"

namespace daylit {

// Calls visit(u, w) for the nodes of the collapsed n × n rule on the one spherical triangle abc
// (collapsed at a; unit vertices; w signed by the orientation of a, b, c).
template <class Visit>
void for_each_triangle_node(const Vec3& a, const Vec3& b, const Vec3& c, const quadrature::UnitGaussRule& rule,
                            Visit&& visit) {
  const Vec3 ab = b - a, ac = c - a;
  const double det = dot(a, cross(ab, ac));
  if (det == 0) return;
  for (std::size_t p = 0; p < rule.x.size(); ++p) {
    const double x = rule.x[p];
    for (std::size_t q = 0; q < rule.x.size(); ++q) {
      const double y = rule.x[q];
      const Vec3 point = a + (x * (1 - y)) * ab + (x * y) * ac;
      const double r = std::sqrt(dot(point, point));  // not hypot: |point| ≤ 1, and this is the hot loop
      visit((1 / r) * point, rule.w[p] * rule.w[q] * x * det / (r * r * r));
    }
  }
}

namespace fan_product_rule_detail {

template <class Visit>
void split(const Vec3& a, const Vec3& b, const Vec3& c, double max_side, int depth, Visit& visit) {
  if (depth < 8 && std::max({angle_between(a, b), angle_between(b, c), angle_between(c, a)}) > max_side) {
    // The midpoints of the three arcs: the children tile the spherical triangle exactly, and the
    // first keeps a as its first vertex.
    const Vec3 ab = normalized(a + b), bc = normalized(b + c), ca = normalized(c + a);
    split(a, ab, ca, max_side, depth + 1, visit);
    split(ab, b, bc, max_side, depth + 1, visit);
    split(ca, bc, c, max_side, depth + 1, visit);
    split(ab, bc, ca, max_side, depth + 1, visit);
    return;
  }
  visit(a, b, c);
}

}  // namespace fan_product_rule_detail

// Calls visit(a, b, c) for every triangle of the region's fan (unit vertices, the loop's
// orientation kept), split as above until no side exceeds `max_side`.
template <class Visit>
void for_each_fan_triangle(const SphericalRegion& region, double max_side, Visit&& visit) {
  for (const DirectionLoop& loop : region.loops) {
    if (loop.size() < 3) continue;
    const Vec3 a = normalized(loop[0]);
    for (std::size_t i = 1; i + 1 < loop.size(); ++i)
      fan_product_rule_detail::split(a, normalized(loop[i]), normalized(loop[i + 1]), max_side, 0, visit);
  }
}

// Calls visit(u, w) for every node (u unit, w its signed share of dσ) of the rule above.
template <class Visit>
void for_each_fan_node(const SphericalRegion& region, const quadrature::UnitGaussRule& rule, double max_side,
                       Visit&& visit) {
  for_each_fan_triangle(region, max_side,
                        [&](const Vec3& a, const Vec3& b, const Vec3& c) { for_each_triangle_node(a, b, c, rule, visit); });
}

}  // namespace daylit
