#pragma once
// Rational moments ∫_A P(u) / (w·u)^q dσ of regions bounded by great arcs (Chen and Arvo 2000,
// "Polynomially-varying luminaires", §2–4, and Chen and Arvo, "Linearly-varying luminaires",
// §3), for a unit axis w with w·u > 0 on the whole region (the region lies strictly on one side
// of the plane w·u = 0; the integrals diverge where it touches that plane along an arc).
//
// Orientation as in moments.hpp: loops counter-clockwise seen from outside, so the outward
// boundary normal of the papers is −m for an edge pole m, which turns their minus signs in front
// of boundary integrals into plus signs.
//
// All results are first computed in double together with the magnitude of every term that went
// into them (through the edge integrals, the Clausen terms and the recurrences); where the
// estimated error (10 + order)·u·κ, κ = magnitude/|value|, exceeds 1e-13 they are recomputed in
// long double, and if need be in __float128 (Cl2 by its series there, clausen.hpp), as
// moments.hpp does. The estimate is returned with the value.

#include <array>
#include <vector>

#include "geometry/spherical_region.hpp"
#include "illumination/factor_moment.hpp"
#include "illumination/precision_escalation.hpp"
#include "illumination/tracked_sum.hpp"

namespace daylit {

// value; relative_error, (10 + order)·u·κ in the precision that was used (see above); precision,
// the one it settled in (0 double, 1 long double, 2 __float128); condition, κ of the double pass,
// which measures how much the recurrences amplified rounding (bench rational reports it against
// the degree).
using RationalMoment = Escalated<double>;

// τ^{0;1} = ∫_A dσ/(w·u) (Chen and Arvo 2000, eq. 28): −Σ_edges (w·m) ∫_arc log(w·u)/(1 − (w·u)²) ds,
// each arc integral Λ(c, s1) − Λ(c, s0) in the arc's frame (eq. 33) through Cl2 (eq. 36,
// clausen.hpp), w any non-zero vector (normalised here).
RationalMoment rational_base_moment(const SphericalRegion& region, const Vec3& w);

// ∫_A Σ_i coef_i u1^{a_i} u2^{b_i} u3^{e_i} dσ in the orthonormal frame (e1, e2, w) (u1 = e1·u,
// u2 = e2·u, u3 = w·u; e_i may be negative). Every term reduces to the solid angle, τ^{0;1} and edge
// integrals by three forms of Stokes' theorem on the sphere (g homogeneous of degree k,
// x_j = e1, e2 or w):
//     ∫_A [∂_j g − (k + 2)(x_j·u) g] dσ = −Σ_edges (x_j·m) ∫_arc g ds,
// which with g = u1^{a−1} u2^b u3^e lowers a by 2 (Chen and Arvo's Theorem 3, eq. 12, in this
// frame), with g = u3^{e+1} u1^a u2^b lowers e by 2 (Theorem 1, eq. 2) and, where the first is
// singular (total degree −1), trades a for e until τ^{0;1} or an edge integral remains. The edge
// integrals ∫_arc u1^a u2^b u3^e ds are binomial sums of G(r, t) = ∫ sin^r s cos^t s ds over the
// arc (linearly-varying paper, eqs. 20–22), t ≥ −q, cached per edge (§3.4). Cost O(edges·D³) for
// total degree D. Accuracy as above; the recurrences amplify rounding with the degree (see
// polynomial_luminaire.hpp for where that stops being tolerable).
struct FrameMonomial {
  double coef;
  int a, b, e;  // a, b ≥ 0
};
// `term_values`, when given, receives each term's ∫ u1^a u2^b u3^e dσ (without coef), from the
// precision the sum settled in. The coefficients and the frame are doubles: the estimate adds
// 4·2^-53 Σ|coef·J| / |result| for their rounding, which no precision of the sum removes.
RationalMoment frame_polynomial_moment(const SphericalRegion& region, const Vec3& e1, const Vec3& e2, const Vec3& w,
                                       const std::vector<FrameMonomial>& terms,
                                       std::vector<double>* term_values = nullptr);

// A unit frame (e1, e2, ŵ) completing ŵ = w/|w|, right-handed (Duff et al.'s basis,
// orthonormal_basis.hpp).
struct AxisFrame {
  Vec3 e1, e2, w;
};
AxisFrame frame_about(const Vec3& w);

// ∫_A Π_k (a_k·u)^{p_k} / (w·u)^q dσ for q ≥ 0 and total numerator degree Σ p_k ≤
// kMaxFrameMomentDegree, by the recurrences of frame_polynomial_moment() with the frame and the
// expansion of the numerator formed in the precision of the sum. w need not be a unit vector:
// (w·u)^q = |w|^q (ŵ·u)^q. Throws daylit::Error where the region does not lie strictly on the
// positive side of w·u = 0 or the degree is too high.
constexpr int kMaxFrameMomentDegree = 12;
RationalMoment rational_moment(const SphericalRegion& region, const std::vector<Factor>& numerator, const Vec3& w,
                               int q);

// The three moments of the linearly-varying paper with denominator power 1 (eqs. 11–13):
//     τ^{n;1}     = ∫ (v·u)^n / (w·u) dσ,
//     τ^{n,1;1}   = ∫ (v·u)^n (a·u) / (w·u) dσ,
//     τ^{n,1,1;1} = ∫ (v·u)^n (a·u)(b·u) / (w·u) dσ,
// for any n ≥ 0, v, a, b any vectors, w non-zero. The recurrences (11)–(13) run upward in n from
// τ^{0;1} and the polynomial axial moments about v (Arvo's eq. 11), with the boundary integrals
// H_k = ∫_arc (v·u)^k/(w·u) ds and ∫_arc (v·u)^k (a·u)/(w·u) ds for every k ≤ n. How those are
// evaluated:
//   exact: binomial sums of the cached G(r, t) (eqs. 21–22 and §3.4), O(n²) per edge;
//   semi_analytic: Gauss–Legendre quadrature with `quadrature_points` nodes per edge of every
//     H_k at once (the powers built by repeated multiplication), O(n·points) per edge (§3.4's
//     "approximate T3 by 1-D quadrature"). Its relative_error adds the difference from the same
//     rule with half the nodes, scaled by the result, to the rounding estimate. The integrand is
//     analytic on the arc, so the error falls geometrically with the nodes once they resolve
//     (v·u)^n's lobe (width ~1/√n) and w·u's distance from zero; bench rational measures it.
enum class RationalMethod { exact, semi_analytic };
struct RationalMomentOptions {
  RationalMethod method = RationalMethod::exact;
  int quadrature_points = 32;
};
RationalMoment rational_moment_n(const SphericalRegion& region, const Vec3& v, int n, const Vec3& w,
                                 const RationalMomentOptions& options = {});
RationalMoment rational_moment_n1(const SphericalRegion& region, const Vec3& v, int n, const Vec3& a, const Vec3& w,
                                  const RationalMomentOptions& options = {});
RationalMoment rational_moment_n11(const SphericalRegion& region, const Vec3& v, int n, const Vec3& a, const Vec3& b,
                                   const Vec3& w, const RationalMomentOptions& options = {});

// Chen and Arvo's closed boundary forms for luminaires of linear and quadratic exitance (2000,
// eqs. 64–67 and 73–77), a second route to the moments above (the tests hold them to each other
// and to quadrature). With the outward normal −m and per edge θ, Ī_x = ∫ (x·u)/(w·u) ds (eq. 67's
// Ī2(1,1)), (w·m) ∫ η ds with η = log(w·u)/(1 − (w·u)²) (eq. 33, through Cl2), and y⊥ = y − (w·y) w,
//     ∫_arc M³(x, y, m) ds = (x·m)(w·y) θ + (y⊥·m) Ī_x − (y⊥·x)(w·m) ∫ η ds          (eq. 65)
//     ∫_arc M⁴(a, b, c, m) ds = (w·a) M³(b,c,m) + (w·b) M³(a,c,m) + (w·c) M³(a,b,m)
//                             + 2 (w·m) ∫ (a·u)(b·u)(c·u)/(w·u) ds − [(c·a)(b·m) + (c·b)(a·m)] θ
//                             − 2 (c·m) ∫ (a·u)(b·u) ds                                   (eq. 76)
// and T^{2;1}(a, b) = ½ Σ_edges ∫ M³, T^{3;2}(a, b, c) = ½ Σ_edges ∫ M⁴ (eqs. 64, 75 with n = −m).
// Irradiance from exitance (a·u)/(w·u) is T^{2;1}(a, n)/π (eq. 67), from h² (e_i·u)(e_j·u)/(w·u)²
// it is h² T^{3;2}(e_i, e_j, n)/π (eqs. 70–77). w non-zero (normalised here).
// `absolute_tolerance` > 0: the double pass is accepted where its estimated absolute error is at
// most that, even if the moment itself is small against its terms (radiosity sums many elements'
// moments, each small against the element's own irradiance where the region is symmetric about
// the axis a: relative accuracy of the moment alone is not what the sum needs; relative_error is
// then infinite for a value of exactly 0).
RationalMoment linear_exitance_moment(const SphericalRegion& region, const Vec3& w, const Vec3& a, const Vec3& b,
                                      double absolute_tolerance = 0);
RationalMoment quadratic_exitance_moment(const SphericalRegion& region, const Vec3& w, const Vec3& a, const Vec3& b,
                                         const Vec3& c);
// linear_exitance_moment(region, w, a1, b, tol) and (region, w, a2, b, tol) in one pass over the
// edges (the Clausen functions of the η integral shared): the two in-plane axes of a linearly
// varying element (radiosity). Same values, same accuracy; the pair escalates together.
std::array<RationalMoment, 2> linear_exitance_moments(const SphericalRegion& region, const Vec3& w, const Vec3& a1,
                                                      const Vec3& a2, const Vec3& b, double absolute_tolerance = 0);

// One great arc's share, in double, of Lambert's integral ∫ (n·u) dσ and of the pair
// linear_exitance_moments(region, w, a1, a2, n) (before its division by |w|: w must be unit):
// the region's values are the sums over its edges. For callers whose regions share edges (the
// elements of a mesh, seen from one point): each shared arc computed once, negated for the
// region that runs it the other way. Each share carries the magnitude of its terms, so that the
// caller can test the sum's accuracy as escalate_tracked() does (and fall back to the escalating
// functions above where it fails). The arc runs from direction `from` to `to` (any lengths,
// w·u > 0 on it); a degenerate arc contributes nothing.
std::array<real::Tracked<double>, 3> linear_element_edge_terms(const Vec3& from, const Vec3& to, const Vec3& w,
                                                              const Vec3& a1, const Vec3& a2, const Vec3& n);

}  // namespace daylit
