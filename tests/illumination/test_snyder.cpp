// Snyder's area-light functions (illumination/snyder.hpp) and the spherical-cap moments behind
// them (illumination/cap_moment.hpp), against references that share no formula with them:
// adaptive Gauss–Legendre quadrature in long double over the sphere, in polar coordinates about
// the cap's axis (the clip enters only as the limits of the inner integral), and over the plane
// for polygons (reference_quadrature.hpp); plus Snyder's identities, which pit independent
// implementations against each other (the sine-power series of eqs. 14–15 against the Stokes
// sums of eq. 24; the closed form of eq. 6 against the same sums).
//
// Tolerances. The implementations were checked while writing these tests against 40-digit mpmath
// quadrature on ~2,000 cases (σ from 1e−6 to π, ω at and around 0, π/2 ± σ, σ and π, n from 0 to
// 10,000): worst relative error 3e−16 for the caps and 5e−16 for the sine-power functions. The
// long-double reference below is converged to ~1e−17 (checked by halving its tolerance), but
// evaluates z = c·u in long double, which near the horizon (slivers of height h) costs it
// ~1e−19·(n + 2)/h relative. Unless a check says otherwise we allow 2e−14: two orders above both.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <vector>

#include "geometry/error.hpp"
#include "illumination/cap_moment.hpp"
#include "illumination/snyder.hpp"
#include "reference_quadrature.hpp"
#include "test_support.hpp"

using namespace daylit;
using daylit::test::LVec3;

