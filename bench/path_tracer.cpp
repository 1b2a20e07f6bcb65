#include "bench/path_tracer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/convex_pieces.hpp"
#include "geometry/error.hpp"
#include "illumination/orthonormal_basis.hpp"
#include "illumination/xoshiro256.hpp"
#include "materials/glass_transmittance.hpp"
#include "materials/surface_reflectance.hpp"
#include "simulation/illuminance.hpp"
#include "simulation/sensor_loop.hpp"

namespace daylit {

namespace {

constexpr double kPi = std::numbers::pi;
// The offset of a ray leaving a surface, relative to the scene's bounding-box diagonal (see the
// header: what it costs).
constexpr double kRelativeOffset = 1e-9;
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
// The cosine of the sun's angular radius, the disk daylit's illuminance cuts (0.533° across).
const double kCosSunRadius = std::cos(kSunHalfAngleDeg * kPi / 180);

Vec3 component_min(const Vec3& a, const Vec3& b) noexcept { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3 component_max(const Vec3& a, const Vec3& b) noexcept { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

// ── Ray casting: triangles and a BVH over them ──────────────────────────────────────────────

struct Triangle {
  Vec3 v0, e1, e2;          // v0, v1 − v0, v2 − v0
  std::uint32_t object;     // occluders 0 … n_o − 1, then apertures n_o … n_o + n_a − 1
};

struct Node {
  Vec3 lo, hi;
  std::uint32_t first, count;  // leaf: triangles [first, first + count); inner: count = 0, children first, first + 1
};

struct Hit {
  double t = std::numeric_limits<double>::infinity();
  std::uint32_t object = kNone;
};

// Slab test of o + t·d, t ∈ (t_min, t_max), against a box (inverse direction given). NaN from
// 0·∞ (origin on a slab plane, direction parallel to it) is dropped by min/max.
bool box_hit(const Vec3& lo, const Vec3& hi, const Vec3& o, const Vec3& inverse, double t_min, double t_max) noexcept {
  for (int axis = 0; axis < 3; ++axis) {
    const double t1 = (lo[axis] - o[axis]) * inverse[axis], t2 = (hi[axis] - o[axis]) * inverse[axis];
    t_min = std::max(t_min, std::min(t1, t2));
    t_max = std::min(t_max, std::max(t1, t2));
  }
  return t_min <= t_max;
}

// Möller and Trumbore, "Fast, minimum storage ray/triangle intersection", JGT 2(1), 1997: the
// parameter t of o + t·d on the triangle, or +∞. No tolerance on the barycentric tests: a ray
// through a shared edge meets both triangles or, by rounding, one of them; missing both needs
// rounding of both tests the same way, which for sampled rays we have not seen happen.
double intersect(const Triangle& tri, const Vec3& o, const Vec3& d) noexcept {
  const Vec3 p = cross(d, tri.e2);
  const double det = dot(tri.e1, p);
  if (det == 0) return std::numeric_limits<double>::infinity();
  const double inv = 1 / det;
  const Vec3 s = o - tri.v0;
  const double u = dot(s, p) * inv;
  if (u < 0 || u > 1) return std::numeric_limits<double>::infinity();
  const Vec3 q = cross(s, tri.e1);
  const double v = dot(d, q) * inv;
  if (v < 0 || u + v > 1) return std::numeric_limits<double>::infinity();
  return dot(tri.e2, q) * inv;
}

class TriangleBvh {
 public:
  explicit TriangleBvh(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {
    if (triangles_.empty()) return;
    std::vector<Vec3> lo(triangles_.size()), hi(triangles_.size()), centre(triangles_.size());
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      const Triangle& t = triangles_[i];
      lo[i] = component_min(component_min(t.v0, t.v0 + t.e1), t.v0 + t.e2);
      hi[i] = component_max(component_max(t.v0, t.v0 + t.e1), t.v0 + t.e2);
      centre[i] = 0.5 * (lo[i] + hi[i]);
    }
    std::vector<std::uint32_t> order(triangles_.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    // Median split on the longest axis of the centres, ≤ 4 triangles a leaf; children in pairs.
    struct Work {
      std::uint32_t node, first, count;
    };
    nodes_.push_back({});
    std::vector<Work> work{{0, 0, std::uint32_t(order.size())}};
    while (!work.empty()) {
      const Work w = work.back();
      work.pop_back();
      Vec3 blo = lo[order[w.first]], bhi = hi[order[w.first]], clo = centre[order[w.first]], chi = clo;
      for (std::uint32_t i = w.first; i < w.first + w.count; ++i) {
        blo = component_min(blo, lo[order[i]]);
        bhi = component_max(bhi, hi[order[i]]);
        clo = component_min(clo, centre[order[i]]);
        chi = component_max(chi, centre[order[i]]);
      }
      nodes_[w.node].lo = blo;
      nodes_[w.node].hi = bhi;
      if (w.count <= 4) {
        nodes_[w.node].first = w.first;
        nodes_[w.node].count = w.count;
        continue;
      }
      const Vec3 extent = chi - clo;
      const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      const std::uint32_t half = w.count / 2;
      std::nth_element(order.begin() + w.first, order.begin() + w.first + half, order.begin() + w.first + w.count,
                       [&](std::uint32_t a, std::uint32_t b) { return centre[a][axis] < centre[b][axis]; });
      const auto child = std::uint32_t(nodes_.size());
      nodes_.push_back({});
      nodes_.push_back({});
      nodes_[w.node].first = child;
      nodes_[w.node].count = 0;
      work.push_back({child, w.first, half});
      work.push_back({child + 1, w.first + half, w.count - half});
    }
    std::vector<Triangle> sorted;
    sorted.reserve(order.size());
    for (std::uint32_t i : order) sorted.push_back(triangles_[i]);
    triangles_ = std::move(sorted);
  }

  // The nearest triangle along o + t·d with t > t_min, skipping the objects `skip_a` and `skip_b`.
  Hit nearest(const Vec3& o, const Vec3& d, double t_min, std::uint32_t skip_a, std::uint32_t skip_b) const noexcept {
    Hit hit;
    if (triangles_.empty()) return hit;
    const Vec3 inverse{1 / d.x, 1 / d.y, 1 / d.z};
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!box_hit(node.lo, node.hi, o, inverse, t_min, hit.t)) continue;
      if (node.count > 0) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
          const Triangle& tri = triangles_[i];
          if (tri.object == skip_a || tri.object == skip_b) continue;
          const double t = intersect(tri, o, d);
          if (t > t_min && t < hit.t) hit = {t, tri.object};
        }
      } else if (top + 2 <= int(std::size(stack))) {  // always: median splits keep the depth ≤ log2(n) + 1
        // Nearer child on top of the stack, so that it is visited first and shrinks hit.t.
        const Node& a = nodes_[node.first];
        const Node& b = nodes_[node.first + 1];
        const double ca = dot(0.5 * (a.lo + a.hi) - o, d), cb = dot(0.5 * (b.lo + b.hi) - o, d);
        stack[top++] = ca < cb ? node.first + 1 : node.first;
        stack[top++] = ca < cb ? node.first : node.first + 1;
      }
    }
    return hit;
  }

