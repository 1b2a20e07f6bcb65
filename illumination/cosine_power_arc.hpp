#pragma once
// Powers of a cosine integrated along one great arc, in the arc's own frame, to a few ulp relative
// at every order: the building block of every moment in moments.hpp (DESIGN.md §7).

#include <cmath>
#include <optional>
#include <vector>

#include "illumination/arc_edge.hpp"
#include "illumination/tracked_sum.hpp"

namespace daylit {

// Along the arc u(t), t ∈ [0, θ], a unit axis w has z(t) = w·u(t) = c cos(t − φ), with c the
// length of w's projection onto the arc's plane (Arvo 1995, eq. 18). With s = t − φ running over
// [s0, s1 = s0 + θ], Arvo's F_k = ∫ cos^k s ds obeys his eq. 19,
//     k F_k = E_{k−1} + (k − 1) F_{k−2},   E_j = cos^j s1 sin s1 − cos^j s0 sin s0,
// with F_0 = θ and F_1 = sin s1 − sin s0, and the edge integrals are G_k = ∫_arc z^k ds = c^k F_k.
//
// Which direction to run the recurrence. Its homogeneous solution decays like 1/√k, so run
// upwards it keeps the absolute error of F_0 and F_1; that is a relative error as long as F_k
// decays no faster, i.e. while the arc holds a maximum of |cos s| (s = 0 or π: the point of the
// great circle nearest to ±w). Otherwise F_k ~ r^k with r = max |cos s| < 1 on the arc, and the
// upward recurrence loses a factor 1/r per order; then we run it downwards from a start K far
// enough above (Miller's algorithm: the start's error shrinks by r per order on the way down).
//
// The differences E_j are formed without subtracting nearly equal numbers: with D_j = cos^j s1 −
// cos^j s0, D_j = cos s1 · D_{j−1} + cos^{j−1} s0 · (cos s1 − cos s0) and E_j = D_j sin s1 +
// cos^j s0 (sin s1 − sin s0), where cos s1 − cos s0 = w·chord / c and sin s1 − sin s0 =
// −w·(m × chord) / c come from the arc's chord (arc_edge.hpp). A 1e-9 rad edge keeps its digits.
template <class R>
class CosinePowerArc {
 public:
  // w must be a unit vector.
  CosinePowerArc(const ArcEdge<R>& arc, const real::V3<R>& w) : arc_(arc) {
    X_ = dot(w, arc.start);
    beta_ = dot(w, arc.start_tangent);
    Y_ = dot(w, arc.end);
    gamma_ = dot(w, arc.end_tangent);
    wm_ = dot(w, arc.normal);
    c_ = real::sqrt(X_ * X_ + beta_ * beta_);
    theta_ = arc.length;
    if (!(c_ > 0)) return;
    cos0_ = X_ / c_;
    sin0_ = -beta_ / c_;
    cos1_ = Y_ / c_;
    sin1_ = -gamma_ / c_;
    dcos_ = dot(w, arc.chord) / c_;
    dsin_ = -dot(w, cross(arc.normal, arc.chord)) / c_;
    // Where the arc lies on its circle, in double: it only chooses the recurrence's direction.
    const double pi = 3.14159265358979323846;
    const double s0 = std::atan2(double(sin0_), double(cos0_)), s1 = s0 + double(theta_);
    const bool holds_maximum = (s0 <= 0 && 0 <= s1) || (s0 <= pi && pi <= s1);
    r_ = holds_maximum ? 1.0 : std::max(std::abs(double(cos0_)), std::abs(double(cos1_)));
    cos_changes_sign_ = (s0 <= pi / 2 && pi / 2 <= s1) || (s0 <= -pi / 2 && -pi / 2 <= s1) ||
                        (s0 <= 1.5 * pi && 1.5 * pi <= s1);
  }

  const ArcEdge<R>& arc() const { return arc_; }
  R c() const { return c_; }
  R w_dot_normal() const { return wm_; }  // w·m, m the arc's pole