namespace {

using LD = long double;
constexpr double kPi = std::numbers::pi;
constexpr LD kPiL = 3.141592653589793238462643383279502884L;

// z^n by binary powering (relative rounding ≤ 2 log₂n ulps: 2e−18 at n = 10,000), far cheaper
// than powl in the inner loops below.
LD ipow(LD z, int n) {
  LD result = 1;
  for (; n > 0; n >>= 1, z *= z)
    if (n & 1) result *= z;
  return result;
}

using daylit::test::relative_error;

// ---- Composite Gauss–Legendre in long double ---------------------------------------------------
//
// Fixed rules on graded panels, converged for every case below (checked while writing the tests by
// splitting every panel in two: the references moved by less than 1e−17 relative).

#ifndef SNYDER_TEST_SPLIT
#define SNYDER_TEST_SPLIT 1  // 2 splits every panel in two: the convergence check
#endif
constexpr int g_split = SNYDER_TEST_SPLIT;

struct GaussRule {
  std::vector<LD> x, w;
  GaussRule() { test::gauss_legendre(20, x, w); }
};

template <class F>
LD composite(F&& f, const std::vector<LD>& cuts) {
  static const GaussRule rule;
  LD total = 0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    for (int part = 0; part < g_split; ++part) {
      const LD a = cuts[i] + (cuts[i + 1] - cuts[i]) * part / g_split;
      const LD b = cuts[i] + (cuts[i + 1] - cuts[i]) * (part + 1) / g_split;
      const LD half = (b - a) / 2, mid = (a + b) / 2;
      for (std::size_t k = 0; k < rule.x.size(); ++k) total += rule.w[k] * half * f(mid + half * rule.x[k]);
    }
  return total;
}

// Cuts on [a, b]: four equal panels, then halving towards a (levels_a times) and towards b
// (levels_b times), where high powers peak and the substitution below leaves the ends.
std::vector<LD> graded(LD a, LD b, int levels_a, int levels_b) {
  std::vector<LD> cuts;
  for (int i = 0; i <= 4; ++i) cuts.push_back(a + (b - a) * i / 4);
  for (int k = 3; k < 3 + levels_a; ++k) cuts.push_back(a + (b - a) * std::ldexp(1.0L, -k));
  for (int k = 3; k < 3 + levels_b; ++k) cuts.push_back(b - (b - a) * std::ldexp(1.0L, -k));
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

// ∫ over [a, b] with θ = a + (b − a) sin²(t/2), t ∈ [0, π]: square-root behaviour at either end
// becomes smooth.
template <class F>
LD integrate_ends(F&& f, LD a, LD b, int levels) {
  // The peaks of high powers sit at the ends, where θ − a ∝ t²: half the levels reach as deep.
  const LD h = (b - a) / 2;
  return composite(
      [&](LD t) {
        const LD s = std::sin(t / 2);
        return f(a + (b - a) * s * s) * h * std::sin(t);
      },
      graded(0, kPiL, levels, levels));
}

// ---- Reference: moments over a cap, in polar coordinates (θ, ψ) about its axis L ----------------
//
// u = cos θ L + sin θ (cos ψ e₁ + sin ψ e₂), e₁ the direction of c's projection, so
// z = c·u = cos(ω − θ) − 2 sin θ sin ω sin²(ψ/2) and L·u = cos θ; the clip z ≥ 0 is the inner range
// |ψ| ≤ ψ_θ, sin²(ψ_θ/2) = cos(ω − θ)/(2 sin θ sin ω). ∫ z^n (L·u)^m dΩ, m ∈ {0, 1}.
// Angles in long double: the exact hemisphere is σ = kPiL/2.

// Levels of halving for z^n: its peak is ~n^−½ wide. Low powers are trigonometric polynomials of
// low degree, which a few panels integrate exactly.
int peak_levels(int n) { return n > 8 ? int(std::ceil(std::log2(std::sqrt(LD(n))))) + 4 : 0; }

// cos(ω − θ) to ~1e−19 relative even where it vanishes (ω − θ near ±π/2, the slivers): as
// sin(π/2 − ω + θ) with π/2 to 128 bits and π/2 − ω exact (Sterbenz) where it is small.
LD cos_difference(LD omega, LD theta) {
  constexpr LD hi = 1.5707963267948966192313216916397514L;  // rounds to 1.57079632679489661925640…
  constexpr LD half_pi_lo = -2.5082788063341660118e-20L;    // π/2 − hi
  const LD e1 = ((hi - omega) + half_pi_lo) + theta;  // π/2 − (ω − θ)
  if (e1 <= hi) return std::sin(e1);
  return std::sin(((hi - theta) + half_pi_lo) + omega);  // π/2 − (θ − ω)
}

LD cap_reference(LD omega, LD sigma, int n, int m, bool clip = true) {
  const LD sw = std::sin(omega);
  const int levels = peak_levels(n);
  auto ring = [&](LD theta) -> LD {
    const LD top = cos_difference(omega, theta), st = std::sin(theta);
    LD psi_max = kPiL;
    if (clip) {
      if (!(top > 0)) return 0;
      const LD h = top / (2 * st * sw);
      if (h < 1) psi_max = 2 * std::asin(std::sqrt(h));
    }
    const LD inner = composite(
        [&](LD psi) {
          const LD s = std::sin(psi / 2);
          const LD z = top - 2 * st * sw * s * s;
          return ipow(clip ? std::max(z, LD(0)) : z, n);
        },
        graded(0, psi_max, levels, 0));  // z^n peaks at ψ = 0
    return 2 * inner * st * (m == 1 ? std::cos(theta) : LD(1));
  };
  // Where the ring starts or stops crossing the horizon (cos(ω ± θ) = 0), and where it passes
  // through the pole (θ = ω, the peak of high powers).
  std::vector<LD> cuts{0, sigma};
  for (LD c : {kPiL / 2 - omega, 3 * kPiL / 2 - omega, omega - kPiL / 2, omega + kPiL / 2, omega})
    if ((clip || c == omega) && c > 0 && c < sigma) cuts.push_back(c);
  std::sort(cuts.begin(), cuts.end());
  LD total = 0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) total += integrate_ends(ring, cuts[i], cuts[i + 1], levels * 2 / 3);
  return total;
}

LD sine_power_reference(int n, double x) {
  const int levels = peak_levels(n) + 4;
  // sin^n peaks at π/2, or at x below it.
  std::vector<LD> cuts;
  if (x > kPiL / 2) {
    cuts = graded(0, kPiL / 2, 0, levels);
    const auto more = graded(kPiL / 2, x, levels, 0);
    cuts.insert(cuts.end(), more.begin() + 1, more.end());
  } else {
    cuts = graded(0, x, 0, levels);
  }
  return composite([&](LD t) { return ipow(std::sin(t), n); }, cuts);
}

}  // namespace

// ---- Lambertian: eqs. 3–6 -----------------------------------------------------------------------

