#include "illumination/moments.hpp"

#include <algorithm>
#include <array>

#include "illumination/arc_power_integral.hpp"
#include "illumination/solid_angle.hpp"

namespace daylit {

namespace {

thread_local MomentAccuracy last_accuracy;

// A sum that remembers the magnitude of what went into it, to detect cancellation.
template <class R>
struct Sum {
  R value = 0, magnitude = 0;
  void add(R term, R term_magnitude) {
    value += term;
    magnitude += term_magnitude;
  }
  void add(R term) { add(term, real::abs(term)); }
};

// Calls f(edge) for every non-degenerate edge of every loop, in precision R.
template <class R, class F>
void for_each_edge(const SphericalRegion& region, F&& f) {
  for (const auto& loop : region.loops) {
    const std::size_t m = loop.size();
    for (std::size_t i = 0; i < m; ++i)
      if (const auto arc = arc_edge(real::V3<R>(loop[i]), real::V3<R>(loop[(i + 1) % m]))) f(*arc);
  }
}

// Van Oosterom–Strackee (see solid_angle.hpp), fan from the first vertex of each loop.
template <class R>
Sum<R> solid_angle_sum(const SphericalRegion& region) {
  Sum<R> sum;
  for (const auto& loop : region.loops) for_each_solid_angle_term<R>(loop, [&](R term) { sum.add(term); });
  return sum;
}

template <class R>
Sum<R> lambert_sum(const SphericalRegion& region, const Vec3& n_in) {
  const real::V3<R> n(n_in);
  Sum<R> sum;
  for_each_edge<R>(region, [&](const ArcEdge<R>& arc) { sum.add(R(0.5) * arc.length * dot(arc.normal, n)); });
  return sum;
}

// τ^k and the magnitudes of their terms, k = 0..n.
template <class R>
std::vector<Sum<R>> axial_moment_sums(const SphericalRegion& region, const Vec3& w_in, int n) {
  const real::V3<R> w(w_in);
  std::vector<Sum<R>> tau(static_cast<std::size_t>(n) + 1);
  tau[0] = solid_angle_sum<R>(region);
  if (n == 0) return tau;
  std::vector<Sum<R>> boundary(static_cast<std::size_t>(n));
  std::vector<R> G;
  for_each_edge<R>(region, [&](const ArcEdge<R>& arc) {
    arc_power_integrals(arc, w, n - 1, G);
    const R wm = dot(w, arc.normal);
    for (int k = 0; k < n; ++k) boundary[k].add(wm * G[k]);
  });
  const R w2 = dot(w, w);
  for (int k = 1; k <= n; ++k) {
    const Sum<R> lower = k >= 2 ? tau[k - 2] : Sum<R>{};
    const R scale = R(k - 1) * w2;
    tau[k].value = (scale * lower.value + boundary[k - 1].value) / R(k + 1);
    tau[k].magnitude = (scale * lower.magnitude + boundary[k - 1].magnitude) / R(k + 1);
  }
  return tau;
}

template <class R>
Sum<R> double_axis_sum(const SphericalRegion& region, const Vec3& w_in, const Vec3& v_in, int n) {
  const real::V3<R> w(w_in), v(v_in);
  Sum<R> boundary;
  std::vector<R> G;
  for_each_edge<R>(region, [&](const ArcEdge<R>& arc) {
    arc_power_integrals(arc, w, n, G);
    boundary.add(dot(v, arc.normal) * G[n]);
  });
  Sum<R> result;
  if (n > 0) {
    const Sum<R> lower = axial_moment_sums<R>(region, w_in, n - 1)[n - 1];
    const R scale = R(n) * dot(w, v);
    result.add(scale * lower.value, real::abs(scale) * lower.magnitude);
  }
  result.add(boundary.value, boundary.magnitude);
  result.value /= R(n + 2);
  result.magnitude /= R(n + 2);
  return result;
}

// Cancellation limits: a result computed with unit roundoff u from terms of total magnitude M
// carries an error of about 10·u·M; these bound it near 1e-13 of the result.
template <class R>
bool well_conditioned(const Sum<R>& s, double kappa_limit) {
  return s.magnitude <= R(kappa_limit) * real::abs(s.value);
}
template <class Sums>
bool well_conditioned(const Sums& sums, double kappa_limit) {
  return std::all_of(sums.begin(), sums.end(), [&](const auto& s) { return well_conditioned(s, kappa_limit); });
}

double to_double(const Sum<double>& s) { return s.value; }
template <class R>
double to_double(const Sum<R>& s) {
  return double(s.value);
}
template <class R>
std::vector<double> to_double(const std::vector<Sum<R>>& sums) {
  std::vector<double> out;
  for (const auto& s : sums) out.push_back(double(s.value));
  return out;
}
template <class R, std::size_t N>
std::array<double, N> to_double(const std::array<Sum<R>, N>& sums) {
  std::array<double, N> out;
  for (std::size_t i = 0; i < N; ++i) out[i] = double(sums[i].value);
  return out;
}

// Largest κ = magnitude/|value| over a result (a Sum or a container of them).
template <class R>
double condition(const Sum<R>& s) {
  return s.magnitude == 0 ? 1.0 : double(s.magnitude / real::abs(s.value));
}
template <class Sums>
double condition(const Sums& sums) {
  double k = 1;
  for (const auto& s : sums) k = std::max(k, condition(s));
  return k;
}

// Evaluates compute(R{}) in double, then long double, then __float128, until the result (a Sum or
// a vector of them) is well conditioned for that precision; records the precision used and the
// error estimate 10·u·κ (u the unit roundoff) for last_moment_accuracy().
template <class F>
auto with_escalation(F&& compute) {
  const auto d = compute(double{});
  if (well_conditioned(d, 64)) {
    last_accuracy = MomentAccuracy{0, 10 * 0x1p-53 * condition(d)};
    return to_double(d);
  }
  const auto l = compute((long double)0);
#ifdef DAYLIT_HAS_FLOAT128
  if (well_conditioned(l, 64.0 * 2048)) {
    last_accuracy = MomentAccuracy{1, 10 * 0x1p-64 * condition(l)};
    return to_double(l);
  }
  const auto q = compute(real::quad(0));
  last_accuracy = MomentAccuracy{2, 10 * 0x1p-113 * condition(q)};
  return to_double(q);
#else
  last_accuracy = MomentAccuracy{1, 10 * 0x1p-64 * condition(l)};
  return to_double(l);
#endif
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
    // ∫_arc (w·u) ds = (w·a) sin θ + (w·s_a)(1 − cos θ): arc_power_integrals() at order 1.
    boundary.add(nm * (dot(w, arc.start) * arc.sin_length + dot(w, arc.start_tangent) * arc.one_minus_cos));
  });
  const R wn = dot(w, n);
  const Sum<R> sigma = solid_angle_sum<R>(region);
  sums[1].add(wn * sigma.value, real::abs(wn) * sigma.magnitude);
  sums[1].add(boundary.value, boundary.magnitude);
  sums[1].value /= R(3);
  sums[1].magnitude /= R(3);
  return sums;
}

}  // namespace

CosineMoments cosine_moments(const SphericalRegion& region, const Vec3& n, const Vec3& w) {
  const auto m = with_escalation([&](auto r) { return cosine_moment_sums<decltype(r)>(region, n, w); });
  return {m[0], m[1]};
}

double lambert(const SphericalRegion& region, const Vec3& n) {
  return with_escalation([&](auto r) { return lambert_sum<decltype(r)>(region, n); });
}

std::vector<double> axial_moments(const SphericalRegion& region, const Vec3& w, int n) {
  return with_escalation([&](auto r) { return axial_moment_sums<decltype(r)>(region, w, n); });
}

double double_axis_moment(const SphericalRegion& region, const Vec3& w, const Vec3& v, int n) {
  return with_escalation([&](auto r) { return double_axis_sum<decltype(r)>(region, w, v, n); });
}

MomentAccuracy last_moment_accuracy() noexcept { return last_accuracy; }

}  // namespace daylit
