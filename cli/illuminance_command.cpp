// `daylit illuminance`: the sky and the sun at one moment, in lux, on the sensor grids of `daylit
// df`'s models. The sun's position comes from the site and a time (NREL SPA, sky/solar_position)
// or is given; the sky is scaled by its zenith luminance or by its unobstructed diffuse horizontal
// illuminance (E_out, computed for every sky, never looked up).

#include "cli/illuminance_command.hpp"

#include <CLI/CLI.hpp>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/model_options.hpp"
#include "simulation/model_inputs.hpp"
#include "report/progress_bar.hpp"
#include "report/model_reports.hpp"
#include "report/reports.hpp"
#include "report/staged_output.hpp"
#include "geometry/error.hpp"
#include "materials/glass_transmittance.hpp"
#include "simulation/illuminance.hpp"
#include "sky/model_sun.hpp"
#include "sky/sky_model.hpp"

namespace daylit::cli {

namespace {

struct IlluminanceOptions {
  ModelFiles files;
  std::string sky = "cie-overcast", method = "quadrature";
  double tolerance = 1e-9;
  double zenith_luminance = 0, diffuse_horizontal = 0, direct_normal = 0;
  std::string time;
  double sun_zenith_deg = 0, sun_azimuth_deg = 0;
  double pressure_hpa = 1013.25, temperature_c = 10;
  std::string geometry = "exact";
  std::string out, summary, image;
  int threads = 0;
  bool quiet = false;
  CLI::Option *zenith_luminance_option = nullptr, *diffuse_horizontal_option = nullptr, *sun_zenith_option = nullptr;
};

// The sun from --time and the site (SPA), or as given, or none.
ModelSun sun_position(const IlluminanceOptions& opt, const std::optional<Site>& site) {
  if (!opt.time.empty()) {
    if (!site) throw Error("--time needs --site: the sun's position depends on where the model stands");
    return sun_at_instant(opt.time, *site, opt.pressure_hpa, opt.temperature_c);
  }
  if (opt.sun_zenith_option->count() > 0) return sun_given(opt.sun_zenith_deg, opt.sun_azimuth_deg, site);
  return {};
}

struct GridLux {
  const SensorGrid* grid;
  IlluminanceResult result;
  std::vector<double> total;
  GridStatistics statistics;
  double run_time_s;
};

void write_lux_csv(std::FILE* out, const std::vector<GridLux>& grids) {
  fmt::print(out, "grid,index,x,y,z,dx,dy,dz,sky_lux,sun_lux,illuminance_lux,sky_error_bound_lux\n");
  for (const auto& g : grids) {
    for (std::size_t i = 0; i < g.grid->sensors.size(); ++i) {
      const Sensor& s = g.grid->sensors[i];
      // 17 significant digits: the values round-trip.
      fmt::print(out, "{},{},{},{},{},{},{},{},{:.17g},{:.17g},{:.17g},{:.3g}\n", g.grid->name, i, s.position.x,
                 s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z, g.result.sky_lux[i],
                 g.result.sun_lux[i], g.total[i], g.result.sky_error_lux[i]);
    }
  }
}

void write_lux_csv(const std::string& path, const std::vector<GridLux>& grids) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) throw Error(path + ": cannot open for writing");
  write_lux_csv(out, grids);
  const bool failed = std::ferror(out) != 0;
  if (std::fclose(out) != 0 || failed) throw Error(path + ": cannot write CSV");
}

