#pragma once
// Climate-based annual illuminance (DESIGN.md §5; issue 14, deliverables 3–4): every hour of a
// weather file, the Perez sky and the sun, on every sensor of a grid, through the daylight
// coefficients of annual_coefficients.hpp.
//
// Per hour and sensor: E_sky = (E_dh / N) [Σ_j c_j B_j + C], with c_j the hour's smooth-part
// coefficients (fit_smooth_sky), B_j the sensor's moments, C the circumsolar term
// c ∫_A G(u_z) e^{dγ} (n·u) T dσ over the sensor's stored regions, by its fixed rules on the pieces
// far from the sun and adaptive cubature split at the sun on those near it (CircumsolarRule,
// sky_quadrature.hpp; the rules' two-order difference and the cubature's estimate count in the
// bound), and N the sky's own
// normalisation (PerezSky). Hours in which Radiance's clamp 5 (negative luminance set to 0)
// acted are not a sum of basis terms: they are integrated by cubature of the whole clamped
// luminance over each region, and counted. The sun: its disk cut exactly by each region
// (cap_clip.hpp), as `daylit illuminance` does. Reflected light (ERC + IRC) is added where the
// caller passes it (annual_reflections.hpp); else results are sky + sun direct.
//
// Blinds (IES LM-83-12, §2.2.6 as the issue words it): in an occupied hour, a window group's
// blinds close when more than `blinds_sensor_share` of the grid's sensors get at least
// `blinds_threshold_lux` of direct sun through that group alone (blinds open); a closed group
// passes `closed_blind_transmittance` of its sky and sun light. The illuminance with blinds is
// what DA, cDA, UDI, sDA and EN 17037 use; ASE and direct_sun_hours use the direct sun with
// blinds open.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geometry/sky_box.hpp"
#include "simulation/annual_coefficients.hpp"
#include "simulation/sky_patches.hpp"
#include "sky/circumsolar_sum.hpp"
#include "sky/perez_sky.hpp"
#include "sky/site.hpp"
#include "sky/weather_file.hpp"

