#pragma once
// The integrand of log_cosine_arc_integral.hpp in t = tan s, f(t) = −log1p(Q/c²)/(2Q) with
// Q = κ² + t² (f = −1/(2c²) at Q = 0, its limit), at many nodes at once: glibc's vector log1p
// (illumination/vector_math.hpp: within 4 ulp, where the scalar function is within 1) where the
// build has it, the scalar loop elsewhere. Nodes past `n` up to the next multiple of 4 are read
// and written too (a whole vector), so both arrays must hold that many.

#include <cstddef>

namespace daylit::rational {

void log_cosine_integrand(const double* t, std::size_t n, double kappa2, double c2, double* out) noexcept;

}  // namespace daylit::rational
