#include "simulation/sunlit_elements.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "illumination/orthonormal_basis.hpp"
#include "simulation/annual_coefficients.hpp"

namespace daylit {

namespace {

struct Point2 {
  double x = 0, y = 0;
};
using Polygon2 = std::vector<Point2>;  // convex, counter-clockwise

double cross2(const Point2& o, const Point2& a, const Point2& b) noexcept {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

double twice_area(const Polygon2& p) noexcept {
  double s = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point2& a = p[i];
    const Point2& b = p[(i + 1) % p.size()];
    s += a.x * b.y - a.y * b.x;
  }
  return s;
}

// The part of convex `p` on the left of the directed line a → b (inside: side ≥ 0) and on its
// right (outside), by one Sutherland–Hodgman pass each. A piece that is only an edge or a vertex
// on the line comes out with (nearly) zero area and is dropped by the caller.
void split_by_line(const Polygon2& p, const Point2& a, const Point2& b, Polygon2& inside, Polygon2& outside) {
  inside.clear();
  outside.clear();
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& c = p[i];
    const Point2& d = p[(i + 1) % n];
    const double sc = cross2(a, b, c), sd = cross2(a, b, d);
    if (sc >= 0) inside.push_back(c);
    if (sc <= 0) outside.push_back(c);
    if ((sc > 0 && sd < 0) || (sc < 0 && sd > 0)) {
      const double t = sc / (sc - sd);
      const Point2 x{c.x + t * (d.x - c.x), c.y + t * (d.y - c.y)};
      inside.push_back(x);
      outside.push_back(x);
    }
  }
}

// A part of the element still to be filtered, at the transmittance its light has so far, and the
// pane it passed farthest from the element.
struct LitPart {
  Polygon2 polygon;
  double weight = 1;
  std::size_t outer = SunlitPart::kDirect;
  double outer_height = -1;
};

}  // namespace

std::vector<ConvexPiece> sun_blocker_pieces(const std::vector<Polygon>& polygons) {
  std::vector<ConvexPiece> out;
  for (std::size_t i = 0; i < polygons.size(); ++i)
    for (ConvexPiece& c : convex_pieces(polygons[i], i)) out.push_back(std::move(c));
  return out;
}

std::vector<ConvexPiece> sun_blocker_pieces(const Scene& scene) {
  std::vector<Polygon> polygons = scene.occluders;
  for (const Aperture& a : scene.apertures) polygons.push_back(a.polygon);
  return sun_blocker_pieces(polygons);
}

std::vector<double> sun_transmittances(const Scene& scene, const Vec3& sun) {
  std::vector<double> out(scene.occluders.size(), 0.0);
  for (const Aperture& a : scene.apertures) out.push_back(ApertureTransmittance(a)(sun));
  return out;
}

