#pragma once
// Sky luminance models that are polynomials in the direction u, so that their sky components are
// closed forms over the exact visible regions.

#include <string>
#include <string_view>
#include <vector>

#include "geometry/spherical_region.hpp"

namespace daylit {

enum class SkyModel {
  cie_overcast,  // Moon–Spencer: L(u) = L_z (1 + 2 u_z)/3, the "16th" sky of ISO 15469:2004 / CIE S 011/E:2003
  uniform,       // L(u) = L
};

// A sky named on the command line: "uniform", "cie-overcast", "cie-1" … "cie-15" (the CIE
// standard general skies of ISO 15469, sky/cie_sky.hpp, which need the sun's position), or "perez"
// (the Perez all-weather sky, sky/perez_sky.hpp, which needs an hour's weather and the sun).
struct SkyName {
  enum class Kind { uniform, cie_overcast, cie_general, perez };
  Kind kind = Kind::cie_overcast;
  int cie_type = 0;  // 1..15 for cie_general
};
// The one parser of sky names; throws daylit::Error naming the choices for anything else.
SkyName parse_sky_name(std::string_view name);

// Parses "cie-overcast" or "uniform" (the polynomial skies of this header); throws daylit::Error
// otherwise, saying that a general sky needs `daylit illuminance`.
SkyModel parse_sky_model(std::string_view name);
std::string_view sky_model_name(SkyModel sky) noexcept;

// Illuminance (per unit zenith luminance L_z for the overcast sky, per unit luminance for the
// uniform sky) on a receiver with unit normal n from the sky seen in `region`. The region must lie
// above the horizon and in front of the receiver (as returned by the visibility routine).
// Overcast: E/L_z = (1/3) [∫_A (n·u) dσ + 2 ∫_A (z·u)(n·u) dσ] (DESIGN.md §3), exact: a Lambert
// term and one double-axis moment of order 1 (Arvo 1995, eq. 14). Uniform: E/L = ∫_A (n·u) dσ.
double sky_irradiance(const SphericalRegion& region, const Vec3& n, SkyModel sky);

// The same through glazing of transmittance T(μ) = Σ_k c_k μ^k, μ = a·u the cosine of incidence
// on a pane with unit normal a (either side: it is turned to face the region). Every term is a
// closed form: uniform, Σ c_k ∫ (a·u)^k (n·u) dσ (double-axis moments, Arvo eq. 14); overcast,
// (1/3) Σ c_k [∫ (a·u)^k (n·u) dσ + 2 ∫ (a·u)^k (z·u)(n·u) dσ], the second of pattern (k, 1, 1)
// (Chen and Arvo 2000, eq. 29), all orders in one pass (polynomial_cosine_moments, moments.hpp).
double sky_irradiance_through_glazing(const SphericalRegion& region, const Vec3& n, SkyModel sky, Vec3 a,
                                      const std::vector<double>& c);

// The luminance of direction u in the same units: (1 + 2 u_z)/3 overcast, 1 uniform (for the
// integrands that are not closed forms: sky_quadrature.hpp).
double sky_relative_luminance(SkyModel sky, const Vec3& u) noexcept;

// Unobstructed horizontal illuminance in the same units: 7π/9 for the overcast sky, π for the
// uniform sky (SKY.md).
double unobstructed_horizontal_irradiance(SkyModel sky) noexcept;

}  // namespace daylit
