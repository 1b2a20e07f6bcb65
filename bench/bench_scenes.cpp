// `daylit bench scenes`: on the bundled samples (office, hall), the sky component by exact geometry,
// float geometry, Monte Carlo ray casting and adaptive cubature over the exact visible region, each
// timed per sensor on one core and compared with the exact closed form; then how run time grows
// with the number of sensors, occluders, apertures and polygon edges (DESIGN.md §6).
//
// Errors: the exact path is the reference (its error is zero by construction; the tests hold it
// to analytic answers and to an all-rational reference). Per sensor, the relative error
// |SC − SC_exact|/SC_exact where SC_exact > 0; over a set of sensors its RMS and maximum, the
// normalised RMS error √mean((SC − SC_exact)²)/√mean(SC_exact²), the largest absolute error
// (percentage points), and how many sensors that see no sky at all got a non-zero value.
//
// Timing (one core, serial loops): exact and float on the sample's whole grid (every 16th sensor
// with --quick), interleaved, best of 2 runs; Monte Carlo and cubature on a subset of sensors
// spread over the grid (200, or 12 with --quick), one run each. Each is timed by the CPU time of
// its thread (plotted) and by the wall clock: on a shared machine the first is what the work
// costs, the second what it took.
//
// Scaling (all cores, office): random sensors on the office floor (1,000 … 100,000); k random
// boxes added in the street (occluders); the window split into k panes (apertures); the window
// replaced by a regular k-gon inscribed in the opening (edges), these three on every 8th sensor of
// the office grid. Timed by CPU time over all threads (and wall time); the exponent is the
// least-squares slope of log CPU time against log count.
//
// Office floor (one core): a generated floor of cellular offices (77 polygons and one glazed
// window a room, up to 10,010 polygons and 130 windows), every window from sensors in a few rooms,
// glazed and unglazed: CPU time per sensor–aperture pair, and how many pairs were decided without
// clipping because walls hide the window (the largest floor is written out as .rad/.pts so that
// another build, today's main for one, can be timed on it with `daylit df --threads 1`).
// MPI (issue 13, part 4): this executable's `df` on the office with the most boxes, one thread per
// process, alone and under `mpirun -n 1` and `-n 2`, with whether the CSVs are byte for byte the
// same (a DAYLIT_MPI build with mpirun on the PATH; otherwise the table says why it is empty).
// Occluders (one core): the office with k boxes in the street (25 … 10,025 polygons) in both
// subtraction orders (SubtractionOrder), with the exponent of CPU time per sensor and the largest
// relative difference of front_to_back (the default) from as_built. Threads: random office sensors on 1 and
// 2 threads, and the speed-up.
//
// Files: scenes_error_vs_time.csv/.png, scenes_scaling.csv/.png, scenes_scaling_fit.csv,
// scenes_pairs.csv (what the visibility routine left out, per grid), scenes_floor.csv,
// scenes_floor_{scene,apertures}.rad and scenes_floor_grid.pts (and scenes_boxes_*: the office with
// the most boxes of the scaling, on its sensors), scenes_occluders_one_core.csv,
// scenes_threads.csv, scenes_direct.csv (what a grid that sees the sky directly pays), scenes_mpi.csv.

#include <unistd.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "bench/bench_suites.hpp"
#include "report/plot.hpp"
#include "report/progress_bar.hpp"
#include "report/staged_output.hpp"
#include "materials/scene_materials.hpp"
#include "geometry/error.hpp"
#include "geometry/sky_box.hpp"
#include "bench/sky_baselines.hpp"
#include "illumination/xoshiro256.hpp"
#include "simulation/sky_component.hpp"

namespace daylit::cli {

namespace {

using bench::clock_type;
using bench::process_cpu_seconds;
using bench::seconds_since;
using bench::thread_cpu_seconds;

struct ScenesSettings {
  std::size_t error_sensors;   // per sample, spread over the grid, for Monte Carlo and cubature
  std::size_t timing_stride;   // exact and float on every k-th sensor of the grid
  int timing_runs;             // best of
  std::vector<long> samples;   // Monte Carlo rays per sensor
  std::vector<double> tolerances;  // cubature, relative
  std::vector<std::size_t> sensor_counts;
  std::vector<int> boxes, panes, edges;
  std::size_t scaling_stride;  // the office grid's sensors used for the geometry scalings
  int scaling_runs;            // best of, as long as the runs so far took less than 2 s
  std::vector<int> floor_rooms;  // the generated office floor: rooms per row (77 polygons a room)
  std::vector<int> order_boxes;  // boxes in the street for the one-core table of subtraction orders
  std::vector<std::size_t> thread_sensors;  // random office sensors timed on 1 and 2 threads
};

ScenesSettings settings_for(bool quick) {
  if (quick) return {12, 16, 1, {16, 256, 4096, 65536}, {1e-3, 1e-6, 1e-9}, {250, 1000}, {0, 16}, {1, 8}, {4, 16}, 32, 1, {1, 2}, {0, 16}, {1000}};
  return {200,
          1,
          2,
          {16, 64, 256, 1024, 4096, 16384, 65536},
          {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12},
          {1000, 3000, 10000, 30000, 100000},
          {0, 1, 2, 4, 8, 16, 32, 64, 128},
          {1, 2, 4, 8, 16, 32, 64},
          {4, 8, 16, 32, 64, 128},
          8,
          3,
          {1, 4, 16, 65},
          {0, 4, 16, 64, 128, 512, 2000},
          {1000, 10000, 100000}};
}

struct Sample {
  std::string name;
  Scene scene;
  SensorGrid grid;
};

Sample load_sample(const std::filesystem::path& dir, const std::string& name) {
  const std::filesystem::path base = dir / name;
  if (!std::filesystem::exists(base / "scene.rad"))
    throw Error((base / "scene.rad").string() + ": not found; give the folder of the bundled samples with --samples DIR");
  Sample s{name, load_scene({(base / "scene.rad").string()}, {(base / "apertures.rad").string()}),
           read_sensor_grid((base / "grid.pts").string())};
  return s;
}

SensorGrid every_kth(const SensorGrid& grid, std::size_t k) {
  SensorGrid out{grid.name, grid.path, {}};
  for (std::size_t i = 0; i < grid.sensors.size(); i += k) out.sensors.push_back(grid.sensors[i]);
  return out;
}

// About `count` sensors spread over the grid's plan: the bounding rectangle of the sensors cut
// into nx × ny cells of about equal sides (nx·ny ≈ count), and the sensor nearest each cell's
// centre (a stride through the file would alias with its rows). Order as in the grid.
SensorGrid spread(const SensorGrid& grid, std::size_t count) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Sensor& s : grid.sensors) {
    x0 = std::min(x0, s.position.x), x1 = std::max(x1, s.position.x);
    y0 = std::min(y0, s.position.y), y1 = std::max(y1, s.position.y);
  }
  const double w = std::max(x1 - x0, 1e-9), h = std::max(y1 - y0, 1e-9);
  const auto nx = std::size_t(std::max(1.0, std::round(std::sqrt(double(count) * w / h))));
  const std::size_t ny = std::max<std::size_t>(1, (count + nx / 2) / nx);
  std::vector<std::size_t> picked;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const double cx = x0 + w * (double(i) + 0.5) / double(nx), cy = y0 + h * (double(j) + 0.5) / double(ny);
      std::size_t best = 0;
      double best_d = 1e300;
      for (std::size_t k = 0; k < grid.sensors.size(); ++k) {
        const double dx = grid.sensors[k].position.x - cx, dy = grid.sensors[k].position.y - cy, d = dx * dx + dy * dy;
        if (d < best_d) best_d = d, best = k;
      }
      picked.push_back(best);
    }
  std::sort(picked.begin(), picked.end());
  picked.erase(std::unique(picked.begin(), picked.end()), picked.end());
  SensorGrid out{grid.name, grid.path, {}};
  for (const std::size_t k : picked) out.sensors.push_back(grid.sensors[k]);
  return out;
}

// ── Errors ──────────────────────────────────────────────────────────────────────────────────

struct ErrorStats {
  std::size_t sensors = 0, with_sky = 0, zero_sky_nonzero = 0, failures = 0;
  double rms_relative = 0, max_relative = 0, normalised_rms = 0, max_abs = 0;
};

// NaN values are sensors where the method failed (float geometry can give up); they are counted
// and left out of the statistics.
ErrorStats error_stats(const std::vector<double>& value, const std::vector<double>& exact) {
  ErrorStats s;
  s.sensors = value.size();
  double rel2 = 0, abs2 = 0, ref2 = 0;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (std::isnan(value[i])) {
      ++s.failures;
      continue;
    }
    const double e = std::abs(value[i] - exact[i]);
    abs2 += e * e;
    ref2 += exact[i] * exact[i];
    s.max_abs = std::max(s.max_abs, e);
    if (exact[i] > 0) {
      ++s.with_sky;
      const double r = e / exact[i];
      rel2 += r * r;
      s.max_relative = std::max(s.max_relative, r);
    } else if (value[i] != 0) {
      ++s.zero_sky_nonzero;
    }
  }
  s.rms_relative = s.with_sky ? std::sqrt(rel2 / double(s.with_sky)) : 0;
  s.normalised_rms = ref2 > 0 ? std::sqrt(abs2 / ref2) : 0;
  return s;
}

