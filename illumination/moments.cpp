#include "illumination/moments.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "illumination/cosine_power_arc.hpp"
#include "illumination/precision_escalation.hpp"
#include "illumination/solid_angle.hpp"

namespace daylit {

namespace {

template <class R>
using Sum = real::Tracked<R>;

template <class R>
Sum<R> lambert_sum(const SphericalRegion& region, const Vec3& n_in) {
  const real::V3<R> n(n_in);
  Sum<R> sum;
  for_each_edge<R>(region, [&](const ArcEdge<R>& arc) { sum.add(R(0.5) * arc.length * dot(arc.normal, n)); });
  return sum;
}

// The edges of the region in the frame of a unit axis w, in precision R.
template <class R>
std::vector<CosinePowerArc<R>> arcs_about(const SphericalRegion& region, const real::V3<R>& w) {
  std::vector<CosinePowerArc<R>> arcs;
  for_each_edge<R>(region, [&](const ArcEdge<R>& arc) { arcs.emplace_back(arc, w); });
  return arcs;
}

// τ^k and the magnitudes of their terms, k = 0..n, for a unit axis (eq. 11 unrolled: with unit w,
// (k + 1) τ^k = σ [k even] + Σ_edges (w·m) Σ_{i ≤ k−1, i ≡ k−1 mod 2} G_i).
template <class R>
std::vector<Sum<R>> axial_moment_sums(const std::vector<CosinePowerArc<R>>& arcs, const Sum<R>& sigma, int n) {
  std::vector<Sum<R>> boundary(static_cast<std::size_t>(n) + 1);  // boundary[i] = Σ (w·m) G_i
  if (n > 0)
    for (const auto& arc : arcs) {
      const std::vector<R> G = arc.forward(n - 1);
      for (int i = 0; i < n; ++i) boundary[i].add(arc.w_dot_normal() * G[i]);
    }
  std::vector<Sum<R>> tau(static_cast<std::size_t>(n) + 1);
  Sum<R> even = sigma, odd;  // running (k + 1) τ^k for even and odd k
  tau[0] = sigma;
  for (int k = 1; k <= n; ++k) {
    Sum<R>& running = k % 2 == 0 ? even : odd;
    running += boundary[k - 1];
    tau[k] = running / R(k + 1);
  }
  return tau;
}

// The complementary form of τ^n (moments.hpp); nullopt where it does not apply (an edge within
// ~1e-3 rad of ±w, where the tails converge too slowly, or a winding number that does not come
// out an integer).
template <class R>
std::optional<Sum<R>> complementary_axial_sum(const std::vector<CosinePowerArc<R>>& arcs, const Sum<R>& sigma, int n) {
  const R two_pi = R(2) * real::pi<R>();
  R winding = n % 2 == 0 ? sigma.value : R(0);
  for (const auto& arc : arcs) winding += n % 2 == 0 ? arc.odd_series_times_wm() : arc.even_series_times_wm();
  winding /= two_pi;
  const R N = real::round(winding);
  if (!(real::abs(winding - N) < R(0.05))) return std::nullopt;
  Sum<R> out;
  out.add(two_pi * N);
  for (const auto& arc : arcs) {
    const std::optional<Sum<R>> tail = arc.tail(n + 1);
    if (!tail) return std::nullopt;
    out += -arc.w_dot_normal() * *tail;
  }
  return out / R(n + 1);
}

// τ^n for a unit axis by whichever of eq. 11 and the complementary form cancels less.
template <class R>
Sum<R> axial_moment_sum(const std::vector<CosinePowerArc<R>>& arcs, const Sum<R>& sigma, int n) {
  const Sum<R> forward = axial_moment_sums<R>(arcs, sigma, n)[n];
  if (forward.magnitude <= R(64) * real::abs(forward.value)) return forward;
  const std::optional<Sum<R>> complementary = complementary_axial_sum(arcs, sigma, n);
  if (complementary && tracked_condition(*complementary) < tracked_condition(forward)) return *complementary;
  return forward;
}

// ∫ (w·u)^n (v·u) dσ for a unit axis w (moments.hpp): (v·w) τ^{n+1} + Σ (v⊥·m) G_n / (n + 2).
template <class R>
Sum<R> double_axis_sum(const std::vector<CosinePowerArc<R>>& arcs, const Sum<R>& sigma, const real::V3<R>& w,
                       const real::V3<R>& v, int n) {
  const R vw = dot(v, w);
  const real::V3<R> v_perp = v - vw * w;
  Sum<R> result;
  if (vw != 0) {
    const Sum<R> tau = axial_moment_sum(arcs, sigma, n + 1);
    result += vw * tau;
  }
  for (const auto& arc : arcs) result.add(dot(v_perp, arc.arc().normal) * arc.G(n) / R(n + 2));
  return result;
}

// ∫ (w·u)^n (a⊥·u)(b⊥·u) dσ for unit w and a⊥, b⊥ ⟂ w (moments.hpp).
template <class R>
Sum<R> perpendicular_pair_sum(const std::vector<CosinePowerArc<R>>& arcs, const Sum<R>& sigma, const real::V3<R>& a_perp,
                              const real::V3<R>& b_perp, int n) {
  Sum<R> result;
  const R ab = dot(a_perp, b_perp);
  if (ab != 0) {
    const Sum<R> tau = axial_moment_sum(arcs, sigma, n);
    result += ab * tau;
  }
  for (const auto& arc : arcs) {
    const R bm = dot(b_perp, arc.arc().normal);
    if (bm == 0) continue;
    R line;  // ∫_arc (w·u)^n (a⊥·u) ds
    if (!(arc.c() > 0)) {
      // w ⟂ the arc's plane: (w·u)^n vanishes for n ≥ 1; for n = 0, ∫ (a⊥·u) ds directly.
      const auto& e = arc.arc();
      line = n > 0 ? R(0) : dot(a_perp, e.start) * e.sin_length + dot(a_perp, e.start_tangent) * e.one_minus_cos;
    } else {
      const R p = dot(a_perp, arc.peak_direction()), q = dot(a_perp, arc.peak_tangent());
      const R c = arc.c();
      // c^n F_{n+1} = G_{n+1}/c; the endpoint powers of cos^{n+1}: −D_{n+1}.
      line = p * arc.G(n + 1) / c - q * real::powi(c, n) * arc.cos_power_difference(n + 1) / R(n + 1);
    }
    result.add(bm * line);
  }
  return result / R(n + 3);
}

template <class R>
Sum<R> triple_axis_sum(const SphericalRegion& region, const Vec3& w_in, const Vec3& a_in, const Vec3& b_in, int n) {
  const real::V3<R> w = real::unit<R>(w_in), a(a_in), b(b_in);
  const auto arcs = arcs_about(region, w);
  const Sum<R> sigma = solid_angle_tracked<R>(region);
  const R aw = dot(a, w), bw = dot(b, w);
  const real::V3<R> a_perp = a - aw * w, b_perp = b - bw * w;
  Sum<R> result;
  auto add = [&](R factor, const Sum<R>& s) {
    if (factor != 0) result += factor * s;
  };
  if (aw != 0 && bw != 0) add(aw * bw, axial_moment_sum(arcs, sigma, n + 2));
  // ∫ (w·u)^{n+1} (x⊥·u) dσ = Σ (x⊥·m) G_{n+1} / (n + 3): double_axis_sum with v ⟂ w.
  if (aw != 0) add(aw, double_axis_sum(arcs, sigma, w, b_perp, n + 1));
  if (bw != 0) add(bw, double_axis_sum(arcs, sigma, w, a_perp, n + 1));
  add(R(1), perpendicular_pair_sum(arcs, sigma, a_perp, b_perp, n));
  return result;
}

// Both sums of cosine_moments(): [0] = ∫(n·u), [1] = ∫(w·u)(n·u) by Arvo's eq. 14 with n = 1:
// 3 ∫(w·u)(n·u) = (w·n) σ + Σ (n·m) ∫_arc (w·u) ds.
template <class R>
std::array<Sum<R>, 2> cosine_moment_sums(const SphericalRegion& region, const Vec3& n_in, const Vec3& w_in) {
  const real::V3<R> n(n_in), w(w_in);
  std::array<Sum<R>, 2> sums;
  Sum<R> boundary;
  for_each_edge<R>(region, [&](const ArcEdge<R>& arc) {
    const R nm = dot(n, arc.normal);
    sums[0].add(R(0.5) * arc.length * nm);
    // ∫_arc (w·u) ds = (w·a) sin θ + (w·s_a)(1 − cos θ): G_1 of cosine_power_arc.hpp.
    boundary.add(nm * (dot(w, arc.start) * arc.sin_length + dot(w, arc.start_tangent) * arc.one_minus_cos));
  });
  const R wn = dot(w, n);
  const Sum<R> sigma = solid_angle_tracked<R>(region);
  sums[1] += wn * sigma;
  sums[1] += boundary;
  sums[1] = sums[1] / R(3);
  return sums;
}

// Both sums of polynomial_cosine_moments() (moments.hpp), for a unit a.
template <class R>
std::array<Sum<R>, 2> polynomial_cosine_sums(const SphericalRegion& region, const Vec3& a_in, const Vec3& n_in,
                                             const Vec3& z_in, const std::vector<double>& c) {
  const real::V3<R> a = real::unit<R>(a_in), n(n_in), z(z_in);
  const int K = int(c.size()) - 1;
  const std::size_t size = std::size_t(K) + 1;
  std::vector<Sum<R>> b_tau(size), b_cos(size), b_lin(size), b_both(size);  // the edge sums of each recurrence
  std::vector<R> F, D;
  for_each_edge<R>(region, [&](const ArcEdge<R>& edge) {
    const CosinePowerArc<R> arc(edge, a);
    const R am = arc.w_dot_normal(), nm = dot(n, edge.normal), zm = dot(z, edge.normal);
    arc.forward_normalized(K + 1, F, D);
    const R cc = arc.c();
    R p = 0, q = 0;
    if (cc > 0) p = dot(z, arc.peak_direction()), q = dot(z, arc.peak_tangent());
    R ck = 1;  // c^k
    for (int k = 0; k <= K; ++k) {
      const R G = ck * F[k];
      b_tau[k].add(am * G);
      b_cos[k].add(nm * G);
      b_lin[k].add(zm * G);
      // ∫_arc (a·u)^k (z·u) ds = c^k [p F_{k+1} − q D_{k+1}/(k + 1)]; where c = 0, (a·u) ≡ 0.
      R H;
      if (cc > 0)
        H = ck * (p * F[k + 1] - q * D[k + 1] / R(k + 1));
      else
        H = k > 0 ? R(0) : dot(z, edge.start) * edge.sin_length + dot(z, edge.start_tangent) * edge.one_minus_cos;
      b_both[k].add(nm * H);
      ck *= cc;
    }
  });
  const R an = dot(a, n), az = dot(a, z), nz = dot(n, z);
  auto combine = [](std::initializer_list<std::pair<R, Sum<R>>> terms, R divisor) {
    Sum<R> s;
    for (const auto& [factor, sum] : terms) s += factor * sum;
    return s / divisor;
  };
  const Sum<R> none{};
  std::vector<Sum<R>> tau(size), lin(size);  // τ^k about a; ∫ (a·u)^k (z·u)
  std::array<Sum<R>, 2> total;
  for (int k = 0; k <= K; ++k) {
    tau[k] = k == 0 ? solid_angle_tracked<R>(region)
                    : combine({{R(k - 1), k >= 2 ? tau[k - 2] : none}, {R(1), b_tau[k - 1]}}, R(k + 1));
    lin[k] = combine({{R(k) * az, k >= 1 ? tau[k - 1] : none}, {R(1), b_lin[k]}}, R(k + 2));
    const Sum<R> cosine = combine({{R(k) * an, k >= 1 ? tau[k - 1] : none}, {R(1), b_cos[k]}}, R(k + 2));
    const Sum<R> both = combine({{R(k) * an, k >= 1 ? lin[k - 1] : none}, {nz, tau[k]}, {R(1), b_both[k]}}, R(k + 3));
    total[0] += R(c[k]) * cosine;
    total[1] += R(c[k]) * both;
  }
  return total;
}

}  // namespace

PolynomialCosineMoments polynomial_cosine_moments(const SphericalRegion& region, const Vec3& a, const Vec3& n,
                                                  const Vec3& z, const std::vector<double>& c) {
  if (c.empty()) return {0, 0};
  // The target is 1e-9 relative, not the 1e-13 of the other kernels. What these sums integrate
  // is a fit: glass's transmittance, within 2.4e-3 absolute for clear glass (the fit's
  // max_error, which the run's notices state and which bounds the glazed sky component's error),
  // or a CIE general sky's fit, off by more; 1e-9 of the moment is a millionth of that. The fit's
  // monomial coefficients reach 1e5 and cancel (κ ~ 1e6 on benign regions, more on regions cut
  // into many loops, whose shared edges cancel too), so double never meets even this target and
  // long double does. At 1e-11 (before 2026-12-06) most calls went on to __float128 (50× slower
  // than long double): on the office sample its arithmetic was 19 % of a glazed `df`'s time, 0.14 s
  // of CPU against 0.09 s now (the open window: 0.07 s), with results moved by at most 2.8e-11.
  const auto m = escalate_tracked(
      int(c.size()) + 1, [&](auto r) { return polynomial_cosine_sums<decltype(r)>(region, a, n, z, c); }, 1e-9);
  return {m.value[0], m.value[1]};
}

CosineMoments cosine_moments(const SphericalRegion& region, const Vec3& n, const Vec3& w) {
  const auto m = escalate_tracked(1, [&](auto r) { return cosine_moment_sums<decltype(r)>(region, n, w); });
  return {m.value[0], m.value[1]};
}

Escalated<double> lambert_with_accuracy(const SphericalRegion& region, const Vec3& n) {
  return escalate_tracked(1, [&](auto r) { return lambert_sum<decltype(r)>(region, n); });
}

Escalated<double> lambert_with_accuracy(const SphericalRegion& region, const Vec3& n, double tolerance,
                                        double absolute_tolerance) {
  return escalate_tracked(
      1, [&](auto r) { return lambert_sum<decltype(r)>(region, n); }, tolerance, absolute_tolerance);
}

double lambert(const SphericalRegion& region, const Vec3& n) { return lambert_with_accuracy(region, n).value; }

// The kernels take a unit axis; (w·u)^n = |w|^n (ŵ·u)^n. |w|^n from |w|² in long double: pow(norm(w),
// n) would raise norm()'s rounding to the n-th power (1.3e-13 at n = 1000 for a normalised w).
static double length_power(const Vec3& w, int n) {
  const long double s = (long double)w.x * w.x + (long double)w.y * w.y + (long double)w.z * w.z;
  return double(std::exp(0.5L * n * std::log1p(s - 1)));
}

// A result of the unit-axis kernels times |w|^n.
static Escalated<double> scaled(Escalated<double> m, double scale) {
  m.value *= scale;
  return m;
}

Escalated<std::vector<double>> axial_moments_with_accuracy(const SphericalRegion& region, const Vec3& w, int n) {
  auto tau = escalate_tracked(n, [&](auto r) {
    using R = decltype(r);
    const auto arcs = arcs_about(region, real::unit<R>(w));
    return axial_moment_sums<R>(arcs, solid_angle_tracked<R>(region), n);
  });
  for (int k = 1; k <= n; ++k) tau.value[k] *= length_power(w, k);
  return tau;
}

std::vector<double> axial_moments(const SphericalRegion& region, const Vec3& w, int n) {
  return axial_moments_with_accuracy(region, w, n).value;
}

Escalated<double> axial_moment_with_accuracy(const SphericalRegion& region, const Vec3& w, int n) {
  return scaled(escalate_tracked(n,
                                 [&](auto r) {
                                   using R = decltype(r);
                                   return axial_moment_sum<R>(arcs_about(region, real::unit<R>(w)),
                                                              solid_angle_tracked<R>(region), n);
                                 }),
                length_power(w, n));
}

double axial_moment(const SphericalRegion& region, const Vec3& w, int n) {
  return axial_moment_with_accuracy(region, w, n).value;
}

Escalated<double> double_axis_moment_with_accuracy(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n) {
  return scaled(escalate_tracked(n + 1,
                                 [&](auto r) {
                                   using R = decltype(r);
                                   const real::V3<R> w_unit = real::unit<R>(w);
                                   return double_axis_sum<R>(arcs_about(region, w_unit), solid_angle_tracked<R>(region),
                                                             w_unit, real::V3<R>(v), n);
                                 }),
                length_power(w, n));
}

double double_axis_moment(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n) {
  return double_axis_moment_with_accuracy(region, w, v, n).value;
}

Escalated<double> triple_axis_moment_with_accuracy(const SphericalRegion& region, const Vec3& w, const Vec3& a,
                                                   const Vec3& b, int n) {
  return scaled(escalate_tracked(n + 2, [&](auto r) { return triple_axis_sum<decltype(r)>(region, w, a, b, n); }),
                length_power(w, n));
}

double triple_axis_moment(const SphericalRegion& region, const Vec3& w, const Vec3& a, const Vec3& b, int n) {
  return triple_axis_moment_with_accuracy(region, w, a, b, n).value;
}

TruncatedMoment axial_moment_truncated(const SphericalRegion& region, const Vec3& w, int n, double tolerance) {
  const auto arcs = arcs_about(region, real::unit<double>(w));
  const Sum<double> sigma = solid_angle_tracked<double>(region);
  Sum<double> sum;
  if (n % 2 == 0) sum.add(sigma.value, sigma.magnitude);
  double dropped = 0;
  int terms = 0;
  for (const auto& arc : arcs) {
    if (n == 0) break;
    double arc_dropped = 0;
    const double wm = arc.w_dot_normal();
    sum.add(wm * arc.truncated_sum((n - 1) % 2, n - 1, tolerance, &arc_dropped, &terms));
    dropped += std::abs(wm) * arc_dropped;
  }
  const double scale = length_power(w, n) / (n + 1);
  return {scale * sum.value, scale * (dropped + 10 * 0x1p-53 * sum.magnitude), terms};
}

TruncatedMoment double_axis_moment_truncated(const SphericalRegion& region, const Vec3& w_in, const Vec3& v, int n,
                                             double tolerance) {
  const real::V3<double> w = real::unit<double>(w_in);
  const double vw = dot(real::V3<double>(v), w);
  const real::V3<double> v_perp = real::V3<double>(v) - vw * w;
  TruncatedMoment axial{0, 0, 0};
  if (vw != 0) axial = axial_moment_truncated(region, w_in / norm(w_in), n + 1, tolerance);
  const auto arcs = arcs_about(region, w);
  // The top-order edge terms of eq. 14, Σ (v⊥·m) G_n / (n + 2): dropped when their bound is.
  double top_bound = 0;
  for (const auto& arc : arcs) top_bound += std::abs(dot(v_perp, arc.arc().normal)) * arc.G_bound(n) / (n + 2);
  TruncatedMoment result{vw * axial.value, std::abs(vw) * axial.error_bound, axial.terms};
  if (top_bound <= tolerance * std::abs(result.value)) {
    result.error_bound += top_bound;
  } else {
    Sum<double> top;
    for (const auto& arc : arcs) top.add(dot(v_perp, arc.arc().normal) * arc.G(n) / (n + 2));
    result.value += top.value;
    result.error_bound += 10 * 0x1p-53 * top.magnitude;
    result.terms += int(arcs.size()) * (n + 1);
  }
  const double scale = length_power(w_in, n);
  return {scale * result.value, scale * result.error_bound, result.terms};
}

}  // namespace daylit
