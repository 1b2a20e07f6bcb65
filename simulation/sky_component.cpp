#include "simulation/sky_component.hpp"

#include <cmath>
#include <string>

#include "illumination/irradiance_gradient.hpp"
#include "simulation/sensor_loop.hpp"

namespace daylit {

namespace {

// Tolerance of the gradient relative to its size. Gradients feed error estimates of grids, for
// which seven digits are more than enough. Double carries them except where edge terms cancel
// strongly: the glazing polynomial's fitted coefficients (up to 1e5 in size, alternating) cost
// five digits in every evaluation, so a tighter target would send every glazed pair to long
// double (about 30 times slower) for digits nobody uses.
constexpr double kGradientTolerance = 1e-7;

// Only the float path can get here with a non-finite value (a division its rounding made zero);
// never report it as a result.
Error non_finite(const Sensor& sensor) {
  return Error("non-finite sky component at sensor (" + std::to_string(sensor.position.x) + ", " +
               std::to_string(sensor.position.y) + ", " + std::to_string(sensor.position.z) +
               ") with float geometry; use --geometry exact");
}

}  // namespace

SkyComponentPoint sky_component_with_gradient(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor,
                                              SkyModel sky, VisibilityCounters& counters) {
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
  for (std::size_t a = 0; a < engine.aperture_count(); ++a) {
    const SphericalRegion region = engine.visible_region(sensor.position, sensor.normal, a, counters, options);
    if (region.empty()) continue;
    const Aperture& aperture = scene.apertures[a];
    if (aperture.angular_transmittance.empty()) {
      irradiance += aperture.transmittance * sky_irradiance(region, sensor.normal, sky);
      L.c = {1};
      gradient += aperture.transmittance *
                  directional_irradiance_gradient(region, sensor.position, sensor.normal, L, kGradientTolerance).value;
    } else {
      // The pane's normal turned to face the region, as sky_irradiance_through_glazing does.
      Vec3 pane = normalized(newell_normal(aperture.polygon.vertices));
      Vec3 inside{};
      for (const Vec3& u : region.loops.front()) inside += normalized(u);
      if (dot(pane, inside) < 0) pane = -1.0 * pane;
      irradiance += sky_irradiance_through_glazing(region, sensor.normal, sky, pane, aperture.angular_transmittance);
      L.axis = pane;
      L.c = aperture.angular_transmittance;
      gradient += directional_irradiance_gradient(region, sensor.position, sensor.normal, L, kGradientTolerance).value;
    }
  }
  // The same expression as sky_component_percent's, so that the two agree to the last bit.
  const double e_out = unobstructed_horizontal_irradiance(sky);
  const SkyComponentPoint point{100 * irradiance / e_out, (100 / e_out) * gradient};
  if (!std::isfinite(point.percent) || !is_finite(point.gradient)) throw non_finite(sensor);
  return point;
}

double sky_component_percent(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor, SkyModel sky,
                             VisibilityCounters& counters) {
  double irradiance = 0;
  for (std::size_t a = 0; a < engine.aperture_count(); ++a) {
    const SphericalRegion region = engine.visible_region(sensor.position, sensor.normal, a, counters);
    if (region.empty()) continue;
    const Aperture& aperture = scene.apertures[a];
    if (aperture.angular_transmittance.empty())
      irradiance += aperture.transmittance * sky_irradiance(region, sensor.normal, sky);
    else
      irradiance += sky_irradiance_through_glazing(region, sensor.normal, sky, normalized(newell_normal(aperture.polygon.vertices)),
                                                   aperture.angular_transmittance);
  }
  const double percent = 100 * irradiance / unobstructed_horizontal_irradiance(sky);
  if (!std::isfinite(percent)) throw non_finite(sensor);
  return percent;
}

SkyComponentResult sky_component(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid,
                                 SkyModel sky, const ProgressCallback& progress, bool gradient) {
  SkyComponentResult result;
  const std::size_t count = grid.sensors.size();
  result.sc_percent.assign(count, 0.0);
  if (gradient) result.sc_gradient.assign(count, Vec3{});
  const auto counters = for_each_sensor<VisibilityCounters>(count, 64, progress, [&](std::size_t i, VisibilityCounters& local) {
    if (gradient) {
      const SkyComponentPoint point = sky_component_with_gradient(engine, scene, grid.sensors[i], sky, local);
      result.sc_percent[i] = point.percent;
      result.sc_gradient[i] = point.gradient;
    } else {
      result.sc_percent[i] = sky_component_percent(engine, scene, grid.sensors[i], sky, local);
    }
  });
  for (const auto& c : counters) result.counters += c;
  return result;
}

}  // namespace daylit
