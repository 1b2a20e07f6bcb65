#include "illumination/solid_angle.hpp"

namespace daylit {

namespace {

// Below this cosine a diagonal is nearly opposite (as nearly_opposite(), spherical_region.hpp).
constexpr double kOppositeCosine = -0.9;

// The lowest cosine between u[k] and the vertices it is not adjacent to (the fan's diagonals
// from k), on unit vectors.
double worst_diagonal_cosine(const std::vector<Vec3>& u, std::size_t k) {
  const std::size_t m = u.size();
  double worst = 1;
  for (std::size_t i = 2; i + 1 < m; ++i) worst = std::min(worst, dot(u[k], u[(k + i) % m]));
  return worst;
}

}  // namespace

FanApex fan_apex(const DirectionLoop& loop) noexcept {
  const std::size_t m = loop.size();
  // The common case first: no diagonal from v0 nearly opposite it (the lengths are taken only for
  // obtuse diagonals: a small, distant polygon has none).
  bool first_is_fine = true;
  for (std::size_t j = 2; j + 1 < m && first_is_fine; ++j) first_is_fine = !nearly_opposite(loop[0], loop[j]);
  if (first_is_fine) return {};
  std::vector<Vec3> u(m);
  for (std::size_t i = 0; i < m; ++i) u[i] = normalized(loop[i]);
  FanApex best;
  double best_cosine = worst_diagonal_cosine(u, 0);
  for (std::size_t k = 1; k < m; ++k)
    if (const double c = worst_diagonal_cosine(u, k); c > best_cosine) {
      best_cosine = c;
      best.vertex = k;
    }
  if (best_cosine >= kOppositeCosine) return best;
  // Every vertex has a nearly opposite one: a direction inside, from the edges' unit normals.
  Vec3 pole{};
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3 normal = cross(u[i], u[(i + 1) % m]);
    if (const double length = norm(normal); length > 0) pole = pole + normal / length;
  }
  if (!(norm(pole) > 0)) return best;
  pole = normalized(pole);
  // A negatively oriented loop's normals point away from it: the pole is then turned round.
  double side = 0;
  for (const Vec3& v : u) side += dot(pole, v);
  if (side < 0) pole = -pole;
  double worst = 1;
  for (const Vec3& v : u) worst = std::min(worst, dot(pole, v));
  if (worst <= best_cosine) return best;
  return {0, true, pole};
}

double solid_angle(const DirectionLoop& loop) noexcept {
  double sum = 0;
  for_each_solid_angle_term<double>(loop, [&](double term) { sum += term; });
  return sum;
}

double solid_angle(const SphericalRegion& region) noexcept {
  double sum = 0;
  for (const auto& loop : region.loops) sum += solid_angle(loop);
  return sum;
}

}  // namespace daylit
