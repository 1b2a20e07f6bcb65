// `daylit bench reflections`: error against run time of the reflected components (ERC + IRC,
// DESIGN.md §4, §8). Today it measures the Monte Carlo path tracer (bench/path_tracer.hpp) at
// N = 16 … 4096 paths per sensor and B = 1 … 16 bounces, and the radiosity
// (simulation/reflected_components.hpp) at element sizes 4, 2 and 1 times its automatic one.
//
// Cases (bench/reflection_cases.hpp): two with closed forms (a plate over upward sensors; a box
// with an open ceiling, Howell's factors), whose reference is exact; and two rooms without one, the
// bundled office (glazed, with its overhang, the building across the street and the ground surface;
// every 30th sensor of grid.pts) and the 4 × 5 × 3 m side-lit room (80 sensors), whose reference is
// a long path-traced run (N = 65,536, B = 16, another seed), stated as such in every row with its
// own standard error, the floor under which no error can be measured.
//
// reflections_error_vs_time.csv: case, method, samples, bounces, sensors, CPU seconds per sensor
// (one thread: the run in a one-thread arena, thread CPU time), RMS over the sensors of the error
// of ERC + IRC (percent DF) and that RMS over the reference's RMS (normalised), the RMS errors of
// ERC and IRC apart, the RMS of the estimate's own standard error, the reference and its RMS
// standard error. reflections_error_vs_time.png: normalised error against CPU time, per case at
// B = 16, and the side-lit room also at B = 1, 2, 4 (truncation). reflections_reference.csv: the
// references per sensor (components and standard errors), what the radiosity is checked against;
// reflections_reference_bounces.csv: the long runs' ERC and IRC per sensor and bounce.

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>

#include "bench/bench_suites.hpp"
#include "bench/path_tracer.hpp"
#include "bench/reflection_cases.hpp"
#include "geometry/error.hpp"
#include "materials/scene_materials.hpp"
#include "materials/surface_reflectance.hpp"
#include "report/plot.hpp"
#include "report/progress_bar.hpp"
#include "report/staged_output.hpp"
#include "simulation/reflected_components.hpp"

namespace daylit::cli {

namespace {

using bench::StatusLine;
using bench::thread_cpu_seconds;
using reflection_cases::ReflectionCase;

struct Settings {
  std::vector<long> samples;
  std::vector<int> bounces;
  long reference_samples;
  int reference_bounces;
  std::size_t office_stride, room_stride;
};

Settings settings(bool quick) {
  if (quick) return {{16, 256}, {1, 4, 8}, 4096, 8, 480, 4};
  return {{16, 64, 256, 1024, 4096}, {1, 2, 4, 8, 16}, 65536, 16, 30, 1};
}

// The reference per sensor: the closed forms, or a long run.
struct Reference {
  std::vector<double> sc, erc, irc, sc_se, erc_se, irc_se, df, df_se;
  std::string description;
  double rms_standard_error = 0;  // RMS over sensors of the reference's σ of ERC + IRC
  std::vector<PathTracedSensor> traced;  // the long run itself (empty for closed forms): per bounce
};

struct Row {
  std::string case_name, method;
  long samples;
  int bounces;
  std::size_t sensors;
  double cpu_s_per_sensor, reflected_rms, reflected_normalised, erc_rms, irc_rms, standard_error_rms;
  std::string reference;
  double reference_se;
};

double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s / double(v.size()));
}

PathTracerOptions tracer_options(const ReflectionCase& c, long samples, int bounces, std::uint64_t seed) {
  PathTracerOptions o;
  o.samples_per_sensor = samples;
  o.max_bounces = bounces;
  o.ground_reflectance = c.ground_reflectance;
  o.sky = c.sky;
  o.seed = seed;
  return o;
}

Reference reference_of(const ReflectionCase& c, const Settings& s) {
  Reference r;
  if (c.exact) {
    r.sc = c.sc, r.erc = c.erc, r.irc = c.irc;
    r.sc_se = r.erc_se = r.irc_se = r.df_se = std::vector<double>(c.sensors.size(), 0.0);
    for (std::size_t i = 0; i < c.sensors.size(); ++i) r.df.push_back(c.sc[i] + c.erc[i] + c.irc[i]);
    r.description = "closed form";
    return r;
  }
  const auto traced = path_trace(c.scene, c.sensors, tracer_options(c, s.reference_samples, s.reference_bounces, 1));
  std::vector<double> se;
  for (const PathTracedSensor& t : traced) {
    r.sc.push_back(t.sc.value), r.sc_se.push_back(t.sc.standard_error);
    r.erc.push_back(t.erc.value), r.erc_se.push_back(t.erc.standard_error);
    r.irc.push_back(t.irc.value), r.irc_se.push_back(t.irc.standard_error);
    r.df.push_back(t.df.value), r.df_se.push_back(t.df.standard_error);
    // σ of ERC + IRC from those of the parts (they are correlated: the bound σ_E + σ_I).
    se.push_back(t.erc.standard_error + t.irc.standard_error);
  }
  r.rms_standard_error = rms(se);
  r.traced = traced;
  r.description = fmt::format("path tracer N={} B={} seed 1 (no closed form)", s.reference_samples, s.reference_bounces);
  return r;
}

