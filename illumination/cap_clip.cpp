#include "illumination/cap_clip.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "illumination/arc_edge.hpp"
#include "illumination/cosine_power_arc.hpp"

namespace daylit {

namespace {

constexpr double pi = std::numbers::pi;

struct Crossing {
  double angle;  // on the cap's circle, φ ∈ (−π, π]
  int change;    // of the winding number when the circle passes it in the direction of increasing φ
};

// A's winding number about s where no edge's great circle comes within ρ of s (then the cap's
// circle crosses no arc and the winding number is the same over the whole cap); nothing where one
// does, or where the count below is too close to call. The count: the signed crossings of the
// loops' arcs with a half great circle from s to −s (−s lies in no visible region, as in the
// series the general path takes, so the winding number there is 0). An arc (a, b) meets the
// half circle's plane (normal k) where k·a and k·b differ in sign, at (k·a) b − (k·b) a, a positive
// combination of a and b; the half circle holds the points with positive component along d. No
// trigonometry: the exact cut costs arcs and arc tangents per edge, and on an annual run's
// reflected sun (every node, view and hour near the sun) this was most of its time.
std::optional<int> winding_clear_of_edges(const SphericalRegion& region, const Vec3& s, double sin_rho) {
  // Clear of an edge with pole m = a × b: (s·m)² ≥ sin²ρ (m·m), with a relative margin far above
  // the rounding of either side.
  const double clear = sin_rho * sin_rho * (1 + 1e-9);
  for (const DirectionLoop& loop : region.loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec3 m = cross(loop[i], loop[i + 1 == loop.size() ? 0 : i + 1]);
      const double sm = dot(s, m);
      if (sm * sm < clear * dot(m, m)) return std::nullopt;
    }
  for (const Vec3& e : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
    const Vec3 k = cross(s, e);
    if (dot(k, k) < 0.25) continue;  // e too close to ±s to span a plane with it well
    const Vec3 d = cross(k, s);      // in the plane, perpendicular to s
    int winding = 0;
    bool decided = true;
    for (const DirectionLoop& loop : region.loops) {
      for (std::size_t i = 0; i < loop.size() && decided; ++i) {
        const Vec3 &a = loop[i], &b = loop[i + 1 == loop.size() ? 0 : i + 1];
        const double ka = dot(k, a) / norm(a), kb = dot(k, b) / norm(b);
        // A vertex on (or within rounding of) the plane: another plane.
        if (std::abs(ka) < 1e-9 || std::abs(kb) < 1e-9) decided = false;
        if (!decided || (ka > 0) == (kb > 0)) continue;
        const double along = dot(d, dot(k, a) * b - dot(k, b) * a) * (dot(k, a) > 0 ? 1 : -1);
        // The crossing at (or near) ±s: s is clear of every edge, so only near −s; too close to call.
        if (std::abs(along) < 1e-9 * norm(a) * norm(b)) decided = false;
        if (decided && along > 0) winding += ka < 0 ? 1 : -1;
      }
      if (!decided) break;
    }
    if (decided) return winding;
  }
  return std::nullopt;
}

}  // namespace

double cap_lambert(const SphericalRegion& region, const Vec3& axis, double rho, const Vec3& n) {
  const Vec3 s = normalized(axis);
  const double sin_rho = std::sin(rho), cos_rho = std::cos(rho);
  // The whole cap inside (or outside) every loop: its winding number times ∫_C (n·u) dσ =
  // π sin²ρ (n·s), the full circle's term below.
  if (const std::optional<int> winding = winding_clear_of_edges(region, s, sin_rho))
    return *winding == 0 ? 0.0 : *winding * pi * sin_rho * sin_rho * dot(n, s);
  const Vec3 p = normalized(cross(s, std::abs(s.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0}));
  const Vec3 q = cross(s, p);
  const real::V3<double> sv(s);
  double sum = 0;
  std::vector<Crossing> crossings;
  std::vector<ArcEdge<double>> arcs;
  for (const DirectionLoop& loop : region.loops) {
    const std::size_t count = loop.size();
    for (std::size_t i = 0; i < count; ++i) {
      const auto arc = arc_edge(real::V3<double>(loop[i]), real::V3<double>(loop[(i + 1) % count]));
      if (!arc) continue;
      arcs.push_back(*arc);
      // The part of the arc inside the cap: t with s·u(t) = c cos(t − φ) ≥ cos ρ.
      const double X = dot(sv, arc->start), beta = dot(sv, arc->start_tangent), sm = dot(sv, arc->normal);
      const double d2 = (sin_rho - std::abs(sm)) * (sin_rho + std::abs(sm));
      if (!(d2 > 0)) continue;  // the arc's great circle misses the cap
      const double alpha = std::atan2(std::sqrt(d2), cos_rho);
      double phi = std::atan2(beta, X);
      // The interval [φ − α, φ + α] (length < π) against [0, θ], θ ≤ π: try φ and φ ± 2π.
      const Vec3 m{arc->normal.x, arc->normal.y, arc->normal.z};
      const Vec3 a{arc->start.x, arc->start.y, arc->start.z}, ta{arc->start_tangent.x, arc->start_tangent.y, arc->start_tangent.z};
      for (double shift : {-2 * pi, 0.0, 2 * pi}) {
        const double lo = phi + shift - alpha, hi = phi + shift + alpha;
        const double t0 = std::max(lo, 0.0), t1 = std::min(hi, double(arc->length));
        if (!(t1 > t0)) continue;
        sum += 0.5 * dot(n, m) * (t1 - t0);
        // Where the arc enters (t = lo) or leaves (t = hi) the cap within the arc, the circle
        // crosses it.
        for (const double t : {lo, hi}) {
          if (t < 0 || t > double(arc->length)) continue;
          const Vec3 x = std::cos(t) * a + std::sin(t) * ta;
          const double angle = std::atan2(dot(x, q), dot(x, p));
          const Vec3 tangent = -std::sin(angle) * p + std::cos(angle) * q;
          crossings.push_back({angle, dot(tangent, m) > 0 ? 1 : -1});
        }
      }
    }
  }
  // The circle is walked once around from a start point in the middle of the widest gap between
  // crossings (never on an arc: a shadow edge through the sun's centre crosses at φ = 0).
  for (Crossing& c : crossings)
    if (c.angle < 0) c.angle += 2 * pi;
  std::sort(crossings.begin(), crossings.end(), [](const Crossing& a, const Crossing& b) { return a.angle < b.angle; });
  double start = 0;
  if (!crossings.empty()) {
    double widest = crossings.front().angle + 2 * pi - crossings.back().angle;
    start = crossings.back().angle + widest / 2;
    for (std::size_t i = 1; i < crossings.size(); ++i)
      if (const double gap = crossings[i].angle - crossings[i - 1].angle; gap > widest) {
        widest = gap;
        start = crossings[i - 1].angle + gap / 2;
      }
    if (start >= 2 * pi) start -= 2 * pi;
    for (Crossing& c : crossings)
      if (c.angle < start) c.angle += 2 * pi;
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& a, const Crossing& b) { return a.angle < b.angle; });
  }
  // A's winding number there, from the complete series of eq. 11 about that direction (odd
  // orders: [u ∈ A] − [−u ∈ A]; −u lies in A only for regions wider than a hemisphere about it,
  // which visible regions never are).
  const real::V3<double> start_point(cos_rho * s + sin_rho * (std::cos(start) * p + std::sin(start) * q));
  double series = 0;
  for (const auto& arc : arcs) series += CosinePowerArc<double>(arc, start_point).even_series_times_wm();
  int winding = int(std::lround(series / (2 * pi)));
  auto circle_term = [&](double phi0, double phi1) {
    const Vec3 chord = (std::sin(phi1) - std::sin(phi0)) * p - (std::cos(phi1) - std::cos(phi0)) * q;
    return 0.5 * (sin_rho * sin_rho * (phi1 - phi0) * dot(n, s) - sin_rho * cos_rho * dot(n, chord));
  };
  double from = start;
  for (const Crossing& c : crossings) {
    if (winding != 0) sum += winding * circle_term(from, c.angle);
    winding += c.change;
    from = c.angle;
  }
  if (winding != 0) sum += winding * circle_term(from, start + 2 * pi);
  return sum;
}

}  // namespace daylit