TEST_CASE("I_hemi_const, I_hemi_cos and the overcast sky against quadrature over the sphere") {
  for (double omega : {0.0, 0.4, kPi / 2, 2.2, kPi - 1e-3, kPi - 1e-7}) {
    INFO("omega = " << omega);
    // The constant hemisphere is the cap σ = π/2 (cap_reference with n = 1: (1/π)∫(N·u) dΩ); the
    // cosine-weighted one the same with the weight L·u. Near ω = π the values are O(ε²) and O(ε³)
    // (ε = π − ω) and the reference's z = c·u carries 1e−19 absolute: 1e−19/ε relative.
    const LD c = cap_reference(omega, kPiL / 2, 1, 0) / kPiL, w = cap_reference(omega, kPiL / 2, 1, 1) / kPiL;
    const double tol = std::max(2e-14, 1e-18 / (kPi - omega));
    CHECK(relative_error(I_hemi_const(omega), c) < tol);
    CHECK(relative_error(I_hemi_cos(omega), w) < tol);
    CHECK(relative_error(I_hemi_overcast(omega), (c + 2 * w) / 3) < tol);
  }
  CHECK(I_hemi_overcast(0) == Approx(7.0 / 9).epsilon(1e-15));
  CHECK(I_hemi_const(kPi) < 1e-32);
  CHECK(I_hemi_cos(kPi) >= 0);
  CHECK(I_hemi_cos(kPi) < 1e-45);
}

TEST_CASE("I_hemi_cos keeps its digits as omega approaches pi, where it vanishes like eps^3") {
  // 2/(3π) (ε³/3 − ε⁵/30 + …) for ω = π − ε (Taylor series of eq. 5), ε exact in double.
  for (double eps : {1e-2, 1e-4, 1e-6}) {
    const double omega = kPi - eps;
    const LD e = (kPiL - omega) - 5.016557612668332023557e-20L;  // π to 128 bits
    const LD series = 2 / (3 * kPiL) * (e * e * e / 3 - e * e * e * e * e / 30 + std::pow(e, 7) / 840);
    INFO("eps = " << eps);
    CHECK(relative_error(I_hemi_cos(omega), series) < 1e-13);  // series truncated at ε⁹: ≤ 1e−13
  }
}

TEST_CASE("I_hemi_sub: exact eq. 6 against quadrature, including the sun and the breakpoints") {
  for (double sigma : {1e-6, kSunHalfAngle, 0.3, 1.2, kPi / 2}) {
    const double b0 = kPi / 2 - sigma, b1 = kPi / 2 + sigma;
    for (double omega : {0.0, b0, b0 + 0.3 * sigma, kPi / 2, b1 - 0.3 * sigma, b1 - 1e-3 * sigma}) {
      if (omega < 0 || omega > kPi) continue;
      INFO("sigma = " << sigma << ", omega = " << omega);
      const LD ref = cap_reference(omega, sigma, 1, 0) / kPiL;
      // At b1 − 1e−3σ the region is a sliver of height ~1e−3σ²: the reference loses ~1e−19·3/h.
      const double tol = omega == b1 - 1e-3 * sigma ? std::max(2e-14, 1e-18 / (sigma * sigma)) : 2e-14;
      CHECK(relative_error(I_hemi_sub(omega, sigma), ref) < tol);
    }
    // Just past π/2 + σ nothing of the source is above the horizon.
    if (b1 + 1e-9 < kPi) CHECK(I_hemi_sub(b1 + 1e-9, sigma) == 0);
    // At π/2 + σ itself (rounded) at most a sliver of width ~1e−16 remains.
    CHECK(I_hemi_sub(b1, sigma) < 1e-30);
  }
}

TEST_CASE("I_hemi_sub reduces to I_hemi_const at sigma = pi/2 and agrees with the cap moments") {
  for (double omega : {0.0, 0.3, 1.0, kPi / 2, 2.0, 3.0, kPi}) {
    INFO("omega = " << omega);
    // σ = π/2 in double is the exact half-angle less 6e−17: the values differ by ~1e−16/(π − ω).
    CHECK(I_hemi_sub(omega, kPi / 2) == Approx(I_hemi_const(omega)).epsilon(omega == kPi ? 1 : 4e-15).margin(1e-32));
    for (double sigma : {1e-6, 0.00465, 0.5, 1.4})
      CHECK(relative_error(I_hemi_sub(omega, sigma), LD(I_hemi_sub_phong(omega, sigma, 1))) < 1e-14);
  }
}

