#include "illumination/factor_moment.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/error.hpp"
#include "illumination/moments.hpp"
#include "illumination/solid_angle.hpp"

namespace daylit {

FactorMoment factor_moment(const SphericalRegion& region, std::vector<Factor> factors) {
  std::erase_if(factors, [](const Factor& f) { return f.power == 0; });
  std::sort(factors.begin(), factors.end(), [](const Factor& a, const Factor& b) { return a.power > b.power; });
  for (const Factor& f : factors)
    if (!(norm(f.axis) > 0) || !is_finite(f.axis)) throw Error("a factor axis must be a finite non-zero vector");

  // The kernels normalise the axes themselves, in the precision they compute in, and raise |a|
  // to the power from |a|² in long double (moments.cpp).
  Escalated<double> m{};
  if (factors.empty()) {
    return {solid_angle(region), 1e-15};
  } else if (factors.size() == 1) {
    m = axial_moment_with_accuracy(region, factors[0].axis, factors[0].power);
  } else if (factors.size() == 2 && factors[1].power == 1) {
    m = double_axis_moment_with_accuracy(region, factors[0].axis, factors[1].axis, factors[0].power);
  } else if (factors.size() == 3 && factors[1].power == 1 && factors[2].power == 1) {
    m = triple_axis_moment_with_accuracy(region, factors[0].axis, factors[1].axis, factors[2].axis, factors[0].power);
  } else {
    std::string pattern;
    for (const Factor& f : factors) {
      if (!pattern.empty()) pattern += ',';
      pattern += std::to_string(f.power);
    }
    throw Error("factor pattern (" + pattern + ") is not supported; supported: (), (n), (n,1), (n,1,1)");
  }
  if (!std::isfinite(m.value)) throw Error("the factors' lengths raised to their powers overflow double");
  return {m.value, m.relative_error};
}

}  // namespace daylit
