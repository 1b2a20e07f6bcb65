#include "illumination/spherical_quadrature.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace daylit {

namespace {

// Dunavant's degree-8 rule on the reference triangle (16 points): barycentric orbits and weights
// (weights sum to 1; multiply by the triangle's area).
struct Orbit {
  int kind;  // 1: centroid, 3: (a, b, b), 6: (a, b, c)
  double a, b, c, weight;
};
constexpr std::array<Orbit, 5> kRule{{
    {1, 1.0 / 3, 1.0 / 3, 1.0 / 3, 0.144315607677787},
    {3, 0.081414823414554, 0.459292588292723, 0, 0.095091634267285},
    {3, 0.658861384496480, 0.170569307751760, 0, 0.103217370534718},
    {3, 0.898905543365938, 0.050547228317031, 0, 0.032458497623198},
    {6, 0.008394777409958, 0.263112829634638, 0.728492392955404, 0.027230314174435},
}};

struct Triangle {
  Vec3 a, b, c;  // not necessarily unit
};

// The rule's 16 points on the reference triangle, in barycentric coordinates (one array per
// coordinate, so that the loop over the points vectorizes), with their weights.
struct RulePoints {
  std::array<double, 16> l0, l1, l2;
  std::array<double, 16> w;
};
RulePoints rule_points() {
  RulePoints r{};
  std::size_t k = 0;
  const auto add = [&](double l0, double l1, double l2, double w) {
    r.l0[k] = l0, r.l1[k] = l1, r.l2[k] = l2;
    r.w[k++] = w;
  };
  for (const Orbit& o : kRule) {
    if (o.kind == 1) {
      add(o.a, o.b, o.c, o.weight);
    } else if (o.kind == 3) {
      add(o.a, o.b, o.b, o.weight), add(o.b, o.a, o.b, o.weight), add(o.b, o.b, o.a, o.weight);
    } else {
      add(o.a, o.b, o.c, o.weight), add(o.a, o.c, o.b, o.weight), add(o.b, o.a, o.c, o.weight);
      add(o.b, o.c, o.a, o.weight), add(o.c, o.a, o.b, o.weight), add(o.c, o.b, o.a, o.weight);
    }
  }
  return r;
}
const RulePoints kPoints = rule_points();

// ∫ over each of `count` ≤ 4 spherical triangles (signed by the orientation of a, b, c): their
// 16 directions each found first and the integrand called once for all of them.
constexpr std::size_t kMaxBatch = 4;
void rules(const Triangle* t, std::size_t count, const DirectionBatch& g, long& evaluations, double* out) {
  std::array<double, 16 * kMaxBatch> x, y, z, inv_r3, values;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 &a = t[i].a, &b = t[i].b, &c = t[i].c;
    double* xi = x.data() + 16 * i;
    double* yi = y.data() + 16 * i;
    double* zi = z.data() + 16 * i;
    double* ri = inv_r3.data() + 16 * i;
    for (std::size_t k = 0; k < 16; ++k) {
      const double l0 = kPoints.l0[k], l1 = kPoints.l1[k], l2 = kPoints.l2[k];
      // The same sums as l0·a + l1·b + l2·c per coordinate.
      const double px = l0 * a.x + l1 * b.x + l2 * c.x, py = l0 * a.y + l1 * b.y + l2 * c.y,
                   pz = l0 * a.z + l1 * b.z + l2 * c.z;
      // √(p·p), not norm()'s hypot: p is a combination of the region's directions, far from
      // overflow, and hypot's care was a tenth of an annual run's time.
      const double inv = 1 / std::sqrt(px * px + py * py + pz * pz);
      xi[k] = px * inv, yi[k] = py * inv, zi[k] = pz * inv;
      ri[k] = inv * inv * inv;
    }
  }
  g(x.data(), y.data(), z.data(), 16 * count, values.data());
  evaluations += long(16 * count);
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 e1 = t[i].b - t[i].a, e2 = t[i].c - t[i].a;
    const double det = dot(t[i].a, cross(e1, e2));  // signed: 2 × the planar area × distance term
    double sum = 0;
    for (std::size_t k = 0; k < 16; ++k) sum += kPoints.w[k] * (values[16 * i + k] * inv_r3[16 * i + k]);
    out[i] = 0.5 * det * sum;  // the reference triangle has area ½
  }
}

struct Adaptive {
  const DirectionBatch& g;
  double tolerance;
  double scale = 0;
  double error = 0;
  long evaluations = 0;

  double integrate(const Triangle& t, double coarse, int depth) {
    const Vec3 ab = 0.5 * (t.a + t.b), bc = 0.5 * (t.b + t.c), ca = 0.5 * (t.c + t.a);
    const std::array<Triangle, 4> children{{{t.a, ab, ca}, {ab, t.b, bc}, {ca, bc, t.c}, {ab, bc, ca}}};
    std::array<double, 4> parts;
    rules(children.data(), 4, g, evaluations, parts.data());
    const double fine = parts[0] + parts[1] + parts[2] + parts[3];
    const double difference = std::abs(fine - coarse);
    scale = std::max(scale, std::abs(fine));
    if (difference <= tolerance * scale || depth >= 16) {
      error += difference;
      return fine;
    }
    double sum = 0;
    for (int i = 0; i < 4; ++i) sum += integrate(children[i], parts[i], depth + 1);
    return sum;
  }
};

}  // namespace

QuadratureResult integrate_over_region(const SphericalRegion& region, const DirectionBatch& g, double tolerance) {
  Adaptive adaptive{g, tolerance};
  // A first pass fixes the scale against which every triangle's agreement is judged.
  std::vector<Triangle> fan;
  for (const DirectionLoop& loop : region.loops)
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) fan.push_back({loop[0], loop[i], loop[i + 1]});
  std::vector<double> coarse(fan.size());
  for (std::size_t i = 0; i < fan.size(); i += kMaxBatch)
    rules(fan.data() + i, std::min(kMaxBatch, fan.size() - i), g, adaptive.evaluations, coarse.data() + i);
  for (double c : coarse) adaptive.scale += std::abs(c);
  double value = 0;
  for (std::size_t i = 0; i < fan.size(); ++i) value += adaptive.integrate(fan[i], coarse[i], 0);
  return {value, adaptive.error, adaptive.evaluations};
}

QuadratureResult integrate_over_region(const SphericalRegion& region, const std::function<double(const Vec3&)>& g,
                                       double tolerance) {
  return integrate_over_region(
      region,
      DirectionBatch([&g](const double* x, const double* y, const double* z, std::size_t n, double* values) {
        for (std::size_t i = 0; i < n; ++i) values[i] = g(Vec3{x[i], y[i], z[i]});
      }),
      tolerance);
}

}  // namespace daylit
