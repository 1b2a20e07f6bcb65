#pragma once
// Independent references for the tests: tensor-product Gauss–Legendre quadrature in long double
// over planar rectangles, integrating over area (not over the sphere), so that it shares no
// formula with the kernels under test; only the 1-D rule is the library's (tested on its own).

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "geometry/vec3.hpp"
#include "illumination/gauss_legendre.hpp"

namespace daylit::test {

struct LVec3 {
  long double x, y, z;
};

// Nodes and weights of the n-point Gauss–Legendre rule on [−1, 1]: the library's one rule
// (illumination/gauss_legendre.hpp), itself checked against closed forms and exact polynomial
// integrals in test_quadrature_rules.cpp.
inline void gauss_legendre(int n, std::vector<long double>& x, std::vector<long double>& w) {
  quadrature::GaussLegendreRule rule = quadrature::gauss_legendre(n);
  x = std::move(rule.x);
  w = std::move(rule.w);
}

// ∫ over the parallelogram origin + s·e1 + t·e2 (s, t ∈ [0, 1]) of f(x) dA, split into
// panels × panels sub-parallelograms with an order-point rule on each.
inline long double integrate_parallelogram(const LVec3& origin, const LVec3& e1, const LVec3& e2,
                                           const std::function<long double(const LVec3&)>& f, int panels = 8,
                                           int order = 24) {
  std::vector<long double> x, w;
  gauss_legendre(order, x, w);
  const LVec3 c{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  const long double area = std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
  long double sum = 0;
  for (int ps = 0; ps < panels; ++ps)
    for (int pt = 0; pt < panels; ++pt)
      for (int i = 0; i < order; ++i)
        for (int j = 0; j < order; ++j) {
          const long double s = (ps + 0.5L * (x[i] + 1)) / panels;
          const long double t = (pt + 0.5L * (x[j] + 1)) / panels;
          const LVec3 q{origin.x + s * e1.x + t * e2.x, origin.y + s * e1.y + t * e2.y, origin.z + s * e1.z + t * e2.z};
          sum += w[i] * w[j] * f(q);
        }
  return sum * area / (4.0L * panels * panels);
}

// Directional integral ∫ g(u) dσ(u) over the directions from p through the parallelogram: the
// surface integral of g(u) |m·(x − p)| / r³ with m the parallelogram's unit normal.
inline long double integrate_directions(const LVec3& p, const LVec3& origin, const LVec3& e1, const LVec3& e2,
                                        const std::function<long double(const LVec3&)>& g, int panels = 8,
                                        int order = 24) {
  LVec3 m{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  const long double ml = std::sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
  m = {m.x / ml, m.y / ml, m.z / ml};
  return integrate_parallelogram(
      origin, e1, e2,
      [&](const LVec3& x) {
        const LVec3 d{x.x - p.x, x.y - p.y, x.z - p.z};
        const long double r = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        const LVec3 u{d.x / r, d.y / r, d.z / r};
        return g(u) * std::abs(m.x * d.x + m.y * d.y + m.z * d.z) / (r * r * r);
      },
      panels, order);
}

// Breakpoints of [lo, hi] graded geometrically towards `focus` (clamped into the interval): the
// panels next to it are scale/16 long and each further one doubles, so a feature of width
// `scale` at the focus (a receiver that close to the plane, an edge that close to a horizon) is
// resolved like a smooth integrand.
inline std::vector<long double> graded_breakpoints(long double lo, long double hi, long double focus,
                                                   long double scale) {
  focus = std::min(std::max(focus, lo), hi);
  std::vector<long double> b{lo}, right;
  std::vector<long double> left;
  for (long double d = scale / 16; focus - d > lo; d *= 2) left.push_back(focus - d);
  for (long double d = scale / 16; focus + d < hi; d *= 2) right.push_back(focus + d);
  for (auto it = left.rbegin(); it != left.rend(); ++it) b.push_back(*it);
  if (focus > lo && focus < hi) b.push_back(focus);
  b.insert(b.end(), right.begin(), right.end());
  b.push_back(hi);
  return b;
}

// ∫ over the parallelogram origin + s·e1 + t·e2 (s, t ∈ [0, 1]) of f(x) dA on panels graded
// towards (focus_s, focus_t) with widths scale_s, scale_t (fractions of e1 and e2), `order`²
// Gauss–Legendre points per panel.
inline long double integrate_parallelogram_graded(const LVec3& origin, const LVec3& e1, const LVec3& e2,
                                                  const std::function<long double(const LVec3&)>& f,
                                                  long double focus_s, long double focus_t, long double scale_s,
                                                  long double scale_t, int order = 12) {
  std::vector<long double> x, w;
  gauss_legendre(order, x, w);
  const LVec3 c{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  const long double area = std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
  const auto bs = graded_breakpoints(0, 1, focus_s, scale_s), bt = graded_breakpoints(0, 1, focus_t, scale_t);
  long double sum = 0;
  for (std::size_t i = 0; i + 1 < bs.size(); ++i)
    for (std::size_t j = 0; j + 1 < bt.size(); ++j) {
      const long double ds = bs[i + 1] - bs[i], dt = bt[j + 1] - bt[j];
      for (int a = 0; a < order; ++a)
        for (int b = 0; b < order; ++b) {
          const long double s = bs[i] + ds * (x[a] + 1) / 2, t = bt[j] + dt * (x[b] + 1) / 2;
          const LVec3 q{origin.x + s * e1.x + t * e2.x, origin.y + s * e1.y + t * e2.y, origin.z + s * e1.z + t * e2.z};
          sum += w[a] * w[b] * ds * dt / 4 * f(q);
        }
    }
  return sum * area;
}

inline LVec3 lvec(const Vec3& v) { return {v.x, v.y, v.z}; }

}  // namespace daylit::test
