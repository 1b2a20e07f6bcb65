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
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/image_options.hpp"
#include "cli/model_options.hpp"
#include "cli/mpi_shards.hpp"
#include "cli/number_checks.hpp"
#include "cli/reflection_options.hpp"
#include "simulation/model_inputs.hpp"
#include "report/progress_bar.hpp"
#include "report/model_reports.hpp"
#include "report/reports.hpp"
#include "report/staged_output.hpp"
#include "geometry/error.hpp"
#include "geometry/sky_box.hpp"
#include "materials/glass_transmittance.hpp"
#include "simulation/illuminance.hpp"
#include "sky/hour_sun.hpp"
#include "sky/model_sun.hpp"
#include "sky/perez_sky.hpp"
#include "sky/sky_model.hpp"
#include "sky/weather_file.hpp"

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
  ReflectionCliOptions reflections;
  // The Perez sky (--sky perez): the hour from --weather and --time, or given.
  std::string weather, perez_clamps = "none";
  double diffuse_irradiance = 0, direct_irradiance = 0, dew_point_c = 11;
  CLI::Option *zenith_luminance_option = nullptr, *diffuse_horizontal_option = nullptr, *sun_zenith_option = nullptr;
  CLI::Option *direct_normal_option = nullptr, *diffuse_irradiance_option = nullptr, *direct_irradiance_option = nullptr,
              *dew_point_option = nullptr;
  ImageCliOptions image_options;
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
  std::vector<double> erc_lux, irc_lux, reflection_error_lux;  // with --components all
};

