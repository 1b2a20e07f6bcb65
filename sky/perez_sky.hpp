#pragma once
// The Perez all-weather sky (Perez, Seals and Michalsky, "All-weather model for sky luminance
// distribution — preliminary configuration and validation", Solar Energy 50(3), 235–245, 1993),
// its sky condition from irradiances (Perez, Ineichen, Seals, Michalsky and Stewart, "Modeling
// daylight availability and irradiance components from direct and global irradiance", Solar
// Energy 44(5), 271–289, 1990) and its normalisation to the hour's diffuse horizontal
// illuminance, computed by adaptive cubature to 1e-12 (not Radiance's sum over 145 directions).
//
// Frame: x east, y north, z up (or the model frame: only the sun's direction matters); θ the
// zenith angle of a direction u (cos θ = u_z), γ its angle from the sun s, Z the sun's zenith angle.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/spherical_region.hpp"
#include "illumination/spherical_quadrature.hpp"

namespace daylit {

// Which departures from the published model are applied.
//  none:     the published model (1993 eqs. 1, 6–8 with Table 1; 1990 eqs. 1, 2, 7, 8), nothing
//            else. An hour whose luminance is negative somewhere in the sky, or diverges at the
//            horizon (b > 0), has no meaning as a luminance and is refused (perez_sky throws).
//  radiance: what Radiance's gendaylit / perezlum.cal / gendaymtx do, each on its own line so
//            that differences can be attributed (read in gendaylit.c of NREL/Radiance at commit
//            633b768, perezlum.cal 1.1 and gendaymtx.c 2.5; facts only, no code):
//            1. the sun's altitude is capped at 87° for the sky ("keeps the circumsolar region
//               off the zenith"; gendaylit and gendaymtx; the sun's disk itself is not moved here);
//            2. Δ is raised to 0.2 when 1.065 < ε < 2.8, for the luminance coefficients only
//               (gendaylit's "correction du modèle de Perez"; the efficacies keep the true Δ);
//            3. (none needed) gendaylit refuses ε > 12.1 and gendaymtx's last bin ends at 12;
//               here, in both modes, bin 8 is open-ended as in Table 1 (6.2–∞);
//            4. the gradation term takes cos θ ≥ 0.01 (perezlum.cal), so b > 0 stays finite;
//            5. negative luminances are set to 0 (gendaymtx's patches);
//            6. a negative direct luminous efficacy is set to 0 (gendaylit, gendaymtx).
//            Radiance also uses Kasten's 1966 air mass and Spencer's eccentricity series; those
//            are not clamps and are not reproduced (Kasten–Young 1989 and SPA's distance here).
enum class PerezClamps { none, radiance };
PerezClamps parse_perez_clamps(std::string_view name);  // "none" or "radiance"; throws daylit::Error
std::string_view perez_clamps_name(PerezClamps clamps) noexcept;

// Relative optical air mass, Kasten and Young, "Revised optical air mass tables and approximation
// formula", Applied Optics 28(22), 4735–4738 (1989): m = 1/(cos Z + 0.50572 (96.07995° − Z)^−1.6364),
// Z in degrees, valid to Z = 90° (m = 38.09 there). Z ∈ [0°, 90°].
double kasten_young_air_mass(double zenith_deg) noexcept;

// Extraterrestrial normal irradiance (W/m²): the solar constant 1367 W/m² that Perez et al. used
// (WRC 1981), scaled by the inverse square of the Earth–sun distance in AU (SPA's R).
inline constexpr double kSolarConstant = 1367;
double extraterrestrial_normal_irradiance(double distance_au) noexcept;

// The hour's sky condition. ε = ((E_dh + E_dn)/E_dh + κZ³)/(1 + κZ³), κ = 1.041, Z in radians
// (1990 eq. 1); Δ = E_dh m / E_0 (eq. 2); W = exp(0.07 T_d − 0.075) cm of precipitable water
// from the dew point T_d (°C; Perez 1990 after Wright et al. 1989).
struct PerezConditionInput {
  double diffuse_horizontal_irradiance = 0;  // E_dh, W/m², > 0
  double direct_normal_irradiance = 0;       // E_dn, W/m², ≥ 0
  double sun_zenith_deg = 0;                 // Z, [0°, 90°)
  double extraterrestrial_normal = kSolarConstant;  // E_0, W/m²
  double dew_point_c = 11;                   // gendaymtx's default where a file has none
};

struct PerezCondition {
  double clearness = 1;    // ε, as computed (before any clamp)
  double brightness = 0;   // Δ, as computed
  double air_mass = 1;     // m
  double precipitable_water_cm = 2;
  int bin = 1;             // 1..8 (Table 1: 1, 1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2, ∞)
  // What the luminance coefficients were computed from (the clamps may change them).
  double clearness_used = 1, brightness_used = 0, sun_zenith_used_deg = 0;
  double a = 0, b = 0, c = 0, d = 0, e = 0;  // 1993 eq. 1, from Table 1 (eqs. 6–8)
  double diffuse_efficacy = 0, direct_efficacy = 0;  // lm/W, 1990 eqs. 7 and 8 (Table 4)
  std::vector<std::string> clamps_applied;           // one line per clamp that changed something
};

// Throws daylit::Error for E_dh ≤ 0, E_dn < 0, Z outside [0°, 90°) or non-finite input. The
// direct efficacy of eq. 8 turns negative for low suns (the c·exp(5.73 Z − 5) term): it is
// returned as it is under PerezClamps::none (perez_hour refuses it only where it is needed).
PerezCondition perez_condition(const PerezConditionInput& input, PerezClamps clamps);

// The sky's luminance for one condition and sun: lv(u) = (1 + a e^{b/cos θ}) (1 + c e^{dγ} + e cos²γ)
// (1993 eq. 1), in relative units; normalised so that ∫ L cos θ dσ over the sky hemisphere is the
// hour's diffuse horizontal illuminance.
class PerezSky {
 public:
  // sun: unit vector towards the sun (above the horizon). Under PerezClamps::radiance the sky's
  // sun is lowered to 87° altitude when higher. Computes the normalisation by cubature (about
  // 1e5–1e6 evaluations, a few ms). Throws daylit::Error under PerezClamps::none when the
  // luminance is negative somewhere above the horizon or diverges there (b > 0 and a ≠ 0): the
  // message names the condition and suggests --perez-clamps radiance.
  PerezSky(const PerezCondition& condition, const Vec3& sun, PerezClamps clamps);