  // G_k = ∫_arc (w·u)^k ds for k = 0..k_max by the upward recurrence: exact in the absolute
  // sense (errors never grow), relative as well where forward_is_stable(k_max).
  std::vector<R> forward(int k_max) const {
    std::vector<R> F(std::size_t(k_max) + 1, R(0));
    F[0] = theta_;
    if (k_max == 0 || !(c_ > 0)) return F;
    F[1] = dsin_;
    R D = 0, cos0_j = 1;  // D_j and cos^j s0, j = 0
    for (int j = 1; j + 1 <= k_max; ++j) {
      D = cos1_ * D + cos0_j * dcos_;
      cos0_j *= cos0_;
      const R E = D * sin1_ + cos0_j * dsin_;
      F[j + 1] = (E + R(j) * F[j - 1]) / R(j + 1);
    }
    R ck = 1;
    for (int k = 1; k <= k_max; ++k) F[k] *= (ck *= c_);
    return F;
  }

  // F_k = ∫ cos^k s ds (without the factor c^k) and D_k = cos^k s1 − cos^k s0 for k = 0..k_max by
  // the upward recurrence: for the low orders (≲ 20) of fused kernels, where it is accurate.
  void forward_normalized(int k_max, std::vector<R>& F, std::vector<R>& D) const {
    F.assign(std::size_t(k_max) + 1, R(0));
    D.assign(std::size_t(k_max) + 1, R(0));
    F[0] = theta_;
    if (!(c_ > 0) || k_max == 0) return;
    F[1] = dsin_;
    D[1] = dcos_;
    R cos0_j = cos0_;  // cos^j s0 for j = 1
    for (int j = 1; j + 1 <= k_max; ++j) {
      const R E = D[j] * sin1_ + cos0_j * dsin_;
      F[j + 1] = (E + R(j) * F[j - 1]) / R(j + 1);
      D[j + 1] = cos1_ * D[j] + cos0_j * dcos_;
      cos0_j *= cos0_;
    }
  }

  // G_k alone, to a few ulp relative, choosing the stable direction.
  R G(int k) const {
    if (k == 0) return theta_;
    if (!(c_ > 0)) return R(0);
    return real::powi(c_, k) * (forward_is_stable(k) ? forward_F(k) : backward_F(k, k));
  }

  // The tail Σ_{j ≥ 0} G_{k0 + 2j} to a few ulp relative (the series converges like (c·r)^{2j}),
  // with the sum of the absolute values of its terms (tracked_sum.hpp). Fails (nullopt) where the
  // series converges too slowly to sum: the arc passes within ~1e-3 rad of ±w.
  std::optional<real::Tracked<R>> tail(int k0) const {
    real::Tracked<R> sum;
    if (!(c_ > 0)) {
      if (k0 == 0) sum.add(theta_);
      return sum;
    }
    const double cr = double(c_) * r_;
    const double log_u = std::log(double(real::unit_roundoff<R>()));
    if (r_ < 1 && cr < 1) {
      // Terms up to j = J reach u relative; Miller's start above that.
      const int J = int(std::ceil((log_u - 2) / (2 * std::log(cr)))) + 1;
      const int k_top = k0 + 2 * J;
      if (!forward_is_stable(k_top)) {
        std::vector<R> F;
        backward_F(k0, k_top, &F);
        R ck = real::powi(c_, k0);
        const R c2 = c_ * c_;
        for (const R& f : F) {
          sum.add(ck * f);
          ck *= c2;
        }
        return sum;
      }
    }
    if (!(cr < 1)) return std::nullopt;
    // Upward, stable here: stop once the rest, bounded by c^k ∫|cos|^k · (c r)²/(1 − (c r)²)
    // since |cos s| ≤ r on the arc, is below u of the sum.
    const R c2 = c_ * c_;
    const R ratio = R(cr * cr / (1 - cr * cr));
    R ck = real::powi(c_, k0);
    auto add_term = [&](long k, R Fk) {  // true once converged
      sum.add(ck * Fk);
      const R abs_integral = (k % 2 == 0 || !cos_changes_sign_) ? real::abs(Fk) : theta_;
      const R bound = ck * abs_integral * ratio;
      ck *= c2;
      return bound <= real::unit_roundoff<R>() * real::abs(sum.value);
    };
    if (k0 == 0 && add_term(0, theta_)) return sum;
    if (k0 == 1 && add_term(1, dsin_)) return sum;
    const long last = 21L * k0 + 200000;  // ~1e-3 rad from ±w: give up
    R F_prev = theta_, F_cur = dsin_;    // F_{k−2}, F_{k−1} for k = 2
    R D = 0, cos0_j = 1;
    for (long k = 2; k <= last; ++k) {
      D = cos1_ * D + cos0_j * dcos_;
      cos0_j *= cos0_;
      const R E = D * sin1_ + cos0_j * dsin_;
      const R F_next = (E + R(k - 1) * F_prev) / R(k);
      F_prev = F_cur;
      F_cur = F_next;
      if (k >= k0 && (k - k0) % 2 == 0 && add_term(k, F_next)) return sum;
    }
    return std::nullopt;
  }