Row measure(const ReflectionCase& c, const Reference& ref, long samples, int bounces) {
  std::vector<PathTracedSensor> traced;
  double cpu = 0;
  // One thread, so that thread CPU time is the serial cost (the machine is shared).
  tbb::task_arena(1).execute([&] {
    const double t0 = thread_cpu_seconds();
    traced = path_trace(c.scene, c.sensors, tracer_options(c, samples, bounces, 1000 + std::uint64_t(samples) * 31 + std::uint64_t(bounces)));
    cpu = thread_cpu_seconds() - t0;
  });
  std::vector<double> reflected, erc, irc, reflected_ref, se;
  for (std::size_t i = 0; i < traced.size(); ++i) {
    reflected.push_back(traced[i].erc.value + traced[i].irc.value - ref.erc[i] - ref.irc[i]);
    erc.push_back(traced[i].erc.value - ref.erc[i]);
    irc.push_back(traced[i].irc.value - ref.irc[i]);
    reflected_ref.push_back(ref.erc[i] + ref.irc[i]);
    se.push_back(traced[i].erc.standard_error + traced[i].irc.standard_error);
  }
  const double error = rms(reflected);
  return {c.name, "path_tracer", samples, bounces, c.sensors.size(), cpu / double(c.sensors.size()), error,
          error / rms(reflected_ref), rms(erc), rms(irc), rms(se), ref.description, ref.rms_standard_error};
}

// The radiosity (simulation/reflected_components.hpp) on the case at `size_factor` times its
// automatic element size (reflected_components.hpp: a fifth of the grid's extent), on one
// thread, its setup (visibility engines, mesh) included in the time; `samples` holds its element
// count, `bounces` its Gauss–Seidel sweeps. Its own error estimate is not in the row: the row
// measures the actual error against the reference.
Row measure_radiosity(const ReflectionCase& c, const Reference& ref, double size_factor) {
  const std::vector<double> reflectance = scene_reflectances(c.scene).reflectance;
  SensorGrid grid;
  grid.name = c.name;
  grid.sensors = c.sensors;
  ReflectionOptions o;
  o.sky = c.sky;
  o.ground_reflectance = c.ground_reflectance;
  o.element_size = size_factor * automatic_element_size(c.scene, {&grid});
  ReflectionResult result;
  double cpu = 0;
  tbb::task_arena(1).execute([&] {
    const double t0 = thread_cpu_seconds();
    const VisibilityEngine engine(c.scene, GeometryMode::exact);
    result = reflected_components(c.scene, reflectance, engine, {&grid}, o);
    cpu = thread_cpu_seconds() - t0;
  });
  std::vector<double> reflected, erc, irc, reflected_ref;
  for (std::size_t i = 0; i < c.sensors.size(); ++i) {
    const double e = result.grids[0].erc_percent[i], r = result.grids[0].irc_percent[i];
    reflected.push_back(e + r - ref.erc[i] - ref.irc[i]);
    erc.push_back(e - ref.erc[i]);
    irc.push_back(r - ref.irc[i]);
    reflected_ref.push_back(ref.erc[i] + ref.irc[i]);
  }
  const double error = rms(reflected);
  return {c.name, "radiosity", long(result.elements), result.sweeps, c.sensors.size(), cpu / double(c.sensors.size()),
          error, error / rms(reflected_ref), rms(erc), rms(irc), 0.0, ref.description, ref.rms_standard_error};
}

ReflectionCase office_case(const std::string& samples_dir, std::size_t stride) {
  const std::filesystem::path base = std::filesystem::path(samples_dir) / "office";
  if (!std::filesystem::exists(base / "scene.rad"))
    throw Error((base / "scene.rad").string() + ": not found; give the folder of the bundled samples with --samples DIR");
  ReflectionCase c;
  c.name = "office";
  c.description = fmt::format("samples/office (glazed, overhang, obstruction, ground surface 0.15), far ground 0.2, CIE overcast, every {}th sensor", stride);
  c.scene = load_scene({(base / "scene.rad").string()}, {(base / "apertures.rad").string()});
  c.sky = SkyModel::cie_overcast;
  const SensorGrid grid = read_sensor_grid((base / "grid.pts").string());
  for (std::size_t i = 0; i < grid.sensors.size(); i += stride) c.sensors.push_back(grid.sensors[i]);
  return c;
}

}  // namespace

