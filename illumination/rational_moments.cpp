#include "illumination/rational_moments.hpp"

#include <cmath>
#include <array>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <type_traits>

#include "geometry/error.hpp"
#include "illumination/cosine_power_arc.hpp"
#include "illumination/gauss_legendre.hpp"
#include "illumination/log_cosine_arc_integral.hpp"
#include "illumination/orthonormal_basis.hpp"
#include "illumination/precision_escalation.hpp"
#include "illumination/rational_edge.hpp"
#include "illumination/solid_angle.hpp"

namespace daylit {

using rational::exact;
using rational::GTable;
using rational::Tracked;
using rational::WFrameArc;

namespace {

// −Σ_edges (w·m) [Λ(c, s1) − Λ(c, s0)] = −Σ_edges sign(w·m) [bracket(s1) − bracket(s0)]/4
// (eqs. 28, 33, 36; lambda_bracket() in clausen.hpp). Edges in w's plane of symmetry (w·m = 0)
// contribute nothing. Short arcs away from the horizon take the difference by quadrature of its
// one-signed integrand instead (log_cosine_arc_integral.hpp), which does not cancel; __float128,
// the ladder's last rung, keeps the brackets.
template <class R>
Tracked<R> base_moment_edge(const WFrameArc<R>& e) {
  if (e.wm == 0) return {};
  if constexpr (std::is_same_v<R, double> || std::is_same_v<R, long double>) {
    if (const auto integral = rational::log_cosine_arc_integral(e))
      return {-e.wm * integral->value, e.kappa() * integral->magnitude};
  }
  const Tracked<R> b1 = lambda_bracket_tracked<R>(e.c, e.kappa(), e.sin1, e.cos1);
  const Tracked<R> b0 = lambda_bracket_tracked<R>(e.c, e.kappa(), e.sin0, e.cos0);
  const R sign = e.wm > 0 ? R(-0.25) : R(0.25);
  return {sign * (b1.value - b0.value), (b1.magnitude + b0.magnitude) / 4};
}

// The moments J(a, b, e) = ∫_A u1^a u2^b u3^e dσ in the frame (e1, e2, w) (rational_moments.hpp),
// memoised, with the edge data and G tables built once.
template <class R>
class FrameMoments {
 public:
  FrameMoments(const SphericalRegion& region, const real::V3<R>& e1, const real::V3<R>& e2, const real::V3<R>& w,
               int max_ab, int e_min, int e_max)
      : region_(region) {
    for_each_edge<R>(region, [&](const ArcEdge<R>& arc) {
      Edge edge{WFrameArc<R>(arc, w), GTable<R>(WFrameArc<R>(arc, w), max_ab + 1, e_min - 1, 2 * max_ab + e_max + 2), 0,
                0, 0, 0, 0, 0};
      const auto& f = edge.frame;
      edge.m1 = dot(e1, arc.normal);
      edge.m2 = dot(e2, arc.normal);
      edge.A1 = dot(e1, f.p);
      edge.B1 = dot(e1, f.q);
      edge.A2 = dot(e2, f.p);
      edge.B2 = dot(e2, f.q);
      edges_.push_back(std::move(edge));
    });
  }

  Tracked<R> J(int a, int b, int e) {
    const auto key = std::make_tuple(a, b, e);
    if (const auto it = memo_.find(key); it != memo_.end()) return it->second;
    const Tracked<R> value = compute(a, b, e);
    memo_.emplace(key, value);
    return value;
  }

 private:
  struct Edge {
    WFrameArc<R> frame;
    GTable<R> G;
    R m1, m2, A1, B1, A2, B2;
  };

  // Σ_edges (x·m) ∫_arc u1^a u2^b u3^e ds, x = e1, e2 or w (axis 1, 2, 3).
  Tracked<R> boundary(int axis, int a, int b, int e) const {
    Tracked<R> sum;
    std::vector<std::pair<R, R>> factors;
    std::vector<R> P, Pm;
    for (const Edge& edge : edges_) {
      const R xm = axis == 1 ? edge.m1 : (axis == 2 ? edge.m2 : edge.frame.wm);
      if (xm == 0) continue;
      factors.assign(std::size_t(a), {edge.A1, edge.B1});
      factors.insert(factors.end(), std::size_t(b), {edge.A2, edge.B2});
      rational::trig_product(factors, P, Pm);
      // u3^e = c^e cos^e s.
      const R ce = e >= 0 ? real::powi(edge.frame.c, e) : real::powi(R(1) / edge.frame.c, -e);
      sum += (xm * ce) * rational::expand_integral(edge.G, P, Pm, e);
    }
    return sum;
  }