TEST_CASE("I_hemi_sub is continuous at the breakpoints pi/2 - sigma, pi/2, pi/2 + sigma") {
  for (double sigma : {1e-6, 0.00465, 0.3, 1.2}) {
    for (double b : {kPi / 2 - sigma, kPi / 2, kPi / 2 + sigma}) {
      const double h = 1e-9 * sigma;
      const double left = I_hemi_sub(b - h, sigma), right = I_hemi_sub(b + h, sigma);
      const double slope = sigma * sigma;  // |dI/dω| ≤ sin²σ
      INFO("sigma = " << sigma << ", breakpoint = " << b);
      CHECK(std::abs(left - right) <= 2.5 * slope * h);
    }
  }
}

TEST_CASE("the Hermite fillet: exact outside, within its measured maximum error inside") {
  // Measured over σ ∈ (0, π/2] (400 values) × 2,000 values of ω in the fillet: the largest absolute
  // error is 6.80e−3 (σ = 1.4035, ω = 2.354; 5.40e−3 at σ = π/2), the largest relative to the
  // peak sin²σ 7.04e−3 (σ = 1.3635); for small σ the error is 3.57e−3 sin³σ.
  double worst = 0, worst_relative = 0;
  for (int i = 1; i <= 40; ++i) {
    const double sigma = kPi / 2 * i / 40;
    for (int j = 0; j <= 200; ++j) {
      const double omega = kPi / 2 - sigma + 2 * sigma * j / 200;
      if (omega < 0 || omega > kPi) continue;
      const double e = std::abs(I_hemi_sub_hermite(omega, sigma) - I_hemi_sub(omega, sigma));
      worst = std::max(worst, e);
      worst_relative = std::max(worst_relative, e / (std::sin(sigma) * std::sin(sigma)));
    }
  }
  CHECK(worst < 6.81e-3);
  CHECK(worst > 6.0e-3);  // it is an approximation: not accidentally the exact function
  CHECK(worst_relative < 7.05e-3);
  for (double sigma : {1e-3, 0.01}) {
    double small = 0;
    for (int j = 0; j <= 200; ++j) {
      const double omega = kPi / 2 - sigma + 2 * sigma * j / 200;
      small = std::max(small, std::abs(I_hemi_sub_hermite(omega, sigma) - I_hemi_sub(omega, sigma)));
    }
    CHECK(small < 3.6e-3 * std::pow(std::sin(sigma), 3));
  }
  // The knots themselves are exact (to the rounding of y = (ω − x₀)/σ at ω = π/2, ~1e−16/σ).
  for (double sigma : {0.01, 0.7, kPi / 2}) {
    CHECK(I_hemi_sub_hermite(kPi / 2, sigma) == Approx(I_hemi_sub(kPi / 2, sigma)).epsilon(1e-13));
    CHECK(I_hemi_sub_hermite(0.2 * (kPi / 2 - sigma), sigma) ==
          Approx(I_hemi_sub(0.2 * (kPi / 2 - sigma), sigma)).epsilon(1e-15));
    CHECK(I_hemi_sub_hermite(kPi / 2 + sigma + 1e-12, sigma) == 0);
  }
}

// ---- Phong: eqs. 13–15, 24 ----------------------------------------------------------------------

TEST_CASE("the sine-power integral S(n, x) against quadrature, and S(n, pi) S(n+1, pi) = 2 pi/(n+1)") {
  for (int n : {0, 1, 2, 7, 100, 1000, 10000}) {
    for (double x : {1e-3, 0.3, kPi / 4, 1.2, kPi / 2 - 1e-3, kPi / 2, 2.0, kPi - 1e-3, kPi}) {
      const LD ref = sine_power_reference(n, x);
      if (ref < 1e-300L) {
        CHECK(sine_power_integral(n, x) < 1e-290);
        continue;
      }
      INFO("n = " << n << ", x = " << x);
      CHECK(relative_error(sine_power_integral(n, x), ref) < 2e-14);
    }
    INFO("n = " << n);
    CHECK(sine_power_integral(n, kPi) * sine_power_integral(n + 1, kPi) == Approx(2 * kPi / (n + 1)).epsilon(1e-14));
  }
}