int run_bench_reflections(const BenchOptions& opt) {
  const auto t_start = bench::clock_type::now();
  const Settings s = settings(opt.quick);
  std::vector<ReflectionCase> cases{reflection_cases::canopy_case(), reflection_cases::open_ceiling_box_case(),
                                    office_case(opt.samples, s.office_stride), reflection_cases::side_lit_room_case()};
  {
    ReflectionCase& room = cases.back();
    std::vector<Sensor> kept;
    for (std::size_t i = 0; i < room.sensors.size(); i += s.room_stride) kept.push_back(room.sensors[i]);
    room.sensors = std::move(kept);
  }
  StatusLine status(!opt.quiet && stderr_is_terminal());
  std::vector<Row> rows;
  std::vector<Reference> references;
  for (const ReflectionCase& c : cases) {
    status.show(fmt::format("bench reflections: {}: reference", c.name));
    const auto r0 = bench::clock_type::now();
    references.push_back(reference_of(c, s));
    const double reference_seconds = bench::seconds_since(r0);
    if (!opt.quiet && !c.exact)
      std::cerr << fmt::format("bench reflections: {} reference ({}, {} sensors): {:.1f} s wall, all threads\n", c.name,
                               references.back().description, c.sensors.size(), reference_seconds);
    for (const int b : s.bounces)
      for (const long n : s.samples) {
        status.show(fmt::format("bench reflections: {}: N = {}, B = {}", c.name, n, b));
        rows.push_back(measure(c, references.back(), n, b));
      }
    // The radiosity's rows: 4, 2 and 1 times its automatic element size (--quick: 8 and 4),
    // against the same reference, timed the same way.
    for (const double factor : opt.quick ? std::vector<double>{8, 4} : std::vector<double>{4, 2, 1}) {
      status.show(fmt::format("bench reflections: {}: radiosity, {} x the automatic element size", c.name, factor));
      rows.push_back(measure_radiosity(c, references.back(), factor));
    }
  }
  status.clear();

  const std::filesystem::path dir(opt.out);
  std::filesystem::create_directories(dir);
  StagedOutputs outputs;
  const std::string csv = (dir / "reflections_error_vs_time.csv").string(), png = (dir / "reflections_error_vs_time.png").string(),
                    ref_csv = (dir / "reflections_reference.csv").string(),
                    bounces_csv = (dir / "reflections_reference_bounces.csv").string();
  {
    std::ofstream f(outputs.stage(csv));
    f << "case,method,samples,bounces,sensors,cpu_s_per_sensor,reflected_rms_error_percent,reflected_normalised_rms_error,"
         "erc_rms_error_percent,irc_rms_error_percent,standard_error_rms_percent,reference,reference_standard_error_rms_percent\n";
    for (const Row& r : rows)
      f << fmt::format("{},{},{},{},{},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{},{:.4e}\n", r.case_name, r.method, r.samples,
                       r.bounces, r.sensors, r.cpu_s_per_sensor, r.reflected_rms, r.reflected_normalised, r.erc_rms, r.irc_rms,
                       r.standard_error_rms, r.reference, r.reference_se);
    if (!f) throw Error(csv + ": cannot write");
  }
  {
    std::ofstream f(outputs.stage(ref_csv));
    f << "case,index,x,y,z,dx,dy,dz,sc_percent,sc_se,erc_percent,erc_se,irc_percent,irc_se,df_percent,df_se,reference\n";
    for (std::size_t k = 0; k < cases.size(); ++k)
      for (std::size_t i = 0; i < cases[k].sensors.size(); ++i) {
        const Sensor& x = cases[k].sensors[i];
        const Reference& r = references[k];
        f << fmt::format("{},{},{:g},{:g},{:g},{:g},{:g},{:g},{:.6g},{:.2e},{:.6g},{:.2e},{:.6g},{:.2e},{:.6g},{:.2e},{}\n", cases[k].name,
                         i, x.position.x, x.position.y, x.position.z, x.normal.x, x.normal.y, x.normal.z, r.sc[i], r.sc_se[i],
                         r.erc[i], r.erc_se[i], r.irc[i], r.irc_se[i], r.df[i], r.df_se[i], r.description);
      }
    if (!f) throw Error(ref_csv + ": cannot write");
  }
  {
    // The long runs bounce by bounce: what a radiosity's Jacobi sweeps can be compared with.
    std::ofstream f(outputs.stage(bounces_csv));
    f << "case,index,bounce,erc_percent,erc_se,irc_percent,irc_se\n";
    for (std::size_t k = 0; k < cases.size(); ++k)
      for (std::size_t i = 0; i < references[k].traced.size(); ++i) {
        const PathTracedSensor& t = references[k].traced[i];
        for (std::size_t b = 0; b < t.irc_by_bounce.size(); ++b)
          f << fmt::format("{},{},{},{:.6g},{:.2e},{:.6g},{:.2e}\n", cases[k].name, i, b, t.erc_by_bounce[b].value,
                           t.erc_by_bounce[b].standard_error, t.irc_by_bounce[b].value, t.irc_by_bounce[b].standard_error);
      }
    if (!f) throw Error(bounces_csv + ": cannot write");
  }
  Plot plot;
  plot.title = "Reflected components (ERC + IRC): error against run time";
  plot.subtitle = fmt::format("path tracer, N = {} ... {} paths per sensor (circles); radiosity (squares); CPU time per "
                              "sensor on one thread", s.samples.front(), s.samples.back());
  plot.x_label = "CPU time per sensor (s)";
  plot.y_label = "RMS error of ERC + IRC / RMS of the reference";
  plot.y_floor = 1e-6;
  const std::vector<PlotColour> colours{{0.15f, 0.35f, 0.75f}, {0.85f, 0.35f, 0.1f}, {0.2f, 0.6f, 0.25f}, {0.55f, 0.2f, 0.6f}};
  const int full = s.bounces.back();
  for (std::size_t k = 0; k < cases.size(); ++k) {
    PlotSeries series{fmt::format("{}, B = {} ({})", cases[k].name, full, cases[k].exact ? "closed form" : "vs long run"), {},
                      colours[k % colours.size()], PlotMarker::circle, true};
    for (const Row& r : rows)
      if (r.method == "path_tracer" && r.case_name == cases[k].name && r.bounces == full)
        series.points.push_back({r.cpu_s_per_sensor, r.reflected_normalised});
    plot.series.push_back(series);
    PlotSeries radiosity{fmt::format("{}, radiosity", cases[k].name), {}, colours[k % colours.size()], PlotMarker::square, true};
    for (const Row& r : rows)
      if (r.method == "radiosity" && r.case_name == cases[k].name)
        radiosity.points.push_back({r.cpu_s_per_sensor, std::max(r.reflected_normalised, 1e-6)});
    plot.series.push_back(radiosity);
  }
  const PlotMarker markers[] = {PlotMarker::triangle, PlotMarker::square, PlotMarker::diamond};
  std::size_t m = 0;
  for (const int b : s.bounces) {
    if (b == full || m >= std::size(markers)) continue;
    PlotSeries series{fmt::format("{}, B = {} (truncated)", cases.back().name, b), {}, colours[3], markers[m++], true};
    for (const Row& r : rows)
      if (r.method == "path_tracer" && r.case_name == cases.back().name && r.bounces == b)
        series.points.push_back({r.cpu_s_per_sensor, r.reflected_normalised});
    plot.series.push_back(series);
  }
  plot.notes = {"Rooms without a closed form are measured against a long path-traced run (reflections_reference.csv), whose own",
                "standard error is the floor of what can be measured (reference_standard_error_rms_percent in the CSV)."};
  write_loglog_plot(outputs.stage(png), plot);
  outputs.commit();

  if (!opt.quiet) {
    std::cerr << fmt::format("{:>18} {:>6} {:>3} {:>12} {:>12} {:>12} {:>12}\n", "case", "N", "B", "s/sensor", "RMS err %", "normalised",
                             "RMS sigma %");
    for (const Row& r : rows)
      std::cerr << fmt::format("{:>18} {:>6} {:>3} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e}\n", r.case_name, r.samples, r.bounces,
                               r.cpu_s_per_sensor, r.reflected_rms, r.reflected_normalised, r.standard_error_rms);
    for (std::size_t k = 0; k < cases.size(); ++k) {
      if (cases[k].exact) continue;
      const Reference& r = references[k];
      const auto mean = [](const std::vector<double>& v) {
        double t = 0;
        for (double x : v) t += x;
        return t / double(v.size());
      };
      // The grid mean's σ: the sensors' estimates are independent, so σ² adds over them.
      const auto mean_se = [](const std::vector<double>& v) {
        double t = 0;
        for (double x : v) t += x * x;
        return std::sqrt(t) / double(v.size());
      };
      std::cerr << fmt::format("{} reference grid mean ({} sensors): SC {:.4f} ± {:.4f}, ERC {:.4f} ± {:.4f}, IRC {:.4f} ± {:.4f}, "
                               "DF {:.4f} ± {:.4f} %\n",
                               cases[k].name, cases[k].sensors.size(), mean(r.sc), mean_se(r.sc_se), mean(r.erc), mean_se(r.erc_se),
                               mean(r.irc), mean_se(r.irc_se), mean(r.df), mean_se(r.df_se));
    }
    std::cerr << fmt::format("bench reflections: wrote {}, {}, {}, {} ({:.1f} s)\n", csv, png, ref_csv, bounces_csv,
                             bench::seconds_since(t_start));
  }
  return 0;
}

}  // namespace daylit::cli