  Tracked<R> compute(int a, int b, int e) {
    const int K = a + b + e;
    if (a == 0 && b == 0) {
      if (e == 0) return solid_angle_tracked<R>(region_);
      if (e == -1) {
        Tracked<R> sum;
        for (const Edge& edge : edges_) sum += base_moment_edge(edge.frame);
        return sum;
      }
      // Stokes with g = u3^{e−1}: (e − 1) J(0,0,e−2) − (e + 1) J(0,0,e) = −Σ (w·m) ∫ u3^{e−1} ds.
      if (e >= 1) return (R(e - 1) * J(0, 0, e - 2) + boundary(3, 0, 0, e - 1)) / R(e + 1);
      // With g = u3^{e+1}: (e + 1) J(0,0,e) − (e + 3) J(0,0,e+2) = −Σ (w·m) ∫ u3^{e+1} ds.
      return (R(e + 3) * J(0, 0, e + 2) - boundary(3, 0, 0, e + 1)) / R(e + 1);
    }
    if (K != -1) {
      // g = u1^{a−1} u2^b u3^e (degree K − 1):
      //     (a − 1) J(a−2,b,e) − (K + 1) J(a,b,e) = −Σ (e1·m) ∫ u1^{a−1} u2^b u3^e ds,
      // and likewise in b with e2.
      if (a >= 1) {
        Tracked<R> r = boundary(1, a - 1, b, e);
        if (a >= 2) r += R(a - 1) * J(a - 2, b, e);
        return r / R(K + 1);
      }
      Tracked<R> r = boundary(2, a, b - 1, e);
      if (b >= 2) r += R(b - 1) * J(a, b - 2, e);
      return r / R(K + 1);
    }
    // Total degree −1 with a + b ≥ 1 (so e ≤ −2): the forms above are singular; g = u1^a u2^b
    // u3^{e+1} (degree 0) gives (e + 1) J(a,b,e) − 2 J(a,b,e+2) = −Σ (w·m) ∫ u1^a u2^b u3^{e+1} ds.
    return (R(2) * J(a, b, e + 2) - boundary(3, a, b, e + 1)) / R(e + 1);
  }

