// `daylit bench`: registers the suites of bench/ (bench_suites.hpp) as subcommands with their
// common options; the measuring is theirs.

#include "cli/bench_command.hpp"

#include <CLI/CLI.hpp>

#include <memory>
#include <vector>

#include "bench/bench_suites.hpp"
#include "cli/mpi_shards.hpp"
#include "cli/number_checks.hpp"

namespace daylit::cli {

std::function<int()> add_bench_command(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "Error against run time of approximate paths beside the exact ones");
  bench->footer(
      "Measures each approximate path beside the exact one on the same cases and writes the results as CSV\n"
      "tables and log-log plots (PNG) into --out. Suites: kernels, scenes, stiff, skies, rational,\n"
      "reflections, annual, pairs, gradient, trace. Every figure is CPU time, the best of several runs (bench/timing.hpp).");
  bench->require_subcommand(1);

  // Each suite: a subcommand with the common options and its runner (bench_suites.hpp).
  struct Suite {
    CLI::App* command;
    std::shared_ptr<BenchOptions> options;
    int (*run)(const BenchOptions&);
  };
  auto suites = std::make_shared<std::vector<Suite>>();
  const auto add_suite = [&](const char* name, const char* summary, const char* description, int (*run)(const BenchOptions&)) {
    auto options = std::make_shared<BenchOptions>();
    options->mpi_build = mpi::built_with_mpi();
    CLI::App* command = bench->add_subcommand(name, summary);
    command->footer(description);
    command->add_option("--out", options->out, "Directory for the tables and plots (created if missing)")->required();
    command->add_flag("--quick", options->quick, "Fewer repetitions, parameters and orders: a smoke run of a few seconds");
    command->add_flag("--quiet", options->quiet, "No progress or summary on stderr");
    suites->push_back({command, options, run});
  };
  add_suite("kernels", "Moment kernels: exact, early termination and Monte Carlo; cost per edge",
            "For six cases (a window seen from a desk, Phong luminaires n = 10 and 100, a glossy reflection n = 1000,\n"
            "a non-convex rooflight) times the exact closed form, early termination at tolerances 1e-2 ... 1e-14 and\n"
            "two stratified Monte Carlo estimators at N = 16 ... 65,536, and measures their errors against a\n"
            "__float128 reference; then times the axial moment on polygons of 4, 16 and 64 edges for orders 1 ...\n"
            "10,000. Writes kernels_error_vs_time.csv/.png and kernels_cost_per_edge.csv/.png. One core.",
            run_bench_kernels);
  add_suite("scenes", "The samples: exact and float geometry, Monte Carlo and cubature; scaling",
            "On the bundled office and hall: the sky component by exact and float geometry (whole grids), Monte\n"
            "Carlo ray casting (stratified, sky x cosine importance, N = 16 ... 65,536 rays) and adaptive cubature\n"
            "over the exact visible region (tolerances 1e-2 ... 1e-12) on 200 sensors per sample, timed on one core\n"
            "and compared with the exact closed form; then run time (all cores) against the number of sensors (up\n"
            "to 100,000), occluders, apertures and window edges, with fitted exponents, and the share of pairs\n"
            "that needed exact construction. Writes scenes_error_vs_time.csv/.png, scenes_scaling.csv/.png,\n"
            "scenes_scaling_fit.csv and scenes_pairs.csv, and prints the tables. About 6 minutes of CPU time\n"
            "(--quick: about 6 s).",
            run_bench_scenes);
  suites->back().command->add_option("--samples", suites->back().options->samples,
                                     "Folder holding the bundled samples office/ and hall/ (default: samples)");
  add_suite("stiff", "Stiff scenes: exact and float geometry against independent references",
            "Receivers in the window's plane, windows seen edge-on, a 1e-12 sr skylight 1 km away, a 2 km opening\n"
            "1 mm away, slivers, flush reveals, coplanar walls, rotated and georeferenced copies: each by exact and\n"
            "float geometry against a long-double polar quadrature over the hand-derived visible part. Writes\n"
            "stiff.csv and prints a table of where float geometry fails and by how much.",
            run_bench_stiff);
  add_suite("skies", "CIE general skies: closed forms of the fit against adaptive cubature",
            "The fifteen CIE standard general skies (ISO 15469) with the sun in three places, through the office's\n"
            "window (as an opening) on every 13th sensor: the fit's closed forms and adaptive cubature at tolerances\n"
            "1e-2 ... 1e-10, timed on one core and compared with cubature at 1e-13; and E_out of each sky by the fit\n"
            "and by cubature. Writes skies_error_vs_time.csv/.png and skies_e_out.csv, and prints a table.",
            run_bench_skies);
  suites->back().command->add_option("--samples", suites->back().options->samples,
                                     "Folder holding the bundled sample office/ (default: samples)");
  add_suite("rational", "Rational moments: Cl2 by GSL, Grosjean and a table; exact O(n^2) and semi-analytic paths",
            "Cl2 by GSL, Grosjean's formula and a long double series, and Chen and Arvo's Lambda by eq. 36 with each\n"
            "and by a tabulated Lambda' (100, 300, 1000 nodes a side), against __float128 references on seeded random\n"
            "arguments; tau^{n,1,1;1} for n = 1 ... 1000 on 4- and 16-edge luminaires by the exact O(n^2) path and by\n"
            "Gauss-Legendre quadrature of T3 (4 ... 128 nodes), with adaptive cubature as the 2-D baseline; and\n"
            "polynomial luminaires of degree 0 ... 16 on stress geometries (estimate, kappa of the double pass,\n"
            "precision). Writes rational_special_functions.csv/.png, rational_moments_error_vs_time.csv/.png,\n"
            "rational_cost_per_edge.png and rational_luminaire_degree.csv. One core; --quick: a few seconds.",
            run_bench_rational);
  add_suite("reflections", "Reflected components (ERC + IRC): path tracer at N paths and B bounces against closed forms and long runs",
            "The Monte Carlo path tracer (next-event estimation through the apertures, MIS, seeded) at N = 16 ... 4096\n"
            "paths per sensor and B = 1 ... 16 bounces on four cases: a plate over upward sensors and a box with an\n"
            "open ceiling (closed forms from Howell's configuration factors), the office sample (every 30th sensor)\n"
            "and a 4 x 5 x 3 m side-lit room (80 sensors; both against a path-traced run at N = 65,536, B = 16,\n"
            "stated as such). CPU time per sensor on one thread. Writes reflections_error_vs_time.csv/.png and\n"
            "reflections_reference.csv and reflections_reference_bounces.csv (the references per sensor and bounce),\n"
            "and prints the table and the rooms' grid means.\n"
            "About 2 minutes of CPU time (--quick: a few seconds).",
            run_bench_reflections);
  suites->back().command->add_option("--samples", suites->back().options->samples,
                                     "Folder holding the bundled sample office/ (default: samples)");
  add_suite("annual", "Annual sky: the exact path, exact patches and sampled patches against a tight reference",
            "On the office (every 40th sensor) and the hall (every 128th), a year (or --weather's records) under the\n"
            "Perez sky and the sun, blinds open: the exact path at basis degrees 8, 16, 32 and circumsolar\n"
            "tolerances 1e-3 and 1e-6, the sky in Reinhart MF 1, 2, 4, 6 patches integrated exactly, and Tregenza's\n"
            "patches sampled by N = 64 ... 16,384 cosine rays per sensor (a patch-based tool's 2-phase sky), all\n"
            "against the exact path at degree 48 and tolerance 1e-9; the sun exact in every run. CPU time per\n"
            "sensor on one thread. Writes annual_error_vs_time.csv/.png and prints the table. The default weather\n"
            "is the three days in tests/data (about a minute); a full year takes about half an hour.",
            run_bench_annual);
  suites->back().command->add_option("--samples", suites->back().options->samples,
                                     "Folder holding the bundled samples office/ and hall/ (default: samples)");
  suites->back().command->add_option("--weather", suites->back().options->weather,
                                     "EPW or .wea weather file (default: tests/data/chicago-ohare-tmy3-jan1-3.epw)");
  add_suite("pairs", "Cost per sensor-aperture pair: exact, float and all-rational geometry",
            "The sky component per sensor-aperture pair on the office and hall samples and on an unobstructed\n"
            "window (the office's dense grid), one thread, in exact (certified intervals), float and rational\n"
            "geometry (every 25th sensor), with the shares of pairs clipped and needing rationals. Writes pairs.csv\n"
            "and prints the table. About a minute (--quick: every 10th sensor of the coarse grids).",
            run_bench_pairs);
  suites->back().command->add_option("--samples", suites->back().options->samples,
                                     "Folder holding the bundled samples office/ and hall/ (default: samples)");
  add_suite("gradient", "Cost of irradiance gradients against the irradiance alone",
            "On the office and hall samples' visible regions: the sky kernels against the gradient kernel, and df\n"
            "against df --gradient per sensor (visibility included); a uniform and a linearly varying luminaire\n"
            "behind an occluder (E against E and its gradient). One thread, best of 5 alternating runs. Writes\n"
            "gradient.csv and prints the table (--quick: 100 sensors per sample).",
            run_bench_gradient);
  suites->back().command->add_option("--samples", suites->back().options->samples,
                                     "Folder holding the bundled samples office/ and hall/ (default: samples)");
  add_suite("trace", "The path tracer on a scene of yours: SC, ERC, IRC and DF with standard errors",
            "The Monte Carlo path tracer of `bench reflections` (its own ray casting, next-event estimation through\n"
            "the apertures, seeded) on --scene, --apertures and --grid as df reads them, under the CIE overcast sky:\n"
            "an independent reference for `df --components all`. Writes trace.csv (df's first columns, then each\n"
            "component in percent and its standard error; the standard errors are conservative). Light beyond\n"
            "--bounces reflections is not estimated. Cost: about 0.1 ms per path and sensor on a room. With a sun\n"
            "(--sun-zenith, --sun-azimuth, --direct-normal-ratio) also its direct light (sun_percent) and its\n"
            "reflections in ERC and IRC, all in percent of the sky's E_out: the reference for\n"
            "`illuminance --components all` with --sky cie-overcast and --direct-normal = ratio x --diffuse-horizontal.",
            run_bench_trace);
  {
    BenchOptions& o = *suites->back().options;
    CLI::App& c = *suites->back().command;
    c.add_option("--scene", o.trace.scene_files, "Radiance scene files (.rad), as for df")->check(CLI::ExistingFile);
    c.add_option("--apertures", o.trace.aperture_files, "Radiance files whose polygons are sky openings, as for df")
        ->check(CLI::ExistingFile);
    c.add_option("--grid", o.trace.grid_files, "Sensor grids (.pts)")->required()->check(CLI::ExistingFile);
    c.add_option("--paths", o.trace.paths, "Paths per sensor (default 16384; the standard error falls as 1/sqrt)")
        ->check(number_in(1, 1e9));
    c.add_option("--bounces", o.trace.bounces, "Surface reflections a path may have (default 16)")->check(number_in(0, 1000));
    c.add_option("--ground-reflectance", o.trace.ground_reflectance, "Reflectance of the far ground (default 0.2)")
        ->check(number_in(0.0, 1.0));
    c.add_option("--seed", o.trace.seed, "Seed of the generators (default 1)");
    c.add_option("--sun-zenith", o.trace.sun_zenith, "A sun's zenith angle (degrees, below 90; with --direct-normal-ratio)")
        ->check(number_in(0.0, 89.99));
    c.add_option("--sun-azimuth", o.trace.sun_azimuth, "The sun's azimuth (degrees clockwise from +y, as illuminance without --site)")
        ->check(number_in(-360.0, 360.0));
    c.add_option("--direct-normal-ratio", o.trace.sun_normal,
                 "The sun's direct normal illuminance over the sky's unobstructed horizontal one (default 0: no sun); "
                 "the sun then adds sun_percent and its reflections, the far ground takes its horizontal part")
        ->check(number_in(0.0, 1e4));
  }
  return [suites] {
    for (const Suite& s : *suites)
      if (s.command->parsed()) return s.run(*s.options);
    return 1;
  };
}

}  // namespace daylit::cli
