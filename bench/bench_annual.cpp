// `daylit bench annual`: error against run time of the annual sky (DESIGN.md §5, §8) on the
// bundled samples, every path against one reference run:
//   - the exact path (the smooth basis and the circumsolar term about the sun) at basis degrees
//     8, 16, 32 and circumsolar tolerances 1e-3 and 1e-6, against the same path at degree 48 and
//     tolerance 1e-9 (the reference);
//   - the sky in Reinhart patches integrated exactly (--sky-patches MF 1, 2, 4, 6), the sun exact:
//     what the discretisation alone changes;
//   - the sampled baseline, a patch-based tool's 2-phase sky (bench/path_tracer.hpp:
//     sampled_patch_coefficients, Tregenza's MF 1 patches at N = 64 … 16,384 cosine-distributed
//     rays per sensor, this project's own ray casting), the sun exact: discretisation and noise.
// Every run has the blinds open (closed transmittance 1), so that all compare the same light.
//
// annual_error_vs_time.csv: case, method, parameter, sensors, hours with a sky, CPU seconds per
// sensor (one thread; the sky's hours, built once per run for every sensor, apart in sky_cpu_s),
// the RMS over sensor-hours of the illuminance error over the reference's RMS, the 95th
// percentile of the relative error over sensor-hours above 50 lx, the share of occupied
// sensor-hours on the other side of 300 lx from the reference, and the mean DA300 difference
// (percentage points). annual_error_vs_time.png: the normalised RMS error against CPU time.

#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>

#include "bench/bench_suites.hpp"
#include "bench/path_tracer.hpp"
#include "geometry/error.hpp"
#include "geometry/sensor_grid.hpp"
#include "materials/scene_materials.hpp"
#include "report/plot.hpp"
#include "report/staged_output.hpp"
#include "simulation/annual.hpp"
#include "sky/weather_file.hpp"

