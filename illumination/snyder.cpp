#include "illumination/snyder.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/error.hpp"
#include "illumination/cap_moment.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "illumination/moments.hpp"

namespace daylit {

namespace {

using LD = long double;

constexpr double kPi = 3.14159265358979323846;
constexpr LD kPiL = 3.141592653589793238462643383279502884L;
// π as a long double (3.14159265358979323851…) and the rest, for the same in long double.
constexpr LD kPiLoL = -5.016557612668332023557e-20L;
constexpr LD kEpsL = 0x1p-64L;

// π − x and π/2 − x with π to 128 bits: exact to rounding where they are small (Sterbenz).
LD pi_minus(LD x) { return (kPiL - x) + kPiLoL; }
LD half_pi_minus(LD x) { return (kPiL / 2 - x) + kPiLoL / 2; }

double clamp_angle(double omega) { return std::clamp(omega, 0.0, kPi); }

// x − sin x for x ∈ [0, 2π]: its Taylor series below 2 (terms fall by x²/20 ≤ 0.2 each, no
// cancellation), directly above (x − sin x ≥ 1.09 there, cancellation ≤ 2×).
LD x_minus_sin(LD x) {
  if (x >= 2) return x - std::sin(x);
  const LD x2 = x * x;
  LD term = x * x2 / 6, sum = 0;
  for (int k = 0; std::fabs(term) > kEpsL / 8 * std::fabs(sum) || k == 0; ++k) {
    sum += term;
    term *= -x2 / LD((2 * k + 4) * (2 * k + 5));
  }
  return sum;
}

// t − atan t for t ∈ [0, 1): halve the angle once (atan t = 2 atan t', t' = t/(1 + √(1 + t²)) ≤
// 0.42), t − 2t' = t³/(1 + √(1 + t²))², and t' − atan t' by its alternating series (ratio ≤ 0.18).
LD t_minus_atan(LD t) {
  const LD r = 1 + std::sqrt(1 + t * t);
  const LD h = t / r, h2 = h * h;
  LD term = h * h2 / 3, sum = 0;
  for (int k = 1; term > kEpsL * sum / 8 || k == 1; ++k) {
    sum += (k % 2 == 1 ? term : -term);
    term *= h2 * (2 * k + 1) / (2 * k + 3);
  }
  return t * t * t / (r * r) + 2 * sum;
}

// S(n, π/2) = ∫_0^{π/2} sin^n θ dθ by S(n) = (n − 1)/n S(n − 2) (positive factors, stable).
LD sine_power_half(int n) {
  LD s = n % 2 == 0 ? kPiL / 2 : 1;
  for (int k = n % 2 == 0 ? 2 : 3; k <= n; k += 2) s *= LD(k - 1) / LD(k);
  return s;
}

// Whether the positive series in sin²y (below) converges quickly enough: sin²y ≤ ½ (≤ 70 terms),
// or n cos²y > 2 (≤ 25 n terms: where the complement would cancel by more than e).
bool use_series(int n, LD s2, LD c2) { return s2 <= 0.5L || LD(n) * c2 > 2; }

// ∫_0^v cos^n t dt by W(m) = (cos^{m−1}v sin v + (m − 1) W(m − 2))/m, every term positive.
LD cosine_power_integral(int n, LD v) {
  const LD c = std::cos(v), s = std::sin(v);
  LD w = n % 2 == 0 ? v : s;
  LD power = n % 2 == 0 ? c : c * c;  // cos^{m−1} v for the first m
  for (int m = n % 2 == 0 ? 2 : 3; m <= n; m += 2) {
    w = (power * s + LD(m - 1) * w) / LD(m);
    power *= c * c;
  }
  return w;
}

// S(n, y) for y ∈ [0, π/2] (see sine_power_integral in the header).
LD sine_power_low(int n, LD y) {
  if (!(y > 0)) return 0;
  if (n == 0) return y;
  const LD s = std::sin(y), c = std::cos(y), s2 = s * s, c2 = c * c;
  if (use_series(n, s2, c2)) {
    LD t = 1, total = 1;
    for (int k = 0; t * s2 > kEpsL * total * c2 / 4; ++k) {
      t *= s2 * LD(n + 2 + 2 * k) / LD(n + 3 + 2 * k);
      total += t;
    }
    return std::pow(s, LD(n + 1)) * c / LD(n + 1) * total;
  }
  return sine_power_half(n) - cosine_power_integral(n, half_pi_minus(y));
}

// Value and derivative of I_hemi_sub at the knots of Snyder's Hermite fillet, evaluated on
// [x0, x1] by his cubic g(y) = a y³ + b y² + c y + d, y = (x − x0)/(x1 − x0).
double hermite(double x, double x0, double x1, double f0, double d0, double f1, double d1) {
  const double h = x1 - x0, y = (x - x0) / h;
  const double g0p = h * d0, g1p = h * d1;
  const double a = g1p + g0p - 2 * (f1 - f0), b = 3 * (f1 - f0) - g1p - 2 * g0p;
  return ((a * y + b) * y + g0p) * y + f0;
}

}  // namespace

double I_hemi_const(double omega) noexcept {
  const double c = std::cos(omega / 2);
  return c * c;
}

double I_hemi_cos(double omega) noexcept {
  omega = clamp_angle(omega);
  const LD eps = pi_minus(omega);  // π − ω
  if (omega <= kPi / 2) {
    const LD s = std::sin(LD(omega)), c = std::cos(LD(omega));
    return double(2 / (3 * kPiL) * (s * s * s + c * eps + s * c * c));
  }
  const LD s = std::sin(eps), c = std::cos(eps);
  // sin³ε − cos ε (ε − sin ε cos ε), ε − sin ε cos ε = (2ε − sin 2ε)/2: the terms cancel to ε³/3.
  return double(2 / (3 * kPiL) * (s * s * s - c * x_minus_sin(2 * eps) / 2));
}

double I_hemi_sum(double omega, double alpha, double beta) noexcept {
  return alpha * I_hemi_const(omega) + beta * I_hemi_cos(omega);
}

double I_hemi_overcast(double omega) noexcept { return I_hemi_sum(omega, 1.0 / 3, 2.0 / 3); }

double I_hemi_sub(double omega, double sigma) {
  if (!(sigma > 0)) return 0;
  omega = clamp_angle(omega);
  sigma = std::min(sigma, kPi);
  if (sigma > kPi / 2) return clipped_cap_axial_moment(omega, sigma, 1) / kPi;
  const LD w = omega, s = sigma;
  const LD cw = std::cos(w), cs = std::cos(s), ss = std::sin(s);
  const LD z_min = std::cos(w + s), z_max = std::cos(w - s);
  if (z_min >= 0) return double(cw * ss * ss);  // the whole source above the horizon
  if (!(z_max > 0)) return 0;                   // the whole source below it
  const LD q = std::sqrt(z_max * -z_min);      // = √(sin²σ − cos²ω)
  const LD psi1 = std::atan2(q, -cw * cs);
  // atan2(q, cos σ) − q cos σ = t sin²σ − (t − atan t), t = q / cos σ, where it cancels (t < 1).
  const LD rim = q >= cs ? std::atan2(q, cs) - q * cs : (q / cs) * ss * ss - t_minus_atan(q / cs);
  const LD first = psi1 * ss * ss * cw;
  const LD value = first + rim;
  if (cw < 0 && std::fabs(first) + rim > 8 * value) return clipped_cap_axial_moment(omega, sigma, 1) / kPi;
  return double(value / kPiL);
}

double I_hemi_sub_hermite(double omega, double sigma) {
  if (!(sigma > 0)) return 0;
  omega = clamp_angle(omega);
  if (sigma > kPi / 2) return I_hemi_sub(omega, sigma);
  const double ss = std::sin(sigma), cs = std::cos(sigma);
  const double x0 = kPi / 2 - sigma, x1 = kPi / 2, x2 = kPi / 2 + sigma;
  if (omega <= x0) return std::cos(omega) * ss * ss;
  if (omega >= x2) return 0;
  const double f0 = ss * ss * ss, d0 = -cs * ss * ss;
  const double f1 = double(x_minus_sin(2 * LD(sigma)) / (2 * kPiL)), d1 = -ss * ss / 2;  // (σ − sin σ cos σ)/π
  if (omega <= x1) return hermite(omega, x0, x1, f0, d0, f1, d1);
  return hermite(omega, x1, x2, f1, d1, 0, 0);
}

double I_poly(const SphericalRegion& region, const Vec3& normal) {
  const Vec3 n = normalized(normal);
  const SphericalRegion visible = clip_to_hemisphere(region, n);
  return visible.empty() ? 0.0 : lambert(visible, n) / kPi;
}

double sine_power_integral(int n, double x) noexcept {
  if (!(x > 0)) return 0;
  x = clamp_angle(x);
  if (x <= kPi / 2) return double(sine_power_low(n, x));
  return double(2 * sine_power_half(n) - sine_power_low(n, pi_minus(x)));
}

double I_hemi_const_phong(double omega, int n) noexcept {
  omega = clamp_angle(omega);
  const LD half = sine_power_half(n);  // S(n, π) = 2 half
  if (omega >= kPi / 2) return double(sine_power_low(n, pi_minus(omega)) / (2 * half));
  return double(1 - sine_power_low(n, omega) / (2 * half));
}

double I_hemi_cos_phong(double omega, int n) noexcept {
  omega = clamp_angle(omega);
  const int m = n + 1;
  const LD half = sine_power_half(m);  // S(n + 1, π) = 2 half
  const LD factor = LD(n + 1) / (LD(n + 2) * 2 * half);
  if (omega <= kPi / 2) {
    const LD s = std::sin(LD(omega)), c = std::cos(LD(omega));
    return double(factor * (std::pow(s, LD(n + 2)) / LD(n + 1) + c * (2 * half - sine_power_low(m, omega))));
  }
  const LD y = pi_minus(omega);
  const LD s = std::sin(y), c = std::cos(y), s2 = s * s, c2 = c * c;
  LD bracket;
  if (use_series(m, s2, c2)) {
    // s^{n+2}/(n+2) Σ_k t_k/(n+1+2k), t_{k+1} = t_k s² (n+3+2k)/(n+4+2k): every term positive.
    LD t = 1, total = LD(1) / LD(n + 1);
    for (int k = 0; t * s2 > kEpsL * total * c2 * LD(n + 1) / 4; ++k) {
      t *= s2 * LD(n + 3 + 2 * k) / LD(n + 4 + 2 * k);
      total += t / LD(n + 3 + 2 * k);
    }
    bracket = std::pow(s, LD(n + 2)) / LD(n + 2) * total;
  } else {
    bracket = std::pow(s, LD(n + 2)) / LD(n + 1) - c * sine_power_low(m, y);
  }
  return double(factor * bracket);
}

double I_hemi_sub_phong(double omega, double sigma, int n) {
  if (!(sigma > 0)) return 0;
  return clipped_cap_axial_moment(omega, sigma, n) * (n + 1) / (2 * kPi);
}

double I_poly_phong(const SphericalRegion& region, const Vec3& R, int n) {
  const Vec3 r = normalized(R);
  const SphericalRegion visible = clip_to_hemisphere(region, r);
  if (visible.empty()) return 0;
  return axial_moment(visible, r, n) * (n + 1) / (2 * kPi);
}

double sphere_half_angle(double distance, double radius) {
  if (!std::isfinite(distance) || !std::isfinite(radius) || !(radius >= 0) || !(distance >= 0))
    throw Error("sphere_half_angle: distance and radius must be finite and non-negative");
  if (radius > distance) throw Error("sphere_half_angle: the point lies inside the sphere (radius > distance)");
  return std::atan2(radius, std::sqrt((distance - radius) * (distance + radius)));
}

double I_hemi_sub_sphere(const Vec3& point, const Vec3& normal, const Vec3& center, double radius) {
  const Vec3 d = center - point;
  const double omega = std::atan2(norm(cross(normal, d)), dot(normal, d));
  return I_hemi_sub(omega, sphere_half_angle(norm(d), radius));
}

}  // namespace daylit
