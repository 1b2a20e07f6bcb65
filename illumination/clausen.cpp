#include "illumination/clausen.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace daylit {

namespace {

// ζ(2n) for n = 1..N in precision R: Σ_{k<K} k^{−s} plus the Euler–Maclaurin tail
//     Σ_{k≥K} k^{−s} = K^{1−s}/(s − 1) + K^{−s}/2 + Σ_{j=1}^{8} B_{2j}/(2j)! (s)_{2j−1} K^{1−s−2j},
// ((s)_m the rising factorial). With K = 64 the first omitted term is below 1e-34 for every s ≥ 2.
template <class R, int N>
std::array<R, N + 1> zeta_even() {
  constexpr int K = 64;
  // B_{2j}/(2j)! for j = 1..8.
  const R b[8] = {R(1) / R(12),
                  R(-1) / R(720),
                  R(1) / R(30240),
                  R(-1) / R(1209600),
                  R(1) / R(47900160),
                  R(-691) / R(1307674368000.0L),
                  R(1) / R(74724249600.0L),
                  R(-3617) / R(10670622842880000.0L)};
  std::array<R, N + 1> z{};
  for (int n = 1; n <= N; ++n) {
    const int s = 2 * n;
    R sum = 0;
    for (int k = K - 1; k >= 1; --k) sum += real::powi(R(1) / R(k), s);  // smallest first
    const R inv_k = R(1) / R(K);
    const R k_pow = real::powi(inv_k, s);  // K^{−s}
    R tail = k_pow * R(K) / R(s - 1) + k_pow / 2;
    R rising = R(s), k_term = k_pow * inv_k;  // (s)_1 and K^{−s−1}
    for (int j = 1; j <= 8; ++j) {
      tail += b[j - 1] * rising * k_term;
      rising *= R(s + 2 * j - 1) * R(s + 2 * j);
      k_term *= inv_k * inv_k;
    }
    z[n] = sum + tail;
  }
  return z;
}

// The Bernoulli-number series of Cl2 (clausen.hpp), on x reduced to [−π, π].
template <class R>
R clausen_series(R x) {
  constexpr int N = 64;
  static const std::array<R, N + 1> zeta = zeta_even<R, N>();
  const R pi = real::pi<R>(), two_pi = 2 * pi;
  if (!(real::abs(x) <= pi)) {
    x -= two_pi * real::round(x / two_pi);  // args here are within a few periods: no loss to speak of
  }
  if (x == 0) return R(0);
  const R head = x - x * real::log(real::abs(x));
  const R y = (x / two_pi) * (x / two_pi);
  const R scale = std::max(real::abs(head), real::abs(x));
  R sum = 0, yn = 1;
  for (int n = 1; n <= N; ++n) {
    yn *= y;
    const R term = zeta[n] / R(n * (2 * n + 1)) * yn;
    sum += term;
    if (real::abs(x * term) < real::unit_roundoff<R>() * scale / 16) break;
  }
  return head + x * sum;
}

// The two series of the double Cl2 (clausen.hpp), their coefficients rounded from long double:
//   about 0:  Cl2(a) = a − a log a + a Σ_{n≥1} ζ(2n)/(n(2n+1)(2π)^{2n}) a^{2n},
//   about π:  Cl2(π − y) = y log 2 − y Σ_{n≥1} (1 − 4^{−n}) ζ(2n)/(n(2n+1)π^{2n}) y^{2n},
// the second from Cl2'(θ) = −log(2 sin(θ/2)) and log cos z = −Σ (4^n − 1) ζ(2n) z^{2n}/(n π^{2n}).
// Each is used where its ratio of terms is at most 1/9 (a ≤ 2π/3, y ≤ π/3), so 18 terms leave
// less than 1e-19 of the result.
constexpr int kSeriesTerms = 18;

struct ClausenSeries {
  std::array<double, kSeriesTerms + 1> about_zero{}, about_pi{};
  ClausenSeries() {
    const auto zeta = zeta_even<long double, kSeriesTerms>();
    const long double pi = real::pi<long double>();
    for (int n = 1; n <= kSeriesTerms; ++n) {
      const long double base = zeta[std::size_t(n)] / ((long double)n * (2 * n + 1));
      about_zero[std::size_t(n)] = double(base / real::powi(2 * pi, 2 * n));
      about_pi[std::size_t(n)] = double((1 - real::powi(0.25L, n)) * base / real::powi(pi, 2 * n));
    }
  }
};

// Σ_{n=1}^{N} c_n u^n by Horner's rule.
double power_series(const std::array<double, kSeriesTerms + 1>& c, double u) {
  double sum = c[kSeriesTerms];
  for (int n = kSeriesTerms - 1; n >= 1; --n) sum = sum * u + c[std::size_t(n)];
  return sum * u;
}

}  // namespace

double clausen(double x) {
  static const ClausenSeries series;
  // 2π in two parts (Cody and Waite): x − k·2π_hi by one fused multiply-add is rounded once,
  // relative to the small result, and k·2π_lo restores what 2π_hi lacks, so the reduced argument
  // keeps its digits down to the zeros at multiples of 2π.
  constexpr double two_pi_hi = 6.28318530717958623200, two_pi_lo = 2.44929359829470635445e-16;
  constexpr double pi_hi = 3.14159265358979311600, pi_lo = 1.22464679914735317723e-16;
  constexpr double ln2 = 0.69314718055994530942;
  if (!std::isfinite(x)) return std::numeric_limits<double>::quiet_NaN();
  const double k = std::nearbyint(x / two_pi_hi);
  const double r = std::fma(-k, two_pi_hi, x) - k * two_pi_lo;  // in [−π, π], up to roundoff
  const double a = std::abs(r);
  double value;
  if (a == 0) {
    value = 0;
  } else if (a <= 2.0943951023931957) {  // 2π/3
    value = a - a * std::log(a) + a * power_series(series.about_zero, a * a);
  } else {
    const double y = std::max(0.0, (pi_hi - a) + pi_lo);
    value = y * ln2 - y * power_series(series.about_pi, y * y);
  }
  return r < 0 ? -value : value;
}