int run_illuminance(IlluminanceOptions opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const SkyName sky_name = parse_sky_name(opt.sky);
  const int type = sky_name.cie_type;
  const GeometryMode mode = opt.geometry == "float"      ? GeometryMode::floating
                            : opt.geometry == "rational" ? GeometryMode::rational
                                                         : GeometryMode::exact;
  if (opt.zenith_luminance_option->count() == 0 && opt.diffuse_horizontal_option->count() == 0)
    throw Error("give the sky's scale: --diffuse-horizontal LUX (its unobstructed horizontal illuminance) or "
                "--zenith-luminance CD_M2");
  const int threads = opt.threads > 0 ? opt.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));

  // The site is read before the model so that the sun can decide the context rule (below).
  std::optional<Site> site;
  if (!opt.files.site.empty()) site = read_site_file(opt.files.site);
  const ModelSun sun = sun_position(opt, site);

  DaylightConditions c;
  c.sky = sky_name.kind == SkyName::Kind::cie_general ? DaylightConditions::Sky::cie_general
          : sky_name.kind == SkyName::Kind::uniform    ? DaylightConditions::Sky::uniform
                                                       : DaylightConditions::Sky::cie_overcast;
  c.sun = sun.direction;
  c.direct_normal = opt.direct_normal;
  c.method = opt.method == "quadrature" ? DaylightConditions::Method::quadrature : DaylightConditions::Method::fit;
  c.quadrature_tolerance = opt.tolerance;
  if (opt.direct_normal > 0 && sun.source == "none")
    throw Error("--direct-normal needs the sun's position: --time with --site, or --sun-zenith and --sun-azimuth");
  if (type > 0) {
    if (sun.source == "none")
      throw Error("sky " + opt.sky + " needs the sun's position: --time with --site, or --sun-zenith and --sun-azimuth");
    if (!(sun.direction.z > 0))
      throw Error(fmt::format("the sun is {:.3f}° below the horizon{}; the CIE general skies are defined for a sun above "
                              "it (use cie-overcast or uniform for twilight)",
                              sun.zenith_deg - 90, opt.time.empty() ? "" : " at " + opt.time));
    c.cie.emplace(type, sun.direction);
    if (c.method == DaylightConditions::Method::fit) c.fit = fit_cie_sky(*c.cie);
  }
  const double e_out_over_lz = unobstructed_sky_irradiance(c);
  c.zenith_luminance = opt.zenith_luminance_option->count() > 0 ? opt.zenith_luminance : opt.diffuse_horizontal / e_out_over_lz;

  // Context buildings below the angular threshold may hide part of the sun's disk (0.53° across):
  // with the sun on, those in its beam are kept, so the sun's illuminance loses nothing.
  std::optional<SunBeam> sun_beam;
  if (c.has_sun()) sun_beam = SunBeam{c.sun, c.sun_half_angle};
  ModelInputs model = load_model(opt.files, c.sky == DaylightConditions::Sky::uniform ? SkyModel::uniform : SkyModel::cie_overcast,
                                 sun_beam);
  if (!opt.quiet)
    for (const auto& notice : model.scene.notices) std::cerr << "notice: " << notice << '\n';

  const VisibilityEngine engine(model.scene, mode);
  const bool show_progress = !opt.quiet && stderr_is_terminal();
  std::vector<GridLux> grids;
  for (const auto& grid : model.grids) {
    const auto tg = std::chrono::steady_clock::now();
    ProgressBar bar("illuminance " + grid.name, grid.sensors.size(), show_progress);
    GridLux g{&grid, illuminance(engine, model.scene, grid, c, [&](std::size_t done) { bar.update(done); }), {}, {}, 0};
    for (std::size_t i = 0; i < grid.sensors.size(); ++i) g.total.push_back(g.result.sky_lux[i] + g.result.sun_lux[i]);
    g.statistics = grid_statistics(g.total, kIlluminanceThresholds);
    g.run_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - tg).count();
    grids.push_back(std::move(g));
  }

  StagedOutputs outputs;
  if (!opt.out.empty() && opt.out != "-") write_lux_csv(outputs.stage(opt.out), grids);
  if (!opt.image.empty()) {
    for (const auto& g : grids) {
      GridReport r;
      r.grid = g.grid;
      r.shown = g.total;
      r.shown_title = "Illuminance (lux)";
      r.shown_unit = "lux";
      r.statistics = g.statistics;
      write_falsecolour_image(outputs.stage(image_path_for(opt.image, g.grid->name, grids.size())), r);
    }
  }

  nlohmann::json summary;
  summary["quantity"] = "illuminance_lux";
  summary["geometry"] = opt.geometry;
  summary["threads"] = threads;
  nlohmann::json sky = {{"model", opt.sky},
                        {"zenith_luminance_cd_m2", c.zenith_luminance},
                        {"unobstructed_horizontal_lux", c.zenith_luminance * e_out_over_lz},
                        {"e_out_over_zenith_luminance", e_out_over_lz}};
  if (type > 0) {
    sky["method"] = opt.method;
    if (c.fit) {
      sky["fit_max_error_over_zenith_luminance"] = c.fit->max_error;
      sky["fit_rms_error_over_zenith_luminance"] = c.fit->rms_error;
    }
    if (c.method == DaylightConditions::Method::quadrature) sky["quadrature_tolerance"] = opt.tolerance;
  }
  long evaluations = 0;
  std::size_t by_quadrature = 0;
  double error_bound = 0;
  for (const auto& g : grids) {
    evaluations += g.result.quadrature_evaluations;
    by_quadrature += g.result.regions_by_quadrature;
    for (double e : g.result.sky_error_lux) error_bound = std::max(error_bound, e);
  }
  sky["sky_error_bound_lux_max"] = error_bound;
  if (evaluations > 0) sky["quadrature_evaluations"] = evaluations;
  if (by_quadrature > 0)
    sky["glazed_regions_by_quadrature"] = {
        {"count", by_quadrature},
        {"why", "the fit's terms times the glass polynomial are moments about three axes, which have no closed form here"}};
  summary["sky"] = sky;

  nlohmann::json sun_json = {{"position", sun.source}};
  if (sun.source != "none") {
    sun_json["zenith_deg"] = sun.zenith_deg;
    sun_json["azimuth_deg"] = sun.azimuth_deg;
    sun_json["direction_model"] = {sun.direction.x, sun.direction.y, sun.direction.z};
    if (!opt.time.empty()) sun_json["time"] = opt.time;
  }
  sun_json["direct_normal_lux"] = opt.direct_normal;
  sun_json["half_angle_deg"] = kSunHalfAngleDeg;
  sun_json["included"] = c.has_sun();
  if (!c.has_sun())
    sun_json["left_out"] = opt.direct_normal > 0 ? "the sun is below the horizon" : "no --direct-normal: sky only";
  double glazing_slope = 0;
  for (const Aperture& a : model.scene.apertures)
    if (!a.angular_transmittance.empty()) glazing_slope = std::max(glazing_slope, max_slope(a.angular_transmittance));
  if (c.has_sun() && glazing_slope > 0)
    sun_json["glazing_transmittance_change_across_disk_max"] = glazing_slope * std::sin(c.sun_half_angle);
  summary["sun"] = sun_json;

  summary["components"] = {
      {"computed", c.has_sun() ? nlohmann::json{"sky_direct", "sun_direct"} : nlohmann::json{"sky_direct"}},
      {"left_out",
       {{"externally_reflected", "not computed (obstructions and the ground are black)"},
        {"internally_reflected", "not computed (room surfaces are black)"}}}};
  if (site) summary["site"] = site_json(*site, opt.files.site);
  if (model.context) {
    nlohmann::json context = context_json(*model.context, opt.files.context);
    // The sun's bound is 0: with the sun on, the buildings in its beam were kept (load_model).
    const double omega = model.context->left_out_solid_angle_sr;
    context["illuminance_change_bound_lux"] = {{"sky", omega * c.zenith_luminance * (c.cie ? c.cie->max_relative_luminance() : 1.0)}, {"sun", 0.0}};
    summary["context"] = context;
  }
  summary["scene"] = scene_json(model.scene, engine);
  for (const auto& g : grids) {
    const auto& s = g.statistics;
    nlohmann::json shares;
    for (std::size_t t = 0; t < s.thresholds.size(); ++t) shares[fmt::format("{:g}", s.thresholds[t])] = s.share_at_or_above[t];
    double sun_share = 0;
    for (double v : g.result.sun_lux) sun_share += v > 0;
    summary["grids"].push_back({{"name", g.grid->name},
                                {"path", g.grid->path},
                                {"count", s.count},
                                {"illuminance_lux", {{"mean", s.mean}, {"median", s.median}, {"min", s.min}, {"max", s.max}}},
                                {"uniformity", {{"min_over_mean", s.min_over_mean}, {"min_over_median", s.min_over_median}}},
                                {"share_at_or_above_lux", shares},
                                {"share_in_direct_sun", s.count ? sun_share / double(s.count) : 0.0},
                                {"run_time_s", g.run_time_s},
                                {"left_out", counters_json(g.result.counters)}});
  }
  summary["run_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!opt.summary.empty()) {
    std::ofstream f(outputs.stage(opt.summary));
    f << summary.dump(2) << '\n';
    if (!f) throw Error(opt.summary + ": cannot write summary");
  }
  outputs.commit();
  if (opt.out.empty() || opt.out == "-") write_lux_csv(stdout, grids);
  if (!opt.quiet) {
    if (sun.source != "none")
      std::cerr << fmt::format("sun: zenith {:.4f}°, azimuth {:.4f}° ({}){}\n", sun.zenith_deg, sun.azimuth_deg,
                               sun.source == "spa" ? "NREL SPA" : "given",
                               c.has_sun() ? fmt::format(", {:g} lux direct normal", c.direct_normal) : ", not included");
    for (const auto& g : grids)
      std::cerr << fmt::format("{}: {} sensors, mean {:.1f} lux, median {:.1f}, min {:.1f}, max {:.1f} ({:.2f} s)\n",
                               g.grid->name, g.statistics.count, g.statistics.mean, g.statistics.median, g.statistics.min,
                               g.statistics.max, g.run_time_s);
  }
  return 0;
}

}  // namespace

