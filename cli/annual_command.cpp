// `daylit annual`: every hour of a weather file (EPW or .wea) under the Perez sky and the sun, on
// every sensor, through daylight coefficients (simulation/annual.hpp), and sDA, ASE, UDI, DA, cDA
// and EN 17037 from the hourly values (simulation/annual_metrics.hpp).

#include "cli/annual_command.hpp"

#include <CLI/CLI.hpp>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/image_options.hpp"
#include "cli/model_options.hpp"
#include "cli/mpi_shards.hpp"
#include "cli/number_checks.hpp"
#include "cli/reflection_options.hpp"
#include "geometry/error.hpp"
#include "geometry/plan_drawing.hpp"
#include "geometry/sky_box.hpp"
#include "materials/surface_reflectance.hpp"
#include "report/annual_reports.hpp"
#include "report/model_reports.hpp"
#include "report/npy_writer.hpp"
#include "report/progress_bar.hpp"
#include "report/reports.hpp"
#include "report/staged_output.hpp"
#include "simulation/annual.hpp"
#include "simulation/annual_metrics.hpp"
#include "simulation/annual_reflections.hpp"
#include "simulation/illuminance.hpp"
#include "simulation/model_inputs.hpp"
#include "sky/weather_file.hpp"

namespace daylit::cli {

namespace {

struct AnnualCommandOptions {
  ModelFiles files;
  std::string weather, out, summary, hourly, image;
  ImageCliOptions image_options;  // the percentage plans' (DA300, UDI) scale, range and contours
  std::string geometry = "exact", perez_clamps = "radiance";
  AnnualOptions annual;
  ReflectionCliOptions reflections;
  int threads = 0;
  bool quiet = false;
};

// A reflection operator's stages as the summary lists them (df's `stages`: stage, wall_s).
nlohmann::json stage_times(const std::vector<ReflectionResult::StageTime>& stages) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& s : stages) out.push_back({{"stage", s.stage}, {"wall_s", s.wall_s}});
  return out;
}

// One path per grid: the given path for one grid, else with the grid's name inserted.
std::string per_grid(const std::string& path, const std::string& grid, std::size_t grids) {
  return image_path_for(path, grid, grids);
}

