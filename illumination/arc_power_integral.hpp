#pragma once
// Integrals of powers of a cosine along a great arc: ∫_arc (w·u)^k ds, k = 0..K.

#include <vector>

#include "illumination/arc_edge.hpp"

namespace daylit {

// G[k] = ∫_0^θ (w·u(t))^k dt for k = 0..k_max, u(t) = a cos t + s sin t the arc (Arvo 1995,
// eq. 18). With X = w·a, Y = w·b and the tangent components β = w·s_a, γ = w·s_b at the two ends,
// integration by parts of eq. 19, multiplied through by c^k, gives the upward recurrence
//     G[k] = (X^{k−1} β − Y^{k−1} γ + (k − 1) |w⊥|² G[k−2]) / k,
// where |w⊥|² = (w·a)² + (w·s_a)² is the squared length of w's projection onto the arc's plane;
// G[0] = θ and G[1] = X sin θ + β (1 − cos θ). O(k_max) per edge. The upward recurrence is
// stable in the sense of Arvo §5.4 (|G[k]| decreases); cancellation at high orders on arcs far
// from w is the business of the stable forms in the kernel issue.
void arc_power_integrals(const ArcEdge& arc, const Vec3& w, int k_max, std::vector<double>& G);

}  // namespace daylit
