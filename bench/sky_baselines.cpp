#include "bench/sky_baselines.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/polygon.hpp"
#include "materials/glass_transmittance.hpp"
#include "illumination/orthonormal_basis.hpp"
#include "illumination/xoshiro256.hpp"

namespace daylit {

namespace {

constexpr double kPi = std::numbers::pi;

double component(const Vec3& v, int axis) noexcept { return v[axis]; }

Vec3 component_min(const Vec3& a, const Vec3& b) noexcept { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3 component_max(const Vec3& a, const Vec3& b) noexcept { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

// Slab test for the ray o + t·u, t > 0 (inverse direction given). A NaN from 0·∞ (origin on a
// slab plane, direction parallel to it: probability 0 for sampled rays) is ignored by min/max.
bool box_hit(const Vec3& lo, const Vec3& hi, const Vec3& o, const Vec3& inverse) noexcept {
  double t_min = 0, t_max = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const double t1 = (component(lo, axis) - component(o, axis)) * component(inverse, axis);
    const double t2 = (component(hi, axis) - component(o, axis)) * component(inverse, axis);
    t_min = std::max(t_min, std::min(t1, t2));
    t_max = std::min(t_max, std::max(t1, t2));
  }
  return t_min <= t_max;
}

// μ ∈ [0, 1] with (3μ² + 4μ³)/7 = ξ: the inverse of the cumulative distribution of the cosine of
// elevation under the density ∝ (1 + 2μ)μ. g(μ) = 4μ³ + 3μ² − 7ξ is increasing and convex on
// [0, 1], and g(√(7ξ/3)) = 4(7ξ/3)^{3/2} ≥ 0, so Newton's method from min(1, √(7ξ/3)) descends
// monotonically onto the root, quadratically after a step or two.
double overcast_elevation_cosine(double xi) noexcept {
  if (!(xi > 0)) return 0;
  double mu = std::min(1.0, std::sqrt(7 * xi / 3));
  for (int i = 0; i < 12; ++i) {
    const double step = ((4 * mu + 3) * mu * mu - 7 * xi) / ((12 * mu + 6) * mu);
    mu -= step;
    if (std::abs(step) <= 1e-16 * mu) break;
  }
  return mu;
}

}  // namespace

// ── RayScene ────────────────────────────────────────────────────────────────────────────────

RayScene::Face RayScene::make_face(const std::vector<Vec3>& vertices) {
  Face f{};
  f.normal = normalized(newell_normal(vertices));
  f.origin = vertices.front();
  const Vec3 a{std::abs(f.normal.x), std::abs(f.normal.y), std::abs(f.normal.z)};
  const int drop = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  f.axis_u = (drop + 1) % 3;
  f.axis_v = (drop + 2) % 3;
  f.first = std::uint32_t(points_.size() / 2);
  f.count = std::uint32_t(vertices.size());
  f.box_min = f.box_max = vertices.front();
  for (const Vec3& v : vertices) {
    const Vec3 d = v - f.origin;
    points_.push_back(component(d, f.axis_u));
    points_.push_back(component(d, f.axis_v));
    f.box_min = component_min(f.box_min, v);
    f.box_max = component_max(f.box_max, v);
  }
  return f;
}

RayScene::RayScene(const Scene& scene) {
  for (const Polygon& p : scene.occluders)
    if (norm(newell_normal(p.vertices)) > 0) occluders_.push_back(make_face(p.vertices));
  for (const Aperture& a : scene.apertures)
    if (norm(newell_normal(a.polygon.vertices)) > 0)
      apertures_.push_back({make_face(a.polygon.vertices), a.transmittance, a.angular_transmittance});
  order_.resize(occluders_.size());
  for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  std::vector<Vec3> centres;
  for (const Face& f : occluders_) centres.push_back(0.5 * (f.box_min + f.box_max));
  nodes_.reserve(2 * occluders_.size() + 1);
  nodes_.push_back({});
  if (!occluders_.empty()) {
    // Iterative build with an explicit work list, children allocated in pairs.
    struct Work {
      std::uint32_t node, first, count;
    };
    std::vector<Work> work{{0, 0, std::uint32_t(order_.size())}};
    while (!work.empty()) {
      const Work w = work.back();
      work.pop_back();
      Vec3 lo = occluders_[order_[w.first]].box_min, hi = occluders_[order_[w.first]].box_max;
      Vec3 clo = centres[order_[w.first]], chi = clo;
      for (std::uint32_t i = w.first; i < w.first + w.count; ++i) {
        lo = component_min(lo, occluders_[order_[i]].box_min);
        hi = component_max(hi, occluders_[order_[i]].box_max);
        clo = component_min(clo, centres[order_[i]]);
        chi = component_max(chi, centres[order_[i]]);
      }
      nodes_[w.node].box_min = lo;
      nodes_[w.node].box_max = hi;
      if (w.count <= 4) {
        nodes_[w.node].first = w.first;
        nodes_[w.node].count = w.count;
        continue;
      }
      const Vec3 extent = chi - clo;
      const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      const std::uint32_t half = w.count / 2;
      std::nth_element(order_.begin() + w.first, order_.begin() + w.first + half, order_.begin() + w.first + w.count,
                       [&](std::uint32_t a, std::uint32_t b) { return component(centres[a], axis) < component(centres[b], axis); });
      const auto child = std::uint32_t(nodes_.size());
      nodes_.push_back({});
      nodes_.push_back({});
      nodes_[w.node].first = child;
      nodes_[w.node].count = 0;
      work.push_back({child, w.first, half});
      work.push_back({child + 1, w.first + half, w.count - half});
    }
  }
}

bool RayScene::hits(const Face& f, const Vec3& o, const Vec3& u) const noexcept {
  const double along = dot(f.normal, u);
  if (along == 0) return false;
  const Vec3 d = o - f.origin;
  const double t = -dot(f.normal, d) / along;
  if (!(t > 0)) return false;
  const Vec3 q = d + t * u;
  const double x = component(q, f.axis_u), y = component(q, f.axis_v);
  // Crossing number (PNPOLY): count the edges that a ray from q along +u₂ crosses.
  bool inside = false;
  const double* p = &points_[2 * std::size_t(f.first)];
  for (std::uint32_t i = 0, j = f.count - 1; i < f.count; j = i++) {
    const double xi = p[2 * i], yi = p[2 * i + 1], xj = p[2 * j], yj = p[2 * j + 1];
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

bool RayScene::occluded(const Vec3& o, const Vec3& u) const noexcept {
  if (occluders_.empty()) return false;
  const Vec3 inverse{1 / u.x, 1 / u.y, 1 / u.z};
  std::uint32_t stack[96];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!box_hit(node.box_min, node.box_max, o, inverse)) continue;
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const Face& f = occluders_[order_[i]];
        if (box_hit(f.box_min, f.box_max, o, inverse) && hits(f, o, u)) return true;
      }
    } else if (top + 2 <= int(std::size(stack))) {  // always: median splits keep the depth ≤ log2(faces) + 1
      stack[top++] = node.first;
      stack[top++] = node.first + 1;
    }
  }
  return false;
}

