#pragma once
// `daylit eval`: exact point evaluations of the kernels, JSON Lines in and out.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace daylit::cli {

std::function<int()> add_eval_command(CLI::App& app);

}  // namespace daylit::cli