 private:
  std::vector<Triangle> triangles_;
  std::vector<Node> nodes_;
};

// ── The scene as the tracer sees it ─────────────────────────────────────────────────────────

struct SurfaceInfo {
  Vec3 normal;  // unit
  double reflectance = 0;
};

// Every field initialised: `area` once was not, and the second aperture of a scene began its sum
// from the first one's (the same stack slot), so next-event estimation drew points with a density
// lower than it divided by (1/9.0 m⁻² against 1/5.4 on a room with a 3.6 and a 1.8 m² window) and
// ERC and IRC came out up to 67 % high with two or more apertures.
struct ApertureInfo {
  Vec3 normal;  // unit
  double area = 0;
  double transmittance = 0;
  double reflectance = 0;            // the pane's diffuse reflectance, both sides (Aperture::reflectance)
  std::vector<double> angular;       // empty: constant
  std::vector<Triangle> triangles;   // for sampling points by area
  std::vector<double> cumulative;    // cumulative triangle areas, last = area
};

struct TracerScene {
  std::vector<SurfaceInfo> surfaces;
  std::vector<ApertureInfo> apertures;
  std::vector<double> aperture_cumulative;  // cumulative aperture areas
  double aperture_area = 0;
  double offset = 0;  // kRelativeOffset × bounding-box diagonal
  TriangleBvh bvh{{}};
};

void add_fan(const std::vector<Vec3>& v, std::uint32_t object, std::vector<Triangle>& out) {
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    const Triangle t{v[0], v[i] - v[0], v[i + 1] - v[0], object};
    if (norm(cross(t.e1, t.e2)) > 0) out.push_back(t);
  }
}