double RayScene::transmittance(const Vec3& o, const Vec3& u) const noexcept {
  double total = 0;
  const Vec3 inverse{1 / u.x, 1 / u.y, 1 / u.z};
  for (const ApertureFace& a : apertures_) {
    if (!box_hit(a.face.box_min, a.face.box_max, o, inverse) || !hits(a.face, o, u)) continue;
    total += a.angular.empty() ? a.transmittance
                               : evaluate_polynomial(a.angular, std::abs(dot(a.face.normal, u)) / norm(u));
  }
  return total;
}

// ── Monte Carlo ─────────────────────────────────────────────────────────────────────────────

double sky_component_monte_carlo(const RayScene& rays, const Sensor& sensor, SkyModel sky, long samples,
                                 std::uint64_t seed) {
  samples = std::max(samples, 1L);
  long nx = std::max(1L, long(std::sqrt(double(samples))));
  while (samples % nx != 0) --nx;
  const long ny = samples / nx;
  const Vec3& n = sensor.normal;
  const Vec3& p = sensor.position;
  const bool overcast = sky == SkyModel::cie_overcast;
  const bool sky_weighted = overcast && n.x == 0 && n.y == 0 && n.z > 0;
  Vec3 e1, e2;
  orthonormal_basis(n, e1, e2);
  const double e_out = unobstructed_horizontal_irradiance(sky);
  Xoshiro256 rng(seed);
  double sum = 0;
  for (long i = 0; i < nx; ++i)
    for (long j = 0; j < ny; ++j) {
      const double xi1 = (double(i) + rng.uniform()) / double(nx), xi2 = (double(j) + rng.uniform()) / double(ny);
      const double phi = 2 * kPi * xi2;
      Vec3 u;
      double weight;
      if (sky_weighted) {
        const double mu = overcast_elevation_cosine(xi1), s = std::sqrt(std::max(0.0, (1 - mu) * (1 + mu)));
        u = {s * std::cos(phi), s * std::sin(phi), mu};
        weight = 1;  // L·cos/p = 7π/9 = E_out
      } else {
        const double r = std::sqrt(xi1);
        u = r * std::cos(phi) * e1 + r * std::sin(phi) * e2 + std::sqrt(1 - xi1) * n;
        if (!(u.z > 0)) continue;  // below the horizon: the ground, not the sky
        weight = kPi * (overcast ? (1 + 2 * u.z) / 3 : 1.0) / e_out;
      }
      const double t = rays.transmittance(p, u);
      if (t == 0 || rays.occluded(p, u)) continue;
      sum += weight * t;
    }
  return 100 * sum / double(samples);
}

