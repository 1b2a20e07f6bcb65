#pragma once
// `daylit illuminance`: illuminance (lux) on sensor grids under a CIE sky and the sun at a given
// site and time.

#include <functional>

namespace CLI {
class App;  // CLI11 (<CLI/CLI.hpp>) is included only where options are declared and parsed
}  // namespace CLI

namespace daylit::cli {

// Registers the subcommand; returns a function that runs it after parsing.
std::function<int()> add_illuminance_command(CLI::App& app);

}  // namespace daylit::cli