TracerScene build(const Scene& scene) {
  TracerScene s;
  std::vector<Triangle> all;
  Vec3 lo{1e300, 1e300, 1e300}, hi = -1.0 * lo;
  const auto grow = [&](const std::vector<Vec3>& vertices) {
    for (const Vec3& v : vertices) lo = component_min(lo, v), hi = component_max(hi, v);
  };
  for (std::size_t i = 0; i < scene.occluders.size(); ++i) {
    const Polygon& p = scene.occluders[i];
    const auto m = scene.materials.find(p.material);
    const SurfaceReflectance r = surface_reflectance(m == scene.materials.end() ? nullptr : &m->second);
    const Vec3 n = newell_normal(p.vertices);
    s.surfaces.push_back({norm(n) > 0 ? normalized(n) : Vec3{0, 0, 1}, r.reflectance});
    if (norm(n) == 0) continue;
    for (const ConvexPiece& piece : convex_pieces(p, i)) add_fan(piece.vertices, std::uint32_t(i), all);
    grow(p.vertices);
  }
  const auto n_o = std::uint32_t(scene.occluders.size());
  for (std::size_t a = 0; a < scene.apertures.size(); ++a) {
    const Aperture& ap = scene.apertures[a];
    ApertureInfo info;
    const Vec3 n = newell_normal(ap.polygon.vertices);
    info.normal = norm(n) > 0 ? normalized(n) : Vec3{0, 0, 1};
    info.transmittance = ap.transmittance;
    info.reflectance = ap.reflectance;
    info.angular = ap.angular_transmittance;
    if (norm(n) > 0)
      for (const ConvexPiece& piece : convex_pieces(ap.polygon, a)) add_fan(piece.vertices, n_o + std::uint32_t(a), info.triangles);
    for (const Triangle& t : info.triangles) {
      info.area += 0.5 * norm(cross(t.e1, t.e2));
      info.cumulative.push_back(info.area);
    }
    all.insert(all.end(), info.triangles.begin(), info.triangles.end());
    grow(ap.polygon.vertices);
    s.aperture_area += info.area;
    s.aperture_cumulative.push_back(s.aperture_area);
    s.apertures.push_back(std::move(info));
  }
  // The panes as surfaces too (index n_o + a), for the paths that reflect off them.
  for (const ApertureInfo& a : s.apertures) s.surfaces.push_back({a.normal, a.reflectance});
  s.offset = all.empty() ? 0 : kRelativeOffset * norm(hi - lo);
  s.bvh = TriangleBvh(std::move(all));
  return s;
}

// What a ray finds: the surface it stops on (or none: the environment), the product of the
// transmittances of the apertures it crossed, and the first of them.
struct Walk {
  std::uint32_t surface = kNone;
  Vec3 point;
  double transmittance = 1;
  std::uint32_t first_aperture = kNone;  // index into apertures
  double first_aperture_t = 0;
};

double aperture_transmittance(const ApertureInfo& a, const Vec3& d) noexcept {
  return a.angular.empty() ? a.transmittance : evaluate_polynomial(a.angular, std::abs(dot(a.normal, d)));
}