  const PerezCondition& condition() const noexcept { return condition_; }
  PerezClamps clamps() const noexcept { return clamps_; }
  const Vec3& sun() const noexcept { return sun_; }  // the sky's sun (after the 87° cap)

  // lv(u) of eq. 1 for a unit u above the horizon (0 below it), with the clamps.
  double luminance_function(const Vec3& u) const noexcept;
  // lv(u)/lv(zenith): the luminance relative to the zenith, as the CIE skies give it.
  double relative_luminance(const Vec3& u) const noexcept { return luminance_function(u) / zenith_value_; }
  // The largest L/L_z over the sky: the larger of the sun's direction (the circumsolar peak) and
  // 40,000 directions spread evenly over the hemisphere (a bound on what a left-out obstruction hides).
  double max_relative_luminance() const;
  // N = ∫ lv(u) cos θ dσ over the upper hemisphere (sr), as nested 1-D integrals in the sun's
  // frame: by a fixed Gauss–Legendre rule (smoothstep-mapped panels) at rising orders 48, 64, 96
  // until two agree to 1e-12 relative, else by adaptive Gauss–Kronrod to 1e-12 relative (both
  // measured 1.4e-16 to 1.5e-15 against tensor Gauss–Legendre in long double); where Radiance's
  // floor at 0 acts, adaptive cubature over the hemisphere, whose triangles the floor's kink
  // crosses (2e-10 measured).
  // The clamps that acted on this sky (b > 0 held at the horizon, negative luminance cut) are
  // appended to condition().clamps_applied.
  double horizontal_integral() const noexcept { return horizontal_integral_; }
  // Whether the fixed rule gave horizontal_integral() (its two orders agreed).
  bool normalised_by_fixed_rule() const noexcept { return normalised_by_fixed_rule_; }
  // The nested adaptive Gauss–Kronrod normalisation alone, whatever gave horizontal_integral()
  // (the fixed rule's check in the tests; its fallback).
  double adaptive_normalisation() const;
  // E_out / L_z = N / lv(zenith): multiply by the zenith luminance to get E_dh.
  double horizontal_irradiance_over_zenith() const noexcept { return horizontal_integral_ / zenith_value_; }
  // gendaylit's normalisation for comparison: Σ lv(u_i) cos θ_i · 2π/144 over its 145 directions
  // (defangle.dat: altitudes 6°, 18°, … 78° in rows of 30, 30, 24, 24, 18, 12, 6 azimuths, and
  // the zenith), which takes every direction to stand for an equal solid angle.
  double radiance_145_point_integral() const;

