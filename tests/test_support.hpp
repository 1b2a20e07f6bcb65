#pragma once
// Small helpers shared by the tests.

#include <cmath>

namespace daylit::test {

// |value − reference| / |reference|, formed in long double (exact for the difference of a double
// result and its reference); |value| itself where the reference is 0, so that a zero reference
// asks for an absolute error.
inline double relative_error(long double value, long double reference) {
  if (reference == 0) return double(std::abs(value));
  return double(std::abs((value - reference) / reference));
}

}  // namespace daylit::test