// Follows o + t·d (d unit) through the apertures, skipping the object `from` (an occluder, or
// n_o + a: the pane of aperture a). A pane that reflects (ρ_p > 0) is a random event: the ray
// passes with probability p = T/(T + ρ_p), its throughput times T/p, or stops on the pane as on a
// surface, its throughput times 1/(1 − p) (the surface's ρ_p then applies): unbiased for both
// parts, and the deterministic crossing where ρ_p = 0.
Walk walk(const TracerScene& s, const Vec3& o, const Vec3& d, std::uint32_t from, Xoshiro256& rng) noexcept {
  Walk w;
  const auto n_o = std::uint32_t(s.surfaces.size() - s.apertures.size());
  double t_min = 0;
  std::uint32_t crossed = kNone;
  while (true) {
    const Hit hit = s.bvh.nearest(o, d, t_min, from, crossed);
    if (hit.object == kNone) return w;
    if (hit.object < n_o) {
      w.surface = hit.object;
      w.point = o + hit.t * d;
      return w;
    }
    const std::uint32_t a = hit.object - n_o;
    // A pane met where the last one was crossed (a pane drawn twice, a double-sided shade in one
    // plane) is passed, as Radiance passes it (within FTINY of the transmitted ray's origin) and
    // as the visibility counts it (geometry/coplanar_panes.hpp).
    if (crossed != kNone && hit.t <= t_min * (1 + 1e-12)) {
      t_min = hit.t;
      crossed = hit.object;
      continue;
    }
    const double t = aperture_transmittance(s.apertures[a], d), rho = s.apertures[a].reflectance;
    if (rho > 0) {
      const double pass = std::max(t, 0.0) / (std::max(t, 0.0) + rho);  // the fit's T may dip below 0 at grazing
      if (!(rng.uniform() < pass)) {
        w.surface = hit.object;
        w.point = o + hit.t * d;
        w.transmittance /= 1 - pass;
        return w;
      }
      w.transmittance /= pass;
    }
    if (w.first_aperture == kNone) w.first_aperture = a, w.first_aperture_t = hit.t;
    w.transmittance *= t;
    t_min = hit.t;
    crossed = hit.object;
  }
}

// Cosine-distributed direction about the unit normal n from (ξ1, ξ2) ∈ [0, 1)² (Malley's method).
Vec3 cosine_direction(const Vec3& n, double xi1, double xi2) noexcept {
  Vec3 e1, e2;
  orthonormal_basis(n, e1, e2);
  const double r = std::sqrt(xi1), phi = 2 * kPi * xi2;
  return normalized(r * std::cos(phi) * e1 + r * std::sin(phi) * e2 + std::sqrt(std::max(0.0, 1 - xi1)) * n);
}

// Index of the first cumulative value above u·total.
std::size_t pick(const std::vector<double>& cumulative, double u) noexcept {
  const double target = u * cumulative.back();
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), target);
  return std::min(std::size_t(it - cumulative.begin()), cumulative.size() - 1);
}

struct Accumulator {
  double sum = 0, squares = 0;
  void add(double x) noexcept { sum += x, squares += x * x; }
  TracedEstimate estimate(long n, double scale) const noexcept {
    const double mean = sum / double(n);
    const double variance = n > 1 ? std::max(0.0, (squares - sum * mean) / double(n - 1)) : 0.0;
    return {scale * mean, scale * std::sqrt(variance / double(n))};
  }
};

class Tracer {
 public:
  Tracer(const TracerScene& s, const PathTracerOptions& o)
      : s_(s),
        o_(o),
        sun_irradiance_(o.sun_normal * unobstructed_horizontal_irradiance(o.sky)),
        ground_(o.ground_reflectance *
                (unobstructed_horizontal_irradiance(o.sky) + sun_irradiance_ * std::max(o.sun.z, 0.0)) / kPi) {
    if (sun_irradiance_ > 0) {
      sun_ = normalized(o.sun);
      orthonormal_basis(sun_, sun_e1_, sun_e2_);
    }
  }

