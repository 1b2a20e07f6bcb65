#pragma once
// Signs of the predicates the visibility routine decides on input coordinates (internal to
// geometry/). ExactSigns answers exactly: CGAL's filtered orientation, or interval arithmetic
// with an exact rational fallback for the expressions that are not kernel predicates. FloatSigns
// answers the same questions in plain double, for the float path that daylit keeps for comparison.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <cmath>

#include "geometry/vec3.hpp"

namespace daylit::predicates {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

inline Epick::Point_3 point3(const Vec3& v) { return {v.x, v.y, v.z}; }
inline Epick::Point_2 drop(const Vec3& v, int k) { return {v[(k + 1) % 3], v[(k + 2) % 3]}; }

inline int sign_of(double x) { return (x > 0) - (x < 0); }

// Interval arithmetic first; exact arithmetic only when the interval contains zero. This is the
// filter of CGAL's Filtered_predicate, written out for expressions that are not kernel predicates.
// The expressions are polynomials in the input doubles (sums, differences and products only), so
// CGAL's exact multiprecision floats (Mpzf, which CGAL's own predicates fall back to) evaluate
// them exactly, without the gcds that rationals spend their time in. The fallback is taken for
// exact zeros, the degeneracies buildings are made of.
template <class Expr>
int filtered_sign_given(const CGAL::Interval_nt<false>& r, const Expr& expr);

template <class Expr>
int filtered_sign(const Expr& expr) {
  CGAL::Interval_nt<false> r;
  {
    CGAL::Protect_FPU_rounding<true> guard;
    r = expr(CGAL::Interval_nt<false>(0));
  }
  return filtered_sign_given(r, expr);
}

// filtered_sign(expr) where the caller has already evaluated expr in intervals, r, by the same
// operations under Protect_FPU_rounding<true> (from parts it keeps: shadow_clipping.hpp's
// vertices), and called this after that guard's scope: the same decision filtered_sign makes.
template <class Expr>
int filtered_sign_given(const CGAL::Interval_nt<false>& r, const Expr& expr) {
  if (r.inf() > 0) return 1;
  if (r.sup() < 0) return -1;
  if (r.inf() == 0 && r.sup() == 0) return 0;
  return int(CGAL::sign(expr(CGAL::Mpzf(0))));
}

// n·(v − p)
template <class T>
T dot_diff(const Vec3& n, const Vec3& v, const Vec3& p) {
  return T(n.x) * (T(v.x) - T(p.x)) + T(n.y) * (T(v.y) - T(p.y)) + T(n.z) * (T(v.z) - T(p.z));
}

// ((a − o) × (b − o)) · (v − p)
template <class T>
T normal_dot_diff(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& v, const Vec3& p) {
  const T ax = T(a.x) - T(o.x), ay = T(a.y) - T(o.y), az = T(a.z) - T(o.z);
  const T bx = T(b.x) - T(o.x), by = T(b.y) - T(o.y), bz = T(b.z) - T(o.z);
  return (ay * bz - az * by) * (T(v.x) - T(p.x)) + (az * bx - ax * bz) * (T(v.y) - T(p.y)) +
         (ax * by - ay * bx) * (T(v.z) - T(p.z));
}

struct ExactSigns {
  // sign det[a − p, b − p, c − p]. Two equal points make it exactly 0: buildings share vertices
  // (a reveal's faces end on the window's corners), and CGAL's filter cannot certify a zero, so
  // without this test each such call is decided in multiprecision (Mpzf): 9 % of `daylit df` on
  // the office before it was added.
  // Then Shewchuk's static filter inline (orient3d's error bound, (7 + 56u)u times the
  // permanent, taken as 8u; the differences rounded in double are part of what it covers), and
  // CGAL's filtered predicate where it cannot decide: the culling's most frequent question.
  static int orient3(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    if (c == a || c == b || c == p || a == b || a == p || b == p) return 0;
    const double ax = a.x - p.x, ay = a.y - p.y, az = a.z - p.z, bx = b.x - p.x, by = b.y - p.y, bz = b.z - p.z;
    const double cx = c.x - p.x, cy = c.y - p.y, cz = c.z - p.z;
    const double value = ax * (by * cz - bz * cy) + bx * (cy * az - cz * ay) + cx * (ay * bz - az * by);
    const double permanent = (std::abs(by * cz) + std::abs(bz * cy)) * std::abs(ax) +
                             (std::abs(cy * az) + std::abs(cz * ay)) * std::abs(bx) +
                             (std::abs(ay * bz) + std::abs(az * by)) * std::abs(cx);
    if (permanent > 0x1p-900 && std::abs(value) > 8 * 0x1p-53 * permanent) return sign_of(value);
    return int(CGAL::orientation(point3(p), point3(a), point3(b), point3(c)));
  }
  // orientation of (a, b, c) in the coordinates that drop axis k
  static int orient2(const Vec3& a, const Vec3& b, const Vec3& c, int k) {
    return int(CGAL::orientation(drop(a, k), drop(b, k), drop(c, k)));
  }
  // The culling asks these of every vertex of every occluder near the view, most far from zero:
  // a static filter first (Shewchuk's, as CGAL's own predicates have), double arithmetic with an
  // a priori bound on its error, then the interval filter, then exact arithmetic. Both bounds
  // come from the rounding of each operation, relative to the magnitudes of the terms as
  // computed: n·(v − p) rounds 4 times on its way (difference, product, two sums), so its error
  // is below 4.0001 u Σ|n_i||v_i − p_i|; ((a − o) × (b − o))·(v − p) rounds 7 times (differences,
  // products and difference in the cross product, then difference, product and sums), below
  // 7.0001 u Σ K_i |v_i − p_i| with K_x = |a_y − o_y||b_z − o_z| + |a_z − o_z||b_y − o_y| and so on.
  // The tests take twice that, and only where the magnitude is far from underflow (2^-900).
  // The same signs as before, so the same results: in the 665-polygon bench scene the intervals
  // had been a quarter of the run.
  static int dot_diff(const Vec3& n, const Vec3& v, const Vec3& p) {
    const double dx = v.x - p.x, dy = v.y - p.y, dz = v.z - p.z;
    const double value = n.x * dx + n.y * dy + n.z * dz;
    const double magnitude = std::abs(n.x) * std::abs(dx) + std::abs(n.y) * std::abs(dy) + std::abs(n.z) * std::abs(dz);
    if (magnitude > 0x1p-900 && std::abs(value) > 8 * 0x1p-53 * magnitude) return sign_of(value);
    return filtered_sign([&](auto zero) { return predicates::dot_diff<decltype(zero)>(n, v, p); });
  }
  static int normal_dot_diff(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& v, const Vec3& p) {
    const double ax = a.x - o.x, ay = a.y - o.y, az = a.z - o.z, bx = b.x - o.x, by = b.y - o.y, bz = b.z - o.z;
    const double dx = v.x - p.x, dy = v.y - p.y, dz = v.z - p.z;
    const double value = (ay * bz - az * by) * dx + (az * bx - ax * bz) * dy + (ax * by - ay * bx) * dz;
    const double magnitude = (std::abs(ay * bz) + std::abs(az * by)) * std::abs(dx) +
                             (std::abs(az * bx) + std::abs(ax * bz)) * std::abs(dy) +
                             (std::abs(ax * by) + std::abs(ay * bx)) * std::abs(dz);
    if (magnitude > 0x1p-900 && std::abs(value) > 16 * 0x1p-53 * magnitude) return sign_of(value);
    return filtered_sign([&](auto zero) { return predicates::normal_dot_diff<decltype(zero)>(o, a, b, v, p); });
  }
};

struct FloatSigns {
  static int orient3(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    return sign_of(dot(cross(a - p, b - p), c - p));
  }
  static int orient2(const Vec3& a, const Vec3& b, const Vec3& c, int k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    return sign_of((b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i]));
  }
  static int dot_diff(const Vec3& n, const Vec3& v, const Vec3& p) { return sign_of(predicates::dot_diff<double>(n, v, p)); }
  static int normal_dot_diff(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& v, const Vec3& p) {
    return sign_of(predicates::normal_dot_diff<double>(o, a, b, v, p));
  }
};

}  // namespace daylit::predicates
