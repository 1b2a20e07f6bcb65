#include "cli/df_command.hpp"

#include <CLI/CLI.hpp>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
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
#include "simulation/model_inputs.hpp"
#include "report/progress_bar.hpp"
#include "report/honeybee_results.hpp"
#include "report/model_reports.hpp"
#include "report/reports.hpp"
#include "report/staged_output.hpp"
#include "geometry/error.hpp"
#include "geometry/sky_box.hpp"
#include "geometry/visibility.hpp"
#include "simulation/daylight_criteria.hpp"
#include "simulation/sky_component.hpp"
#include "simulation/reflected_components.hpp"
#include "materials/surface_reflectance.hpp"

namespace daylit::cli {

namespace {

struct DfOptions {
  ModelFiles files;
  std::string sky = "cie-overcast";
  std::string geometry = "exact";
  std::string order = "front-to-back";
  std::string out, summary, image, results;
  int threads = 0;
  bool quiet = false;
  bool gradient = false, refine = false;
  double refine_tolerance = 0.01;  // DF percentage points of a cell's mean
  ReflectionCliOptions reflections;
  double median_diffuse_lux = 0;   // EN 17037's E_v,d,med; 0: no EN 17037 block
  ImageCliOptions image_options;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int run_df(DfOptions opt) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!mpi::root()) opt.quiet = true;  // under MPI, rank 0 alone speaks (and writes)
  if (opt.reflections.all() && (opt.gradient || opt.refine))
    throw Error("--gradient and --refine concern the sky component alone; use them with --components sc");
  const SkyModel sky = parse_sky_model(opt.sky);
  const ImageScale image_scale_asked = image_scale(opt.image_options);
  const GeometryMode mode = opt.geometry == "float"      ? GeometryMode::floating
                            : opt.geometry == "rational" ? GeometryMode::rational
                                                         : GeometryMode::exact;
  const int threads = opt.threads > 0 ? opt.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));

  ModelInputs model = load_model(opt.files, sky);
  const Scene& scene = model.scene;
  const std::vector<SensorGrid>& grids = model.grids;
  if (!opt.quiet) {
    for (const auto& notice : scene.notices) std::cerr << "notice: " << notice << '\n';
    notice_unused_reflection_options(opt.reflections, opt.quiet, scene);
  }

  const SubtractionOrder order = opt.order == "front-to-back" ? SubtractionOrder::front_to_back : SubtractionOrder::as_built;
  const VisibilityEngine engine(scene, mode, order);
  const std::unique_ptr<DirectSky> direct = direct_sky(scene, grids, mode, order);
  const VisibilityEngine* direct_engine = direct ? &direct->engine : nullptr;
  const bool show_progress = !opt.quiet && stderr_is_terminal();

  std::vector<GridReport> reports;
  double reflections_time_s = 0;
  const std::vector<std::string> hosts = mpi::hosts();
  const std::vector<std::uint64_t> rank_threads = mpi::gather_per_rank(std::uint64_t(threads));
  std::vector<mpi::ShardedGrid> shards;
  for (const auto& grid : grids) {
    const auto tg = std::chrono::steady_clock::now();
    // The sky component is sharded (cli/mpi_shards.hpp): this rank computes its block of the
    // grid's sensors (all of them with one rank) and rank 0 gathers the blocks in grid order, so
    // that from here on it holds the whole grid's values as one process computes them.
    SensorGrid storage;
    const SensorGrid& block = mpi::rank_block(grid, storage);
    ProgressBar bar("df " + grid.name, block.sensors.size(), show_progress);
    const bool gradient = opt.gradient || opt.refine;
    SkyComponentResult sc = sky_component(engine, scene, block, sky, [&](std::size_t done) { bar.update(done); }, gradient, direct_engine);
    shards.push_back({grid.name, grid.sensors.size(), {seconds_since(tg)}});
    if (mpi::several()) {  // one rank: the values are the grid's already (no copies of millions)
      sc.sc_percent = mpi::gather(sc.sc_percent, grid.sensors.size());
      if (gradient) sc.sc_gradient = mpi::gather(sc.sc_gradient, grid.sensors.size());
    }
    sc.counters = mpi::sum(sc.counters);
    for (double b : mpi::gather_per_rank(sc.pane_bound_percent)) sc.pane_bound_percent = std::max(sc.pane_bound_percent, b);
    shards.back().time_s = mpi::gather_per_rank(shards.back().time_s.front());
    if (!mpi::root()) continue;  // the statistics, refinement and reports are rank 0's
    GridReport r;
    r.grid = &grid;
    r.sc_percent = sc.sc_percent;
    r.df_percent = std::move(sc.sc_percent);  // DF = SC: the components computed in this run
    r.df_gradient = std::move(sc.sc_gradient);
    r.statistics = grid_statistics(r.df_percent);
    r.counters = sc.counters;
    r.pane_bound_percent = sc.pane_bound_percent;
    if (opt.refine)
      r.refinement = refine_grid(engine, scene, sky, grid, r.df_percent, r.df_gradient, opt.refine_tolerance, r.counters, direct_engine);
    r.run_time_s = seconds_since(tg);
    reports.push_back(std::move(r));
  }

  // The other ranks' part of the run ends here. Rank 0 solves the reflected components alone:
  // the radiosity is one solution for the whole model, whose mesh (its automatic element size,
  // the surface sides left out) depends on every grid's sensors, so it is not sharded.
  if (!mpi::root()) return 0;

  // Apertures that every sensor sees only enclosed space through: a window between two rooms that
  // nothing marks as interior (a Honeybee folder files such windows in scene/, beside exterior glass
  // shades, where the HBJSON says Surface and its reader refuses the model). Zeros are then the
  // answer, but not one to give without a word.
  const bool sky_seen = std::any_of(reports.begin(), reports.end(), [](const GridReport& r) {
    return std::any_of(r.sc_percent.begin(), r.sc_percent.end(), [](double v) { return v > 0; });
  });
  if (!sky_seen && !reports.empty()) {
    model.scene.notices.push_back(
        "no sensor sees the sky through any of the " + std::to_string(scene.apertures.size()) +
        " apertures: each one's outside is closed by the model's surfaces, or lies behind every sensor, so every "
        "sky component is 0. A window between rooms taken for an opening to the sky?");
    if (!opt.quiet) std::cerr << "notice: " << model.scene.notices.back() << '\n';
  }

  // ---- Reflected components (DESIGN.md §4), over all grids at once: one radiosity solution.
  std::optional<ReflectionResult> reflections;
  std::map<std::string, SurfaceReflectance> used_materials;
  if (opt.reflections.all()) {
    SceneReflectances scene_rho = scene_reflectances(scene);
    const std::vector<double>& reflectance = scene_rho.reflectance;
    used_materials = std::move(scene_rho.materials);
    ReflectionOptions ro = reflection_options(opt.reflections);
    ro.sky = sky;
    ro.mode = mode;
    std::vector<const SensorGrid*> grid_ptrs;
    for (const auto& g : grids) grid_ptrs.push_back(&g);
    const auto tr = std::chrono::steady_clock::now();
    ro.on_progress = reflection_progress_bars(show_progress);
    reflections = reflected_components(scene, reflectance, engine, grid_ptrs, ro);
    reflections_time_s = seconds_since(tr);
    if (!opt.quiet && reflections->black)
      std::cerr << "notice: nothing reflects (every surface black and --ground-reflectance 0): ERC = IRC = 0, no "
                   "radiosity work done\n";
    if (!opt.quiet && !reflections->stopped.empty()) std::cerr << "notice: " << reflections->stopped << '\n';
    for (std::size_t g = 0; g < reports.size(); ++g) {
      GridReport& r = reports[g];
      const SensorReflections& sr = reflections->grids[g];
      r.erc_percent = sr.erc_percent;
      r.irc_percent = sr.irc_percent;
      r.reflection_error_percent = sr.error_percent;
      for (std::size_t i = 0; i < r.df_percent.size(); ++i) r.df_percent[i] = r.sc_percent[i] + sr.erc_percent[i] + sr.irc_percent[i];
      r.statistics = grid_statistics(r.df_percent);
    }
  }

  StagedOutputs outputs;
  if (!opt.out.empty() && opt.out != "-") {
    write_csv(outputs.stage(opt.out), reports);
  }
  if (!opt.results.empty()) stage_honeybee_results(outputs, opt.results, reports);
  // Each grid's walls and apertures: drawn on its image, and BREEAM's perimeter band in the summary.
  std::vector<const SensorGrid*> report_grids;
  for (const auto& r : reports) report_grids.push_back(r.grid);
  const std::vector<PlanDrawing> plans = plan_drawings(scene, report_grids);
  if (!opt.image.empty()) {
    for (std::size_t g = 0; g < reports.size(); ++g) {
      GridReport r = reports[g];
      r.plan = &plans[g];
      r.scale = image_scale_asked;
      write_falsecolour_image(outputs.stage(image_path_for(opt.image, r.grid->name, reports.size())), r);
    }
  }

  nlohmann::json summary;
  summary["sky"] = std::string(sky_model_name(sky));
  summary["geometry"] = opt.geometry;
  summary["subtraction_order"] = opt.order;
  summary["threads"] = threads;
  if (reflections) {
    summary["components"] = reflection_summary(*reflections, used_materials, opt.reflections, reflections_time_s,
                                               "per unit zenith luminance");
    summary["components"]["df_percent_is"] = "sc_percent + erc_percent + irc_percent";
  } else {
    summary["components"] = {
        {"computed", {"sc"}},
        {"left_out",
         {{"erc", "externally reflected component: not computed (--components sc)"},
          {"irc", "internally reflected component: not computed (--components sc)"}}},
        {"df_percent_is", "sc_percent"}};
  }
  if (model.site) summary["site"] = site_json(*model.site, opt.files.site);
  if (model.context) summary["context"] = context_json(*model.context, opt.files.context);
  summary["scene"] = scene_json(scene, engine);
  if (mpi::several())
    summary["mpi"] = mpi::summary_json(
        shards, hosts, rank_threads, "the sky component (and its gradient): every grid's sensors in blocks, one per rank",
        "on every rank: reading the model and building the visibility engine; on rank 0 alone: the reflected components "
        "(one radiosity solution for the whole model; the other ranks wait), --refine's added sensors, the statistics "
        "and every output");
  for (std::size_t g = 0; g < reports.size(); ++g) {
    const GridReport& r = reports[g];
    const auto& s = r.statistics;
    nlohmann::json shares;
    for (std::size_t t = 0; t < s.share_at_or_above.size(); ++t)
      shares[fmt::format("{:g}", s.thresholds[t])] = s.share_at_or_above[t];
    summary["grids"].push_back({{"name", r.grid->name},
                                {"path", r.grid->path},
                                {"count", s.count},
                                {"sees_sky_directly", r.grid->sees_sky_directly},
                                {"df_percent", {{"mean", s.mean}, {"median", s.median}, {"min", s.min}, {"max", s.max}}},
                                {"uniformity", {{"min_over_mean", s.min_over_mean}, {"min_over_median", s.min_over_median}}},
                                {"share_at_or_above_df_percent", shares},
                                {"run_time_s", r.run_time_s},
                                {"pane_bound_percent", r.pane_bound_percent},
                                {"left_out", counters_json(r.counters)}});
    if (!r.erc_percent.empty()) {
      nlohmann::json per;
      const double mean_df = s.mean;
      for (const auto& [name, values] : {std::pair<const char*, const std::vector<double>*>{"sc_percent", &r.sc_percent},
                                         {"erc_percent", &r.erc_percent},
                                         {"irc_percent", &r.irc_percent},
                                         {"reflection_error_estimate_percent", &r.reflection_error_percent}}) {
        const GridStatistics c = grid_statistics(*values);
        per[name] = {{"mean", c.mean}, {"median", c.median}, {"min", c.min}, {"max", c.max},
                     {"uniformity_min_over_mean", c.min_over_mean},
                     {"share_of_mean_df", mean_df > 0 ? c.mean / mean_df : 0.0}};
      }
      summary["grids"].back()["components"] = per;
    }
    if (opt.median_diffuse_lux > 0)
      summary["grids"].back()["en17037_df_method"] = en17037_json(en17037_df_method(r.df_percent, opt.median_diffuse_lux));
    summary["grids"].back()["breeam_hea_01"] =
        breeam_json(breeam_hea01(*r.grid, r.df_percent, plans[g]),
                    reflections ? "sc_percent + erc_percent + irc_percent" : "sc_percent (--components sc)");
    if (r.refinement) {
      const GridRefinement& f = *r.refinement;
      summary["grids"].back()["refinement"] = {
          {"estimator",
           "midpoint-rule error of each cell's mean, (w^2/24)(H11 + H22), H from the exact DF gradients of the "
           "neighbouring sensors (Holzschuch and Sillion 1995, section 3.2); cells: squares of side w, the nearest-"
           "neighbour spacing in the sensor's plane; means weighted by cell area"},
          {"tolerance_df_percent", f.tolerance},
          {"cells_split", f.cells_split},
          {"sensors_added", f.added.size()},
          {"cells_without_neighbours", f.cells_without_neighbours},
          {"mean_df_percent", {{"before", f.mean_before}, {"after", f.mean_after}}},
          {"estimated_error_of_mean_df_percent", {{"before", f.error_before}, {"after", f.error_after}}}};
    }
  }
  summary["run_time_s"] = seconds_since(t0);
  if (!opt.summary.empty()) {
    std::ofstream f(outputs.stage(opt.summary));
    f << summary.dump(2) << '\n';
    if (!f) throw Error(opt.summary + ": cannot write summary");
  }
  outputs.commit();
  if (opt.out.empty() || opt.out == "-") write_csv(stdout, reports);
  if (!opt.quiet)
    for (const auto& r : reports) {
      std::cerr << fmt::format("{}: {} sensors, mean DF {:.3f} %, median {:.3f} %, min {:.3f} %, max {:.3f} % ({:.2f} s)\n",
                               r.grid->name, r.statistics.count, r.statistics.mean, r.statistics.median,
                               r.statistics.min, r.statistics.max, r.run_time_s);
      if (const auto& f = r.refinement)
        std::cerr << fmt::format("{}: refined {} of {} cells (+{} sensors): mean DF {:.6f} % -> {:.6f} %, estimated error of "
                                 "the mean {:.3g} % -> {:.3g} %\n",
                                 r.grid->name, f->cells_split, r.statistics.count, f->added.size(), f->mean_before,
                                 f->mean_after, f->error_before, f->error_after);
    }
  return 0;
}

}  // namespace

