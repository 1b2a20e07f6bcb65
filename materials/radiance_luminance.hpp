#pragma once
// Radiance's grey value of a colour: the luminance weights of its default RGB primaries, as
// Radiance's `bright()` (src/common/color.h, CIE_rf/CIE_gf/CIE_bf) applies them to reflectances and
// transmittances alike. One definition for every material of materials/.

namespace daylit {

inline constexpr double kRadianceLuminanceWeights[3] = {0.265, 0.670, 0.065};

// The luminance-weighted grey value of (r, g, b); exact for grey colours up to rounding.
constexpr double radiance_luminance(double r, double g, double b) noexcept {
  return kRadianceLuminanceWeights[0] * r + kRadianceLuminanceWeights[1] * g + kRadianceLuminanceWeights[2] * b;
}

}  // namespace daylit
