#pragma once
// The one Gauss–Legendre rule: the semi-analytic rational moments (rational_moments.cpp), the
// tests' reference quadrature (tests/reference_quadrature.hpp) and bench stiff's reference
// (bench/stiff_scenes.hpp) all take their nodes and weights from here.

#include <cmath>
#include <vector>

namespace daylit::quadrature {

// The n-point rule on [−1, 1] (n ≥ 1), nodes in decreasing order, in long double: exact for
// polynomials of degree ≤ 2n − 1. Nodes by Newton's method on P_n from the asymptotic guess
// cos(π(i + 3/4)/(n + 1/2)) (Abramowitz and Stegun 22.16.6), P_n and P_n' by the three-term
// recurrence; weights 2/((1 − x²) P_n'(x)²) (A&S 25.4.29). Newton stops at a step below 1e-19
// (converged to an ulp of long double, 3–4 steps). Accuracy: nodes and weights within a few ulp
// of long double for n ≤ 1000, which tests/illumination/test_quadrature_rules.cpp checks against closed forms
// and exact integrals of monomials. O(n²).
struct GaussLegendreRule {
  std::vector<long double> x, w;
};

inline GaussLegendreRule gauss_legendre(int n) {
  GaussLegendreRule rule;
  rule.x.assign(std::size_t(n), 0);
  rule.w.assign(std::size_t(n), 0);
  const long double pi = 3.141592653589793238462643383279502884L;
  for (int i = 0; i < n; ++i) {
    long double t = std::cos(pi * (i + 0.75L) / (n + 0.5L)), dp = 0;
    for (int iter = 0; iter < 100; ++iter) {
      long double p0 = 1, p1 = t;
      for (int k = 2; k <= n; ++k) {
        const long double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (t * p1 - p0) / (t * t - 1);
      const long double step = p1 / dp;
      t -= step;
      if (std::abs(step) < 1e-19L) break;
    }
    rule.x[std::size_t(i)] = t;
    rule.w[std::size_t(i)] = 2 / ((1 - t * t) * dp * dp);
  }
  return rule;
}

// The same rule mapped to [0, 1], rounded to double: the fixed product rules over fan triangles
// (simulation/annual_coefficients.cpp, annual_reflections.cpp).
struct UnitGaussRule {
  std::vector<double> x, w;
};
inline UnitGaussRule gauss_legendre_unit(int n) {
  const GaussLegendreRule r = gauss_legendre(n);
  UnitGaussRule u;
  for (int i = 0; i < n; ++i) {
    u.x.push_back(double((r.x[std::size_t(i)] + 1) / 2));
    u.w.push_back(double(r.w[std::size_t(i)] / 2));
  }
  return u;
}

}  // namespace daylit::quadrature
