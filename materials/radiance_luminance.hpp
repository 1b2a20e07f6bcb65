#pragma once
// Radiance's grey value of a colour: the luminance weights of its default RGB primaries, as
// Radiance's `bright()` (src/common/color.h, CIE_rf/CIE_gf/CIE_bf) applies them to reflectances and
// transmittances alike. One definition for every material of materials/.

namespace daylit {

inline constexpr double kRadianceLuminanceWeights[3] = {0.265, 0.670, 0.065};

// The luminance-weighted grey value of (r, g, b). The weights sum to 1, so a grey colour's value
// is the grey itself, returned as given rather than rounded through three products (0.6 would
// come out an ulp off: an OBJ aperture's trans T T T 0 0 1 1 must pass T exactly).
constexpr double radiance_luminance(double r, double g, double b) noexcept {
  if (r == g && g == b) return r;
  return kRadianceLuminanceWeights[0] * r + kRadianceLuminanceWeights[1] * g + kRadianceLuminanceWeights[2] * b;
}

}  // namespace daylit