struct ErrorRow {
  std::string sample, method, parameter;
  double time_per_sensor_s;  // CPU time of the one thread that ran it
  double wall_per_sensor_s;
  double work_per_sensor;  // rays (Monte Carlo), integrand evaluations (cubature), pairs (geometry)
  ErrorStats errors;
};

// ── One core: exact, float, Monte Carlo, cubature on a sample ───────────────────────────────

struct SerialRun {
  std::vector<double> sc;
  VisibilityCounters counters;
  double seconds = 0, cpu_seconds = 0;  // wall, and this thread's CPU time
};

SerialRun run_serial(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid) {
  SerialRun r;
  r.sc.resize(grid.sensors.size());
  const auto t0 = clock_type::now();
  const double c0 = thread_cpu_seconds();
  for (std::size_t i = 0; i < grid.sensors.size(); ++i) {
    try {
      r.sc[i] = sky_component_percent(engine, scene, grid.sensors[i], SkyModel::cie_overcast, r.counters);
    } catch (const Error&) {
      if (engine.mode() != GeometryMode::floating) throw;
      r.sc[i] = std::nan("");  // the float path gave up at this sensor
    }
  }
  r.seconds = seconds_since(t0);
  r.cpu_seconds = thread_cpu_seconds() - c0;
  return r;
}

struct PairsRow {
  std::string sample, grid;
  std::size_t sensors;
  VisibilityCounters counters;
};

struct SampleResult {
  std::vector<ErrorRow> rows;
  PairsRow pairs;
  double exact_s_per_sensor, float_s_per_sensor;  // CPU time
};

SampleResult measure_sample(const Sample& s, const ScenesSettings& settings, bench::StatusLine& status) {
  SampleResult out;
  const std::string prefix = "bench scenes: " + s.name + ": ";
  status.show(prefix + "building the visibility structures");
  const VisibilityEngine exact_engine(s.scene, GeometryMode::exact), float_engine(s.scene, GeometryMode::floating);
  const SensorGrid timing = every_kth(s.grid, settings.timing_stride);

  // Exact and float, interleaved so that the machine's load hits both alike; best of the runs.
  SerialRun exact, floating;
  exact.cpu_seconds = floating.cpu_seconds = 1e300;
  for (int run = 0; run < settings.timing_runs; ++run) {
    status.show(prefix + fmt::format("exact and float geometry, {} sensors, run {}/{}", timing.sensors.size(), run + 1,
                                     settings.timing_runs));
    SerialRun e = run_serial(exact_engine, s.scene, timing), f = run_serial(float_engine, s.scene, timing);
    if (e.cpu_seconds < exact.cpu_seconds) exact = std::move(e);
    if (f.cpu_seconds < floating.cpu_seconds) floating = std::move(f);
  }
  const double n_timing = double(timing.sensors.size());
  out.exact_s_per_sensor = exact.cpu_seconds / n_timing;
  out.float_s_per_sensor = floating.cpu_seconds / n_timing;
  out.pairs = {s.name, timing.sensors.size() == s.grid.sensors.size() ? "grid.pts" : fmt::format("grid.pts, every {}th", settings.timing_stride),
               timing.sensors.size(), exact.counters};
  const double pairs_per_sensor = double(exact.counters.pairs) / n_timing;
  out.rows.push_back({s.name, "exact", "", out.exact_s_per_sensor, exact.seconds / n_timing, pairs_per_sensor,
                      error_stats(exact.sc, exact.sc)});
  out.rows.push_back({s.name, "float", "", out.float_s_per_sensor, floating.seconds / n_timing, pairs_per_sensor,
                      error_stats(floating.sc, exact.sc)});

  // Monte Carlo and cubature on sensors spread over the grid, against the exact values there.
  const SensorGrid subset = spread(s.grid, settings.error_sensors);
  std::vector<double> reference;
  {
    VisibilityCounters unused;
    for (const Sensor& sensor : subset.sensors)
      reference.push_back(sky_component_percent(exact_engine, s.scene, sensor, SkyModel::cie_overcast, unused));
  }
  const RayScene rays(s.scene);
  for (const long n : settings.samples) {
    status.show(prefix + fmt::format("Monte Carlo, {} rays per sensor, {} sensors", n, subset.sensors.size()));
    std::vector<double> sc(subset.sensors.size());
    const auto t0 = clock_type::now();
    const double c0 = thread_cpu_seconds();
    for (std::size_t i = 0; i < sc.size(); ++i)
      sc[i] = sky_component_monte_carlo(rays, subset.sensors[i], SkyModel::cie_overcast, n, std::uint64_t(n) * 1000003 + i);
    const double cpu = (thread_cpu_seconds() - c0) / double(sc.size()), wall = seconds_since(t0) / double(sc.size());
    out.rows.push_back({s.name, "monte_carlo", std::to_string(n), cpu, wall, double(n), error_stats(sc, reference)});
  }
  for (const double tolerance : settings.tolerances) {
    status.show(prefix + fmt::format("adaptive cubature, tolerance {:g}, {} sensors", tolerance, subset.sensors.size()));
    std::vector<double> sc(subset.sensors.size());
    long evaluations = 0;
    VisibilityCounters unused;
    const auto t0 = clock_type::now();
    const double c0 = thread_cpu_seconds();
    for (std::size_t i = 0; i < sc.size(); ++i) {
      const CubatureResult r = sky_component_cubature(exact_engine, s.scene, subset.sensors[i], SkyModel::cie_overcast, tolerance, unused);
      sc[i] = r.sc_percent;
      evaluations += r.evaluations;
    }
    const double cpu = (thread_cpu_seconds() - c0) / double(sc.size()), wall = seconds_since(t0) / double(sc.size());
    out.rows.push_back({s.name, "cubature", fmt::format("{:g}", tolerance), cpu, wall, double(evaluations) / double(sc.size()),
                        error_stats(sc, reference)});
  }
  return out;
}

// ── All cores: scaling ──────────────────────────────────────────────────────────────────────

struct ScalingRow {
  std::string dimension;  // sensors, occluders, apertures, edges
  int parameter;          // the count varied (sensors; boxes added; panes; polygon edges)
  double x;               // what the exponent is fitted against (sensors; occluder polygons; panes; edges)
  std::string mode;       // exact, float
  std::size_t sensors;
  int threads;
  double seconds, cpu_seconds;  // wall; CPU time of all threads
  std::size_t occluder_polygons, occluder_pieces, aperture_pieces;
  VisibilityCounters counters;
  double sc_mean;
};

struct Timed {
  double seconds, cpu_seconds;
  SkyComponentResult result;
};

// Best (by CPU time) of `runs` runs, stopping early once the runs have taken 2 s of wall time.
Timed time_parallel(const VisibilityEngine& engine, const Scene& scene, const SensorGrid& grid, int runs) {
  Timed best{1e300, 1e300, {}};
  double total = 0;
  for (int run = 0; run < runs && total < 2; ++run) {
    const auto t0 = clock_type::now();
    const double c0 = process_cpu_seconds();
    SkyComponentResult r = sky_component(engine, scene, grid, SkyModel::cie_overcast);
    const double t = seconds_since(t0), c = process_cpu_seconds() - c0;
    total += t;
    if (c < best.cpu_seconds) best = {t, c, std::move(r)};
  }
  return best;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / double(v.size());
}

// Sensors uniformly at random (seeded) on the office's work plane, 2 cm from the walls.
SensorGrid random_office_grid(std::size_t count) {
  Xoshiro256 rng(20240501 + count);  // the same sensors on every platform (std distributions differ)
  SensorGrid g{fmt::format("random{}", count), "", {}};
  g.sensors.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double x = rng.uniform(0.02, 3.98), y = rng.uniform(0.02, 5.98);
    g.sensors.push_back({{x, y, 0.85}, {0, 0, 1}});
  }
  return g;
}

// A closed box without its floor, faces pointing out.
std::vector<Polygon> box(const Vec3& lo, const Vec3& hi, const std::string& name) {
  const auto face = [&](std::vector<Vec3> v, const char* side) {
    Polygon p;
    p.vertices = std::move(v);
    p.name = name + " " + side;
    p.where = {"bench scenes: " + name, 0};
    return p;
  };
  return {face({{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}}, "south"),
          face({{hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}}, "north"),
          face({{lo.x, hi.y, lo.z}, {lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}}, "west"),
          face({{hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}}, "east"),
          face({{lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}}, "roof")};
}

