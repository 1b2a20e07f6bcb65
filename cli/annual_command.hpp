#pragma once
// `daylit annual`: a year of hourly illuminance under the Perez sky and the sun from a weather
// file, on the sensor grids of `daylit df`'s models, and the climate-based metrics from it.

#include <functional>

namespace CLI {
class App;  // CLI11 (<CLI/CLI.hpp>) is included only where options are declared and parsed
}  // namespace CLI

namespace daylit::cli {

// Registers the subcommand; returns a function that runs it after parsing.
std::function<int()> add_annual_command(CLI::App& app);

}  // namespace daylit::cli
