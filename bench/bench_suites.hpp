#pragma once
// What the suites of `daylit bench` share (cli/bench_command.cpp registers them): their options, entry
// points, and the progress line; their one timing scheme is bench/timing.hpp.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/timing.hpp"

namespace daylit::cli {

struct BenchOptions {
  std::string out;
  bool quick = false;
  bool quiet = false;
  std::string samples = "samples";  // `scenes`, `skies`, `reflections`, `annual`: the folder holding office/ and hall/
  std::string weather = "tests/data/chicago-ohare-tmy3-jan1-3.epw";  // `annual`: an EPW or .wea
  // `scenes`: this daylit was built with DAYLIT_MPI (cli/mpi_shards.hpp), so that its MPI table
  // can run it under mpirun.
  bool mpi_build = false;
  // `trace`: the user's scene and the path tracer's settings (path_tracer.hpp).
  struct Trace {
    std::vector<std::string> scene_files, aperture_files, grid_files;
    long paths = 16384;
    int bounces = 16;
    double ground_reflectance = 0.2;
    std::uint64_t seed = 1;
    // A sun (degrees; azimuth clockwise from +y) and its direct normal irradiance over the sky's
    // unobstructed horizontal one (0: none).
    double sun_zenith = 0, sun_azimuth = 0, sun_normal = 0;
  } trace;
};

// `daylit bench kernels`: the moment kernels exact, by early termination and by Monte Carlo; cost
// per edge.
int run_bench_kernels(const BenchOptions& options);
// `daylit bench pairs`: the cost per sensor–aperture pair in exact, float and rational geometry.
int run_bench_pairs(const BenchOptions& options);
// `daylit bench gradient`: the cost of irradiance gradients against the irradiance alone.
int run_bench_gradient(const BenchOptions& options);
// `daylit bench scenes`: error against run time on the bundled samples, and how run time grows.
int run_bench_scenes(const BenchOptions& options);
// `daylit bench stiff`: exact and float geometry against independent references on stiff scenes.
int run_bench_stiff(const BenchOptions& options);
// `daylit bench skies`: the CIE general skies by the fit's closed forms and by cubature.
int run_bench_skies(const BenchOptions& options);
// `daylit bench rational`: Cl2 and Λ by GSL, Grosjean and a table; rational moments exact and
// semi-analytic; polynomial luminaires by degree.
int run_bench_rational(const BenchOptions& options);
// `daylit bench reflections`: ERC + IRC by the path tracer (and, once it lands, the radiosity) on
// closed-form cases and the samples' rooms.
int run_bench_reflections(const BenchOptions& options);
// `daylit bench annual`: the annual sky by the exact path, in exact patches and sampled, against a
// tight reference run.
int run_bench_annual(const BenchOptions& options);
// `daylit bench trace`: the path tracer on the user's scene (SC, ERC, IRC, DF with standard errors).
int run_bench_trace(const BenchOptions& options);

namespace bench {

// Progress on stderr, one overwritten line, when enabled (a terminal and not --quiet).
class StatusLine {
 public:
  explicit StatusLine(bool enabled) : enabled_(enabled) {}
  StatusLine(const StatusLine&) = delete;
  StatusLine& operator=(const StatusLine&) = delete;
  ~StatusLine() { clear(); }
  void show(const std::string& text) {
    if (!enabled_) return;
    std::fprintf(stderr, "\r%-78.78s", text.c_str());
    std::fflush(stderr);
    drawn_ = true;
  }
  // Ends the line, so that what is printed next starts on a fresh one.
  void clear() {
    if (drawn_) std::fprintf(stderr, "\r%78s\r", "");
    drawn_ = false;
  }

 private:
  bool enabled_, drawn_ = false;
};

}  // namespace bench

}  // namespace daylit::cli