long double clausen(long double x) { return clausen_series(x); }

#if DAYLIT_HAVE_FLOAT128
real::quad clausen(real::quad x) { return clausen_series(x); }
#endif

double clausen_grosjean(double x) {
  constexpr double pi = 3.14159265358979323846, ln2 = 0.69314718055994530942;
  x = std::remainder(x, 2 * pi);  // [−π, π]
  if (x == 0) return 0;
  const double sign = x < 0 ? -1 : 1;
  const double t = std::abs(x);
  const double value = -t * std::log(std::sin(t / 2)) + t * (pi * pi - t * t) * (120 - 7 * pi * pi + 3 * t * t) / 2880 +
                       (2 * ln2 - 1.25) * std::sin(t) - (89.0 / 128 - ln2) * std::sin(2 * t) +
                       (2 * ln2 / 3 - 449.0 / 972) * std::sin(3 * t) - (4259.0 / 12288 - ln2 / 2) * std::sin(4 * t) +
                       (0.4 * ln2 - 10397.0 / 37500) * std::sin(5 * t);
  return sign * value;
}

double chen_arvo_lambda(double alpha, double beta, ClausenMethod method) {
  const double kappa = std::sqrt((1 - alpha) * (1 + alpha));
  if (kappa == 0) {
    // Eq. 35: Λ(1, β) = −β − cot β log cos β (odd in β; 0 at β = 0).
    if (beta == 0) return 0;
    return -beta - std::log(std::cos(beta)) / std::tan(beta);
  }
  return lambda_bracket<double>(alpha, kappa, std::sin(beta), std::cos(beta), method) / (4 * kappa);
}

namespace {

// Λ'(α, β) for β ∈ [0, π/2] in long double: the closed boundary forms of eqs. 43–45, eq. 36
// less λ inside.
long double lambda_prime_node(long double alpha, long double beta) {
  const long double pi = 3.141592653589793238462643383279502884L, ln2 = 0.693147180559945309417232121458176568L;
  if (beta == 0) return 0;
  if (alpha == 0) return clausen(pi - 2 * beta) / 2 - beta * ln2;  // Lobachevsky's function, eq. 43
  const long double kappa = std::sqrt((1 - alpha) * (1 + alpha));
  if (kappa == 0) return beta >= pi / 2 ? -pi / 2 : -beta - std::log(std::cos(beta)) / std::tan(beta);  // eq. 44
  if (beta >= pi / 2) return -pi / (2 * kappa) * std::log1p(kappa);                                      // eq. 45
  const long double sb = std::sin(beta), cb = std::cos(beta);
  const long double lambda = lambda_bracket<long double>(alpha, kappa, sb, cb) / (4 * kappa);
  const long double small_lambda = std::log(alpha) * std::atan2(sb, kappa * cb) / kappa;  // eq. 41
  return lambda - small_lambda;
}

}  // namespace

LambdaPrimeTable::LambdaPrimeTable(int nodes_per_axis) : n_(std::max(nodes_per_axis, 2)) {
  const long double half_pi = 1.570796326794896619231321691639751442L;
  values_.resize(std::size_t(n_) * n_);
  for (int i = 0; i < n_; ++i)
    for (int j = 0; j < n_; ++j) {
      const long double alpha = (long double)i / (n_ - 1), beta = half_pi * j / (n_ - 1);
      values_[std::size_t(i) * n_ + j] = double(lambda_prime_node(alpha, beta));
    }
}

double LambdaPrimeTable::lambda_prime(double alpha, double beta) const {
  if (beta < 0) return -lambda_prime(alpha, -beta);
  const double half_pi = 1.5707963267948966;
  const double x = std::clamp(alpha, 0.0, 1.0) * (n_ - 1), y = std::clamp(beta / half_pi, 0.0, 1.0) * (n_ - 1);
  const int i = std::min(int(x), n_ - 2), j = std::min(int(y), n_ - 2);
  const double fx = x - i, fy = y - j;
  auto at = [&](int a, int b) { return values_[std::size_t(a) * n_ + b]; };
  return (1 - fx) * ((1 - fy) * at(i, j) + fy * at(i, j + 1)) + fx * ((1 - fy) * at(i + 1, j) + fy * at(i + 1, j + 1));
}

double LambdaPrimeTable::lambda(double alpha, double beta) const {
  const double kappa = std::sqrt((1 - alpha) * (1 + alpha));
  // λ = log α · μ/κ (eq. 41); its limit at α = 1 is 0, and log α = ½ log1p(−κ²) keeps its
  // digits near there.
  const double small_lambda =
      kappa == 0 ? 0.0 : 0.5 * std::log1p(-kappa * kappa) * std::atan2(std::sin(beta), kappa * std::cos(beta)) / kappa;
  return small_lambda + lambda_prime(alpha, beta);
}

}  // namespace daylit