std::function<int()> add_df_command(CLI::App& app) {
  auto opt = std::make_shared<DfOptions>();
  CLI::App* df = app.add_subcommand("df", "Daylight factors on sensor grids (sky component, exact)");
  df->description(
      "Computes the daylight factor at every sensor of the grids under a CIE overcast (or uniform) sky.\n"
      "Each aperture is clipped exactly against the occluders as seen from each sensor, and the sky is\n"
      "integrated over what stays visible in closed form: no rays, no noise. Reported: the sky component\n"
      "(SC) and, with --components all, the externally and internally reflected components (ERC, IRC)\n"
      "from a radiosity solution with exact transport, with an estimate of their error per sensor.\n"
      "With --site and --context, neighbouring buildings given as GeoJSON footprints (WGS84, with a\n"
      "height property) are placed in the model frame and extruded into opaque prisms; those that cannot\n"
      "be seen through any aperture, and those smaller than --context-min-angle from every aperture, are\n"
      "left out, and the summary says how many and bounds what that changes.");
  ModelFiles& files = opt->files;
  df->add_option("--scene", files.scene_files, "Radiance scene files (.rad): occluders; glass polygons are apertures")
      ->check(CLI::ExistingFile);
  df->add_option("--apertures", files.aperture_files, "Radiance files whose polygons are sky openings")->check(CLI::ExistingFile);
  df->add_option("--grid", files.grid_files, "Sensor grids (.pts: x y z dx dy dz per line); with --model, the model's grids by default")->check(CLI::ExistingFile);
  add_model_options(*df, files);
  df->add_option("--sky", opt->sky, "Sky model: cie-overcast (default) or uniform")
      ->check(CLI::IsMember({"cie-overcast", "uniform"}));
  df->add_option("--out", opt->out, "CSV file for per-sensor results (default, or -: standard output; ./- for a file named -)");
  df->add_option("--results", opt->results,
                 "Existing folder for results in Honeybee's layout: <grid>.res (one DF % per line) and grids_info.json");
  df->add_option("--summary", opt->summary, "JSON file for per-grid statistics and what was left out");
  CLI::Option* image = df->add_option("--image", opt->image,
                                      "PNG plan image per grid (grid name appended when there are several), the walls "
                                      "cut at the grid's height and the apertures drawn over the values");
  add_image_options(*df, opt->image_options, image, "DF %");
  df->add_option("--geometry", opt->geometry,
                 "Visibility arithmetic: exact (default: certified intervals, rationals where needed), float (plain "
                 "doubles, for comparison) or rational (rationals throughout: a slow reference)")
      ->check(CLI::IsMember({"exact", "float", "rational"}));
  df->add_option("--subtraction-order", opt->order,
                 "Order in which occluders' shadows are subtracted: front-to-back (default: nearest first, shadows hidden "
                 "behind others skipped by boxes, pieces merged where their union is convex) or as-built (the order of "
                 "daylit before 2026-12, to reproduce its results to the last bit: the same region partitioned otherwise, "
                 "so results differ in the last digits, a few 1e-14; far slower among many occluders)")
      ->check(CLI::IsMember({"as-built", "front-to-back"}));
  df->add_option("--threads", opt->threads, "Worker threads (default: all cores)")->check(non_negative_number());
  df->add_option("--site", files.site,
                 "Site JSON: {\"latitude_deg\", \"longitude_deg\", \"elevation_m\", \"north_deg\"} (north_deg: true north's angle "
                 "clockwise from the model's +y, seen from above) or {\"utm\": {\"zone\", \"northern\"}, \"origin_easting_m\", "
                 "\"origin_northing_m\", \"elevation_m\"} for a model on a UTM grid")
      ->check(CLI::ExistingFile);
  df->add_option("--context", files.context,
                 "GeoJSON of neighbouring buildings: Polygon/MultiPolygon footprints in WGS84 with a \"height\" property "
                 "(m; optional \"min_height\" or \"base\"), extruded into occluders; needs --site")
      ->check(CLI::ExistingFile);
  df->add_option("--context-min-angle", files.context_min_angle_deg,
                 "Leave out context buildings whose angular size from every aperture is below this (degrees; default 0.1, "
                 "0: keep all that can be seen); the summary bounds the change it makes")
      ->check(number_in(0.0, 179.0));
  df->add_flag("--gradient", opt->gradient,
               "Also the gradient of DF with respect to the sensor's position (exact: the boundary term of Arvo's irradiance "
               "Jacobian, occluder edges included): CSV columns ddf_dx, ddf_dy, ddf_dz in % per model unit");
  df->add_flag("--refine", opt->refine,
               "Split the cells of the grid where the gradients say it is too coarse (Holzschuch-Sillion 3.2): each sensor's "
               "cell is a square of its nearest-neighbour spacing; cells whose estimated error of the mean exceeds "
               "--refine-tolerance get 2x2 new sensors (CSV columns added, cell_area; implies --gradient); the summary and "
               "stderr give the estimated error of the grid's mean DF before and after");
  df->add_option("--refine-tolerance", opt->refine_tolerance,
                 "Estimated error of a cell's mean DF above which --refine splits it (DF percentage points; default 0.01)")
      ->check(positive_number());
  add_reflection_options(*df, opt->reflections, "DF");
  df->add_option("--median-diffuse-lux", opt->median_diffuse_lux,
                 "The site's median diffuse horizontal illuminance over the daylight hours (lux; EN 17037 Table A.3): "
                 "the summary then assesses each grid by EN 17037's daylight-factor method (targets 100 E/E_med for its "
                 "three levels, over 50 % and 95 % of the sensors)")
      ->check(positive_number());
  df->add_flag("--quiet", opt->quiet, "No progress bar or notices on stderr");
  return [opt] { return run_df(*opt); };
}

}  // namespace daylit::cli
