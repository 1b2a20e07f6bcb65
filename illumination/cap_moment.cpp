#include "illumination/cap_moment.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "illumination/precision_escalation.hpp"
#include "illumination/real_vector.hpp"

namespace daylit {

namespace {

using real::condition;
using real::unit_roundoff;

template <class R>
using Sum = real::Tracked<R>;

// ---- The cap of half-angle s ≤ π/2 cut by the horizon: arc integrals and Stokes sums ----------
//
// Frame: c = z axis, L = (sin w, 0, cos w). The cap's circle is C(φ) = cos s L + sin s (cos φ L₁ +
// sin φ L₂) (Snyder eq. 18); measured from its top (ψ = π − φ) its height is z = a + β cos ψ with
// a = cos s cos w, β = sin s sin w, so z runs from z_max = a + β = cos(w − s) down to
// z_min = a − β = cos(w + s). Above the horizon lies the arc |ψ| ≤ ψ₁, cos ψ₁ = −a/β (ψ₁ = π when
// the circle does not cross). Along it x dy − y dx = sin s (d − c cos ψ) dψ, d = sin s cos w,
// c = cos s sin w (Snyder eq. 20), hence with the arc integrals
//     f_m = ∫_{−ψ₁}^{ψ₁} z^m dψ,   g_m = ∫_{−ψ₁}^{ψ₁} z^m cos ψ dψ,
// J(i) = sin s (d f_{i−1} − c g_{i−1}) for i ≥ 2, plus the horizon arc K = 2 atan2(q, cos s) for
// i = 1 (q = √(β² − a²) = √(z_max·(−z_min)); Snyder eq. 23 in a form that needs no acos).
//
// Arc integrals. Integrating by parts (Snyder appendix D; the end term z^m sin ψ vanishes at ψ₁):
//     f_m = a f_{m−1} + β g_{m−1},   (m + 1) g_m = m (β f_{m−1} + a g_{m−1}),
// f_0 = 2ψ₁, g_0 = 2 sin ψ₁. When a ≥ 0 every term is non-negative and the upward recurrence is
// stable. When a < 0 (the circle's top is nearer the horizon than its bottom, |z_min| > z_max)
// the recurrence's other solution grows like |z_min|^m against the wanted z_max^m; eliminating g,
//     m f_m = (2m − 1) a f_{m−1} + (m − 1) q² f_{m−2}
// run downwards has only positive terms. It is started at the top from the series (s₁ = sin(ψ₁/2),
// z = z_max (1 − x²) with x = sin(ψ/2)/s₁)
//     f_m ∝ z_max^m Σ_k T_k(m),  T_0 = 1,  T_{k+1} = T_k (2k+1)² s₁² / ((2k+2)(2m+2k+3)),
// whose ratio s₁² = z_max/(2β) ≤ ½, and normalised by f_0 = 2ψ₁ (Miller); then
// g_m = (f_{m+1} − a f_m)/β, again a sum of positive terms.
template <class R>
class SmallCap {
 public:
  // The cap {L·u ≥ cos s}, s ∈ [0, π/2], at angle w ∈ [0, π] from the pole. Prepares P(k) for
  // k_lo ≤ k ≤ k_hi and f_m for m ≤ m_f (m_f < 0: none), and their tails if `with_tail` (and they
  // converge: not with the pole on the rim). When every one of them is bounded by
  // `negligible` (the region far below the pole and n large), zero() says so and nothing is built.
  SmallCap(R w, R s, int k_lo, int k_hi, int m_f, R negligible, bool with_tail) {
    const R pi = real::pi<R>();
    cw_ = real::cos(w), sw_ = real::sin(w), cs_ = real::cos(s), ss_ = real::sin(s);
    const R sin_half = real::sin(s / 2);
    half_sin2_ = sin_half * sin_half;
    a_ = cs_ * cw_;
    beta_ = ss_ * sw_;
    z_max_ = real::cos(w - s);
    const R z_min = real::cos(w + s);
    pole_ = w < s ? 1 : 0;
    const bool on_boundary = w == s;
    if (!(s > 0) || !(z_max_ > 0)) {
      zero_ = true;
      return;
    }
    clipped_ = z_min < 0;
    q2_ = z_max_ * -z_min;  // β² − a², negative when the circle does not cross the horizon
    q_ = clipped_ ? real::sqrt(q2_) : R(0);
    psi1_ = clipped_ ? real::atan2(q_, -a_) : pi;

    // 1 − z_max = 2 sin²((w − s)/2) keeps ln z_max accurate near the pole.
    const R half_gap = real::sin((w - s) / 2);
    const R ln_zmax = z_max_ > R(0.5) ? real::log1p(-2 * half_gap * half_gap) : real::log(z_max_);
    const int m_lo = m_f >= 0 ? std::min(k_lo, m_f) : k_lo;
    if (pole_ == 0 && !on_boundary && ln_zmax < 0 &&
        real::log(4 * pi * R(k_hi + 2)) + R(std::max(m_lo, 0)) * ln_zmax < real::log(negligible)) {
      zero_ = true;
      return;
    }

    // Tail length: J(i) falls off like i·z_max^i; stop where z_max^T is below u/64 with 10 %
    // to spare for the polynomial factor.
    int tail_length = 0;
    tail_ok_ = with_tail && !on_boundary && ln_zmax < 0;
    if (tail_ok_) {
      const R t = R(1.1) * real::log(unit_roundoff<R>() / 64) / ln_zmax + 8;
      const R budget = R(2) * R(k_hi + 2) + 20000;
      if (t > budget) tail_ok_ = false;
      else tail_length = int(t);
    }
    m_ = std::max({k_hi - 1, m_f, tail_ok_ ? std::max(k_hi + 1, m_f) + tail_length : 0, 0});
    f_.assign(std::size_t(m_) + 2, R(0));
    g_.assign(std::size_t(m_) + 1, R(0));
    if (a_ >= 0) upward();
    else downward();
  }

