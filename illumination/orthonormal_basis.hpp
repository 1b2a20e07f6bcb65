#pragma once
// An orthonormal basis of the plane perpendicular to a unit vector: the frames the samplers draw
// directions in (the kernels' Monte Carlo and the sky baselines) and the frame (e1, e2, w) of the
// rational moments (rational_moments.hpp).

#include <cmath>

#include "geometry/vec3.hpp"
#include "illumination/real_vector.hpp"

namespace daylit {

// {e1, e2} with {e1, e2, n} right-handed and orthonormal, for unit n, in precision R, without a
// branch on a small component: Duff et al., "Building an orthonormal basis, revisited", JCGT 6(1),
// 2017, listing 3. Orthonormal to a few ulp of R for every unit n (including n = ±z).
template <class R>
struct PerpendicularBasis {
  real::V3<R> e1, e2;
};
template <class R>
PerpendicularBasis<R> perpendicular_basis(const real::V3<R>& n) noexcept {
  // copysign(1, n.z), written for every R (the sign of a zero survives the conversion to double).
  const R s = std::signbit(double(n.z)) ? R(-1) : R(1);
  const R a = R(-1) / (s + n.z);
  const R b = n.x * n.y * a;
  return {{1 + s * n.x * n.x * a, s * b, -s * n.x}, {b, s + n.y * n.y * a, -n.y}};
}

inline void orthonormal_basis(const Vec3& n, Vec3& e1, Vec3& e2) noexcept {
  const PerpendicularBasis<double> f = perpendicular_basis(real::V3<double>(n));
  e1 = {f.e1.x, f.e1.y, f.e1.z};
  e2 = {f.e2.x, f.e2.y, f.e2.z};
}

}  // namespace daylit
