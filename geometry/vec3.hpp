#pragma once
// Plain double-precision 3-vectors: the currency between geometry/, illumination/ and sky/.
// No CGAL here on purpose (DESIGN.md §1): the kernels compile fast and stay portable.

#include <cmath>

namespace daylit {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr double operator[](int i) const noexcept { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3& operator+=(const Vec3& o) noexcept { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr Vec3& operator-=(const Vec3& o) noexcept { x -= o.x; y -= o.y; z -= o.z; return *this; }
  constexpr Vec3& operator*=(double s) noexcept { x *= s; y *= s; z *= s; return *this; }
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

constexpr Vec3 operator+(Vec3 a, const Vec3& b) noexcept { return a += b; }
constexpr Vec3 operator-(Vec3 a, const Vec3& b) noexcept { return a -= b; }
constexpr Vec3 operator-(const Vec3& a) noexcept { return {-a.x, -a.y, -a.z}; }
constexpr Vec3 operator*(Vec3 a, double s) noexcept { return a *= s; }
constexpr Vec3 operator*(double s, Vec3 a) noexcept { return a *= s; }
constexpr Vec3 operator/(const Vec3& a, double s) noexcept { return {a.x / s, a.y / s, a.z / s}; }

constexpr double dot(const Vec3& a, const Vec3& b) noexcept { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) noexcept {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Euclidean length without overflow or underflow for any finite vector.
inline double norm(const Vec3& a) noexcept { return std::hypot(a.x, a.y, a.z); }
inline Vec3 normalized(const Vec3& a) noexcept { return a / norm(a); }
// The angle between two directions, accurate near 0 and π (where acos of the cosine is not).
inline double angle_between(const Vec3& a, const Vec3& b) noexcept { return std::atan2(norm(cross(a, b)), dot(a, b)); }
inline bool is_finite(const Vec3& a) noexcept {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

}  // namespace daylit