TEST_CASE("I_hemi_const_phong and I_hemi_cos_phong against quadrature over the sphere") {
  struct Case {
    int n;
    double omega;
  };
  std::vector<Case> cases{{1000, 0.5}, {1000, 2.0}, {10000, 0.5}, {10000, 1.6}};
  for (int n : {0, 1, 2, 5})
    for (double omega : {0.0, 0.5, kPi / 2, 2.0, 2.8, kPi - 1e-4}) cases.push_back({n, omega});
  for (const auto& [n, omega] : cases) {
    const LD norm = LD(n + 1) / (2 * kPiL);
    const LD c = norm * cap_reference(omega, kPiL / 2, n, 0), w = norm * cap_reference(omega, kPiL / 2, n, 1);
    INFO("n = " << n << ", omega = " << omega);
    // Near ω = π the reference's z = c·u carries 1e−19 absolute on values of size ε^{n+1}.
    const double tol = std::max(2e-14, 1e-19 * (n + 2) / (kPi - omega));
    CHECK(relative_error(I_hemi_const_phong(omega, n), c) < tol);
    CHECK(relative_error(I_hemi_cos_phong(omega, n), w) < tol);
  }
  CHECK(I_hemi_const_phong(2.8, 10000) == 0);  // 1e−5000: below every double
}

TEST_CASE("Snyder's identities for the Phong functions") {
  for (double omega : {0.0, 0.1, 1.0, kPi / 2, 2.0, 3.0, kPi - 1e-6}) {
    INFO("omega = " << omega);
    CHECK(I_hemi_const_phong(omega, 1) == Approx(I_hemi_const(omega)).epsilon(1e-14).margin(1e-300));
    CHECK(I_hemi_cos_phong(omega, 1) == Approx(I_hemi_cos(omega)).epsilon(1e-14).margin(1e-300));
    // I_hemi_sub_phong(ω, π/2, n) = I_hemi_const_phong(ω, n): the Stokes sums against the
    // sine-power series. σ = π/2 is 6e−17 short of the hemisphere in double: relative ~n·1e−16
    // where the region is a thin lune (ω near π).
    for (int n : {0, 1, 2, 3, 1000, 10000}) {
      const double a = I_hemi_sub_phong(omega, kPi / 2, n), b = I_hemi_const_phong(omega, n);
      INFO("n = " << n);
      if (b < 1e-300) {
        CHECK(a < 1e-290);
      } else {
        CHECK(relative_error(a, b) < (omega > 2.5 ? 1e-9 : 2e-14) * std::max(1, n / 100));
      }
    }
  }
  // I_hemi_sub_phong(0, σ, n) = 1 − cos^{n+1}σ, here as −expm1((n+1) log1p(−2 sin²(σ/2))) in
  // long double (log cos σ itself would lose 1e−7 relative at σ = 1e−6).
  for (double sigma : {1e-6, kSunHalfAngle, 0.3, 1.0, kPi / 2 - 1e-7}) {
    for (int n : {0, 1, 2, 3, 10, 1000, 10000}) {
      const LD h = std::sin(LD(sigma) / 2);
      const LD expected = -std::expm1(LD(n + 1) * std::log1p(-2 * h * h));
      INFO("sigma = " << sigma << ", n = " << n);
      CHECK(relative_error(I_hemi_sub_phong(0, sigma, n), expected) < 1e-14);
    }
  }
}

TEST_CASE("I_hemi_sub_phong, even and odd n, against quadrature: stiff exponents and angles") {
  struct Case {
    double omega, sigma;
    int n;
  };
  // High exponents where the result is a normal double: the pole inside the source, on its rim
  // (ω = σ) and outside it; the sun's disk near R; a clipped source.
  std::vector<Case> cases{{0, 0.3, 10000},          {0.15, 0.3, 10000},   {0.3, 0.3, 10000},
                          {0.45, 0.3, 1000},        {1.36, 0.3, 100},     {0.002, kSunHalfAngle, 10000},
                          {0.01, kSunHalfAngle, 10000}, {5e-7, 1e-6, 10000}, {0.6, kPi / 2, 1000}};
  for (double sigma : {1e-6, kSunHalfAngle, 0.3, kPi / 2}) {
    const double b0 = kPi / 2 - sigma, b1 = kPi / 2 + sigma;
    // (ω = 2σ = π with σ = π/2 in doubles is a sliver 6e−17 high, which the long-double reference
    // cannot resolve; the cap tests below cover it against the 40-digit values noted there.)
    for (double omega : {0.0, 0.5 * sigma, sigma, 2 * sigma, b0, b0 + 0.3 * sigma, kPi / 2, b1 - 0.3 * sigma})
      if (omega >= 0 && omega < 3)
        for (int n : {0, 1, 2, 3}) cases.push_back({omega, sigma, n});
  }
  for (const Case& c : cases) {
    const LD ref = LD(c.n + 1) / (2 * kPiL) * cap_reference(c.omega, c.sigma, c.n, 0);
    INFO("omega = " << c.omega << ", sigma = " << c.sigma << ", n = " << c.n);
    CHECK(relative_error(I_hemi_sub_phong(c.omega, c.sigma, c.n), ref) < 2e-14);
  }
}

