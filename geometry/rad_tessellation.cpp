#include "geometry/rad_tessellation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace daylit {

namespace {

constexpr double kPi = std::numbers::pi;

// Segments around a full circle so that the sagitta of each chord, r (1 − cos(π/n)), is at most
// relative_deviation · r; at least 8 so that no facet spans more than 45°.
int segments_for(double relative_deviation) {
  const double half_angle = std::acos(1 - std::clamp(relative_deviation, 1e-9, 0.5));
  return std::max(8, int(std::ceil(kPi / half_angle)));
}

// Two unit vectors perpendicular to the unit axis a and to each other, (e1, e2, a) right-handed.
void frame(const Vec3& a, Vec3& e1, Vec3& e2) {
  const Vec3 helper = std::abs(a.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  e1 = normalized(cross(helper, a));
  e2 = cross(a, e1);
}

Vec3 on_circle(const Vec3& centre, const Vec3& e1, const Vec3& e2, double r, int k, int n) {
  const double t = 2 * kPi * k / n;
  return centre + (r * std::cos(t)) * e1 + (r * std::sin(t)) * e2;
}

Polygon facet(const std::string& name, const std::string& modifier, const SourceLocation& where, std::vector<Vec3> v,
              bool reverse) {
  if (reverse) std::reverse(v.begin(), v.end());
  Polygon p;
  p.vertices = std::move(v);
  p.name = name;
  p.material = modifier;
  p.where = where;
  return p;
}

void need(std::size_t have, std::size_t want, std::string_view type, const std::string& name, const SourceLocation& where) {
  if (have != want)
    throw input_error(where, std::string(type) + " '" + name + "' has " + std::to_string(have) + " real arguments; Radiance's " +
                                 std::string(type) + " takes " + std::to_string(want));
}

void finite(const std::vector<double>& reals, std::string_view type, const std::string& name, const SourceLocation& where) {
  for (double x : reals)
    if (!std::isfinite(x) || std::abs(x) > 1e12)
      throw input_error(where, std::string(type) + " '" + name + "' has an argument that is not finite or beyond 1e12");
}

// A band between two coaxial circles (cylinder, cone, one ring of a sphere): quads, or triangles
// where a radius is zero. Outward (away from the axis) when `outward`, else inward.
void band(Tessellation& t, const std::string& name, const std::string& modifier, const SourceLocation& where,
          const Vec3& c0, double r0, const Vec3& c1, double r1, const Vec3& e1, const Vec3& e2, int n, bool outward) {
  for (int k = 0; k < n; ++k) {
    std::vector<Vec3> v;
    // Counter-clockwise about the outward normal: (c0, k), (c0, k+1), (c1, k+1), (c1, k) with e1 × e2 = axis.
    if (r0 > 0) {
      v.push_back(on_circle(c0, e1, e2, r0, k, n));
      v.push_back(on_circle(c0, e1, e2, r0, k + 1, n));
    } else {
      v.push_back(c0);
    }
    if (r1 > 0) {
      v.push_back(on_circle(c1, e1, e2, r1, k + 1, n));
      v.push_back(on_circle(c1, e1, e2, r1, k, n));
    } else {
      v.push_back(c1);
    }
    if (v.size() >= 3) t.facets.push_back(facet(name, modifier, where, std::move(v), !outward));
  }
}

}  // namespace

bool is_curved_primitive(std::string_view type) noexcept {
  return type == "sphere" || type == "ring" || type == "cylinder" || type == "tube" || type == "cone" || type == "cup";
}

Tessellation tessellate_primitive(std::string_view type, const std::string& name, const std::string& modifier,
                                  const std::vector<double>& reals, const SourceLocation& where, double relative_deviation) {
  Tessellation t;
  const int n = segments_for(relative_deviation);
  t.segments = n;
  const double sagitta = 1 - std::cos(kPi / n);
  const auto positive = [&](double r, const char* what) {
    if (!(r > 0)) throw input_error(where, std::string(type) + " '" + name + "': the " + what + " must be positive");
  };
  if (type == "sphere") {
    need(reals.size(), 4, type, name, where);
    finite(reals, type, name, where);
    const Vec3 c{reals[0], reals[1], reals[2]};
    const double r = std::abs(reals[3]);
    positive(r, "radius");
    // Latitude bands between the poles about z, inward for a negative radius. A facet spans both
    // directions, so its vertices' angle from its centre is up to √2 times a chord's half-angle:
    // the circles get the segments of half the deviation (the half-angle shrinks by √2).
    const int ns = segments_for(relative_deviation / 2), bands = std::max(4, ns / 2);
    t.segments = ns;
    const Vec3 e1{1, 0, 0}, e2{0, 1, 0};
    for (int b = 0; b < bands; ++b) {
      const double p0 = -kPi / 2 + kPi * b / bands, p1 = -kPi / 2 + kPi * (b + 1) / bands;
      const double r0 = b == 0 ? 0 : r * std::cos(p0), r1 = b + 1 == bands ? 0 : r * std::cos(p1);
      band(t, name, modifier, where, c + Vec3{0, 0, r * std::sin(p0)}, r0, c + Vec3{0, 0, r * std::sin(p1)}, r1, e1, e2, ns,
           reals[3] > 0);
    }
    // The deviation as built: r minus each facet's plane's distance from the centre (its vertices
    // lie on the sphere, so the facet's farthest point from the surface is its plane's foot).
    for (const Polygon& f : t.facets) {
      const Vec3 normal = normalized(newell_normal(f.vertices));
      t.max_deviation = std::max(t.max_deviation, r - std::abs(dot(normal, f.vertices[0] - c)));
    }
    return t;
  }
  if (type == "ring") {
    need(reals.size(), 8, type, name, where);
    finite(reals, type, name, where);
    const Vec3 c{reals[0], reals[1], reals[2]}, axis{reals[3], reals[4], reals[5]};
    const double r0 = reals[6], r1 = reals[7];
    if (!(norm(axis) > 0)) throw input_error(where, "ring '" + name + "': the surface normal is zero");
    if (!(r0 >= 0 && r1 > r0)) throw input_error(where, "ring '" + name + "': the radii must satisfy 0 <= inner < outer");
    Vec3 e1, e2;
    const Vec3 a = normalized(axis);
    frame(a, e1, e2);
    if (r0 == 0) {
      std::vector<Vec3> v;
      for (int k = 0; k < n; ++k) v.push_back(on_circle(c, e1, e2, r1, k, n));
      t.facets.push_back(facet(name, modifier, where, std::move(v), false));
    } else {
      for (int k = 0; k < n; ++k)
        t.facets.push_back(facet(name, modifier, where,
                                 {on_circle(c, e1, e2, r0, k, n), on_circle(c, e1, e2, r1, k, n), on_circle(c, e1, e2, r1, k + 1, n),
                                  on_circle(c, e1, e2, r0, k + 1, n)},
                                 false));
    }
    t.max_deviation = r1 * sagitta;
    return t;
  }
  const bool cone = type == "cone" || type == "cup";
  need(reals.size(), cone ? 8 : 7, type, name, where);
  finite(reals, type, name, where);
  const Vec3 c0{reals[0], reals[1], reals[2]}, c1{reals[3], reals[4], reals[5]};
  const double r0 = cone ? reals[6] : reals[6], r1 = cone ? reals[7] : reals[6];
  if (!(norm(c1 - c0) > 0)) throw input_error(where, std::string(type) + " '" + name + "': its two ends coincide");
  if (cone) {
    if (!(r0 >= 0 && r1 >= 0 && r0 + r1 > 0))
      throw input_error(where, std::string(type) + " '" + name + "': the radii must be non-negative and not both zero");
  } else {
    positive(r0, "radius");
  }
  Vec3 e1, e2;
  frame(normalized(c1 - c0), e1, e2);
  band(t, name, modifier, where, c0, r0, c1, r1, e1, e2, n, type == "cylinder" || type == "cone");
  t.max_deviation = std::max(r0, r1) * sagitta;
  return t;
}

}  // namespace daylit
