// daylit: exact daylight factors and illuminance in building models.

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <string>

#include "cli/annual_command.hpp"
#include "cli/bench_command.hpp"
#include "cli/df_command.hpp"
#include "cli/eval_command.hpp"
#include "cli/grid_command.hpp"
#include "cli/illuminance_command.hpp"
#include "cli/mpi_shards.hpp"
#include "cli/process_memory.hpp"
#include "cli/sun_command.hpp"
#include "geometry/error.hpp"

int main(int argc, char** argv) {
  daylit::cli::use_transparent_huge_pages(argv);
  daylit::cli::keep_freed_memory();
  // Under mpirun every rank runs main; without MPI (or without mpirun) there is one rank.
  namespace mpi = daylit::cli::mpi;
  const mpi::Session session(argc, argv);
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
  // The command line is the same on every rank, so is its verdict: rank 0 alone says it.
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return mpi::root() ? app.exit(e) : 0;  // --help, --version
    if (mpi::root()) app.exit(e);                                        // prints "error: ..." and the usage hint
    return 2;
  }
  // df, illuminance and annual shard their sensors over the ranks (cli/mpi_shards.hpp); the other
  // commands run on rank 0 alone while the others wait.
  int code = 0;
  std::string message;
  try {
    if (app.got_subcommand("df")) code = run_df();
    else if (app.got_subcommand("illuminance")) code = run_illuminance();
    else if (app.got_subcommand("annual")) code = run_annual();
    else if (!mpi::root()) code = 0;
    else if (app.got_subcommand("eval")) code = run_eval();
    else if (app.got_subcommand("bench")) code = run_bench();
    else if (app.got_subcommand("sun")) code = run_sun();
    else if (app.got_subcommand("grid")) code = run_grid();
  } catch (const mpi::RankFailure& e) {
    return mpi::report(e);  // the ranks have agreed on it already
  } catch (const daylit::Error& e) {
    code = 1;
    message = std::string("error: ") + e.what();
  } catch (const std::exception& e) {
    code = 3;
    message = std::string("error: internal: ") + e.what();
  }
  // Every rank ends here once: a failure on one (rank 0 writing the outputs, a sensor of another's
  // block) becomes every rank's exit code, and rank 0 prints the message.
  return mpi::finish(code, message);
}
