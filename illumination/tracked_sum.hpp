#pragma once
// A sum that carries the sum of the absolute values of its terms, so that the cancellation in it
// can be measured (DESIGN.md §9, "Cancellation no rewrite removes"): every kernel that escalates
// its precision (precision_escalation.hpp) builds its result from these.
//
// Rounding: for a sum of n terms formed in a precision of unit roundoff u, |fl(Σ t) − Σ t| ≤
// ~n·u·Σ|t| whatever cancelled on the way (Higham, "Accuracy and stability of numerical
// algorithms", 2nd ed., §4.2), so the relative error of the value is about u·κ with the condition
// number κ = Σ|t| / |Σ t|. Rounding is monotone, so the magnitude formed here never falls below
// |value| and κ ≥ 1 for every sum of tracked terms.

#include <limits>
#include <type_traits>

#include "illumination/real_vector.hpp"

namespace daylit::real {

// value = Σ t_i and magnitude = Σ |t_i| (or a bound on it that the caller knows better), over
// terms in precision R. T is R, or V3<R> for a vector-valued sum whose magnitude is a scalar
// bound on Σ |t_i| (Euclidean norms).
template <class R, class T = R>
struct Tracked {
  T value{};
  R magnitude = 0;

  // A term whose own rounding is a few ulp of itself: magnitude |term|.
  void add(R term)
    requires std::is_same_v<T, R>
  {
    value += term;
    magnitude += abs(term);
  }
  // A term that is itself the result of a cancelling computation, with the magnitude of its terms.
  void add(const T& term, R term_magnitude) {
    value = value + term;
    magnitude += term_magnitude;
  }
  Tracked& operator+=(const Tracked& o) {
    value = value + o.value;
    magnitude += o.magnitude;
    return *this;
  }
  Tracked& operator-=(const Tracked& o) {
    value = value - o.value;
    magnitude += o.magnitude;
    return *this;
  }
};

template <class R, class T>
Tracked<R, T> operator+(Tracked<R, T> a, const Tracked<R, T>& b) {
  return a += b;
}
template <class R, class T>
Tracked<R, T> operator-(Tracked<R, T> a, const Tracked<R, T>& b) {
  return a -= b;
}
// Scaling by a number known to a few ulp: the magnitudes scale by its absolute value.
template <class R, class T>
Tracked<R, T> operator*(R s, const Tracked<R, T>& a) {
  return {s * a.value, abs(s) * a.magnitude};
}
template <class R, class T>
Tracked<R, T> operator/(const Tracked<R, T>& a, R s) {
  return {a.value / s, a.magnitude / abs(s)};
}

// A value computed without cancellation (to a few ulp of itself).
template <class R>
Tracked<R> exact(R v) {
  return {v, abs(v)};
}

// The condition number κ = magnitude / |value|, in R. The one convention at zero: an exact zero
// made of zeros (magnitude 0) has κ = 1, no cancellation; a zero made of non-zero terms has
// κ = +∞ (every digit cancelled).
template <class R>
R condition(const Tracked<R>& s) {
  if (s.magnitude == 0) return R(1);
  if (s.value == 0) return R(std::numeric_limits<double>::infinity());
  return s.magnitude / abs(s.value);
}
template <class R>
R condition(const Tracked<R, V3<R>>& s) {
  if (s.magnitude == 0) return R(1);
  const R size = norm(s.value);
  if (size == 0) return R(std::numeric_limits<double>::infinity());
  return s.magnitude / size;
}

}  // namespace daylit::real
