// `daylit bench stiff`: the stiff and extreme scenes of bench/stiff_scenes.hpp (DESIGN.md §5 at
// the scene level), each computed by exact geometry and by float geometry and compared with its
// independent long-double reference; a table of where float fails and by how much.
//
// stiff.csv: case, reference, exact, float, exact_rel_error, float_rel_error (relative errors;
// absolute, in percentage points, where the reference is 0), then the reference's own estimated
// relative error, the tolerance the tests hold the exact path to, the times, and the description.
// Float "fails" where its error exceeds that tolerance or it gives no finite answer.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>

#include "bench/stiff_scenes.hpp"
#include "bench/bench_suites.hpp"
#include "report/progress_bar.hpp"
#include "report/staged_output.hpp"
#include "geometry/error.hpp"
#include "simulation/sky_component.hpp"

namespace daylit::cli {

namespace {

using bench::clock_type;
using bench::seconds_since;

struct Outcome {
  double value;  // NaN: no finite answer
  double seconds;
  std::string failure;
};

Outcome compute(const stiff::StiffCase& c, GeometryMode mode, int repetitions) {
  const VisibilityEngine engine(c.scene, mode);
  Outcome out{std::nan(""), 1e300, ""};
  for (int i = 0; i < repetitions; ++i) {
    VisibilityCounters counters;
    // The one timing scheme (bench/timing.hpp): thread CPU time, the best of the repetitions.
    const double t0 = bench::thread_cpu_seconds();
    try {
      out.value = sky_component_percent(engine, c.scene, c.sensor, SkyModel::cie_overcast, counters);
    } catch (const Error& e) {
      out.failure = e.what();
      return out;
    }
    out.seconds = std::min(out.seconds, bench::thread_cpu_seconds() - t0);
  }
  return out;
}

double error_against(double value, long double reference) {
  if (std::isnan(value)) return value;
  return reference == 0 ? std::abs(value) : double(std::abs((long double)value - reference) / std::abs(reference));
}

struct StiffRow {
  const stiff::StiffCase* c;
  stiff::ReferenceValue reference;
  Outcome exact, floating;
  double exact_error, float_error;
  bool float_fails;
};

std::string csv_number(double x) { return std::isnan(x) ? "nan" : fmt::format("{:.17g}", x); }
std::string quoted(const std::string& s) { return "\"" + s + "\""; }

}  // namespace

int run_bench_stiff(const BenchOptions& opt) {
  const auto t0 = clock_type::now();
  std::error_code ec;
  std::filesystem::create_directories(opt.out, ec);
  if (!std::filesystem::is_directory(opt.out)) throw Error(opt.out + ": cannot create the output directory");
  const int repetitions = opt.quick ? 1 : 5;

  const std::vector<stiff::StiffCase> cases = stiff::stiff_cases();
  std::vector<StiffRow> rows;
  {
    bench::StatusLine status(!opt.quiet && stderr_is_terminal());
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const stiff::StiffCase& c = cases[i];
      status.show(fmt::format("bench stiff: case {}/{} {}", i + 1, cases.size(), c.name));
      StiffRow r{&c, stiff::reference_sky_component(c), compute(c, GeometryMode::exact, repetitions),
                 compute(c, GeometryMode::floating, repetitions), 0, 0, false};
      if (std::isnan(r.exact.value)) throw Error("bench stiff: the exact path failed on " + c.name + ": " + r.exact.failure);
      r.exact_error = error_against(r.exact.value, r.reference.sc_percent);
      r.float_error = error_against(r.floating.value, r.reference.sc_percent);
      r.float_fails = !(r.float_error <= c.tolerance);
      rows.push_back(r);
    }
  }

  StagedOutputs outputs;
  const std::string csv = (std::filesystem::path(opt.out) / "stiff.csv").string();
  {
    std::ofstream f(outputs.stage(csv));
    f << "case,reference,exact,float,exact_rel_error,float_rel_error,reference_rel_error_estimate,tolerance,float_fails,"
         "exact_time_s,float_time_s,float_failure,description\n";
    for (const StiffRow& r : rows)
      f << fmt::format("{},{:.20Lg},{},{},{:.3e},{:.3e},{:.1e},{:.0e},{},{:.3e},{},{},{}\n", r.c->name, r.reference.sc_percent,
                       csv_number(r.exact.value), csv_number(r.floating.value), r.exact_error, r.float_error,
                       double(r.reference.relative_error), r.c->tolerance, r.float_fails ? "yes" : "no", r.exact.seconds,
                       std::isnan(r.floating.value) ? "" : fmt::format("{:.3e}", r.floating.seconds), quoted(r.floating.failure),
                       quoted(r.c->description));
    if (!f) throw Error(csv + ": cannot write");
  }
  outputs.commit();

  {  // the results: on stdout even with --quiet, which silences stderr
    std::cout << "| case | reference SC (%) | exact rel. error | float rel. error | float geometry |\n|---|---|---|---|---|\n";
    std::size_t fails = 0;
    for (const StiffRow& r : rows) {
      // Where float stays within the tolerance but is visibly worse than exact, say so too; the
      // floor keeps roundoff-level differences (and exact's own zeros) from reading as a verdict.
      const double floor = r.reference.sc_percent == 0 ? 1e-19 : 1e-16;
      std::string verdict = "as exact";
      if (std::isnan(r.floating.value))
        verdict = "**fails**: no answer (" + r.floating.failure + ")";
      else if (r.float_fails)
        verdict = fmt::format("**fails**: {:.1e} x the tolerance {:.0e}", r.float_error / r.c->tolerance, r.c->tolerance);
      else if (r.float_error > 10 * std::max(r.exact_error, floor))
        verdict = fmt::format("within tolerance, {:.0f} x exact's error", r.float_error / std::max(r.exact_error, floor));
      fails += r.float_fails;
      std::cout << fmt::format("| {} | {:.12Lg} | {:.1e} | {:.1e} | {} |\n", r.c->name, r.reference.sc_percent, r.exact_error,
                               r.float_error, verdict);
    }
    std::cout << fmt::format("\nFloat geometry fails in {} of {} cases; exact geometry is within tolerance in {} of {}. "
                             "(Errors are absolute, in percent, where the reference is 0.)\n",
                             fails, rows.size(),
                             std::count_if(rows.begin(), rows.end(), [](const StiffRow& r) { return r.exact_error <= r.c->tolerance; }),
                             rows.size());
    if (!opt.quiet) std::cerr << fmt::format("bench stiff: wrote {} ({:.1f} s)\n", csv, seconds_since(t0));
  }
  return 0;
}

}  // namespace daylit::cli