namespace daylit::cli {

namespace {

using bench::StatusLine;
using bench::thread_cpu_seconds;

struct Case {
  std::string name;
  Scene scene;
  SensorGrid grid;
};

Case load_case(const std::filesystem::path& dir, const std::string& name, std::size_t stride) {
  const std::filesystem::path base = dir / name;
  if (!std::filesystem::exists(base / "scene.rad"))
    throw Error((base / "scene.rad").string() + ": not found; give the folder of the bundled samples with --samples DIR");
  Case c{name, load_scene({(base / "scene.rad").string()}, {(base / "apertures.rad").string()}), {}};
  const SensorGrid all = read_sensor_grid((base / "grid.pts").string());
  c.grid.name = all.name;
  c.grid.path = all.path;
  for (std::size_t i = 0; i < all.sensors.size(); i += stride) c.grid.sensors.push_back(all.sensors[i]);
  return c;
}

struct Run {
  std::vector<float> illuminance;  // [sensor × hours]
  std::vector<float> direct_sun;
  double cpu_s = 0, sky_cpu_s = 0;
};

// One annual run of a case on one thread: the sky's hours, then the grid.
Run annual_run(const Case& c, const VisibilityEngine& engine, const WeatherFile& weather, const Site& site,
               const AnnualOptions& options) {
  Run r;
  tbb::task_arena(1).execute([&] {
    double t0 = thread_cpu_seconds();
    const AnnualSky sky = annual_sky(weather, site, options);
    r.sky_cpu_s = thread_cpu_seconds() - t0;
    t0 = thread_cpu_seconds();
    AnnualGridResult g = annual_grid(engine, c.scene, c.grid, sky, options);
    r.cpu_s = thread_cpu_seconds() - t0;
    r.illuminance = std::move(g.illuminance);
    r.direct_sun = std::move(g.direct_sun);
  });
  return r;
}

struct Row {
  std::string case_name, method, parameter;
  std::size_t sensors = 0, sky_hours = 0;
  double cpu_s_per_sensor = 0, sky_cpu_s = 0, rms_normalised = 0, p95_relative = 0, flipped_share = 0, da300_difference = 0;
};

// The errors of `values` against the reference, over every sensor-hour.
void measure(Row& row, const std::vector<float>& values, const std::vector<float>& reference, const std::vector<bool>& occupied,
             std::size_t sensors, std::size_t hours) {
  double square = 0, reference_square = 0, flipped = 0, occupied_count = 0, da_difference = 0;
  std::vector<double> relative;
  for (std::size_t i = 0; i < sensors; ++i) {
    double da = 0, da_ref = 0, occupied_hours = 0;
    for (std::size_t h = 0; h < hours; ++h) {
      const double v = values[i * hours + h], e = reference[i * hours + h];
      square += (v - e) * (v - e);
      reference_square += e * e;
      if (e > 50) relative.push_back(std::abs(v - e) / e);
      if (!occupied[h]) continue;
      ++occupied_hours;
      da += v >= 300;
      da_ref += e >= 300;
      flipped += (v >= 300) != (e >= 300);
    }
    occupied_count += occupied_hours;
    if (occupied_hours > 0) da_difference += 100 * (da - da_ref) / occupied_hours;
  }
  row.rms_normalised = reference_square > 0 ? std::sqrt(square / reference_square) : 0;
  if (!relative.empty()) {
    std::sort(relative.begin(), relative.end());
    row.p95_relative = relative[std::min(relative.size() - 1, std::size_t(0.95 * double(relative.size())))];
  }
  row.flipped_share = occupied_count > 0 ? flipped / occupied_count : 0;
  row.da300_difference = sensors > 0 ? da_difference / double(sensors) : 0;
}

}  // namespace

int run_bench_annual(const BenchOptions& opt) {
  const auto t_start = bench::clock_type::now();
  StatusLine status(!opt.quiet && isatty(2));
  const WeatherFile weather = read_weather_file(opt.weather);
  const Site site = Site::geographic(weather.location.latitude_deg, weather.location.longitude_deg,
                                     weather.location.elevation_m, 0);
  const std::size_t office_stride = opt.quick ? 240 : 40, hall_stride = opt.quick ? 1152 : 128;
  std::vector<Case> cases;
  cases.push_back(load_case(opt.samples, "office", office_stride));
  cases.push_back(load_case(opt.samples, "hall", hall_stride));

  AnnualOptions base;
  base.closed_blind_transmittance = 1;  // blinds have no effect: every path compares the same light
  std::vector<Row> rows;
  for (const Case& c : cases) {
    const VisibilityEngine engine(c.scene, GeometryMode::exact);
    const std::size_t n = c.grid.sensors.size();
    status.show(fmt::format("annual {}: reference (degree 48; circumsolar 1e-9)", c.name));
    AnnualOptions reference_options = base;
    reference_options.degree = 48;
    reference_options.circumsolar_tolerance = 1e-9;
    const Run reference = annual_run(c, engine, weather, site, reference_options);
    const AnnualSky reference_sky = annual_sky(weather, site, reference_options);
    const std::size_t hours = reference_sky.hours.size();
    std::size_t sky_hours = 0;
    std::vector<bool> occupied(hours);
    for (std::size_t h = 0; h < hours; ++h) {
      occupied[h] = reference_sky.hours[h].occupied;
      sky_hours += reference_sky.hours[h].sky;
    }
    const auto add_row = [&](const std::string& method, const std::string& parameter, const Run& run) {
      Row row{c.name, method, parameter, n, sky_hours};
      row.cpu_s_per_sensor = run.cpu_s / double(n);
      row.sky_cpu_s = run.sky_cpu_s;
      measure(row, run.illuminance, reference.illuminance, occupied, n, hours);
      rows.push_back(row);
    };
    add_row("reference", "degree 48; circumsolar 1e-9", reference);
    // The exact path at coarser settings.
    for (const int degree : opt.quick ? std::vector<int>{8, 32} : std::vector<int>{8, 16, 32})
      for (const double tolerance : {1e-3, 1e-6}) {
        status.show(fmt::format("annual {}: exact, degree {}, circumsolar {:g}", c.name, degree, tolerance));
        AnnualOptions o = base;
        o.degree = degree;
        o.circumsolar_tolerance = tolerance;
        add_row("exact", fmt::format("degree {}; circumsolar {:g}", degree, tolerance), annual_run(c, engine, weather, site, o));
      }
    // The sky in patches, integrated exactly; the sun exact.
    for (const int mf : opt.quick ? std::vector<int>{1, 4} : std::vector<int>{1, 2, 4, 6}) {
      status.show(fmt::format("annual {}: sky in MF:{} patches", c.name, mf));
      AnnualOptions o = base;
      o.sky_patch_mf = mf;
      add_row("patches_exact", fmt::format("MF:{}", mf), annual_run(c, engine, weather, site, o));
    }
    // The sampled baseline: MF:1 patches' coefficients by rays, then the same hourly sums; the sun
    // exact (the reference's own direct sun, blinds open).
    AnnualOptions mf1 = base;
    mf1.sky_patch_mf = 1;
    const AnnualSky patch_sky = annual_sky(weather, site, mf1);
    for (const long rays : opt.quick ? std::vector<long>{64, 1024} : std::vector<long>{64, 256, 1024, 4096, 16384}) {
      status.show(fmt::format("annual {}: sampled MF:1 coefficients, {} rays per sensor", c.name, rays));
      Run run;
      tbb::task_arena(1).execute([&] {
        const double t0 = thread_cpu_seconds();
        const std::vector<std::vector<double>> dc = sampled_patch_coefficients(c.scene, c.grid.sensors, patch_sky.patches, rays, 7);
        run.illuminance.assign(n * hours, 0.0f);
        for (std::size_t i = 0; i < n; ++i)
          for (std::size_t h = 0; h < hours; ++h) {
            const AnnualHour& hour = patch_sky.hours[h];
            if (!hour.sky) continue;
            double e = 0;
            for (std::size_t p = 0; p < dc[i].size(); ++p) e += dc[i][p] * hour.patch_luminance[p];
            run.illuminance[i * hours + h] = float(e + reference.direct_sun[i * hours + h]);
          }
        run.cpu_s = thread_cpu_seconds() - t0;
      });
      add_row("sampled", fmt::format("MF:1; {} rays", rays), run);
    }
  }
  status.clear();

  const std::filesystem::path dir(opt.out);
  std::filesystem::create_directories(dir);
  StagedOutputs outputs;
  const std::string csv = (dir / "annual_error_vs_time.csv").string(), png = (dir / "annual_error_vs_time.png").string();
  {
    std::ofstream f(outputs.stage(csv));
    f << "case,method,parameter,sensors,sky_hours,cpu_s_per_sensor,sky_cpu_s,rms_normalised_error,p95_relative_error,"
         "flipped_300lx_share,da300_difference_points\n";
    for (const Row& r : rows)
      f << fmt::format("{},{},{},{},{},{:.4e},{:.3f},{:.4e},{:.4e},{:.4e},{:.4f}\n", r.case_name, r.method, r.parameter, r.sensors,
                       r.sky_hours, r.cpu_s_per_sensor, r.sky_cpu_s, r.rms_normalised, r.p95_relative, r.flipped_share,
                       r.da300_difference);
    if (!f) throw Error(csv + ": cannot write");
  }
  Plot plot;
  plot.title = "Annual illuminance: error against run time";
  plot.subtitle = fmt::format("{} ({} records); office every {}th sensor, hall every {}th; one thread", weather.path,
                              weather.records.size(), office_stride, hall_stride);
  plot.x_label = "CPU time per sensor (s)";
  plot.y_label = "RMS error / RMS of the reference (degree 48; circumsolar 1e-9)";
  plot.y_floor = 1e-9;
  const std::vector<PlotColour> colours{{0.15f, 0.35f, 0.75f}, {0.85f, 0.35f, 0.1f}, {0.2f, 0.6f, 0.25f}};
  const PlotMarker markers[] = {PlotMarker::circle, PlotMarker::square};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    std::size_t m = 0;
    for (const char* method : {"exact", "patches_exact", "sampled"}) {
      PlotSeries series{fmt::format("{}, {}", cases[k].name, method), {}, colours[m++], markers[k % 2], std::string(method) != "exact"};
      for (const Row& r : rows)
        if (r.case_name == cases[k].name && r.method == method)
          series.points.push_back({r.cpu_s_per_sensor, std::max(r.rms_normalised, 1e-9)});
      plot.series.push_back(series);
    }
  }
  plot.notes = {"patches_exact: Reinhart MF 1, 2, 4, 6 integrated exactly (the sky's discretisation alone); sampled: MF 1",
                "coefficients by N cosine rays (discretisation and noise). The sun is exact in every run; blinds open."};
  write_loglog_plot(outputs.stage(png), plot);
  outputs.commit();

  if (!opt.quiet) {
    std::cerr << fmt::format("{:>7} {:>14} {:>30} {:>12} {:>12} {:>12} {:>10} {:>9}\n", "case", "method", "parameter", "s/sensor",
                             "RMS norm.", "p95 rel.", "flip 300", "dDA300");
    for (const Row& r : rows)
      std::cerr << fmt::format("{:>7} {:>14} {:>30} {:>12.3e} {:>12.3e} {:>12.3e} {:>10.2e} {:>9.3f}\n", r.case_name, r.method,
                               r.parameter, r.cpu_s_per_sensor, r.rms_normalised, r.p95_relative, r.flipped_share,
                               r.da300_difference);
    std::cerr << fmt::format("bench annual: wrote {}, {} ({:.1f} s)\n", csv, png, bench::seconds_since(t_start));
  }
  return 0;
}

}  // namespace daylit::cli