TEST_CASE("I_hemi_sub_phong is continuous where the source meets the horizon and the pole") {
  for (int n : {0, 1, 2, 1000}) {
    for (double sigma : {1e-6, 0.3, 1.2}) {
      for (double b : {kPi / 2 - sigma, sigma}) {
        const double h = 1e-10 * sigma;
        const double left = I_hemi_sub_phong(b - h, sigma, n), right = I_hemi_sub_phong(b + h, sigma, n);
        INFO("n = " << n << ", sigma = " << sigma << ", breakpoint = " << b);
        // |dI/dω| ≤ (n + 1) sin σ for this normalisation.
        CHECK(std::abs(left - right) <= 2 * (n + 1) * std::sin(sigma) * 2 * h + 1e-15 * std::abs(left));
      }
    }
  }
}

// ---- Caps as regions: cap_moment ----------------------------------------------------------------

TEST_CASE("cap_moment: (), (c^n) and (c^n, L^1) against quadrature, caps of every size") {
  const Vec3 c{0, 0, 1};
  auto check = [&](double omega, double sigma, int n) {
    const Vec3 L{std::sin(omega), 0, std::cos(omega)};
    // The reference takes the angle of the double vector L itself (to 1e−19), so that slivers,
    // whose size the last bit of L decides, are the same region for both.
    const LD angle = std::atan2(LD(L.x), LD(L.z));
    const LD a = cap_reference(angle, sigma, n, 0), d = cap_reference(angle, sigma, n, 1);
    INFO("sigma = " << sigma << ", omega = " << omega << ", n = " << n);
    CHECK(relative_error(cap_moment(L, sigma, c, {{c, n}}), a) <= 2e-14);
    // D(n) changes sign for caps beyond a hemisphere: there the bound is relative to I(n).
    const double dn = cap_moment(L, sigma, c, {{c, n}, {L, 1}});
    CHECK(std::abs(LD(dn) - d) <= 2e-14L * std::max(std::abs(d), 1e-3L * a));
    if (n == 0) CHECK(relative_error(cap_moment(L, sigma, c, {}), a) <= 2e-14);
  };
  for (double sigma : {1e-6, 0.2, 1.4, kPi / 2, 2.0, 3.0, kPi})
    for (double omega : {0.0, 0.1, 1.0, kPi / 2 - sigma + 0.2, kPi / 2, 2.6, kPi})
      if (omega >= 0 && omega <= kPi && !(sigma == kPi / 2 && omega == kPi))
        for (int n : {0, 2, 7}) check(omega, sigma, n);
  // σ = π/2 and L = −c in doubles: L's angle is π − 1.2e−16 and σ is π/2 − 6.1e−17, which leaves a
  // sliver 6.1e−17 high that long double cannot resolve. 40-digit values (mpmath, integrating over
  // z with the square-root ends removed): n = 0: 7.173437107865090e−33; n = 2: 5.310560369151894e−66.
  const Vec3 down{std::sin(kPi), 0, -1};
  CHECK(cap_moment(down, kPi / 2, c, {{c, 0}, {down, 1}}) == Approx(7.173437107865090e-33).epsilon(1e-14));
  CHECK(cap_moment(down, kPi / 2, c, {{c, 2}, {down, 1}}) == Approx(5.310560369151894e-66).epsilon(1e-14));
  // n = 1000, where the results are normal doubles: caps small and large, pole in and out.
  check(0.1, 0.2, 1000);
  check(0.1, 1.4, 1000);
  check(1.0, 2.0, 1000);
  check(2.6, 3.0, 1000);
}