std::function<int()> add_illuminance_command(CLI::App& app) {
  auto opt = std::make_shared<IlluminanceOptions>();
  CLI::App* cmd = app.add_subcommand("illuminance", "Illuminance (lux) on sensor grids from a CIE sky and the sun");
  cmd->description(
      "Computes the illuminance at every sensor from the sky and the sun seen through the apertures, each\n"
      "aperture clipped exactly against the occluders as seen from the sensor. Skies: uniform, cie-overcast\n"
      "(exact closed forms), and the fifteen CIE general skies cie-1 ... cie-15 (ISO 15469), integrated by\n"
      "adaptive cubature of the standard's formula or by the closed forms of a fit of their luminance (its\n"
      "error bound is reported per sensor). The sun is a uniform disk 0.533 degrees across, cut exactly by what each sensor sees, scaled\n"
      "by --direct-normal. Its position: --time and --site (NREL SPA), or --sun-zenith and --sun-azimuth.\n"
      "Externally and internally reflected light is not computed.");
  auto& f = opt->files;
  cmd->add_option("--scene", f.scene_files, "Radiance scene files (.rad): occluders; glass polygons are apertures")
      ->check(CLI::ExistingFile);
  cmd->add_option("--apertures", f.aperture_files, "Radiance files whose polygons are sky openings")->check(CLI::ExistingFile);
  cmd->add_option("--grid", f.grid_files, "Sensor grids (.pts: x y z dx dy dz per line); with --model, the model's grids by default")->check(CLI::ExistingFile);
  add_model_options(*cmd, f);
  cmd->add_option("--sky", opt->sky, "uniform, cie-overcast (default) or cie-1 ... cie-15")
      ->check(CLI::Validator(
          [](std::string& s) -> std::string {
            try {
              parse_sky_name(s);
              return "";
            } catch (const Error& e) {
              return e.what();
            }
          },
          "SKY"));
  cmd->add_option("--sky-method", opt->method,
                  "CIE general skies: quadrature (adaptive cubature of the standard's formula over each visible region; "
                  "default) or fit (closed forms of a fitted luminance, with a bound per sensor; slower here, see `daylit "
                  "bench skies`)")
      ->check(CLI::IsMember({"fit", "quadrature"}));
  cmd->add_option("--tolerance", opt->tolerance, "Relative tolerance of the cubature (default 1e-9)")
      ->check(CLI::Range(1e-14, 1e-2));
  opt->diffuse_horizontal_option =
      cmd->add_option("--diffuse-horizontal", opt->diffuse_horizontal,
                      "The sky's unobstructed horizontal illuminance E_out (lux); sets the zenith luminance")
          ->check(CLI::Range(0.0, 1e6));
  opt->zenith_luminance_option = cmd->add_option("--zenith-luminance", opt->zenith_luminance, "The sky's zenith luminance L_z (cd/m2)")
                                     ->check(CLI::Range(0.0, 1e7))
                                     ->excludes(opt->diffuse_horizontal_option);
  cmd->add_option("--direct-normal", opt->direct_normal, "The sun's direct normal illuminance (lux; default 0: no sun)")
      ->check(CLI::Range(0.0, 2e5));
  auto* time = cmd->add_option("--time", opt->time, "Date and time with UTC offset, e.g. 2026-06-21T13:00:00+02:00 (needs --site)");
  opt->sun_zenith_option = cmd->add_option("--sun-zenith", opt->sun_zenith_deg, "The sun's zenith angle (degrees)")
                               ->check(CLI::Range(0.0, 180.0))
                               ->excludes(time);
  auto* azimuth = cmd->add_option("--sun-azimuth", opt->sun_azimuth_deg,
                                  "The sun's azimuth (degrees clockwise from true north; north is +y without --site)")
                      ->check(CLI::Range(-360.0, 360.0))
                      ->excludes(time);
  opt->sun_zenith_option->needs(azimuth);
  azimuth->needs(opt->sun_zenith_option);
  cmd->add_option("--pressure-hpa", opt->pressure_hpa, "Local pressure for refraction (hPa; default 1013.25)")
      ->check(CLI::Range(0.0, 5000.0));
  cmd->add_option("--temperature-c", opt->temperature_c, "Local temperature for refraction (°C; default 10)")
      ->check(CLI::Range(-273.0, 6000.0));
  cmd->add_option("--site", f.site, "Site JSON (as for `daylit df`): places the model on the Earth")->check(CLI::ExistingFile);
  cmd->add_option("--context", f.context, "GeoJSON of neighbouring buildings (as for `daylit df`); needs --site")
      ->check(CLI::ExistingFile);
  cmd->add_option("--context-min-angle", f.context_min_angle_deg,
                  "Leave out context buildings smaller than this from every aperture (degrees; default 0.1), except those "
                  "in the sun's beam, which may hide part of its disk")
      ->check(CLI::Range(0.0, 179.0));
  cmd->add_option("--out", opt->out, "CSV file for per-sensor results (default, or -: standard output; ./- for a file named -)");
  cmd->add_option("--summary", opt->summary, "JSON file for per-grid statistics, the sky, the sun and what was left out");
  cmd->add_option("--image", opt->image, "PNG plan image per grid (grid name appended when there are several)");
  cmd->add_option("--geometry", opt->geometry, "Visibility arithmetic: exact (default), float or rational (as for `daylit df`)")
      ->check(CLI::IsMember({"exact", "float", "rational"}));
  cmd->add_option("--threads", opt->threads, "Worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--quiet", opt->quiet, "No progress bar or notices on stderr");
  return [opt] { return run_illuminance(*opt); };
}

}  // namespace daylit::cli
