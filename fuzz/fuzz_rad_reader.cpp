// Fuzz target: the .rad reader on arbitrary bytes, then what `daylit df` does next with what it
// accepted: the scene's assembly and the exact convex decomposition of every polygon (which finds
// boundaries that cross themselves). Any input must end in content or in a daylit::Error whose
// message names the file and a line; any other exception, crash or sanitizer report is a finding.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "materials/scene_materials.hpp"
#include "geometry/error.hpp"
#include "geometry/rad_reader.hpp"
#include "geometry/scene.hpp"
#include "geometry/visibility.hpp"

namespace {

// "fuzz.rad:<line>: ...", with a line of at least 1.
bool names_file_and_line(const char* message) {
  const char* prefix = "fuzz.rad:";
  if (std::strncmp(message, prefix, std::strlen(prefix)) != 0) return false;
  char* end = nullptr;
  const long line = std::strtol(message + std::strlen(prefix), &end, 10);
  return line >= 1 && *end == ':';
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // The first byte decides whether the file is read as a scene or as an aperture file.
  const bool aperture_file = size > 0 && (data[0] & 1);
  try {
    daylit::RadContent content;
    daylit::read_rad_text(text, "fuzz.rad", aperture_file, content);
    const daylit::Scene scene = daylit::assemble_scene(content);
    const daylit::VisibilityEngine engine(scene, daylit::GeometryMode::exact);
    // Every polygon the reader accepts has a finite, planar outline; the decomposition keeps
    // pieces of at least 3 vertices.
    (void)engine.occluder_piece_count();
  } catch (const daylit::Error& e) {
    if (!names_file_and_line(e.what())) {
      std::fprintf(stderr, "error message lacks file:line: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