SunlitElements::SunlitElements(const std::vector<ConvexPiece>& pieces, const std::vector<double>& transmittance,
                               const Vec3& sun, double scale)
    : sun_(normalized(sun)), tolerance_(1e-9 * scale) {
  orthonormal_basis(sun_, across_u_, across_v_);
  double u0 = std::numeric_limits<double>::infinity(), u1 = -u0, v0 = u0, v1 = -u0;
  for (const ConvexPiece& c : pieces) {
    Piece p;
    p.piece = &c;
    p.transmittance = transmittance.at(c.source);
    p.u_min = p.v_min = std::numeric_limits<double>::infinity();
    p.u_max = p.v_max = p.depth_max = -std::numeric_limits<double>::infinity();
    for (const Vec3& v : c.vertices) {
      const double u = dot(across_u_, v), w = dot(across_v_, v);
      p.u_min = std::min(p.u_min, u);
      p.u_max = std::max(p.u_max, u);
      p.v_min = std::min(p.v_min, w);
      p.v_max = std::max(p.v_max, w);
      p.depth_max = std::max(p.depth_max, dot(sun_, v));
    }
    u0 = std::min(u0, p.u_min);
    u1 = std::max(u1, p.u_max);
    v0 = std::min(v0, p.v_min);
    v1 = std::max(v1, p.v_max);
    pieces_.push_back(p);
  }
  if (pieces_.empty()) return;
  // Pieces more than a quarter of everything across (a ground polygon around a building) are
  // checked for every element; the grid covers the others, so that a large ground does not
  // stretch its cells over the whole site and leave the building in one of them.
  const double whole = std::max(u1 - u0, v1 - v0);
  u0 = v0 = std::numeric_limits<double>::infinity();
  u1 = v1 = -u0;
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    const Piece& p = pieces_[i];
    if (std::max(p.u_max - p.u_min, p.v_max - p.v_min) > whole / 4) {
      large_.push_back(std::uint32_t(i));
      continue;
    }
    u0 = std::min(u0, p.u_min);
    u1 = std::max(u1, p.u_max);
    v0 = std::min(v0, p.v_min);
    v1 = std::max(v1, p.v_max);
  }
  const std::size_t gridded = pieces_.size() - large_.size();
  if (gridded == 0) return;
  // About one piece per cell, square cells, at most 256 a side.
  const double span = std::max({u1 - u0, v1 - v0, 1e-300});
  const int side = std::clamp(int(std::ceil(std::sqrt(double(gridded)))), 1, 256);
  cell_ = span / side;
  grid_u0_ = u0;
  grid_v0_ = v0;
  cells_u_ = std::clamp(int(std::ceil((u1 - u0) / cell_)), 1, side);
  cells_v_ = std::clamp(int(std::ceil((v1 - v0) / cell_)), 1, side);
  cells_.assign(std::size_t(cells_u_) * std::size_t(cells_v_), {});
  std::size_t next_large = 0;
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    if (next_large < large_.size() && large_[next_large] == i) {
      ++next_large;
      continue;
    }
    const Piece& p = pieces_[i];
    const int a1 = cell_of(p.u_max, grid_u0_, cells_u_), b1 = cell_of(p.v_max, grid_v0_, cells_v_);
    for (int a = cell_of(p.u_min, grid_u0_, cells_u_); a <= a1; ++a)
      for (int b = cell_of(p.v_min, grid_v0_, cells_v_); b <= b1; ++b)
        cells_[std::size_t(a) * std::size_t(cells_v_) + std::size_t(b)].push_back(std::uint32_t(i));
  }
}

int SunlitElements::cell_of(double x, double origin, int count) const noexcept {
  return std::clamp(int(std::floor((x - origin) / cell_)), 0, count - 1);
}

