#pragma once
// The sky component of the daylight factor on a sensor grid: the main flow of DESIGN.md §2.

#include <cstddef>
#include <functional>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

struct SkyComponentResult {
  std::vector<double> sc_percent;  // per sensor, in grid order
  VisibilityCounters counters;
};

// Called now and then with the number of sensors finished so far (from any thread, serialised).
using ProgressCallback = std::function<void(std::size_t done)>;

// SC = 100 · Σ_apertures E_a / E_out, E_a the sky illuminance through the exact visible region
// of aperture a times its transmittance (constant, or glass's polynomial in the cosine of incidence,
// integrated with it: sky_irradiance_through_glazing). Runs in parallel over sensors (oneTBB,
// as many threads as the caller's arena allows); every sensor is computed independently, so results do not depend on the thread count.
SkyComponentResult sky_component(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid,
                                 SkyModel sky, const ProgressCallback& progress = {});

// The same for one sensor (no threading): the sky component in percent.
double sky_component_percent(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor, SkyModel sky,
                             VisibilityCounters& counters);

}  // namespace daylit
