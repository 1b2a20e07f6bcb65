#pragma once
// 3-vectors over a real type R (double, long double, or __float128 where the compiler has it), so
// that a kernel can be re-run in extended precision when its edge terms cancel (DESIGN.md §7).

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/vec3.hpp"

// DAYLIT_HAVE_FLOAT128 (1 or 0): whether the kernels have a __float128 rung. It comes from the
// build (CMake option DAYLIT_FLOAT128, which also links libquadmath), never from sniffing the
// compiler.
#ifndef DAYLIT_HAVE_FLOAT128
#error "DAYLIT_HAVE_FLOAT128 is set by the build (CMake option DAYLIT_FLOAT128)"
#endif
#if DAYLIT_HAVE_FLOAT128
#include <quadmath.h>
#endif

namespace daylit::real {

// Elementary functions over double, long double and __float128 under one name, for kernels
// templated on the precision.
using std::abs;
using std::atan2;
using std::atanh;
using std::cos;
using std::log;
using std::log1p;
using std::round;
using std::sin;
using std::sqrt;
#if DAYLIT_HAVE_FLOAT128
using quad = __float128;
inline quad abs(quad x) { return fabsq(x); }
inline quad atan2(quad y, quad x) { return atan2q(y, x); }
inline quad atanh(quad x) { return atanhq(x); }
inline quad cos(quad x) { return cosq(x); }
inline quad log(quad x) { return logq(x); }
inline quad log1p(quad x) { return log1pq(x); }
inline quad round(quad x) { return roundq(x); }
inline quad sin(quad x) { return sinq(x); }
inline quad sqrt(quad x) { return sqrtq(x); }
#endif

template <class R>
R pi() {
  return R(3.14159265358979323846264338327950288L);
}
#if DAYLIT_HAVE_FLOAT128
template <>
inline quad pi<quad>() {
  static const quad value = 4 * atanq(quad(1));  // M_PIq needs GNU literal suffixes
  return value;
}
#endif

// Unit roundoff u of R: 2^-53, 2^-64 (x87 long double) or 2^-113.
template <class R>
constexpr R unit_roundoff() {
  return std::numeric_limits<R>::epsilon() / 2;
}
#if DAYLIT_HAVE_FLOAT128
template <>
inline quad unit_roundoff<quad>() {
  return quad(0x1p-113L);  // exact: 2^-113 is a long double
}
#endif

// x^k for k ≥ 0 by binary powering: exact powers for the recurrences without a pow() shim for
// every precision; underflows to zero like the quantity it stands for.
template <class R>
R powi(R x, int k) {
  R result = 1;
  for (; k > 0; k >>= 1, x *= x)
    if (k & 1) result *= x;
  return result;
}

template <class R>
struct V3 {
  R x = 0, y = 0, z = 0;

  V3() = default;
  V3(R x_, R y_, R z_) : x(x_), y(y_), z(z_) {}
  explicit V3(const Vec3& v) : x(v.x), y(v.y), z(v.z) {}
};

template <class R> V3<R> operator+(const V3<R>& a, const V3<R>& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class R> V3<R> operator-(const V3<R>& a, const V3<R>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class R> V3<R> operator*(R s, const V3<R>& a) { return {s * a.x, s * a.y, s * a.z}; }
template <class R> V3<R> operator/(const V3<R>& a, R s) { return {a.x / s, a.y / s, a.z / s}; }
template <class R> R dot(const V3<R>& a, const V3<R>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class R> V3<R> cross(const V3<R>& a, const V3<R>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Length, scaled against overflow and underflow (std::hypot has no __float128 overload).
template <class R> R norm(const V3<R>& a) {
  const R m = std::max({abs(a.x), abs(a.y), abs(a.z)});
  if (!(m > 0)) return R(0);
  const V3<R> s = a / m;
  return m * sqrt(dot(s, s));
}

// v/|v| formed in R from a double vector (non-zero).
template <class R>
V3<R> unit(const Vec3& v) {
  const V3<R> r(v);
  return r / norm(r);
}

}  // namespace daylit::real
