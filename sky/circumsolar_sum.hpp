#pragma once
// The Perez sky's circumsolar term summed over the fixed nodes of a quadrature rule: the hot loop
// of an annual run (simulation/annual.hpp), where each sensor's rule is evaluated in every hour.
//
//   Σ_i w_i G(t_i) c e^{d γ_i},  G(t) = 1 + a e^{b/t},  t_i = max(u_z,i, t_min),  γ_i = acos(s·u_i)
//
// (Perez, Seals and Michalsky 1993, eq. 1: the circumsolar factor times the gradation), over nodes
// above the horizon (u_z > 0: the sky has none below, and a node there is not to be added). The nodes are kept as arrays of coordinates so that the
// sum runs four directions at a time: with GCC on x86-64 the exponentials and arc cosines come from
// glibc's vector math library (libmvec, within 4 ulp), with an AVX2 version chosen at run time
// where the processor has it (measured on the development machine: 5.6 against 25 ns per node);
// elsewhere it is the plain loop. γ is taken as acos(s·u), not atan2(|s × u|, s·u): near the sun
// it loses relative accuracy, but its absolute error (≈ ε / sin γ, below 1e-8 rad unless u is
// within 1e-8 of the sun) moves e^{dγ} by far less than any tolerance asked of these sums. The order of the additions differs from a loop node by node, so
// results differ from it by rounding only.

#include <cstddef>
#include <vector>

#include "geometry/vec3.hpp"

namespace daylit {

struct DirectionNodes {
  std::vector<double> x, y, z, weight;
  void push_back(const Vec3& u, double w) {  // u_z > 0
    x.push_back(u.x);
    y.push_back(u.y);
    z.push_back(u.z);
    weight.push_back(w);
  }
  std::size_t size() const noexcept { return weight.size(); }
};

// The sum above over the nodes [begin, end), for the sky's sun s (unit) and coefficients a, b, c,
// d; t_min the floor on cos θ (0 for the published model, Radiance's 0.01 under its clamps).
double circumsolar_sum(const DirectionNodes& nodes, std::size_t begin, std::size_t end, const Vec3& sun, double a,
                       double b, double c, double d, double t_min) noexcept;

// The term itself, c G(t) e^{dγ}, at n directions (values[i]; 0 where u_z ≤ 0): the integrand of
// the adaptive cubature near the sun, given its 16 directions at a time.
void circumsolar_values(const double* x, const double* y, const double* z, std::size_t n, const Vec3& sun, double a,
                        double b, double c, double d, double t_min, double* values) noexcept;

}  // namespace daylit