// The office with k boxes (1–4 m footprints, 2–12 m high) at random in the street between the
// window wall and the building across it (y from −17.5 to −1.5 m).
Scene office_with_boxes(const Scene& office, int k) {
  Scene s = office;
  Xoshiro256 rng(7);
  for (int i = 0; i < k; ++i) {
    const double x = rng.uniform(-8, 12), y = rng.uniform(-15.5, -3.5), hx = rng.uniform(0.5, 2), hy = rng.uniform(0.5, 2),
                 h = rng.uniform(2, 12);
    for (auto& f : box({x - hx, y - hy, 0}, {x + hx, y + hy, h}, fmt::format("box {}", i))) s.occluders.push_back(std::move(f));
  }
  return s;
}

// The office's window (x 0.8..3.2, z 0.9..2.4 at y = −0.3) as k panes side by side.
Scene office_with_panes(const Scene& office, int k) {
  Scene s = office;
  const Aperture window = office.apertures.at(0);
  s.apertures.clear();
  for (int i = 0; i < k; ++i) {
    const double x0 = 0.8 + 2.4 * i / k, x1 = i + 1 == k ? 3.2 : 0.8 + 2.4 * (i + 1) / k;
    Aperture pane = window;
    pane.polygon.vertices = {{x0, -0.3, 0.9}, {x0, -0.3, 2.4}, {x1, -0.3, 2.4}, {x1, -0.3, 0.9}};
    pane.polygon.name = fmt::format("pane {}", i);
    s.apertures.push_back(std::move(pane));
  }
  return s;
}

// The office's window replaced by a regular k-gon inscribed in the opening's ellipse.
Scene office_with_polygon_window(const Scene& office, int k) {
  Scene s = office;
  Aperture& window = s.apertures.at(0);
  const Vec3 normal = newell_normal(window.polygon.vertices);
  std::vector<Vec3> v;
  for (int i = 0; i < k; ++i) {
    const double t = 2 * std::numbers::pi * (i + 0.5) / k;
    v.push_back({2 + 1.2 * std::cos(t), -0.3, 1.65 + 0.75 * std::sin(t)});
  }
  if (dot(newell_normal(v), normal) < 0) std::reverse(v.begin(), v.end());
  window.polygon.vertices = std::move(v);
  return s;
}

// ── A generated office floor: what real models are made of ─────────────────────────────────

// Two rows of `rooms_per_row` cellular offices (4 m × 6 m × 3 m inside, partitions 0.2 m) on either
// side of a 2 m corridor, each with the office sample's glazed window (2.4 m × 1.5 m, in the plane
// of the facade's outer face) in a 0.3 m facade, a reveal, two mullions and a transom, four desks,
// four chairs and a cabinet: 77 polygons a room, so 65 rooms a row make 10,010. Every room's window
// is an aperture: from each sensor, all but one are other rooms' windows, seen (or not) through
// walls and furniture, the case that made the cost follow the scene rather than what is visible.
// The north row mirrors the south one (y → 14 − y, vertex order reversed to keep the normals).
// Sensors: `sensors_per_room` (a 2 × 3 grid, or fewer) at 0.85 m in the rooms listed.
struct Floor {
  Scene scene;
  SensorGrid grid;
};

Floor office_floor(const Scene& office, int rooms_per_row, const std::vector<int>& sensor_rooms) {
  Floor f;
  f.grid = {fmt::format("floor{}", 2 * rooms_per_row), "", {}};
  const Aperture window = office.apertures.at(0);
  Xoshiro256 rng(31);
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < rooms_per_row; ++i) {
      const double x0 = 4.2 * i;
      const std::string room = fmt::format("room {}{}", row == 0 ? 's' : 'n', i);
      std::vector<Polygon> polygons;
      const auto add = [&](std::vector<Vec3> v, const std::string& what) {
        Polygon p;
        p.vertices = std::move(v);
        p.name = room + " " + what;
        p.where = {"bench scenes: " + p.name, 0};
        polygons.push_back(std::move(p));
      };
      const double X = x0 + 4;
      add({{x0, 0, 0}, {X, 0, 0}, {X, 6, 0}, {x0, 6, 0}}, "floor");
      add({{x0, 0, 3}, {x0, 6, 3}, {X, 6, 3}, {X, 0, 3}}, "ceiling");
      add({{x0, 0, 0}, {x0, 6, 0}, {x0, 6, 3}, {x0, 0, 3}}, "west wall");
      add({{X, 0, 0}, {X, 0, 3}, {X, 6, 3}, {X, 6, 0}}, "east wall");
      add({{x0, 6, 0}, {X, 6, 0}, {X, 6, 3}, {x0, 6, 3}}, "corridor wall");
      // Window wall around the opening x0+0.8..x0+3.2, z 0.9..2.4: inner face (normal +y) and outer face.
      const double a = x0 + 0.8, b = x0 + 3.2;
      const auto rect_y = [&](double y, double u0, double u1, double z0, double z1, bool plus, const std::string& what) {
        std::vector<Vec3> v{{u0, y, z0}, {u0, y, z1}, {u1, y, z1}, {u1, y, z0}};
        if (!plus) std::reverse(v.begin(), v.end());
        add(std::move(v), what);
      };
      for (const auto& [y, plus, face] : {std::tuple{0.0, true, "inner"}, std::tuple{-0.3, false, "outer"}}) {
        const double u0 = plus ? x0 : x0 - 0.1, u1 = plus ? X : X + 0.1;
        rect_y(y, u0, u1, 0, 0.9, plus, std::string(face) + " sill wall");
        rect_y(y, u0, u1, 2.4, 3, plus, std::string(face) + " head wall");
        rect_y(y, u0, a, 0.9, 2.4, plus, std::string(face) + " west wall");
        rect_y(y, b, u1, 0.9, 2.4, plus, std::string(face) + " east wall");
      }
      add({{a, 0, 0.9}, {b, 0, 0.9}, {b, -0.3, 0.9}, {a, -0.3, 0.9}}, "sill");
      add({{a, 0, 2.4}, {a, -0.3, 2.4}, {b, -0.3, 2.4}, {b, 0, 2.4}}, "head");
      add({{a, 0, 0.9}, {a, -0.3, 0.9}, {a, -0.3, 2.4}, {a, 0, 2.4}}, "west jamb");
      add({{b, 0, 0.9}, {b, 0, 2.4}, {b, -0.3, 2.4}, {b, -0.3, 0.9}}, "east jamb");
      const auto add_box = [&](const Vec3& lo, const Vec3& hi, const std::string& what) {
        for (Polygon& p : box(lo, hi, room + " " + what)) polygons.push_back(std::move(p));
      };
      for (int m = 1; m <= 2; ++m) {
        const double xm = a + 2.4 * m / 3;
        add_box({xm - 0.025, -0.2, 0.9}, {xm + 0.025, -0.1, 2.4}, fmt::format("mullion {}", m));
      }
      add_box({a, -0.2, 1.875}, {b, -0.1, 1.925}, "transom");
      for (int d = 0; d < 4; ++d) {
        const double dx = x0 + 0.3 + 1.9 * (d % 2) + rng.uniform(0, 0.2), dy = 1.2 + 2.2 * (d / 2) + rng.uniform(0, 0.3);
        add_box({dx, dy, 0}, {dx + 1.4, dy + 0.7, 0.75}, fmt::format("desk {}", d));
        add_box({dx + 0.45, dy + 0.8, 0}, {dx + 0.95, dy + 1.3, 0.45}, fmt::format("chair {}", d));
      }
      add_box({x0 + 3.4, 4.5, 0}, {x0 + 3.9, 5.9, 1.8}, "cabinet");
      Aperture pane = window;
      pane.polygon.vertices = {{a, -0.3, 0.9}, {a, -0.3, 2.4}, {b, -0.3, 2.4}, {b, -0.3, 0.9}};
      if (dot(newell_normal(pane.polygon.vertices), newell_normal(window.polygon.vertices)) < 0)
        std::reverse(pane.polygon.vertices.begin(), pane.polygon.vertices.end());
      pane.polygon.name = room + " window";
      std::vector<Sensor> sensors;
      if (std::find(sensor_rooms.begin(), sensor_rooms.end(), row * rooms_per_row + i) != sensor_rooms.end())
        for (int sy = 0; sy < 3; ++sy)
          for (int sx = 0; sx < 2; ++sx) sensors.push_back({{x0 + 1 + 2 * sx, double(1 + 2 * sy), 0.85}, {0, 0, 1}});
      if (row == 1) {  // mirror: y → 14 − y
        const auto mirror = [](Vec3& v) { v.y = 14 - v.y; };
        for (Polygon& p : polygons) {
          for (Vec3& v : p.vertices) mirror(v);
          std::reverse(p.vertices.begin(), p.vertices.end());
        }
        for (Vec3& v : pane.polygon.vertices) mirror(v);
        std::reverse(pane.polygon.vertices.begin(), pane.polygon.vertices.end());
        for (Sensor& sensor : sensors) mirror(sensor.position);
      }
      for (Polygon& p : polygons) f.scene.occluders.push_back(std::move(p));
      f.scene.apertures.push_back(std::move(pane));
      for (const Sensor& sensor : sensors) f.grid.sensors.push_back(sensor);
    }
  return f;
}

