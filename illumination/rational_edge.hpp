#pragma once
// Per-edge building blocks of the rational moments (rational_moments.cpp): an arc in the frame
// of the denominator's axis w, the integrals G(r, t) = ∫ sin^r s cos^t s ds over it, and numbers
// that carry the magnitude of what was summed into them (tracked_sum.hpp), to estimate cancellation.

#include <algorithm>
#include <vector>

#include "illumination/arc_edge.hpp"
#include "illumination/clausen.hpp"
#include "illumination/tracked_sum.hpp"

namespace daylit::rational {

using real::exact;
using real::Tracked;

// One great arc in the frame of a unit axis w with w·u > 0 on it: u(s) = p cos s + q sin s for
// s ∈ [s0, s1], s1 − s0 = θ, with w·u = c cos s (Chen and Arvo 2000, eq. 32; Arvo 1995, eq. 18).
// The endpoint cosines and sines come from dot products, and their differences from the chord,
// as in cosine_power_arc.hpp, so that short arcs keep their digits. Requires c > 0, which holds
// where w·u > 0 at the endpoints (|s0|, |s1| < π/2 then).
template <class R>
struct WFrameArc {
  ArcEdge<R> arc;
  R c, wm;  // length of w's projection on the arc's plane; w·m
  R cos0, sin0, cos1, sin1, dcos, dsin;
  real::V3<R> p, q;

  WFrameArc(const ArcEdge<R>& e, const real::V3<R>& w) : arc(e) {
    const R X = dot(w, e.start), beta = dot(w, e.start_tangent);
    wm = dot(w, e.normal);
    c = real::sqrt(X * X + beta * beta);
    cos0 = X / c;
    sin0 = -beta / c;
    cos1 = dot(w, e.end) / c;
    sin1 = -dot(w, e.end_tangent) / c;
    dcos = dot(w, e.chord) / c;
    dsin = -dot(w, cross(e.normal, e.chord)) / c;
    p = (X * e.start + beta * e.start_tangent) / c;
    q = (X * e.start_tangent - beta * e.start) / c;
  }

