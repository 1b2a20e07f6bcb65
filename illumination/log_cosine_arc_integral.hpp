#pragma once
// The integral Λ(c, s1) − Λ(c, s0) = ∫_{s0}^{s1} log(c cos s)/(1 − c² cos² s) ds along one arc in
// the frame of w (Chen and Arvo 2000, eqs. 33–34; WFrameArc in rational_edge.hpp), by Gauss–
// Legendre quadrature where the arc is short beside its distance from w's horizon.
//
// Why: eq. 36 gives each Λ from three Clausen integrals of O(1) size, so on an arc of length θ the
// difference of the two brackets cancels like 1/θ. A radiosity element of size s seen from d away
// has θ ≈ s/d, and its Stokes sum cancels by another 1/θ; on a refined mesh (s/d ≈ 0.02) that
// cancellation sent 8 % of the node–element pairs of the room sample to long double (25 % of the
// run). The integrand itself has one sign, so a quadrature of it does not cancel at all.
//
// The integrand in one piece: with q = 1 − c² cos² s = κ² + c² sin² s (κ = |w·m| = √(1 − c²),
// both given to full relative precision), it is φ(q) = log(1 − q)/(2q), φ(0) = −½. q is a sum of
// two non-negative terms, so the node values are good to a few ulp; log(1 − q) is taken as
// log1p(−q) for q ≤ ½ and as 2 log(c cos s) beyond (where 1 − q would lose digits). φ ≤ −½.
//
// The rule: φ(q(s)) is analytic except where cos s = 0 (q = 1; log's branch cut runs along
// Re s = ±π/2), so on an arc of half-length h whose nearer end is D from ±π/2 it is analytic in the
// Bernstein ellipse with ρ = t + √(t² − 1), t = 1 + D/h, and the n-point rule's error falls like
// ρ^{−2n} (Trefethen, Approximation Theory and Approximation Practice, thm. 19.3). n is the least
// with ρ^{2n} ≥ 2^{10}/u (a thousandfold margin for the constant of the theorem and the size of φ
// on the ellipse against its size on the arc, checked against the brackets in __float128 in
// tests/illumination/test_log_cosine_arc_integral.cpp); arcs that would need more than
// kMaxNodes, or that come within 1/16 rad of the horizon (where an ulp of s is a large part of the
// distance to the singularity), return nothing and the caller takes the brackets.

#include <array>
#include <cmath>
#include <optional>
#include <type_traits>

#include "illumination/gauss_legendre.hpp"
#include "illumination/rational_edge.hpp"

namespace daylit::rational {

namespace log_cosine_detail {

constexpr int kMaxNodes = 16;
constexpr double kHorizonMargin = 1.0 / 16;

// The rules of 1…kMaxNodes points on [−1, 1] in R, and the least t = 1 + D/h each one serves.
template <class R>
struct Rules {
  std::array<std::array<R, kMaxNodes>, kMaxNodes + 1> x{}, w{};
  std::array<R, kMaxNodes + 1> min_t{};
  Rules() {
    const long double target = 1024.0L / (long double)real::unit_roundoff<R>();
    for (int n = 1; n <= kMaxNodes; ++n) {
      const quadrature::GaussLegendreRule rule = quadrature::gauss_legendre(n);
      for (int i = 0; i < n; ++i) x[n][i] = R(rule.x[std::size_t(i)]), w[n][i] = R(rule.w[std::size_t(i)]);
      const long double rho = std::pow(target, 1.0L / (2 * n));
      min_t[n] = R((rho + 1 / rho) / 2);
    }
  }
};

}  // namespace log_cosine_detail

// ∫_{s0}^{s1} log(c cos s)/(1 − c² cos² s) ds over the arc e and its magnitude (for R = double
// and long double; the rule's nodes are long double's), or nothing where the rule does not serve.
template <class R>
std::optional<Tracked<R>> log_cosine_arc_integral(const WFrameArc<R>& e) {
  using namespace log_cosine_detail;
  static_assert(std::is_same_v<R, double> || std::is_same_v<R, long double>);
  static const Rules<R> rules;
  const R half_pi = real::pi<R>() / 2;
  const R s0 = real::atan2(e.sin0, e.cos0);  // cos s0 > 0 on the arc: s0 ∈ (−π/2, π/2)
  const R h = e.arc.length / 2, mid = s0 + h;
  const R distance = half_pi - (real::abs(mid) + h);  // from the nearer end to ±π/2
  if (!(distance >= R(kHorizonMargin)) || !(h > 0)) return std::nullopt;
  const R t = 1 + distance / h;
  int n = 1;
  while (n <= kMaxNodes && t < rules.min_t[n]) ++n;
  if (n > kMaxNodes) return std::nullopt;
  const R c = e.c, kappa = e.kappa(), kappa2 = kappa * kappa;
  // φ at the node of angle s from sin s and cos s.
  auto phi = [&](R sin_s, R cos_s) {
    const R q = kappa2 + c * c * sin_s * sin_s;
    if (q == 0) return R(-0.5);
    return q <= R(0.5) ? real::log1p(-q) / (2 * q) : real::log(c * cos_s) / q;
  };
  // The nodes come in pairs mid ± δ (the rule is symmetric): their sines and cosines by the
  // angle-addition formulas from mid's and δ's, one sincos per pair. Their absolute error of a few
  // ulp moves q by as much, which φ (Lipschitz where q ≤ ½) and log(c cos s) (cos s ≥ sin D there)
  // take as a few ulp relative, within the 1/D below.
  const R sin_mid = real::sin(mid), cos_mid = real::cos(mid);
  R sum = n % 2 ? rules.w[n][n / 2] * phi(sin_mid, cos_mid) : R(0);
  for (int i = 0; i < n / 2; ++i) {
    const R delta = h * rules.x[n][i], sin_d = real::sin(delta), cos_d = real::cos(delta);
    const R a = sin_mid * cos_d, b = cos_mid * sin_d, ca = cos_mid * cos_d, cb = sin_mid * sin_d;
    sum += rules.w[n][i] * (phi(a + b, ca - cb) + phi(a - b, ca + cb));
  }
  const R value = h * sum;
  // Every term has φ's sign, so the sum's rounding is a few ulp of itself; the node values carry
  // a few ulp of their own and the nodes' positions an ulp of s, which moves φ by at most
  // u·|s|/D relative (φ's logarithmic growth towards the horizon): hence 2 + 1/D.
  return Tracked<R>{value, real::abs(value) * (2 + 1 / distance)};
}

}  // namespace daylit::rational