  const SphericalRegion& region_;
  std::vector<Edge> edges_;
  std::map<std::tuple<int, int, int>, Tracked<R>> memo_;
};

// The region must lie strictly on the positive side of w·u = 0 (then so do its arcs, which are
// shorter than π).
void check_side(const SphericalRegion& region, const Vec3& w) {
  if (!(norm(w) > 0) || !is_finite(w)) throw Error("the denominator axis must be a finite non-zero vector");
  for (const auto& loop : region.loops)
    for (const Vec3& v : loop)
      if (!(dot(w, v) > 0))
        throw Error("the region must lie strictly on the positive side of the denominator's plane w·u = 0 "
                    "(there the integral diverges)");
}

}  // namespace

AxisFrame frame_about(const Vec3& w_in) {
  const Vec3 w = normalized(w_in);
  const PerpendicularBasis<double> f = perpendicular_basis(real::V3<double>(w));
  return {{f.e1.x, f.e1.y, f.e1.z}, {f.e2.x, f.e2.y, f.e2.z}, w};
}

RationalMoment rational_base_moment(const SphericalRegion& region, const Vec3& w) {
  check_side(region, w);
  const double scale = 1 / norm(w);
  RationalMoment m = escalate_tracked(1, [&](auto r) {
    using R = decltype(r);
    const real::V3<R> wr = real::unit<R>(w);
    Tracked<R> sum;
    for_each_edge<R>(region, [&](const ArcEdge<R>& arc) { sum += base_moment_edge(WFrameArc<R>(arc, wr)); });
    return sum;
  });
  m.value *= scale;
  return m;
}

RationalMoment frame_polynomial_moment(const SphericalRegion& region, const Vec3& e1, const Vec3& e2, const Vec3& w,
                                       const std::vector<FrameMonomial>& terms, std::vector<double>* term_values) {
  check_side(region, w);
  int max_ab = 0, e_min = 0, e_max = 0;
  for (const auto& t : terms) {
    if (t.a < 0 || t.b < 0) throw Error("frame monomials need a, b ≥ 0");
    max_ab = std::max(max_ab, t.a + t.b);
    e_min = std::min(e_min, t.e);
    e_max = std::max(e_max, t.e);
  }
  std::vector<double> values;
  RationalMoment m = escalate_tracked(max_ab + std::max(e_max, -e_min), [&](auto r) {
    using R = decltype(r);
    FrameMoments<R> J(region, real::unit<R>(e1), real::unit<R>(e2), real::unit<R>(w), max_ab, e_min, e_max);
    Tracked<R> sum;
    values.clear();
    for (const auto& t : terms) {
      const Tracked<R> j = J.J(t.a, t.b, t.e);
      values.push_back(double(j.value));
      if (t.coef != 0) sum += R(t.coef) * j;
    }
    return sum;
  });
  // The coefficients and the frame arrive rounded to double, whatever precision the sum ran in:
  // a few units of 2^-53 of each term, relative to the result where the terms cancel.
  double terms_magnitude = 0;
  for (std::size_t i = 0; i < terms.size(); ++i) terms_magnitude += std::abs(terms[i].coef * values[i]);
  if (terms_magnitude > 0) m.relative_error += 4 * 0x1p-53 * terms_magnitude / std::abs(m.value);
  if (term_values) *term_values = std::move(values);
  return m;
}

RationalMoment rational_moment(const SphericalRegion& region, const std::vector<Factor>& numerator, const Vec3& w,
                               int q) {
  if (q < 0) throw Error("the denominator's power must be ≥ 0");
  check_side(region, w);
  int degree = 0;
  for (const Factor& f : numerator) {
    if (f.power < 0) throw Error("factor powers must be ≥ 0");
    if (!(norm(f.axis) > 0) || !is_finite(f.axis)) throw Error("a factor axis must be a finite non-zero vector");
    degree += f.power;
  }
  if (degree > kMaxFrameMomentDegree)
    throw Error("rational moments with a numerator of total degree " + std::to_string(degree) + " > " +
                std::to_string(kMaxFrameMomentDegree) + " are not supported (except (n), (n,1), (n,1,1) with power 1)");
  // The frame and the expansion of Π (a_k·u)^{p_k} in (u1, u2, u3) are formed in the precision of
  // the sum (frame_about's construction redone in R): rounded to double first, the coefficients
  // would carry 2^-53 errors into results whose terms cancel (1e-14 measured on ∫ (a·u)(b·u)/(w·u)).
  RationalMoment m = escalate_tracked(degree + q, [&](auto r) {
    using R = decltype(r);
    const real::V3<R> wr = real::unit<R>(w);
    const PerpendicularBasis<R> basis = perpendicular_basis(wr);  // frame_about() in R
    const real::V3<R>& e1 = basis.e1;
    const real::V3<R>& e2 = basis.e2;
    // c[a][b]: coefficient of u1^a u2^b u3^{d−a−b}, with the magnitudes of its terms.
    int d = 0;
    std::vector<std::vector<Tracked<R>>> coef(1, std::vector<Tracked<R>>(1, exact(R(1))));
    for (const Factor& fac : numerator)
      for (int p = 0; p < fac.power; ++p) {
        const real::V3<R> ax(fac.axis);
        const R x = dot(ax, e1), y = dot(ax, e2), z = dot(ax, wr);
        std::vector<std::vector<Tracked<R>>> next(std::size_t(d) + 2, std::vector<Tracked<R>>(std::size_t(d) + 2));
        for (int a = 0; a <= d; ++a)
          for (int b = 0; a + b <= d; ++b) {
            next[a + 1][b] += x * coef[a][b];
            next[a][b + 1] += y * coef[a][b];
            next[a][b] += z * coef[a][b];
          }
        coef.swap(next);
        ++d;
      }
    FrameMoments<R> J(region, e1, e2, wr, d, std::min(-q, 0), d);
    Tracked<R> sum;
    for (int a = 0; a <= d; ++a)
      for (int b = 0; a + b <= d; ++b) {
        const Tracked<R>& k = coef[a][b];
        if (k.value == 0 && k.magnitude == 0) continue;
        const Tracked<R> j = J.J(a, b, d - a - b - q);
        // The product of two sums: value k·j, magnitude |k|·|j|'s terms plus k's terms times |j|.
        sum += Tracked<R>{k.value * j.value, real::abs(k.value) * j.magnitude + k.magnitude * real::abs(j.value)};
      }
    return sum;
  });
  m.value /= std::pow(norm(w), q);
  return m;
}

}  // namespace daylit

