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
// The integrand in t = tan s, which needs no trigonometric function at the nodes (sines and
// cosines of the nodes were most of the cost in s): with cos² s = 1/(1 + t²), ds = dt/(1 + t²)
// and κ² = 1 − c² (κ = |w·m|),
//     ∫ log(c cos s)/(1 − c² cos² s) ds = ∫_{t0}^{t1} f(t) dt,   f(t) = −log1p(Q/c²)/(2Q),
// Q = κ² + t² (log c − ½ log(1 + t²) = −½ log((1 + t²)/c²) and (1 + t²)/c² = 1 + Q/c²). Q is a
// sum of two non-negative terms, so the node values are good to a few ulp; f(0) = −1/(2c²) at
// Q = 0, where f is analytic (log1p(x)/x is).
//
// The rule: f is analytic except where Q/c² = −1, i.e. t² = −1: branch points at t = ±i, cuts
// along the imaginary axis beyond them. On [t0, t1] of half-length H whose nearest point to ±i is
// D away (D² = 1 + the distance of the interval from 0, squared), f is analytic in the Bernstein
// ellipse with ρ = a + √(a² − 1), a = 1 + D/H (that ellipse lies within D of the interval), and
// the n-point rule's error falls like ρ^{−2n} (Trefethen, Approximation Theory and Approximation
// Practice, thm. 19.3). n is the least with ρ^{2n} ≥ 2^{14}/u (a margin for the constant of
// the theorem and the size of f on the ellipse against its size on the interval, checked against
// the brackets in __float128 in tests/illumination/test_log_cosine_arc_integral.cpp: the worst
// error there is 11 ulp; with 2^{10}, 40–50 ulp on the longest arcs the rule serves, whose
// ellipse passes close to the logarithmic branch points);
// arcs that would need more than kMaxNodes, or that come within 1/16 rad of the horizon (|t| ≥
// cot(1/16): there an ulp of an endpoint's cosine is a large part of it), return nothing and the
// caller takes the brackets.
//
// H is taken as sin θ/(2 cos s0 cos s1) (= (t1 − t0)/2 without its cancellation), with the sine
// of the arc's length θ as arc_edge gives it, to full relative precision: a short arc's integral is
// as accurate as its length, not as the difference of its endpoints' tangents.

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <type_traits>

#include "illumination/gauss_legendre.hpp"
#include "illumination/log_cosine_integrand.hpp"
#include "illumination/rational_edge.hpp"

namespace daylit::rational {

namespace log_cosine_detail {

constexpr int kMaxNodes = 16;
constexpr double kHorizonMargin = 1.0 / 16;

// The rules of 1…kMaxNodes points on [−1, 1] in R, and the least a = 1 + D/H each one serves.
template <class R>
struct Rules {
  std::array<std::array<R, kMaxNodes>, kMaxNodes + 1> x{}, w{};
  std::array<R, kMaxNodes + 1> min_a{};
  Rules() {
    const long double target = 16384.0L / (long double)real::unit_roundoff<R>();
    for (int n = 1; n <= kMaxNodes; ++n) {
      const quadrature::GaussLegendreRule rule = quadrature::gauss_legendre(n);
      for (int i = 0; i < n; ++i) x[n][i] = R(rule.x[std::size_t(i)]), w[n][i] = R(rule.w[std::size_t(i)]);
      const long double rho = std::pow(target, 1.0L / (2 * n));
      min_a[n] = R((rho + 1 / rho) / 2);
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
  static const R max_tangent = R(1) / std::tan(R(kHorizonMargin));
  // cos s > 0 on the arc, s1 = s0 + θ.
  const R t0 = e.sin0 / e.cos0, t1 = e.sin1 / e.cos1;
  const R reach = std::max(real::abs(t0), real::abs(t1));
  if (!(reach < max_tangent)) return std::nullopt;
  const R h = e.arc.sin_length / (2 * e.cos0 * e.cos1), mid = (t0 + t1) / 2;
  if (!(h > 0)) return std::nullopt;
  const R nearest = t0 > 0 ? t0 : (t1 < 0 ? -t1 : R(0));
  const R a = 1 + real::sqrt(1 + nearest * nearest) / h;
  int n = 1;
  while (n <= kMaxNodes && a < rules.min_a[n]) ++n;
  if (n > kMaxNodes) return std::nullopt;
  const R c2 = e.c * e.c, kappa = e.kappa(), kappa2 = kappa * kappa;
  // The nodes in pairs mid ± δ_i, then mid where n is odd; their values f(t) all at once in double
  // (log_cosine_integrand.hpp: the vector log1p), one by one in long double.
  std::array<R, kMaxNodes + 3> t{}, f{};
  for (int i = 0; i < n / 2; ++i) {
    const R delta = h * rules.x[n][i];
    t[std::size_t(2 * i)] = mid + delta;
    t[std::size_t(2 * i + 1)] = mid - delta;
  }
  if (n % 2) t[std::size_t(n - 1)] = mid;
  if constexpr (std::is_same_v<R, double>) {
    log_cosine_integrand(t.data(), std::size_t(n), kappa2, c2, f.data());
  } else {
    for (int i = 0; i < n; ++i) {
      const R q = kappa2 + t[std::size_t(i)] * t[std::size_t(i)];
      f[std::size_t(i)] = q == 0 ? R(-0.5) / c2 : -real::log1p(q / c2) / (2 * q);
    }
  }
  R sum = n % 2 ? rules.w[n][n / 2] * f[std::size_t(n - 1)] : R(0);
  for (int i = 0; i < n / 2; ++i) sum += rules.w[n][i] * (f[std::size_t(2 * i)] + f[std::size_t(2 * i + 1)]);
  const R value = h * sum;
  // Every term has f's sign, so the sum's rounding is a few ulp of itself. The nodes' values carry
  // a few ulp of their own (the vector log1p up to 4, where the scalar one is within 1), and their
  // positions an ulp of t, which moves f by at most 2 ulp relative (|t f′/f| ≤ 2: log1p(x)/x has
  // logarithmic derivative between −1/x and 0); h carries an ulp of each cosine, relative
  // 1/cos = √(1 + t²) ≤ 1 + |t| ulp: hence 6 + reach.
  return Tracked<R>{value, real::abs(value) * (6 + reach)};
}

}  // namespace daylit::rational