void write_lux_csv(std::FILE* out, const std::vector<GridLux>& grids) {
  const bool reflected = !grids.empty() && !grids.front().erc_lux.empty();
  fmt::print(out, "grid,index,x,y,z,dx,dy,dz,sky_lux,sun_lux,{}illuminance_lux,sky_error_bound_lux{}\n",
             reflected ? "erc_lux,irc_lux," : "", reflected ? ",reflection_error_estimate_lux" : "");
  for (const auto& g : grids) {
    for (std::size_t i = 0; i < g.grid->sensors.size(); ++i) {
      const Sensor& s = g.grid->sensors[i];
      // 17 significant digits: the values round-trip.
      fmt::print(out, "{},{},{},{},{},{},{},{},{:.17g},{:.17g},", g.grid->name, i, s.position.x, s.position.y,
                 s.position.z, s.normal.x, s.normal.y, s.normal.z, g.result.sky_lux[i], g.result.sun_lux[i]);
      if (reflected) fmt::print(out, "{:.17g},{:.17g},", g.erc_lux[i], g.irc_lux[i]);
      fmt::print(out, "{:.17g},{:.3g}", g.total[i], g.result.sky_error_lux[i]);
      if (reflected) fmt::print(out, ",{:.3g}", g.reflection_error_lux[i]);
      fmt::print(out, "\n");
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

// ---- The Perez sky of one hour (--sky perez) ------------------------------------------------
// From a weather file's record (--weather with --time: the hour that holds the time, its sun by
// the hour-ending convention, the site from the file unless --site is given) or from irradiances
// given on the command line with the sun of --time/--site or --sun-zenith/--sun-azimuth.
struct PerezSetup {
  std::optional<PerezHour> hour;
  ModelSun sun;
  nlohmann::json weather;           // what was read and which hour was used
  std::string site_source = "none";  // "--site", "weather file" or "none"
  std::vector<std::string> notices;
};

PerezSetup perez_setup(const IlluminanceOptions& opt, std::optional<Site>& site) {
  PerezSetup p;
  PerezHourInput in;
  in.clamps = parse_perez_clamps(opt.perez_clamps);
  if (opt.zenith_luminance_option->count() > 0)
    throw Error("--zenith-luminance does not apply to the Perez sky: its scale is the hour's diffuse horizontal illuminance");
  if (!opt.weather.empty()) {
    for (const CLI::Option* o : {opt.diffuse_horizontal_option, opt.direct_normal_option, opt.diffuse_irradiance_option,
                                 opt.direct_irradiance_option, opt.dew_point_option, opt.sun_zenith_option})
      if (o->count() > 0) throw Error(o->get_name() + " cannot be given with --weather: the weather file gives the hour");
    if (opt.time.empty()) throw Error("--weather needs --time to pick the hour");
    const WeatherFile file = read_weather_file(opt.weather);
    p.site_source = site ? "--site" : "weather file";
    if (!site) site = Site::geographic(file.location.latitude_deg, file.location.longitude_deg, file.location.elevation_m, 0);
    const WeatherHour w = weather_hour(file, parse_iso8601_time(opt.time), site->origin().latitude_deg,
                                       site->origin().longitude_deg, site->origin().height_m, opt.pressure_hpa,
                                       opt.temperature_c);
    const WeatherRecord& r = *w.record;
    if (!w.sun.up)
      throw Error(fmt::format("{}:{}: the sun is below the horizon for the whole hour {}:00–{}:00 local standard time; the "
                              "Perez sky needs it up",
                              file.path, r.line, w.hour_ending - 1, w.hour_ending));
    // A typical-year file takes each month from another year; the record is found by month, day
    // and hour, the sun computed for the year asked. Said, because `annual` takes the record's
    // own year, and the two suns differ by up to 0.3° (near the equinoxes).
    if (r.year > 0 && r.year != w.local_standard.year)
      p.notices.push_back(fmt::format("{}:{}: the record is from {}, --time asks for {}: the sun is taken for {} (`daylit "
                                      "annual` takes each record's own year; give --time in {} for the same sun)",
                                      file.path, r.line, r.year, w.local_standard.year, w.local_standard.year, r.year));
    p.sun.source = "spa";
    p.sun.zenith_deg = w.sun.position.zenith_deg;
    p.sun.azimuth_deg = w.sun.position.azimuth_deg;
    p.sun.distance_au = w.sun.position.distance_au;
    const PerezClamps clamps = in.clamps;
    in = perez_hour_input(r, file.photometric);
    in.clamps = clamps;
    if (r.diffuse_horizontal_irradiance == 0.0 || (file.photometric && r.diffuse_horizontal_illuminance == 0.0))
      throw Error(fmt::format("{}:{}: the diffuse horizontal value of this hour is 0 with the sun up for {:.0f} min of it: "
                              "there is no sky to model (the Perez sky needs E_dh > 0)",
                              file.path, r.line, 60 * w.sun.up_fraction));
    const auto& i = w.sun.instant;
    p.weather = {{"path", file.path},
                 {"format", weather_format_name(file.format)},
                 {"place", file.location.place},
                 {"time_zone_h", file.location.time_zone_h},
                 {"records", file.records.size()},
                 {"record", {{"line", r.line}, {"year", r.year}, {"month", r.month}, {"day", r.day}, {"hour", r.hour}}},
                 {"sun_year", w.local_standard.year},
                 {"hour", fmt::format("{:02}-{:02} {:02}:00–{:02}:00 local standard time (UTC{:+g})", r.month, r.day,
                                      w.hour_ending - 1, w.hour_ending, file.location.time_zone_h)},
                 {"sun_taken_at", fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:06.3f} (UTC{:+g})", i.year, i.month, i.day,
                                              i.hour, i.minute, i.second, file.location.time_zone_h)},
                 {"sun_up_fraction_of_hour", w.sun.up_fraction},
                 {"convention", file.format == WeatherFormat::epw
                                    ? "EPW hour h covers (h-1, h] local standard time; the sun at its middle, or at the "
                                      "middle of the part of it the sun is up (sunrise and sunset hours)"
                                    : ".wea: the sun at the time written"},
                 {"missing_values",
                  {{"policy", fmt::format("records lacking direct normal or diffuse horizontal values are skipped and "
                                          "counted; more than {:g} % is refused; missing illuminances come from Perez's "
                                          "efficacies (so does 0 lux beside a positive irradiance), a missing dew point is 11 C",
                                          100 * kMaxMissingShare)},
                   {"unusable_records", file.unusable_records},
                   {"missing_dew_points", file.missing_dew_points},
                   {"missing_illuminances", file.missing_illuminances},
                   {"zero_illuminances_taken_as_missing", file.zero_illuminances_taken_as_missing}}}};
  } else {
    p.sun = sun_position(opt, site);
    p.site_source = site ? "--site" : "none";
    if (p.sun.source == "none")
      throw Error("sky perez needs the sun's position: --weather with --time, --time with --site, or --sun-zenith and "
                  "--sun-azimuth");
    if (opt.diffuse_irradiance_option->count() == 0 || opt.direct_irradiance_option->count() == 0)
      throw Error("sky perez needs the hour's --diffuse-horizontal-irradiance and --direct-normal-irradiance (W/m2), or "
                  "--weather with --time");
    in.diffuse_horizontal_irradiance = opt.diffuse_irradiance;
    in.direct_normal_irradiance = opt.direct_irradiance;
    if (opt.diffuse_horizontal_option->count() > 0) in.diffuse_horizontal_illuminance = opt.diffuse_horizontal;
    if (opt.direct_normal_option->count() > 0) in.direct_normal_illuminance = opt.direct_normal;
    if (opt.dew_point_option->count() > 0) in.dew_point_c = opt.dew_point_c;
  }
  if (!(p.sun.zenith_deg < 90))
    throw Error(fmt::format("the sun is {:.3f}° below the horizon; the Perez sky needs it above", p.sun.zenith_deg - 90));
  // sun_position() turned a given or SPA sun into the model frame; the weather's sun is turned here.
  if (!opt.weather.empty()) p.sun.direction = site->model_direction(p.sun.azimuth_deg, 90 - p.sun.zenith_deg);
  in.sun_zenith_deg = p.sun.zenith_deg;
  in.sun = p.sun.direction;
  in.distance_au = p.sun.distance_au;
  p.hour.emplace(perez_hour(in));
  return p;
}

nlohmann::json perez_json(const PerezHour& h, const PerezSetup& setup) {
  const PerezCondition& c = h.sky.condition();
  nlohmann::json j = {
      {"reference", "Perez, Seals and Michalsky 1993 (Solar Energy 50(3) 235-245); efficacies Perez et al. 1990"},
      {"clamps", perez_clamps_name(h.sky.clamps())},
      {"clamps_applied", c.clamps_applied},
      {"clearness_epsilon", c.clearness},
      {"brightness_delta", c.brightness},
      {"bin", c.bin},
      {"air_mass_kasten_young", c.air_mass},
      {"coefficients", {{"a", c.a}, {"b", c.b}, {"c", c.c}, {"d", c.d}, {"e", c.e}}},
      {"diffuse_horizontal_irradiance_w_m2", h.diffuse_horizontal_irradiance},
      {"direct_normal_irradiance_w_m2", h.direct_normal_irradiance},
      {"diffuse_horizontal_lux", h.diffuse_horizontal_lux},
      {"diffuse_horizontal_lux_source", h.diffuse_lux_from_efficacy ? "Perez 1990 diffuse efficacy" : "given"},
      {"direct_normal_lux", h.direct_normal_lux},
      {"direct_normal_lux_source", h.direct_lux_from_efficacy ? "Perez 1990 direct efficacy" : "given"},
      {"dew_point", h.dew_point_assumed ? "not given: 11 C assumed" : "given"},
      {"normalisation_sr", h.sky.horizontal_integral()},
      {"normalisation_method", "adaptive cubature over the hemisphere to 1e-12"},
      {"radiance_145_point_sum_over_normalisation", h.sky.radiance_145_point_integral() / h.sky.horizontal_integral()},
      {"site_source", setup.site_source}};
  if (h.iterations > 0) j["irradiance_from_illuminance_iterations"] = h.iterations;
  return j;
}
// ---- end of the Perez sky ------------------------------------------------------------------

int run_illuminance(IlluminanceOptions opt) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!mpi::root()) opt.quiet = true;  // under MPI, rank 0 alone speaks (and writes)
  const SkyName sky_name = parse_sky_name(opt.sky);
  const ImageScale image_scale_asked = image_scale(opt.image_options);
  const int type = sky_name.cie_type;
  const GeometryMode mode = opt.geometry == "float"      ? GeometryMode::floating
                            : opt.geometry == "rational" ? GeometryMode::rational
                                                         : GeometryMode::exact;
  const bool perez = sky_name.kind == SkyName::Kind::perez;
  if (!opt.weather.empty() && !perez) throw Error("--weather is read by --sky perez only");
  if (!perez && opt.zenith_luminance_option->count() == 0 && opt.diffuse_horizontal_option->count() == 0)
    throw Error("give the sky's scale: --diffuse-horizontal LUX (its unobstructed horizontal illuminance) or "
                "--zenith-luminance CD_M2");
  const int threads = opt.threads > 0 ? opt.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));

  // The site is read before the model so that the sun can decide the context rule (below).
  std::optional<Site> site;
  if (!opt.files.site.empty()) site = read_site_file(opt.files.site);
  std::optional<PerezSetup> perez_hour_setup;
  if (perez) perez_hour_setup = perez_setup(opt, site);
  const ModelSun sun = perez ? perez_hour_setup->sun : sun_position(opt, site);

  DaylightConditions c;
  c.sky = sky_name.kind == SkyName::Kind::cie_general ? DaylightConditions::Sky::cie_general
          : sky_name.kind == SkyName::Kind::uniform    ? DaylightConditions::Sky::uniform
          : sky_name.kind == SkyName::Kind::perez      ? DaylightConditions::Sky::perez
                                                       : DaylightConditions::Sky::cie_overcast;
  c.sun = sun.direction;
  c.direct_normal = perez ? perez_hour_setup->hour->direct_normal_lux : opt.direct_normal;
  if (perez) c.perez.emplace(perez_hour_setup->hour->sky);
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
  c.zenith_luminance = perez ? perez_hour_setup->hour->diffuse_horizontal_lux / e_out_over_lz
                       : opt.zenith_luminance_option->count() > 0 ? opt.zenith_luminance
                                                                  : opt.diffuse_horizontal / e_out_over_lz;

  // Context buildings below the angular threshold may hide part of the sun's disk (0.53° across):
  // with the sun on, those in its beam are kept, so the sun's illuminance loses nothing.
  std::optional<SunBeam> sun_beam;
  if (c.has_sun()) sun_beam = SunBeam{c.sun, c.sun_half_angle};
  ModelInputs model = load_model(opt.files, c.sky == DaylightConditions::Sky::uniform ? SkyModel::uniform : SkyModel::cie_overcast,
                                 sun_beam);
  if (!opt.quiet) {
    for (const auto& notice : model.scene.notices) std::cerr << "notice: " << notice << '\n';
    if (perez_hour_setup)
      for (const auto& notice : perez_hour_setup->notices) std::cerr << "notice: " << notice << '\n';
  }

  const VisibilityEngine engine(model.scene, mode);
  const std::unique_ptr<DirectSky> direct = direct_sky(model.scene, model.grids, mode, SubtractionOrder::front_to_back);
  const bool show_progress = !opt.quiet && stderr_is_terminal();
  std::vector<GridLux> grids;
  const std::vector<std::string> hosts = mpi::hosts();
  const std::vector<std::uint64_t> rank_threads = mpi::gather_per_rank(std::uint64_t(threads));
  std::vector<mpi::ShardedGrid> shards;
  for (const auto& grid : model.grids) {
    const auto tg = std::chrono::steady_clock::now();
    // Sharded as in df (cli/mpi_shards.hpp): this rank's block of the sensors, gathered on rank 0
    // in grid order. The sky's setup above (its E_out, the CIE fit, the Perez normalisation) is
    // done by every rank: it is per run, not per sensor.
    SensorGrid storage;
    const SensorGrid& block = mpi::rank_block(grid, storage);
    ProgressBar bar("illuminance " + grid.name, block.sensors.size(), show_progress);
    GridLux g{&grid, illuminance(engine, model.scene, block, c, [&](std::size_t done) { bar.update(done); }, direct ? &direct->engine : nullptr), {}, {}, 0, {}, {}, {}};
    shards.push_back({grid.name, grid.sensors.size(), {std::chrono::duration<double>(std::chrono::steady_clock::now() - tg).count()}});
    g.result.sky_lux = mpi::gather(g.result.sky_lux, grid.sensors.size());
    g.result.sun_lux = mpi::gather(g.result.sun_lux, grid.sensors.size());
    g.result.sky_error_lux = mpi::gather(g.result.sky_error_lux, grid.sensors.size());
    g.result.counters = mpi::sum(g.result.counters);
    g.result.quadrature_evaluations = long(mpi::sum(std::uint64_t(g.result.quadrature_evaluations)));
    g.result.regions_by_quadrature = std::size_t(mpi::sum(std::uint64_t(g.result.regions_by_quadrature)));
    shards.back().time_s = mpi::gather_per_rank(shards.back().time_s.front());
    if (!mpi::root()) continue;  // the totals, statistics and reports are rank 0's
    for (std::size_t i = 0; i < grid.sensors.size(); ++i) g.total.push_back(g.result.sky_lux[i] + g.result.sun_lux[i]);
    g.statistics = grid_statistics(g.total, kIlluminanceThresholds);
    g.run_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - tg).count();
    grids.push_back(std::move(g));
  }

  // The other ranks' part ends here: rank 0 solves the reflected components alone (one radiosity
  // solution for the whole model, as in df) and writes every output.
  if (!mpi::root()) return 0;

  // ---- Reflected components (--components all): one radiosity solution lit by this sky and sun.
  notice_unused_reflection_options(opt.reflections, opt.quiet, model.scene);
  std::optional<ReflectionResult> reflections;
  std::map<std::string, SurfaceReflectance> used_materials;
  double reflections_time_s = 0;
  const double horizontal_lux = unobstructed_daylight_lux(c);
  if (opt.reflections.all()) {
    const auto tr = std::chrono::steady_clock::now();
    SceneReflectances rho = scene_reflectances(model.scene);
    used_materials = std::move(rho.materials);
    std::vector<const SensorGrid*> grid_ptrs;
    for (const auto& g : model.grids) grid_ptrs.push_back(&g);
    if (horizontal_lux > 0) {
      ReflectionOptions ro = reflection_options(opt.reflections);
      ro.mode = mode;
      // The sky at the nodes; the sun integrated over the elements (ReflectionOptions::sun).
      DaylightConditions sky_alone = c;
      sky_alone.direct_normal = 0;
      ro.light = [sky_alone](const SphericalRegion& above, const Vec3& n, const Aperture* aperture) {
        return daylight_irradiance(sky_alone, aperture, above, n);
      };
      ro.light_horizontal = horizontal_lux;
      if (c.has_sun()) ro.sun = ReflectionOptions::Sun{c.sun, c.direct_normal};
      ro.on_progress = reflection_progress_bars(show_progress);
      reflections = reflected_components(model.scene, rho.reflectance, engine, grid_ptrs, ro);
      if (!opt.quiet && !reflections->stopped.empty()) std::cerr << "notice: " << reflections->stopped << '\n';
    } else {
      // No light outside at all (the sun down, no sky): nothing to reflect, exactly.
      ReflectionResult none;
      none.black = true;
      for (const auto& g : model.grids)
        none.grids.push_back({std::vector<double>(g.sensors.size(), 0.0), std::vector<double>(g.sensors.size(), 0.0),
                              std::vector<double>(g.sensors.size(), 0.0)});
      reflections = std::move(none);
    }
    reflections_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - tr).count();
    // Percent of the unobstructed horizontal illuminance, as DF is, back to lux.
    const double to_lux = horizontal_lux / 100;
    for (std::size_t k = 0; k < grids.size(); ++k) {
      GridLux& g = grids[k];
      const SensorReflections& r = reflections->grids[k];
      for (std::size_t i = 0; i < g.total.size(); ++i) {
        g.erc_lux.push_back(to_lux * r.erc_percent[i]);
        g.irc_lux.push_back(to_lux * r.irc_percent[i]);
        g.reflection_error_lux.push_back(to_lux * r.error_percent[i]);
        g.total[i] += g.erc_lux[i] + g.irc_lux[i];
      }
      g.statistics = grid_statistics(g.total, kIlluminanceThresholds);
    }
  }

  StagedOutputs outputs;
  if (!opt.out.empty() && opt.out != "-") write_lux_csv(outputs.stage(opt.out), grids);
  if (!opt.image.empty()) {
    std::vector<const SensorGrid*> shown;
    for (const auto& g : grids) shown.push_back(g.grid);
    const std::vector<PlanDrawing> plans = plan_drawings(model.scene, shown);
    for (std::size_t gi = 0; gi < grids.size(); ++gi) {
      const auto& g = grids[gi];
      GridReport r;
      r.grid = g.grid;
      r.plan = &plans[gi];
      r.scale = image_scale_asked;
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
  if (perez) {
    sky["perez"] = perez_json(*perez_hour_setup->hour, *perez_hour_setup);
    sky["method"] = "quadrature";
    sky["quadrature_tolerance"] = opt.tolerance;
    if (!opt.weather.empty()) summary["weather"] = perez_hour_setup->weather;
  }
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
  sun_json["direct_normal_lux"] = c.direct_normal;
  sun_json["half_angle_deg"] = kSunHalfAngleDeg;
  sun_json["included"] = c.has_sun();
  if (!c.has_sun())
    sun_json["left_out"] = c.direct_normal > 0 ? "the sun is below the horizon" : "no direct normal illuminance: sky only";
  double glazing_slope = 0;
  for (const Aperture& a : model.scene.apertures)
    if (!a.angular_transmittance.empty()) glazing_slope = std::max(glazing_slope, max_slope(a.angular_transmittance));
  if (c.has_sun() && glazing_slope > 0)
    sun_json["glazing_transmittance_change_across_disk_max"] = glazing_slope * std::sin(c.sun_half_angle);
  summary["sun"] = sun_json;

  if (reflections) {
    summary["components"] = reflection_summary(*reflections, used_materials, opt.reflections, reflections_time_s, "lux");
    summary["components"]["computed"] = c.has_sun() ? nlohmann::json{"sky_direct", "sun_direct", "erc", "irc"}
                                                    : nlohmann::json{"sky_direct", "erc", "irc"};
    summary["components"]["illuminance_lux_is"] = "sky_lux + sun_lux + erc_lux + irc_lux";
    summary["components"]["lit_by"] = {
        {"first_bounce", c.has_sun() ? "the sky, through the apertures and seen directly, at the nodes; the sun integrated "
                                       "over each element (its parallel beam past every polygon, the panes' transmittances "
                                       "along it, the lit parts projected onto the element's linear functions; the disk as "
                                       "a point)"
                                     : "the sky, through the apertures and seen directly"},
        {"unobstructed_horizontal_lux", horizontal_lux},
        {"far_ground_luminance_is", "ground_reflectance x unobstructed_horizontal_lux / pi (sky and sun)"}};
    if (horizontal_lux == 0) summary["components"]["radiosity"] = "none: no light outside (sun down, no sky), ERC = IRC = 0";
  } else {
    summary["components"] = {
        {"computed", c.has_sun() ? nlohmann::json{"sky_direct", "sun_direct"} : nlohmann::json{"sky_direct"}},
        {"left_out",
         {{"externally_reflected", "not computed (--components sc)"},
          {"internally_reflected", "not computed (--components sc)"}}}};
  }
  if (site) {
    summary["site"] = site_json(*site, opt.files.site);
    if (perez) summary["site"]["source"] = perez_hour_setup->site_source;
  }
  if (model.context) {
    nlohmann::json context = context_json(*model.context, opt.files.context);
    // The sun's bound is 0: with the sun on, the buildings in its beam were kept (load_model).
    const double omega = model.context->left_out_solid_angle_sr;
    context["illuminance_change_bound_lux"] = {{"sky", omega * c.zenith_luminance * (c.cie     ? c.cie->max_relative_luminance()
                                                      : c.perez ? c.perez->max_relative_luminance()
                                                                : 1.0)}, {"sun", 0.0}};
    summary["context"] = context;
  }
  summary["scene"] = scene_json(model.scene, engine);
  if (mpi::several())
    summary["mpi"] = mpi::summary_json(
        shards, hosts, rank_threads, "the sky and sun illuminance: every grid's sensors in blocks, one per rank",
        "on every rank: reading the model, the sky's setup (E_out, a CIE fit, the Perez normalisation) and the "
        "visibility engine; on rank 0 alone: the reflected components (one radiosity solution for the whole model; the "
        "other ranks wait), the statistics and every output");
  for (const auto& g : grids) {
    const auto& s = g.statistics;
    nlohmann::json shares;
    for (std::size_t t = 0; t < s.thresholds.size(); ++t) shares[fmt::format("{:g}", s.thresholds[t])] = s.share_at_or_above[t];
    double sun_share = 0;
    for (double v : g.result.sun_lux) sun_share += v > 0;
    summary["grids"].push_back({{"name", g.grid->name},
                                {"path", g.grid->path},
                                {"count", s.count},
                                {"sees_sky_directly", g.grid->sees_sky_directly},
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
    if (perez && !opt.weather.empty())
      std::cerr << fmt::format("weather: {} line {}, {}; site from {}\n", opt.weather,
                               perez_hour_setup->weather["record"]["line"].get<int>(),
                               perez_hour_setup->weather["hour"].get<std::string>(), perez_hour_setup->site_source);
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
  CLI::App* cmd = app.add_subcommand("illuminance", "Illuminance (lux) on sensor grids from a CIE or Perez sky and the sun");
  cmd->description(
      "Computes the illuminance at every sensor from the sky and the sun seen through the apertures, each\n"
      "aperture clipped exactly against the occluders as seen from the sensor. Skies: uniform, cie-overcast\n"
      "(exact closed forms), and the fifteen CIE general skies cie-1 ... cie-15 (ISO 15469), integrated by\n"
      "adaptive cubature of the standard's formula or by the closed forms of a fit of their luminance (its\n"
      "error bound is reported per sensor), and the Perez all-weather sky (perez; Perez, Seals and Michalsky 1993)\n"
      "by adaptive cubature, normalised exactly to the hour's diffuse horizontal illuminance, from a weather file's\n"
      "hour (--weather F.epw|F.wea --time T) or from the hour's irradiances given. The sun is a uniform disk 0.533\n"
      "degrees across, cut exactly by what each sensor sees, scaled by --direct-normal (or the weather's hour). Its\n"
      "position: --time and --site (NREL SPA), or --sun-zenith and --sun-azimuth.\n"
      "With --components all also the externally and internally reflected light (ERC, IRC), by the radiosity of\n"
      "`daylit df --components all` lit by this sky and sun; by default direct light alone.");
  auto& f = opt->files;
  cmd->add_option("--scene", f.scene_files, "Radiance scene files (.rad): occluders; glass polygons are apertures")
      ->check(CLI::ExistingFile);
  cmd->add_option("--apertures", f.aperture_files, "Radiance files whose polygons are sky openings")->check(CLI::ExistingFile);
  cmd->add_option("--grid", f.grid_files, "Sensor grids (.pts: x y z dx dy dz per line); with --model, the model's grids by default")->check(CLI::ExistingFile);
  add_model_options(*cmd, f);
  cmd->add_option("--sky", opt->sky, "uniform, cie-overcast (default), cie-1 ... cie-15, or perez (the Perez all-weather sky)")
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
      ->check(number_in(1e-14, 1e-2));
  opt->diffuse_horizontal_option =
      cmd->add_option("--diffuse-horizontal", opt->diffuse_horizontal,
                      "The sky's unobstructed horizontal illuminance E_out (lux); sets the zenith luminance")
          ->check(number_in(0.0, 1e6));
  opt->zenith_luminance_option = cmd->add_option("--zenith-luminance", opt->zenith_luminance, "The sky's zenith luminance L_z (cd/m2)")
                                     ->check(number_in(0.0, 1e7))
                                     ->excludes(opt->diffuse_horizontal_option);
  opt->direct_normal_option =
      cmd->add_option("--direct-normal", opt->direct_normal,
                      "The sun's direct normal illuminance (lux; default 0: no sun; perez: default from the efficacy)")
          ->check(number_in(0.0, 2e5));
  cmd->add_option("--weather", opt->weather,
                  "perez: an EnergyPlus .epw or Radiance .wea file; --time picks the hour that holds it (EPW hours end at "
                  "their time stamp); the site comes from the file unless --site is given")
      ->check(CLI::ExistingFile);
  opt->diffuse_irradiance_option =
      cmd->add_option("--diffuse-horizontal-irradiance", opt->diffuse_irradiance,
                      "perez without --weather: the hour's diffuse horizontal irradiance (W/m2)")
          ->check(number_in(0.0, 2000.0));
  opt->direct_irradiance_option = cmd->add_option("--direct-normal-irradiance", opt->direct_irradiance,
                                                  "perez without --weather: the hour's direct normal irradiance (W/m2)")
                                      ->check(number_in(0.0, 2000.0));
  opt->dew_point_option = cmd->add_option("--dew-point", opt->dew_point_c,
                                          "perez without --weather: dew point for the efficacies (C; default 11)")
                              ->check(number_in(-100.0, 60.0));
  cmd->add_option("--perez-clamps", opt->perez_clamps,
                  "perez: none (the published model, default; hours it cannot represent are refused) or radiance "
                  "(gendaylit's limits: sun altitude <= 87 deg, Delta >= 0.2 for 1.065 < epsilon < 2.8, cos(theta) >= "
                  "0.01 in the gradation, luminance and direct efficacy >= 0)")
      ->check(CLI::IsMember({"none", "radiance"}));
  auto* time = cmd->add_option("--time", opt->time, "Date and time with UTC offset, e.g. 2026-06-21T13:00:00+02:00 (needs --site, or --weather for perez)");
  opt->sun_zenith_option = cmd->add_option("--sun-zenith", opt->sun_zenith_deg, "The sun's zenith angle (degrees)")
                               ->check(number_in(0.0, 180.0))
                               ->excludes(time);
  auto* azimuth = cmd->add_option("--sun-azimuth", opt->sun_azimuth_deg,
                                  "The sun's azimuth (degrees clockwise from true north; north is +y without --site)")
                      ->check(number_in(-360.0, 360.0))
                      ->excludes(time);
  opt->sun_zenith_option->needs(azimuth);
  azimuth->needs(opt->sun_zenith_option);
  cmd->add_option("--pressure-hpa", opt->pressure_hpa, "Local pressure for refraction (hPa; default 1013.25)")
      ->check(number_in(0.0, 5000.0));
  cmd->add_option("--temperature-c", opt->temperature_c, "Local temperature for refraction (°C; default 10)")
      ->check(number_in(-273.0, 6000.0));
  cmd->add_option("--site", f.site, "Site JSON (as for `daylit df`): places the model on the Earth")->check(CLI::ExistingFile);
  cmd->add_option("--context", f.context, "GeoJSON of neighbouring buildings (as for `daylit df`); needs --site")
      ->check(CLI::ExistingFile);
  cmd->add_option("--context-min-angle", f.context_min_angle_deg,
                  "Leave out context buildings smaller than this from every aperture (degrees; default 0.1), except those "
                  "in the sun's beam, which may hide part of its disk")
      ->check(number_in(0.0, 179.0));
  cmd->add_option("--out", opt->out, "CSV file for per-sensor results (default, or -: standard output; ./- for a file named -)");
  cmd->add_option("--summary", opt->summary, "JSON file for per-grid statistics, the sky, the sun and what was left out");
  CLI::Option* image = cmd->add_option("--image", opt->image,
                                       "PNG plan image per grid (grid name appended when there are several), the walls "
                                       "cut at the grid's height and the apertures drawn over the values");
  add_image_options(*cmd, opt->image_options, image, "lux");
  cmd->add_option("--geometry", opt->geometry, "Visibility arithmetic: exact (default), float or rational (as for `daylit df`)")
      ->check(CLI::IsMember({"exact", "float", "rational"}));
  cmd->add_option("--threads", opt->threads, "Worker threads (default: all cores)")->check(non_negative_number());
  add_reflection_options(*cmd, opt->reflections, "illuminance");
  cmd->add_flag("--quiet", opt->quiet, "No progress bar or notices on stderr");
  return [opt] { return run_illuminance(*opt); };
}

}  // namespace daylit::cli