 private:
  PerezCondition condition_;
  PerezClamps clamps_;
  Vec3 sun_;
  double zenith_value_ = 1, horizontal_integral_ = 0;
  bool normalised_by_fixed_rule_ = false;
  struct SunFrame;
  double sun_frame_normalisation();  // N where the luminance is gradation × indicatrix
  double fixed_rule_normalisation(std::size_t order_index) const;

 public:
  // The fixed rule's orders, tried in turn (sun_frame_normalisation).
  static constexpr int kFixedOrders[] = {48, 64, 96};
};

// ∫_A (L/L_z)(u) (n·u) T(u) dσ over a region above the horizon and in front of the receiver, by
// adaptive cubature (sky_quadrature.hpp) to the relative tolerance given.
QuadratureResult perez_sky_irradiance_quadrature(const PerezSky& sky, const SphericalRegion& region, const Vec3& n,
                                                 double tolerance,
                                                 const std::function<double(const Vec3&)>& transmittance = {});

// One hour's Perez sky and the sun's direct normal illuminance, from what a weather file or the
// command line gives. The condition (ε, Δ) needs irradiances; the sky's and the sun's scale need
// illuminances. Where an illuminance is not given it is the irradiance times Perez's efficacy
// (1990 eqs. 7–8); where only illuminances are given (a .wea in lux), the irradiances are found
// by fixed-point iteration E = lux / efficacy(ε(E), Δ(E)) from E = lux · 1367/127500 (the ratio
// of the solar constants that gendaymtx starts from), to 1e-9 relative or 100 steps (Radiance
// stops after 5 steps or within 10 W/m²); `iterations` says how many were taken.
struct PerezHourInput {
  std::optional<double> diffuse_horizontal_irradiance, direct_normal_irradiance;    // W/m²
  std::optional<double> diffuse_horizontal_illuminance, direct_normal_illuminance;  // lux
  std::optional<double> dew_point_c;  // 11 °C (gendaymtx's default) when not given
  double sun_zenith_deg = 0;          // the true sun
  Vec3 sun{0, 0, 1};                  // unit, towards the sun (the frame the sky is evaluated in)
  double distance_au = 1;             // Earth–sun distance (SPA's R) for E_0
  PerezClamps clamps = PerezClamps::none;
};

struct WeatherRecord;  // sky/weather_file.hpp
// The hour's irradiances (or, for a photometric .wea, illuminances), illuminances and dew point
// from a weather record, as `illuminance --sky perez --weather` and `annual` take them.
PerezHourInput perez_hour_input(const WeatherRecord& record, bool photometric);

struct PerezHour {
  PerezSky sky;
  double diffuse_horizontal_lux = 0, direct_normal_lux = 0;
  double diffuse_horizontal_irradiance = 0, direct_normal_irradiance = 0;  // W/m², as used for ε and Δ
  bool diffuse_lux_from_efficacy = false, direct_lux_from_efficacy = false, dew_point_assumed = false;
  int iterations = 0;  // of the illuminance-to-irradiance iteration (0 when irradiances were given)
};
// Throws daylit::Error as perez_condition and PerezSky do, when neither the irradiances nor the
// illuminances are given, when the direct illuminance must come from a negative efficacy (under
// PerezClamps::none, with E_dn > 0), or when the iteration meets a zero efficacy.
PerezHour perez_hour(const PerezHourInput& input);

}  // namespace daylit
