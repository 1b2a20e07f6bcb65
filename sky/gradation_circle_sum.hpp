#pragma once
// The inner sum of the Perez sky's normalisation (PerezSky, sky/perez_sky.cpp): the gradation
// times cos θ over the nodes of one arc of a circle about the sun,
//
//   Σ_j w_j G(t_j) t_j,   t_j = max(A + B cos(ψ_lo + h x_j), 0),   G(t) = 1 + a e^{b / max(t, t_floor)}
//
// (Perez, Seals and Michalsky 1993, eq. 1's gradation; A = cos γ sin α, B = sin γ cos α about a sun
// at altitude α). t_floor > 0: Radiance's floor cos θ ≥ 0.01, or the least normal double where
// there is none, so that a node on the horizon (t = 0) gives G·t = 0, the limit for b ≤ 0 (b > 0
// occurs only under the floor). Four nodes at a time with glibc's vector cos and exp where GCC on
// x86-64 has them (as sky/circumsolar_sum.hpp); the plain loop elsewhere. Results differ from a
// loop node by node by rounding only.

#include <cstddef>

namespace daylit {

double gradation_circle_sum(const double* x, const double* w, std::size_t n, double psi_lo, double h, double A,
                            double B, double a, double b, double t_floor) noexcept;

}  // namespace daylit