// A model as `daylit df` reads it, so that any build (today's, another branch's) can be timed on
// the same model: occluders of a grey plastic (a `void` polygon is nothing in Radiance, and so in
// daylit since it reads scenes as Radiance does: the files once held void occluders, which `df`
// left out), apertures as the office's glass.
void write_model(const Floor& f, const std::string& scene_path, const std::string& apertures_path, const std::string& grid_path) {
  const auto polygon_text = [](const std::string& modifier, const Polygon& p, std::size_t k) {
    std::string t = fmt::format("{} polygon p{}\n0\n0\n{}\n", modifier, k, 3 * p.vertices.size());
    for (const Vec3& v : p.vertices) t += fmt::format("  {:.17g} {:.17g} {:.17g}\n", v.x, v.y, v.z);
    return t;
  };
  std::ofstream scene(scene_path), apertures(apertures_path), grid(grid_path);
  scene << "# daylit bench scenes: " << f.grid.name << " (" << f.scene.occluders.size() << " polygons)\n";
  scene << "void plastic grey\n0\n0\n5 0.5 0.5 0.5 0 0\n";
  for (std::size_t k = 0; k < f.scene.occluders.size(); ++k) scene << polygon_text("grey", f.scene.occluders[k], k);
  apertures << "void glass clear_glass\n0\n0\n3 0.96 0.96 0.96\n";
  for (std::size_t k = 0; k < f.scene.apertures.size(); ++k) apertures << polygon_text("clear_glass", f.scene.apertures[k].polygon, k);
  for (const Sensor& s : f.grid.sensors)
    grid << fmt::format("{:.17g} {:.17g} {:.17g} {:g} {:g} {:g}\n", s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y,
                        s.normal.z);
  if (!scene || !apertures || !grid) throw Error(scene_path + ": cannot write the generated model");
}

struct FloorRow {
  int rooms;
  std::string glazing;  // glazed (the office's glass) or unglazed (the same transmittance at every angle)
  std::size_t polygons, pieces, apertures, sensors;
  double cpu_seconds, seconds;
  VisibilityCounters counters;
  double sc_mean;
};

// One core, serial: every aperture from every sensor of the rooms listed; best of `runs`.
std::vector<FloorRow> measure_floor(const Sample& office, const std::vector<int>& rooms_per_row, int runs, bench::StatusLine& status,
                                    Floor& largest) {
  std::vector<FloorRow> rows;
  for (const int r : rooms_per_row) {
    // Sensors in up to four rooms spread along the south row and one of the north row.
    std::vector<int> sensor_rooms;
    for (int k = 0; k < std::min(r, 4); ++k) sensor_rooms.push_back(k * r / std::min(r, 4));
    sensor_rooms.push_back(r + r / 2);
    Floor floor = office_floor(office.scene, r, sensor_rooms);
    for (const bool glazed : {true, false}) {
      Scene scene = floor.scene;
      if (!glazed)
        for (Aperture& a : scene.apertures) a.angular_transmittance.clear();
      status.show(fmt::format("bench scenes: office floor, {} rooms, {}, {} sensors", 2 * r, glazed ? "glazed" : "unglazed",
                              floor.grid.sensors.size()));
      const VisibilityEngine engine(scene, GeometryMode::exact);
      SerialRun best;
      best.cpu_seconds = 1e300;
      for (int run = 0; run < runs; ++run) {
        SerialRun t = run_serial(engine, scene, floor.grid);
        if (t.cpu_seconds < best.cpu_seconds) best = std::move(t);
      }
      rows.push_back({2 * r, glazed ? "glazed" : "unglazed", scene.occluders.size(), engine.occluder_piece_count(), scene.apertures.size(),
                      floor.grid.sensors.size(), best.cpu_seconds, best.seconds, best.counters, mean(best.sc)});
    }
    if (r == rooms_per_row.back()) largest = std::move(floor);
  }
  return rows;
}

void write_floor_table(const std::string& path, const std::vector<FloorRow>& rows) {
  std::ofstream f(path);
  f << "rooms,glazing,occluder_polygons,occluder_pieces,apertures,sensors,pairs,cpu_s,wall_s,cpu_per_sensor_s,cpu_per_pair_s,"
       "pairs_not_facing,pairs_unobstructed,pairs_covered,pairs_clipped,pairs_rational,occluder_pieces_tested,occluder_pieces_clipped,"
       "sc_mean_percent\n";
  for (const FloorRow& r : rows) {
    const VisibilityCounters& c = r.counters;
    const double pairs = double(r.sensors * r.apertures);
    f << fmt::format("{},{},{},{},{},{},{},{:.4e},{:.4e},{:.4e},{:.4e},{},{},{},{},{},{},{},{:.12g}\n", r.rooms, r.glazing, r.polygons,
                     r.pieces, r.apertures, r.sensors, r.sensors * r.apertures, r.cpu_seconds, r.seconds, r.cpu_seconds / double(r.sensors),
                     r.cpu_seconds / pairs, c.pairs_not_facing, c.pairs_unobstructed, c.pairs_covered, c.pairs_clipped, c.pairs_rational,
                     c.occluders_tested, c.occluders_clipped, r.sc_mean);
  }
  if (!f) throw Error(path + ": cannot write");
}

// ── One core: occluders, in the order as built and front to back ───────────────────────────

struct OrderRow {
  int boxes;
  std::size_t polygons;
  std::string order;  // as_built, front_to_back
  std::size_t sensors;
  double cpu_seconds;
  VisibilityCounters counters;
  double max_relative_difference;  // of SC against as_built at the same sensors (0 for as_built)
};

// The office with k boxes in the street (as in the scaling), one core, serial, on every
// `stride`-th sensor of the grid (4 and 64 times fewer above 256 and 1,024 boxes: as built, the
// 10,025-polygon case costs seconds per sensor), in both subtraction orders.
std::vector<OrderRow> measure_orders(const Sample& office, const std::vector<int>& boxes, std::size_t stride, bench::StatusLine& status) {
  std::vector<OrderRow> rows;
  for (const int k : boxes) {
    const Scene scene = office_with_boxes(office.scene, k);
    const SensorGrid grid = every_kth(office.grid, (k > 1024 ? 64 : k > 256 ? 4 : 1) * stride);
    std::vector<double> as_built;
    for (const SubtractionOrder order : {SubtractionOrder::as_built, SubtractionOrder::front_to_back}) {
      const bool front = order == SubtractionOrder::front_to_back;
      status.show(fmt::format("bench scenes: one core, {} boxes, {}, {} sensors", k, front ? "front to back" : "as built", grid.sensors.size()));
      const VisibilityEngine engine(scene, GeometryMode::exact, order);
      const SerialRun r = run_serial(engine, scene, grid);
      double worst = 0;
      if (!front) as_built = r.sc;
      else
        for (std::size_t i = 0; i < r.sc.size(); ++i)
          if (as_built[i] != r.sc[i]) worst = std::max(worst, std::abs(r.sc[i] - as_built[i]) / std::abs(as_built[i]));
      rows.push_back({k, scene.occluders.size(), front ? "front_to_back" : "as_built", grid.sensors.size(), r.cpu_seconds, r.counters, worst});
    }
  }
  return rows;
}

// Least-squares slope of log(CPU time per sensor) against log(occluder polygons), per order.
double order_exponent(const std::vector<OrderRow>& rows, const std::string& order) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  double n = 0;
  for (const OrderRow& r : rows)
    if (r.order == order) {
      const double x = std::log(double(r.polygons)), y = std::log(r.cpu_seconds / double(r.sensors));
      sx += x, sy += y, sxx += x * x, sxy += x * y, n += 1;
    }
  return n >= 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0;
}

void write_order_table(const std::string& path, const std::vector<OrderRow>& rows) {
  std::ofstream f(path);
  f << "boxes,occluder_polygons,order,sensors,cpu_s,cpu_per_sensor_s,occluder_pieces_clipped_per_pair,shadows_skipped_per_pair,"
       "pairs_covered,max_relative_difference_to_as_built\n";
  for (const OrderRow& r : rows) {
    const double pairs = double(std::max<std::uint64_t>(r.counters.pairs, 1));
    f << fmt::format("{},{},{},{},{:.4e},{:.4e},{:.3f},{:.3f},{},{:.3e}\n", r.boxes, r.polygons, r.order, r.sensors, r.cpu_seconds,
                     r.cpu_seconds / double(r.sensors), double(r.counters.occluders_clipped) / pairs,
                     double(r.counters.occluders_skipped) / pairs, r.counters.pairs_covered, r.max_relative_difference);
  }
  if (!f) throw Error(path + ": cannot write");
}