// ── Adaptive cubature ───────────────────────────────────────────────────────────────────────

namespace {

// L(u)·T(u)·(n·u) for unit u.
struct SkyIntegrand {
  Vec3 n;
  bool overcast;
  double transmittance;
  const std::vector<double>* angular;  // null: constant
  Vec3 pane_normal;                    // unit

  double operator()(const Vec3& u) const noexcept {
    const double l = overcast ? (1 + 2 * u.z) / 3 : 1.0;
    const double t = angular ? evaluate_polynomial(*angular, std::abs(dot(pane_normal, u))) : transmittance;
    return l * t * dot(n, u);
  }
};

// Radon's 7-point rule of degree 5 on a triangle (Stroud 1971, T2:5-1), barycentric.
const double kSqrt15 = std::sqrt(15.0);
const double kA1 = (6 - kSqrt15) / 21, kA2 = (6 + kSqrt15) / 21;
const double kW0 = 9.0 / 40, kW1 = (155 - kSqrt15) / 1200, kW2 = (155 + kSqrt15) / 1200;

// ∫ f dσ over the central projection of the flat triangle abc (points, not necessarily unit),
// signed by orientation: ½·det[a, b, c]·Σ w_i f(x̂_i)/|x_i|³.
double triangle_rule(const Vec3& a, const Vec3& b, const Vec3& c, const SkyIntegrand& f) noexcept {
  const auto g = [&](const Vec3& x) {
    const double r = norm(x);
    return f(x / r) / (r * r * r);
  };
  const auto symmetric = [&](double alpha) {
    const double beta = 1 - 2 * alpha;
    return g(alpha * a + alpha * b + beta * c) + g(alpha * a + beta * b + alpha * c) + g(beta * a + alpha * b + alpha * c);
  };
  const double sum = kW0 * g((a + b + c) / 3) + kW1 * symmetric(kA1) + kW2 * symmetric(kA2);
  return 0.5 * dot(a, cross(b - a, c - a)) * sum;
}

struct Cell {
  std::array<Vec3, 3> v;
  std::array<double, 4> child_rule;
  double value;  // Σ child_rule
  double error;  // |value − rule on the cell|
  const SkyIntegrand* f;