  // |w·m|: √(1 − c²) from the pole, accurate where c → 1.
  R kappa() const { return real::abs(wm); }
};

// G(r, t) = ∫_{s0}^{s1} sin^r s cos^t s ds for 0 ≤ r ≤ r_max, t_min ≤ t ≤ t_max (t_min ≥ −∞ is
// fine: cos s > 0 on the arc). Recurrences of the linearly-varying paper (§3.3):
//   r = 0, t ≥ 2: t G(0,t) = [sin s cos^{t−1} s] + (t − 1) G(0, t−2)  (Arvo's eq. 19, upward, exact
//     in the absolute sense), with the endpoint differences from the chord as in
//     cosine_power_arc.hpp; G(0,0) = θ, G(0,1) = sin s1 − sin s0;
//   r = 0, t < 0: G(0,−1) = atanh((sin s1 − sin s0)/(1 − sin s0 sin s1)) (the paper's log tan form
//     without its cancellation), G(0,−2) = sin θ/(cos s0 cos s1), and downward
//     (t + 1) G(0,t) = (t + 2) G(0,t+2) − [sin s cos^{t+1} s];
//   r = 1: G(1,t) = −[cos^{t+1} s]/(t + 1), G(1,−1) = −log1p((cos s1 − cos s0)/cos s0);
//   r ≥ 2: (r + t) G(r,t) = (r − 1) G(r−2,t) − [sin^{r−1} s cos^{t+1} s], and where r + t = 0,
//     G(r,t) = G(r−2,t) − G(r−2,t+2) (sin² = 1 − cos²).
// Every entry carries the magnitude of its terms.
template <class R>
class GTable {
 public:
  // Entries with r + t > max_sum are left at zero (the recurrences for r + t ≤ max_sum never read
  // them): the moments of order n need only r + t ≤ n, half the table.
  GTable(const WFrameArc<R>& e, int r_max, int t_min, int t_max, int max_sum = 1 << 30)
      : r_max_(r_max), t_min_(t_min), t_max_(t_max + 2), width_(t_max_ - t_min + 1) {
    g_.assign(std::size_t(r_max + 1) * width_, Tracked<R>{});
    // D_j = cos^j s1 − cos^j s0 without cancellation: D_j = cos s1 D_{j−1} + cos^{j−1} s0 (cos s1 − cos s0).
    const int j_max = std::max(t_max_ + 1, -t_min_ + 1) + 1;
    std::vector<R> D(std::size_t(j_max) + 1, R(0)), c0(std::size_t(j_max) + 1, R(1));
    for (int j = 1; j <= j_max; ++j) {
      D[j] = e.cos1 * D[j - 1] + c0[j - 1] * e.dcos;
      c0[j] = c0[j - 1] * e.cos0;
    }
    // Powers of the endpoint sines (0 ... r_max) and cosines (t_min + 1 ... t_max_ + 1).
    std::vector<R> s0(std::size_t(r_max_) + 1, R(1)), s1 = s0;
    for (int i = 1; i <= r_max_; ++i) s0[i] = s0[i - 1] * e.sin0, s1[i] = s1[i - 1] * e.sin1;
    const int k_lo = std::min(t_min_ + 1, 0), k_hi = t_max_ + 1;
    std::vector<R> c0p(std::size_t(k_hi - k_lo) + 1), c1p(c0p.size());
    c0p[-k_lo] = c1p[-k_lo] = R(1);
    for (int k = 1; k <= k_hi; ++k) c0p[k - k_lo] = c0p[k - 1 - k_lo] * e.cos0, c1p[k - k_lo] = c1p[k - 1 - k_lo] * e.cos1;
    for (int k = -1; k >= k_lo; --k) c0p[k - k_lo] = c0p[k + 1 - k_lo] / e.cos0, c1p[k - k_lo] = c1p[k + 1 - k_lo] / e.cos1;
    auto endpoint = [&](int sin_power, int cos_power) {  // [sin^i s cos^k s]_{s0}^{s1}, magnitude
      const R b = s1[sin_power] * c1p[cos_power - k_lo], a = s0[sin_power] * c0p[cos_power - k_lo];
      return Tracked<R>{b - a, real::abs(b) + real::abs(a)};
    };
    // Column r = 0.
    at(0, 0) = exact(e.arc.length);
    if (t_max_ >= 1) at(0, 1) = exact(e.dsin);
    for (int t = 2; t <= t_max_; ++t) {
      // E_{t−1} = D_{t−1} sin s1 + cos^{t−1} s0 (sin s1 − sin s0).
      const R x = D[t - 1] * e.sin1, y = c0[t - 1] * e.dsin;
      const Tracked<R> E{x + y, real::abs(x) + real::abs(y)};
      at(0, t) = (E + R(t - 1) * at(0, t - 2)) / R(t);
    }
    if (t_min_ <= -1) {
      const R one_minus = (e.cos0 * e.cos0 + e.cos1 * e.cos1 + e.dsin * e.dsin) / 2;  // 1 − sin s0 sin s1
      at(0, -1) = exact(real::atanh(e.dsin / one_minus));
    }
    if (t_min_ <= -2) at(0, -2) = exact(e.arc.sin_length / (e.cos0 * e.cos1));
    for (int t = -3; t >= t_min_; --t) at(0, t) = (R(t + 2) * at(0, t + 2) - endpoint(1, t + 1)) / R(t + 1);
    // Column r = 1.
    if (r_max_ >= 1)
      for (int t = t_min_; t <= t_max_; ++t) {
        if (t == -1) {
          at(1, t) = exact(-real::log1p(e.dcos / e.cos0));
        } else if (t >= 0) {
          at(1, t) = exact(-D[t + 1] / R(t + 1));
        } else {
          const int k = -(t + 1);  // cos^{−k} s1 − cos^{−k} s0 = −D_k/(cos s0 cos s1)^k
          at(1, t) = exact(D[k] / (real::powi(e.cos0 * e.cos1, k) * R(t + 1)));
        }
      }
    // Columns r ≥ 2.
    for (int r = 2; r <= r_max_; ++r)
      for (int t = t_min_; t <= std::min(t_max_, max_sum - r); ++t) {
        if (r + t != 0)
          at(r, t) = (R(r - 1) * at(r - 2, t) - endpoint(r - 1, t + 1)) / R(r + t);
        else
          at(r, t) = at(r - 2, t) - at(r - 2, t + 2);
      }
  }

  const Tracked<R>& operator()(int r, int t) const { return g_[std::size_t(r) * width_ + (t - t_min_)]; }

 private:
  Tracked<R>& at(int r, int t) { return g_[std::size_t(r) * width_ + (t - t_min_)]; }
  int r_max_, t_min_, t_max_, width_;
  std::vector<Tracked<R>> g_;
};

// Coefficients P_r of Π_i (A_i cos s + B_i sin s) = Σ_r P_r sin^r s cos^{m−r} s, and those of the
// same product with |A_i|, |B_i| (the magnitudes of the expansion's terms).
template <class R>
void trig_product(const std::vector<std::pair<R, R>>& factors, std::vector<R>& P, std::vector<R>& Pm) {
  P.assign(1, R(1));
  Pm.assign(1, R(1));
  for (const auto& [A, B] : factors) {
    std::vector<R> next(P.size() + 1, R(0)), next_m(P.size() + 1, R(0));
    for (std::size_t r = 0; r < P.size(); ++r) {
      next[r] += A * P[r];
      next[r + 1] += B * P[r];
      next_m[r] += real::abs(A) * Pm[r];
      next_m[r + 1] += real::abs(B) * Pm[r];
    }
    P.swap(next);
    Pm.swap(next_m);
  }
}

// ∫_arc Σ_r P_r sin^r s cos^{m−r+t} s ds = Σ_r P_r G(r, m − r + t) (m = P.size() − 1).
template <class R>
Tracked<R> expand_integral(const GTable<R>& G, const std::vector<R>& P, const std::vector<R>& Pm, int t) {
  const int m = int(P.size()) - 1;
  Tracked<R> sum;
  for (int r = 0; r <= m; ++r) {
    if (P[r] == 0 && Pm[r] == 0) continue;
    const Tracked<R>& g = G(r, m - r + t);
    sum.value += P[r] * g.value;
    sum.magnitude += Pm[r] * g.magnitude;
  }
  return sum;
}

}  // namespace daylit::rational
