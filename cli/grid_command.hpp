#pragma once
// `daylit grid`: sensor grids on the floors of rooms (simulation/floor_grid.hpp), written as .pts.

#include <functional>

namespace CLI {
class App;  // CLI11 (<CLI/CLI.hpp>) is included only where options are declared and parsed
}  // namespace CLI

namespace daylit::cli {

// Registers the subcommand; returns a function that runs it after parsing.
std::function<int()> add_grid_command(CLI::App& app);

}  // namespace daylit::cli
