#include "simulation/grid_refinement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <tuple>
#include <unordered_map>

#include "simulation/sky_component.hpp"

namespace daylit {

namespace {

// Sensors in buckets of a uniform grid of side b, for nearest-neighbour and position queries.
class SensorHash {
 public:
  SensorHash(const std::vector<Sensor>& sensors, double b) : sensors_(sensors), b_(b) {
    for (std::size_t i = 0; i < sensors.size(); ++i) buckets_[key(sensors[i].position)].push_back(i);
  }

  // The nearest other sensor with the same normal, nearly in the sensor's plane (its offset along
  // the normal within 1e-3 of its distance), searching rings of buckets outwards; -1 if none.
  long nearest(std::size_t i, int max_ring) const {
    const Sensor& s = sensors_[i];
    const Key c = key(s.position);
    long best = -1;
    double best_distance = HUGE_VAL;
    for (int r = 0; r <= max_ring; ++r) {
      // Every sensor in ring r or beyond is at least (r − 1)·b away.
      if (best >= 0 && best_distance <= (r - 1) * b_) break;
      for (long dx = -r; dx <= r; ++dx)
        for (long dy = -r; dy <= r; ++dy)
          for (long dz = -r; dz <= r; ++dz) {
            if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != r) continue;
            const auto it = buckets_.find({c[0] + dx, c[1] + dy, c[2] + dz});
            if (it == buckets_.end()) continue;
            for (const std::size_t j : it->second) {
              if (j == i || !same_plane(s, sensors_[j])) continue;
              const double d = norm(sensors_[j].position - s.position);
              if (d > 0 && d < best_distance) {
                best = long(j);
                best_distance = d;
              }
            }
          }
    }
    return best;
  }

  // A sensor with normal n within `tolerance` of x, or -1.
  long at(const Vec3& x, const Vec3& n, double tolerance) const {
    const Key c = key(x);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = buckets_.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == buckets_.end()) continue;
          for (const std::size_t j : it->second)
            if (norm(sensors_[j].normal - n) <= 1e-9 && norm(sensors_[j].position - x) <= tolerance) return long(j);
        }
    return -1;
  }

 private:
  using Key = std::array<long, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const noexcept {
      return std::size_t(k[0]) * 73856093u ^ std::size_t(k[1]) * 19349663u ^ std::size_t(k[2]) * 83492791u;
    }
  };
  Key key(const Vec3& x) const { return {long(std::floor(x.x / b_)), long(std::floor(x.y / b_)), long(std::floor(x.z / b_))}; }
  static bool same_plane(const Sensor& s, const Sensor& t) {
    const Vec3 d = t.position - s.position;
    return norm(s.normal - t.normal) <= 1e-9 && std::abs(dot(s.normal, d)) <= 1e-3 * norm(d);
  }

  const std::vector<Sensor>& sensors_;
  double b_;
  std::unordered_map<Key, std::vector<std::size_t>, KeyHash> buckets_;
};

// Axes of the plane with normal n: t1 along the world axis most nearly in the plane (x for
// horizontal sensors), t2 = n × t1.
std::pair<Vec3, Vec3> plane_axes(const Vec3& n) {
  const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Vec3* e = &axes[0];
  for (const Vec3& a : axes)
    if (std::abs(dot(a, n)) < std::abs(dot(*e, n))) e = &a;
  const Vec3 t1 = normalized(*e - dot(*e, n) * n);
  return {t1, cross(n, t1)};
}

// Curvature along an axis from the in-plane gradient component g at the cell and its neighbours
// at ±w (either may be missing): central where both exist, else one-sided; nothing if neither.
std::optional<double> curvature(double g, const double* plus, const double* minus, double w) {
  if (plus && minus) return (*plus - *minus) / (2 * w);
  if (plus) return (*plus - g) / w;
  if (minus) return (g - *minus) / w;
  return std::nullopt;
}

}  // namespace

std::vector<SensorCell> infer_cells(const SensorGrid& grid) {
  const auto& sensors = grid.sensors;
  std::vector<SensorCell> cells(sensors.size());
  if (sensors.empty()) return cells;
  Vec3 lo = sensors[0].position, hi = lo;
  for (const Sensor& s : sensors) {
    lo = {std::min(lo.x, s.position.x), std::min(lo.y, s.position.y), std::min(lo.z, s.position.z)};
    hi = {std::max(hi.x, s.position.x), std::max(hi.y, s.position.y), std::max(hi.z, s.position.z)};
  }
  // Bucket side ≈ the spacing of a planar grid of N sensors over the two largest extents; any
  // side gives correct answers, this one few sensors per bucket.
  std::array<double, 3> e{hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  std::sort(e.begin(), e.end());
  const double n = double(sensors.size());
  double b = e[1] > 0 ? std::sqrt(e[2] * e[1] / n) : (e[2] > 0 ? e[2] / n : 1.0);
  if (!(b > 0) || !std::isfinite(b)) b = 1;
  const SensorHash hash(sensors, b);
  const int max_ring = int(std::min(1e6, std::ceil(e[2] / b) + 1));
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    SensorCell& c = cells[i];
    std::tie(c.t1, c.t2) = plane_axes(sensors[i].normal);
    const long j = hash.nearest(i, max_ring);
    if (j < 0) continue;
    c.width = norm(sensors[std::size_t(j)].position - sensors[i].position);
    const Vec3& p = sensors[i].position;
    const Vec3 steps[4] = {c.width * c.t1, -c.width * c.t1, c.width * c.t2, -c.width * c.t2};
    for (int k = 0; k < 4; ++k) c.neighbour[k] = hash.at(p + steps[k], sensors[i].normal, 1e-3 * c.width);
  }
  return cells;
}

