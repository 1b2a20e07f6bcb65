// Fuzz target: the OBJ and .mtl readers on arbitrary bytes, then what `daylit df` does next with
// what they accepted: the faces' roles (materials/obj_materials.hpp), the scene's assembly and the
// exact convex decomposition of every polygon. The input is an .obj text, optionally followed by
// a line "#mtl" and the text of the library fuzz.mtl (which the .obj names with `mtllib fuzz.mtl`;
// any other library is missing). The first byte's low bit reads the file y up in millimetres.
// Any input must end in a scene or in a daylit::Error whose message names fuzz.obj or fuzz.mtl
// and a line; any other exception, crash or sanitizer report is a finding.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "geometry/error.hpp"
#include "geometry/obj_model.hpp"
#include "geometry/scene.hpp"
#include "geometry/visibility.hpp"
#include "materials/obj_materials.hpp"
#include "materials/scene_materials.hpp"

namespace {

// "fuzz.obj:<line>: ..." or "fuzz.mtl:<line>: ...", with a line of at least 1.
bool names_file_and_line(const char* message) {
  for (const char* prefix : {"fuzz.obj:", "fuzz.mtl:"}) {
    if (std::strncmp(message, prefix, std::strlen(prefix)) != 0) continue;
    char* end = nullptr;
    const long line = std::strtol(message + std::strlen(prefix), &end, 10);
    return line >= 1 && *end == ':';
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find("\n#mtl\n");
  const std::string obj = input.substr(0, split);
  const std::string mtl = split == std::string::npos ? std::string() : input.substr(split + 6);
  daylit::ObjOptions options;
  if (size > 0 && (data[0] & 1)) {
    options.up = daylit::ObjUpAxis::y;
    options.metres_per_unit = 0.001;
  }
  try {
    const daylit::ObjModel model =
        daylit::parse_obj(obj, "fuzz.obj", options, [&](const std::string& name) -> std::optional<std::pair<std::string, std::string>> {
          if (name != "fuzz.mtl" || split == std::string::npos) return std::nullopt;
          return std::pair{std::string("fuzz.mtl"), mtl};
        });
    const daylit::Scene scene = daylit::assemble_scene(daylit::obj_rad_content(model));
    const daylit::VisibilityEngine engine(scene, daylit::GeometryMode::exact);
    (void)engine.occluder_piece_count();
  } catch (const daylit::Error& e) {
    if (!names_file_and_line(e.what())) {
      std::fprintf(stderr, "error message lacks file:line: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
