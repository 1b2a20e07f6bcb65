#include "illumination/irradiance_gradient.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "geometry/error.hpp"
#include "illumination/arc_edge.hpp"
#include "illumination/gauss_kronrod.hpp"
#include "illumination/precision_escalation.hpp"
#include "illumination/tracked_sum.hpp"

namespace daylit {

namespace {

using real::V3;

template <class R>
struct Complex {
  R re = 0, im = 0;
};
template <class R> Complex<R> operator*(const Complex<R>& a, const Complex<R>& b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}
template <class R> Complex<R> operator+(const Complex<R>& a, const Complex<R>& b) { return {a.re + b.re, a.im + b.im}; }
template <class R> Complex<R> conj(const Complex<R>& a) { return {a.re, -a.im}; }

// A real trigonometric polynomial Σ_{k=−d..d} C_k e^{ikt}, with C_{−k} = conj(C_k): C_0..C_d kept,
// d < kMaxTrigDegree (on the stack: the kernel runs once per edge of every sensor's region).
constexpr std::size_t kMaxTrigDegree = 64;
template <class R>
struct TrigPolynomial {
  std::array<Complex<R>, kMaxTrigDegree> c;  // only c[0..size) is meaningful
  std::size_t size = 1;                      // d + 1
};

// The linear form w·u(t) = (w·A) cos t + (w·S) sin t = γ e^{it} + conj(γ) e^{−it},
// γ = ((w·A) − i (w·S))/2.
template <class R>
Complex<R> linear_form(const V3<R>& w, const V3<R>& A, const V3<R>& S) {
  return {dot(w, A) / 2, -dot(w, S) / 2};
}

// P ← P·(γ e^{it} + conj(γ) e^{−it}), in place: coefficient k of the product is
// γ C_{k−1} + conj(γ) C_{k+1}. The caller keeps the degree below kMaxTrigDegree.
template <class R>
void times_linear(TrigPolynomial<R>& P, const Complex<R>& g) {
  const std::size_t d = P.size - 1;
  const auto old = [&](std::size_t k) { return k <= d ? P.c[k] : Complex<R>{}; };
  const Complex<R> g_bar = conj(g);
  Complex<R> previous = P.c[0];  // the old C_{k−1}
  const Complex<R> zeroth{2 * (g_bar * old(1)).re, 0};
  for (std::size_t k = 1; k <= d + 1; ++k) {
    const Complex<R> current = old(k);
    P.c[k] = g * previous + g_bar * old(k + 1);
    previous = current;
  }
  P.c[0] = zeroth;
  P.size = d + 2;
}

// ∫_0^θ P(t) dt = C_0 θ + 2 Σ_{k ≥ 1} Re[C_k (sin kθ + i (1 − cos kθ))/k], and the sum of the
// absolute values of its terms. sin kθ and cos kθ − 1 by the angle-addition recurrence written
// for the differences from (0, 1) (cos((k+1)θ) − 1 = c_k + c_1 + c_k c_1 − s_k s_1, sin((k+1)θ) =
// s_k + s_1 + s_k c_1 + c_k s_1), started from the arc's sin θ and 1 − cos θ (arc_edge.hpp, from
// the chord): no trigonometric call, and short arcs keep their relative precision; the error grows
// by an ulp per order.
template <class R>
real::Tracked<R> integrate(const TrigPolynomial<R>& P, const ArcEdge<R>& arc) {
  real::Tracked<R> sum;
  sum.add(P.c[0].re * arc.length);
  const R s1 = arc.sin_length, c1 = -arc.one_minus_cos;
  R s = s1, c = c1;  // sin kθ, cos kθ − 1 for k = 1
  for (std::size_t k = 1; k < P.size; ++k) {
    const R term = 2 * (P.c[k].re * s + P.c[k].im * c) / R(k);
    sum.add(term);
    const R s_next = s + s1 + s * c1 + c * s1;
    c = c + c1 + c * c1 - s * s1;
    s = s_next;
  }
  return sum;
}

// A vector sum with the magnitude of its terms (tracked_sum.hpp).
template <class R>
using VectorSum = real::Tracked<R, V3<R>>;

// The line of a moving edge seen from the receiver: μ, the unit normal of its plane through p
// (sign left to the caller), and w with w·u = 1/r, r the distance along u to the line.
template <class R>
struct EdgeLine {
  V3<R> c, w;
};

template <class R>
std::optional<EdgeLine<R>> edge_line(const EdgeSource& source, const Vec3& origin) {
  // Differences of the input doubles in R: exact in long double and __float128 for inputs of
  // similar exponents, and no worse than one rounding in double.
  const V3<R> a = V3<R>(source.a) - V3<R>(origin);
  const V3<R> d = V3<R>(source.b) - V3<R>(source.a);
  const V3<R> c = cross(a, d);
  const R c2 = dot(c, c);
  // The receiver on the line: the edge's arc has no length (or the input is degenerate).
  if (!(c2 > 0)) return std::nullopt;
  return EdgeLine<R>{c, cross(d, c) / c2};
}

// Calls f(arc, μ, w) for every edge of the region that moves with the receiver.
template <class R, class F>
void for_each_moving_edge(const SphericalRegion& region, const Vec3& origin, F&& f) {
  if (!region.has_edge_sources()) throw Error("irradiance gradient: the region carries no edge sources");
  for (std::size_t l = 0; l < region.loops.size(); ++l) {
    const DirectionLoop& loop = region.loops[l];
    const EdgeSourceLoop& sources = region.edge_sources[l];
    if (sources.size() != loop.size()) throw Error("irradiance gradient: edge sources do not match the loop");
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const EdgeSource& source = sources[i];
      if (source.kind == EdgeSource::Kind::receiver_plane || source.kind == EdgeSource::Kind::horizon) continue;
      if (source.kind == EdgeSource::Kind::unknown) throw Error("irradiance gradient: an edge of unknown source");
      const auto arc = arc_edge(V3<R>(loop[i]), V3<R>(loop[(i + 1) % loop.size()]));
      if (!arc) continue;
      const auto line = edge_line<R>(source, origin);
      if (!line) continue;
      // μ points into the region: the side of the arc's pole (moments.hpp's orientation).
      V3<R> mu = line->c / real::norm(line->c);
      if (dot(mu, arc->normal) < 0) mu = R(-1) * mu;
      f(*arc, mu, line->w);
    }
  }
}

template <class R>
VectorSum<R> directional_gradient_sum(const SphericalRegion& region, const Vec3& origin, const Vec3& n_in,
                                      const DirectionalRadiance& L) {
  const V3<R> n(n_in), beta(L.beta), axis(L.axis);
  // A bound on |L(u)| over the sphere with |c_k| in place of c_k: the scale against which the
  // rounding of the Horner sums (which may cancel, as fitted glazing polynomials do) is measured.
  R bound = 0;
  for (std::size_t k = L.c.size(); k-- > 0;) bound = bound * real::norm(axis) + real::abs(R(L.c[k]));
  bound *= real::abs(R(L.alpha)) + real::norm(beta);
  VectorSum<R> sum;
  for_each_moving_edge<R>(region, origin, [&](const ArcEdge<R>& arc, const V3<R>& mu, const V3<R>& w) {
    const V3<R>& A = arc.start;
    const V3<R>& S = arc.start_tangent;
    // T(u) = Σ c_k (a·u)^k by Horner's rule on trigonometric polynomials.
    const Complex<R> ga = linear_form(axis, A, S);
    TrigPolynomial<R> T;
    T.c[0] = {R(L.c.back()), 0};
    for (std::size_t k = L.c.size() - 1; k-- > 0;) {
      times_linear(T, ga);
      T.c[0].re += R(L.c[k]);
    }
    TrigPolynomial<R> P = T;
    times_linear(P, linear_form(beta, A, S));
    for (std::size_t k = 0; k < T.size; ++k) P.c[k] = P.c[k] + Complex<R>{R(L.alpha) * T.c[k].re, R(L.alpha) * T.c[k].im};
    times_linear(P, linear_form(n, A, S));
    times_linear(P, linear_form(w, A, S));
    const real::Tracked<R> integral = integrate(P, arc);
    // ∫|integrand| ≤ θ · bound · |n| · |w|, and at least the magnitude of the terms summed.
    sum.add(integral.value * mu, std::max(integral.magnitude, arc.length * bound * real::norm(n) * real::norm(w)));
  });
  return sum;
}

// The gradient rounded to double, with the estimate 10·u·κ of its relative error (κ of the
// vector sum, tracked_sum.hpp).
template <class R>
Attempt<Vec3> finish(const VectorSum<R>& sum) {
  const R kappa = real::condition(sum);
  return {{double(sum.value.x), double(sum.value.y), double(sum.value.z)},
          double(R(10) * real::unit_roundoff<R>() * kappa),
          double(kappa)};
}

// ---------------------------------------------------------------------------------------------
// Polynomial exitances.

int degree(const ExitancePolynomial& M) {
  int d = 0;
  for (const ExitanceTerm& t : M)
    if (t.coef != 0) d = std::max(d, t.i + t.j + t.k);
  return d;
}

// ∂M/∂x_axis.
ExitancePolynomial derivative(const ExitancePolynomial& M, int axis) {
  ExitancePolynomial out;
  for (const ExitanceTerm& t : M) {
    const int power = axis == 0 ? t.i : (axis == 1 ? t.j : t.k);
    if (power == 0 || t.coef == 0) continue;
    ExitanceTerm d = t;
    d.coef *= power;
    (axis == 0 ? d.i : (axis == 1 ? d.j : d.k)) -= 1;
    out.push_back(d);
  }
  return out;
}

ExitancePolynomial scaled(const ExitancePolynomial& M, double s) {
  ExitancePolynomial out = M;
  for (ExitanceTerm& t : out) t.coef *= s;
  return out;
}

ExitancePolynomial operator+(ExitancePolynomial a, const ExitancePolynomial& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// (x_axis − c)·M.
ExitancePolynomial times_coordinate_minus(const ExitancePolynomial& M, int axis, double c) {
  ExitancePolynomial out = scaled(M, -c);
  for (ExitanceTerm t : M) {
    (axis == 0 ? t.i : (axis == 1 ? t.j : t.k)) += 1;
    out.push_back(t);
  }
  return out;
}

template <class R>
R evaluate(const ExitancePolynomial& M, const V3<R>& x) {
  R sum = 0;
  for (const ExitanceTerm& t : M) sum += R(t.coef) * real::powi(x.x, t.i) * real::powi(x.y, t.j) * real::powi(x.z, t.k);
  return sum;
}

// ∫_a^b f by bisection until each panel's error estimate is within `tolerance` of the arc's
// ∫|f| times the panel's share of [a, b], or within 50 u of the panel's own ∫|f| (where rounding,
// not the rule, limits it). Adds ∫ f and ∫|f| to `sum`. Sets `failed` (and stops refining) where
// the estimate is not a number (the integrand overflowed) or `budget` panels were used up.
template <class R, class F>
void adaptive(const F& f, R a, R b, R tolerance_per_length, int& budget, real::Tracked<R>& sum, bool& failed) {
  const quadrature::KronrodPanel<R> p = quadrature::gauss_kronrod_15(f, a, b);
  --budget;
  const R allowed = std::max(tolerance_per_length * (b - a), R(50) * real::unit_roundoff<R>() * p.magnitude);
  const bool converged = p.error <= allowed;
  if (converged || budget <= 0 || !(p.error == p.error) || failed) {
    failed |= !converged;
    sum.add(p.integral, p.magnitude);
    return;
  }
  const R m = (a + b) / 2;
  adaptive(f, a, m, tolerance_per_length, budget, sum, failed);
  adaptive(f, m, b, tolerance_per_length, budget, sum, failed);
}

// The boundary term of a polynomial exitance, (1/π) Σ μ ∫_arc M(x(u)) (n·u)(w·u) ds, in R.
template <class R>
VectorSum<R> exitance_boundary_sum(const SphericalRegion& region, const Vec3& origin, const Vec3& n_in, const Vec3& nu_in,
                                   double D, const ExitancePolynomial& M, double tolerance, bool& failed) {
  const V3<R> n(n_in), nu(nu_in), p(origin);
  const R pi = real::pi<R>();
  VectorSum<R> sum;
  for_each_moving_edge<R>(region, origin, [&](const ArcEdge<R>& arc, const V3<R>& mu, const V3<R>& w) {
    const auto f = [&](R t) {
      const V3<R> u = real::cos(t) * arc.start + real::sin(t) * arc.start_tangent;
      const V3<R> x = p + (R(D) / dot(nu, u)) * u;
      return evaluate(M, x) * dot(n, u) * dot(w, u);
    };
    // ∫|f| first, coarsely, to set the absolute tolerance of the arc.
    const quadrature::KronrodPanel<R> coarse = quadrature::gauss_kronrod_15(f, R(0), arc.length);
    const R tolerance_per_length = R(tolerance) * coarse.magnitude / arc.length;
    real::Tracked<R> integral;
    // 2000 panels (30,000 evaluations) per arc: a receiver 1e-9 from the luminaire's plane needs
    // a few hundred, where the integrand's poles come within 1e-9 of the arc's ends.
    int budget = 2000;
    adaptive(f, R(0), arc.length, tolerance_per_length, budget, integral, failed);
    sum.add((integral.value / pi) * mu, integral.magnitude / pi);
  });
  return sum;
}

}  // namespace

IrradianceGradient directional_irradiance_gradient(const SphericalRegion& region, const Vec3& origin, const Vec3& n,
                                                   const DirectionalRadiance& radiance, double tolerance) {
  if (radiance.c.empty()) throw Error("irradiance gradient: empty radiance polynomial");
  // The integrand's degree is that of c plus 3 (α + β·u, n·u, w·u).
  if (radiance.c.size() + 3 > kMaxTrigDegree)
    throw Error("irradiance gradient: radiance polynomial of degree " + std::to_string(radiance.c.size() - 1) + " above " +
                std::to_string(kMaxTrigDegree - 4));
  const auto g = escalate(
      [&](auto zero) { return finish(directional_gradient_sum<decltype(zero)>(region, origin, n, radiance)); }, tolerance);
  return {g.value, g.relative_error, g.precision};
}

LuminaireGradient polynomial_luminaire_gradient(const SphericalRegion& region, const Vec3& origin, const Vec3& n,
                                                const Vec3& plane_point, const Vec3& plane_normal,
                                                const ExitancePolynomial& exitance, double tolerance) {
  LuminaireGradient out;
  const LuminaireIrradiance E = polynomial_luminaire_irradiance(region, origin, n, plane_point, plane_normal, exitance);
  out.value = E.value;
  out.relative_error = E.relative_error;
  if (region.empty()) return out;
  // ν facing away from the origin, D > 0 its distance to the plane.
  Vec3 nu = normalized(plane_normal);
  double D = dot(nu, plane_point - origin);
  if (D < 0) {
    nu = -1.0 * nu;
    D = -D;
  }
  if (!(D > 0)) throw Error("irradiance gradient: the origin lies in the luminaire's plane");

  // Boundary term.
  IrradianceGradient boundary;
  if (degree(exitance) == 0) {
    DirectionalRadiance L;
    L.alpha = 0;
    for (const ExitanceTerm& t : exitance) L.alpha += t.coef;
    L.alpha /= std::numbers::pi;
    boundary = directional_irradiance_gradient(region, origin, n, L, tolerance);
  } else {
    // Each arc to arc_tolerance of its ∫|integrand|: the error of the sum is then within
    // (10u + arc_tolerance)·κ of it, κ = Σ ∫|integrand| / |sum|. The first attempt guesses κ = 10;
    // where edge terms cancel more, the next precision is tried with the arc tolerance tightened by
    // the κ just measured.
    double kappa = 10;
    const auto attempt = [&](auto zero) {
      using R = decltype(zero);
      const double u = double(real::unit_roundoff<R>());
      const double arc_tolerance = std::max(tolerance / (2 * kappa), 100 * u);
      bool failed = false;
      const VectorSum<R> sum = exitance_boundary_sum<R>(region, origin, n, nu, D, exitance, arc_tolerance, failed);
      Attempt<Vec3> a = finish(sum);
      kappa = a.condition;
      a.relative_error = failed ? HUGE_VAL : (10 * u + arc_tolerance) * kappa;
      return a;
    };
    const auto b = escalate(attempt, tolerance);
    boundary = {b.value, b.relative_error, b.precision};
  }

  // Interior term E[g] − (ν/D) E[(x − p)·g], g = (I − νν^T)∇M.
  Vec3 interior{};
  double interior_error = 0;  // absolute
  if (degree(exitance) > 0) {
    std::array<ExitancePolynomial, 3> gradient_M;
    for (int a = 0; a < 3; ++a) gradient_M[a] = derivative(exitance, a);
    ExitancePolynomial normal_part = scaled(gradient_M[0], nu.x) + scaled(gradient_M[1], nu.y) + scaled(gradient_M[2], nu.z);
    ExitancePolynomial radial;  // (x − p)·g
    double* components[3] = {&interior.x, &interior.y, &interior.z};
    for (int a = 0; a < 3; ++a) {
      const ExitancePolynomial g = gradient_M[a] + scaled(normal_part, -nu[a]);
      radial = radial + times_coordinate_minus(g, a, origin[a]);
      const LuminaireIrradiance Eg = polynomial_luminaire_irradiance(region, origin, n, plane_point, plane_normal, g);
      *components[a] = Eg.value;
      interior_error += Eg.relative_error * std::abs(Eg.value);
    }
    const LuminaireIrradiance Er = polynomial_luminaire_irradiance(region, origin, n, plane_point, plane_normal, radial);
    interior -= (Er.value / D) * nu;
    interior_error += Er.relative_error * std::abs(Er.value) / D;
  }
  out.gradient = boundary.value + interior;
  const double size = norm(out.gradient);
  const double error = boundary.relative_error * norm(boundary.value) + interior_error;
  out.relative_error = std::max(out.relative_error, size > 0 ? error / size : (error > 0 ? HUGE_VAL : 0.0));
  return out;
}

}  // namespace daylit
