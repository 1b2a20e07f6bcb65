// Fuzz target: the context-building reader (GeoJSON footprints, sky/context_buildings.hpp) on
// arbitrary bytes, placed with a fixed site, and what `daylit df` does next with the faces: the
// exact convex decomposition. Any input must end in buildings with finite faces or in a
// daylit::Error naming the file.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "geometry/error.hpp"
#include "geometry/visibility.hpp"
#include "sky/context_buildings.hpp"
#include "sky/site.hpp"

namespace {

[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "%s: %s\n", what, detail.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const daylit::Site site = daylit::parse_site_json(
      R"({"latitude_deg": 41.3925, "longitude_deg": 2.164, "elevation_m": 95.0, "north_deg": 45.0})", "site.json");
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const daylit::ContextBuildings context = daylit::parse_context_buildings(text, "fuzz.geojson", site);
    daylit::Scene scene;
    for (const auto& building : context.buildings)
      for (const auto& face : building.faces) {
        for (const auto& v : face.vertices)
          if (!daylit::is_finite(v)) finding("non-finite face vertex", building.label);
        scene.occluders.push_back(face);
      }
    const daylit::VisibilityEngine engine(scene, daylit::GeometryMode::exact);
    (void)engine.occluder_piece_count();
  } catch (const daylit::Error& e) {
    if (std::string(e.what()).find("fuzz.geojson") == std::string::npos) finding("error message lacks the file", e.what());
  }
  return 0;
}
