#include "simulation/annual.hpp"

#include "simulation/pane_transmittance.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <numbers>

#include <fmt/format.h>

#include "geometry/error.hpp"
#include "illumination/cap_clip.hpp"
#include "illumination/fan_product_rule.hpp"
#include "illumination/gauss_legendre.hpp"
#include "materials/glass_transmittance.hpp"
#include "simulation/annual_reflections.hpp"
#include "simulation/illuminance.hpp"
#include "simulation/pane_transmittance.hpp"
#include "simulation/sensor_loop.hpp"
#include "sky/hour_sun.hpp"
#include "sky/sky_quadrature.hpp"

namespace daylit {

namespace {

// Σ_j a_j b_j with four partial sums: one running sum waits on each addition before the next (the
// smooth sky's dot product was a tenth of an annual run's hourly time), four keep the adder busy.
double dot_product(const double* a, const double* b, std::size_t n) noexcept {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  std::size_t j = 0;
  for (; j + 4 <= n; j += 4) {
    s0 += a[j] * b[j];
    s1 += a[j + 1] * b[j + 1];
    s2 += a[j + 2] * b[j + 2];
    s3 += a[j + 3] * b[j + 3];
  }
  for (; j < n; ++j) s0 += a[j] * b[j];
  return (s0 + s1) + (s2 + s3);
}

constexpr double kMinCosRadiance = 0.01;  // perezlum.cal's floor on cos θ (perez_sky.hpp, clamp 4)

int year_of(const WeatherRecord& r) {
  if (r.year > 0) return r.year;
  return r.month == 2 && r.day == 29 ? 2024 : 2025;  // a .wea has no year: any year with the date
}

// EPW: hour ending h covers (h − 1, h]; 8:00–18:00 are h = 9..18. A .wea's time x: 8 ≤ x < 18.
bool occupied(const WeatherFile& file, const WeatherRecord& r) {
  if (file.format == WeatherFormat::epw) return r.hour >= 9 && r.hour <= 18;
  return r.hour >= 8 && r.hour < 18;
}

// The clamp a line of PerezCondition::clamps_applied names, by the numbering of perez_sky.hpp.
std::string clamp_kind(const std::string& line) {
  const auto starts = [&](const char* prefix) { return line.rfind(prefix, 0) == 0; };
  if (starts("sun altitude")) return "1: sun altitude lowered to 87 deg for the sky";
  if (starts("Δ")) return "2: Delta raised to 0.2 for the luminance coefficients";
  if (starts("b =")) return "4: gradation held at cos(theta) = 0.01 (b > 0)";
  if (starts("negative luminance")) return "5: negative luminance set to 0 (hour by full cubature)";
  if (starts("direct efficacy")) return "6: negative direct efficacy set to 0";
  return line;
}

}  // namespace

double direct_sun_lux(const Scene& scene, const SeenRegion& seen, const Vec3& n, const Vec3& sun, double direct_normal_lux) {
  const double rho = kSunHalfAngleDeg * std::numbers::pi / 180;
  const double visible = cap_lambert(seen.region, sun, rho, n);
  if (visible == 0) return 0;
  const double sin_rho = std::sin(rho);
  // Snyder 1996, eq. 6 (as simulation/illuminance.cpp): L_s = E_dn / (π sin²ρ); glass's T at the
  // disk's centre (through panes in front: each pane's at the sun).
  const double t = SeenTransmittance(scene, seen)(sun);
  return seen.sign * t * direct_normal_lux / (std::numbers::pi * sin_rho * sin_rho) * visible;
}

CircumsolarRule circumsolar_rule(const Scene& scene, const Sensor& sensor, const SensorCoefficients& coefficients) {
  CircumsolarRule rule;
  rule.regions = coefficients.regions.size();
  static const quadrature::UnitGaussRule high = quadrature::gauss_legendre_unit(kCircumsolarOrderHigh),
                                         low = quadrature::gauss_legendre_unit(kCircumsolarOrderLow),
                                         lowest = quadrature::gauss_legendre_unit(kCircumsolarOrderLowest);
  for (std::size_t r = 0; r < coefficients.regions.size(); ++r) {
    const SeenRegion& seen = coefficients.regions[r];
    const SeenTransmittance transmittance(scene, seen);
    for_each_fan_triangle(seen.region, kCircumsolarMaxSide, [&](const Vec3& a, const Vec3& b, const Vec3& c) {
      CircumsolarRule::Piece piece{a, b, c, r};
      // The cap about the normalised centroid through the farthest vertex holds the triangle (a
      // cap under a hemisphere is convex); the sun is near when within that radius + the margin.
      piece.centre = normalized(a + b + c);
      const double radius = std::max({angle_between(piece.centre, a), angle_between(piece.centre, b), angle_between(piece.centre, c)});
      piece.near_cos = std::cos(std::min(std::numbers::pi, radius + kCircumsolarMargin));
      // The sky has nothing below the horizon (the sum takes nodes above it only).
      DirectionNodes* nodes = &rule.high;
      const auto add = [&](const Vec3& u, double area) {
        if (u.z > 0) nodes->push_back(u, seen.sign * area * dot(sensor.normal, u) * transmittance(u));
      };
      piece.high_begin = rule.high.size();
      for_each_triangle_node(a, b, c, high, add);
      piece.high_end = rule.high.size();
      nodes = &rule.low;
      piece.low_begin = rule.low.size();
      for_each_triangle_node(a, b, c, low, add);
      piece.low_end = rule.low.size();
      nodes = &rule.lowest;
      piece.lowest_begin = rule.lowest.size();
      for_each_triangle_node(a, b, c, lowest, add);
      piece.lowest_end = rule.lowest.size();
      rule.pieces.push_back(piece);
    });
  }
  return rule;
}

SkyPatchCentre reinhart_patch_centre(double azimuth_deg, double altitude_deg, int mf) {
  if (mf < 1) throw Error("the Reinhart subdivision MF must be at least 1");
  constexpr int kTregenzaRow[7] = {30, 30, 24, 24, 18, 12, 6};
  const double row_height = 90.0 / (7 * mf + 0.5);
  const int row = int(std::floor(std::max(altitude_deg, 0.0) / row_height));
  if (row >= 7 * mf) return {0, 90};  // the polar cap
  const int count = kTregenzaRow[row / mf] * mf;
  const double width = 360.0 / count;
  const double az = std::fmod(std::fmod(azimuth_deg, 360.0) + 360.0, 360.0);
  const int patch = int(std::lround(az / width)) % count;
  return {patch * width, (row + 0.5) * row_height};
}

AnnualHour annual_hour(const PerezSky& sky, const Vec3& sun, double diffuse_horizontal_lux, double direct_normal_lux,
                       const AnnualOptions& options) {
  AnnualHour hour;
  hour.sky = true;
  hour.sun = normalized(sun);
  hour.sun_altitude_deg = std::asin(std::clamp(hour.sun.z, -1.0, 1.0)) * 180 / std::numbers::pi;
  hour.direct_normal_lux = direct_normal_lux;
  hour.diffuse_horizontal_lux = diffuse_horizontal_lux;
  hour.scale = diffuse_horizontal_lux / sky.horizontal_integral();
  const PerezCondition& c = sky.condition();
  for (const std::string& line : c.clamps_applied)
    if (line.rfind("negative luminance", 0) == 0) hour.floored = true;
  hour.fit = fit_smooth_sky(c.a, c.b, c.e, sky.clamps() == PerezClamps::radiance ? kMinCosRadiance : 0.0, sky.sun(),
                            options.degree);
  hour.perez.emplace(sky);
  return hour;
}

AnnualSky annual_sky(const WeatherFile& weather, const Site& site, const AnnualOptions& options) {
  AnnualSky out;
  out.hours.resize(weather.records.size());
  if (options.sky_patch_mf > 0) out.patches = reinhart_patches(options.sky_patch_mf, site);
  const double lat = site.origin().latitude_deg, lon = site.origin().longitude_deg, h = site.origin().height_m;
  tbb::parallel_for(std::size_t(0), weather.records.size(), [&](std::size_t i) {
    const WeatherRecord& r = weather.records[i];
    AnnualHour& hour = out.hours[i];
    hour.record = &r;
    hour.occupied = occupied(weather, r);
    const HourSun sun =
        weather.format == WeatherFormat::epw
            ? sun_for_hour_ending(year_of(r), r.month, r.day, int(r.hour), weather.location.time_zone_h, lat, lon, h,
                                  options.pressure_hpa, options.temperature_c)
            : sun_at_hour(year_of(r), r.month, r.day, r.hour, weather.location.time_zone_h, lat, lon, h,
                          options.pressure_hpa, options.temperature_c);
    hour.hour_ending = weather.format == WeatherFormat::epw ? int(r.hour) : int(std::floor(r.hour)) + 1;
    hour.sun_altitude_deg = sun.position.elevation_deg;
    if (!sun.up || !(sun.position.zenith_deg < 90)) {
      hour.skipped = "sun down";
      return;
    }
    if (!r.usable) {
      hour.skipped = "missing direct or diffuse value";
      return;
    }
    PerezHourInput in = perez_hour_input(r, weather.photometric);
    in.clamps = options.clamps;
    if (r.diffuse_horizontal_irradiance == 0.0 || (weather.photometric && r.diffuse_horizontal_illuminance == 0.0)) {
      hour.skipped = "diffuse horizontal value 0 with the sun up";
      return;
    }
    hour.sun = site.model_direction(sun.position.azimuth_deg, 90 - sun.position.zenith_deg);
    in.sun_zenith_deg = sun.position.zenith_deg;
    in.sun = hour.sun;
    in.distance_au = sun.position.distance_au;
    try {
      PerezHour p = perez_hour(in);
      AnnualHour built = annual_hour(p.sky, hour.sun, p.diffuse_horizontal_lux, p.direct_normal_lux, options);
      built.record = hour.record;
      built.occupied = hour.occupied;
      built.hour_ending = hour.hour_ending;
      built.sun_altitude_deg = hour.sun_altitude_deg;
      hour = std::move(built);
      if (!out.patches.empty()) hour.patch_luminance = patch_luminances(out.patches, *hour.perez, hour.diffuse_horizontal_lux);
      if (options.sun_patch_mf > 0) {
        const SkyPatchCentre centre = reinhart_patch_centre(sun.position.azimuth_deg, 90 - sun.position.zenith_deg,
                                                            options.sun_patch_mf);
        hour.sun = site.model_direction(centre.azimuth_deg, centre.altitude_deg);
      }
    } catch (const Error& e) {
      hour.skipped = std::string("refused: ") + e.what();
    }
  });
  std::map<std::string, std::size_t> counts;
  for (const AnnualHour& hour : out.hours) {
    if (hour.sky) {
      ++out.sky_hours;
      out.floored_hours += hour.floored;
      out.fixed_rule_hours += hour.perez->normalised_by_fixed_rule();
      out.max_fit_error = std::max(out.max_fit_error, hour.fit.bound_factor);
      for (const std::string& line : hour.perez->condition().clamps_applied) ++counts[clamp_kind(line)];
    } else if (hour.skipped.rfind("refused", 0) == 0) {
      ++out.refused_hours;
    }
  }
  out.clamp_counts.assign(counts.begin(), counts.end());
  if (out.sky_hours == 0) throw Error(weather.path + ": no hour with the sun up and a usable sky");
  return out;
}

HourIlluminance hour_illuminance(const Scene& scene, const Sensor& sensor, const SensorCoefficients& coefficients,
                                 const AnnualHour& hour, const AnnualOptions& options, const CircumsolarRule* rule) {
  HourIlluminance out;
  if (!hour.sky) return out;
  const std::size_t size = hour.fit.coefficients.size(), groups = coefficients.lambert.size();
  const PerezSky& sky = *hour.perez;
  const PerezCondition& c = sky.condition();
  double lambert = 0, lambert_max = 0;
  for (double l : coefficients.lambert) {
    lambert += l;
    lambert_max = std::max(lambert_max, l);
  }
  double value = 0, error = 0;
  if (!hour.floored) {
    for (std::size_t g = 0; g < groups; ++g) value += dot_product(hour.fit.coefficients.data(), coefficients.sky_direct.data() + g * size, size);
    error += hour.fit.bound_over(coefficients.min_uz, coefficients.max_uz) * lambert +
             coefficients.moment_error * lambert_max * hour.fit.coefficients_abs_sum;
  }
  const double min_cos = sky.clamps() == PerezClamps::radiance ? kMinCosRadiance : 0.0;
  // An open aperture's constant τ scales a cubature's result; else T along each direction
  // (through panes: each pane's at its own cosine, SeenTransmittance).
  const auto cubature = [&](const SeenRegion& seen, const SphericalRegion& region) {
    const SeenTransmittance along(scene, seen);
    std::function<double(const Vec3&)> transmittance;
    double scale = along.value();
    if (!along.constant()) {
      transmittance = [&along](const Vec3& u) { return along(u); };
      scale = 1;
    }
    // The circumsolar term's 16 directions per triangle at a time (circumsolar_values), times
    // (n·u)₊ and T (the constant τ of an open aperture is `scale`).
    const Vec3 n = sensor.normal;
    const DirectionBatch batch = [&](const double* x, const double* y, const double* z, std::size_t count, double* out) {
      circumsolar_values(x, y, z, count, sky.sun(), c.a, c.b, c.c, c.d, min_cos, out);
      for (std::size_t i = 0; i < count; ++i) out[i] *= std::max(0.0, n.x * x[i] + n.y * y[i] + n.z * z[i]);
      if (!along.constant()) along.multiply(x, y, z, count, out);
    };
    const QuadratureResult q =
        hour.floored ? sky_irradiance_quadrature([&sky](const Vec3& u) { return sky.luminance_function(u); }, sky.sun(),
                                                 region, sensor.normal, options.circumsolar_tolerance, transmittance)
                     : integrate_over_region(split_at_sun(region, sky.sun()), batch, options.circumsolar_tolerance);
    return QuadratureResult{seen.sign * scale * q.value, scale * q.error_estimate, q.evaluations};
  };
  // The circumsolar term by the sensor's fixed rules on the pieces far from the sun and adaptive
  // cubature on those near it (CircumsolarRule); where the far pieces' two orders disagree, or
  // without a rule, the whole term by adaptive cubature split at the sun.
  bool fixed = rule != nullptr && !hour.floored && c.c != 0 && rule->regions == coefficients.regions.size();
  if (fixed) {
    double low = 0, lowest = 0, near = 0, near_error = 0;
    std::vector<SphericalRegion> near_pieces(coefficients.regions.size());
    std::vector<const CircumsolarRule::Piece*> far;
    for (const CircumsolarRule::Piece& piece : rule->pieces) {
      if (dot(piece.centre, sky.sun()) >= piece.near_cos) {
        near_pieces[piece.region].loops.push_back({piece.a, piece.b, piece.c});
        continue;
      }
      far.push_back(&piece);
      low += circumsolar_sum(rule->low, piece.low_begin, piece.low_end, sky.sun(), c.a, c.b, c.c, c.d, min_cos);
      lowest += circumsolar_sum(rule->lowest, piece.lowest_begin, piece.lowest_end, sky.sun(), c.a, c.b, c.c, c.d, min_cos);
    }
    for (std::size_t r = 0; r < near_pieces.size(); ++r) {
      if (near_pieces[r].empty()) continue;
      const QuadratureResult q = cubature(coefficients.regions[r], near_pieces[r]);
      near += q.value;
      near_error += q.error_estimate;
      out.adaptive = true;
    }
    if (std::abs(low - lowest) <= options.circumsolar_tolerance * std::abs(low + near)) {
      value += low + near;
      error += std::abs(low - lowest) + near_error;
      out.far_order = kCircumsolarOrderLow;
    } else {
      double high = 0;
      for (const CircumsolarRule::Piece* piece : far)
        high += circumsolar_sum(rule->high, piece->high_begin, piece->high_end, sky.sun(), c.a, c.b, c.c, c.d, min_cos);
      if (std::abs(high - low) <= options.circumsolar_tolerance * std::abs(high + near)) {
        value += high + near;
        error += std::abs(high - low) + near_error;
        out.far_order = kCircumsolarOrderHigh;
      } else {
        fixed = false;
      }
    }
  }
  // The regions the sun's disk may touch: the rule's pieces tile each region, and a disk more than
  // kCircumsolarMargin (5°, against its 0.27° radius) from every piece of a region lies outside it,
  // where cap_lambert's answer is exactly 0 (most regions in most hours).
  std::vector<char> sun_near;
  if (rule != nullptr && rule->regions == coefficients.regions.size() && hour.direct_normal_lux > 0) {
    sun_near.assign(coefficients.regions.size(), 0);
    for (const CircumsolarRule::Piece& piece : rule->pieces)
      if (dot(piece.centre, hour.sun) >= piece.near_cos) sun_near[piece.region] = 1;
  }
  for (std::size_t r = 0; r < coefficients.regions.size(); ++r) {
    const SeenRegion& seen = coefficients.regions[r];
    if (!fixed && (hour.floored || c.c != 0)) {
      const QuadratureResult q = cubature(seen, seen.region);
      value += q.value;
      error += q.error_estimate;
      out.adaptive = true;
    }
    if (hour.direct_normal_lux > 0 && (sun_near.empty() || sun_near[r]))
      out.sun_lux += direct_sun_lux(scene, seen, sensor.normal, hour.sun, hour.direct_normal_lux);
  }
  out.sky_lux = hour.scale * value;
  out.bound_lux = hour.scale * error;
  return out;
}

HourIlluminance patch_hour_illuminance(const Scene& scene, const Sensor& sensor, const SensorCoefficients& coefficients,
                                       const std::vector<double>& patch_coefficients, double patch_spread,
                                       const AnnualHour& hour) {
  HourIlluminance out;
  if (!hour.sky) return out;
  for (std::size_t p = 0; p < patch_coefficients.size(); ++p) out.sky_lux += patch_coefficients[p] * hour.patch_luminance[p];
  out.bound_lux = (patch_spread + coefficients.pane_spread) * out.sky_lux;
  if (hour.direct_normal_lux > 0)
    for (const SeenRegion& seen : coefficients.regions)
      out.sun_lux += direct_sun_lux(scene, seen, sensor.normal, hour.sun, hour.direct_normal_lux);
  return out;
}

std::vector<std::uint8_t> blinds_rule(const std::vector<float>& sun_by_group, std::size_t sensors, std::size_t groups,
                                      double threshold_lux, double share) {
  std::vector<std::uint8_t> closed(groups, 0);
  for (std::size_t g = 0; g < groups; ++g) {
    std::size_t lit = 0;
    for (std::size_t i = 0; i < sensors; ++i) lit += sun_by_group[i * groups + g] >= threshold_lux;
    closed[g] = blinds_closed(lit, sensors, share);
  }
  return closed;
}

double reflected_share(const std::vector<double>& occupied_lux, const std::vector<double>& occupied_reflected_lux) {
  double all = 0, reflected_all = 0;
  for (std::size_t i = 0; i < occupied_lux.size(); ++i) {
    all += occupied_lux[i];
    reflected_all += occupied_reflected_lux[i];
  }
  return all > 0 ? reflected_all / all : 0;
}

AnnualGridResult annual_grid(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid,
                             const AnnualSky& sky, const AnnualOptions& options, const ProgressCallback& progress,
                             const ReflectedHours* reflected, const BlindsCounts& whole_grid, const DirectSky* direct) {
  const auto t0 = std::chrono::steady_clock::now();
  const WindowGroups groups = window_groups(scene);
  AnnualGridResult r;
  r.sensors = grid.sensors.size();
  r.hours = sky.hours.size();
  r.groups = groups.names.size();
  const std::vector<SensorCoefficients> coefficients =
      annual_coefficients(engine, scene, grid, groups, options.degree, r.counters);
  for (const auto& c : coefficients) r.max_moment_error = std::max(r.max_moment_error, c.moment_error);
  // The sky seen directly: one more part per sensor, the box's open faces its apertures (one group).
  const bool sees_directly = direct != nullptr && grid.sees_sky_directly;
  std::vector<SensorCoefficients> direct_coefficients;
  if (sees_directly) {
    direct_coefficients = annual_coefficients(direct->engine, direct->scene, grid, window_groups(direct->scene),
                                              options.degree, r.counters);
    for (const auto& c : direct_coefficients) r.max_moment_error = std::max(r.max_moment_error, c.moment_error);
  }
  const auto t1 = std::chrono::steady_clock::now();
  r.coefficient_time_s = std::chrono::duration<double>(t1 - t0).count();

  const std::size_t n = r.sensors, hours = r.hours, ng = r.groups;
  // Pass 1: the direct sun per group, blinds open ([hour][sensor × group]), for the blinds rule.
  std::vector<float> sun(hours * n * ng, 0.0f);
  for_each_sensor<int>(n, 16, {}, [&](std::size_t i, int&) {
    const Sensor& s = grid.sensors[i];
    for (std::size_t h = 0; h < hours; ++h) {
      const AnnualHour& hour = sky.hours[h];
      if (!hour.sky || hour.direct_normal_lux <= 0) continue;
      for (const SeenRegion& seen : coefficients[i].regions)
        sun[(h * n + i) * ng + std::size_t(groups.group_of_aperture[std::size_t(seen.aperture)])] +=
            float(direct_sun_lux(scene, seen, s.normal, hour.sun, hour.direct_normal_lux));
    }
  });
  // The blinds rule (blinds_rule, by its counts, which whole_grid makes the whole grid's).
  std::vector<std::uint64_t> lit(hours * ng, 0);
  r.direct_sun.assign(n * hours, 0.0f);
  for (std::size_t h = 0; h < hours; ++h) {
    const float* slice = sun.data() + h * n * ng;
    for (std::size_t i = 0; i < n; ++i) {
      float total = 0;
      for (std::size_t g = 0; g < ng; ++g) {
        total += slice[i * ng + g];
        lit[h * ng + g] += slice[i * ng + g] >= options.blinds_threshold_lux;
      }
      r.direct_sun[i * hours + h] = total;
    }
  }
  // The sun seen directly: in each hour's direct sun, not in the blinds rule (no blinds outdoors).
  if (sees_directly)
    for_each_sensor<int>(n, 16, {}, [&](std::size_t i, int&) {
      for (std::size_t h = 0; h < hours; ++h) {
        const AnnualHour& hour = sky.hours[h];
        if (!hour.sky || hour.direct_normal_lux <= 0) continue;
        for (const SeenRegion& seen : direct_coefficients[i].regions)
          r.direct_sun[i * hours + h] +=
              float(direct_sun_lux(direct->scene, seen, grid.sensors[i].normal, hour.sun, hour.direct_normal_lux));
      }
    });
  std::uint64_t sensors_total = n;
  if (whole_grid) whole_grid(lit, sensors_total);
  if (lit.size() != hours * ng) throw Error("the blinds counts do not match the grid's hours and window groups");
  r.blinds_closed.assign(hours * ng, 0);
  for (std::size_t k = 0; k < hours * ng; ++k)
    r.blinds_closed[k] = blinds_closed(lit[k], sensors_total, options.blinds_sensor_share);
  // Pass 2: sky and sun per group with the blinds, per sensor.
  r.illuminance.assign(n * hours, 0.0f);
  r.max_bound_lux.assign(n, 0.0);
  r.max_bound_relative.assign(n, 0.0);
  // The reflected part's channels: the groups, then the light of surfaces lit outdoors, which
  // enters by every group in proportion to its aperture area.
  std::vector<double> group_area(ng, 0.0);
  double area = 0;
  for (std::size_t a = 0; a < scene.apertures.size(); ++a) {
    const double w = norm(newell_normal(scene.apertures[a].polygon.vertices)) / 2;
    group_area[std::size_t(groups.group_of_aperture[a])] += w;
    area += w;
  }
  if (reflected != nullptr) {
    if (reflected->sensors != n || reflected->hours != hours || reflected->channels != ng + 1 ||
        reflected->outdoors.size() != n)
      throw Error("the reflected hours do not match the grid");
    r.reflections = true;
    r.max_reflection_estimate_lux.assign(n, 0.0);
    r.max_reflection_estimate_relative.assign(n, 0.0);
  }
  std::vector<double> occupied_total(n, 0.0), occupied_reflected(n, 0.0);
  const bool patches = !sky.patches.empty();
  const auto adaptive_counts = for_each_sensor<std::size_t>(n, 4, progress, [&](std::size_t i, std::size_t& adaptive) {
    const Sensor& s = grid.sensors[i];
    const SensorCoefficients& c = coefficients[i];
    const std::size_t size = std::size_t(annual_basis_size(options.degree));
    // The group's own coefficients and regions: the hour through group g alone.
    std::vector<SensorCoefficients> parts(ng);
    std::vector<CircumsolarRule> rules;
    for (std::size_t g = 0; g < ng; ++g) {
      SensorCoefficients& part = parts[g];
      part.sky_direct.assign(c.sky_direct.begin() + std::ptrdiff_t(g * size), c.sky_direct.begin() + std::ptrdiff_t((g + 1) * size));
      part.lambert = {c.lambert[g]};
      part.moment_error = c.moment_error;
      part.pane_spread = c.pane_spread;
      part.min_uz = c.min_uz;
      part.max_uz = c.max_uz;
      for (const SeenRegion& seen : c.regions)
        if (std::size_t(groups.group_of_aperture[std::size_t(seen.aperture)]) == g) part.regions.push_back(seen);
      if (patches) continue;  // the sky by patches: no circumsolar rule
      rules.push_back(circumsolar_rule(scene, s, part));
    }
    // With the sky in patches: each group's patch coefficients, once per sensor.
    std::vector<std::vector<double>> patch_dc;
    std::vector<double> patch_spread(ng, 0.0);
    if (patches)
      for (std::size_t g = 0; g < ng; ++g) {
        patch_dc.emplace_back(sky.patches.size(), 0.0);
        for (const SeenRegion& seen : parts[g].regions)
          add_patch_coefficients(sky.patches, seen.region, s.normal, seen.transmitting(scene), patch_dc[g], patch_spread[g],
                                 seen.sign);
      }
    // The sky seen directly, its rule or patch coefficients as a group's.
    CircumsolarRule direct_rule;
    std::vector<double> direct_patch_dc;
    double direct_patch_spread = 0;
    if (sees_directly) {
      if (patches) {
        direct_patch_dc.assign(sky.patches.size(), 0.0);
        for (const SeenRegion& seen : direct_coefficients[i].regions)
          add_patch_coefficients(sky.patches, seen.region, s.normal, seen.transmitting(direct->scene), direct_patch_dc,
                                 direct_patch_spread, seen.sign);
      } else {
        direct_rule = circumsolar_rule(direct->scene, s, direct_coefficients[i]);
      }
    }
    for (std::size_t h = 0; h < hours; ++h) {
      const AnnualHour& hour = sky.hours[h];
      if (!hour.sky) continue;
      double total = 0, bound = 0;
      if (sees_directly) {
        const HourIlluminance e =
            patches ? patch_hour_illuminance(direct->scene, s, direct_coefficients[i], direct_patch_dc, direct_patch_spread, hour)
                    : hour_illuminance(direct->scene, s, direct_coefficients[i], hour, options, &direct_rule);
        adaptive += e.adaptive;
        total += e.sky_lux + e.sun_lux;
        bound += e.bound_lux;
      }
      for (std::size_t g = 0; g < ng; ++g) {
        const SensorCoefficients& part = parts[g];
        const HourIlluminance e = patches ? patch_hour_illuminance(scene, s, part, patch_dc[g], patch_spread[g], hour)
                                          : hour_illuminance(scene, s, part, hour, options, &rules[g]);
        adaptive += e.adaptive;
        const double factor = r.blinds_closed[h * ng + g] ? options.closed_blind_transmittance : 1.0;
        total += factor * (e.sky_lux + e.sun_lux);
        bound += factor * e.bound_lux;
      }
      if (reflected != nullptr) {
        const float* lux = &reflected->lux[(i * hours + h) * (ng + 1)];
        double part = 0, outdoor_factor = 0;
        for (std::size_t g = 0; g < ng; ++g) {
          const double factor = r.blinds_closed[h * ng + g] ? options.closed_blind_transmittance : 1.0;
          part += factor * lux[g];
          outdoor_factor += area > 0 ? factor * group_area[g] / area : 0;
        }
        // A sensor that sees the sky or the far ground directly (or a model without apertures)
        // takes the light from outdoors as it comes: no window, no blinds. The reflection
        // operator decides it, by df's own test (ReflectionOperator::sensor_outdoors).
        if (reflected->outdoors[i] != 0 || !(area > 0)) outdoor_factor = 1;
        part += outdoor_factor * lux[ng];
        // The estimate with the largest factor of the hour (blinds open where any group is open).
        double largest = 0;
        for (std::size_t g = 0; g < ng; ++g)
          largest = std::max(largest, r.blinds_closed[h * ng + g] ? options.closed_blind_transmittance : 1.0);
        const double estimate = largest * reflected->estimate[i * hours + h];
        total += part;
        r.max_reflection_estimate_lux[i] = std::max(r.max_reflection_estimate_lux[i], estimate);
        // Relative to the hour's illuminance where that is at least 100 lx (UDI's lowest band): at
        // dawn a few lux carry estimates of their own size, which say nothing of the results.
        if (total >= 100)
          r.max_reflection_estimate_relative[i] = std::max(r.max_reflection_estimate_relative[i], estimate / total);
        if (hour.occupied) occupied_reflected[i] += part;
      }
      if (hour.occupied) occupied_total[i] += total;
      r.illuminance[i * hours + h] = float(total);
      if (bound > r.max_bound_lux[i]) r.max_bound_lux[i] = bound;
      if (total > 0) r.max_bound_relative[i] = std::max(r.max_bound_relative[i], bound / total);
    }
  });
  for (std::size_t a : adaptive_counts) r.adaptive_circumsolar += a;
  r.reflected_share = reflected_share(occupied_total, occupied_reflected);
  r.occupied_lux = std::move(occupied_total);
  r.occupied_reflected_lux = std::move(occupied_reflected);
  r.hourly_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  return r;
}

}  // namespace daylit
