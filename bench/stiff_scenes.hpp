#pragma once
// Stiff and extreme scenes (DESIGN.md §5 at the scene level) and an independent reference for
// each: what `daylit bench stiff` measures exact and float geometry against, and what
// tests/geometry/test_stiff_scenes.cpp holds the exact path to.
//
// Each case is one sensor in a small scene, with the part of the aperture that the sensor sees
// worked out by hand (a window minus a shadow strip, the window ∩ the projection of a reveal's
// outer opening, ...) as convex planar polygons in the case's local frame. The reference clips
// them to the receiver's tangent plane and horizon and integrates the overcast sky over them in
// long double by nested adaptive Gauss–Legendre quadrature, over their area or in polar
// coordinates about the foot of the perpendicular from the sensor to their plane. It shares no
// code and no formula with daylit's path (no clipping of 3D geometry, no spherical polygons, no
// boundary integrals).
//
// Header-only so that the CLI and the tests can both include it without a library of its own.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "illumination/gauss_legendre.hpp"
#include "illumination/tracked_sum.hpp"
#include "materials/glass_transmittance.hpp"

namespace daylit::stiff {

using Real = long double;

struct RVec {
  Real x = 0, y = 0, z = 0;
};
inline RVec operator+(const RVec& a, const RVec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline RVec operator-(const RVec& a, const RVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline RVec operator*(Real s, const RVec& a) { return {s * a.x, s * a.y, s * a.z}; }
inline Real dot(const RVec& a, const RVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline RVec cross(const RVec& a, const RVec& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline Real norm(const RVec& a) { return std::sqrt(dot(a, a)); }
inline RVec rvec(const Vec3& v) { return {v.x, v.y, v.z}; }

// A convex planar polygon of the aperture that the sensor sees (before the cut by its tangent
// plane and horizon), in the case's local frame, and the aperture's transmittance there.
struct VisiblePiece {
  std::vector<RVec> vertices;
  Real transmittance = 1;
  std::vector<Real> angular{};  // T(μ) = Σ angular[k] μ^k, μ the cosine of incidence; empty: constant
};

struct StiffCase {
  std::string name;         // CSV key
  std::string description;  // what is stiff about it
  Scene scene;              // what daylit is given (possibly rotated and moved)
  Sensor sensor;            // in the scene's coordinates
  RVec p, n;                // the sensor in the local frame (n unit)
  std::vector<VisiblePiece> visible;
  // Relative tolerance for the exact path against the reference (absolute, in percent, when the
  // reference is 0), and why it is what it is.
  double tolerance;
  std::string tolerance_note;
};

// ── Reference ───────────────────────────────────────────────────────────────────────────────

namespace detail {

// The 20-point Gauss–Legendre rule on [−1, 1] (illumination/gauss_legendre.hpp).
struct GaussLegendre20 {
  static constexpr int n = 20;
  std::array<Real, n> x{}, w{};
  GaussLegendre20() {
    const quadrature::GaussLegendreRule rule = quadrature::gauss_legendre(n);
    std::copy(rule.x.begin(), rule.x.end(), x.begin());
    std::copy(rule.w.begin(), rule.w.end(), w.begin());
  }
};

inline const GaussLegendre20& gauss_legendre20() {
  static const GaussLegendre20 rule;
  return rule;
}

template <class F>
Real gauss_legendre(const F& f, Real a, Real b) {
  const GaussLegendre20& r = gauss_legendre20();
  const Real half = (b - a) / 2, mid = (a + b) / 2;
  Real sum = 0;
  for (int i = 0; i < GaussLegendre20::n; ++i) sum += r.w[std::size_t(i)] * f(mid + half * r.x[std::size_t(i)]);
  return half * sum;
}

// Adaptive bisection: accept the two halves when they agree with the whole to `tolerance`
// (absolute, the same on every subinterval: the halves are far more accurate than the test).
template <class F>
Real adaptive(const F& f, Real a, Real b, Real whole, Real tolerance, int depth) {
  const Real m = (a + b) / 2, left = gauss_legendre(f, a, m), right = gauss_legendre(f, m, b);
  if (depth <= 0 || std::abs(left + right - whole) <= tolerance) return left + right;
  return adaptive(f, a, m, left, tolerance, depth - 1) + adaptive(f, m, b, right, tolerance, depth - 1);
}

// ∫_a^b f to about `relative` times ∫|f| (estimated by one rule first).
template <class F>
Real integrate(const F& f, Real a, Real b, Real relative) {
  if (a == b) return 0;
  const Real whole = gauss_legendre(f, a, b);
  const Real scale = gauss_legendre([&](Real t) { return std::abs(f(t)); }, a, b);
  if (scale == 0) return 0;
  return adaptive(f, a, b, whole, relative * std::abs(scale), 40);
}

struct P2 {
  Real x, y;
};
inline Real cross2(const P2& a, const P2& b) { return a.x * b.y - a.y * b.x; }
inline Real dot2(const P2& a, const P2& b) { return a.x * b.x + a.y * b.y; }

// Sutherland–Hodgman: the part of a convex polygon where a·x + b·y + c ≥ 0.
inline std::vector<P2> clip(const std::vector<P2>& poly, Real a, Real b, Real c) {
  std::vector<P2> out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const P2 &P = poly[i], &Q = poly[(i + 1) % poly.size()];
    const Real fp = a * P.x + b * P.y + c, fq = a * Q.x + b * Q.y + c;
    if (fp >= 0) out.push_back(P);
    if ((fp > 0 && fq < 0) || (fp < 0 && fq > 0)) {
      const Real t = fp / (fp - fq);
      out.push_back({P.x + t * (Q.x - P.x), P.y + t * (Q.y - P.y)});
    }
  }
  return out;
}

}  // namespace detail

struct ReferenceValue {
  Real sc_percent;
  Real relative_error;  // estimate: the quadrature's target, 1e-17, times Σ|terms|/|Σ terms|
};

// Overcast sky component (percent) through one visible piece: (100/E_out)·∫ L(u)·T(u)·(n·u) dσ
// with L = (1 + 2u_z)/3, E_out = 7π/9, over the piece ∩ {n·(x − p) ≥ 0} ∩ {z ≥ p_z}, the cut
// made in the piece's plane (Sutherland–Hodgman in long double).
//
// Let f be the foot of the perpendicular from p to the piece's plane (unit normal w, distance h).
// Where f lies outside the piece, the integral is taken over its area, dσ = h dA/r³, on a fan of
// triangles from its first vertex (each mapped from the unit square by Duffy's collapse, so the
// integrand is smooth and positive and nothing cancels). Where f lies inside or on the boundary,
// h dA/r³ peaks at f, and polar coordinates about f are used instead: u = cos θ·w + sin θ·d(φ),
// dσ = sin θ dθ dφ, on the fan of triangles (f, A, B) over the edges, φ sweeping from A to B and θ
// running from 0 to atan2(R(φ), h), R(φ) the distance from f to the edge's line along d(φ). All
// terms are then positive too. Both integrals are nested adaptive 20-point Gauss–Legendre rules.
inline ReferenceValue reference_piece(const RVec& p, const RVec& n_in, const VisiblePiece& piece) {
  using namespace detail;
  const auto& V = piece.vertices;
  RVec N{};
  for (std::size_t i = 1; i + 1 < V.size(); ++i) N = N + cross(V[i] - V[0], V[i + 1] - V[0]);
  RVec w = (1 / norm(N)) * N;
  Real h = dot(w, V[0] - p);
  if (h == 0) return {0, 0};
  if (h < 0) w = Real(-1) * w, h = -h;
  const RVec e1 = (1 / norm(V[1] - V[0])) * (V[1] - V[0]);
  const RVec e2 = cross(w, e1);
  const RVec n = (1 / norm(n_in)) * n_in;
  std::vector<P2> q;
  for (const RVec& v : V) q.push_back({dot(v - p, e1), dot(v - p, e2)});
  q = clip(q, dot(n, e1), dot(n, e2), h * dot(n, w));  // receiver's tangent plane
  q = clip(q, e1.z, e2.z, h * w.z);                    // horizon
  if (q.size() < 3) return {0, 0};
  Real area = 0;
  for (std::size_t i = 0; i < q.size(); ++i) area += cross2(q[i], q[(i + 1) % q.size()]);
  if (area == 0) return {0, 0};

  const auto g = [&](const RVec& u) {
    const Real mu = std::abs(dot(w, u));
    Real t = piece.transmittance;
    if (!piece.angular.empty()) {
      t = 0;
      for (auto k = piece.angular.size(); k-- > 0;) t = t * mu + piece.angular[k];
    }
    return (1 + 2 * u.z) / 3 * t * dot(n, u);
  };
  const Real relative = 1e-17L;
  // f inside, on the boundary, or outside: the sweeps of the edges about f add up to ±2π inside,
  // less on the boundary (an edge through f has no sweep), 0 outside.
  bool on_boundary = false;
  Real sweep_sum = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const P2 A = q[i], B = q[(i + 1) % q.size()];
    if (cross2(A, B) == 0 && dot2(A, B) <= 0) on_boundary = true;
    if (cross2(A, B) != 0) sweep_sum += std::atan2(cross2(A, B), dot2(A, B));
  }
  const bool outside = !on_boundary && std::abs(sweep_sum) < 1;
  real::Tracked<Real> sum;  // the integral's pieces, with their magnitudes (tracked_sum.hpp)
  if (outside) {
    for (std::size_t i = 1; i + 1 < q.size(); ++i) {
      const P2 A = q[0], AB{q[i].x - A.x, q[i].y - A.y}, BC{q[i + 1].x - q[i].x, q[i + 1].y - q[i].y};
      const Real jacobian = std::abs(cross2(AB, P2{q[i + 1].x - A.x, q[i + 1].y - A.y}));
      const Real term = integrate(
          [&](Real a) {
            return a * integrate(
                           [&](Real b) {
                             const Real s = A.x + a * (AB.x + b * BC.x), t = A.y + a * (AB.y + b * BC.y);
                             const RVec x = h * w + s * e1 + t * e2;
                             const Real r = norm(x);
                             return g((1 / r) * x) * h / (r * r * r);
                           },
                           0, 1, relative / 4);
          },
          0, 1, relative);
      sum.add(jacobian * term);
    }
  } else {
    for (std::size_t i = 0; i < q.size(); ++i) {
      const P2 A = q[i], B = q[(i + 1) % q.size()];
      const Real c = cross2(A, B);
      if (c == 0) continue;  // f on this edge's line: a triangle of zero area
      const Real sweep = std::atan2(c, dot2(A, B)), ra = std::sqrt(dot2(A, A));
      const P2 a_hat{A.x / ra, A.y / ra}, a_perp{-a_hat.y, a_hat.x}, e{B.x - A.x, B.y - A.y};
      const Real line = cross2(A, e);
      const Real term = integrate(
          [&](Real phi) {
            const P2 d2{std::cos(phi) * a_hat.x + std::sin(phi) * a_perp.x, std::cos(phi) * a_hat.y + std::sin(phi) * a_perp.y};
            const Real R = line / cross2(d2, e);
            const RVec d = d2.x * e1 + d2.y * e2;
            return integrate([&](Real theta) { return g(std::cos(theta) * w + std::sin(theta) * d) * std::sin(theta); }, 0,
                             std::atan2(R, h), relative / 4);
          },
          0, sweep, relative);
      sum.add((area > 0 ? 1 : -1) * term);
    }
  }
  const Real to_percent = 100 / (7 * 3.141592653589793238462643383279502884L / 9);
  return {sum.value * to_percent, relative * real::condition(sum)};
}

inline ReferenceValue reference_sky_component(const StiffCase& c) {
  Real sum = 0, error = 0;
  for (const VisiblePiece& piece : c.visible) {
    const ReferenceValue r = reference_piece(c.p, c.n, piece);
    sum += r.sc_percent;
    error += r.relative_error * std::abs(r.sc_percent);
  }
  return {sum, sum != 0 ? error / std::abs(sum) : 0};
}

// ── Cases ───────────────────────────────────────────────────────────────────────────────────

namespace detail {

inline Polygon polygon(std::vector<Vec3> vertices, std::string name) {
  Polygon p;
  p.vertices = std::move(vertices);
  p.name = std::move(name);
  p.where = {"stiff case", 1};
  return p;
}

inline std::vector<RVec> rvecs(const std::vector<Vec3>& v) {
  std::vector<RVec> out;
  for (const Vec3& x : v) out.push_back(rvec(x));
  return out;
}

// x ∈ [x0, x1], z ∈ [z0, z1] in the plane y = y0 (local frame, long double corners).
inline std::vector<RVec> rect_y(Real y0, Real x0, Real x1, Real z0, Real z1) {
  return {{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}};
}

// The windows of the cases: y = 0, x ∈ [0, width], z ∈ [1, 2]; the room is at y > 0.
inline std::vector<Vec3> window(double width = 2) { return {{0, 0, 1}, {width, 0, 1}, {width, 0, 2}, {0, 0, 2}}; }

// A wall in the window's plane, x ∈ [x0, x1], z ∈ [0, 3], with the window cut out by a seam.
inline Polygon wall_with_seam_hole(double x0, double x1, double width = 2) {
  return polygon({{x0, 0, 0}, {x1, 0, 0}, {x1, 0, 3}, {x0, 0, 3}, {x0, 0, 1}, {0, 0, 1}, {0, 0, 2}, {width, 0, 2}, {width, 0, 1}, {0, 0, 1}, {x0, 0, 1}},
                 "wall");
}

// Four faces of a reveal of depth d outside the window (y ∈ [−d, 0]), flush with its edges.
inline std::vector<Polygon> reveal(double d, double width = 2) {
  return {polygon({{0, 0, 1}, {0, -d, 1}, {0, -d, 2}, {0, 0, 2}}, "jamb left"),
          polygon({{width, 0, 1}, {width, 0, 2}, {width, -d, 2}, {width, -d, 1}}, "jamb right"),
          polygon({{0, 0, 1}, {width, 0, 1}, {width, -d, 1}, {0, -d, 1}}, "sill"),
          polygon({{0, 0, 2}, {0, -d, 2}, {width, -d, 2}, {width, 0, 2}}, "head")};
}

// What p sees through a window of the given width with a reveal of depth d: the window ∩ the
// projection from p of the outer opening (y = −d) onto y = 0, i.e. the opening scaled by
// s = p_y/(p_y + d) about p's foot point.
inline VisiblePiece reveal_visible(const RVec& p, Real d, Real width = 2) {
  const Real s = p.y / (p.y + d);
  const auto proj = [&](Real a, Real pa) { return pa + (a - pa) * s; };
  const Real x0 = std::max<Real>(0, proj(0, p.x)), x1 = std::min<Real>(width, proj(width, p.x));
  const Real z0 = std::max<Real>(1, proj(1, p.z)), z1 = std::min<Real>(2, proj(2, p.z));
  return {rect_y(0, x0, x1, z0, z1)};
}

inline Sensor sensor(const Vec3& p, const Vec3& n) { return {p, normalized(n)}; }

}  // namespace detail

inline std::vector<StiffCase> stiff_cases() {
  using namespace detail;
  std::vector<StiffCase> cases;
  const Vec3 up{0, 0, 1};
  const auto add = [&](std::string name, std::string description, Scene scene, const Vec3& p, const Vec3& n,
                       std::vector<VisiblePiece> visible, double tolerance, std::string note) {
    StiffCase c{std::move(name), std::move(description), std::move(scene), sensor(p, n), rvec(p), rvec(normalized(n)),
                std::move(visible), tolerance, std::move(note)};
    cases.push_back(std::move(c));
  };
  const auto window_scene = [](double width = 2) {
    Scene s;
    s.apertures.push_back({polygon(window(width), "window"), 1.0});
    return s;
  };
  // Tolerances. Where the region is of ordinary size the exact path is off by roundoff only
  // (measured ≤ 7e-16 on these cases); 1e-13 leaves room for other compilers and libms. Where it
  // is 1e-7 thick or 1e-6 wide, the directions' certification to 2^-45 of their length (README)
  // would allow up to ~1e-7 relative, though the intervals are far tighter in practice (measured
  // ≤ 2e-16): those cases are held to the 1e-9 the issue asks for. Where the answer in decimals is
  // 0 the bound is 1e-15 percentage points: a view that closes to a line in decimals need not close
  // in the input doubles (reveal_closes_view keeps a real sliver of ~1e-18 %, see there).
  const std::string roundoff = "roundoff only (measured <= 7e-16); room for other compilers";
  const std::string thin = "directions certified to 2^-45 of their length could allow ~1e-7 here; measured ~1e-16; the issue's 1e-9";
  const std::string zero = "0 in decimals; the input doubles may leave a real sliver of ~1e-18 %";

  // Receiver in the aperture's plane, and a tangent plane through the window (n·u → 0 on A).
  add("receiver_in_window_plane", "sensor in the window's plane (y = 0) beside it, facing along it: sees none of it",
      window_scene(), {3, 0, 1.5}, {-1, 0.2, 0}, {{rect_y(0, 0, 2, 1, 2)}}, 1e-15, zero);
  add("tangent_plane_halves_window", "vertical sensor facing +x whose tangent plane x = 1 halves the window: n.u -> 0 along the cut",
      window_scene(), {1, 1.5, 0.85}, {1, 0, 0}, {{rect_y(0, 0, 2, 1, 2)}}, 1e-13, roundoff);
  // Window seen edge-on.
  add("window_edge_on_1e-7", "sensor 1e-7 m in front of the window's plane, 1 m to its side, facing along the wall: the window edge-on",
      window_scene(), {-1, 1e-7, 1.2}, {1, 0, 0}, {{rect_y(0, 0, 2, 1, 2)}}, 1e-9, thin);
  add("window_edge_on_1e-3", "sensor 1 mm in front of the window's plane, 1 m to its side: nearly edge-on", window_scene(),
      {-1, 1e-3, 1.2}, {1, 0, 0}, {{rect_y(0, 0, 2, 1, 2)}}, 1e-13, roundoff);
  // Tiny aperture far away, and a huge one very near.
  {
    const std::vector<Vec3> s{{0.3, 0.2, 1000}, {0.3, 0.201, 1000}, {0.301, 0.201, 1000}, {0.301, 0.2, 1000}};
    Scene scene;
    scene.apertures.push_back({polygon(s, "skylight"), 1.0});
    add("tiny_far_skylight", "1 mm square skylight 1 km above an upward sensor, slightly off its zenith: solid angle 1e-12 sr",
        scene, {0, 0, 0}, up, {{rvecs(s)}}, 1e-9, thin);
    // An occluder at half the height whose edge projects onto the middle of the skylight.
    const double edge = 0.15025;
    scene.occluders.push_back(polygon({{-10, -10, 500}, {edge, -10, 500}, {edge, 10, 500}, {-10, 10, 500}}, "half cover"));
    const Real cut = 2 * Real(edge);
    add("tiny_far_skylight_half_shadowed",
        "the same skylight with an occluder at 500 m whose edge projects onto its middle: a shadow edge placed to 1e-9 of the skylight",
        scene, {0, 0, 0}, up,
        {{{{cut, Real(0.2), 1000}, {cut, Real(0.201), 1000}, {Real(0.301), Real(0.201), 1000}, {Real(0.301), Real(0.2), 1000}}}},
        1e-9, thin);
  }
  {
    const std::vector<Vec3> s{{-700, -1000, 1e-3}, {-700, 1000, 1e-3}, {1300, 1000, 1e-3}, {1300, -1000, 1e-3}};
    Scene scene;
    scene.apertures.push_back({polygon(s, "ceiling"), 1.0});
    add("huge_near_ceiling", "2 km square opening 1 mm above an upward sensor, off centre: nearly the whole sky, arcs of length ~pi",
        scene, {0, 0, 0}, up, {{rvecs(s)}}, 1e-13, roundoff);
  }
  // Slivers.
  {
    Scene scene = window_scene();
    const double x0 = 1, x1 = 1 + 1e-9, y = -0.5;
    scene.occluders.push_back(polygon({{x0, y, -5}, {x1, y, -5}, {x1, y, 10}, {x0, y, 10}}, "sliver"));
    const Vec3 p{0.7, 2, 0.85};
    const RVec pl = rvec(p);
    const auto proj = [&](Real x) { return pl.x + (x - pl.x) * pl.y / (pl.y - Real(y)); };
    add("sliver_occluder", "a 1e-9 m wide vertical bar 0.5 m outside the window: its shadow is a strip 8e-10 m wide", scene, p,
        up, {{rect_y(0, 0, proj(x0), 1, 2)}, {rect_y(0, proj(x1), 2, 1, 2)}}, 1e-13, roundoff);
  }
  {
    const double z0 = 1.5, z1 = 1.5 + 1e-8;
    Scene scene;
    scene.apertures.push_back({polygon({{0, 0, z0}, {2, 0, z0}, {2, 0, z1}, {0, 0, z1}}, "slit"), 1.0});
    add("sliver_window", "a slit window 2 m by 1e-8 m", scene, {1, 2, 0.85}, up, {{rect_y(0, 0, 2, z0, z1)}}, 1e-9, thin);
  }
  // Degeneracies buildings are made of: coplanar walls, collinear edges, flush reveals.
  {
    Scene scene = window_scene();
    scene.occluders.push_back(wall_with_seam_hole(-3, 5));
    add("coplanar_wall_seam_hole", "a wall in the window's plane with the window cut out by a seam: hides nothing", scene,
        {-1, 0.5, 0.85}, up, {{rect_y(0, 0, 2, 1, 2)}}, 1e-13, roundoff);
  }
  {
    Scene scene = window_scene();
    scene.occluders.push_back(polygon({{0, 0, 1}, {1, 0, 1}, {1, 0, 2}, {0, 0, 2}}, "left half"));
    add("collinear_half_cover", "an occluder in the window's plane sharing three of its edges, covering its left half", scene,
        {0.7, 2.5, 0.85}, up, {{rect_y(0, 1, 2, 1, 2)}}, 1e-13, roundoff);
  }
  {
    Scene scene = window_scene();
    scene.occluders.push_back(polygon(window(), "shutter"));
    add("coplanar_shutter", "an occluder identical to the window, in its plane: hides all of it", scene, {1, 2, 0.85}, up, {}, 1e-15, zero);
  }
  add("tangent_plane_on_window_edge", "vertical sensor whose tangent plane x = 0 contains the window's left edge: n.u = 0 along it",
      window_scene(), {0, 1.5, 0.85}, {1, 0, 0}, {{rect_y(0, 0, 2, 1, 2)}}, 1e-13, roundoff);
  {
    // From (−6, 0.9) the outer edge of the right jamb (x = 2, y = −0.3) projects onto x = 0 in
    // decimals (s = 0.9/1.2 = 3/4): the opening closes to a line. In the input doubles 0.9/1.2 is
    // not 3/4, and the edge projects to x = 9.25e-17: a real sliver 0.71 m high stays visible
    // (~1e-18 %), which the exact modes keep.
    Scene scene = window_scene();
    for (auto& f : reveal(0.3)) scene.occluders.push_back(f);
    scene.occluders.push_back(wall_with_seam_hole(-3, 5));
    add("reveal_closes_view", "a sensor from which the far jamb's outer edge projects onto the window's near edge (in decimals): a 1e-18 % sliver in doubles",
        scene, {-6, 0.9, 0.85}, up, {}, 1e-15, zero);
  }
  {
    Scene scene = window_scene();
    for (auto& f : reveal(0.3)) scene.occluders.push_back(f);
    const Vec3 p{1, 1.2, 1};
    add("sensor_in_sill_plane", "a sensor in the plane of the sill (z = 1), which it sees edge-on: the horizon cuts where the sill does",
        scene, p, up, {reveal_visible(rvec(p), 0.3)}, 1e-13, roundoff);
  }
  for (const auto& [name, p] : {std::pair{"reveal_flush", Vec3{0.5, 1.5, 0.85}}, std::pair{"reveal_flush_horizon", Vec3{1, 0.6, 1.5}}}) {
    Scene scene = window_scene();
    for (auto& f : reveal(0.3)) scene.occluders.push_back(f);
    scene.occluders.push_back(wall_with_seam_hole(-3, 5));
    add(name, std::string("0.3 m reveal flush with the window's edges, and a coplanar wall with a seamed hole") +
                  (p.z > 1 ? "; the horizon cuts the window" : ""),
        scene, p, up, {reveal_visible(rvec(p), 0.3)}, 1e-13, roundoff);
  }
  {
    // The hall's rooflight: glazing at z = 6.7 over an opening x ∈ [2.8, 5.2], y ∈ [2.2, 3.8] in a
    // roof whose underside (z = 6) is tiled around it, reveals and kerb faces flush with it.
    const double x0 = 2.8, x1 = 5.2, y0 = 2.2, y1 = 3.8;
    Scene scene;
    scene.apertures.push_back({polygon({{x0, y0, 6.7}, {x1, y0, 6.7}, {x1, y1, 6.7}, {x0, y1, 6.7}}, "glazing"), 1.0});
    scene.occluders.push_back(polygon({{0, 0, 6}, {24, 0, 6}, {24, y0, 6}, {0, y0, 6}}, "tile south"));
    scene.occluders.push_back(polygon({{0, y1, 6}, {24, y1, 6}, {24, 12, 6}, {0, 12, 6}}, "tile north"));
    scene.occluders.push_back(polygon({{0, y0, 6}, {x0, y0, 6}, {x0, y1, 6}, {0, y1, 6}}, "tile west"));
    scene.occluders.push_back(polygon({{x1, y0, 6}, {24, y0, 6}, {24, y1, 6}, {x1, y1, 6}}, "tile east"));
    for (const auto& [lo, hi] : {std::pair{6.0, 6.4}, std::pair{6.4, 6.7}}) {
      scene.occluders.push_back(polygon({{x0, y0, lo}, {x0, y1, lo}, {x0, y1, hi}, {x0, y0, hi}}, "west face"));
      scene.occluders.push_back(polygon({{x1, y0, lo}, {x1, y0, hi}, {x1, y1, hi}, {x1, y1, lo}}, "east face"));
      scene.occluders.push_back(polygon({{x0, y0, lo}, {x0, y0, hi}, {x1, y0, hi}, {x1, y0, lo}}, "south face"));
      scene.occluders.push_back(polygon({{x0, y1, lo}, {x1, y1, lo}, {x1, y1, hi}, {x0, y1, hi}}, "north face"));
    }
    const Vec3 p{4.1, 3.1, 0.85};
    const RVec pl = rvec(p);
    const Real s = (Real(6.7) - pl.z) / (Real(6) - pl.z);
    const auto proj = [&](Real a, Real pa) { return pa + (a - pa) * s; };
    const Real u0 = std::max<Real>(x0, proj(x0, pl.x)), u1 = std::min<Real>(x1, proj(x1, pl.x));
    const Real v0 = std::max<Real>(y0, proj(y0, pl.y)), v1 = std::min<Real>(y1, proj(y1, pl.y));
    add("rooflight_kerb", "the hall's rooflight: reveals and kerb flush with the opening, tiled ceiling around it", scene, p, up,
        {{{{u0, v0, Real(6.7)}, {u1, v0, Real(6.7)}, {u1, v1, Real(6.7)}, {u0, v1, Real(6.7)}}}}, 1e-13, roundoff);
  }
  // Rotated and georeferenced copies of the reveal.
  {
    // Rotation by the Pythagorean angle (cos, sin) = (3/5, 4/5) and a move to (512345.5,
    // 5432109.25, 100): every local x and y is a multiple of 5/2^k, so every rotated and moved
    // coordinate is exactly representable and the scene daylit gets is exactly the local one
    // moved: the reference of the local frame holds to roundoff.
    const auto place = [](const Vec3& v) {
      return Vec3{3 * (v.x / 5) - 4 * (v.y / 5) + 512345.5, 4 * (v.x / 5) + 3 * (v.y / 5) + 5432109.25, v.z + 100};
    };
    const auto placed = [&](Polygon poly) {
      for (auto& v : poly.vertices) v = place(v);
      return poly;
    };
    const double width = 2.5, d = 0.3125;
    Scene scene;
    scene.apertures.push_back({placed(polygon(window(width), "window")), 1.0});
    for (auto& f : reveal(d, width)) scene.occluders.push_back(placed(f));
    scene.occluders.push_back(placed(wall_with_seam_hole(-3.75, 6.25, width)));
    int k = 0;
    for (const Vec3 p : {Vec3{0.625, 1.875, 0.875}, Vec3{1.25, 0.625, 1.5}, Vec3{3.75, 2.5, 0.5}}) {
      StiffCase c{"reveal_georef_exact_inputs_" + std::string(1, char('a' + k++)),
                  "a reveal rotated by atan(4/3) and moved to 5.4e6 m, every coordinate exactly representable",
                  scene,
                  sensor(place(p), up),
                  rvec(p),
                  {0, 0, 1},
                  {reveal_visible(rvec(p), d, width)},
                  1e-13,
                  "the inputs are exact and the clipping works relative to the sensor: roundoff only"};
      cases.push_back(std::move(c));
    }
  }
  {
    // Rotated by 0.7 rad and moved to (512345.678, 5432109.876, 123.4), as tests/geometry/test_visibility.cpp
    // does. Rounding the moved inputs (ulp(5.4e6) = 9.3e-10 m) moves every vertex, the sensor's
    // included, by up to 4.7e-10 m horizontally; the edges of the visible region (the window's, and
    // the outer opening's projected with s ≤ 1) move by at most 3 × 4.7e-10 m, each changing SC by
    // about that over the region's width (≥ 0.4 m here) relative: a few 1e-9 at most, bound 1e-8.
    const double c = std::cos(0.7), s = std::sin(0.7);
    const auto place = [&](const Vec3& v) { return Vec3{c * v.x - s * v.y + 512345.678, s * v.x + c * v.y + 5432109.876, v.z + 123.4}; };
    const auto placed = [&](Polygon poly) {
      for (auto& v : poly.vertices) v = place(v);
      return poly;
    };
    Scene scene;
    scene.apertures.push_back({placed(polygon(window(), "window")), 1.0});
    for (auto& f : reveal(0.3)) scene.occluders.push_back(placed(f));
    scene.occluders.push_back(placed(wall_with_seam_hole(-3, 5)));
    int k = 0;
    for (const Vec3 p : {Vec3{0.5, 1.5, 0.85}, Vec3{1, 0.6, 1.5}, Vec3{3, 2, 0.5}}) {
      StiffCase r{"reveal_georef_rotated_0.7_" + std::string(1, char('a' + k++)),
                  "the reveal rotated by 0.7 rad and moved to 5.4e6 m (inputs rounded there, as a georeferenced model's are)",
                  scene,
                  sensor(place(p), up),
                  rvec(p),
                  {0, 0, 1},
                  {reveal_visible(rvec(p), 0.3)},
                  1e-8,
                  "rounding the moved inputs (ulp 9.3e-10 m at 5.4e6 m) moves the region's edges by up to 1.4e-9 m: a few 1e-9 of SC"};
      cases.push_back(std::move(r));
    }
  }
  // Rotated and georeferenced copies of other cases, inputs rounded as in reveal_georef_rotated_0.7.
  // Rounding moves each vertex by up to 4.7e-10 m horizontally; a region of width L then moves by
  // ≲ 4 × 1.4e-9 m / L relative: 1e-8 for the metre-sized regions, 2e-5 for the half-millimetre one.
  {
    const double c = std::cos(0.7), s = std::sin(0.7);
    const auto place = [&](const Vec3& v) { return Vec3{c * v.x - s * v.y + 512345.678, s * v.x + c * v.y + 5432109.876, v.z + 123.4}; };
    const auto copy_of = [&](const std::string& name, double tolerance, const std::string& note) {
      const auto it = std::find_if(cases.begin(), cases.end(), [&](const StiffCase& k) { return k.name == name; });
      StiffCase k = *it;
      for (Polygon& poly : k.scene.occluders)
        for (Vec3& v : poly.vertices) v = place(v);
      for (Aperture& a : k.scene.apertures)
        for (Vec3& v : a.polygon.vertices) v = place(v);
      const Vec3 n = k.sensor.normal;
      k.sensor = {place(k.sensor.position), {c * n.x - s * n.y, s * n.x + c * n.y, n.z}};
      k.name += "_georef";
      k.description += "; rotated by 0.7 rad and moved to 5.4e6 m (inputs rounded)";
      k.tolerance = tolerance;
      k.tolerance_note = note;
      return k;
    };
    const std::string metre = "rounding the moved inputs moves the region's edges by up to 1.4e-9 m: ~1e-9 relative per edge";
    std::vector<StiffCase> copies{
        copy_of("collinear_half_cover", 1e-8, metre),
        copy_of("coplanar_shutter", 1e-15, "the shutter's and the window's vertices round alike: still exactly covered"),
        copy_of("rooflight_kerb", 1e-8, metre),
        copy_of("tangent_plane_halves_window", 1e-8, metre),
        copy_of("tiny_far_skylight_half_shadowed", 2e-5,
                "rounding moves the skylight's and the shadow's edges by up to 1.4e-9 m on a region 5e-4 m wide"),
    };
    for (auto& k : copies) cases.push_back(std::move(k));
  }
  // Glazing at grazing incidence: the transmittance polynomial where it matters most.
  {
    const TransmittancePolynomial fit = fit_glass_transmittance({{0.96, 0.96, 0.96}, 1.52});
    Scene scene;
    Aperture glass{polygon(window(), "glazing"), glass_transmittance({{0.96, 0.96, 0.96}, 1.52}, 1.0), fit.coefficients,
                   fit.max_error};
    scene.apertures.push_back(glass);
    VisiblePiece piece{rect_y(0, 0, 2, 1, 2)};
    piece.angular.assign(fit.coefficients.begin(), fit.coefficients.end());
    add("glazing_grazing", "clear glass (T(mu) a degree-12 polynomial) seen at 70-80 deg incidence by a vertical sensor", scene,
        {6, 0.8, 1.2}, {-1, 0, 0}, {piece}, 1e-13,
        "the polynomial's coefficients cancel in the sum of moments (measured 2e-15)");
  }
  return cases;
}

}  // namespace daylit::stiff
