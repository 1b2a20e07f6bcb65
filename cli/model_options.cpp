#include "cli/model_options.hpp"

#include <CLI/CLI.hpp>

#include "cli/number_checks.hpp"
#include "simulation/model_inputs.hpp"

namespace daylit::cli {

void add_model_options(CLI::App& command, ModelFiles& files) {
  command.add_option("--model", files.model,
                     "A Honeybee model: an HBJSON file, or a Honeybee Radiance folder (the folder holding model/, as "
                     "model-to-rad-folder writes it). Its rooms, apertures, doors and shades with their modifiers "
                     "(Honeybee's defaults where none is assigned), and its sensor grids unless --grid is given. Or a "
                     "Wavefront OBJ model (a path ending in .obj) with the .mtl files it names, which needs --grid (see "
                     "--obj-materials, --obj-scale, --obj-up). --scene and --apertures files are added to it")
      ->check(CLI::ExistingPath);
  command.add_option("--obj-materials", files.obj_materials,
                     "With an OBJ --model: a JSON map from material and group names (or * and ? patterns) to roles, "
                     "{\"materials\": {\"Glass\": {\"role\": \"glass\", \"transmittance\": 0.7}, \"Wall\": {\"role\": "
                     "\"opaque\", \"reflectance\": 0.5}, \"Tree\": {\"role\": \"ignore\"}}, \"groups\": {...}, "
                     "\"aperture_groups\": [\"Window*\"]}. Roles: opaque (reflectance), aperture (constant "
                     "transmittance), glass (Radiance's angular glass: transmittance or transmissivity, refractive_index), "
                     "ignore. Without it: .mtl materials with d < 1 are apertures, the rest opaque with their Kd")
      ->check(CLI::ExistingFile);
  command.add_option("--obj-scale", files.obj.metres_per_unit,
                     "With an OBJ --model: metres per unit of the file (default 1; millimetres: 0.001, inches: 0.0254). "
                     "--grid, --site and --context are in metres")
      ->check(positive_number());
  command
      .add_option_function<std::string>(
          "--obj-up", [&files](const std::string& up) { files.obj.up = up == "y" ? ObjUpAxis::y : ObjUpAxis::z; },
          "With an OBJ --model: the file's up axis, z (default: as written) or y ((x, y, z) becomes (x, -z, y): "
          "Blender writes y up by default, SketchUp with Swap YZ, 3ds Max with Flip YZ-axis)")
      ->check(CLI::IsMember({"z", "y"}));
  command.add_option("--bsdf-transmittance", files.bsdf_transmittance,
                     "Uniform visible transmittance (0 to 1) for apertures of Radiance's BSDF/aBSDF type, whose angular "
                     "data daylit does not read (without it such an aperture is an error)")
      ->check(number_in(0.0, 1.0));
  // Sensors come from --grid or from the model: without either the command line is incomplete,
  // a usage error (exit code 2, README "Exit codes"), found when parsing ends.
  CLI::App* app = &command;
  command.parse_complete_callback([app] {
    if (app->count("--grid") == 0 && app->count("--model") == 0)
      throw CLI::RequiredError("--grid or --model (the sensors come from a grid file or from the model)");
    // The OBJ options describe an OBJ file: given for another model (or none), a usage error.
    const std::string model = app->count("--model") ? app->get_option("--model")->as<std::string>() : std::string();
    for (const char* o : {"--obj-materials", "--obj-scale", "--obj-up"})
      if (app->count(o) && !is_obj_path(model))
        throw CLI::ValidationError(o, "applies to an OBJ model: a --model ending in .obj");
  });
}

}  // namespace daylit::cli
