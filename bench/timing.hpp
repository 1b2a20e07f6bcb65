#pragma once
// The one timing scheme of `daylit bench`, for every suite:
//
//   - Figures are CPU time, never the wall clock: the machines this runs on are shared, and CPU
//     time is what a run costs. Serial work is timed by the calling thread's CPU clock; parallel
//     work by the process's CPU clock (over the thread count, for work as evenly divisible as
//     independent sensors, it is the wall time on idle cores).
//   - Each figure is the best (the minimum) of several repetitions: other work on the machine only
//     ever adds time, so the minimum is the least disturbed estimate.
//   - Calls too short for the clock's resolution are timed in batches: each batch at least
//     1/min_runs of the target, until both the target total and min_runs batches are reached.
//
// The wall clock (seconds_since) is for progress messages only.

#include <time.h>

#include <algorithm>
#include <chrono>

namespace daylit::cli::bench {

using clock_type = std::chrono::steady_clock;

inline double seconds_since(clock_type::time_point t0) {
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

inline double cpu_seconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
inline double thread_cpu_seconds() { return cpu_seconds(CLOCK_THREAD_CPUTIME_ID); }
inline double process_cpu_seconds() { return cpu_seconds(CLOCK_PROCESS_CPUTIME_ID); }

// How long to measure one figure: at least `target_seconds` of CPU time in all, over at least
// `min_runs` repetitions (batches, for per-call figures).
struct Repetitions {
  double target_seconds = 0.2;
  int min_runs = 5;
};

// Keeps timed results from being optimised away.
inline volatile double timing_sink = 0;

// The best thread CPU seconds per call of f(repetition) (f returns a double, summed into the
// sink), in batches sized from a first call so that each lasts at least target/min_runs.
template <class F>
double cpu_seconds_per_call(F&& f, const Repetitions& r) {
  double t0 = thread_cpu_seconds();
  timing_sink = f(0L);  // warm-up, and a first estimate of one call
  const double single = std::max(thread_cpu_seconds() - t0, 1e-9);
  const long batch = std::max(1L, long(r.target_seconds / r.min_runs / single));
  double best = 1e300, total = 0;
  long repetition = 1;
  for (int runs = 0; runs < r.min_runs || total < r.target_seconds; ++runs) {
    t0 = thread_cpu_seconds();
    double acc = 0;
    for (long i = 0; i < batch; ++i) acc += f(repetition++);
    const double t = thread_cpu_seconds() - t0;
    timing_sink = acc;
    best = std::min(best, t / double(batch));
    total += t;
  }
  return best;
}

// The best CPU seconds of a whole run of f() over `runs` repetitions: the calling thread's CPU
// time (serial work) or the process's (parallel work).
enum class CpuClock { thread, process };
template <class F>
double best_cpu_seconds(F&& f, int runs, CpuClock clock = CpuClock::thread) {
  const auto now = [clock] { return clock == CpuClock::thread ? thread_cpu_seconds() : process_cpu_seconds(); };
  double best = 1e300;
  for (int r = 0; r < std::max(runs, 1); ++r) {
    const double t0 = now();
    f();
    best = std::min(best, now() - t0);
  }
  return best;
}

}  // namespace daylit::cli::bench
