// `daylit bench skies`: the CIE standard general skies (ISO 15469) through the office's window,
// by the closed forms of the fitted luminance and by adaptive cubature at tolerances 1e-2 … 1e-10,
// against cubature at 1e-13: error against run time for both paths (DESIGN.md §6), and E_out of
// every sky by the fit against cubature over the hemisphere.
//
// The window is taken as an opening (no glass), so that the fit's closed forms apply: behind glass
// `daylit illuminance` integrates CIE skies by cubature whatever the method. The visible regions
// are computed once per sensor, outside the timings: the times are those of the sky integrals.
//
// skies_error_vs_time.csv: type, sun, method, parameter (cubature tolerance; 0 for the fit),
// seconds per sensor (thread CPU time, best of the repetitions), RMS and maximum relative error
// over the sensors that see sky, and for the fit its maximum error on the hemisphere (relative to
// L_z) and the time to build it (once per sky and sun).
// skies_e_out.csv: type, sun, E_out/L_z by cubature (1e-13) and by the fit, their relative
// difference, the fit's maximum error.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>

#include <fmt/format.h>

#include "bench/bench_suites.hpp"
#include "report/plot.hpp"
#include "report/progress_bar.hpp"
#include "report/staged_output.hpp"
#include "materials/scene_materials.hpp"
#include "geometry/error.hpp"
#include "sky/cie_sky.hpp"
#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"

namespace daylit::cli {

namespace {

using bench::StatusLine;
using bench::thread_cpu_seconds;

struct SunCase {
  std::string name;
  double zenith_deg, azimuth_deg;  // the office: +y is north, its window faces south (−y)
};

struct Row {
  int type;
  std::string sun, method;
  double parameter, seconds, rms, max, fit_max_error, fit_seconds;
};

struct SensorRegion {
  SphericalRegion region;
  Vec3 normal;
};

// f at every sensor, and the best over the repetitions of its CPU time per sensor.
template <class F>
std::pair<std::vector<double>, double> per_sensor(const std::vector<SensorRegion>& sensors, int repetitions, F&& f) {
  std::vector<double> values(sensors.size());
  double best = 1e300;
  for (int r = 0; r < repetitions; ++r) {
    const double t0 = thread_cpu_seconds();
    for (std::size_t i = 0; i < sensors.size(); ++i) values[i] = f(sensors[i]);
    best = std::min(best, (thread_cpu_seconds() - t0) / double(sensors.size()));
  }
  return {values, best};
}

void errors(const std::vector<double>& values, const std::vector<double>& reference, double& rms, double& max) {
  double sum = 0;
  max = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double e = std::abs(values[i] - reference[i]) / reference[i];
    sum += e * e;
    max = std::max(max, e);
  }
  rms = std::sqrt(sum / double(values.size()));
}

}  // namespace

