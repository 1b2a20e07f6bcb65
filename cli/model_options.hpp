#pragma once
// The options that `daylit df` and `daylit illuminance` share for models users already have:
// --model (an HBJSON file, a Honeybee Radiance folder, or an OBJ model with --obj-materials,
// --obj-scale and --obj-up) and --bsdf-transmittance.

namespace CLI {
class App;
}

namespace daylit {
struct ModelFiles;
}

namespace daylit::cli {

// Adds --model, the OBJ options and --bsdf-transmittance to `command`, which must already have --grid, and requires
// one of --grid and --model when parsing completes.
void add_model_options(CLI::App& command, ModelFiles& files);

}  // namespace daylit::cli
