#pragma once
// An axis-aligned box, grown point by point: the bound of the culling hierarchy's nodes
// (visibility.cpp), of the panes compared for lying in one plane (coplanar_panes.cpp), and of the
// sensors and apertures a radiosity mesh is graded towards (reflected_components.cpp).

#include <algorithm>
#include <cmath>

#include "geometry/vec3.hpp"

namespace daylit {

struct Box {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void add(const Vec3& v) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  void add(const Box& b) {
    add(b.lo);
    add(b.hi);
  }
  bool empty() const { return !(lo.x <= hi.x); }
  Vec3 center() const { return 0.5 * (lo + hi); }
  Vec3 half() const { return 0.5 * (hi - lo); }
  double longest_side() const { return empty() ? 0 : std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}); }
  // Whether the two boxes, each grown by `margin`, meet.
  bool meets(const Box& o, double margin) const {
    return lo.x - margin <= o.hi.x && o.lo.x - margin <= hi.x && lo.y - margin <= o.hi.y &&
           o.lo.y - margin <= hi.y && lo.z - margin <= o.hi.z && o.lo.z - margin <= hi.z;
  }
  // Squared distance from p to the box (0 inside), and the distance.
  double distance2(const Vec3& p) const {
    double d = 0;
    for (int k = 0; k < 3; ++k) {
      const double e = std::max({lo[k] - p[k], 0.0, p[k] - hi[k]});
      d += e * e;
    }
    return d;
  }
  double distance(const Vec3& p) const {
    return std::hypot(std::max({lo.x - p.x, 0.0, p.x - hi.x}), std::max({lo.y - p.y, 0.0, p.y - hi.y}),
                      std::max({lo.z - p.z, 0.0, p.z - hi.z}));
  }
};

}  // namespace daylit