std::vector<double> cell_mean_errors(const std::vector<SensorCell>& cells, const std::vector<Vec3>& gradient) {
  std::vector<double> errors(cells.size(), 0.0);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const SensorCell& c = cells[i];
    if (!(c.width > 0)) continue;
    double trace = 0;
    bool any = false;
    for (int axis = 0; axis < 2; ++axis) {
      const Vec3& t = axis == 0 ? c.t1 : c.t2;
      const long up = c.neighbour[2 * axis], down = c.neighbour[2 * axis + 1];
      const double g = dot(t, gradient[i]);
      const double g_up = up >= 0 ? dot(t, gradient[std::size_t(up)]) : 0;
      const double g_down = down >= 0 ? dot(t, gradient[std::size_t(down)]) : 0;
      if (const auto h = curvature(g, up >= 0 ? &g_up : nullptr, down >= 0 ? &g_down : nullptr, c.width)) {
        trace += *h;
        any = true;
      }
    }
    if (any) errors[i] = c.width * c.width / 24 * trace;
  }
  return errors;
}

GridRefinement refine_grid(const VisibilityEngine& engine, const Scene& scene, SkyModel sky, const SensorGrid& grid,
                           const std::vector<double>& df_percent, const std::vector<Vec3>& gradient, double tolerance,
                           VisibilityCounters& counters, const VisibilityEngine* direct) {
  GridRefinement out;
  out.tolerance = tolerance;
  const std::vector<SensorCell> cells = infer_cells(grid);
  const std::vector<double> errors = cell_mean_errors(cells, gradient);
  const std::size_t count = grid.sensors.size();
  double area = 0, weighted = 0, weighted_error = 0;
  SensorGrid children;
  children.name = grid.name;
  children.path = grid.path;
  children.sees_sky_directly = grid.sees_sky_directly;
  for (std::size_t i = 0; i < count; ++i) {
    const SensorCell& c = cells[i];
    const double a = c.width * c.width;
    area += a;
    weighted += a * df_percent[i];
    weighted_error += a * errors[i];
    const bool estimable = c.width > 0 && std::any_of(std::begin(c.neighbour), std::end(c.neighbour), [](long j) { return j >= 0; });
    if (!estimable) ++out.cells_without_neighbours;
    if (!(std::abs(errors[i]) > tolerance)) continue;
    ++out.cells_split;
    const Vec3& p = grid.sensors[i].position;
    const double q = c.width / 4;
    // Children in the order (−,−), (+,−), (−,+), (+,+) along (t1, t2).
    for (const double s2 : {-1.0, 1.0})
      for (const double s1 : {-1.0, 1.0}) {
        children.sensors.push_back({p + (s1 * q) * c.t1 + (s2 * q) * c.t2, grid.sensors[i].normal});
        out.parent.push_back(i);
      }
  }
  // With no area at all (isolated sensors only), the plain mean.
  out.mean_before = area > 0 ? weighted / area : 0;
  if (!(area > 0)) {
    for (const double df : df_percent) out.mean_before += df / double(count);
  }
  out.error_before = area > 0 ? std::abs(weighted_error) / area : 0;
  out.cell_area.resize(count + children.sensors.size(), 0.0);
  for (std::size_t i = 0; i < count; ++i) out.cell_area[i] = cells[i].width * cells[i].width;
  if (!children.sensors.empty()) {
    const SkyComponentResult r = sky_component(engine, scene, children, sky, {}, true, direct);
    counters += r.counters;
    out.added = children.sensors;
    out.added_df = r.sc_percent;
    out.added_gradient = r.sc_gradient;
  }
  // After: the split cells' areas and errors replaced by their children's, whose curvature comes
  // from the differences of their siblings' gradients at distance w/2.
  double area_after = area, weighted_after = weighted, error_after = weighted_error;
  for (std::size_t k = 0; k < out.added.size(); k += 4) {
    const std::size_t i = out.parent[k];
    const SensorCell& c = cells[i];
    const double a = c.width * c.width, w = c.width / 2;
    weighted_after -= a * df_percent[i];
    error_after -= a * errors[i];
    out.cell_area[i] = 0;
    const Vec3* g = &out.added_gradient[k];
    const double h11 = (dot(c.t1, g[1]) - dot(c.t1, g[0]) + dot(c.t1, g[3]) - dot(c.t1, g[2])) / (2 * w);
    const double h22 = (dot(c.t2, g[2]) - dot(c.t2, g[0]) + dot(c.t2, g[3]) - dot(c.t2, g[1])) / (2 * w);
    const double child_error = w * w / 24 * (h11 + h22);
    for (std::size_t m = 0; m < 4; ++m) {
      weighted_after += w * w * out.added_df[k + m];
      error_after += w * w * child_error;
      out.cell_area[count + k + m] = w * w;
    }
  }
  out.mean_after = area_after > 0 ? weighted_after / area_after : out.mean_before;
  out.error_after = area_after > 0 ? std::abs(error_after) / area_after : 0;
  return out;
}

}  // namespace daylit
