#pragma once
// Illuminance (lux) on sensor grids from a sky and the sun at one moment: what `daylit
// illuminance` computes. The sky is integrated over the exact visible region of every aperture
// (closed forms where the luminance is a polynomial in the direction, else the CIE fit's closed
// forms or adaptive cubature); the sun is Snyder's sub-hemispherical source, a uniform disk cut
// exactly by the same regions (cap_clip.hpp).

#include <numbers>
#include <optional>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "sky/cie_sky.hpp"
#include "sky/perez_sky.hpp"
#include "simulation/sky_component.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

// The sun's apparent angular radius: 0.533° across (the disk; the true value varies by
// ±1.7 % over the year with the Earth–sun distance, which scales the radiance, not E_dn).
inline constexpr double kSunHalfAngleDeg = 0.2665;

// The sky's luminance distribution and scale, and the sun.
struct DaylightConditions {
  enum class Sky { uniform, cie_overcast, cie_general, perez };
  enum class Method { fit, quadrature };  // for cie_general skies
  Sky sky = Sky::cie_overcast;
  std::optional<CieSky> cie;      // cie_general: the type and the sun it is drawn for
  std::optional<CieSkyFit> fit;   // cie_general with Method::fit
  std::optional<PerezSky> perez;  // perez: the hour's sky (always by cubature, at quadrature_tolerance)
  Method method = Method::quadrature;
  double quadrature_tolerance = 1e-9;  // relative, per region (spherical_quadrature.hpp)
  double zenith_luminance = 0;         // L_z, cd/m² (the uniform sky's luminance)
  // The sun: unit vector in the model frame, and its direct normal illuminance (lux); no sun when
  // direct_normal is 0 or the sun is at or below the horizon.
  Vec3 sun{0, 0, 1};
  double direct_normal = 0;
  double sun_half_angle = kSunHalfAngleDeg * std::numbers::pi / 180;

  bool has_sun() const noexcept { return direct_normal > 0 && sun.z > 0; }
};

// E_out / L_z: the unobstructed horizontal illuminance of the sky per unit zenith luminance. The
// overcast and uniform skies in closed form (7π/9, π); a CIE general sky by adaptive cubature of
// its luminance over the hemisphere to 1e-12 (computed, not looked up); the Perez sky's own
// normalisation (the same cubature, done once when the PerezSky is built).
double unobstructed_sky_irradiance(const DaylightConditions& conditions);

// The illuminance (lux) on a receiver with unit normal n from the sky and the sun seen in `region`
// (above the horizon) through `aperture` (its transmittance, glass T(μ) included) or, where
// `aperture` is nullptr, directly: what the reflected components' first bounce needs from these
// conditions (simulation/reflected_components.hpp, ReflectionOptions::light). The sky's
// cubature error, where it has one, is not returned.
double daylight_irradiance(const DaylightConditions& conditions, const Aperture* aperture, const SphericalRegion& region,
                           const Vec3& n);

// The unobstructed horizontal illuminance (lux) of the sky and the sun together: what sets the far
// ground's luminance ρ_g·E/π (as gensky's ground glow, which includes the sun).
double unobstructed_daylight_lux(const DaylightConditions& conditions);

struct IlluminanceResult {
  std::vector<double> sky_lux, sun_lux;  // per sensor, in grid order
  // Per sensor, a bound on |computed − true| sky illuminance: 0 for the overcast and uniform skies
  // (their closed forms are exact to roundoff); the fit's maximum error times L_z times Σ τ·∫(n·u)
  // for the CIE fit; the cubature's error estimate for the quadrature path.
  std::vector<double> sky_error_lux;
  VisibilityCounters counters;
  long quadrature_evaluations = 0;
  std::size_t regions_by_quadrature = 0;  // glazed regions under CIE general skies (see below)
};

// Sky (and sun) illuminance at every sensor, in parallel as sky_component does.
// Through glass (T(μ) a polynomial in the cosine of incidence): the overcast and uniform skies in
// closed form (sky_irradiance_through_glazing); CIE general skies by adaptive cubature of L·T
// whatever the method, because the fit's terms times T's powers are moments about three axes,
// which have no closed form here. The sun through glass takes T at the sun's centre: over a disk
// of radius ρ = 4.65 mrad the cosine of incidence changes by at most ρ, and T by at most
// ρ·max|T'| (the summary states it).
// `direct`: the sky box's engine (geometry/sky_box.hpp); where the grid sees the sky directly
// (SensorGrid::sees_sky_directly), the sky and sun seen past every surface are added, exactly.
IlluminanceResult illuminance(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid,
                              const DaylightConditions& conditions, const ProgressCallback& progress = {},
                              const VisibilityEngine* direct = nullptr);

}  // namespace daylit