// ── Threads: the same work on 1 and 2 threads ─────────────────────────────────────────────

struct ThreadRow {
  std::size_t sensors;
  int threads;
  double seconds, cpu_seconds;
};

// Random office sensors, exact geometry, in a TBB arena of 1 and of 2 threads (best of `runs`).
// On a machine whose cores are shared the wall-clock speed-up says more about the load than the
// code; the CPU time says what the work costs.
std::vector<ThreadRow> measure_threads(const Sample& office, const std::vector<std::size_t>& counts, int runs, bench::StatusLine& status) {
  std::vector<ThreadRow> rows;
  const VisibilityEngine engine(office.scene, GeometryMode::exact);
  for (const std::size_t n : counts) {
    const SensorGrid grid = random_office_grid(n);
    for (const int threads : {1, 2}) {
      status.show(fmt::format("bench scenes: {} sensors on {} thread{}", n, threads, threads > 1 ? "s" : ""));
      tbb::task_arena arena(threads);
      Timed t{};
      arena.execute([&] { t = time_parallel(engine, office.scene, grid, runs); });
      rows.push_back({n, threads, t.seconds, t.cpu_seconds});
    }
  }
  return rows;
}

void write_thread_table(const std::string& path, const std::vector<ThreadRow>& rows) {
  std::ofstream f(path);
  f << "sensors,threads,wall_s,cpu_s,cpu_per_sensor_s,speed_up_wall\n";
  for (const ThreadRow& r : rows) {
    double one = 0;
    for (const ThreadRow& q : rows)
      if (q.sensors == r.sensors && q.threads == 1) one = q.seconds;
    f << fmt::format("{},{},{:.4e},{:.4e},{:.4e},{:.3f}\n", r.sensors, r.threads, r.seconds, r.cpu_seconds, r.cpu_seconds / double(r.sensors),
                     one / r.seconds);
  }
  if (!f) throw Error(path + ": cannot write");
}

std::vector<ScalingRow> measure_scaling(const Sample& office, const ScenesSettings& settings, bench::StatusLine& status,
                                        PairsRow& large_grid_pairs) {
  std::vector<ScalingRow> rows;
  const int threads = tbb::this_task_arena::max_concurrency();
  const auto measure = [&](const std::string& dimension, int parameter, double x, const Scene& scene, const SensorGrid& grid, int runs) {
    for (const GeometryMode mode : {GeometryMode::exact, GeometryMode::floating}) {
      const char* mode_name = mode == GeometryMode::exact ? "exact" : "float";
      status.show(fmt::format("bench scenes: scaling, {} = {}, {}, {} sensors", dimension, parameter, mode_name, grid.sensors.size()));
      const VisibilityEngine engine(scene, mode);
      Timed t = time_parallel(engine, scene, grid, runs);
      rows.push_back({dimension, parameter, x, mode_name, grid.sensors.size(), threads, t.seconds, t.cpu_seconds, scene.occluders.size(),
                      engine.occluder_piece_count(), engine.aperture_piece_count(), t.result.counters, mean(t.result.sc_percent)});
    }
  };
  for (const std::size_t n : settings.sensor_counts) {
    const SensorGrid grid = random_office_grid(n);
    measure("sensors", int(n), double(n), office.scene, grid, settings.scaling_runs);
    if (n == settings.sensor_counts.back()) {
      const ScalingRow& exact = rows[rows.size() - 2];
      large_grid_pairs = {"office", fmt::format("{} random sensors", n), n, exact.counters};
    }
  }
  const SensorGrid grid = every_kth(office.grid, settings.scaling_stride);
  for (const int k : settings.boxes) {
    const Scene scene = office_with_boxes(office.scene, k);
    measure("occluders", k, double(scene.occluders.size()), scene, grid, settings.scaling_runs);
  }
  for (const int k : settings.panes) measure("apertures", k, k, office_with_panes(office.scene, k), grid, settings.scaling_runs);
  for (const int k : settings.edges) measure("edges", k, k, office_with_polygon_window(office.scene, k), grid, settings.scaling_runs);
  return rows;
}

struct Fit {
  std::string dimension, mode;
  double exponent;
  std::size_t points;
  double x_low, x_high;
};

// Least-squares slope of log(CPU time) against log(x).
std::vector<Fit> fit_exponents(const std::vector<ScalingRow>& rows) {
  std::vector<Fit> fits;
  for (const char* dimension : {"sensors", "occluders", "apertures", "edges"})
    for (const char* mode : {"exact", "float"}) {
      double sx = 0, sy = 0, sxx = 0, sxy = 0, lo = 1e300, hi = 0;
      std::size_t n = 0;
      for (const ScalingRow& r : rows)
        if (r.dimension == dimension && r.mode == mode && r.x > 0 && r.cpu_seconds > 0) {
          const double x = std::log(r.x), y = std::log(r.cpu_seconds);
          sx += x, sy += y, sxx += x * x, sxy += x * y;
          lo = std::min(lo, r.x), hi = std::max(hi, r.x);
          ++n;
        }
      if (n >= 2) fits.push_back({dimension, mode, (n * sxy - sx * sy) / (n * sxx - sx * sx), n, lo, hi});
    }
  return fits;
}

// ── Reports ─────────────────────────────────────────────────────────────────────────────────

void write_error_table(const std::string& path, const std::vector<ErrorRow>& rows) {
  std::ofstream f(path);
  f << "sample,method,parameter,sensors,cpu_time_per_sensor_s,rms_relative_error,max_relative_error,normalised_rms_error,"
       "max_abs_error_percent,sensors_with_sky,zero_sky_sensors_nonzero,failures,work_per_sensor,wall_time_per_sensor_s,threads\n";
  for (const ErrorRow& r : rows)
    f << fmt::format("{},{},{},{},{:.4e},{:.3e},{:.3e},{:.3e},{:.3e},{},{},{},{:.6g},{:.4e},1\n", r.sample, r.method, r.parameter,
                     r.errors.sensors, r.time_per_sensor_s, r.errors.rms_relative, r.errors.max_relative,
                     r.errors.normalised_rms, r.errors.max_abs, r.errors.with_sky, r.errors.zero_sky_nonzero,
                     r.errors.failures, r.work_per_sensor, r.wall_per_sensor_s);
  if (!f) throw Error(path + ": cannot write");
}

void write_scaling_table(const std::string& path, const std::vector<ScalingRow>& rows) {
  std::ofstream f(path);
  f << "dimension,parameter,fit_x,mode,sensors,threads,cpu_s,wall_s,cpu_per_sensor_s,occluder_polygons,occluder_pieces,"
       "aperture_pieces,pairs,pairs_clipped,pairs_rational,occluder_pieces_clipped,sc_mean_percent\n";
  for (const ScalingRow& r : rows)
    f << fmt::format("{},{},{},{},{},{},{:.4e},{:.4e},{:.4e},{},{},{},{},{},{},{},{:.12g}\n", r.dimension, r.parameter, r.x, r.mode,
                     r.sensors, r.threads, r.cpu_seconds, r.seconds, r.cpu_seconds / double(r.sensors), r.occluder_polygons, r.occluder_pieces,
                     r.aperture_pieces, r.counters.pairs, r.counters.pairs_clipped, r.counters.pairs_rational,
                     r.counters.occluders_clipped, r.sc_mean);
  if (!f) throw Error(path + ": cannot write");
}

void write_fit_table(const std::string& path, const std::vector<Fit>& fits) {
  std::ofstream f(path);
  f << "dimension,mode,exponent,points,x_low,x_high\n";
  for (const Fit& r : fits) f << fmt::format("{},{},{:.3f},{},{:g},{:g}\n", r.dimension, r.mode, r.exponent, r.points, r.x_low, r.x_high);
  if (!f) throw Error(path + ": cannot write");
}

void write_pairs_table(const std::string& path, const std::vector<PairsRow>& rows) {
  std::ofstream f(path);
  f << "sample,grid,sensors,pairs,pairs_not_facing,pairs_without_clipping,pairs_clipped_in_certified_intervals,"
       "pairs_needing_exact_rationals,share_without_clipping,share_clipped_exactly,share_rational,occluder_pieces_culled_by_boxes,"
       "occluder_pieces_tested_exactly,occluder_pieces_clipped\n";
  for (const PairsRow& r : rows) {
    const VisibilityCounters& c = r.counters;
    const double pairs = double(std::max<std::uint64_t>(c.pairs, 1));
    f << fmt::format("{},\"{}\",{},{},{},{},{},{},{:.4f},{:.4f},{:.6f},{},{},{}\n", r.sample, r.grid, r.sensors, c.pairs,
                     c.pairs_not_facing, c.pairs_unobstructed, c.pairs_clipped - c.pairs_rational, c.pairs_rational,
                     double(c.pairs_unobstructed) / pairs, double(c.pairs_clipped) / pairs, double(c.pairs_rational) / pairs,
                     c.occluders_box_culled, c.occluders_tested, c.occluders_clipped);
  }
  if (!f) throw Error(path + ": cannot write");
}

