#pragma once
// `daylit eval`: exact point evaluations of the kernels, JSON Lines in and out.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace daylit::cli {

std::function<int()> add_eval_command(CLI::App& app);

// The answer to one query line (without its newline), as one line of JSON: {"id": …, "value": v}
// or {"id": …, "error": "…"}. Input errors (invalid JSON, nesting beyond 64 levels) name `where`
// ("file:line"). Never throws for any input; used by `daylit eval` and its fuzz target.
std::string answer_line(const std::string& line, const std::string& where);

}  // namespace daylit::cli