  bool zero() const { return zero_; }
  R pole() const { return R(pole_); }
  R a() const { return a_; }
  R q2() const { return q2_; }
  R z_max() const { return z_max_; }
  bool has_tail() const { return tail_ok_; }
  int length() const { return m_; }
  R f(int m) const { return zero_ ? R(0) : f_[std::size_t(m)]; }
  // The horizon arc inside the cap (radians).
  R horizon_arc() const { return zero_ || !clipped_ ? R(0) : 2 * real::atan2(q_, cs_); }

  // P(k) = (k + 1) ∫ z^k dΩ by the forward Stokes sum (Snyder eq. 16): odd k: Σ_{i odd ≤ k} J(i);
  // even k: I(0) + Σ_{2 ≤ i ≤ k even} J(i). I(0), the solid angle of the cut cap, by Gauss–Bonnet:
  // I(0) = 2α − 2ψ₁ cos s with α = atan2(q, −cos w) the interior angle at the two corners, written
  // 2(α − ψ₁) + 4ψ₁ sin²(s/2) and α − ψ₁ = atan2(q cos w (1 − cos s), cos s cos²w + q²).
  Sum<R> forward(int k) const {
    Sum<R> sum;
    if (zero_) return sum;
    if (k % 2 == 0) {
      if (clipped_) {
        const R angle_gap = real::atan2(q_ * cw_ * 2 * half_sin2_, cs_ * cw_ * cw_ + q_ * q_);
        const R rim = 4 * psi1_ * half_sin2_;
        sum.add(2 * angle_gap + rim, 2 * real::abs(angle_gap) + rim);
      } else {
        const R cap = 4 * real::pi<R>() * half_sin2_;
        sum.add(cap, cap);
      }
    }
    for (int i = k % 2 == 0 ? 2 : 1; i <= k; i += 2) add_J(sum, i);
    return sum;
  }