// ---------------------------------------------------------------------------------------------
// τ^{n;1}, τ^{n,1;1}, τ^{n,1,1;1} (rational_moments.hpp).

namespace daylit {

namespace {

// Gauss–Legendre nodes and weights (gauss_legendre.hpp) mapped to [0, 1], cached per thread.
const std::pair<std::vector<long double>, std::vector<long double>>& gauss_legendre_unit(int n) {
  thread_local std::map<int, std::pair<std::vector<long double>, std::vector<long double>>> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  quadrature::GaussLegendreRule rule = quadrature::gauss_legendre(n);
  for (std::size_t i = 0; i < rule.x.size(); ++i) {
    rule.x[i] = (1 - rule.x[i]) / 2;
    rule.w[i] /= 2;
  }
  return cache.emplace(n, std::make_pair(std::move(rule.x), std::move(rule.w))).first->second;
}

// Which of the three moments.
enum class Pattern { n, n1, n11 };

// Edge integrals of one arc for the recurrences: H[k] = ∫ (v·u)^k/(w·u) ds (k ≤ n),
// H2 = ∫ (v·u)^n (a·u)/(w·u) ds, P[k] = ∫ (v·u)^k ds (k ≤ n).
template <class R>
struct EdgeIntegrals {
  std::vector<Tracked<R>> H, P;
  Tracked<R> H2;
};

template <class R>
EdgeIntegrals<R> exact_edge_integrals(const WFrameArc<R>& f, const real::V3<R>& v, const real::V3<R>& a, int n,
                                      bool want_h2) {
  EdgeIntegrals<R> out;
  const GTable<R> G(f, n + 1, -1, n + 1, n);
  const R Av = dot(v, f.p), Bv = dot(v, f.q);
  // (Av cos s + Bv sin s)^k = Σ_r P_r sin^r cos^{k−r}, built one factor at a time (§3.4's
  // caching: every order reuses the previous one's coefficients and the one G table).
  std::vector<R> P{R(1)}, Pm{R(1)};
  P.reserve(std::size_t(n) + 2);
  Pm.reserve(std::size_t(n) + 2);
  const R abs_A = real::abs(Av), abs_B = real::abs(Bv);
  for (int k = 0; k <= n; ++k) {
    if (k > 0) {
      // Multiply by (Av cos + Bv sin) in place, from the top coefficient down.
      P.push_back(Bv * P.back());
      Pm.push_back(abs_B * Pm.back());
      for (std::size_t r = P.size() - 2; r > 0; --r) {
        P[r] = Av * P[r] + Bv * P[r - 1];
        Pm[r] = abs_A * Pm[r] + abs_B * Pm[r - 1];
      }
      P[0] *= Av;
      Pm[0] *= abs_A;
    }
    out.H.push_back(rational::expand_integral(G, P, Pm, -1) / f.c);
    out.P.push_back(rational::expand_integral(G, P, Pm, 0));
  }
  if (want_h2) {
    std::vector<std::pair<R, R>> one{{dot(a, f.p), dot(a, f.q)}};
    std::vector<R> Q, Qm;
    rational::trig_product(one, Q, Qm);
    std::vector<R> PQ(P.size() + 1, R(0)), PQm(P.size() + 1, R(0));
    for (std::size_t r = 0; r < P.size(); ++r) {
      PQ[r] += Q[0] * P[r];
      PQ[r + 1] += Q[1] * P[r];
      PQm[r] += Qm[0] * Pm[r];
      PQm[r + 1] += Qm[1] * Pm[r];
    }
    out.H2 = rational::expand_integral(G, PQ, PQm, -1) / f.c;
  }
  return out;
}

// The same by `points`-node Gauss–Legendre quadrature along the arc for H and H2 (the paper's
// semi-analytic T3), with P exact by Arvo's upward recurrence (cosine_power_arc.hpp).
template <class R>
EdgeIntegrals<R> quadrature_edge_integrals(const WFrameArc<R>& f, const real::V3<R>& v, const real::V3<R>& a,
                                           const real::V3<R>& w, int n, bool want_h2, int points) {
  EdgeIntegrals<R> out;
  out.H.assign(std::size_t(n) + 1, Tracked<R>{});
  const auto& [x, wt] = gauss_legendre_unit(points);
  const auto& e = f.arc;
  for (int i = 0; i < points; ++i) {
    const R t = R(x[i]) * e.length, weight = R(wt[i]) * e.length;
    const real::V3<R> u = real::cos(t) * e.start + real::sin(t) * e.start_tangent;
    const R vu = dot(v, u), wu = dot(w, u);
    R term = weight / wu;
    for (int k = 0; k <= n; ++k) {
      out.H[k] += exact(term);
      if (k == n && want_h2) out.H2 += exact(term * dot(a, u));
      term *= vu;
    }
  }
  const R vn = real::norm(v);
  out.P.assign(std::size_t(n) + 1, Tracked<R>{});
  out.P[0] = exact(e.length);
  if (n > 0 && vn > 0) {
    const CosinePowerArc<R> arc(e, v / vn);
    const std::vector<R> Gk = arc.forward(n);
    R scale = 1;
    for (int k = 1; k <= n; ++k) {
      scale *= vn;
      // Upward: exact in the absolute sense (errors ~u θ c^k), not always relative.
      out.P[k] = {scale * Gk[k], scale * std::max(real::abs(Gk[k]), e.length * real::powi(arc.c(), k))};
    }
  }
  return out;
}

template <class R>
Tracked<R> q1_moment(const SphericalRegion& region, const Vec3& v_in, int n, const Vec3& a_in, const Vec3& b_in,
                     const Vec3& w_in, Pattern pattern, const RationalMomentOptions& options, int points) {
  const real::V3<R> w = real::unit<R>(w_in), v(v_in), a(a_in), b(b_in);
  const R wv = dot(w, v), wa = dot(w, a), wb = dot(w, b);
  const real::V3<R> v_perp = v - wv * w, a_perp = a - wa * w, b_perp = b - wb * w;
  const bool want_h2 = pattern == Pattern::n11;
  // Σ_edges (x·m) × edge integral, for the boundary terms of eqs. 11–14.
  std::vector<Tracked<R>> SH(std::size_t(n) + 1), SP(std::size_t(n) + 1), SHa(std::size_t(n) + 1);
  Tracked<R> SPa, SHb, base;
  for_each_edge<R>(region, [&](const ArcEdge<R>& arc) {
    const WFrameArc<R> f(arc, w);
    base += base_moment_edge(f);
    const EdgeIntegrals<R> I = options.method == RationalMethod::exact
                                   ? exact_edge_integrals(f, v, a, n, want_h2)
                                   : quadrature_edge_integrals(f, v, a, w, n, want_h2, points);
    const R vpm = dot(v_perp, arc.normal), vm = dot(v, arc.normal), apm = dot(a_perp, arc.normal);
    for (int k = 0; k <= n; ++k) {
      SH[k] += vpm * I.H[k];
      SP[k] += vm * I.P[k];
      SHa[k] += apm * I.H[k];
    }
    SPa += dot(a, arc.normal) * I.P[n];
    if (want_h2) SHb += dot(b_perp, arc.normal) * I.H2;
  });
  const Tracked<R> sigma = solid_angle_tracked<R>(region);
  // Polynomial axial moments about v (Arvo's eq. 11): (k + 1) τ̄^k = (k − 1)|v|² τ̄^{k−2} + Σ (v·m) P_{k−1}.
  const R v2 = dot(v, v);
  std::vector<Tracked<R>> tau(std::size_t(n) + 1);
  tau[0] = sigma;
  for (int k = 1; k <= n; ++k) {
    Tracked<R> r = SP[k - 1];
    if (k >= 2) r += R(k - 1) * v2 * tau[k - 2];
    tau[k] = r / R(k + 1);
  }
  // Eq. 11 upward: k τ^{k;1} = k (w·v) τ̄^{k−1} + (k − 1) |v⊥|² τ^{k−2;1} + Σ (v⊥·m) H_{k−1}.
  const R d = dot(v_perp, v_perp);
  std::vector<Tracked<R>> rat(std::size_t(n) + 1);
  rat[0] = base;
  for (int k = 1; k <= n; ++k) {
    Tracked<R> r = SH[k - 1];
    if (k >= 2) r += R(k - 1) * d * rat[k - 2];
    rat[k] = wv * tau[k - 1] + r / R(k);
  }
  if (pattern == Pattern::n) return rat[n];
  // Eq. 12: (n + 1)[τ^{n,1;1} − (w·a) τ̄^n] = n (a⊥·v) τ^{n−1;1} + Σ (a⊥·m) H_n.
  auto n1 = [&](int k) {
    Tracked<R> r = SHa[k];
    if (k >= 1) r += R(k) * dot(a_perp, v) * rat[k - 1];
    return wa * tau[k] + r / R(k + 1);
  };
  if (pattern == Pattern::n1) return n1(n);
  // Eq. 13 with Arvo's eq. 14 for τ̄^{n,1}(v, a): (n + 2) τ̄^{n,1} = n (v·a) τ̄^{n−1} + Σ (a·m) P_n.
  Tracked<R> double_axis = SPa;
  if (n >= 1) double_axis += R(n) * dot(v, a) * tau[n - 1];
  double_axis = double_axis / R(n + 2);
  Tracked<R> r = SHb + dot(b_perp, a) * rat[n];
  if (n >= 1) r += R(n) * dot(b_perp, v) * n1(n - 1);
  return wb * double_axis + r / R(n + 2);
}

RationalMoment q1_dispatch(const SphericalRegion& region, const Vec3& v, int n, const Vec3& a, const Vec3& b,
                           const Vec3& w, Pattern pattern, const RationalMomentOptions& options) {
  check_side(region, w);
  if (n < 0) throw Error("the numerator's power must be ≥ 0");
  if (!is_finite(v) || !is_finite(a) || !is_finite(b)) throw Error("factor axes must be finite");
  if (options.method == RationalMethod::semi_analytic && options.quadrature_points < 2)
    throw Error("semi-analytic rational moments need at least 2 quadrature points");
  const double scale = 1 / norm(w);
  auto run = [&](int points) {
    return escalate_tracked(n + 2, [&](auto r) {
      return q1_moment<decltype(r)>(region, v, n, a, b, w, pattern, options, points);
    });
  };
  RationalMoment m = run(options.quadrature_points);
  if (options.method == RationalMethod::semi_analytic) {
    // The rule with half the nodes: their difference bounds the coarser one's error, so it
    // overstates the finer one's.
    const RationalMoment coarse = run(std::max(options.quadrature_points / 2, 1));
    m.relative_error += std::abs(m.value - coarse.value) / std::abs(m.value);
  }
  m.value *= scale;
  return m;
}

}  // namespace

RationalMoment rational_moment_n(const SphericalRegion& region, const Vec3& v, int n, const Vec3& w,
                                 const RationalMomentOptions& options) {
  return q1_dispatch(region, v, n, v, v, w, Pattern::n, options);
}

RationalMoment rational_moment_n1(const SphericalRegion& region, const Vec3& v, int n, const Vec3& a, const Vec3& w,
                                  const RationalMomentOptions& options) {
  return q1_dispatch(region, v, n, a, a, w, Pattern::n1, options);
}

RationalMoment rational_moment_n11(const SphericalRegion& region, const Vec3& v, int n, const Vec3& a, const Vec3& b,
                                   const Vec3& w, const RationalMomentOptions& options) {
  return q1_dispatch(region, v, n, a, b, w, Pattern::n11, options);
}

}  // namespace daylit

