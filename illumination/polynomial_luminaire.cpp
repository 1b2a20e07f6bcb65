#include "illumination/polynomial_luminaire.hpp"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "geometry/error.hpp"
#include "illumination/rational_moments.hpp"
#include "illumination/tracked_sum.hpp"

namespace daylit {

namespace {

// A polynomial in the in-plane coordinates (ξ, ζ): coefficient of ξ^a ζ^b at [a][b].
using PlanePolynomial = std::vector<std::vector<long double>>;

PlanePolynomial multiply(const PlanePolynomial& p, const PlanePolynomial& q) {
  const std::size_t n = p.size() + q.size() - 1;
  PlanePolynomial r(n, std::vector<long double>(n, 0.0L));
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t b = 0; b < p[a].size(); ++b) {
      if (p[a][b] == 0) continue;
      for (std::size_t c = 0; c < q.size(); ++c)
        for (std::size_t d = 0; d < q[c].size(); ++d) r[a + c][b + d] += p[a][b] * q[c][d];
    }
  return r;
}

}  // namespace

LuminaireIrradiance polynomial_luminaire_irradiance(const SphericalRegion& region, const Vec3& origin,
                                                    const Vec3& normal, const Vec3& plane_point,
                                                    const Vec3& plane_normal, const ExitancePolynomial& exitance) {
  if (!is_finite(origin) || !is_finite(normal) || !is_finite(plane_point) || !is_finite(plane_normal))
    throw Error("luminaire irradiance: the origin, normals and plane point must be finite");
  if (!(norm(plane_normal) > 0)) throw Error("luminaire irradiance: the plane normal must be non-zero");
  int degree = 0;
  for (const ExitanceTerm& t : exitance) {
    if (t.i < 0 || t.j < 0 || t.k < 0) throw Error("exitance exponents must be ≥ 0");
    if (!std::isfinite(t.coef)) throw Error("exitance coefficients must be finite");
    if (t.coef != 0) degree = std::max(degree, t.i + t.j + t.k);
  }
  if (degree > kMaxExitanceDegree)
    throw Error("exitance of degree " + std::to_string(degree) + " is not supported: above degree " +
                std::to_string(kMaxExitanceDegree) +
                " the recurrences of Theorem 4 lose more digits than __float128 carries");
  const Vec3 N = normalized(plane_normal);
  const double side = dot(N, plane_point - origin);
  if (region.empty() || side == 0 || exitance.empty()) return {0, 0, double_precision, 1};
  const Vec3 w = side > 0 ? N : -N;
  const double h = std::abs(side);
  for (const auto& loop : region.loops)
    for (const Vec3& v : loop)
      if (!(dot(w, v) > 0))
        throw Error("luminaire irradiance: a direction of the region does not meet the luminaire's plane in front "
                    "of the origin");

  // The exitance in in-plane coordinates about the foot of the perpendicular p0 = origin + h w:
  // x = p0 + ξ e1 + ζ e2, each world coordinate an affine form in (ξ, ζ). Long double: the
  // re-expansion cancels where the polynomial is given about a point far from the luminaire.
  const AxisFrame f = frame_about(w);
  const Vec3 p0 = origin + h * w;
  std::array<std::vector<PlanePolynomial>, 3> powers;  // powers[c][i] = (world coordinate c)^i
  for (int c = 0; c < 3; ++c) {
    PlanePolynomial affine(2, std::vector<long double>(2, 0.0L));
    affine[0][0] = p0[c];
    affine[1][0] = f.e1[c];
    affine[0][1] = f.e2[c];
    powers[c].push_back(PlanePolynomial(1, std::vector<long double>(1, 1.0L)));
    for (int i = 1; i <= degree; ++i) powers[c].push_back(multiply(powers[c].back(), affine));
  }
  // With the magnitudes of their terms (tracked_sum.hpp), for the rounding of the re-expansion.
  std::vector<std::vector<real::Tracked<long double>>> m(
      std::size_t(degree) + 1, std::vector<real::Tracked<long double>>(std::size_t(degree) + 1));
  for (const ExitanceTerm& t : exitance) {
    if (t.coef == 0) continue;
    const PlanePolynomial term = multiply(multiply(powers[0][t.i], powers[1][t.j]), powers[2][t.k]);
    for (std::size_t a = 0; a < term.size() && a < m.size(); ++a)
      for (std::size_t b = 0; b < term[a].size() && b < m.size(); ++b) {
        m[a][b].add(t.coef * term[a][b]);
      }
  }

  // E = (1/π) Σ m_ab h^{a+b} ∫ u1^a u2^b (n·u) u3^{−(a+b)} dσ, n·u = n1 u1 + n2 u2 + n3 u3.
  const double n1 = dot(normal, f.e1), n2 = dot(normal, f.e2), n3 = dot(normal, f.w);
  // The (a, b) pairs give three monomials each; `sources` remembers them for the error bound.
  std::vector<FrameMonomial> monomials;
  std::vector<std::pair<int, int>> sources;
  for (int a = 0; a <= degree; ++a)
    for (int b = 0; a + b <= degree; ++b) {
      if (m[a][b].value == 0) continue;
      const long double k = m[a][b].value * std::pow((long double)h, a + b) / std::numbers::pi_v<long double>;
      const int e = -(a + b);
      monomials.push_back({double(k * n1), a + 1, b, e});
      monomials.push_back({double(k * n2), a, b + 1, e});
      monomials.push_back({double(k * n3), a, b, e + 1});
      for (int i = 0; i < 3; ++i) sources.emplace_back(a, b);
    }
  std::vector<double> values;
  const RationalMoment r = frame_polynomial_moment(region, f.e1, f.e2, f.w, monomials, &values);
  // Each m_ab carries a rounding error of about 8 u |m|_ab (long double sums of products of
  // the coordinates' powers): where the exitance is given about a point far from the luminaire,
  // these cancel and dominate everything else.
  long double reexpansion = 0;
  for (std::size_t i = 0; i < monomials.size(); i += 3) {
    const auto [a, b] = sources[i];
    const long double k = m[a][b].magnitude * std::pow((long double)h, a + b) / std::numbers::pi_v<long double>;
    reexpansion += k * std::abs(n1 * values[i] + n2 * values[i + 1] + n3 * values[i + 2]);
  }
  const double reexpansion_error = double(8 * 0x1p-64L * reexpansion) / std::abs(r.value);
  return {r.value, r.relative_error + reexpansion_error, r.precision, r.condition};
}

}  // namespace daylit