TEST_CASE("cap_moment: non-unit axes scale, factors merge, and either order is accepted") {
  const Vec3 c{0, 0.6, 0.8}, L{0.8, 0, 0.6};
  const double sigma = 0.7;
  const double base = cap_moment(L, sigma, c, {{c, 3}, {L, 1}});
  CHECK(cap_moment(2.5 * L, sigma, 4.0 * c, {{L * 3.0, 1}, {c * 2.0, 3}}) == Approx(base * 24).epsilon(1e-15));
  CHECK(cap_moment(L, sigma, c, {{c, 1}, {c, 2}, {L, 1}, {L, 0}}) == Approx(base).epsilon(1e-15));
  // Parallel within 1e−12 rad counts as parallel.
  const Vec3 c_tilted{0, 0.6 + 4e-13, 0.8 - 3e-13};
  CHECK(cap_moment(L, sigma, c, {{c_tilted, 3}, {L, 1}}) == Approx(base).epsilon(1e-12));
  // Without a clip: the cap's solid angle and its moments about its own axis.
  CHECK(cap_moment(L, sigma, std::nullopt, {}) == Approx(2 * kPi * (1 - std::cos(sigma))).epsilon(1e-15));
  for (int k : {1, 2, 5, 10000})
    CHECK(relative_error(cap_moment(L, sigma, std::nullopt, {{L, k}}),
                         cap_reference(0, sigma, k, 0, false)) < 2e-14);
  CHECK(cap_moment(L, kPi, std::nullopt, {{L, 3}}) == Approx(0).margin(1e-15));
  CHECK(cap_moment(L, kPi, std::nullopt, {{L, 2}}) == Approx(4 * kPi / 3).epsilon(1e-15));
  CHECK(relative_error(cap_moment(L, 1e-6, std::nullopt, {{L, 7}}), cap_reference(0, 1e-6, 7, 0, false)) < 2e-14);
  CHECK(relative_error(cap_moment(L, 2.5, std::nullopt, {{L, 7}}), cap_reference(0, 2.5, 7, 0, false)) < 2e-14);
}

TEST_CASE("cap_moment refuses what it cannot do, by name") {
  const Vec3 c{0, 0, 1}, L{1, 0, 1};
  CHECK_THROWS_WITH(cap_moment(L, 0.5, c, {{c, 2}, {L, 2}}), Catch::Contains("(c^2, L^2)"));
  CHECK_THROWS_WITH(cap_moment(L, 0.5, c, {{{0, 1, 0}, 1}}), Catch::Contains("parallel neither"));
  CHECK_THROWS_WITH(cap_moment(L, 0.5, std::nullopt, {{c, 1}}), Catch::Contains("parallel neither"));
  CHECK_THROWS_WITH(cap_moment(L, 0.5, c, {{-1.0 * c, 1}}), Catch::Contains("parallel neither"));
  CHECK_THROWS_AS(cap_moment({0, 0, 0}, 0.5, c, {}), Error);
  CHECK_THROWS_AS(cap_moment(L, 0, c, {}), Error);
  CHECK_THROWS_AS(cap_moment(L, 3.2, c, {}), Error);
  CHECK_THROWS_AS(cap_moment(L, 0.5, Vec3{0, 0, 0}, {}), Error);
  CHECK_THROWS_AS(cap_moment(L, 0.5, c, {{{0, 0, 0}, 1}}), Error);
  CHECK_THROWS_AS(cap_moment(L, 0.5, c, {{c, 200000}}), Error);
}

// ---- Polygons: eqs. 8 and 25 --------------------------------------------------------------------

