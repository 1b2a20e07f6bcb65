#pragma once
// The altitude and azimuth of many directions at once: what the reflection operator's hat
// functions over a grid of directions (annual_reflections.cpp, node_columns) ask of every node of
// its product rule (175 million on the office sample's 10,308 nodes). Four directions at a time
// with glibc's vector asin and atan2 where GCC on x86-64 has them (as sky/circumsolar_sum.hpp);
// the plain loop elsewhere. Results differ from std::asin and std::atan2 by rounding only
// (libmvec's error bound: 4 ulp).

#include <cstddef>

namespace daylit {

// For unit directions (x[i], y[i], z[i]): altitude[i] = asin(clamp(z, 0, 1)) ∈ [0, π/2] and
// azimuth[i] = atan2(y, x) taken to [0, 2π).
void altitude_azimuth(const double* x, const double* y, const double* z, double* altitude, double* azimuth,
                      std::size_t n) noexcept;

}  // namespace daylit
