// daylit: exact daylight factors and illuminance in building models.

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "cli/annual_command.hpp"
#include "cli/bench_command.hpp"
#include "cli/df_command.hpp"
#include "cli/eval_command.hpp"
#include "cli/grid_command.hpp"
#include "cli/illuminance_command.hpp"
#include "cli/sun_command.hpp"
#include "geometry/error.hpp"

int main(int argc, char** argv) {
  CLI::App app("daylit: exact daylight factors. Windows are clipped against the geometry in exact\n"
               "arithmetic and the sky is integrated over what stays visible in closed form.");
  app.require_subcommand(1);
  // Argument errors read like every other error: "error: --site: latitude 95 is not within …".
  app.failure_message([](const CLI::App* a, const CLI::Error& e) { return "error: " + CLI::FailureMessage::simple(a, e); });
  auto run_df = daylit::cli::add_df_command(app);
  auto run_illuminance = daylit::cli::add_illuminance_command(app);
  auto run_eval = daylit::cli::add_eval_command(app);
  auto run_bench = daylit::cli::add_bench_command(app);
  auto run_sun = daylit::cli::add_sun_command(app);
  auto run_grid = daylit::cli::add_grid_command(app);
  auto run_annual = daylit::cli::add_annual_command(app);
  // Exit codes, a contract for scripts (README, "Exit codes"): 0 success (and --help), 1 input
  // that cannot be used (a file, a line, a value in it), 2 a command line that cannot be parsed
  // (unknown or missing option, a value an option refuses), 3 an internal error.
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    app.exit(e);                                      // prints "error: ..." and the usage hint
    return 2;
  }
  try {
    if (app.got_subcommand("df")) return run_df();
    if (app.got_subcommand("illuminance")) return run_illuminance();
    if (app.got_subcommand("eval")) return run_eval();
    if (app.got_subcommand("bench")) return run_bench();
    if (app.got_subcommand("sun")) return run_sun();
    if (app.got_subcommand("grid")) return run_grid();
    if (app.got_subcommand("annual")) return run_annual();
  } catch (const daylit::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: internal: " << e.what() << '\n';
    return 3;
  }
  return 0;
}