TEST_CASE("I_poly and I_poly_phong clip to the hemisphere about R and match quadrature") {
  // The square y = 1, x, z ∈ [−1, 1] seen from the origin; R ∝ (0, 0.5, 1) keeps z ≥ −0.5 of it.
  const auto region = directions_through({{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}}, {});
  const Vec3 R{0, 0.5, 1};
  const Vec3 r = normalized(R);
  for (int n : {0, 1, 2, 5, 40}) {
    const LD ref = test::integrate_directions({0, 0, 0}, {-1, 1, -0.5L}, {2, 0, 0}, {0, 0, 1.5L}, [&](const LVec3& u) {
      return ipow(r.x * u.x + r.y * u.y + r.z * u.z, n);
    });
    INFO("n = " << n);
    // Gauss–Legendre over the plane converges to ~1e−16 here (reference_quadrature.hpp).
    CHECK(relative_error(I_poly_phong(region, R, n), LD(n + 1) / (2 * kPiL) * ref) < 1e-13);
  }
  CHECK(I_poly_phong(region, R, 1) == Approx(I_poly(region, R)).epsilon(1e-14));
  // High exponents with R through the square (the lobe, ~0.01 rad wide, inside it): 24 × 24 panels
  // converge to 4e−17 here (checked against 32 × 32; 16 × 16 leaves 2e−11 at n = 10,000).
  const Vec3 r2 = normalized(Vec3{0, 1, 0.2});
  for (int n : {1000, 10000}) {
    const LD ref = test::integrate_directions(
        {0, 0, 0}, {-1, 1, -1}, {2, 0, 0}, {0, 0, 2},
        [&](const LVec3& u) { return ipow(r2.x * u.x + r2.y * u.y + r2.z * u.z, n); }, 24, 24);
    INFO("n = " << n);
    CHECK(relative_error(I_poly_phong(region, r2, n), LD(n + 1) / (2 * kPiL) * ref) < 2e-14);
  }
  // Far off the axis: R ∝ (0, 1, 2.5) keeps z ≥ −0.4 of the square, whose nearest point to R, the
  // middle of the top edge, is 23° away; the lobe there is ~1/n wide, so strips graded towards z = 1
  // (converged to 1e−19: doubling panels or strips changes nothing). The kernel (moments.hpp)
  // promises ~1e−13 here, where the integrand's condition n·tan δ is ~400 (measured: 4e−14 at
  // n = 100, 2.1e−13 at n = 1000).
  const Vec3 r3 = normalized(Vec3{0, 1, 2.5});
  for (int n : {100, 1000}) {
    LD ref = 0;
    for (int k = 0; k <= 14; ++k) {
      const LD z0 = k == 0 ? -0.4L : 1 - 1.4L * std::ldexp(1.0L, -k), z1 = k == 14 ? 1 : 1 - 1.4L * std::ldexp(1.0L, -k - 1);
      ref += test::integrate_directions({0, 0, 0}, {-1, 1, z0}, {2, 0, 0}, {0, 0, z1 - z0}, [&](const LVec3& u) {
        return ipow(r3.x * u.x + r3.y * u.y + r3.z * u.z, n);
      }, 8, 24);
    }
    INFO("n = " << n);
    CHECK(relative_error(I_poly_phong(region, r3, n), LD(n + 1) / (2 * kPiL) * ref) < 1e-12);
  }
  CHECK(I_poly_phong(region, {0, -1, 0}, 3) == 0);  // all of it behind R
}

// ---- Spherical luminaires: eq. 7 ----------------------------------------------------------------

TEST_CASE("sphere_half_angle solves sin sigma = r/d, also as r approaches d") {
  for (auto [d, r] : {std::pair{2.0, 1.0}, {1.0 + 1e-12, 1.0}, {1.496e11, 6.957e8}, {5.0, 0.0}, {3.0, 3.0}}) {
    const double sigma = sphere_half_angle(d, r);
    INFO("d = " << d << ", r = " << r);
    CHECK(std::sin(LD(sigma)) * LD(d) == Approx(r).epsilon(1e-15).margin(1e-300));
    // cos σ·d = √(d² − r²): the form that keeps its digits as r → d.
    CHECK(double(std::cos(LD(sigma)) * LD(d)) == Approx(std::sqrt((d - r) * (d + r))).epsilon(1e-15).margin(2e-16));
  }
  CHECK(sphere_half_angle(2, 1) == Approx(kPi / 6).epsilon(1e-15));
  CHECK_THROWS_AS(sphere_half_angle(1, 2), Error);
  CHECK_THROWS_AS(sphere_half_angle(-1, 0), Error);
}

TEST_CASE("a sphere, and the sun's disk, seen from a point with a normal") {
  // The sun: 0.533° across, at 1 au.
  const Vec3 point{10, -3, 2};
  const double distance = 1.496e11, radius = 6.957e8;
  const double sigma = sphere_half_angle(distance, radius);
  CHECK(sigma == Approx(kSunHalfAngle).epsilon(2e-3));
  for (double elevation : {0.5, sigma / 2, 0.0, -sigma / 2}) {
    const Vec3 center = point + distance * Vec3{std::cos(elevation), 0, std::sin(elevation)};
    const double got = I_hemi_sub_sphere(point, {0, 0, 3}, center, radius);  // horizontal receiver
    const double omega = kPi / 2 - elevation;
    INFO("elevation = " << elevation);
    // ω from the vectors carries the rounding of the 1.5e11 m coordinates (~1e−16 relative).
    CHECK(got == Approx(I_hemi_sub(omega, sigma)).epsilon(1e-9));
    if (elevation > sigma)  // the whole disk above the horizon: Nusselt's cos ω sin²σ
      CHECK(got == Approx(std::cos(omega) * (radius / distance) * (radius / distance)).epsilon(1e-14));
    else
      CHECK(relative_error(got, cap_reference(omega, sigma, 1, 0) / kPiL) < 1e-9);
  }
}
