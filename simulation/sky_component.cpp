#include "simulation/sky_component.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "illumination/irradiance_gradient.hpp"
#include "simulation/pane_transmittance.hpp"
#include "simulation/sensor_loop.hpp"
#include "sky/sky_quadrature.hpp"

namespace daylit {

namespace {

// Tolerance of the gradient relative to its size. Gradients feed error estimates of grids, for
// which seven digits are more than enough. Double carries them except where edge terms cancel
// strongly: the glazing polynomial's fitted coefficients (up to 1e5 in size, alternating) cost
// five digits in every evaluation, so a tighter target would send every glazed pair to long
// double (about 30 times slower) for digits nobody uses.
constexpr double kGradientTolerance = 1e-7;

// Relative tolerance of the cubature over regions seen through panes at different angles
// (sky_component_percent). The glass fit itself is good to about 1e-3 (materials' degree-12 fit),
// so tighter would buy no accuracy, only time; looser would let the cubature's error, not the
// stated fit error, set the result's.
constexpr double kPaneTolerance = 1e-6;
// A region whose constant-T bound is below this (irradiance per unit zenith luminance: 4e-5 DF
// points under the overcast sky) keeps the closed form with its bound: the slivers of a region
// cut by many panes (a tree crown of 361-gons, thousands of regions per sensor) would cost the
// cubature minutes and change the result by less than their bounds' sum, which is reported.
constexpr double kPaneBoundKept = 1e-6;

// Only the float path can get here with a non-finite value (a division its rounding made zero);
// never report it as a result.
Error non_finite(const Sensor& sensor) {
  return Error("non-finite sky component at sensor (" + std::to_string(sensor.position.x) + ", " +
               std::to_string(sensor.position.y) + ", " + std::to_string(sensor.position.z) +
               ") with float geometry; use --geometry exact");
}

}  // namespace

double pane_term_sky_irradiance(const Scene& scene, const Sensor& sensor, SkyModel sky, const SphericalRegion& region,
                                const PaneTerm& term, double closed, double& bound) {
  if (term.transmittance.spread * std::abs(closed) <= kPaneBoundKept) {
    bound += term.transmittance.spread * std::abs(closed);
    return closed;
  }
  const TransmittanceAlong transmittance(scene, term.aperture, term.panes);
  const QuadratureResult q = sky_irradiance_quadrature([&](const Vec3& u) { return sky_relative_luminance(sky, u); },
                                                       Vec3{0, 0, 1}, region, sensor.normal, kPaneTolerance, transmittance);
  bound += q.error_estimate;
  return q.value;
}


SkyComponentPoint sky_component_with_gradient(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor,
                                              SkyModel sky, VisibilityCounters& counters, const VisibilityEngine* direct) {
  VisibilityOptions options;
  options.edge_sources = true;
  double irradiance = 0;
  Vec3 gradient{};
  // The sky's luminance as DirectionalRadiance: uniform L = 1; overcast (1 + 2 u_z)/3.
  DirectionalRadiance L;
  if (sky == SkyModel::cie_overcast) {
    L.alpha = 1.0 / 3;
    L.beta = {0, 0, 2.0 / 3};
  }
  // A region's part, negated for a count taken back (PaneView, sign −1). The irradiance of a pane
  // term is sky_component_percent's (pane_term_sky_irradiance); its gradient takes the combined
  // aperture's closed form (a pane at another angle as constant over the region).
  double unused_bound = 0;
  const auto add = [&](const SphericalRegion& region, const Aperture& aperture, double sign = 1,
                       const PaneTerm* term = nullptr) {
    double e;
    Vec3 g;
    if (aperture.angular_transmittance.empty()) {
      e = aperture.transmittance * sky_irradiance(region, sensor.normal, sky);
      L.c = {1};
      g = aperture.transmittance *
          directional_irradiance_gradient(region, sensor.position, sensor.normal, L, kGradientTolerance).value;
    } else {
      // The pane's normal turned to face the region, as sky_irradiance_through_glazing does.
      Vec3 pane = normalized(newell_normal(aperture.polygon.vertices));
      Vec3 inside{};
      for (const Vec3& u : region.loops.front()) inside += normalized(u);
      if (dot(pane, inside) < 0) pane = -1.0 * pane;
      e = sky_irradiance_through_glazing(region, sensor.normal, sky, pane, aperture.angular_transmittance);
      L.axis = pane;
      L.c = aperture.angular_transmittance;
      g = directional_irradiance_gradient(region, sensor.position, sensor.normal, L, kGradientTolerance).value;
    }
    if (term) e = pane_term_sky_irradiance(scene, sensor, sky, region, *term, e, unused_bound);
    irradiance += sign * e;
    gradient += sign * g;
  };
  for (std::size_t a = 0; a < engine.aperture_count(); ++a) {
    const ApertureView view = engine.aperture_view(sensor.position, sensor.normal, a, counters, options);
    if (!view.region.empty()) add(view.region, scene.apertures[a]);
    for (const PaneView& behind : view.behind)
      for (const PaneTerm& term : pane_terms(scene, a, behind))
        add(behind.region, term.transmittance.combined, term.sign, &term);
  }
  if (direct) {
    const Aperture open{Polygon{}, 1.0};
    for (std::size_t f = 0; f < direct->aperture_count(); ++f) {
      const SphericalRegion region = direct->visible_region(sensor.position, sensor.normal, f, counters, options);
      if (!region.empty()) add(region, open);
    }
  }
  // The same expression as sky_component_percent's, so that the two agree to the last bit.
  const double e_out = unobstructed_horizontal_irradiance(sky);
  const SkyComponentPoint point{100 * irradiance / e_out, (100 / e_out) * gradient};
  if (!std::isfinite(point.percent) || !is_finite(point.gradient)) throw non_finite(sensor);
  return point;
}

double sky_component_percent(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor, SkyModel sky,
                             VisibilityCounters& counters, double* pane_bound_percent, const VisibilityEngine* direct) {
  const auto through = [&](const SphericalRegion& region, const Aperture& aperture) {
    if (aperture.angular_transmittance.empty()) return aperture.transmittance * sky_irradiance(region, sensor.normal, sky);
    return sky_irradiance_through_glazing(region, sensor.normal, sky, normalized(newell_normal(aperture.polygon.vertices)),
                                          aperture.angular_transmittance);
  };
  double irradiance = 0, bound = 0;
  for (std::size_t a = 0; a < engine.aperture_count(); ++a) {
    const ApertureView view = engine.aperture_view(sensor.position, sensor.normal, a, counters);
    if (!view.region.empty()) irradiance += through(view.region, scene.apertures[a]);
    for (const PaneView& behind : view.behind)
      for (const PaneTerm& term : pane_terms(scene, a, behind))
        irradiance += term.sign * pane_term_sky_irradiance(scene, sensor, sky, behind.region, term,
                                                       through(behind.region, term.transmittance.combined), bound);
  }
  if (direct)
    for (std::size_t f = 0; f < direct->aperture_count(); ++f) {
      const SphericalRegion region = direct->visible_region(sensor.position, sensor.normal, f, counters);
      if (!region.empty()) irradiance += sky_irradiance(region, sensor.normal, sky);
    }
  const double e_out = unobstructed_horizontal_irradiance(sky);
  const double percent = 100 * irradiance / e_out;
  if (!std::isfinite(percent)) throw non_finite(sensor);
  if (pane_bound_percent) *pane_bound_percent = 100 * bound / e_out;
  return percent;
}

SkyComponentResult sky_component(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid,
                                 SkyModel sky, const ProgressCallback& progress, bool gradient,
                                 const VisibilityEngine* direct) {
  SkyComponentResult result;
  if (!grid.sees_sky_directly) direct = nullptr;
  const std::size_t count = grid.sensors.size();
  result.sc_percent.assign(count, 0.0);
  if (gradient) result.sc_gradient.assign(count, Vec3{});
  struct Local {
    VisibilityCounters counters;
    double pane_bound_percent = 0;
  };
  const auto counters = for_each_sensor<Local>(count, 64, progress, [&](std::size_t i, Local& local) {
    if (gradient) {
      const SkyComponentPoint point = sky_component_with_gradient(engine, scene, grid.sensors[i], sky, local.counters, direct);
      result.sc_percent[i] = point.percent;
      result.sc_gradient[i] = point.gradient;
    } else {
      double bound = 0;
      result.sc_percent[i] = sky_component_percent(engine, scene, grid.sensors[i], sky, local.counters, &bound, direct);
      local.pane_bound_percent = std::max(local.pane_bound_percent, bound);
    }
  });
  for (const auto& c : counters) {
    result.counters += c.counters;
    result.pane_bound_percent = std::max(result.pane_bound_percent, c.pane_bound_percent);
  }
  return result;
}

}  // namespace daylit
