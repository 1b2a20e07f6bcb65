#pragma once
// `daylit sun`: the sun's topocentric zenith and azimuth at a site and an instant (NREL's SPA,
// sky/solar_position.hpp), as one line of JSON.

#include <functional>

namespace CLI {
class App;  // CLI11 (<CLI/CLI.hpp>) is included only where options are declared and parsed
}  // namespace CLI

namespace daylit::cli {

// Registers the subcommand; returns a function that runs it after parsing.
std::function<int()> add_sun_command(CLI::App& app);

}  // namespace daylit::cli