const PlotColour kExactColour{0.05f, 0.05f, 0.05f}, kFloatColour{0.80f, 0.15f, 0.15f}, kMonteCarloColour{0.15f, 0.40f, 0.85f},
    kCubatureColour{0.10f, 0.62f, 0.30f};

Plot error_plot(const std::vector<ErrorRow>& rows, const std::vector<std::string>& samples, const ScenesSettings& s) {
  struct Method {
    const char* key;
    const char* legend;
    PlotColour colour;
  };
  const Method methods[] = {{"exact", "exact geometry, closed form (the reference)", kExactColour},
                            {"float", "float geometry, closed form", kFloatColour},
                            {"monte_carlo", "Monte Carlo rays, sky x cosine importance", kMonteCarloColour},
                            {"cubature", "adaptive cubature on the exact region", kCubatureColour}};
  const PlotMarker markers[] = {PlotMarker::circle, PlotMarker::square, PlotMarker::triangle, PlotMarker::diamond};
  Plot plot;
  plot.title = "Sky component on the samples: relative error against run time";
  plot.subtitle = "CPU time per sensor on one core; RMS over the sensors that see sky of |SC - SC_exact| / SC_exact";
  plot.x_label = "CPU time per sensor (s)";
  plot.y_label = "RMS relative error";
  plot.y_floor = 1e-17;
  for (const Method& m : methods) plot.series.push_back({m.legend, {}, m.colour, PlotMarker::none, true});
  for (std::size_t i = 0; i < samples.size(); ++i)
    plot.series.push_back({samples[i], {}, {0.45f, 0.45f, 0.45f}, markers[i % std::size(markers)], false});
  // Drawn in reverse, so that the single points of exact and float lie on top of the curves.
  for (std::size_t i = 0; i < samples.size(); ++i)
    for (auto it = std::rbegin(methods); it != std::rend(methods); ++it) {
      const Method& m = *it;
      PlotSeries series{"", {}, m.colour, markers[i % std::size(markers)], true};
      for (const ErrorRow& r : rows)
        if (r.sample == samples[i] && r.method == m.key) series.points.push_back({r.time_per_sensor_s, r.errors.rms_relative});
      plot.series.push_back(std::move(series));
    }
  plot.notes = {
      fmt::format("Monte Carlo: N = {} ... {} rays per sensor, stratified, density proportional to sky luminance x cosine.",
                  s.samples.front(), s.samples.back()),
      fmt::format("Cubature: Radon's degree-5 rule, adaptive, relative tolerance {:g} ... {:g}; its time includes the exact "
                  "visible region.",
                  s.tolerances.front(), s.tolerances.back()),
      fmt::format("Exact and float: the whole grid{}; Monte Carlo and cubature: {} sensors spread over it. "
                  "Table: scenes_error_vs_time.csv.",
                  s.timing_stride > 1 ? fmt::format(" (every {}th sensor)", s.timing_stride) : "", s.error_sensors),
      "Office, Monte Carlo: sensors at the back see slivers of sky (SC ~ 0.001 %) that few rays hit, and dominate the "
      "RMS; the CSV also has the normalised RMS error.",
  };
  return plot;
}

Plot scaling_plot(const std::vector<ScalingRow>& rows, const std::vector<Fit>& fits) {
  struct Dimension {
    const char* key;
    const char* legend;
    PlotColour colour;
  };
  const Dimension dimensions[] = {{"sensors", "sensors (random, office floor)", {0.15f, 0.40f, 0.85f}},
                                  {"occluders", "occluder polygons (boxes in the street)", {0.80f, 0.15f, 0.15f}},
                                  {"apertures", "apertures (window split into panes)", {0.10f, 0.62f, 0.30f}},
                                  {"edges", "window edges (regular k-gon)", {0.60f, 0.30f, 0.70f}}};
  Plot plot;
  plot.title = "Office: run time against the size of the problem";
  plot.subtitle = fmt::format("CPU time (all {} threads) of the sky component over a grid, best of up to 3 runs",
                              rows.empty() ? 0 : rows.front().threads);
  plot.x_label = "count (sensors, occluder polygons, apertures, edges)";
  plot.y_label = "CPU time (s)";
  for (const Dimension& d : dimensions) {
    std::string legend = d.legend;
    for (const Fit& f : fits)
      if (f.dimension == d.key && f.mode == std::string("exact")) legend += fmt::format(", slope {:.2f}", f.exponent);
    for (const char* mode : {"exact", "float"}) {
      const bool exact = mode == std::string("exact");
      PlotSeries series{exact ? legend : "", {}, d.colour, exact ? PlotMarker::circle : PlotMarker::square, exact};
      for (const ScalingRow& r : rows)
        if (r.dimension == d.key && r.mode == mode) series.points.push_back({r.x, r.cpu_seconds});
      plot.series.push_back(std::move(series));
    }
  }
  plot.series.push_back({"exact geometry: circles, joined", {}, {0.45f, 0.45f, 0.45f}, PlotMarker::circle, true});
  plot.series.push_back({"float geometry: squares", {}, {0.45f, 0.45f, 0.45f}, PlotMarker::square, false});
  std::string exponents;
  for (const Fit& f : fits)
    if (f.mode == std::string("float")) exponents += fmt::format("{}{} {:.2f}", exponents.empty() ? "" : ", ", f.dimension, f.exponent);
  std::size_t sensors = 0;
  for (const ScalingRow& r : rows)
    if (r.dimension != "sensors") sensors = r.sensors;
  plot.notes = {"Exponents: least-squares slopes of log time against log count (legend: exact geometry; float: " + exponents + ").",
                fmt::format("Occluders, apertures and edges on {} sensors of the office grid. Table: scenes_scaling.csv.", sensors)};
  return plot;
}

std::string seconds_text(double s) {
  if (s >= 1) return fmt::format("{:.2f} s", s);
  if (s >= 1e-3) return fmt::format("{:.3g} ms", 1e3 * s);
  return fmt::format("{:.3g} us", 1e6 * s);
}

void print_summary(std::ostream& out, const std::vector<ErrorRow>& rows, const std::vector<SampleResult>& results,
                   const std::vector<ScalingRow>& scaling, const std::vector<Fit>& fits, const std::vector<PairsRow>& pairs,
                   const ScenesSettings& settings) {
  out << "## Error against run time (one core; CPU time per sensor; relative errors where SC_exact > 0)\n\n";
  out << "| sample | method | parameter | CPU time per sensor | wall time | RMS rel. error | max rel. error | normalised RMS | "
         "sky-less sensors given sky |\n";
  out << "|---|---|---|---|---|---|---|---|---|\n";
  for (const ErrorRow& r : rows)
    out << fmt::format("| {} | {} | {} | {} | {} | {:.2e} | {:.2e} | {:.2e} | {} |\n", r.sample, r.method, r.parameter,
                       seconds_text(r.time_per_sensor_s), seconds_text(r.wall_per_sensor_s), r.errors.rms_relative,
                       r.errors.max_relative, r.errors.normalised_rms, r.errors.zero_sky_nonzero);
  out << "\nexact / float CPU time per sensor, one core:";
  for (const SampleResult& s : results)
    out << fmt::format(" {} {:.2f};", s.pairs.sample, s.exact_s_per_sensor / s.float_s_per_sensor);
  out << " (target: at most 2)\n";

  out << "\n## Scaling (CPU time over all threads) and exponents\n\n| dimension | mode | exponent | range |\n|---|---|---|---|\n";
  for (const Fit& f : fits) out << fmt::format("| {} | {} | {:.2f} | {:g} ... {:g} |\n", f.dimension, f.mode, f.exponent, f.x_low, f.x_high);
  const std::size_t largest = settings.sensor_counts.back();
  const ScalingRow *exact = nullptr, *floating = nullptr;
  for (const ScalingRow& r : scaling)
    if (r.dimension == "sensors" && r.parameter == int(largest)) (r.mode == "exact" ? exact : floating) = &r;
  if (exact && floating) {
    const double threads = exact->threads, idle = exact->cpu_seconds / threads;
    out << fmt::format("\noffice, {} random sensors on {} threads: exact {:.2f} s wall, {:.2f} s CPU ({:.2f} s on {} idle cores); "
                       "float {:.2f} s wall, {:.2f} s CPU; exact/float {:.2f} (CPU), {:.2f} (wall)",
                       largest, exact->threads, exact->seconds, exact->cpu_seconds, idle, exact->threads, floating->seconds,
                       floating->cpu_seconds, exact->cpu_seconds / floating->cpu_seconds, exact->seconds / floating->seconds);
    if (largest >= 100000)
      out << fmt::format("\ntargets: 100,000 sensors under 10 s on 2 cores: {} ({:.2f} s of CPU over 2 cores); exact within 2x of "
                         "float: {}\n",
                         exact->cpu_seconds / 2 < 10 ? "met" : "NOT met", exact->cpu_seconds / 2,
                         exact->cpu_seconds <= 2 * floating->cpu_seconds ? "met" : "NOT met");
    else
      out << "\n(--quick: the 100,000-sensor target is measured by the full run)\n";
  }

  out << "\n## What the visibility routine left out (exact geometry)\n\n";
  out << "| sample | grid | pairs | not facing | without clipping | clipped, certified in intervals | needing exact rationals |\n";
  out << "|---|---|---|---|---|---|---|\n";
  for (const PairsRow& p : pairs) {
    const VisibilityCounters& c = p.counters;
    const double n = double(std::max<std::uint64_t>(c.pairs, 1));
    out << fmt::format("| {} | {} | {} | {:.1f} % | {:.1f} % | {:.1f} % | {:.3f} % |\n", p.sample, p.grid, c.pairs,
                       100 * double(c.pairs_not_facing) / n, 100 * double(c.pairs_unobstructed) / n,
                       100 * double(c.pairs_clipped - c.pairs_rational) / n, 100 * double(c.pairs_rational) / n);
  }
  out << "\nThe machine may be shared: CPU times are what the work costs, wall times what it took here.\n";
}

