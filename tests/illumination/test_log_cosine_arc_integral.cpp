// The quadrature of ∫ log(c cos s)/(1 − c² cos² s) ds along short arcs (log_cosine_arc_integral.hpp)
// against the same integral from Chen and Arvo's closed form, eq. 36's brackets, evaluated in
// __float128 on the same arc (their Clausen integrals are checked against MPFR in test_clausen.cpp;
// the brackets' difference cancels like 1/θ, which __float128's 1e-34 leaves far below the
// tolerances here for θ ≥ 1e-9).

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "illumination/log_cosine_arc_integral.hpp"

using namespace daylit;
using rational::WFrameArc;

namespace {

constexpr double pi = 3.14159265358979323846;

// The arc from s0 to s0 + θ of the great circle whose normal m has w·m = κ, in w = +z's frame:
// u(s) = p cos s + q sin s with p = (w − κ m)/c, q = m × p, so that w·u = c cos s.
struct ArcCase {
  Vec3 from, to;
};
ArcCase make_arc(double kappa, double s0, double theta, double azimuth) {
  const double c = std::sqrt((1 - kappa) * (1 + kappa));
  const Vec3 m{c * std::cos(azimuth), c * std::sin(azimuth), kappa};
  const Vec3 w{0, 0, 1};
  const Vec3 p = (1 / c) * (w - kappa * m);
  const Vec3 q = cross(m, p);
  auto u = [&](double s) { return std::cos(s) * p + std::sin(s) * q; };
  return {u(s0), u(s0 + theta)};
}

#if DAYLIT_HAVE_FLOAT128
// (bracket(s1) − bracket(s0))/(4κ) = Λ(c, s1) − Λ(c, s0) in __float128 on the arc between the
// same double endpoints, and its own error: the brackets' terms are O(1) and their difference
// O(κθ), so where κθ is below 1e-16 even __float128 leaves ~1e-18 of it (16 ulp of the terms'
// magnitudes, divided by 4κ).
struct Reference {
  double value, error;
};
Reference reference(const ArcCase& a) {
  using Q = real::quad;
  const auto arc = arc_edge(real::V3<Q>(a.from), real::V3<Q>(a.to));
  REQUIRE(arc);
  const WFrameArc<Q> f(*arc, real::V3<Q>(Vec3{0, 0, 1}));
  const auto b1 = lambda_bracket_tracked<Q>(f.c, f.kappa(), f.sin1, f.cos1);
  const auto b0 = lambda_bracket_tracked<Q>(f.c, f.kappa(), f.sin0, f.cos0);
  const Q scale = 4 * f.kappa();
  return {double((b1.value - b0.value) / scale),
          double(16 * real::unit_roundoff<Q>() * (b1.magnitude + b0.magnitude) / scale)};
}

template <class R>
std::optional<real::Tracked<R>> quadrature(const ArcCase& a) {
  const auto arc = arc_edge(real::V3<R>(a.from), real::V3<R>(a.to));
  REQUIRE(arc);
  return rational::log_cosine_arc_integral(WFrameArc<R>(*arc, real::V3<R>(Vec3{0, 0, 1})));
}
#endif

}  // namespace

#if DAYLIT_HAVE_FLOAT128
TEST_CASE("the quadrature along a short arc agrees with the closed form, within its own estimate", "[clausen]") {
  // Arcs of every length the rule serves (down to 1e-9 rad), every distance from w (c from 1e-6
  // to 1, κ from 1e-9 to 1 − 1e-12) and from the horizon (down to the rule's 1/16 rad margin).
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> unit(0, 1);
  int served = 0, served_long = 0;
  double worst_ratio = 0;
  for (int i = 0; i < 20000; ++i) {
    const double kappa = i % 5 == 0 ? std::pow(10.0, -9 * unit(rng)) : i % 5 == 1 ? 1 - std::pow(10.0, -12 * unit(rng)) : unit(rng);
    const double theta = std::pow(10.0, -9 * unit(rng)) * (i % 3 == 0 ? 1.5 : 0.5);
    const double s0 = (pi / 2 - 0.06) * (2 * unit(rng) - 1);
    if (std::abs(s0 + theta) >= pi / 2 - 0.06 || kappa <= 0 || kappa >= 1) continue;
    const ArcCase a = make_arc(kappa, s0, theta, 2 * pi * unit(rng));
    const auto d = quadrature<double>(a);
    if (!d) continue;
    ++served;
    const Reference r = reference(a);
    const double ref = r.value;
    // The estimate the precision ladder applies to it (precision_escalation.hpp: (10 + order)·u
    // times the magnitude, order ≥ 0): the error must be within it.
    const double error = std::abs(d->value - ref), estimate = 10 * 0x1p-53 * d->magnitude;
    INFO("kappa " << kappa << " s0 " << s0 << " theta " << theta << " value " << d->value << " ref " << ref);
    CHECK(error <= estimate + r.error);
    worst_ratio = std::max(worst_ratio, (error - r.error) / (0x1p-53 * std::abs(ref)));
    // Long double (which needs more nodes, so serves fewer arcs): within its own (2^11 times
    // smaller) unit, beside the rounding of it and the reference to double.
    if (const auto l = quadrature<long double>(a)) {
      ++served_long;
      CHECK(std::abs(double(l->value) - ref) <= 10 * 0x1p-64 * double(l->magnitude) + 0x1p-52 * std::abs(ref) + r.error);
    }
  }
  // Most of these arcs are short enough for the rule; in ulps of the result the error stays small
  // (the 1/θ of the brackets in double would be up to 1e9 ulp here).
  CHECK(served > 10000);
  CHECK(served_long > 10000);
  CHECK(worst_ratio < 64);
}
#endif

TEST_CASE("the quadrature declines long arcs and arcs near the horizon", "[clausen]") {
  auto served = [](double kappa, double s0, double theta) {
    const ArcCase a = make_arc(kappa, s0, theta, 0.3);
    const auto arc = arc_edge(real::V3<double>(a.from), real::V3<double>(a.to));
    REQUIRE(arc);
    return rational::log_cosine_arc_integral(WFrameArc<double>(*arc, real::V3<double>(Vec3{0, 0, 1}))).has_value();
  };
  CHECK(served(0.5, 0.1, 1e-3));
  CHECK_FALSE(served(0.5, -1.0, 2.0));              // long: its ellipse reaches the horizon
  CHECK_FALSE(served(0.5, pi / 2 - 0.05, 1e-4));    // ends 0.05 rad from the horizon
  CHECK(served(0.5, pi / 2 - 0.2, 1e-4));
}