  bool operator<(const Cell& o) const noexcept { return error < o.error; }
};

std::array<std::array<Vec3, 3>, 4> children(const std::array<Vec3, 3>& t) {
  const Vec3 ab = 0.5 * (t[0] + t[1]), bc = 0.5 * (t[1] + t[2]), ca = 0.5 * (t[2] + t[0]);
  return {{{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}}};
}

Cell make_cell(const std::array<Vec3, 3>& t, double own_rule, const SkyIntegrand* f, long& evaluations) {
  Cell c{t, {}, 0, 0, f};
  const auto kids = children(t);
  for (int i = 0; i < 4; ++i) {
    c.child_rule[std::size_t(i)] = triangle_rule(kids[std::size_t(i)][0], kids[std::size_t(i)][1], kids[std::size_t(i)][2], *f);
    c.value += c.child_rule[std::size_t(i)];
  }
  evaluations += 28;
  c.error = std::abs(c.value - own_rule);
  return c;
}

}  // namespace

CubatureResult sky_component_cubature(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor,
                                      SkyModel sky, double relative_tolerance, VisibilityCounters& counters) {
  constexpr long kMaxEvaluations = 4'000'000;
  std::vector<SkyIntegrand> integrands;
  integrands.reserve(engine.aperture_count());
  std::vector<std::pair<SphericalRegion, std::size_t>> regions;
  for (std::size_t a = 0; a < engine.aperture_count(); ++a) {
    SphericalRegion region = engine.visible_region(sensor.position, sensor.normal, a, counters);
    if (region.empty()) continue;
    const Aperture& ap = scene.apertures[a];
    integrands.push_back({sensor.normal, sky == SkyModel::cie_overcast, ap.transmittance,
                          ap.angular_transmittance.empty() ? nullptr : &ap.angular_transmittance,
                          normalized(newell_normal(ap.polygon.vertices))});
    regions.emplace_back(std::move(region), integrands.size() - 1);
  }
  long evaluations = 0;
  std::vector<Cell> cells;  // a max-heap on the error estimate
  for (const auto& [region, index] : regions)
    for (const DirectionLoop& loop : region.loops) {
      if (loop.size() < 3) continue;
      const Vec3 apex = normalized(loop[0]);
      for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
        const std::array<Vec3, 3> t{apex, normalized(loop[i]), normalized(loop[i + 1])};
        const double own = triangle_rule(t[0], t[1], t[2], integrands[index]);
        evaluations += 7;
        cells.push_back(make_cell(t, own, &integrands[index], evaluations));
      }
    }
  std::make_heap(cells.begin(), cells.end());
  // Running sums decide when to stop; they are re-summed from the cells before a decision to
  // stop is taken, so that no drift of the running sums ends the refinement early.
  const auto resum = [&](double& value, double& error) {
    value = error = 0;
    for (const Cell& c : cells) value += c.value, error += c.error;
  };
  double value, error;
  resum(value, error);
  while (!cells.empty() && evaluations < kMaxEvaluations) {
    if (error <= relative_tolerance * std::abs(value)) {
      resum(value, error);
      if (error <= relative_tolerance * std::abs(value)) break;
    }
    std::pop_heap(cells.begin(), cells.end());
    const Cell worst = cells.back();
    cells.pop_back();
    value -= worst.value;
    error -= worst.error;
    const auto kids = children(worst.v);
    for (std::size_t i = 0; i < 4; ++i) {
      cells.push_back(make_cell(kids[i], worst.child_rule[i], worst.f, evaluations));
      value += cells.back().value;
      error += cells.back().error;
      std::push_heap(cells.begin(), cells.end());
    }
  }
  resum(value, error);
  return {100 * value / unobstructed_horizontal_irradiance(sky), evaluations};
}

}  // namespace daylit
