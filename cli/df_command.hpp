#pragma once
// `daylit df`: daylight factors on sensor grids of building models.

#include <functional>

namespace CLI {
class App;  // CLI11 (<CLI/CLI.hpp>) is included only where options are declared and parsed
}  // namespace CLI

namespace daylit::cli {

// Registers the subcommand; returns a function that runs it after parsing.
std::function<int()> add_df_command(CLI::App& app);

}  // namespace daylit::cli