void SunlitElements::candidates(double u0, double u1, double v0, double v1, std::vector<std::uint32_t>& out) const {
  out = large_;
  if (cells_.empty()) return;
  for (int a = cell_of(u0, grid_u0_, cells_u_); a <= cell_of(u1, grid_u0_, cells_u_); ++a)
    for (int b = cell_of(v0, grid_v0_, cells_v_); b <= cell_of(v1, grid_v0_, cells_v_); ++b) {
      const auto& cell = cells_[std::size_t(a) * std::size_t(cells_v_) + std::size_t(b)];
      out.insert(out.end(), cell.begin(), cell.end());
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

std::array<double, 3> SunlitElements::basis_integrals(const RadiosityElement& element, const Vec3& n,
                                                      std::size_t own) const {
  std::array<double, 3> out{0, 0, 0};
  for (const SunlitPart& part : parts(element, n, own))
    for (std::size_t k = 0; k < 3; ++k) out[k] += part.integrals[k];
  return out;
}

std::vector<SunlitPart> SunlitElements::parts(const RadiosityElement& element, const Vec3& n, std::size_t own) const {
  std::vector<SunlitPart> out;
  // A side the sun grazes at less than 1e-9 rad gets at most 1e-9 E_dn per unit area, nothing
  // against any tolerance, and would project the polygons above it up to 1e9 times the model's
  // size away: left out.
  const double facing = dot(n, sun_);
  if (!(facing > 1e-9)) return out;
  // The element's plane, in coordinates (e1, e2) with e2 = normal × e1: its vertices run
  // counter-clockwise about element.normal, so counter-clockwise in these coordinates.
  const Vec3& origin = element.vertices[0];
  const Vec3 e1 = normalized(element.vertices[1] - origin);
  const Vec3 e2 = cross(element.normal, e1);
  // y's shadow on the plane along the beam: y − (d/facing) s, d = n·(y − origin) its height in front.
  const auto shadow = [&](const Vec3& y, double d) {
    const Vec3 f = y - (d / facing) * sun_ - origin;
    return Point2{dot(e1, f), dot(e2, f)};
  };
  double u_min = std::numeric_limits<double>::infinity(), u_max = -u_min, v_min = u_min, v_max = -u_min;
  double depth_min = u_min;
  Polygon2 triangle;
  for (const Vec3& v : element.vertices) {
    triangle.push_back(shadow(v, 0));
    const double u = dot(across_u_, v), w = dot(across_v_, v);
    u_min = std::min(u_min, u);
    u_max = std::max(u_max, u);
    v_min = std::min(v_min, w);
    v_max = std::max(v_max, w);
    depth_min = std::min(depth_min, dot(sun_, v));
  }
  std::vector<LitPart> lit{{triangle}}, next;
  const double area_floor = 1e-14 * twice_area(triangle);
  Polygon2 shade, inside, outside;
  std::vector<double> height;
  std::vector<std::uint32_t> near;
  candidates(u_min, u_max, v_min, v_max, near);
  for (const std::uint32_t index : near) {
    const Piece& p = pieces_[index];
    if (p.piece->source == own) continue;
    // Only what lies across the element's beam and ahead of it can reach it.
    if (p.u_max < u_min || p.u_min > u_max || p.v_max < v_min || p.v_min > v_max || p.depth_max <= depth_min) continue;
    // The piece's part in front of the plane, projected. Heights within the tolerance are the
    // plane's own: a polygon in the plane (the element's neighbours on its surface, a pane flush
    // with it) casts nothing, and one that meets it along an edge (a wall on the floor) casts its
    // shadow from that edge on, with no sliver of light let through at the joint.
    const std::vector<Vec3>& v = p.piece->vertices;
    height.clear();
    double highest = 0;
    for (const Vec3& a : v) {
      const double d = dot(n, a - origin);
      height.push_back(std::abs(d) <= tolerance_ ? 0.0 : d);
      highest = std::max(highest, d);
    }
    if (highest <= tolerance_) continue;
    shade.clear();
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::size_t j = (i + 1) % v.size();
      const double da = height[i], db = height[j];
      if (da >= 0) shade.push_back(shadow(v[i], da));
      if ((da > 0 && db < 0) || (da < 0 && db > 0)) shade.push_back(shadow(v[i] + (da / (da - db)) * (v[j] - v[i]), 0));
    }
    if (shade.size() < 3) continue;
    const double twice = twice_area(shade);
    if (std::abs(twice) <= area_floor) continue;
    if (twice < 0) std::reverse(shade.begin(), shade.end());
    // Cut every lit part by the shade: what lies outside keeps its weight, what lies under it is
    // dropped (opaque) or filtered.
    next.clear();
    for (LitPart& part : lit) {
      Polygon2 rest = std::move(part.polygon);
      bool under = true;
      for (std::size_t i = 0; i < shade.size() && under; ++i) {
        split_by_line(rest, shade[i], shade[(i + 1) % shade.size()], inside, outside);
        if (outside.size() >= 3 && twice_area(outside) > area_floor)
          next.push_back({outside, part.weight, part.outer, part.outer_height});
        under = inside.size() >= 3 && twice_area(inside) > area_floor;
        rest.swap(inside);
      }
      if (!under || p.transmittance == 0) continue;
      LitPart filtered{std::move(rest), part.weight * p.transmittance, part.outer, part.outer_height};
      if (highest > filtered.outer_height) {
        filtered.outer = p.piece->source;
        filtered.outer_height = highest;
      }
      next.push_back(std::move(filtered));
    }
    lit.swap(next);
    if (lit.empty()) return out;
  }
  // ∫ φ_k over a part is its area times φ_k at its centroid (φ_k is linear); summed by window.
  for (const LitPart& part : lit) {
    const Polygon2& q = part.polygon;
    double twice = 0, cx = 0, cy = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      const Point2& a = q[i];
      const Point2& b = q[(i + 1) % q.size()];
      const double w = a.x * b.y - a.y * b.x;
      twice += w;
      cx += (a.x + b.x) * w;
      cy += (a.y + b.y) * w;
    }
    if (!(twice > 0) || part.weight == 0) continue;
    auto it = std::find_if(out.begin(), out.end(), [&](const SunlitPart& s) { return s.outer_polygon == part.outer; });
    if (it == out.end()) it = out.insert(out.end(), SunlitPart{part.outer, {0, 0, 0}});
    const Vec3 centroid = origin + (cx / (3 * twice)) * e1 + (cy / (3 * twice)) * e2;
    for (int k = 0; k < 3; ++k) it->integrals[std::size_t(k)] += part.weight * 0.5 * twice * element.basis(k, centroid);
  }
  return out;
}

}  // namespace daylit
