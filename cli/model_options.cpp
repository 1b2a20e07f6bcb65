#include "cli/model_options.hpp"

#include <CLI/CLI.hpp>

#include "simulation/model_inputs.hpp"

namespace daylit::cli {

void add_model_options(CLI::App& command, ModelFiles& files) {
  command.add_option("--model", files.model,
                     "A Honeybee model: an HBJSON file, or a Honeybee Radiance folder (the folder holding model/, as "
                     "model-to-rad-folder writes it). Its rooms, apertures, doors and shades with their modifiers "
                     "(Honeybee's defaults where none is assigned), and its sensor grids unless --grid is given; "
                     "--scene and --apertures files are added to it")
      ->check(CLI::ExistingPath);
  command.add_option("--bsdf-transmittance", files.bsdf_transmittance,
                     "Uniform visible transmittance (0 to 1) for apertures of Radiance's BSDF/aBSDF type, whose angular "
                     "data daylit does not read (without it such an aperture is an error)")
      ->check(CLI::Range(0.0, 1.0));
  // Sensors come from --grid or from the model: without either the command line is incomplete,
  // a usage error (exit code 2, README "Exit codes"), found when parsing ends.
  CLI::App* app = &command;
  command.parse_complete_callback([app] {
    if (app->count("--grid") == 0 && app->count("--model") == 0)
      throw CLI::RequiredError("--grid or --model (the sensors come from a grid file or from the model)");
  });
}

}  // namespace daylit::cli