  // Σ G_i over i = first, first + 2, …, ≤ last by the upward recurrence, stopped once the rest is
  // bounded below tolerance·|sum| (Arvo 1995 §5.4, eq. 21; the bound as in tail()). Adds the
  // bound on what was dropped to *dropped and the orders evaluated to *terms.
  R truncated_sum(int first, int last, double tolerance, R* dropped, int* terms) const {
    R sum = 0;
    if (!(c_ > 0)) {
      ++*terms;
      return first == 0 ? theta_ : R(0);
    }
    const double cr = double(c_) * r_;
    const R ratio = cr < 1 ? R(cr * cr / (1 - cr * cr)) : R(HUGE_VAL);
    R F_prev = theta_, F_cur = dsin_, D = 0, cos0_j = 1, ck = 1;  // F_{k−2}, F_{k−1}, c^k
    for (int k = 0; k <= last; ++k) {
      R Fk;
      if (k < 2) {
        Fk = k == 0 ? theta_ : dsin_;
      } else {
        D = cos1_ * D + cos0_j * dcos_;
        cos0_j *= cos0_;
        Fk = (D * sin1_ + cos0_j * dsin_ + R(k - 1) * F_prev) / R(k);
        F_prev = F_cur;
        F_cur = Fk;
      }
      if (k >= first && (k - first) % 2 == 0) {
        ++*terms;
        sum += ck * Fk;
        const R abs_integral = (k % 2 == 0 || !cos_changes_sign_) ? real::abs(Fk) : theta_;
        const R rest = ck * abs_integral * ratio;
        if (k + 2 <= last && rest <= R(tolerance) * real::abs(sum)) {
          *dropped += rest;
          return sum;
        }
      }
      ck *= c_;
    }
    return sum;
  }

  // Bound on |G_k| = c^k |F_k| ≤ c^k θ r^k, in O(1).
  R G_bound(int k) const { return real::powi(c_, k) * theta_ * R(std::pow(r_, k)); }

  // D_{k} = cos^k s1 − cos^k s0 (Arvo's endpoint powers), without cancellation.
  R cos_power_difference(int k) const {
    if (!(c_ > 0)) return R(0);
    R D = 0, cos0_j = 1;
    for (int j = 1; j <= k; ++j) {
      D = cos1_ * D + cos0_j * dcos_;
      cos0_j *= cos0_;
    }
    return D;
  }

  // Unit vectors of the arc's plane: p where s = 0 (nearest to w) and q = m × p (increasing s).
  // Only meaningful for c > 0.
  real::V3<R> peak_direction() const { return (X_ * arc_.start + beta_ * arc_.start_tangent) / c_; }
  real::V3<R> peak_tangent() const { return (X_ * arc_.start_tangent - beta_ * arc_.start) / c_; }