  // Σ_{j ≥ 0} J(k + 2 + 2j), so that P(k) = 2π·pole() − tail(k) (only when has_tail()).
  Sum<R> tail(int k) const {
    Sum<R> sum;
    if (zero_) return sum;
    for (int i = k + 2; i - 1 <= m_; i += 2) add_J(sum, i);
    return sum;
  }

  // F_m = Σ_{j ≥ 0} f_{m+2j} = ∫_arc z^m/(1 − z²) dψ (only when has_tail()).
  R tail_f(int m) const {
    R sum = 0;
    if (zero_) return sum;
    for (int i = m; i <= m_ + 1; i += 2) sum += f_[std::size_t(i)];
    return sum;
  }

 private:
  void add_J(Sum<R>& sum, int i) const {
    const R d = ss_ * cw_, c = cs_ * sw_;
    const R t1 = ss_ * d * f_[std::size_t(i - 1)], t2 = -ss_ * c * g_[std::size_t(i - 1)];
    sum.add(t1 + t2, real::abs(t1) + real::abs(t2));
    if (i == 1 && clipped_) {
      const R k = horizon_arc();
      sum.add(k, k);
    }
  }

  void upward() {
    f_[0] = 2 * psi1_;
    g_[0] = clipped_ ? 2 * q_ / beta_ : R(0);
    for (int m = 1; m <= m_ + 1; ++m) {
      f_[m] = a_ * f_[m - 1] + beta_ * g_[m - 1];
      if (m <= m_) g_[m] = R(m) / R(m + 1) * (beta_ * f_[m - 1] + a_ * g_[m - 1]);
    }
  }

  void downward() {
    const R s1_sq = z_max_ / (2 * beta_);
    const R q2 = q_ * q_;
    const R u = unit_roundoff<R>();
    auto series = [&](int m) {
      R term = 1, sum = 1;
      for (int k = 0; term > u * sum / 4; ++k) {
        term *= R(2 * k + 1) * R(2 * k + 1) / (R(2 * k + 2) * R(2 * m + 2 * k + 3)) * s1_sq;
        sum += term;
      }
      return sum;
    };
    const int top = m_ + 1;
    f_[top] = series(top);
    f_[top - 1] = series(top - 1) / (z_max_ * R(2 * top) / R(2 * top + 1));
    for (int m = top; m >= 2; --m)
      f_[m - 2] = (R(m) * f_[m] - R(2 * m - 1) * a_ * f_[m - 1]) / (R(m - 1) * q2);
    const R scale = 2 * psi1_ / f_[0];
    for (R& v : f_) v *= scale;
    for (int m = 0; m <= m_; ++m) g_[m] = (f_[m + 1] - a_ * f_[m]) / beta_;
  }

