#pragma once
// Moments ∫_A Π_k (a_k·u)^{p_k} dσ(u) of a region of directions for the factor patterns that
// have closed forms here, dispatched to Arvo's axial and double-axis moments.

#include <vector>

#include "geometry/spherical_region.hpp"

namespace daylit {

struct Factor {
  Vec3 axis;  // need not be a unit vector: (a·u)^p = |a|^p (â·u)^p
  int power;  // ≥ 0
};

struct FactorMoment {
  double value;
  double relative_error;  // estimate from the kernels' cancellation check (moments.hpp)
};

// Patterns (after dropping powers 0): () the solid angle; (n) the axial moment (Arvo eq. 11);
// (n, 1) in either order the double-axis moment (eq. 14); (n, 1, 1) by Chen and Arvo's eq. 29
// (moments.hpp). All O(n·edges) closed forms, accurate at every order. Others throw
// daylit::Error naming the pattern. Throws as well when |a|^p overflows (an underflow gives 0).
FactorMoment factor_moment(const SphericalRegion& region, std::vector<Factor> factors);

}  // namespace daylit
