#pragma once
// Checks of numeric options. CLI11's Range, PositiveNumber and NonNegativeNumber let "nan" through
// (every comparison with NaN is false: `--reflection-tolerance nan` ran with no tolerance met or
// refused) and word a refusal with DBL_MAX written out in 309 digits. These refuse anything but a
// finite number in the range, and say which range in a line.

#include <cmath>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace daylit::cli {

// A finite number in [least, most] (an open end where `strict_least`: (least, most]).
inline CLI::Validator number_in(double least, double most, bool strict_least = false) {
  const std::string range = strict_least && most == std::numeric_limits<double>::max() ? fmt::format("> {}", least)
                            : most == std::numeric_limits<double>::max()              ? fmt::format(">= {}", least)
                                                                                      : fmt::format("in [{}, {}]", least, most);
  return CLI::Validator(
      [=](std::string& input) -> std::string {
        double v = 0;
        const bool number = CLI::detail::lexical_cast(input, v);
        if (number && std::isfinite(v) && (strict_least ? v > least : v >= least) && v <= most) return {};
        return fmt::format("{} is not a finite number {}", input, range);
      },
      range);
}

inline CLI::Validator positive_number() { return number_in(0, std::numeric_limits<double>::max(), true); }
inline CLI::Validator non_negative_number() { return number_in(0, std::numeric_limits<double>::max()); }

}  // namespace daylit::cli
