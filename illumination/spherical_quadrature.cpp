#include "illumination/spherical_quadrature.hpp"

#include <array>
#include <cmath>

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

// ∫ over the spherical triangle (signed by the orientation of a, b, c).
double rule(const Triangle& t, const std::function<double(const Vec3&)>& g, long& evaluations) {
  const Vec3 e1 = t.b - t.a, e2 = t.c - t.a;
  const double det = dot(t.a, cross(e1, e2));  // signed: 2 × the planar area × distance term
  double sum = 0;
  auto at = [&](double l0, double l1, double l2) {
    const Vec3 p = l0 * t.a + l1 * t.b + l2 * t.c;
    // √(p·p), not norm()'s hypot: p is a combination of the region's directions, far from
    // overflow, and hypot's care was a tenth of an annual run's time.
    const double r = std::sqrt(dot(p, p));
    ++evaluations;
    return g(p / r) / (r * r * r);
  };
  for (const Orbit& o : kRule) {
    double s = 0;
    if (o.kind == 1) {
      s = at(o.a, o.b, o.c);
    } else if (o.kind == 3) {
      s = at(o.a, o.b, o.b) + at(o.b, o.a, o.b) + at(o.b, o.b, o.a);
    } else {
      s = at(o.a, o.b, o.c) + at(o.a, o.c, o.b) + at(o.b, o.a, o.c) + at(o.b, o.c, o.a) + at(o.c, o.a, o.b) +
          at(o.c, o.b, o.a);
    }
    sum += o.weight * s;
  }
  return 0.5 * det * sum;  // the reference triangle has area ½
}

struct Adaptive {
  const std::function<double(const Vec3&)>& g;
  double tolerance;
  double scale = 0;
  double error = 0;
  long evaluations = 0;

  double integrate(const Triangle& t, double coarse, int depth) {
    const Vec3 ab = 0.5 * (t.a + t.b), bc = 0.5 * (t.b + t.c), ca = 0.5 * (t.c + t.a);
    const std::array<Triangle, 4> children{{{t.a, ab, ca}, {ab, t.b, bc}, {ca, bc, t.c}, {ab, bc, ca}}};
    std::array<double, 4> parts;
    double fine = 0;
    for (int i = 0; i < 4; ++i) fine += parts[i] = rule(children[i], g, evaluations);
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

QuadratureResult integrate_over_region(const SphericalRegion& region, const std::function<double(const Vec3&)>& g,
                                       double tolerance) {
  Adaptive adaptive{g, tolerance};
  // A first pass fixes the scale against which every triangle's agreement is judged.
  std::vector<std::pair<Triangle, double>> fan;
  for (const DirectionLoop& loop : region.loops)
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
      const Triangle t{loop[0], loop[i], loop[i + 1]};
      fan.emplace_back(t, rule(t, g, adaptive.evaluations));
    }
  for (const auto& [t, coarse] : fan) adaptive.scale += std::abs(coarse);
  double value = 0;
  for (const auto& [t, coarse] : fan) value += adaptive.integrate(t, coarse, 0);
  return {value, adaptive.error, adaptive.evaluations};
}

}  // namespace daylit