// ---------------------------------------------------------------------------------------------
// Eqs. 64–67 and 73–77: the tensors M³ and M⁴ on each edge (rational_moments.hpp).

namespace daylit {

namespace {

// The per-edge integrals of M³ and M⁴ contracted with their axes, in the frame of w.
template <class R>
struct TensorEdge {
  const WFrameArc<R>& f;
  const GTable<R>* G;  // products only (tensor_moment with a third axis); m3 needs G(0,0), G(1,−1)
  const real::V3<R>& w;
  Tracked<R> eta_w;  // (w·m) ∫ η ds
  // G(0,0) = θ and G(1,−1) = −log1p((cos s1 − cos s0)/cos s0), as GTable has them: the two
  // entries m3 reads, without building the table (most of a radiosity run's per-edge work).
  Tracked<R> g00 = exact(f.arc.length), g1m1 = exact(-real::log1p(f.dcos / f.cos0));

  Tracked<R> theta() const { return exact(f.arc.length); }
  // Ī_x = ∫ (x·u)/(w·u) ds = [A G(0,0) + B G(1,−1)]/c with x·u = A cos s + B sin s.
  Tracked<R> rational_linear(const real::V3<R>& x) const { return (dot(x, f.p) * g00 + dot(x, f.q) * g1m1) / f.c; }
  // ∫ Π (x_i·u) (w·u)^t ds.
  Tracked<R> product(std::initializer_list<real::V3<R>> axes, int t) const {
    std::vector<std::pair<R, R>> factors;
    for (const auto& x : axes) factors.push_back({dot(x, f.p), dot(x, f.q)});
    std::vector<R> P, Pm;
    rational::trig_product(factors, P, Pm);
    const R ct = t >= 0 ? real::powi(f.c, t) : real::powi(R(1) / f.c, -t);
    return ct * rational::expand_integral(*G, P, Pm, t);
  }
  // ∫ M³(x, y, m) ds (eq. 65).
  Tracked<R> m3(const real::V3<R>& x, const real::V3<R>& y) const {
    const real::V3<R>& m = f.arc.normal;
    const real::V3<R> y_perp = y - dot(w, y) * w;
    return (dot(x, m) * dot(w, y)) * theta() + dot(y_perp, m) * rational_linear(x) - dot(y_perp, x) * eta_w;
  }
};

template <class R>
Tracked<R> tensor_moment(const SphericalRegion& region, const Vec3& w_in, const Vec3& a_in, const Vec3& b_in,
                         const Vec3* c_in) {
  const real::V3<R> w = real::unit<R>(w_in), a(a_in), b(b_in);
  Tracked<R> sum;
  for_each_edge<R>(region, [&](const ArcEdge<R>& arc) {
    const WFrameArc<R> f(arc, w);
    Tracked<R> eta_w = base_moment_edge(f);  // −(w·m) ∫ η ds
    eta_w.value = -eta_w.value;
    if (!c_in) {
      sum += TensorEdge<R>{f, nullptr, w, eta_w}.m3(a, b);
      return;
    }
    const GTable<R> G(f, 3, -1, 3);
    const TensorEdge<R> e{f, &G, w, eta_w};
    const real::V3<R> c(*c_in), &m = arc.normal;
    sum += dot(w, a) * e.m3(b, c);
    sum += dot(w, b) * e.m3(a, c);
    sum += dot(w, c) * e.m3(a, b);
    sum += (R(2) * dot(w, m)) * e.product({a, b, c}, -1);
    sum -= (dot(c, a) * dot(b, m) + dot(c, b) * dot(a, m)) * e.theta();
    sum -= (R(2) * dot(c, m)) * e.product({a, b}, 0);
  });
  return Tracked<R>{sum.value / 2, sum.magnitude / 2};
}

}  // namespace

RationalMoment linear_exitance_moment(const SphericalRegion& region, const Vec3& w, const Vec3& a, const Vec3& b,
                                      double absolute_tolerance) {
  check_side(region, w);
  if (!is_finite(a) || !is_finite(b)) throw Error("factor axes must be finite");
  RationalMoment m = escalate_tracked(
      2, [&](auto r) { return tensor_moment<decltype(r)>(region, w, a, b, nullptr); }, 1e-13, absolute_tolerance * norm(w));
  m.value /= norm(w);
  return m;
}

// Both moments T^{2;1}(a1, b) and T^{2;1}(a2, b) in one pass over the edges: the arc's frame,
// its G table and the η integral (Clausen functions, most of the cost) are shared.
template <class R>
std::array<Tracked<R>, 2> tensor_moment_pair(const SphericalRegion& region, const Vec3& w_in, const Vec3& a1_in,
                                             const Vec3& a2_in, const Vec3& b_in) {
  const real::V3<R> w = real::unit<R>(w_in), a1(a1_in), a2(a2_in), b(b_in);
  Tracked<R> s1, s2;
  for_each_edge<R>(region, [&](const ArcEdge<R>& arc) {
    const WFrameArc<R> f(arc, w);
    Tracked<R> eta_w = base_moment_edge(f);  // −(w·m) ∫ η ds
    eta_w.value = -eta_w.value;
    const TensorEdge<R> e{f, nullptr, w, eta_w};
    s1 += e.m3(a1, b);
    s2 += e.m3(a2, b);
  });
  return {s1 / R(2), s2 / R(2)};
}

std::array<real::Tracked<double>, 3> linear_element_edge_terms(const Vec3& from, const Vec3& to, const Vec3& w,
                                                              const Vec3& a1, const Vec3& a2, const Vec3& n) {
  using R = double;
  std::array<Tracked<R>, 3> out{};
  const auto arc = arc_edge(real::V3<R>(from), real::V3<R>(to));
  if (!arc) return out;
  const real::V3<R> wr(w), a1r(a1), a2r(a2), nr(n);
  // Lambert's formula: ½ θ (m·n) (lambert_sum in moments.cpp).
  out[0].add(R(0.5) * arc->length * dot(arc->normal, nr));
  // tensor_moment_pair's terms for this arc.
  const WFrameArc<R> f(*arc, wr);
  Tracked<R> eta_w = base_moment_edge(f);
  eta_w.value = -eta_w.value;
  const TensorEdge<R> e{f, nullptr, wr, eta_w};
  out[1] = e.m3(a1r, nr) / R(2);
  out[2] = e.m3(a2r, nr) / R(2);
  return out;
}

std::array<RationalMoment, 2> linear_exitance_moments(const SphericalRegion& region, const Vec3& w, const Vec3& a1,
                                                      const Vec3& a2, const Vec3& b, double absolute_tolerance) {
  check_side(region, w);
  if (!is_finite(a1) || !is_finite(a2) || !is_finite(b)) throw Error("factor axes must be finite");
  // The pair escalates together (the one ladder, precision_escalation.hpp): its κ is the larger
  // of the two, its absolute estimate from the larger magnitude.
  const Escalated<std::array<double, 2>> pair = escalate_tracked(
      2, [&](auto r) { return tensor_moment_pair<decltype(r)>(region, w, a1, a2, b); }, 1e-13,
      absolute_tolerance * norm(w));
  std::array<RationalMoment, 2> out;
  for (int i = 0; i < 2; ++i) out[i] = {pair.value[i] / norm(w), pair.relative_error, pair.precision, pair.condition};
  return out;
}

RationalMoment quadratic_exitance_moment(const SphericalRegion& region, const Vec3& w, const Vec3& a, const Vec3& b,
                                         const Vec3& c) {
  check_side(region, w);
  if (!is_finite(a) || !is_finite(b) || !is_finite(c)) throw Error("factor axes must be finite");
  RationalMoment m = escalate_tracked(3, [&](auto r) { return tensor_moment<decltype(r)>(region, w, a, b, &c); });
  m.value /= norm(w) * norm(w);
  return m;
}

}  // namespace daylit
