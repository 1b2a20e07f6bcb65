#include "illumination/arc_power_integral.hpp"

namespace daylit {

void arc_power_integrals(const ArcEdge& arc, const Vec3& w, int k_max, std::vector<double>& G) {
  G.assign(std::size_t(k_max) + 1, 0.0);
  G[0] = arc.length;
  if (k_max == 0) return;
  const double X = dot(w, arc.start);
  const double Y = dot(w, arc.end);
  const double beta = dot(w, arc.start_tangent);
  const double gamma = dot(w, arc.end_tangent);
  G[1] = X * arc.sin_length + beta * arc.one_minus_cos;
  const double c2 = X * X + beta * beta;
  double Xp = X, Yp = Y;  // X^{k−1}, Y^{k−1} for k = 2
  for (int k = 2; k <= k_max; ++k) {
    G[k] = (Xp * beta - Yp * gamma + (k - 1) * c2 * G[k - 2]) / k;
    Xp *= X;
    Yp *= Y;
  }
}

}  // namespace daylit