void print_order_summary(std::ostream& out, const std::vector<OrderRow>& rows) {
  out << "\n## Occluders, one core: the subtraction order as built and front to back (the default)\n\n";
  out << "| boxes | occluder polygons | order | sensors | CPU per sensor | pieces clipped per pair | shadows skipped per pair | max rel. "
         "difference to as built |\n|---|---|---|---|---|---|---|---|\n";
  for (const OrderRow& r : rows) {
    const double pairs = double(std::max<std::uint64_t>(r.counters.pairs, 1));
    out << fmt::format("| {} | {} | {} | {} | {} | {:.1f} | {:.1f} | {:.2e} |\n", r.boxes, r.polygons, r.order, r.sensors,
                       seconds_text(r.cpu_seconds / double(r.sensors)), double(r.counters.occluders_clipped) / pairs,
                       double(r.counters.occluders_skipped) / pairs, r.max_relative_difference);
  }
  out << fmt::format("\nexponent in the number of occluder polygons (CPU time per sensor): as built {:.2f}, front to back {:.2f}\n",
                     order_exponent(rows, "as_built"), order_exponent(rows, "front_to_back"));
}

void print_thread_summary(std::ostream& out, const std::vector<ThreadRow>& rows) {
  out << "\n## Threads (office, random sensors, exact)\n\n| sensors | threads | wall | CPU | CPU per sensor | speed-up (wall) |\n"
         "|---|---|---|---|---|---|\n";
  for (const ThreadRow& r : rows) {
    double one = 0;
    for (const ThreadRow& q : rows)
      if (q.sensors == r.sensors && q.threads == 1) one = q.seconds;
    out << fmt::format("| {} | {} | {} | {} | {} | {:.2f} |\n", r.sensors, r.threads, seconds_text(r.seconds), seconds_text(r.cpu_seconds),
                       seconds_text(r.cpu_seconds / double(r.sensors)), one / r.seconds);
  }
}

// ── The sky seen directly (geometry/sky_box.hpp): what a grid flagged as seeing it pays ────────

struct DirectRow {
  std::string grid;
  std::size_t sensors = 0, seeing = 0;  // seeing: sensors whose SC the direct view raises
  double apertures_only_s = 0, with_direct_s = 0;  // CPU per sensor, best of the runs
};

// The sky component of every sensor through the apertures alone, then with the direct view (the
// grid flagged), one core, each the best of `runs`.
DirectRow measure_direct(const std::string& name, const Scene& scene, SensorGrid grid, int runs) {
  grid.sees_sky_directly = true;
  const VisibilityEngine engine(scene, GeometryMode::exact);
  const std::unique_ptr<DirectSky> direct = direct_sky(scene, {grid}, GeometryMode::exact, SubtractionOrder::front_to_back);
  DirectRow row{name, grid.sensors.size(), 0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  const double n = double(grid.sensors.size());
  for (int run = 0; run < runs; ++run) {
    VisibilityCounters counters;
    std::vector<double> alone;
    double c0 = thread_cpu_seconds();
    for (const Sensor& sensor : grid.sensors)
      alone.push_back(sky_component_percent(engine, scene, sensor, SkyModel::cie_overcast, counters));
    row.apertures_only_s = std::min(row.apertures_only_s, (thread_cpu_seconds() - c0) / n);
    row.seeing = 0;
    c0 = thread_cpu_seconds();
    for (std::size_t i = 0; i < grid.sensors.size(); ++i)
      row.seeing += sky_component_percent(engine, scene, grid.sensors[i], SkyModel::cie_overcast, counters, nullptr,
                                          &direct->engine) > alone[i];
    row.with_direct_s = std::min(row.with_direct_s, (thread_cpu_seconds() - c0) / n);
  }
  return row;
}

void write_direct_table(const std::string& path, const std::vector<DirectRow>& rows) {
  std::ofstream f(path);
  f << "grid,sensors,sensors_seeing_sky_directly,apertures_only_cpu_s_per_sensor,with_direct_view_cpu_s_per_sensor,ratio\n";
  for (const DirectRow& r : rows)
    f << fmt::format("{},{},{},{:.6g},{:.6g},{:.4g}\n", r.grid, r.sensors, r.seeing, r.apertures_only_s, r.with_direct_s,
                     r.with_direct_s / r.apertures_only_s);
}

void print_direct_summary(std::ostream& out, const std::vector<DirectRow>& rows) {
  out << "\n## The sky seen directly (one core, exact; the grid flagged as seeing it)\n\n"
         "| grid | sensors | seeing it | apertures only | with the direct view | ratio |\n|---|---|---|---|---|---|\n";
  for (const DirectRow& r : rows)
    out << fmt::format("| {} | {} | {} | {} | {} | {:.2f} |\n", r.grid, r.sensors, r.seeing, seconds_text(r.apertures_only_s),
                       seconds_text(r.with_direct_s), r.with_direct_s / r.apertures_only_s);
}

// ── MPI ranks: `mpirun -n R daylit df` on the office with boxes ─────────────────────────────

struct MpiRow {
  int ranks = 0;     // 0: one process without mpirun (the reference)
  double seconds = 0;  // wall, best of the runs: process start and MPI's launch included
  bool identical = true;  // the CSV byte for byte the single process's
};

std::string file_text(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// This executable's `df` on the office with the most boxes of the scaling (the model written into
// `dir`) and the sensors of `grid`, one thread per process: alone, then under `mpirun -n 1` and
// `-n 2` (issue 13, part 4: the speed-up over ranks and that they change nothing). Needs a
// DAYLIT_MPI build and mpirun on the PATH; otherwise no rows, and `note` says why.
std::vector<MpiRow> measure_mpi(const std::filesystem::path& dir, const std::filesystem::path& grid, bool mpi_build,
                                int runs, std::string& note) {
  if (!mpi_build) {
    note = "not measured: this daylit is built without DAYLIT_MPI (cmake -DDAYLIT_MPI=ON)";
    return {};
  }
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0) {
    note = "not measured: mpirun is not on the PATH";
    return {};
  }
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  const auto quoted = [](const std::filesystem::path& p) { return "'" + p.string() + "'"; };
  // OpenMPI refuses root without --allow-run-as-root; two ranks on fewer cores need --oversubscribe.
  const std::string launch = std::string("mpirun --oversubscribe") + (geteuid() == 0 ? " --allow-run-as-root" : "");
  const std::filesystem::path reference = dir / "scenes_mpi_ranks_0.csv";
  std::vector<MpiRow> rows;
  for (const int ranks : {0, 1, 2}) {
    const std::filesystem::path csv = dir / fmt::format("scenes_mpi_ranks_{}.csv", ranks);
    const std::string command =
        (ranks > 0 ? fmt::format("{} -n {} ", launch, ranks) : std::string()) + quoted(self) + " df --scene " +
        quoted(dir / "scenes_boxes_scene.rad") + " --apertures " + quoted(dir / "scenes_boxes_apertures.rad") + " --grid " +
        quoted(grid) + " --threads 1 --quiet --out " + quoted(csv) + " > /dev/null 2>&1";
    MpiRow row{ranks, std::numeric_limits<double>::infinity(), true};
    for (int run = 0; run < runs; ++run) {
      const auto t0 = clock_type::now();
      if (std::system(command.c_str()) != 0) {
        note = "failed: " + command;
        return rows;
      }
      row.seconds = std::min(row.seconds, seconds_since(t0));
    }
    row.identical = ranks == 0 || file_text(csv) == file_text(reference);
    if (ranks > 0) std::filesystem::remove(csv);
    rows.push_back(row);
  }
  std::filesystem::remove(reference);
  note = "the office with the most boxes of the scaling (scenes_boxes_*) on " + grid.string() +
         ", daylit df --threads 1 per process; the wall times include starting the processes and, under mpirun, MPI";
  return rows;
}

void write_mpi_table(const std::string& path, const std::vector<MpiRow>& rows, const std::string& note) {
  std::ofstream f(path);
  f << "# " << note << "\n";
  f << "ranks,wall_s,speed_up_wall,identical_to_one_process\n";
  for (const MpiRow& r : rows)
    f << fmt::format("{},{:.4e},{:.3f},{}\n", r.ranks == 0 ? std::string("none") : std::to_string(r.ranks), r.seconds,
                     rows.front().seconds / r.seconds, r.identical ? "yes" : "no");
  if (!f) throw Error(path + ": cannot write");
}

void print_mpi_summary(std::ostream& out, const std::vector<MpiRow>& rows, const std::string& note) {
  out << "\n## MPI ranks (" << note << ")\n";
  if (rows.empty()) return;
  out << "\n| ranks | wall | speed-up (wall) | CSV identical to one process |\n|---|---|---|---|\n";
  for (const MpiRow& r : rows)
    out << fmt::format("| {} | {} | {:.2f} | {} |\n", r.ranks == 0 ? std::string("none (no mpirun)") : std::to_string(r.ranks),
                       seconds_text(r.seconds), rows.front().seconds / r.seconds, r.identical ? "yes" : "no");
}

void print_floor_summary(std::ostream& out, const std::vector<FloorRow>& rows) {
  out << "\n## The generated office floor (one core; every window from sensors in a few rooms)\n\n";
  out << "| rooms | glazing | occluder polygons | apertures | pairs | CPU per pair | covered | clipped | pieces clipped per pair |\n";
  out << "|---|---|---|---|---|---|---|---|---|\n";
  for (const FloorRow& r : rows) {
    const double pairs = double(r.sensors * r.apertures);
    out << fmt::format("| {} | {} | {} | {} | {} | {} | {:.1f} % | {:.1f} % | {:.1f} |\n", r.rooms, r.glazing, r.polygons, r.apertures,
                       r.sensors * r.apertures, seconds_text(r.cpu_seconds / pairs), 100 * double(r.counters.pairs_covered) / pairs,
                       100 * double(r.counters.pairs_clipped) / pairs, double(r.counters.occluders_clipped) / pairs);
  }
}

}  // namespace