  R cw_ = 0, sw_ = 0, cs_ = 0, ss_ = 0, half_sin2_ = 0;
  R a_ = 0, beta_ = 0, z_max_ = 0, q2_ = 0, q_ = 0, psi1_ = 0;
  int pole_ = 0;
  bool zero_ = false, clipped_ = false, tail_ok_ = false;
  int m_ = 0;
  std::vector<R> f_, g_;
};

template <class R>
struct Estimate {
  R value = 0;
  R relative_error = 0;
};

// ∫_{C∩H} z^n dΩ (times_cap_axis false) or ∫_{C∩H} z^n (L·u) dΩ (true) for σ ∈ (0, π], ω ∈ [0, π],
// with the candidate of least cancellation and its error estimate u·κ·(16 + 2√m).
//
// σ > π/2: C = S² ∖ C' with C' the cap (−L, π − σ) at angle π − ω, and ∫_H z^k dΩ = 2π/(k + 1), so
// P(k) = 2π − P'(k): from the forward sum 2π − F', from the tail 2π(1 − [c ∈ C']) + T' (no
// cancellation when the pole lies in C', where the region is small). The circle and its arc are
// the same, so f_m and the horizon arc carry over (the latter as 2π − K').
//
// Double-axis moment (divergence theorem with X = z^n (L − (L·u)u), which vanishes on the horizon
// for n ≥ 1; for n = 0 the horizon contributes −cos ω per unit length):
//     n ≥ 1: (n + 2) D(n) = cos ω P(n − 1) + sin²σ f_n,      n = 0: 2 D(0) = sin²σ f_0 + cos ω K.
// Where the region is a sliver below the pole (cos ω < 0) the two terms cancel by ~1/z_max
// (1e+32 for σ = π/2 and ω = π in doubles). Putting P(n − 1) in its tail form and f_n =
// Σ_k (f_{n+2k} − f_{n+2k+2}) and collecting under one integral over the arc gives, for every
// n ≥ 0 (the horizon terms cancel at n = 0) and both sizes of cap,
//     (n + 2) D(n) = 2π cos ω [c ∈ C] + ∫_arc z^n B(z)/(1 − z²) dψ,  B = (β² − a²) + a z − sin²σ z²,
// i.e. (β² − a²) F_n + a F_{n+1} − sin²σ F_{n+2} with F_m = Σ_k f_{m+2k}: B is concave and
// B(0) = q², B(z_max) = z_max sin σ cos σ sin(ω − σ), so only the three terms of B can cancel, by
// ~1/cos σ at worst (10 for that sliver).
//
// The error estimate adds the rounding of ω − σ in z_max = cos(ω − σ), which the result magnifies
// by ~(n + 2)/z_max when the region is a sliver under the horizon's edge of the circle.
template <class R>
Estimate<R> clipped_cap_moment(R omega, R sigma, int n, bool times_cap_axis) {
  const R pi = real::pi<R>(), two_pi = 2 * pi;
  const bool big = sigma > pi / 2;
  const R w = big ? pi - omega : omega, s = big ? pi - sigma : sigma;
  const R cos_omega = real::cos(omega), sin_sigma = real::sin(sigma);
  const int k = times_cap_axis ? n - 1 : n;  // order of P needed; −1: none
  const R underflow = R(1e-300) * R(1e-30);  // below every double
  const R negligible =
      big ? R(1e-40) * two_pi * (times_cap_axis ? real::abs(cos_omega) : R(1)) + underflow : underflow;

  // The candidate of least cancellation with the arc integrals of `cap`.
  auto best_of = [&](const SmallCap<R>& cap) {
    std::vector<Sum<R>> candidates;  // of P(k)
    if (k >= 0) {
      const Sum<R> fw = cap.forward(k);
      candidates.push_back(big ? Sum<R>{two_pi - fw.value, two_pi + fw.magnitude} : fw);
      if (!cap.zero() && cap.has_tail()) {
        const Sum<R> t = cap.tail(k);
        const R p = cap.pole();
        candidates.push_back(big ? Sum<R>{two_pi * (1 - p) + t.value, two_pi * (1 - p) + t.magnitude}
                                 : Sum<R>{two_pi * p - t.value, two_pi * p + t.magnitude});
      }
    }
    std::vector<Sum<R>> results;
    if (!times_cap_axis) {
      for (const Sum<R>& p : candidates) results.push_back({p.value / R(n + 1), p.magnitude / R(n + 1)});
    } else {
      const R rim = sin_sigma * sin_sigma * cap.f(n);
      if (n == 0) {
        const R horizon = big ? two_pi - cap.horizon_arc() : cap.horizon_arc();
        const R t = cos_omega * horizon;
        results.push_back({(rim + t) / 2, (rim + real::abs(t)) / 2});
      } else {
        for (const Sum<R>& p : candidates)
          results.push_back(
              {(cos_omega * p.value + rim) / R(n + 2), (real::abs(cos_omega) * p.magnitude + rim) / R(n + 2)});
      }
      if (!cap.zero() && cap.has_tail()) {
        const R pole = big ? 1 - cap.pole() : cap.pole();
        const R t0 = two_pi * cos_omega * pole, t1 = cap.q2() * cap.tail_f(n), t2 = cap.a() * cap.tail_f(n + 1),
                t3 = -sin_sigma * sin_sigma * cap.tail_f(n + 2);
        results.push_back(
            {(t0 + t1 + t2 + t3) / R(n + 2), (real::abs(t0) + real::abs(t1) + real::abs(t2) + real::abs(t3)) / R(n + 2)});
      }
    }
    Sum<R> best = results.front();
    for (const Sum<R>& r : results)
      if (condition(r) < condition(best)) best = r;
    return best;
  };

  // The forward sums alone first (no tail to build); the tails only where those cancel.
  const int m_f = times_cap_axis ? n + 2 : -1;
  const SmallCap<R> forward_only(w, s, std::max(k, 0), std::max(k, 0), m_f, negligible, false);
  Sum<R> best = best_of(forward_only);
  int length = forward_only.length();
  if (condition(best) > 4) {
    const SmallCap<R> cap(w, s, std::max(k, 0), std::max(k, 0), m_f, negligible, true);
    const Sum<R> with_tail = best_of(cap);
    if (condition(with_tail) < condition(best)) {
      best = with_tail;
      length = cap.length();
    }
  }
  const R u = unit_roundoff<R>();
  R error = u * condition(best) * (16 + 2 * real::sqrt(R(length)));
  if (!forward_only.zero() && forward_only.z_max() < R(0.5))
    error += u * (real::abs(w) + real::abs(s)) / forward_only.z_max() * R(std::max(n, 0) + 2);
  return {best.value, error};
}

using Evaluation = Escalated<double>;

// Long double first; __float128 when the estimate exceeds 4e−16 (a few ulps of the double result).
template <class Angle>
Evaluation evaluate(Angle&& omega_in, double sigma, int n, bool times_cap_axis) {
  return escalate(
      [&](auto zero) {
        using R = decltype(zero);
        const auto e = clipped_cap_moment<R>(omega_in(zero), R(sigma), n, times_cap_axis);
        return Attempt<double>{double(e.value), double(e.relative_error)};
      },
      4e-16, long_double_precision);
}

Evaluation clipped_cap(double omega, double sigma, int n, bool times_cap_axis) {
  return evaluate([&](auto zero) { return decltype(zero)(omega); }, sigma, n, times_cap_axis);
}

// The same with ω measured between two vectors in the working precision (atan2 of |a×b| and a·b,
// never acos: DESIGN.md §3).
Evaluation clipped_cap(const Vec3& axis, const Vec3& clip, double sigma, int n, bool times_cap_axis) {
  return evaluate(
      [&](auto zero) {
        using R = decltype(zero);
        const real::V3<R> a(axis), b(clip);
        return real::atan2(real::norm(cross(a, b)), dot(a, b));
      },
      sigma, n, times_cap_axis);
}

constexpr int kMaxPower = 100000;

void check_power(long long n) {
  if (n < 0 || n > kMaxPower)
    throw Error("cap moments take powers from 0 to " + std::to_string(kMaxPower) + ", not " + std::to_string(n));
}

// Whether a is a positive multiple of b (both finite, non-zero), within 1e−12 radians.
bool positively_parallel(const Vec3& a, const Vec3& b) {
  const Vec3 ua = normalized(a), ub = normalized(b);
  return dot(ua, ub) > 0 && norm(cross(ua, ub)) <= 1e-12;
}

// "[x, y, z]" to 17 significant digits, for messages (std::to_chars: no streams in a kernel).
std::string vector_text(const Vec3& v) {
  std::string out = "[";
  for (const double c : {v.x, v.y, v.z}) {
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof buf, c, std::chars_format::general, 17).ptr;
    out.append(buf, end).append(", ");
  }
  out.resize(out.size() - 2);
  return out + "]";
}

// 1 − cos^m σ without cancellation: −expm1(m ln cos σ) with ln cos σ = log1p(−2 sin²(σ/2)) for
// σ < π/3; for σ > 2π/3 the same with |cos σ| = 1 − 2 cos²(σ/2); between, |cos σ| ≤ ½ and the
// plain form cannot cancel.
double one_minus_cos_power(double sigma, int m) {
  if (sigma < M_PI / 3) {
    const double s = std::sin(sigma / 2);
    return -std::expm1(m * std::log1p(-2 * s * s));
  }
  if (sigma <= 2 * M_PI / 3) return 1 - std::pow(std::cos(sigma), m);
  const double c = std::cos(sigma / 2);
  const double log_magnitude = std::log1p(-2 * c * c);  // ln |cos σ|
  return m % 2 == 0 ? -std::expm1(m * log_magnitude) : 1 + std::exp(m * log_magnitude);
}

}  // namespace

