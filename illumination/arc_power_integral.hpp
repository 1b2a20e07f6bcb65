#pragma once
// Integrals of powers of a cosine along a great arc: ∫_arc (w·u)^k ds, k = 0..K.

#include <vector>

#include "illumination/arc_edge.hpp"

namespace daylit {

// G[k] = ∫_0^θ (w·u(t))^k dt for k = 0..k_max, u(t) = a cos t + s sin t the arc (Arvo 1995,
// eq. 18). With X = w·a, Y = w·b and the tangent components β = w·s_a, γ = w·s_b at the two ends,
// integration by parts (Arvo's eq. 19, multiplied through by c^k) gives the upward recurrence
//     G[k] = (X^{k−1} β − Y^{k−1} γ + (k − 1) |w⊥|² G[k−2]) / k,
// where |w⊥|² = (w·a)² + (w·s_a)² is the squared length of w's projection onto the arc's plane;
// G[0] = θ and G[1] = X sin θ + β (1 − cos θ). O(k_max) per edge. The terms decrease in
// magnitude (Arvo §5.4), so the upward recurrence does not amplify its own rounding.
template <class R>
void arc_power_integrals(const ArcEdge<R>& arc, const real::V3<R>& w, int k_max, std::vector<R>& G) {
  G.assign(std::size_t(k_max) + 1, R(0));
  G[0] = arc.length;
  if (k_max == 0) return;
  const R X = dot(w, arc.start);
  const R Y = dot(w, arc.end);
  const R beta = dot(w, arc.start_tangent);
  const R gamma = dot(w, arc.end_tangent);
  G[1] = X * arc.sin_length + beta * arc.one_minus_cos;
  const R c2 = X * X + beta * beta;
  R Xp = X, Yp = Y;  // X^{k−1}, Y^{k−1} for k = 2
  for (int k = 2; k <= k_max; ++k) {
    G[k] = (Xp * beta - Yp * gamma + R(k - 1) * c2 * G[k - 2]) / R(k);
    Xp *= X;
    Yp *= Y;
  }
}

}  // namespace daylit
