#pragma once
// The reflected components' command-line options, shared by `daylit df` and `daylit
// illuminance`: --components, --ground-reflectance, --reflection-tolerance, --element-size,
// --max-refinements, --element-grading and --reflection-transport; what they become for simulation/reflected_components.hpp; the summary's
// `components` section; the notice for options given where they do not apply.

#include <CLI/CLI.hpp>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "materials/surface_reflectance.hpp"
#include "simulation/reflected_components.hpp"

namespace daylit::cli {

struct ReflectionCliOptions {
  // The sky component alone by default: the radiosity is fast on rooms (the room sample in 1.6 s)
  // but not yet on models whose many rooms share planes (a 7-room Honeybee house: 3.4 minutes at
  // element size 3, against 0.08 s for SC; README, "Known limits").
  std::string components = "sc";
  double ground_reflectance = 0.2;
  double tolerance = 0.05;  // percentage points of E_out (DF points), every sensor's ERC + IRC
  double element_size = 0;  // model units; 0: automatic (reflected_components.hpp)
  int max_refinements = 2;
  double grading = 0.5;     // farther from the sensors and apertures: edge ≤ grading × distance
  std::string transport = "reciprocal";  // or "collocated" (reciprocal_transport.hpp)
  std::vector<const CLI::Option*> options;  // those beside --components, for the notice

  bool all() const { return components == "all"; }
};

// Registers the options on `command`; `what` names the quantity ("DF" or "illuminance").
void add_reflection_options(CLI::App& command, ReflectionCliOptions& options, const std::string& what);

// The options as reflected_components() takes them (sky and light are the caller's).
ReflectionOptions reflection_options(const ReflectionCliOptions& options);

// With --components sc, a notice for each reflection option given (it would be ignored), and one
// for the scene's reflecting materials, whose reflectances the sky component does not use.
void notice_unused_reflection_options(const ReflectionCliOptions& options, bool quiet, const Scene& scene);

// A progress bar per stage of the radiosity (ReflectionOptions::on_progress), drawn where `shown`.
std::function<void(const std::string&, const std::string&, std::size_t, std::size_t)> reflection_progress_bars(
    bool shown);

// The summary's `components` section for a run with reflections; `unit` says what the energy
// balance's fluxes are per ("per unit zenith luminance", "lux").
nlohmann::json reflection_summary(const ReflectionResult& r, const std::map<std::string, SurfaceReflectance>& materials,
                                  const ReflectionCliOptions& opt, double run_time_s, const std::string& unit);

}  // namespace daylit::cli