double clipped_cap_axial_moment(double omega, double half_angle, int n) {
  check_power(n);
  if (!(half_angle > 0)) return 0;
  return clipped_cap(std::clamp(omega, 0.0, M_PI), std::min(half_angle, M_PI), n, false).value;
}

double clipped_cap_double_axis_moment(double omega, double half_angle, int n) {
  check_power(n);
  if (!(half_angle > 0)) return 0;
  return clipped_cap(std::clamp(omega, 0.0, M_PI), std::min(half_angle, M_PI), n, true).value;
}

double cap_moment(const Vec3& cap_axis, double half_angle, const std::optional<Vec3>& clip,
                  const std::vector<Factor>& factors) {
  if (!is_finite(cap_axis) || !(norm(cap_axis) > 0)) throw Error("the cap axis must be a finite non-zero vector");
  if (!(half_angle > 0 && half_angle <= M_PI))
    throw Error("the cap half-angle must be in (0, pi] radians");
  if (clip && (!is_finite(*clip) || !(norm(*clip) > 0))) throw Error("the clip normal must be a finite non-zero vector");

  long long clip_power = 0, axis_power = 0;
  double scale = 1;
  for (const Factor& f : factors) {
    if (f.power < 0) throw Error("factor powers must be non-negative");
    if (f.power == 0) continue;
    if (f.power > kMaxPower || clip_power + axis_power + f.power > 2 * kMaxPower)
      throw Error("cap moments take powers up to " + std::to_string(kMaxPower));
    if (!is_finite(f.axis) || !(norm(f.axis) > 0)) throw Error("a factor axis must be a finite non-zero vector");
    if (clip && positively_parallel(f.axis, *clip)) clip_power += f.power;
    else if (positively_parallel(f.axis, cap_axis)) axis_power += f.power;
    else
      throw Error("cap moment: the factor axis " + vector_text(f.axis) +
                  " is parallel neither to the clip normal nor to the cap axis; supported: (c^n) and "
                  "(c^n, L^1) with a clip c, (L^k) without (L the cap axis)");
    scale *= std::pow(norm(f.axis), f.power);
  }

  double value = 0, error = 0;
  if (clip) {
    if (axis_power > 1)
      throw Error("cap moment: the factor pattern (c^" + std::to_string(clip_power) + ", L^" +
                  std::to_string(axis_power) + ") is not supported; supported with a clip c: (), (c^n), (c^n, L^1)");
    check_power(clip_power);
    const Evaluation e = clipped_cap(cap_axis, *clip, half_angle, int(clip_power), axis_power == 1);
    value = e.value;
    error = e.relative_error;
  } else {
    check_power(axis_power);
    value = 2 * M_PI * one_minus_cos_power(half_angle, int(axis_power) + 1) / double(axis_power + 1);
    error = 1e-15;
  }
  if (!(error <= 1e-10))
    throw Error("cap moment: the estimated relative error " + std::to_string(error) + " exceeds 1e-10");
  const double result = scale * value;
  if (!std::isfinite(result) || (scale == 0 && value != 0))
    throw Error("the factors' lengths raised to their powers overflow or underflow double");
  return result;
}

}  // namespace daylit
