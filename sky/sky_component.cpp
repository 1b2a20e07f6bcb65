#include "sky/sky_component.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <string>
#include <mutex>

namespace daylit {

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
  // Only the float path can get here with a non-finite value (a division its rounding made
  // zero); never report it as a result.
  if (!std::isfinite(percent))
    throw Error("non-finite sky component at sensor (" + std::to_string(sensor.position.x) + ", " +
                std::to_string(sensor.position.y) + ", " + std::to_string(sensor.position.z) +
                ") with float geometry; use --geometry exact");
  return percent;
}

SkyComponentResult sky_component(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid,
                                 SkyModel sky, const ProgressCallback& progress) {
  SkyComponentResult result;
  const std::size_t count = grid.sensors.size();
  result.sc_percent.assign(count, 0.0);
  tbb::enumerable_thread_specific<VisibilityCounters> counters;
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 64), [&](const tbb::blocked_range<std::size_t>& range) {
    VisibilityCounters& local = counters.local();
    for (std::size_t i = range.begin(); i != range.end(); ++i)
      result.sc_percent[i] = sky_component_percent(engine, scene, grid.sensors[i], sky, local);
    const std::size_t now = done += range.size();
    if (progress) {
      std::unique_lock lock(progress_mutex, std::try_to_lock);
      if (lock) progress(now);
    }
  });
  for (const auto& c : counters) result.counters += c;
  if (progress) progress(count);
  return result;
}

}  // namespace daylit
