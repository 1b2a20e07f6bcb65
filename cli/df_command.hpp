#pragma once
// `daylit df`: daylight factors on sensor grids of building models.

#include <CLI/CLI.hpp>

namespace daylit::cli {

// Registers the subcommand; returns a function that runs it after parsing.
std::function<int()> add_df_command(CLI::App& app);

}  // namespace daylit::cli