int run_bench_skies(const BenchOptions& opt) {
  const auto t_start = bench::clock_type::now();
  const std::filesystem::path base = std::filesystem::path(opt.samples) / "office";
  if (!std::filesystem::exists(base / "scene.rad"))
    throw Error((base / "scene.rad").string() + ": not found; give the folder of the bundled samples with --samples DIR");
  Scene scene = load_scene({(base / "scene.rad").string()}, {(base / "apertures.rad").string()});
  for (Aperture& a : scene.apertures) a.angular_transmittance.clear();  // an opening: see the header
  const SensorGrid grid = read_sensor_grid((base / "grid.pts").string());
  const VisibilityEngine engine(scene, GeometryMode::exact);

  // Every k-th sensor that sees sky through the window.
  const std::size_t stride = opt.quick ? 97 : 13;
  std::vector<SensorRegion> sensors;
  for (std::size_t i = 0; i < grid.sensors.size(); i += stride) {
    VisibilityCounters counters;
    SphericalRegion region;
    for (std::size_t a = 0; a < engine.aperture_count(); ++a)
      for (auto& loop : engine.visible_region(grid.sensors[i].position, grid.sensors[i].normal, a, counters).loops)
        region.loops.push_back(std::move(loop));
    if (!region.empty()) sensors.push_back({std::move(region), grid.sensors[i].normal});
  }
  if (sensors.empty()) throw Error("no sensor of the office sees sky");

  const std::vector<int> types = opt.quick ? std::vector<int>{3, 12} : std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  const std::vector<SunCase> suns = opt.quick ? std::vector<SunCase>{{"south 50", 50, 180}}
                                              : std::vector<SunCase>{{"south 50", 50, 180}, {"north-west 30", 30, 315}, {"east 75", 75, 90}};
  const std::vector<double> tolerances = opt.quick ? std::vector<double>{1e-3, 1e-8} : std::vector<double>{1e-2, 1e-4, 1e-6, 1e-8, 1e-10};
  const int repetitions = opt.quick ? 1 : 3;
  StatusLine status(!opt.quiet && stderr_is_terminal());
  std::vector<Row> rows;
  std::string e_out_table = "type,sun,e_out_cubature,e_out_fit,relative_difference,fit_max_error\n";
  std::size_t done = 0;
  for (const SunCase& sun : suns) {
    for (const int type : types) {
      status.show(fmt::format("bench skies: type {}, sun {} ({}/{})", type, sun.name, ++done, types.size() * suns.size()));
      const CieSky sky(type, sun_direction(sun.zenith_deg, sun.azimuth_deg));
      const double tf = thread_cpu_seconds();
      const CieSkyFit fit = fit_cie_sky(sky);
      const double fit_seconds = thread_cpu_seconds() - tf;
      const auto [reference, reference_seconds] = per_sensor(sensors, 1, [&](const SensorRegion& s) {
        return cie_sky_irradiance_quadrature(sky, s.region, s.normal, 1e-13).value;
      });
      (void)reference_seconds;
      const auto [fitted, fit_time] = per_sensor(sensors, repetitions, [&](const SensorRegion& s) {
        return cie_sky_irradiance(fit, sky.sun, s.region, s.normal);
      });
      Row r{type, sun.name, "fit", 0, fit_time, 0, 0, fit.max_error, fit_seconds};
      errors(fitted, reference, r.rms, r.max);
      rows.push_back(r);
      for (const double tolerance : tolerances) {
        const auto [values, seconds] = per_sensor(sensors, repetitions, [&](const SensorRegion& s) {
          return cie_sky_irradiance_quadrature(sky, s.region, s.normal, tolerance).value;
        });
        Row q{type, sun.name, "cubature", tolerance, seconds, 0, 0, 0, 0};
        errors(values, reference, q.rms, q.max);
        rows.push_back(q);
      }
      const double e_cubature = cie_sky_irradiance_quadrature(sky, sky_hemisphere(), {0, 0, 1}, 1e-13).value;
      const double e_fit = cie_sky_irradiance(fit, sky.sun, sky_hemisphere(), {0, 0, 1});
      e_out_table += fmt::format("{},{},{:.17g},{:.17g},{:.3e},{:.3e}\n", type, sun.name, e_cubature, e_fit,
                                 std::abs(e_fit - e_cubature) / e_cubature, fit.max_error);
    }
  }
  status.clear();

  const std::filesystem::path dir(opt.out);
  std::filesystem::create_directories(dir);
  StagedOutputs outputs;
  const std::string csv = (dir / "skies_error_vs_time.csv").string(), png = (dir / "skies_error_vs_time.png").string(),
                    e_out_csv = (dir / "skies_e_out.csv").string();
  {
    std::ofstream f(outputs.stage(csv));
    f << "type,sun,method,parameter,seconds_per_sensor,rms_relative_error,max_relative_error,fit_max_error,fit_seconds\n";
    for (const Row& r : rows)
      f << fmt::format("{},{},{},{:g},{:.4e},{:.3e},{:.3e},{:.3e},{:.4e}\n", r.type, r.sun, r.method, r.parameter, r.seconds,
                       r.rms, r.max, r.fit_max_error, r.fit_seconds);
    if (!f) throw Error(csv + ": cannot write");
  }
  {
    std::ofstream f(outputs.stage(e_out_csv));
    f << e_out_table;
    if (!f) throw Error(e_out_csv + ": cannot write");
  }
  Plot plot;
  plot.title = "CIE general skies through the office window: relative error against run time";
  plot.subtitle = fmt::format("CPU time per sensor of the sky integral (visible regions precomputed), {} sensors; reference: cubature at 1e-13",
                              sensors.size());
  plot.x_label = "CPU time per sensor (s)";
  plot.y_label = "RMS relative error";
  plot.y_floor = 1e-16;
  // The cubature: mean time and RMS error over all skies at each tolerance; the fit: one point per sky.
  PlotSeries cubature{"adaptive cubature, tolerance 1e-2 ... 1e-10 (mean over skies)", {}, {0.15f, 0.35f, 0.75f}, PlotMarker::square, true};
  for (const double tolerance : tolerances) {
    double t = 0, e2 = 0;
    int n = 0;
    for (const Row& r : rows)
      if (r.method == "cubature" && r.parameter == tolerance) t += r.seconds, e2 += r.rms * r.rms, ++n;
    cubature.points.push_back({t / n, std::sqrt(e2 / n)});
  }
  PlotSeries fit_points{"closed forms of the fit (one point per sky and sun)", {}, {0.85f, 0.35f, 0.1f}, PlotMarker::circle, false};
  for (const Row& r : rows)
    if (r.method == "fit") fit_points.points.push_back({r.seconds, r.rms});
  plot.series = {cubature, fit_points};
  plot.notes = {"The fit's errors follow its maximum error on the hemisphere (skies_error_vs_time.csv, fit_max_error);",
                "types 1-6 fit to 1e-7 or better, the clear skies 7-15 to 1e-3 ... 1e-1 of L_z near the sun."};
  write_loglog_plot(outputs.stage(png), plot);
  outputs.commit();
  if (!opt.quiet) {
    std::cerr << fmt::format("{:>4} {:>14} {:>12} {:>12} {:>12} | cubature 1e-6: {:>12} {:>12}\n", "type", "sun", "fit s/sensor",
                             "fit RMS", "fit max err", "s/sensor", "RMS");
    for (const Row& r : rows) {
      if (r.method != "fit") continue;
      const auto q = std::find_if(rows.begin(), rows.end(), [&](const Row& x) {
        return x.method == "cubature" && x.type == r.type && x.sun == r.sun && x.parameter == (opt.quick ? 1e-3 : 1e-6);
      });
      std::cerr << fmt::format("{:>4} {:>14} {:>12.3e} {:>12.3e} {:>12.3e} | {:>26.3e} {:>12.3e}\n", r.type, r.sun, r.seconds, r.rms,
                               r.fit_max_error, q->seconds, q->rms);
    }
    std::cerr << fmt::format("bench skies: wrote {}, {}, {} ({:.1f} s)\n", csv, png, e_out_csv, bench::seconds_since(t_start));
  }
  return 0;
}

}  // namespace daylit::cli
