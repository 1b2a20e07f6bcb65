#include "simulation/illuminance.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "geometry/error.hpp"
#include "illumination/cap_clip.hpp"
#include "materials/glass_transmittance.hpp"
#include "illumination/moments.hpp"
#include "simulation/pane_transmittance.hpp"
#include "simulation/sensor_loop.hpp"
#include "simulation/sky_component.hpp"

namespace daylit {

namespace {

struct SensorIlluminance {
  double sky = 0, sun = 0, sky_error = 0;
  long evaluations = 0;
  std::size_t regions_by_quadrature = 0;
};

// The pane's unit normal, either side: T depends on |a·u| only, and the glazing closed forms turn
// it towards the region themselves.
Vec3 pane_normal(const Aperture& aperture) { return normalized(newell_normal(aperture.polygon.vertices)); }

// E/L_z from the sky seen in `region` by adaptive cubature of the Perez or CIE general sky's
// relative luminance, with T along each direction (`transmittance`; where empty, the constant
// `scale`), and the cubature's estimate as its bound.
void add_sky_by_cubature(const DaylightConditions& c, const std::function<double(const Vec3&)>& transmittance,
                         double scale, const SphericalRegion& region, const Vec3& n, SensorIlluminance& out) {
  if (c.sky == DaylightConditions::Sky::perez) {
    const QuadratureResult q = perez_sky_irradiance_quadrature(*c.perez, region, n, c.quadrature_tolerance, transmittance);
    out.sky += scale * q.value;
    out.sky_error += scale * q.error_estimate;
    out.evaluations += q.evaluations;
    return;
  }
  const CieQuadrature q = cie_sky_irradiance_quadrature(*c.cie, region, n, c.quadrature_tolerance, transmittance);
  out.sky += scale * q.value;
  out.sky_error += scale * q.error_estimate;
  out.evaluations += q.evaluations;
  out.regions_by_quadrature += transmittance && c.method == DaylightConditions::Method::fit;
}

// E/L_z from the sky seen in `region` through `aperture`, with a bound on its error.
void add_sky(const DaylightConditions& c, const Aperture& aperture, const SphericalRegion& region, const Vec3& n,
             SensorIlluminance& out) {
  const bool glazed = !aperture.angular_transmittance.empty();
  // Glass's T(μ) about the pane's normal, for the skies integrated by cubature.
  std::function<double(const Vec3&)> transmittance;
  if (glazed) {
    const Vec3 a = pane_normal(aperture);
    transmittance = [&aperture, a](const Vec3& u) {
      return evaluate_polynomial(aperture.angular_transmittance, std::abs(dot(a, u)));
    };
  }
  const double scale = glazed ? 1.0 : aperture.transmittance;
  if (c.sky == DaylightConditions::Sky::perez ||
      (c.sky == DaylightConditions::Sky::cie_general && (glazed || c.method == DaylightConditions::Method::quadrature))) {
    add_sky_by_cubature(c, transmittance, scale, region, n, out);
    return;
  }
  if (c.sky != DaylightConditions::Sky::cie_general) {
    const SkyModel model = c.sky == DaylightConditions::Sky::uniform ? SkyModel::uniform : SkyModel::cie_overcast;
    out.sky += glazed ? sky_irradiance_through_glazing(region, n, model, pane_normal(aperture),
                                                       aperture.angular_transmittance)
                      : aperture.transmittance * sky_irradiance(region, n, model);
    return;
  }
  // |fit − L/L_z| ≤ max_error on the hemisphere, so the integral against (n·u) ≥ 0 is off by at
  // most max_error · ∫_A (n·u) dσ.
  out.sky += aperture.transmittance * cie_sky_irradiance(*c.fit, c.cie->sun, region, n);
  out.sky_error += aperture.transmittance * c.fit->max_error * lambert(region, n);
}

// E/L_z from the sky seen through a pane term (pane_transmittance.hpp). Where every pane is
// parallel to the aperture (spread 0) the combined aperture is exact; else each direction takes
// every pane's T at its own cosine: by the cubature of the Perez and CIE general skies, or, for the
// uniform and overcast skies, as df's sky component does (pane_term_sky_irradiance).
void add_pane_term_sky(const DaylightConditions& c, const Scene& scene, const Sensor& sensor, const PaneTerm& term,
                       const SphericalRegion& region, SensorIlluminance& out) {
  if (term.transmittance.spread == 0) {
    add_sky(c, term.transmittance.combined, region, sensor.normal, out);
    return;
  }
  if (c.sky == DaylightConditions::Sky::perez || c.sky == DaylightConditions::Sky::cie_general) {
    const TransmittanceAlong along(scene, term.aperture, term.panes);
    add_sky_by_cubature(c, [&along](const Vec3& u) { return along(u); }, 1.0, region, sensor.normal, out);
    return;
  }
  SensorIlluminance closed;
  add_sky(c, term.transmittance.combined, region, sensor.normal, closed);
  const SkyModel model = c.sky == DaylightConditions::Sky::uniform ? SkyModel::uniform : SkyModel::cie_overcast;
  out.sky += pane_term_sky_irradiance(scene, sensor, model, region, term, closed.sky, out.sky_error);
}

// Direct sunlight through `aperture`: the disk's radiance L_s = E_dn / (π sin²ρ) (a uniform disk of
// angular radius ρ gives E_dn on a surface facing it: Snyder 1996, eq. 6 with the receiver on the
// axis) times ∫ over the visible part of the disk of (n·u) dσ, in closed form (cap_clip.hpp).
// Without the transmittance: the disk's light over the region.
double sun_disk(const DaylightConditions& c, const SphericalRegion& region, const Vec3& n) {
  const double visible = cap_lambert(region, c.sun, c.sun_half_angle, n);
  if (visible == 0) return 0;
  const double sin_rho = std::sin(c.sun_half_angle);
  return c.direct_normal / (std::numbers::pi * sin_rho * sin_rho) * visible;
}

double sun_through(const DaylightConditions& c, const Aperture& aperture, const SphericalRegion& region, const Vec3& n) {
  const double disk = sun_disk(c, region, n);
  if (disk == 0) return 0;
  const double t = aperture.angular_transmittance.empty()
                       ? aperture.transmittance
                       : evaluate_polynomial(aperture.angular_transmittance,
                                             std::abs(dot(pane_normal(aperture), c.sun)));
  return t * disk;
}

SensorIlluminance sensor_illuminance(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor,
                                     const DaylightConditions& c, VisibilityCounters& counters,
                                     const VisibilityEngine* direct) {
  SensorIlluminance out;
  for (std::size_t a = 0; a < engine.aperture_count(); ++a) {
    const ApertureView view = engine.aperture_view(sensor.position, sensor.normal, a, counters);
    if (!view.region.empty()) {
      add_sky(c, scene.apertures[a], view.region, sensor.normal, out);
      if (c.has_sun()) out.sun += sun_through(c, scene.apertures[a], view.region, sensor.normal);
    }
    // Through panes in front as well: the sky with their transmittances and the aperture's
    // (add_pane_term_sky), the sun with each pane's T at the sun.
    for (const PaneView& behind : view.behind) {
      const double disk = c.has_sun() ? sun_disk(c, behind.region, sensor.normal) : 0.0;
      for (const PaneTerm& term : pane_terms(scene, a, behind)) {
        SensorIlluminance part;
        add_pane_term_sky(c, scene, sensor, term, behind.region, part);
        out.sky += term.sign * part.sky;
        out.sky_error += part.sky_error;
        out.evaluations += part.evaluations;
        out.regions_by_quadrature += part.regions_by_quadrature;
        if (disk > 0) out.sun += term.sign * transmittance_along(scene, term.aperture, term.panes, c.sun) * disk;
      }
    }
  }
  // The sky and sun seen directly, past every surface (geometry/sky_box.hpp), unfiltered.
  if (direct) {
    const Aperture open{Polygon{}, 1.0};
    for (std::size_t f = 0; f < direct->aperture_count(); ++f) {
      const SphericalRegion region = direct->visible_region(sensor.position, sensor.normal, f, counters);
      if (region.empty()) continue;
      add_sky(c, open, region, sensor.normal, out);
      if (c.has_sun()) out.sun += sun_disk(c, region, sensor.normal);
    }
  }
  out.sky *= c.zenith_luminance;
  out.sky_error *= c.zenith_luminance;
  if (!std::isfinite(out.sky) || !std::isfinite(out.sun))
    throw Error("non-finite illuminance at sensor (" + std::to_string(sensor.position.x) + ", " +
                std::to_string(sensor.position.y) + ", " + std::to_string(sensor.position.z) +
                ") with float geometry; use --geometry exact");
  return out;
}

}  // namespace

double daylight_irradiance(const DaylightConditions& c, const Aperture* aperture, const SphericalRegion& region,
                           const Vec3& n) {
  if (region.empty()) return 0;
  const Aperture open{Polygon{}, 1.0};
  const Aperture& through = aperture ? *aperture : open;
  SensorIlluminance s;
  add_sky(c, through, region, n, s);
  double e = s.sky * c.zenith_luminance;
  if (c.has_sun()) e += sun_through(c, through, region, n);
  return e;
}

double unobstructed_daylight_lux(const DaylightConditions& c) {
  return c.zenith_luminance * unobstructed_sky_irradiance(c) + (c.has_sun() ? c.direct_normal * c.sun.z : 0.0);
}

double unobstructed_sky_irradiance(const DaylightConditions& c) {
  switch (c.sky) {
    case DaylightConditions::Sky::uniform: return unobstructed_horizontal_irradiance(SkyModel::uniform);
    case DaylightConditions::Sky::cie_overcast: return unobstructed_horizontal_irradiance(SkyModel::cie_overcast);
    case DaylightConditions::Sky::cie_general: break;
    case DaylightConditions::Sky::perez:
      if (!c.perez) throw Error("a Perez sky needs its hour's sky");
      return c.perez->horizontal_irradiance_over_zenith();
  }
  return cie_sky_irradiance_quadrature(*c.cie, sky_hemisphere(), {0, 0, 1}, 1e-12).value;
}

IlluminanceResult illuminance(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid,
                              const DaylightConditions& conditions, const ProgressCallback& progress,
                              const VisibilityEngine* direct) {
  if (!grid.sees_sky_directly) direct = nullptr;
  if (conditions.sky == DaylightConditions::Sky::cie_general &&
      (!conditions.cie || (conditions.method == DaylightConditions::Method::fit && !conditions.fit)))
    throw Error("a CIE general sky needs its type and sun (and its fit for the fit method)");
  if (conditions.sky == DaylightConditions::Sky::perez && !conditions.perez) throw Error("a Perez sky needs its hour's sky");
  IlluminanceResult result;
  const std::size_t count = grid.sensors.size();
  result.sky_lux.assign(count, 0.0);
  result.sun_lux.assign(count, 0.0);
  result.sky_error_lux.assign(count, 0.0);
  struct Local {
    VisibilityCounters counters;
    long evaluations = 0;
    std::size_t regions_by_quadrature = 0;
  };
  const auto locals = for_each_sensor<Local>(count, 16, progress, [&](std::size_t i, Local& local) {
    const SensorIlluminance s = sensor_illuminance(engine, scene, grid.sensors[i], conditions, local.counters, direct);
    result.sky_lux[i] = s.sky;
    result.sun_lux[i] = s.sun;
    result.sky_error_lux[i] = s.sky_error;
    local.evaluations += s.evaluations;
    local.regions_by_quadrature += s.regions_by_quadrature;
  });
  for (const Local& l : locals) {
    result.counters += l.counters;
    result.quadrature_evaluations += l.evaluations;
    result.regions_by_quadrature += l.regions_by_quadrature;
  }
  return result;
}

}  // namespace daylit
