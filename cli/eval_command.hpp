#pragma once
// `daylit eval`: exact point evaluations of the kernels, JSON Lines in and out.

#include <functional>
#include <string>

namespace CLI {
class App;  // CLI11 (<CLI/CLI.hpp>) is included only where options are declared and parsed
}  // namespace CLI

namespace daylit::cli {

std::function<int()> add_eval_command(CLI::App& app);

}  // namespace daylit::cli
