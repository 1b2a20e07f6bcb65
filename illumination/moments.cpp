#include "illumination/moments.hpp"

#include "illumination/arc_power_integral.hpp"
#include "illumination/solid_angle.hpp"

namespace daylit {

namespace {

// Calls f(edge) for every non-degenerate edge of every loop.
template <class F>
void for_each_edge(const SphericalRegion& region, F&& f) {
  for (const auto& loop : region.loops) {
    const std::size_t m = loop.size();
    for (std::size_t i = 0; i < m; ++i)
      if (const auto arc = arc_edge(loop[i], loop[(i + 1) % m])) f(*arc);
  }
}

}  // namespace

double lambert(const SphericalRegion& region, const Vec3& n) noexcept {
  double sum = 0;
  for_each_edge(region, [&](const ArcEdge& arc) { sum += arc.length * dot(arc.normal, n); });
  return 0.5 * sum;
}

std::vector<double> axial_moments(const SphericalRegion& region, const Vec3& w, int n) {
  std::vector<double> tau(std::size_t(n) + 1, 0.0);
  tau[0] = solid_angle(region);
  if (n == 0) return tau;
  // boundary[k] = Σ_edges (w·m) ∫_arc (w·u)^k ds, k = 0..n−1
  std::vector<double> boundary(std::size_t(n), 0.0), G;
  for_each_edge(region, [&](const ArcEdge& arc) {
    arc_power_integrals(arc, w, n - 1, G);
    const double wm = dot(w, arc.normal);
    for (int k = 0; k < n; ++k) boundary[k] += wm * G[k];
  });
  const double w2 = dot(w, w);
  for (int k = 1; k <= n; ++k) tau[k] = ((k - 1) * w2 * (k >= 2 ? tau[k - 2] : 0.0) + boundary[k - 1]) / (k + 1);
  return tau;
}

double double_axis_moment(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n) {
  double boundary = 0;
  std::vector<double> G;
  for_each_edge(region, [&](const ArcEdge& arc) {
    arc_power_integrals(arc, w, n, G);
    boundary += dot(v, arc.normal) * G[n];
  });
  const double lower = n > 0 ? n * dot(w, v) * axial_moments(region, w, n - 1)[n - 1] : 0.0;
  return (lower + boundary) / (n + 2);
}

}  // namespace daylit