  // The complete series Σ_k G_k of one parity as closed forms, times w·m:
  //     (w·m) ∫_arc dz/(1 − z²) ds   (even k)   and   (w·m) ∫_arc z/(1 − z²) ds   (odd k).
  // With κ = |w·m| = √(1 − c²): ∫ ds/(1 − c² cos² s) = [atan2(sin s, κ cos s)]/κ, and
  // ∫ c cos s/(1 − c² cos² s) ds = [atan2(c sin s, κ)]/κ; the factor w·m = ±κ cancels the 1/κ,
  // so neither form divides by a small number. Singular only where the arc passes through ±w.
  R even_series_times_wm() const {
    if (!(c_ > 0)) return wm_ * theta_;
    const R kappa = real::abs(wm_);
    R delta = real::atan2(-gamma_, kappa * Y_) - real::atan2(-beta_, kappa * X_);
    // The true increase lies in [0, π] for an arc of length θ ≤ π (tan has period π).
    if (delta < R(-1.5707963267948966)) delta += R(2) * real::pi<R>();
    return wm_ < 0 ? -delta : (wm_ > 0 ? delta : R(0));
  }
  R odd_series_times_wm() const {
    if (!(c_ > 0)) return R(0);
    const R kappa = real::abs(wm_);
    const R delta = real::atan2(-gamma_, kappa) - real::atan2(-beta_, kappa);
    return wm_ < 0 ? -delta : (wm_ > 0 ? delta : R(0));
  }

 private:
  bool forward_is_stable(int k) const { return r_ >= 1 || double(k) * std::log(r_) >= std::log(1e-4); }

  R forward_F(int k) const {
    R F_prev = theta_, F_cur = dsin_;
    if (k == 0) return F_prev;
    R D = 0, cos0_j = 1;
    for (int j = 1; j + 1 <= k; ++j) {
      D = cos1_ * D + cos0_j * dcos_;
      cos0_j *= cos0_;
      const R E = D * sin1_ + cos0_j * dsin_;
      const R F_next = (E + R(j) * F_prev) / R(j + 1);
      F_prev = F_cur;
      F_cur = F_next;
    }
    return F_cur;
  }

  // F_k for k = k_lo, k_lo + 2, …, k_hi by Miller's downward recurrence from F_K = 0, K − k_hi
  // chosen so that r^{K − k_hi} < u. Returns F_{k_lo}; fills *all (ascending) when given.
  R backward_F(int k_lo, int k_hi, std::vector<R>* all = nullptr) const {
    const double log_u = std::log(double(real::unit_roundoff<R>()));
    int extra = int(std::ceil((log_u - 4) / std::log(r_))) + 2;
    extra += extra % 2;
    const int K = k_hi + extra;
    // E_j for j < K, upward (the D recurrence is stable: no cancellation between its terms).
    std::vector<R> E(std::size_t(K), R(0));
    R D = 0, cos0_j = 1;
    for (int j = 1; j < K; ++j) {
      D = cos1_ * D + cos0_j * dcos_;
      cos0_j *= cos0_;
      E[j] = D * sin1_ + cos0_j * dsin_;
    }
    if (all) all->assign(std::size_t((k_hi - k_lo) / 2) + 1, R(0));
    R F = 0;  // F_K
    for (int k = K; k > k_lo; k -= 2) {
      F = (R(k) * F - E[k - 1]) / R(k - 1);  // F_{k−2}
      const int i = k - 2;
      if (all && i <= k_hi) (*all)[std::size_t((i - k_lo) / 2)] = F;
    }
    return F;
  }

  ArcEdge<R> arc_;
  R X_ = 0, beta_ = 0, Y_ = 0, gamma_ = 0, wm_ = 0, c_ = 0, theta_ = 0;
  R cos0_ = 1, sin0_ = 0, cos1_ = 1, sin1_ = 0, dcos_ = 0, dsin_ = 0;
  double r_ = 1;
  bool cos_changes_sign_ = false;
};

}  // namespace daylit