int run_annual(AnnualCommandOptions opt) {
  const ImageScale percent_scale = image_scale(opt.image_options);  // refused before any work
  const auto t0 = std::chrono::steady_clock::now();
  const int threads = opt.threads > 0 ? opt.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const GeometryMode mode = opt.geometry == "float"      ? GeometryMode::floating
                            : opt.geometry == "rational" ? GeometryMode::rational
                                                         : GeometryMode::exact;
  opt.annual.clamps = parse_perez_clamps(opt.perez_clamps);
  if (!mpi::root()) opt.quiet = true;  // under MPI, rank 0 alone speaks (and writes)
  const WeatherFile weather = read_weather_file(opt.weather);
  std::optional<Site> site;
  std::string site_source = "--site";
  if (!opt.files.site.empty()) {
    site = read_site_file(opt.files.site);
  } else {
    site = Site::geographic(weather.location.latitude_deg, weather.location.longitude_deg, weather.location.elevation_m, 0);
    site_source = "weather file (true north along +y)";
  }
  // The sun moves over the year: context buildings are kept or left out by their angular size
  // alone (no sun beam), and the summary states the bound for the sky.
  ModelInputs model = load_model(opt.files, SkyModel::cie_overcast);
  if (!opt.quiet)
    for (const auto& notice : model.scene.notices) std::cerr << "notice: " << notice << '\n';
  // Under mpirun every rank computes the whole AnnualSky (the Perez sky of every hour: a few
  // seconds of CPU a year), since every sensor's hourly pass needs every hour.
  const auto t_sky = std::chrono::steady_clock::now();
  const AnnualSky sky = annual_sky(weather, *site, opt.annual);
  const double sky_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_sky).count();
  if (!opt.quiet && sky.refused_hours > 0)
    std::cerr << fmt::format("notice: {} hours the published Perez model cannot serve are left dark (--perez-clamps none); "
                             "--perez-clamps radiance serves them\n",
                             sky.refused_hours);
  std::vector<bool> occupied, daylight_hours;
  std::vector<double> altitude;
  for (const AnnualHour& h : sky.hours) {
    occupied.push_back(h.occupied);
    altitude.push_back(h.sun_altitude_deg);
  }
  daylight_hours = en17037_daylight_hours(altitude);

  const VisibilityEngine engine(model.scene, mode);
  const std::unique_ptr<DirectSky> direct = direct_sky(model.scene, model.grids, mode, SubtractionOrder::front_to_back);
  const WindowGroups groups = window_groups(model.scene);
  const bool show_progress = !opt.quiet && stderr_is_terminal();
  // ---- Reflected components (annual_reflections.hpp): one operator over all grids, on the asked
  // mesh and on one twice as coarse (for the estimate).
  if (!opt.quiet) notice_unused_reflection_options(opt.reflections, opt.quiet, model.scene);
  if (!opt.quiet && opt.reflections.all())
    for (const CLI::Option* o : opt.reflections.options)
      if (o->count() > 0 && (o->get_name() == "--reflection-tolerance" || o->get_name() == "--max-refinements"))
        std::cerr << "notice: " << o->get_name()
                  << " is not used by annual runs: the reflected part is computed at --element-size, its estimate "
                     "against a mesh twice as coarse\n";
  // This rank's block of every grid's sensors (cli/mpi_shards.hpp; with one rank, the whole grid).
  std::vector<SensorGrid> storage(model.grids.size());
  std::vector<const SensorGrid*> blocks;
  for (std::size_t g = 0; g < model.grids.size(); ++g) blocks.push_back(&mpi::rank_block(model.grids[g], storage[g]));
  const std::vector<std::string> hosts = mpi::hosts();
  const std::vector<std::uint64_t> rank_threads = mpi::gather_per_rank(std::uint64_t(threads));
  std::vector<mpi::ShardedGrid> shards;
  std::optional<ReflectionOperator> fine_op, coarse_op;
  std::map<std::string, SurfaceReflectance> used_materials;
  double operator_time = 0;
  if (opt.reflections.all()) {
    const auto tr = std::chrono::steady_clock::now();
    SceneReflectances rho = scene_reflectances(model.scene);
    used_materials = std::move(rho.materials);
    ReflectionOptions ro = reflection_options(opt.reflections);
    ro.mode = mode;
    ro.on_progress = reflection_progress_bars(show_progress);
    // The mesh comes from every grid's sensors, so every rank builds it and solves the LU (a fixed
    // cost per rank); the rows of W only for this rank's block of each grid.
    std::vector<const SensorGrid*> grid_ptrs, block_ptrs = blocks;
    for (const auto& g : model.grids) grid_ptrs.push_back(&g);
    fine_op = reflection_operator(model.scene, rho.reflectance, engine, grid_ptrs, ro, false, kReflectionMaxNodes,
                                  &block_ptrs);
    coarse_op = reflection_operator(model.scene, rho.reflectance, engine, grid_ptrs, ro, true, kReflectionMaxNodes,
                                    &block_ptrs);
    operator_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - tr).count();
  }
  double reflected_hours_time = 0;
  std::vector<AnnualGridReport> grids;
  // The blinds rule's counts of lit sensors, per hour and group, summed over the ranks' blocks:
  // every rank closes the blinds the whole grid's sensors close (annual.hpp, BlindsCounts).
  BlindsCounts whole_grid;
  if (mpi::several())
    whole_grid = [](std::vector<std::uint64_t>& lit, std::uint64_t& sensors) {
      lit.push_back(sensors);
      lit = mpi::sum_on_every_rank(lit);
      sensors = lit.back();
      lit.pop_back();
    };
  // The reflected hours of a batch of grids at a time (annual_reflections.hpp: the per-node work
  // once per batch), each grid's released once its metrics are taken.
  std::vector<std::optional<ReflectedHours>> reflected(model.grids.size());
  std::vector<std::vector<std::size_t>> batches;
  if (fine_op) batches = reflected_batches(*fine_op, sky.hours.size(), groups.names.size(), kReflectedBatchBytes);
  for (std::size_t gi = 0, batch = 0; gi < model.grids.size(); ++gi) {
    const SensorGrid& grid = model.grids[gi];
    const SensorGrid& block = *blocks[gi];
    const auto tg = std::chrono::steady_clock::now();
    if (batch < batches.size() && batches[batch].front() == gi) {
      ReflectedGrids found = reflected_hours(model.scene, *fine_op, &*coarse_op, batches[batch], groups.group_of_aperture,
                                             groups.names.size(), sky, opt.reflections.ground_reflectance);
      reflected_hours_time += found.time_s;
      for (std::size_t i = 0; i < batches[batch].size(); ++i) reflected[batches[batch][i]] = std::move(found.grids[i]);
      ++batch;
    }
    ProgressBar bar("annual " + grid.name, block.sensors.size(), show_progress);
    AnnualGridReport g;
    g.grid = &grid;
    g.result = annual_grid(engine, model.scene, block, sky, opt.annual, [&](std::size_t done) { bar.update(done); },
                           reflected[gi] ? &*reflected[gi] : nullptr, whole_grid, direct.get());
    reflected[gi].reset();
    const auto tc = std::chrono::steady_clock::now();
    shards.push_back({grid.name, grid.sensors.size(), {std::chrono::duration<double>(tc - tg).count()}});
    if (mpi::several()) {
      // Rank 0 gathers the blocks in grid order: per-sensor rows concatenate into the single
      // process's arrays; integers are summed; reflected_share is recomputed from the gathered
      // per-sensor sums, in sensor order, as one process sums them. blinds_closed is the same on
      // every rank (from the summed counts).
      AnnualGridResult& r = g.result;
      const std::size_t n = grid.sensors.size();
      r.illuminance = mpi::gather(r.illuminance, n, r.hours);
      r.direct_sun = mpi::gather(r.direct_sun, n, r.hours);
      r.max_bound_lux = mpi::gather(r.max_bound_lux, n);
      r.max_bound_relative = mpi::gather(r.max_bound_relative, n);
      r.occupied_lux = mpi::gather(r.occupied_lux, n);
      r.occupied_reflected_lux = mpi::gather(r.occupied_reflected_lux, n);
      if (r.reflections) {
        r.max_reflection_estimate_lux = mpi::gather(r.max_reflection_estimate_lux, n);
        r.max_reflection_estimate_relative = mpi::gather(r.max_reflection_estimate_relative, n);
      }
      r.counters = mpi::sum(r.counters);
      r.adaptive_circumsolar = std::size_t(mpi::sum(std::uint64_t(r.adaptive_circumsolar)));
      for (double e : mpi::gather_per_rank(r.max_moment_error)) r.max_moment_error = std::max(r.max_moment_error, e);
      shards.back().time_s = mpi::gather_per_rank(shards.back().time_s.front());
      // run_time_s.hourly: rank 0's hourly pass and its wait for the other ranks' blocks.
      r.hourly_time_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - tc).count();
      if (!mpi::root()) continue;  // the metrics and every output are rank 0's
      r.sensors = n;
      r.reflected_share = reflected_share(r.occupied_lux, r.occupied_reflected_lux);
    }
    g.sensors = sensor_metrics(g.result.illuminance, g.result.direct_sun, g.result.sensors, g.result.hours, occupied,
                               daylight_hours);
    g.metrics = grid_metrics(g.result.illuminance, g.sensors, g.result.hours, occupied, daylight_hours);
    grids.push_back(std::move(g));
  }
  if (!mpi::root()) return 0;

  StagedOutputs outputs;
  if (!opt.out.empty()) write_annual_csv(outputs.stage(opt.out), grids);
  if (!opt.hourly.empty())
    for (const auto& g : grids)
      write_npy_float32(outputs.stage(per_grid(opt.hourly, g.grid->name, grids.size())), g.result.illuminance,
                        g.result.sensors, g.result.hours);
  if (!opt.image.empty()) {
    // One falsecolour plan per grid and metric, named <stem>-<grid>-<metric>.png.
    const struct {
      const char* key;
      const char* title;
      double SensorMetrics::*value;
    } shown[] = {{"da_300", "Daylight autonomy DA300 (% of occupied hours)", &SensorMetrics::da_300_percent},
                 {"udi_autonomous", "UDI 300-3000 lx (% of occupied hours)", &SensorMetrics::udi_autonomous_percent}};
    for (const auto& g : grids) {
      // The plans show the walls cut at the grid's height and the apertures, as df's do.
      const PlanDrawing plan = plan_drawing(model.scene, plan_height(*g.grid));
      for (const auto& s : shown) {
        GridReport r;
        r.grid = g.grid;
        r.plan = &plan;
        for (const SensorMetrics& m : g.sensors) r.shown.push_back(m.*(s.value));
        r.shown_title = s.title;
        r.shown_unit = "%";
        r.scale = percent_scale;
        r.statistics = grid_statistics(r.shown, {50});
        write_falsecolour_image(outputs.stage(per_grid(opt.image, g.grid->name + "-" + s.key, 2)), r);
      }
      GridReport r;
      r.grid = g.grid;
      r.plan = &plan;
      for (const SensorMetrics& m : g.sensors) r.shown.push_back(m.direct_sun_hours);
      r.shown_title = "Direct sun hours (occupied, >= 1000 lx, blinds open)";
      r.shown_unit = "h";
      r.statistics = grid_statistics(r.shown, {250});
      write_falsecolour_image(outputs.stage(per_grid(opt.image, g.grid->name + "-direct_sun_hours", 2)), r);
      write_temporal_map(outputs.stage(per_grid(opt.image, g.grid->name + "-temporal", 2)), g, sky);
    }
  }

  nlohmann::json summary;
  summary["quantity"] = "annual illuminance (lux) and climate-based metrics";
  if (fine_op) {
    nlohmann::json mats;
    for (const auto& [name, m] : used_materials) mats[name] = {{"reflectance", m.reflectance}, {"description", m.description}};
    const DirectionGrid direction_grid;
    summary["components"] = {
        {"computed", {"sky_direct", "sun_direct", "externally_reflected", "internally_reflected"}},
        {"ground_reflectance", opt.reflections.ground_reflectance},
        {"materials", mats},
        {"method",
         "the radiosity of `daylit df --components all` written as a linear map W (sensor x mesh node, by a dense LU); "
         "each node's first bounce per hour from the sky (its luminance interpolated bilinearly on a grid of directions, "
         "the grid's hat functions integrated over the node's exactly visible regions by a product Gauss rule), the "
         "sun (every hour, integrated over each element: its parallel beam past every polygon, the panes' "
         "transmittances along it, the lit parts projected onto the element's linear functions; the disk as a point) and "
         "the far ground (rho_g E_h / pi, exact); blinds scale the light each window group lets in"},
        {"direction_grid", {{"altitude_step_deg", 90.0 / direction_grid.rows},
                            {"azimuth_step_deg", 360.0 / direction_grid.columns},
                            {"gauss_points_per_direction", kReflectionRuleOrder},
                            {"largest_triangle_deg", kReflectionTriangleDeg}}},
        {"mesh", {{"elements", fine_op->elements},
                  {"nodes", fine_op->nodes.size()},
                  {"element_size", fine_op->element_size},
                  {"coarse_mesh_elements", coarse_op->elements},
                  {"surface_sides_solved", fine_op->sides_solved},
                  {"surface_sides_left_out", fine_op->sides_left_out}}},
        {"left_out", {{"specular", "specular parts of plastic and metal, and the reflection of glass and trans panes, "
                                   "are reflected diffusely (see materials; their energy is kept)"}}},
        {"run_time_s", {{"operators", operator_time}, {"hours", reflected_hours_time}}},
        {"run_time_by_stage",
         {{"reported_mesh_operator", stage_times(fine_op->stages)}, {"coarse_mesh_operator", stage_times(coarse_op->stages)}}}};
  } else {
    summary["components"] = {
        {"computed", {"sky_direct", "sun_direct"}},
        {"left_out",
         {{"externally_reflected", "not computed (--components sc; --components all computes it)"},
          {"internally_reflected", "not computed (--components sc; --components all computes it)"}}}};
  }
  summary["weather"] = {{"path", weather.path},
                        {"format", weather_format_name(weather.format)},
                        {"place", weather.location.place},
                        {"records", weather.records.size()},
                        {"unusable_records", weather.unusable_records},
                        {"missing_illuminances", weather.missing_illuminances},
                        {"zero_illuminances_taken_as_missing", weather.zero_illuminances_taken_as_missing}};
  summary["site"] = site_json(*site, opt.files.site);
  summary["site"]["source"] = site_source;
  summary["sky"] = annual_sky_json(sky, opt.annual);
  summary["sky"]["discretisation"] = annual_sky_mode_json(sky, opt.annual);
  summary["sky"]["run_time_s"] = sky_time;
  summary["blinds"] = {{"rule", "IES LM-83: a window group's blinds close in an hour when more than 2 % of the grid's sensors "
                                "get >= 1000 lx of direct sun through it (blinds open)"},
                       {"window_groups", "apertures sharing a material name"},
                       {"groups", groups.names},
                       {"closed_transmittance", opt.annual.closed_blind_transmittance},
                       {"closed_applies_to", "the group's sky and sun light alike"}};
  summary["sun"] = {{"disk_half_angle_deg", kSunHalfAngleDeg},
                    {"position", opt.annual.sun_patch_mf > 0
                                     ? fmt::format("centre of its Reinhart MF:{} patch (--sun-patches; not the true sun)",
                                                   opt.annual.sun_patch_mf)
                                     : std::string("NREL SPA at the hour's sun time (true sun)")}};
  summary["hours"] = {{"occupied", "8:00-18:00 local standard time (EPW hours ending 9..18)"},
                      {"en17037_daylight_hours", "the 4380 hours of highest sun altitude (half the year)"},
                      {"dark_hours_in_occupied", "count as 0 lux"}};
  summary["scene"] = scene_json(model.scene, engine);
  if (model.context) summary["context"] = context_json(*model.context, opt.files.context);
  for (const auto& g : grids) summary["grids"].push_back(annual_grid_json(g, groups.names));
  if (!opt.hourly.empty())
    summary["hourly_file"] = {{"format", ".npy 1.0, little-endian float32, shape (sensors, records): illuminance with "
                                         "blinds (lux), rows in grid order, columns in weather-file order"}};
  summary["threads"] = threads;
  if (mpi::several())
    summary["mpi"] = mpi::summary_json(
        shards, hosts, rank_threads,
        "every grid's sensors in blocks, one per rank: the daylight coefficients, the direct sun, the hourly pass and, "
        "with --components all, the sensors' rows of the reflection operators and the reflected hours; the LM-83 blinds "
        "rule from the lit sensors of the whole grid (counts summed over the ranks in every hour)",
        "on every rank: reading the model and the weather, the Perez sky of every hour (AnnualSky), the visibility "
        "engine and, with --components all, both operators' meshes, their nodes' views and transport and the dense LU "
        "(a fixed cost per rank, the same on each: the mesh depends on every grid's sensors); on rank 0 alone: the "
        "metrics and every output");
  summary["run_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!opt.summary.empty()) {
    std::ofstream f(outputs.stage(opt.summary));
    f << summary.dump(2) << '\n';
    if (!f) throw Error(opt.summary + ": cannot write summary");
  }
  outputs.commit();
  if (opt.out.empty()) write_annual_csv(stdout, grids);
  if (!opt.quiet) {
    std::cerr << fmt::format("weather: {} ({} records, {} with a sky, {} floored hours by full cubature)\n", weather.path,
                             weather.records.size(), sky.sky_hours, sky.floored_hours);
    for (const auto& g : grids)
      std::cerr << fmt::format("{}: {} sensors, sDA300/50% {:.1f} %, ASE1000,250 {:.1f} %, mean UDI 300-3000 {:.1f} % "
                               "({:.2f} s)\n",
                               g.grid->name, g.result.sensors, g.metrics.sda_300_50_percent, g.metrics.ase_1000_250_percent,
                               g.metrics.mean_udi_autonomous_percent, g.result.coefficient_time_s + g.result.hourly_time_s);
  }
  return 0;
}

}  // namespace

