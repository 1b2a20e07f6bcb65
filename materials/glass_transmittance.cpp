#include "materials/glass_transmittance.hpp"

#include "illumination/least_squares.hpp"
#include "materials/radiance_luminance.hpp"

#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace daylit {

double evaluate_polynomial(const std::vector<double>& c, double mu) noexcept {
  double sum = 0;
  for (auto it = c.rbegin(); it != c.rend(); ++it) sum = sum * mu + *it;
  return sum;
}

double max_slope(const std::vector<double>& c) {
  std::vector<double> derivative;
  for (std::size_t k = 1; k < c.size(); ++k) derivative.push_back(double(k) * c[k]);
  double slope = 0;
  for (int i = 0; i <= 1000; ++i) slope = std::max(slope, std::abs(evaluate_polynomial(derivative, i / 1000.0)));
  return slope;
}

std::optional<double> glass_transmissivity(double transmittance, double refractive_index) {
  const auto at = [&](double t) { return glass_transmittance({{t, t, t}, refractive_index}, 1.0); };
  if (!(transmittance >= 0) || transmittance > at(1.0)) return std::nullopt;
  double lo = 0, hi = 1;
  for (int i = 0; i < 64 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (at(mid) < transmittance ? lo : hi) = mid;
  }
  return std::abs(at(lo) - transmittance) <= std::abs(at(hi) - transmittance) ? lo : hi;
}

namespace {

// Least-squares coefficients of Chebyshev polynomials T_j(2μ − 1), j ≤ degree, on the samples
// (the well-conditioned basis), then the monomial coefficients of the sum.
std::vector<double> least_squares_monomials(const std::vector<double>& mu, const std::vector<double>& value, int degree) {
  const std::size_t m = mu.size(), n = std::size_t(degree) + 1;
  std::vector<long double> A(m * n), b(value.begin(), value.end());
  for (std::size_t i = 0; i < m; ++i) {
    const long double x = 2.0L * mu[i] - 1;
    long double t0 = 1, t1 = x;
    for (std::size_t j = 0; j < n; ++j) {
      if (j < 2) {
        A[i * n + j] = j == 0 ? t0 : t1;
      } else {
        const long double t2 = 2 * x * t1 - t0;
        A[i * n + j] = t2;
        t0 = t1;
        t1 = t2;
      }
    }
  }
  const std::vector<long double> chebyshev = least_squares(std::move(A), std::move(b), m, n);
  // Monomials in μ of T_j(2μ − 1), by T_{j+1} = 2(2μ − 1) T_j − T_{j−1}.
  std::vector<long double> monomial(n, 0), previous(n, 0), current(n, 0);
  previous[0] = 1;                      // T_0
  current[0] = -1, current[1] = 2;      // T_1 = 2μ − 1
  for (std::size_t j = 0; j < n; ++j) {
    const std::vector<long double>& T = j == 0 ? previous : current;
    for (std::size_t k = 0; k < n; ++k) monomial[k] += chebyshev[j] * T[k];
    if (j >= 1 && j + 1 < n) {
      std::vector<long double> next(n, 0);
      for (std::size_t k = 0; k < n; ++k) {
        next[k] = -2 * current[k] - previous[k];
        if (k > 0) next[k] += 4 * current[k - 1];
      }
      previous = current;
      current = next;
    }
  }
  return {monomial.begin(), monomial.end()};
}

// m_glass's angle terms at cosine of incidence μ ∈ (0, 1]: the refracted cosine
// cos θ_t = √(1 − (1 − μ²)/n²) and the two polarisations' Fresnel reflectances; then, per channel
// of transmissivity t, the pass transmittance d = t^{1/cos θ_t}, and `per_pass(r_s, r_p, d)`
// summed with Radiance's luminance weights.
template <class PerPass>
double luminance_over_channels(const GlassOptics& glass, double mu, PerPass&& per_pass) {
  const double n = glass.refractive_index;
  const double cos_t = std::sqrt((1 - 1 / (n * n)) + mu * mu / (n * n));
  const double rs = std::pow((mu - n * cos_t) / (mu + n * cos_t), 2);
  const double rp = std::pow((1 / mu - n / cos_t) / (1 / mu + n / cos_t), 2);
  double total = 0;
  for (int c = 0; c < 3; ++c) total += kRadianceLuminanceWeights[c] * per_pass(rs, rp, std::pow(glass.transmissivity[c], 1 / cos_t));
  return total;
}

}  // namespace

double glass_transmittance(const GlassOptics& glass, double mu) {
  mu = std::clamp(mu, 0.0, 1.0);
  if (mu == 0) return 0;  // grazing: the Fresnel reflectances reach 1
  return luminance_over_channels(glass, mu, [](double rs, double rp, double d) {
    return 0.5 * (1 - rs) * (1 - rs) * d / (1 - rs * rs * d * d) + 0.5 * (1 - rp) * (1 - rp) * d / (1 - rp * rp * d * d);
  });
}

double glass_reflectance(const GlassOptics& glass, double mu) {
  mu = std::clamp(mu, 0.0, 1.0);
  if (mu == 0) return 1;  // grazing: r_s = r_p = 1
  return luminance_over_channels(glass, mu, [](double rs, double rp, double d) {
    const double d2 = d * d;
    return 0.5 * rs * (1 + (1 - 2 * rs) * d2) / (1 - rs * rs * d2) + 0.5 * rp * (1 + (1 - 2 * rp) * d2) / (1 - rp * rp * d2);
  });
}

double glass_diffuse_reflectance(const GlassOptics& glass) {
  constexpr std::size_t kPoints = 64;
  gsl_integration_glfixed_table* table = gsl_integration_glfixed_table_alloc(kPoints);
  double sum = 0;
  for (std::size_t i = 0; i < kPoints; ++i) {
    double mu = 0, weight = 0;
    gsl_integration_glfixed_point(0, 1, i, &mu, &weight, table);
    sum += weight * 2 * mu * glass_reflectance(glass, mu);
  }
  gsl_integration_glfixed_table_free(table);
  return sum;
}

TransmittancePolynomial fit_glass_transmittance(const GlassOptics& glass, double tolerance) {
  return fit_transmittance([&](double mu) { return glass_transmittance(glass, mu); }, tolerance);
}

TransmittancePolynomial fit_transmittance(const std::function<double(double)>& transmittance, double tolerance) {
  constexpr int kSamples = 600, kChecks = 20001, kMaxDegree = 12;
  std::vector<double> mu(kSamples), value(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    mu[i] = 0.5 * (1 - std::cos(std::numbers::pi * (i + 0.5) / kSamples));  // Chebyshev points on [0, 1]
    value[i] = transmittance(mu[i]);
  }
  std::vector<double> check_mu(kChecks), check_value(kChecks);
  for (int i = 0; i < kChecks; ++i) {
    check_mu[i] = double(i) / (kChecks - 1);
    check_value[i] = transmittance(check_mu[i]);
  }
  auto max_error = [&](const std::vector<double>& c) {
    double e = 0;
    for (int i = 0; i < kChecks; ++i) e = std::max(e, std::abs(evaluate_polynomial(c, check_mu[i]) - check_value[i]));
    return e;
  };
  TransmittancePolynomial best;
  for (int degree = 1; degree <= kMaxDegree; ++degree) {
    TransmittancePolynomial fit{least_squares_monomials(mu, value, degree), 0};
    fit.max_error = max_error(fit.coefficients);
    if (best.coefficients.empty() || fit.max_error < best.max_error) best = fit;
    if (best.max_error <= tolerance) break;
  }
  return best;
}

}  // namespace daylit
