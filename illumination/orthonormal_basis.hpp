#pragma once
// An orthonormal basis of the plane perpendicular to a unit vector, for the samplers that draw
// directions about an axis (the kernels' Monte Carlo and the sky baselines).

#include <cmath>

#include "geometry/vec3.hpp"

namespace daylit {

// {e1, e2} with {e1, e2, n} right-handed and orthonormal, for unit n, without a branch on a small
// component: Duff et al., "Building an orthonormal basis, revisited", JCGT 6(1), 2017, listing 3.
inline void orthonormal_basis(const Vec3& n, Vec3& e1, Vec3& e2) noexcept {
  const double s = std::copysign(1.0, n.z);
  const double a = -1.0 / (s + n.z);
  const double b = n.x * n.y * a;
  e1 = {1 + s * n.x * n.x * a, s * b, -s * n.x};
  e2 = {b, s + n.y * n.y * a, -n.y};
}

}  // namespace daylit
