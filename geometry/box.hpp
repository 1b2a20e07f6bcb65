#pragma once
// An axis-aligned box, grown point by point: the bound of the culling hierarchy's nodes
// (visibility.cpp) and of the panes compared for lying in one plane (coplanar_panes.cpp).

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
  Vec3 center() const { return 0.5 * (lo + hi); }
  Vec3 half() const { return 0.5 * (hi - lo); }
};

}  // namespace daylit
