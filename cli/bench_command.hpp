#pragma once
// `daylit bench SUITE`: error against run time of the approximate paths beside the exact ones, on
// the same cases, as CSV tables and log–log plots a reader can open (DESIGN.md §6). Suites:
// `kernels` (the moment kernels against early termination and Monte Carlo), `scenes` (the samples:
// exact and float geometry, Monte Carlo, cubature; scaling) and `stiff` (stiff scenes against
// independent references); see bench_suites.hpp.

#include <functional>

namespace CLI {
class App;  // CLI11 (<CLI/CLI.hpp>) is included only where options are declared and parsed
}  // namespace CLI

namespace daylit::cli {

// Registers `bench` and its suites; returns a function that runs the suite named after parsing.
std::function<int()> add_bench_command(CLI::App& app);

}  // namespace daylit::cli
