#pragma once
// The sky component of the daylight factor on a sensor grid: the main flow of DESIGN.md §2.

#include <cstddef>
#include <functional>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "simulation/pane_transmittance.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

struct SkyComponentResult {
  std::vector<double> sc_percent;  // per sensor, in grid order
  std::vector<Vec3> sc_gradient;   // per sensor when asked for: ∇_p SC, percent per model unit
  VisibilityCounters counters;
  // The largest over the sensors (DF points) of what the regions seen through glass panes not
  // parallel to the aperture may be off by: the adaptive cubature's error estimate where they are
  // integrated with each pane's T at its own cosine, plus the constant-T bound of the small
  // regions kept in closed form (sky_component.cpp, kPaneBoundKept); 0 where none is.
  double pane_bound_percent = 0;
};

// Called now and then with the number of sensors finished so far (from any thread, serialised).
using ProgressCallback = std::function<void(std::size_t done)>;

// SC = 100 · Σ_apertures E_a / E_out, E_a the sky illuminance through the exact visible region
// of aperture a times its transmittance (constant, or glass's polynomial in the cosine of incidence,
// integrated with it: sky_irradiance_through_glazing). Runs in parallel over sensors (oneTBB,
// as many threads as the caller's arena allows); every sensor is computed independently, so results do not depend on the thread count.
// With `gradient`, also ∇_p SC at every sensor (sky_component_with_gradient).
// `direct`: the sky box's engine (geometry/sky_box.hpp: DirectSky::engine); where the grid sees the
// sky directly (SensorGrid::sees_sky_directly), SC also counts the sky seen past every surface and
// pane, exactly (a façade, a courtyard, a sensor outdoors). nullptr, or another grid: apertures only.
SkyComponentResult sky_component(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid,
                                 SkyModel sky, const ProgressCallback& progress = {}, bool gradient = false,
                                 const VisibilityEngine* direct = nullptr);

// Where panes lie in front of an aperture (VisibilityEngine::aperture_view), the sky seen through
// them too is counted with all their transmittances (pane_transmittance.hpp).
// The same for one sensor (no threading): the sky component in percent, and in `pane_bound_percent`
// the bound of SkyComponentResult::pane_bound_percent at this sensor. `direct` (not nullptr): the
// sky seen directly as well, through its faces.
double sky_component_percent(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor, SkyModel sky,
                             VisibilityCounters& counters, double* pane_bound_percent = nullptr,
                             const VisibilityEngine* direct = nullptr);

// The sky irradiance a PaneTerm gives over its region, before its sign, from the closed form
// `closed` of its combined aperture; what it may be off by is added to `bound`. A glass pane not
// parallel to the aperture makes the product of transmittances a polynomial in two cosines of
// incidence, which the moments about one axis do not take, and taking one factor as constant over
// the region cost up to 9 % (tilted tree-crown panes): there each direction takes every pane's T
// at its own cosine, integrated by adaptive cubature to kPaneTolerance, whose error estimate is
// the bound. (The cubature needs a sun to split at; these skies have none, so the zenith serves.)
// (The illuminance command takes it for the uniform and overcast skies as well.)
double pane_term_sky_irradiance(const Scene& scene, const Sensor& sensor, SkyModel sky, const SphericalRegion& region,
                                const PaneTerm& term, double closed, double& bound);

// The sky component and its gradient with respect to the sensor's position (normal fixed), in
// percent and percent per model unit. The sky's luminance depends on the direction only (times
// the glazing's polynomial in the cosine of incidence), so only the boundary term of Arvo's
// irradiance Jacobian (SIGGRAPH 1994) is there: a polynomial integrated in closed form along
// every edge of the visible region that lies on an aperture or occluder edge
// (illumination/irradiance_gradient.hpp); edges on the horizon and the receiver's plane stay.
// Exact up to rounding: estimated relative error below 1e-7 of |∇SC| (recomputed in long double
// or __float128 where edge terms cancel).
struct SkyComponentPoint {
  double percent = 0;
  Vec3 gradient{};
};
// `direct` as for sky_component_percent: the edges its faces share with each other cancel, so the
// gradient of the sky seen directly comes from the surfaces' edges alone.
SkyComponentPoint sky_component_with_gradient(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor,
                                              SkyModel sky, VisibilityCounters& counters,
                                              const VisibilityEngine* direct = nullptr);

}  // namespace daylit