  // A direction uniform over the sun's disk (solid angle: cos θ uniform in [cos ρ, 1]).
  Vec3 sun_direction(Xoshiro256& rng) const noexcept {
    const double cos_t = 1 - rng.uniform() * (1 - kCosSunRadius), sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
    const double phi = 2 * kPi * rng.uniform();
    return normalized(cos_t * sun_ + sin_t * (std::cos(phi) * sun_e1_ + std::sin(phi) * sun_e2_));
  }

  // The sun's irradiance on (x, n) along one direction of its disk, through the apertures; 0
  // where an occluder or a reflecting pane's event stops it. `from`: the object x lies on.
  double sun_irradiance(const Vec3& x, const Vec3& n, std::uint32_t from, Xoshiro256& rng) const noexcept {
    if (!(sun_irradiance_ > 0)) return 0;
    const Vec3 d = sun_direction(rng);
    const double cos_x = dot(n, d);
    if (!(cos_x > 0)) return 0;
    const Walk w = walk(s_, x, d, from, rng);
    return w.surface == kNone ? sun_irradiance_ * cos_x * w.transmittance : 0.0;
  }

  double environment(const Vec3& d) const noexcept { return d.z > 0 ? sky_relative_luminance(o_.sky, d) : (d.z < 0 ? ground_ : 0.0); }

  // Solid-angle density with which next-event estimation draws direction d from x, d crossing
  // aperture a first at distance t.
  double nee_density(std::uint32_t a, double t, const Vec3& d) const noexcept {
    const double cos_y = std::abs(dot(s_.apertures[a].normal, d));
    return cos_y > 0 ? t * t / (s_.aperture_area * cos_y) : std::numeric_limits<double>::infinity();
  }

  // One path: fills sc, erc[k], irc[k] (irradiance units, without the 100/E_out).
  void path(const Sensor& sensor, double xi1, double xi2, Xoshiro256& rng, double& sc, double& sun, std::vector<double>& erc,
            std::vector<double>& irc) const noexcept {
    sun += sun_irradiance(sensor.position, sensor.normal, kNone, rng);
    const Vec3 d0 = cosine_direction(sensor.normal, xi1, xi2);
    const Walk first = walk(s_, sensor.position, d0, kNone, rng);
    double beta = kPi * first.transmittance;  // E ≈ π·L(d) under cosine sampling
    if (first.surface == kNone) {
      if (d0.z > 0) sc += beta * environment(d0);
      else erc[0] += beta * environment(d0);
      return;
    }
    std::vector<double>& out = first.first_aperture != kNone ? erc : irc;
    std::uint32_t surface = first.surface;
    Vec3 x = first.point, incoming = d0;
    for (int k = 1; k <= o_.max_bounces; ++k) {
      const SurfaceInfo& info = s_.surfaces[surface];
      if (info.reflectance == 0) return;
      // The side the path is on: two-sided, it reflects into the half-space it came from.
      const Vec3 n = dot(info.normal, incoming) < 0 ? info.normal : -1.0 * info.normal;
      const Vec3 origin = x + s_.offset * n;
      const double f = info.reflectance / kPi;  // Lambertian BRDF
      // Next-event estimation towards the sun.
      out[k] += beta * f * sun_irradiance(origin, n, surface, rng);
      // Next-event estimation through an aperture drawn by area.
      if (!s_.apertures.empty() && s_.aperture_area > 0) {
        const std::uint32_t a = std::uint32_t(pick(s_.aperture_cumulative, rng.uniform()));
        const ApertureInfo& ap = s_.apertures[a];
        const Triangle& tri = ap.triangles[pick(ap.cumulative, rng.uniform())];
        double u = rng.uniform(), v = rng.uniform();
        if (u + v > 1) u = 1 - u, v = 1 - v;
        const Vec3 y = tri.v0 + u * tri.e1 + v * tri.e2;
        const Vec3 to = y - origin;
        const double distance = norm(to);
        const Vec3 d = to / distance;
        const double cos_x = dot(n, d);
        if (cos_x > 0 && distance > 0) {
          const Walk w = walk(s_, origin, d, surface, rng);
          // Counted only where a is the first aperture crossed (each direction belongs to one).
          if (w.surface == kNone && w.first_aperture == a) {
            const double p_nee = nee_density(a, w.first_aperture_t, d), p_bsdf = cos_x / kPi;
            const double weight = p_nee * p_nee / (p_nee * p_nee + p_bsdf * p_bsdf);
            if (std::isfinite(p_nee)) out[k] += beta * f * cos_x * w.transmittance * environment(d) * weight / p_nee;
          }
        }
      }
      // Continuation: cosine sampling, throughput × ρ.
      const Vec3 d = cosine_direction(n, rng.uniform(), rng.uniform());
      beta *= info.reflectance;
      const Walk w = walk(s_, origin, d, surface, rng);
      if (w.surface == kNone) {
        double weight = 1;
        if (w.first_aperture != kNone) {
          const double p_nee = nee_density(w.first_aperture, w.first_aperture_t, d), p_bsdf = dot(n, d) / kPi;
          weight = std::isfinite(p_nee) ? p_bsdf * p_bsdf / (p_nee * p_nee + p_bsdf * p_bsdf) : 1.0;
        }
        out[k] += beta * w.transmittance * environment(d) * weight;
        return;
      }
      beta *= w.transmittance;
      surface = w.surface;
      x = w.point;
      incoming = d;
    }
  }

