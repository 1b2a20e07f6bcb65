#include "illumination/monte_carlo.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/error.hpp"
#include "illumination/orthonormal_basis.hpp"
#include "illumination/xoshiro256.hpp"

namespace daylit {

namespace {

constexpr double kPi = std::numbers::pi;

// x^k, k ≥ 0, by binary powering: exact for small k and several times faster than std::pow.
double power(double x, int k) noexcept {
  double result = 1;
  for (; k > 0; k >>= 1, x *= x)
    if (k & 1) result *= x;
  return result;
}

// +1 or −1; a zero counts as positive, the same way wherever the same product is computed.
int sign(double x) noexcept { return x >= 0 ? 1 : -1; }

// 1 − cos of the angle between unit vectors, from the chord: keeps its digits for tiny angles.
double cap_height(const Vec3& axis, const Vec3& u) noexcept {
  const Vec3 chord = axis - u;
  return 0.5 * dot(chord, chord);
}

double max_height(const Vec3& axis, const std::vector<Vec3>& units) noexcept {
  double h = 0;
  for (const Vec3& p : units) h = std::max(h, cap_height(axis, p));
  return h;
}

// Calls y(ξ₁, ξ₂) twice in each of the N/2 cells (three times in the first when N is odd) of an
// nx × ny grid of the unit square (nx ≤ ny, nx·ny = N/2, nx as close to √(N/2) as divides it), and
// returns measure × the stratified mean, with its standard error from the within-cell spread.
template <class Y>
MonteCarloEstimate stratified(long samples, std::uint64_t seed, double measure, Y&& y) {
  if (samples < 2) throw Error("Monte Carlo estimates need at least 2 samples");
  const long cells = samples / 2;
  long nx = std::max(1L, long(std::sqrt(double(cells))));
  while (cells % nx != 0) --nx;
  const long ny = cells / nx;
  Xoshiro256 rng(seed);
  const auto uniform = [&rng] { return rng.uniform(); };
  double sum = 0, variance = 0;
  for (long i = 0; i < nx; ++i)
    for (long j = 0; j < ny; ++j) {
      const int count = (i == 0 && j == 0 && samples % 2 == 1) ? 3 : 2;
      double mean = 0, m2 = 0;  // Welford
      for (int k = 0; k < count; ++k) {
        const double xi1 = (double(i) + uniform()) / double(nx);
        const double xi2 = (double(j) + uniform()) / double(ny);
        const double value = y(xi1, xi2);
        const double delta = value - mean;
        mean += delta / (k + 1);
        m2 += delta * (value - mean);
      }
      sum += mean;
      variance += m2 / (count - 1) / count;  // variance of this cell's mean
    }
  return {measure * sum / double(cells), measure * std::sqrt(variance) / double(cells)};
}

}  // namespace

double SphericalCap::solid_angle() const noexcept { return 2 * kPi * height; }

RegionWinding::RegionWinding(const SphericalRegion& region) {
  std::vector<Vec3> units;
  for (const auto& loop : region.loops) {
    const std::size_t first = vertices_.size(), m = loop.size();
    for (const Vec3& v : loop) {
      vertices_.push_back(v);
      units.push_back(normalized(v));
    }
    for (std::size_t i = 0; i < m; ++i) {
      const Vec3 &a = loop[i], &b = loop[(i + 1) % m];
      const Vec3 pole = cross(a, b - a);  // robust edge plane (DESIGN.md §7); only its sign is used
      if (pole == Vec3{}) continue;       // a degenerate edge bounds nothing
      edges_.push_back({first + i, first + (i + 1) % m, pole, {0, 0}});
    }
  }
  if (units.empty()) {
    cap_ = {{0, 0, 1}, 0};
  } else {
    // Bădoiu and Clarkson, "Smaller core-sets for balls" (2003): c ← c + (farthest − c)/(k + 1)
    // approaches the centre of the smallest enclosing ball; its direction is a good cap axis.
    Vec3 mean{}, c = units[0];
    for (const Vec3& p : units) mean += p;
    for (int k = 1; k <= 64; ++k) {
      const Vec3* far = &units[0];
      double far_d = -1;
      for (const Vec3& p : units)
        if (const double d = dot(p - c, p - c); d > far_d) far_d = d, far = &p;
      c += (*far - c) * (1.0 / (k + 1));
    }
    SphericalCap best{{0, 0, 1}, 3};
    for (const Vec3& candidate : {c, mean}) {
      if (!(norm(candidate) > 1e-12)) continue;
      const Vec3 axis = normalized(candidate);
      if (const double h = max_height(axis, units); h < best.height) best = {axis, h};
    }
    if (!(best.height <= 1 + 1e-9))
      throw Error("Monte Carlo moments need a region within a hemisphere; this one's vertices are spread wider");
    best.height = std::min(1.0, best.height * (1 + 1e-9));
    cap_ = best;
  }
  // Two reference directions about 178° from the axis (outside any cap of half-angle ≤ 90°) and
  // 3° apart, so that every u in the cap is at least 1° away from the antipode of one of them
  // and the great arc from u to it is well defined.
  Vec3 e1, e2;
  orthonormal_basis(cap_.axis, e1, e2);
  reference_[0] = normalized(-cap_.axis + 0.03 * e1 + 0.02 * e2);
  reference_[1] = normalized(-cap_.axis - 0.02 * e1 + 0.03 * e2);
  for (Edge& e : edges_)
    for (int r = 0; r < 2; ++r) e.reference_side[r] = sign(dot(e.pole, reference_[r]));
}

int RegionWinding::winding(const Vec3& u) const noexcept {
  constexpr double kCosOneDegree = 0.99984769515639124;
  const int r = dot(u, reference_[0]) < -kCosOneDegree ? 1 : 0;
  const Vec3 path_pole = cross(u, reference_[r]);
  int w = 0;
  for (const Edge& e : edges_) {
    // S2's CrossingSign for arcs u→q and a→b: with s = sign det(u, q, a), they cross iff
    // det(u, q, b) = −s, det(a, b, q) = s and det(a, b, u) = −s; u then lies on the side
    // det(a, b, u) of the edge, the left (inside) when it is positive.
    const int s = sign(dot(path_pole, vertices_[e.start]));
    if (sign(dot(path_pole, vertices_[e.end])) == s) continue;
    if (e.reference_side[r] != s) continue;
    const int side_u = sign(dot(e.pole, u));
    if (side_u == -s) w += side_u;
  }
  return w;
}

double MomentIntegrand::operator()(const Vec3& u) const noexcept {
  const double lobe = power(dot(w, u), n);
  return v ? lobe * dot(*v, u) : lobe;
}

MonteCarloEstimate moment_uniform_stratified(const SphericalRegion& region, const MomentIntegrand& f, long samples,
                                             std::uint64_t seed) {
  const RegionWinding winding(region);
  const SphericalCap& cap = winding.bounding_cap();
  Vec3 e1, e2;
  orthonormal_basis(cap.axis, e1, e2);
  return stratified(samples, seed, cap.solid_angle(), [&](double xi1, double xi2) {
    const double t = xi1 * cap.height;  // 1 − cos θ
    const double r = std::sqrt(t * (2 - t));
    const double phi = 2 * kPi * xi2;
    const Vec3 u = (1 - t) * cap.axis + (r * std::cos(phi)) * e1 + (r * std::sin(phi)) * e2;
    const int k = winding.winding(u);
    return k == 0 ? 0.0 : k * f(u);
  });
}

MonteCarloEstimate moment_lobe_importance(const SphericalRegion& region, const MomentIntegrand& f, long samples,
                                          std::uint64_t seed) {
  const RegionWinding winding(region);
  const SphericalCap& cap = winding.bounding_cap();
  const double w_length = norm(f.w);
  if (!(w_length > 0)) throw Error("the lobe axis w must be non-zero");
  const Vec3 w = f.w / w_length;
  // Which side(s) of the plane w·u = 0 the cap reaches: angle(axis, ±w) + half-angle ≤ π/2.
  const double half_angle = 2 * std::asin(std::sqrt(0.5 * cap.height));
  const double axis_angle = std::atan2(norm(cross(cap.axis, w)), dot(cap.axis, w));
  const bool positive_only = axis_angle + half_angle <= kPi / 2;
  const bool negative_only = (kPi - axis_angle) + half_angle <= kPi / 2;
  const bool both = !positive_only && !negative_only;
  Vec3 e1, e2;
  orthonormal_basis(w, e1, e2);
  const double n1 = f.n + 1.0;
  // f/pdf = (2π or 4π)/(n+1) · |w|^n · side^n (v·u)^m winding(u).
  const double measure = (both ? 4 : 2) * kPi / n1 * power(w_length, f.n);
  return stratified(samples, seed, measure, [&](double xi1, double xi2) {
    double side = negative_only ? -1 : 1;
    if (both) {
      side = xi1 < 0.5 ? 1 : -1;
      xi1 = xi1 < 0.5 ? 2 * xi1 : 2 * xi1 - 1;
    }
    // cos θ = ξ^{1/(n+1)}, with 1 − cos θ = −expm1(ln ξ/(n+1)) to keep narrow lobes' digits.
    const double t = -std::expm1(std::log(xi1) / n1);
    const double r = std::sqrt(t * (2 - t));
    const double phi = 2 * kPi * xi2;
    const Vec3 u = side * ((1 - t) * w) + (r * std::cos(phi)) * e1 + (r * std::sin(phi)) * e2;
    const int k = winding.winding(u);
    if (k == 0) return 0.0;
    const double parity = (f.n % 2 == 1) ? side : 1.0;
    return k * parity * (f.v ? dot(*f.v, u) : 1.0);
  });
}

}  // namespace daylit