int run_bench_scenes(const BenchOptions& opt) {
  const auto t0 = clock_type::now();
  const ScenesSettings settings = settings_for(opt.quick);
  std::error_code ec;
  std::filesystem::create_directories(opt.out, ec);
  if (!std::filesystem::is_directory(opt.out)) throw Error(opt.out + ": cannot create the output directory");
  const std::filesystem::path dir(opt.out);

  const std::vector<Sample> samples{load_sample(opt.samples, "office"), load_sample(opt.samples, "hall")};
  std::vector<SampleResult> results;
  std::vector<ErrorRow> rows;
  std::vector<PairsRow> pairs;
  std::vector<ScalingRow> scaling;
  std::vector<FloorRow> floor_rows;
  std::vector<OrderRow> order_rows;
  std::vector<ThreadRow> thread_rows;
  std::vector<DirectRow> direct_rows;
  Floor floor;
  {
    bench::StatusLine status(!opt.quiet && stderr_is_terminal());
    for (const Sample& s : samples) {
      results.push_back(measure_sample(s, settings, status));
      rows.insert(rows.end(), results.back().rows.begin(), results.back().rows.end());
      pairs.push_back(results.back().pairs);
    }
    PairsRow large{};
    scaling = measure_scaling(samples.front(), settings, status, large);
    pairs.push_back(large);
    floor_rows = measure_floor(samples.front(), settings.floor_rooms, settings.timing_runs, status, floor);
    order_rows = measure_orders(samples.front(), settings.order_boxes, settings.scaling_stride, status);
    thread_rows = measure_threads(samples.front(), settings.thread_sensors, settings.scaling_runs, status);
    // Enclosed grids (nothing seen directly: the cost of a flag set in vain) and the office's grid
    // lifted 40 m, above its roof (every sensor sees the whole sky).
    for (const Sample& sample : samples)
      direct_rows.push_back(measure_direct(sample.name, sample.scene, every_kth(sample.grid, settings.scaling_stride),
                                           settings.timing_runs));
    SensorGrid lifted = every_kth(samples.front().grid, settings.scaling_stride);
    for (Sensor& sensor : lifted.sensors) sensor.position.z += 40;
    direct_rows.push_back(measure_direct("office + 40 m", samples.front().scene, lifted, settings.timing_runs));
    status.clear();
  }
  const std::vector<Fit> fits = fit_exponents(scaling);
  std::vector<std::string> names;
  for (const Sample& s : samples) names.push_back(s.name);

  StagedOutputs outputs;
  const auto file = [&](const char* name) { return (dir / name).string(); };
  write_error_table(outputs.stage(file("scenes_error_vs_time.csv")), rows);
  write_scaling_table(outputs.stage(file("scenes_scaling.csv")), scaling);
  write_fit_table(outputs.stage(file("scenes_scaling_fit.csv")), fits);
  write_pairs_table(outputs.stage(file("scenes_pairs.csv")), pairs);
  write_floor_table(outputs.stage(file("scenes_floor.csv")), floor_rows);
  write_order_table(outputs.stage(file("scenes_occluders_one_core.csv")), order_rows);
  write_thread_table(outputs.stage(file("scenes_threads.csv")), thread_rows);
  write_direct_table(outputs.stage(file("scenes_direct.csv")), direct_rows);
  write_model(floor, outputs.stage(file("scenes_floor_scene.rad")), outputs.stage(file("scenes_floor_apertures.rad")),
              outputs.stage(file("scenes_floor_grid.pts")));
  // The office with the most boxes of the scaling (665 polygons with 128), on the sensors it used.
  Floor boxes{office_with_boxes(samples.front().scene, settings.boxes.back()), every_kth(samples.front().grid, settings.scaling_stride)};
  boxes.grid.name = fmt::format("office with {} boxes", settings.boxes.back());
  write_model(boxes, outputs.stage(file("scenes_boxes_scene.rad")), outputs.stage(file("scenes_boxes_apertures.rad")),
              outputs.stage(file("scenes_boxes_grid.pts")));
  write_loglog_plot(outputs.stage(file("scenes_error_vs_time.png")), error_plot(rows, names, settings));
  write_loglog_plot(outputs.stage(file("scenes_scaling.png")), scaling_plot(scaling, fits));
  outputs.commit();
  // MPI ranks on the model just written (processes of this executable, under mpirun).
  std::string mpi_note;
  // The whole office grid (2,400 sensors), where the ranks have work enough to show; --quick: the
  // scaling's every 8th sensor.
  const std::filesystem::path mpi_grid = opt.quick ? dir / "scenes_boxes_grid.pts"
                                                   : std::filesystem::path(opt.samples) / "office" / "grid.pts";
  const std::vector<MpiRow> mpi_rows = measure_mpi(dir, mpi_grid, opt.mpi_build, opt.quick ? 1 : 3, mpi_note);
  {
    StagedOutputs mpi_output;
    write_mpi_table(mpi_output.stage(file("scenes_mpi.csv")), mpi_rows, mpi_note);
    mpi_output.commit();
  }
  print_summary(std::cout, rows, results, scaling, fits, pairs, settings);  // the results: stdout even with --quiet
  print_floor_summary(std::cout, floor_rows);
  print_order_summary(std::cout, order_rows);
  print_thread_summary(std::cout, thread_rows);
  print_direct_summary(std::cout, direct_rows);
  print_mpi_summary(std::cout, mpi_rows, mpi_note);
  if (!opt.quiet)
    std::cerr << fmt::format("bench scenes: wrote scenes_error_vs_time.csv/.png, scenes_scaling.csv/.png, scenes_scaling_fit.csv, "
                             "scenes_pairs.csv, scenes_floor.csv, the largest floor (scenes_floor_scene.rad, "
                             "scenes_floor_apertures.rad, scenes_floor_grid.pts), the office with boxes (scenes_boxes_*), "
                             "scenes_occluders_one_core.csv, scenes_threads.csv, scenes_direct.csv and scenes_mpi.csv "
                             "into {} ({:.1f} s)\n",
                             opt.out, seconds_since(t0));
  return 0;
}

}  // namespace daylit::cli