std::function<int()> add_annual_command(CLI::App& app) {
  auto opt = std::make_shared<AnnualCommandOptions>();
  CLI::App* cmd = app.add_subcommand("annual", "A year of hourly illuminance (Perez sky and sun) and sDA, ASE, UDI, DA, EN 17037");
  cmd->description(
      "Computes the illuminance at every sensor for every hour of a weather file under the Perez all-weather sky\n"
      "and the sun, through daylight coefficients: per sensor once, the moments of what it sees through the\n"
      "apertures (exact visible regions) against a Chebyshev basis in the direction; per hour, the sky's fit in that\n"
      "basis (its error bound beside each result), the circumsolar term and the sun's disk over the same regions.\n"
      "Metrics: direct sun hours and ASE1000,250 (blinds open), DA300, cDA300, UDI (100/300/3000 lx) and\n"
      "sDA300/50% with the LM-83 blinds rule over 8:00-18:00 local standard time, EN 17037's illuminance method\n"
      "over 4380 daylight hours. With --components all the externally and internally reflected light too (the\n"
      "radiosity of `daylit df`, as a linear map of each hour's sky, sun and ground); by default sky + sun direct.");
  auto& f = opt->files;
  cmd->add_option("--scene", f.scene_files, "Radiance scene files (.rad): occluders; glass polygons are apertures")
      ->check(CLI::ExistingFile);
  cmd->add_option("--apertures", f.aperture_files, "Radiance files whose polygons are sky openings")->check(CLI::ExistingFile);
  cmd->add_option("--grid", f.grid_files, "Sensor grids (.pts: x y z dx dy dz per line); default: the --model's grids")
      ->check(CLI::ExistingFile);
  add_model_options(*cmd, f);
  cmd->add_option("--weather", opt->weather, "EnergyPlus .epw or Radiance .wea weather file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--site", f.site, "Site JSON (as for `daylit df`); default: the weather file's location, +y true north")
      ->check(CLI::ExistingFile);
  cmd->add_option("--context", f.context, "GeoJSON of neighbouring buildings (as for `daylit df`); needs --site")
      ->check(CLI::ExistingFile);
  cmd->add_option("--context-min-angle", f.context_min_angle_deg,
                  "Leave out context buildings smaller than this from every aperture (degrees; default 0.1)")
      ->check(number_in(0.0, 179.0));
  cmd->add_option("--perez-clamps", opt->perez_clamps,
                  "radiance (default for annual runs: Radiance's limits, each counted in the summary) or none (the published "
                  "model; hours it cannot serve are left dark and counted)")
      ->check(CLI::IsMember({"none", "radiance"}));
  cmd->add_option("--degree", opt->annual.degree, "Degree of the sky basis in u_z (default 32)")->check(number_in(0, 64));
  cmd->add_option("--circumsolar-tolerance", opt->annual.circumsolar_tolerance,
                  "Relative tolerance of the circumsolar cubature per region (default 1e-6)")
      ->check(number_in(1e-12, 1e-1));
  cmd->add_option("--closed-blind-transmittance", opt->annual.closed_blind_transmittance,
                  "Share of a window group's light that passes when its blinds are closed (default 0.2)")
      ->check(number_in(0.0, 1.0));
  cmd->add_option("--sun-patches", opt->annual.sun_patch_mf,
                  "Put the sun's disk at the centre of its Reinhart MF patch (1 = Tregenza's 145 ... 6) instead of the true "
                  "sun, to measure what a patch-based sky does to ASE (default 0: the true sun)")
      ->check(number_in(0, 6));
  cmd->add_option("--sky-patches", opt->annual.sky_patch_mf,
                  "Take the sky in Reinhart MF patches (1 = Tregenza's 145 ... 6), each uniform at its centre's luminance "
                  "as patch-based tools do, integrated exactly over the visible regions (default 0: the exact sky)")
      ->check(number_in(0, 6));
  add_reflection_options(*cmd, opt->reflections, "illuminance");
  cmd->add_option("--out", opt->out, "CSV file for per-sensor metrics (default: standard output)");
  cmd->add_option("--summary", opt->summary, "JSON file: per-grid metrics, pass levels, the sky's hours and clamps, bounds");
  cmd->add_option("--hourly", opt->hourly, "NumPy .npy file of hourly illuminance per sensor (float32; grid name appended when several)");
  CLI::Option* image = cmd->add_option(
      "--image", opt->image,
      "PNG plans of per-sensor metrics and a temporal map per grid (<stem>-<grid>-{da_300,udi_autonomous,direct_sun_hours,temporal}.png)");
  // The percentage plans (DA300, UDI) take df's image options; the direct sun hours (h) and the
  // temporal map (lux) keep their own automatic scales.
  add_image_options(*cmd, opt->image_options, image, "% of occupied hours, the DA300 and UDI plans");
  cmd->add_option("--geometry", opt->geometry, "Visibility arithmetic: exact (default), float or rational (as for `daylit df`)")
      ->check(CLI::IsMember({"exact", "float", "rational"}));
  cmd->add_option("--pressure-hpa", opt->annual.pressure_hpa, "Local pressure for refraction (hPa; default 1013.25)")
      ->check(number_in(0.0, 5000.0));
  cmd->add_option("--temperature-c", opt->annual.temperature_c, "Local temperature for refraction (°C; default 10)")
      ->check(number_in(-273.0, 6000.0));
  cmd->add_option("--threads", opt->threads, "Worker threads (default: all cores)")->check(non_negative_number());
  cmd->add_flag("--quiet", opt->quiet, "No progress bar or notices on stderr");
  return [opt] { return run_annual(*opt); };
}

}  // namespace daylit::cli
