#pragma once
// The precision ladder of the kernels (DESIGN.md §9, "Cancellation no rewrite removes"): a kernel
// templated on its real type runs in double, then long double, then __float128, until its own
// estimate of its relative error meets the tolerance. The result, its estimate and the precision
// that produced it come back by value.

#include <algorithm>
#include <array>
#include <vector>

#include <limits>

#include "illumination/real_vector.hpp"  // DAYLIT_HAVE_FLOAT128
#include "illumination/tracked_sum.hpp"

namespace daylit {

// The rungs of the ladder, as the int the results carry: 0 double, 1 long double, 2 __float128.
enum Precision : int { double_precision = 0, long_double_precision = 1, float128_precision = 2 };

inline const char* precision_name(int p) noexcept {
  return p == double_precision ? "double" : p == long_double_precision ? "long double" : "float128";
}

// One attempt of a kernel in some precision: its result rounded to double (a number, or an array
// or vector of them) and its own estimate of the relative error; `condition` is the κ it measured
// where it has one (tracked_sum.hpp).
template <class V>
struct Attempt {
  V value;
  double relative_error;
  double condition = 1;
  // Its estimate of the absolute error, where a caller may accept that instead (escalate's
  // absolute_tolerance); +∞ where the kernel has none.
  double absolute_error = std::numeric_limits<double>::infinity();
};

// What escalate() returns: the first attempt whose estimate met the tolerance (or the last rung's),
// the precision that gave it, and the κ of the first attempt, which says how much the kernel
// amplifies rounding whatever precision settled it.
template <class V>
struct Escalated {
  V value;
  double relative_error;
  int precision;
  double condition;
};

// Calls attempt(R{}) for R = double (unless `first` is higher), long double, __float128, and
// returns the first whose relative_error ≤ tolerance, or whose absolute_error ≤
// absolute_tolerance where that is positive (a result that is small beside what the caller adds
// it to needs no relative accuracy: radiosity's transport, where an element's share of a
// receiver's irradiance matters only to a fraction of the total); the last rung's result
// otherwise (its estimate then says how far it is from the tolerance). `attempt` may keep state
// between calls (a later rung may tighten what it asks of itself from what an earlier one measured).
template <class F>
auto escalate(F&& attempt, double tolerance, int first = double_precision, double absolute_tolerance = 0)
    -> Escalated<decltype(attempt(double{}).value)> {
  using V = decltype(attempt(double{}).value);
  bool have_condition = false;
  double first_condition = 1;
  auto take = [&](const auto& a, int precision) {
    if (!have_condition) first_condition = a.condition, have_condition = true;
    return Escalated<V>{a.value, a.relative_error, precision, first_condition};
  };
  if (first <= double_precision) {
    const auto d = attempt(double{});
    const auto r = take(d, double_precision);
    if (d.relative_error <= tolerance || (absolute_tolerance > 0 && d.absolute_error <= absolute_tolerance)) return r;
  }
  const auto l = attempt((long double)0);
#if DAYLIT_HAVE_FLOAT128
  const auto r = take(l, long_double_precision);
  if (l.relative_error <= tolerance || (absolute_tolerance > 0 && l.absolute_error <= absolute_tolerance)) return r;
  return take(attempt(real::quad(0)), float128_precision);
#else
  return take(l, long_double_precision);
#endif
}

// ---- Tracked results ------------------------------------------------------------------------
// A kernel's result as a tracked sum, or an array or vector of them; its κ (the largest of the
// elements'), and the same rounded to double.

template <class R>
double tracked_condition(const real::Tracked<R>& s) {
  return double(real::condition(s));
}
template <class Container>
double tracked_condition(const Container& sums) {
  double k = 1;  // no element cancels below 1 (tracked_sum.hpp)
  for (const auto& s : sums) k = std::max(k, tracked_condition(s));
  return k;
}

template <class R>
double tracked_magnitude(const real::Tracked<R>& s) {
  return double(s.magnitude);
}
template <class Container>
double tracked_magnitude(const Container& sums) {
  double m = 0;
  for (const auto& s : sums) m = std::max(m, tracked_magnitude(s));
  return m;
}

template <class R>
double to_double(const real::Tracked<R>& s) {
  return double(s.value);
}
template <class R>
std::vector<double> to_double(const std::vector<real::Tracked<R>>& sums) {
  std::vector<double> out;
  out.reserve(sums.size());
  for (const auto& s : sums) out.push_back(double(s.value));
  return out;
}
template <class R, std::size_t N>
std::array<double, N> to_double(const std::array<real::Tracked<R>, N>& sums) {
  std::array<double, N> out;
  for (std::size_t i = 0; i < N; ++i) out[i] = double(sums[i].value);
  return out;
}

// escalate() for kernels whose compute(R{}) returns tracked sums, with the estimate
// (10 + order)·u·κ (u the unit roundoff of R). The order enters because the terms of an order-n
// moment carry n-th powers, whose rounding is n·u relative: a 1e-4 rad luminaire at n = 1000 has
// κ ≈ 60 and an error of 1e-11 in double, 1e-16 in long double. The absolute estimate is
// (10 + order)·u·Σ|terms| (the largest element's, for several sums).
template <class F>
auto escalate_tracked(int order, F&& compute, double tolerance = 1e-13, double absolute_tolerance = 0) {
  return escalate(
      [&](auto zero) {
        using R = decltype(zero);
        const auto sums = compute(zero);
        const double kappa = tracked_condition(sums);
        const double u = double(real::unit_roundoff<R>());
        return Attempt<decltype(to_double(sums))>{to_double(sums), (10.0 + order) * u * kappa, kappa,
                                                  (10.0 + order) * u * tracked_magnitude(sums)};
      },
      tolerance, double_precision, absolute_tolerance);
}

}  // namespace daylit