namespace daylit {

struct AnnualOptions {
  int degree = 32;                            // of the gradation's Chebyshev fit (test_perez_sky: the convergence table)
  PerezClamps clamps = PerezClamps::radiance;  // see below: the annual default
  double circumsolar_tolerance = 1e-6;        // relative, per region (spherical_quadrature.hpp)
  double closed_blind_transmittance = 0.2;
  double blinds_threshold_lux = 1000, blinds_sensor_share = 0.02;
  double pressure_hpa = 1013.25, temperature_c = 10;
  // 0: the sun's disk at the true sun (exact). MF ≥ 1: at the centre of the Reinhart MF patch
  // that holds the sun (reinhart_patch_centre), as patch-based tools place it, to measure what
  // the sky's discretisation alone does to ASE, direct sun hours and the blinds. The sky is exact
  // either way.
  int sun_patch_mf = 0;
  // 0: the exact sky (the smooth basis and the circumsolar term about the sun). MF ≥ 1: the sky in
  // Reinhart MF patches, each uniform at its centre's luminance and normalised as gendaymtx does,
  // each integrated exactly over the visible regions (sky_patches.hpp): what a patch-based sky
  // changes, without noise. The sun is --sun-patches' either way.
  int sky_patch_mf = 0;
};

// The centre (azimuth clockwise from true north, altitude; degrees) of the Reinhart patch of
// subdivision MF (MF = 1: Tregenza's 145 patches) that holds the direction (azimuth, altitude):
// rows of 90°/(7 MF + 0.5) in altitude with {30, 30, 24, 24, 18, 12, 6}·MF patches (each of
// Tregenza's rows split MF times), the first patch of every row centred on true north, and a
// polar cap of half a row (Reinhart and Walkenhorst 2001; Radiance's reinhart.cal, whose
// azimuth origin may differ: a turn of the patches changes the count by the sun's position
// within its patch, not the patch size).
struct SkyPatchCentre {
  double azimuth_deg, altitude_deg;
};
SkyPatchCentre reinhart_patch_centre(double azimuth_deg, double altitude_deg, int mf);

// One record of the weather file, as the annual run takes it.
struct AnnualHour {
  const WeatherRecord* record = nullptr;
  int hour_ending = 0;          // EPW hour (1–24); for a .wea the hour that holds its time
  bool occupied = false;        // 8:00–18:00 local standard time (LEED v4 / LM-83: 3,650 h a year)
  double sun_altitude_deg = -90;  // SPA, at the hour's sun time (EN 17037's daylight hours take the highest)
  bool sky = false;             // a Perez sky was built (sun up, usable record, E_dh > 0)
  std::string skipped;          // why not, when not ("sun down" and others)
  Vec3 sun{0, 0, 1};            // the true sun, model frame
  double direct_normal_lux = 0, diffuse_horizontal_lux = 0;
  double scale = 0;             // E_dh / N (lux per unit of lv·sr)
  std::optional<PerezSky> perez;
  SmoothSkyFit fit;
  bool floored = false;         // clamp 5 acted: the whole luminance by cubature
  std::vector<double> patch_luminance;  // AnnualOptions::sky_patch_mf: per patch (patch_luminances)
};

// One hour from its sky (which carries its own clamps), the true sun (model frame, unit) and the
// hour's diffuse horizontal and direct normal illuminances (lux).
AnnualHour annual_hour(const PerezSky& sky, const Vec3& sun, double diffuse_horizontal_lux, double direct_normal_lux,
                       const AnnualOptions& options);

struct AnnualSky {
  std::vector<AnnualHour> hours;  // one per record, in file order
  std::vector<SkyPatch> patches;  // AnnualOptions::sky_patch_mf ≥ 1: the sky's patches
  std::size_t sky_hours = 0, floored_hours = 0, refused_hours = 0;
  std::size_t fixed_rule_hours = 0;  // hours normalised by PerezSky's fixed rule (the others: adaptive)
  std::vector<std::pair<std::string, std::size_t>> clamp_counts;  // clamp line → hours it acted in
  double max_fit_error = 0;       // the largest ε_G (1 + |e|) over the hours
};

// The hours of a weather file for a site (the model frame comes from it). Hours the published
// model cannot serve under PerezClamps::none are skipped and counted (refused_hours), never
// silently. Throws daylit::Error for a file without any usable sun-up hour.
AnnualSky annual_sky(const WeatherFile& weather, const Site& site, const AnnualOptions& options);

// The hourly results of one grid.
struct AnnualGridResult {
  std::size_t sensors = 0, hours = 0;
  // [sensor × hours], row-major by sensor: illuminance with blinds (sky + sun direct), lux.
  std::vector<float> illuminance;
  // [sensor × hours]: direct sun alone, blinds open (ASE, direct_sun_hours).
  std::vector<float> direct_sun;
  // Per sensor: the largest per-hour bound on |computed − true| sky illuminance (lux), and the
  // hour it occurred in; the bound is the fit's ε_G(1 + |e|)·lambert + the moments' estimate +
  // the circumsolar (or floored-hour) cubature's estimate, all times E_dh/N.
  std::vector<double> max_bound_lux;
  std::vector<double> max_bound_relative;  // that bound over the hour's illuminance (where > 0)
  // [hours × groups]: whether the group's blinds were closed.
  std::vector<std::uint8_t> blinds_closed;
  std::size_t groups = 0;
  double max_moment_error = 0;
  std::size_t adaptive_circumsolar = 0;  // sensor-hour-groups in which any of the circumsolar term went to adaptive cubature
  VisibilityCounters counters;
  double coefficient_time_s = 0, hourly_time_s = 0;
  // With reflections (annual_reflections.hpp): per sensor the largest per-hour error estimate of
  // the reflected part (lux, with blinds) and that over the hour's illuminance (hours of at least
  // 100 lx); the grid's
  // reflected share of the occupied hours' illuminance (with blinds).
  bool reflections = false;
  std::vector<double> max_reflection_estimate_lux, max_reflection_estimate_relative;
  double reflected_share = 0;
  // Per sensor, the occupied hours' illuminance (with blinds, lux·h) and its reflected part (0
  // without reflections), summed in hour order: reflected_share is reflected_share() of them, so a
  // caller that computed the sensors in blocks finds the whole grid's share from the gathered sums.
  std::vector<double> occupied_lux, occupied_reflected_lux;
};

// Σ_i reflected_i / Σ_i total_i over the sensors in order (0 where the total is 0).
double reflected_share(const std::vector<double>& occupied_lux, const std::vector<double>& occupied_reflected_lux);

// The LM-83 rule counts, per hour and window group, the sensors that get at least the threshold
// of direct sun through the group ([hours × groups]), out of `sensors`. A caller that passes
// annual_grid one block of a grid (MPI ranks, cli/mpi_shards.hpp) turns the block's counts and
// sensors into the whole grid's here (a sum over the blocks: integers, exact in any order), so
// that every block's blinds are the whole grid's.
using BlindsCounts = std::function<void(std::vector<std::uint64_t>& lit_per_hour_group, std::uint64_t& sensors)>;

struct ReflectedHours;

// `reflected`: the grid's reflected part per hour and window group (annual_reflections.hpp), added
// to the sky and sun with each group's blinds factor; the light on surfaces lit outdoors enters by
// every group, weighted by the groups' aperture areas (exact with one group). nullptr: sky + sun
// direct only. `whole_grid`: see BlindsCounts (empty: `grid` is the whole grid).
// `direct` (geometry/sky_box.hpp), where the grid sees the sky directly
// (SensorGrid::sees_sky_directly): the sky and sun seen past every surface, one more part per
// sensor (its regions indexed by direct->scene's apertures, the box's open faces), in the exact or
// the patch path as the groups are, never behind blinds; its sun counts in direct_sun.
AnnualGridResult annual_grid(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid,
                             const AnnualSky& sky, const AnnualOptions& options, const ProgressCallback& progress = {},
                             const ReflectedHours* reflected = nullptr, const BlindsCounts& whole_grid = {},
                             const DirectSky* direct = nullptr);

// One sensor's sky illuminance in one hour through the given coefficients (all groups, no blinds),
// and the bound on its error: the path annual_grid takes, for tests.
struct HourIlluminance {
  double sky_lux = 0, sun_lux = 0, bound_lux = 0;
  bool adaptive = false;   // the circumsolar term (or a floored hour) went to adaptive cubature
  int far_order = 0;       // the order the far pieces' fixed rules gave (CircumsolarRule), 0: none
};

// Fixed product Gauss rules (kCircumsolarOrderHigh², kCircumsolarOrderLow² and
// kCircumsolarOrderLowest² points per fan triangle, the triangles split to sides of at most
// kCircumsolarMaxSide as the moments' are: fan_product_rule.hpp) over a sensor's regions, with
// (n·u) T(u) in the weights: built once per sensor, they integrate the hour's circumsolar term
// c·G(u_z)·e^{dγ} as sums (circumsolar_sum). Per hour, the pieces (split triangles) whose cap lies
// more than kCircumsolarMargin from the sky's sun take their nodes' sums; the few near it, where
// the kink of e^{dγ} at the sun would spoil a fixed rule, go to adaptive cubature split at the sun,
// over those pieces alone. Over the far pieces the low order is taken with its difference from the
// lowest as the estimate of its error, when that is within the circumsolar tolerance of the whole
// term; else the high order, with its difference from the low; else the whole term goes to adaptive
// cubature. (The pair 6/8 decides 98.5 % of the office sample's sensor-hours, Chicago year, at
// 100 nodes a piece instead of 12/8's 208: the hourly pass 9.9 → 8.1 s on 300 of its sensors.)
// (A product rule in the sun's frame — a fan from the sun, Duffy-collapsed there — was tried twice:
// unsplit, it needed order 20 against 14 to reach 1e-6 on test_perez_sky's window; split to 1 rad,
// its orders 12 and 8 agreed in only a third of the near-sun hours, the sun lying close to the
// edges of its thin triangles. Neither paid.)
inline constexpr int kCircumsolarOrderHigh = 12, kCircumsolarOrderLow = 8, kCircumsolarOrderLowest = 6;
inline constexpr double kCircumsolarMargin = 5 * 3.14159265358979323846 / 180;
// 1 rad: on the room sample (40 sensors, Chicago year) the sensor-hours sent to adaptive cubature
// fell from 120,569 (unsplit) to 48,390, most of the rest with the sun within the margin; 0.7 rad
// took 45,006 but more nodes per hour.
inline constexpr double kCircumsolarMaxSide = 1.0;
struct CircumsolarRule {
  struct Piece {
    Vec3 a, b, c;                  // unit vertices, the region's orientation
    std::size_t region = 0;        // SensorCoefficients::regions
    std::size_t high_begin = 0, high_end = 0, low_begin = 0, low_end = 0, lowest_begin = 0, lowest_end = 0;  // its nodes
    Vec3 centre{};                 // a cap about `centre` holds the piece...
    double near_cos = 1;           // ...and the sun is near it when centre·sun ≥ this (cap + margin)
  };
  std::vector<Piece> pieces;
  DirectionNodes high, low, lowest;  // (n·u) T(u) dσ in the weights, region's sign included
  std::size_t regions = 0;
};
CircumsolarRule circumsolar_rule(const Scene& scene, const Sensor& sensor, const SensorCoefficients& coefficients);

// The same hour with the sky in patches (AnnualOptions::sky_patch_mf): Σ_P coefficient_P L_P
// (add_patch_coefficients over the sensor's regions, hour.patch_luminance), and the sun as
// hour_illuminance takes it. The bound covers glass's and tilted panes' T only: the patches'
// discretisation is what this mode is for, and has no bound.
HourIlluminance patch_hour_illuminance(const Scene& scene, const Sensor& sensor, const SensorCoefficients& coefficients,
                                       const std::vector<double>& patch_coefficients, double patch_spread,
                                       const AnnualHour& hour);

HourIlluminance hour_illuminance(const Scene& scene, const Sensor& sensor, const SensorCoefficients& coefficients,
                                 const AnnualHour& hour, const AnnualOptions& options,
                                 const CircumsolarRule* rule = nullptr);

// Direct sun (lux) at a sensor through one seen region: L_s ∫_{disk ∩ A} (n·u) dσ × T(sun), T the
// aperture's and the panes' in front of it at the sun (transmittance_along).
double direct_sun_lux(const Scene& scene, const SeenRegion& seen, const Vec3& n, const Vec3& sun, double direct_normal_lux);

// The LM-83 rule for one hour: closed[g] when more than `share` of the sensors get ≥ threshold
// lux from group g's direct sun alone. sun_by_group is [sensor × groups]. (annual_grid counts
// the lit sensors itself, for BlindsCounts, and compares as blinds_closed does.)
std::vector<std::uint8_t> blinds_rule(const std::vector<float>& sun_by_group, std::size_t sensors, std::size_t groups,
                                      double threshold_lux, double share);
// The rule's comparison: more than `share` of `sensors` lit.
inline bool blinds_closed(std::uint64_t lit, std::uint64_t sensors, double share) {
  return double(lit) > share * double(sensors);
}

}  // namespace daylit