 private:
  const TracerScene& s_;
  const PathTracerOptions& o_;
  double sun_irradiance_;  // direct normal, in the sky's units
  double ground_;
  Vec3 sun_{0, 0, 1}, sun_e1_{1, 0, 0}, sun_e2_{0, 1, 0};
};

}  // namespace

std::vector<PathTracedSensor> path_trace(const Scene& scene, const std::vector<Sensor>& sensors,
                                         const PathTracerOptions& options) {
  if (options.samples_per_sensor < 1) throw Error("path tracer: samples per sensor must be at least 1");
  if (options.max_bounces < 0) throw Error("path tracer: the bounce count must be at least 0");
  if (!(options.ground_reflectance >= 0 && options.ground_reflectance <= 1))
    throw Error("path tracer: the ground reflectance must lie in [0, 1]");
  if (!(options.sun_normal >= 0) || !std::isfinite(options.sun_normal))
    throw Error("path tracer: the sun's direct normal irradiance must be a number >= 0");
  if (options.sun_normal > 0 && !(norm(options.sun) > 0 && options.sun.z > 0))
    throw Error("path tracer: the sun must be above the horizon");
  const TracerScene s = build(scene);
  const Tracer tracer(s, options);
  const long n = options.samples_per_sensor;
  long nx = std::max(1L, long(std::sqrt(double(n))));
  while (n % nx != 0) --nx;
  const long ny = n / nx;
  const auto bounces = std::size_t(options.max_bounces) + 1;
  const double scale = 100 / unobstructed_horizontal_irradiance(options.sky);
  std::vector<PathTracedSensor> results(sensors.size());
  for_each_sensor<int>(sensors.size(), 1, {}, [&](std::size_t i, int&) {
    // A generator per sensor, seeded from the run's seed and the sensor's index (SplitMix64
    // inside Xoshiro256 decorrelates neighbouring seeds).
    Xoshiro256 rng(options.seed * 0x9e3779b97f4a7c15ULL + std::uint64_t(i));
    Accumulator sc, sun, erc, irc, df;
    std::vector<Accumulator> erc_k(bounces), irc_k(bounces);
    std::vector<double> e(bounces), r(bounces);
    for (long a = 0; a < nx; ++a)
      for (long b = 0; b < ny; ++b) {
        double c = 0, direct_sun = 0;
        std::fill(e.begin(), e.end(), 0.0);
        std::fill(r.begin(), r.end(), 0.0);
        const double xi1 = (double(a) + rng.uniform()) / double(nx), xi2 = (double(b) + rng.uniform()) / double(ny);
        tracer.path(sensors[i], xi1, xi2, rng, c, direct_sun, e, r);
        double e_sum = 0, r_sum = 0;
        for (std::size_t k = 0; k < bounces; ++k) {
          erc_k[k].add(e[k]);
          irc_k[k].add(r[k]);
          e_sum += e[k];
          r_sum += r[k];
        }
        sc.add(c);
        sun.add(direct_sun);
        erc.add(e_sum);
        irc.add(r_sum);
        df.add(c + direct_sun + e_sum + r_sum);
      }
    PathTracedSensor& out = results[i];
    out.sc = sc.estimate(n, scale);
    out.sun = sun.estimate(n, scale);
    out.erc = erc.estimate(n, scale);
    out.irc = irc.estimate(n, scale);
    out.df = df.estimate(n, scale);
    for (std::size_t k = 0; k < bounces; ++k) {
      out.erc_by_bounce.push_back(erc_k[k].estimate(n, scale));
      out.irc_by_bounce.push_back(irc_k[k].estimate(n, scale));
    }
  });
  return results;
}

