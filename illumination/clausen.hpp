#pragma once
// The Clausen integral Cl2 and Chen and Arvo's special function Λ(α, β) built on it (Chen and
// Arvo 2000, §4.1–4.2, eqs. 33–45): the one non-elementary ingredient of rational moments with a
// denominator (w·u) (rational_moments.hpp).

#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "illumination/real_vector.hpp"
#include "illumination/tracked_sum.hpp"

namespace daylit {

// Cl2(x) = −∫_0^x log|2 sin(t/2)| dt = Σ_k sin(kx)/k², for any real x (odd, period 2π, zero at
// multiples of π). x reduced to [−π, π] (Cody–Waite), then one of two series: about 0 for
// |x| ≤ 2π/3 (Lewin 1958, eq. 4.21, below) and about π beyond (clausen.cpp), each with ratio of
// terms ≤ 1/9, 18 terms by Horner's rule. Within 16 ulp of max(|Cl2|, 1) over [−2π, 4π] (proven
// against MPFR in tests/illumination/test_clausen.cpp). Written here rather than GSL's
// gsl_sf_clausen (as accurate, and the baseline of `bench rational`) because the radiosity
// transport calls it six times per edge: GSL's Chebyshev series with its error estimate was 28 %
// of a run's time.
double clausen(double x);

// Cl2 in long double and __float128 for the escalated sums of rational_moments.cpp, by the
// series Cl2(x) = x − x log|x| + x Σ_{n≥1} ζ(2n)/(n(2n+1)) (x/2π)^{2n} on x reduced to [−π, π]
// (Lewin 1958, eq. 4.21; the ratio of terms is ≤ 1/4 there), with ζ(2n) from Euler–Maclaurin.
// Absolute error a few units of R's roundoff times max(|x log|x||, 1).
long double clausen(long double x);
#if DAYLIT_HAVE_FLOAT128
real::quad clausen(real::quad x);
#endif

// Grosjean's approximation (1984; Chen and Arvo 2000, eq. 39) from elementary functions, extended
// to all x by oddness and period: an approximate path for bench rational (absolute error ~1e-6).
double clausen_grosjean(double x);

// Which Cl2 evaluates Λ in lambda_bracket(): clausen(), or Grosjean's approximation.
enum class ClausenMethod { series, grosjean };

// 4·√(1 − α²)·Λ(α, β) with Λ(α, β) = ∫_0^β log(α cos θ)/(1 − α² cos² θ) dθ (eq. 34), by eq. 36:
//     2 Cl2(2μ) − Cl2(4μ − 2η) − Cl2(2η) + 2(η − μ) log γ,
// for 0 < α ≤ 1 with κ = √(1 − α²) given separately (both are edge data known to full relative
// precision: α = c and κ = |w·m| of an arc; forming one from the other would lose digits where it
// is small), and β given as (sin β, cos β) with cos β > 0. The forms below avoid every
// cancellation of eq. 36 as written: μ = atan2(sin β, κ cos β); log γ = 2 log α − 2 log1p(κ)
// (γ = α²/(1 + κ)², eq. 36's (1 − κ)²/α² without its cancellation as α → 0); and
// η = atan2(sin β cos β (1 + κ), κ cos² β − sin² β), eq. 36's η with 1 − γ = 2κ/(1 + κ)
// substituted, which stays defined at α = 1 (κ = 0), where eq. 36 reads 0/0 and the bracket is 0
// (Λ(1, β) is finite, eq. 35). η lies in [0, π] for β ≥ 0 (eq. 121); β < 0 by oddness (eq. 38).
// The product with κ is what the edge terms need (they carry w·m = ±κ), and it spares the
// division by κ that makes Λ itself lose digits near α = 1. The tracked form carries the sum of the
// absolute values of the bracket's terms and of its Cl2's error scale (for cancellation estimates).
template <class R>
real::Tracked<R> lambda_bracket_tracked(R alpha, R kappa, R sin_beta, R cos_beta,
                                        ClausenMethod method = ClausenMethod::series) {
  if (sin_beta < 0) {
    const real::Tracked<R> b = lambda_bracket_tracked<R>(alpha, kappa, -sin_beta, cos_beta, method);
    return {-b.value, b.magnitude};
  }
  if (sin_beta == 0) return {};
  const R mu = real::atan2(sin_beta, kappa * cos_beta);
  const R eta = real::atan2(sin_beta * cos_beta * (1 + kappa), kappa * cos_beta * cos_beta - sin_beta * sin_beta);
  const R log_gamma = 2 * real::log(alpha) - 2 * real::log1p(kappa);
  auto cl2 = [&](R x) -> R {
    if constexpr (std::is_same_v<R, double>)
      if (method == ClausenMethod::grosjean) return clausen_grosjean(x);
    return clausen(x);
  };
  const R t1 = 2 * cl2(2 * mu), t2 = cl2(4 * mu - 2 * eta), t3 = cl2(2 * eta), t4 = 2 * (eta - mu) * log_gamma;
  // Each Cl2 is good to a few units of roundoff of max(|Cl2|, 1) (both series), not of
  // |Cl2|: hence the 4 (= 2 + 1 + 1, the weights of the three terms) beside their values.
  return {t1 - t2 - t3 + t4, real::abs(t1) + real::abs(t2) + real::abs(t3) + real::abs(t4) + 4};
}

// The bracket alone.
template <class R>
R lambda_bracket(R alpha, R kappa, R sin_beta, R cos_beta, ClausenMethod method = ClausenMethod::series) {
  return lambda_bracket_tracked<R>(alpha, kappa, sin_beta, cos_beta, method).value;
}

// Λ(α, β) itself for 0 < α ≤ 1, |β| ≤ π/2: eq. 35 at α = 1, eq. 36 (through lambda_bracket)
// otherwise. Loses relative accuracy like 1/κ as α → 1 (the bracket is O(κ)), which is why the
// kernels use lambda_bracket() directly.
double chen_arvo_lambda(double alpha, double beta, ClausenMethod method = ClausenMethod::series);

// The tabulated path of §4.2 (eqs. 40–45): Λ = λ + Λ' with λ(α, β) = log α · atan(tan β/κ)/κ in
// closed form (eq. 41) and Λ'(α, β) = ∫_0^β log(cos θ)/(1 − α² cos² θ) dθ (eq. 42), bounded on
// [0, 1] × [0, π/2], read by bilinear interpolation from a regular grid whose nodes come from eq. 36
// in long double and, on the edges, from eqs. 43–45 (α = 0: Lobachevsky's function
// ½ Cl2(π − 2β) − β log 2; α = 1: eq. 44; β = π/2: eq. 45). Chen and Arvo report 0.2% relative
// error for a 300 × 300 grid; bench rational measures it.
class LambdaPrimeTable {
 public:
  explicit LambdaPrimeTable(int nodes_per_axis = 300);
  double lambda_prime(double alpha, double beta) const;  // Λ'(α, β), |β| ≤ π/2 (odd in β)
  double lambda(double alpha, double beta) const;        // λ + Λ', 0 < α ≤ 1

 private:
  int n_;
  std::vector<double> values_;  // n_ × n_, α major
};

}  // namespace daylit
