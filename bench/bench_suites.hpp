#pragma once
// What the suites of `daylit bench` share (cli/bench_command.cpp registers them): their options, entry
// points, and small helpers for timing and progress.

#include <time.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace daylit::cli {

struct BenchOptions {
  std::string out;
  bool quick = false;
  bool quiet = false;
  std::string samples = "samples";  // `scenes`, `skies`, `reflections`: the folder holding office/ and hall/
};

// `daylit bench kernels`: the moment kernels exact, by early termination and by Monte Carlo; cost
// per edge.
int run_bench_kernels(const BenchOptions& options);
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

namespace bench {

using clock_type = std::chrono::steady_clock;

inline double seconds_since(clock_type::time_point t0) {
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

// CPU time of the calling thread, and of the whole process (all threads), in seconds. On a
// machine shared with other work they measure what a run costs better than the wall clock does:
// a serial loop's thread CPU time is its wall time on an idle core, and a parallel run's process
// CPU time over its thread count is, for work as evenly divisible as independent sensors, its
// wall time on idle cores.
inline double cpu_seconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
inline double thread_cpu_seconds() { return cpu_seconds(CLOCK_THREAD_CPUTIME_ID); }
inline double process_cpu_seconds() { return cpu_seconds(CLOCK_PROCESS_CPUTIME_ID); }

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