std::vector<std::vector<double>> sampled_patch_coefficients(const Scene& scene, const std::vector<Sensor>& sensors,
                                                            const std::vector<SkyPatch>& patches, long samples,
                                                            std::uint64_t seed) {
  if (samples < 1) throw Error("sampled patch coefficients: samples per sensor must be at least 1");
  // The layout of reinhart_patches: 144 MF² + 1 patches, rows of Tregenza's counts times MF.
  const int mf = int(std::lround(std::sqrt(double(patches.size() - 1) / 144)));
  if (patches.size() != std::size_t(144 * mf * mf + 1)) throw Error("sampled patch coefficients: not a Reinhart layout");
  constexpr int kTregenzaRow[7] = {30, 30, 24, 24, 18, 12, 6};
  std::vector<std::size_t> row_start{0};
  for (int r = 0; r < 7 * mf; ++r) row_start.push_back(row_start.back() + std::size_t(kTregenzaRow[r / mf] * mf));
  const double row_height = 90.0 / (7 * mf + 0.5);
  const auto patch_of = [&](const Vec3& d) {
    const int row = int(std::floor(std::asin(std::clamp(d.z, -1.0, 1.0)) * 180 / kPi / row_height));
    if (row >= 7 * mf) return patches.size() - 1;
    for (std::size_t k = row_start[std::size_t(row)]; k < row_start[std::size_t(row) + 1]; ++k)
      if (dot(patches[k].from, d) >= 0 && dot(patches[k].to, d) >= 0) return k;
    return row_start[std::size_t(row)];  // on a boundary within rounding: either side is as good
  };
  const TracerScene s = build(scene);
  long nx = std::max(1L, long(std::sqrt(double(samples))));
  while (samples % nx != 0) --nx;
  const long ny = samples / nx;
  std::vector<std::vector<double>> out(sensors.size(), std::vector<double>(patches.size(), 0.0));
  for_each_sensor<int>(sensors.size(), 1, {}, [&](std::size_t i, int&) {
    Xoshiro256 rng(seed * 0x9e3779b97f4a7c15ULL + std::uint64_t(i));
    const Sensor& sensor = sensors[i];
    for (long a = 0; a < nx; ++a)
      for (long b = 0; b < ny; ++b) {
        const double xi1 = (double(a) + rng.uniform()) / double(nx), xi2 = (double(b) + rng.uniform()) / double(ny);
        const Vec3 d = cosine_direction(sensor.normal, xi1, xi2);
        if (!(d.z > 0)) continue;
        const Walk w = walk(s, sensor.position, d, kNone, rng);
        if (w.surface != kNone || w.first_aperture == kNone) continue;
        out[i][patch_of(d)] += kPi * w.transmittance / double(samples);
      }
  });
  return out;
}

}  // namespace daylit
