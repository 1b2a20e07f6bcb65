// The one Gauss–Legendre rule (illumination/gauss_legendre.hpp) and the one Gauss–Kronrod rule
// (illumination/gauss_kronrod.hpp), checked on their own before the references of the other tests
// are built on them: nodes and weights against closed forms (Abramowitz and Stegun, table 25.4),
// exact integration of every monomial up to the rule's degree, and the Kronrod rule's Gauss nodes
// against the Gauss–Legendre rule.
//
// Tolerances: in long double (ε = 2^-63 ≈ 1.1e-19), a node or weight from Newton's method is good
// to a few ε; a monomial x^k summed over n nodes of positive weight loses about k·ε relative per
// node through the power and n·ε through the sum, so 4(k + n)·ε bounds it with room to spare.

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "illumination/gauss_kronrod.hpp"
#include "illumination/gauss_legendre.hpp"

using namespace daylit;

namespace {

constexpr long double kEps = std::numeric_limits<long double>::epsilon();

// ∫_{−1}^{1} x^k dx.
long double monomial_integral(int k) { return k % 2 == 1 ? 0.0L : 2.0L / (k + 1); }

}  // namespace

TEST_CASE("Gauss-Legendre nodes and weights match their closed forms for n = 1, 2, 3, 5") {
  const auto close = [](long double a, long double b) { return std::abs(a - b) <= 8 * kEps * std::max(1.0L, std::abs(b)); };
  const auto r1 = quadrature::gauss_legendre(1);
  CHECK(std::abs(r1.x[0]) <= 8 * kEps);
  CHECK(close(r1.w[0], 2));
  const auto r2 = quadrature::gauss_legendre(2);
  CHECK(close(r2.x[0], 1 / std::sqrt(3.0L)));
  CHECK(close(r2.x[1], -1 / std::sqrt(3.0L)));
  CHECK(close(r2.w[0], 1));
  CHECK(close(r2.w[1], 1));
  const auto r3 = quadrature::gauss_legendre(3);
  CHECK(close(r3.x[0], std::sqrt(0.6L)));
  CHECK(std::abs(r3.x[1]) <= 8 * kEps);
  CHECK(close(r3.x[2], -std::sqrt(0.6L)));
  CHECK(close(r3.w[0], 5.0L / 9));
  CHECK(close(r3.w[1], 8.0L / 9));
  CHECK(close(r3.w[2], 5.0L / 9));
  // n = 5: ±(1/3)√(5 ∓ 2√(10/7)) and 0; weights (322 ± 13√70)/900 and 128/225.
  const auto r5 = quadrature::gauss_legendre(5);
  const long double outer = std::sqrt(5 + 2 * std::sqrt(10.0L / 7)) / 3, inner = std::sqrt(5 - 2 * std::sqrt(10.0L / 7)) / 3;
  CHECK(close(r5.x[0], outer));
  CHECK(close(r5.x[1], inner));
  CHECK(std::abs(r5.x[2]) <= 8 * kEps);
  CHECK(close(r5.x[3], -inner));
  CHECK(close(r5.x[4], -outer));
  CHECK(close(r5.w[0], (322 - 13 * std::sqrt(70.0L)) / 900));
  CHECK(close(r5.w[1], (322 + 13 * std::sqrt(70.0L)) / 900));
  CHECK(close(r5.w[2], 128.0L / 225));
}

TEST_CASE("the n-point Gauss-Legendre rule integrates every monomial of degree up to 2n - 1 exactly") {
  for (int n : {1, 2, 3, 4, 7, 12, 20, 24, 32, 64, 128, 512}) {
    const auto rule = quadrature::gauss_legendre(n);
    REQUIRE(int(rule.x.size()) == n);
    for (int i = 0; i < n; ++i) {
      CHECK(rule.w[std::size_t(i)] > 0);
      CHECK(std::abs(rule.x[std::size_t(i)] + rule.x[std::size_t(n - 1 - i)]) <= 8 * kEps);  // symmetric, decreasing
      if (i > 0) CHECK(rule.x[std::size_t(i)] < rule.x[std::size_t(i - 1)]);
    }
    // Monomials beyond degree ~60 are too small at most nodes to test anything more.
    for (int k = 0; k <= std::min(2 * n - 1, 60); ++k) {
      long double sum = 0;
      for (int i = 0; i < n; ++i) sum += rule.w[std::size_t(i)] * std::pow(rule.x[std::size_t(i)], (long double)k);
      INFO("n = " << n << ", k = " << k);
      CHECK(std::abs(sum - monomial_integral(k)) <= 4 * (k + n) * kEps * 2);
    }
    // ... and not degree 2n (the rule's degree is exactly 2n − 1): ∫ x^{2n} is missed by a margin.
    if (n <= 24) {
      long double sum = 0;
      for (int i = 0; i < n; ++i) sum += rule.w[std::size_t(i)] * std::pow(rule.x[std::size_t(i)], (long double)(2 * n));
      CHECK(std::abs(sum - monomial_integral(2 * n)) > 1e-3L * monomial_integral(2 * n) * std::pow(0.25L, n));
    }
  }
}

TEST_CASE("the Kronrod 15-point rule's Gauss nodes are the 7-point Gauss-Legendre rule's, and both are exact to their degrees") {
  const auto g7 = quadrature::gauss_legendre(7);
  // Kronrod nodes x_1, x_3, x_5 (and x_7 = 0) are the Gauss nodes; g7 runs from +1 down.
  for (int j = 0; j < 4; ++j) {
    INFO("Gauss node " << j);
    CHECK(std::abs(quadrature::kXgk[2 * j + 1] - g7.x[std::size_t(j)]) <= 8 * kEps);
    CHECK(std::abs(quadrature::kWg[j] - g7.w[std::size_t(j)]) <= 8 * kEps);
  }
  // The panel routine on [a, b]: K15 exact to degree 23 (3·7 + 2, 7 odd), its G7 (inside the
  // error estimate) to 13.
  const long double a = -0.3L, b = 1.7L;
  for (int k = 0; k <= 23; ++k) {
    const auto f = [k](long double t) { return std::pow(t, (long double)k); };
    const auto p = quadrature::gauss_kronrod_15(f, a, b);
    const long double exact = (std::pow(b, (long double)(k + 1)) - std::pow(a, (long double)(k + 1))) / (k + 1);
    INFO("k = " << k);
    CHECK(std::abs(p.integral - exact) <= 64 * (k + 15) * kEps * std::abs(exact));
    if (k <= 13) CHECK(p.error <= 1e3L * kEps * std::abs(exact));  // G7 exact too: |K15 − G7| is rounding
  }
  // Degree 24 is beyond K15, and its error estimate covers what it misses.
  const auto f24 = [](long double t) { return std::pow(t, 24.0L); };
  const auto p24 = quadrature::gauss_kronrod_15(f24, a, b);
  const long double exact24 = (std::pow(b, 25.0L) - std::pow(a, 25.0L)) / 25;
  CHECK(std::abs(p24.integral - exact24) > 1e3L * kEps * exact24);
  CHECK(p24.error >= std::abs(p24.integral - exact24));
}
