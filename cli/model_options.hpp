#pragma once
// The options that `daylit df` and `daylit illuminance` share for models users already have:
// --model (an HBJSON file or a Honeybee Radiance folder) and --bsdf-transmittance.

namespace CLI {
class App;
}

namespace daylit {
struct ModelFiles;
}

namespace daylit::cli {

// Adds --model and --bsdf-transmittance to `command`, which must already have --grid, and requires
// one of --grid and --model when parsing completes.
void add_model_options(CLI::App& command, ModelFiles& files);

}  // namespace daylit::cli
