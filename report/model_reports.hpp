#pragma once
// The summary sections that describe a model: its site, the context buildings placed and left out,
// the scene (occluders, apertures, notices) and what the visibility routine did.

#include <string>

#include <nlohmann/json.hpp>

#include "geometry/scene.hpp"
#include "geometry/visibility.hpp"
#include "sky/context_buildings.hpp"
#include "simulation/daylight_criteria.hpp"
#include "sky/site.hpp"

namespace daylit::cli {

nlohmann::json site_json(const Site& site, const std::string& path);
nlohmann::json context_json(const ContextPlacement& context, const std::string& path);
nlohmann::json scene_json(const Scene& scene, const VisibilityEngine& engine);
nlohmann::json counters_json(const VisibilityCounters& c);
// The summary block of EN 17037's daylight-factor method (simulation/daylight_criteria.hpp).
nlohmann::json en17037_json(const En17037Assessment& a);
// BREEAM Hea 01's figures (simulation/daylight_criteria.hpp); `df_is` says what the DF holds.
nlohmann::json breeam_json(const BreeamHea01& b, const std::string& df_is);

}  // namespace daylit::cli
