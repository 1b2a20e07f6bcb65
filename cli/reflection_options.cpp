#include "cli/reflection_options.hpp"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>

#include <fmt/format.h>

#include "cli/number_checks.hpp"
#include "report/progress_bar.hpp"

namespace daylit::cli {

void add_reflection_options(CLI::App& command, ReflectionCliOptions& o, const std::string& what) {
  command
      .add_option("--components", o.components,
                  "sc (default): direct light alone (the sky component; the sun too for illuminance); all: also the "
                  "externally and internally reflected components (ERC, IRC) of the " + what + ", by an "
                  "exact-transport radiosity solution with an error estimate per sensor")
      ->check(CLI::IsMember({"sc", "all"}));
  o.options.push_back(command.add_option("--ground-reflectance", o.ground_reflectance,
                                         "Reflectance of the far ground: directions below the horizon that meet no "
                                         "surface see rho_g E_h / pi (default 0.2, as gensky's ground glow); the model's "
                                         "own ground polygons are surfaces")
                          ->check(number_in(0.0, 0.999999)));
  o.options.push_back(command.add_option("--reflection-tolerance", o.tolerance,
                                         "Target of every sensor's estimated error of ERC + IRC, in percent of the "
                                         "unobstructed horizontal illuminance (DF points; default 0.05): while it is "
                                         "not met and --max-refinements allows, the elements that matter most to the "
                                         "sensors over it are split again")
                          ->check(positive_number()));
  o.options.push_back(command.add_option("--element-size", o.element_size,
                                         "Longest element edge near the sensors and apertures (model units; default: a "
                                         "fifth of the longest side of the box around a grid's sensors, or of half the "
                                         "room's span around them where that is longer), growing with "
                                         "the distance farther away; the error estimate compares with elements twice "
                                         "as large")
                          ->check(positive_number()));
  o.options.push_back(command.add_option("--max-refinements", o.max_refinements,
                                         "Further rounds of local refinement while the tolerance is not met "
                                         "(default 2; 0: the first mesh and its uniform split only)")
                          ->check(number_in(0, 8)));
  o.options.push_back(command.add_option("--element-grading", o.grading,
                                         "How fast elements grow away from the sensors and apertures: an element at "
                                         "distance d from them has edges up to max(element size, grading x d) "
                                         "(default 0.5); smaller values refine the far surfaces too, for convergence "
                                         "studies")
                          ->check(number_in(0.01, 10.0)));
  o.options.push_back(command.add_option("--reflection-transport", o.transport,
                                         "reciprocal (default): the transport between elements as collocated at the "
                                         "nodes, made symmetric (reciprocity) with every node's emission accounted for "
                                         "(closure), so that energy is conserved to roundoff on every mesh; collocated: "
                                         "the rows as collocated, whose energy balance is off by the mesh's reciprocity "
                                         "defect (reported, falling under refinement), for comparison")
                          ->check(CLI::IsMember({"reciprocal", "collocated"})));
}

namespace {

// The memory this process may use: the machine's, or its control group's limit where lower
// (a container's: cgroup v2's memory.max, v1's memory.limit_in_bytes); 0 where unknown.
std::size_t usable_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  std::size_t bytes = pages > 0 && page > 0 ? std::size_t(pages) * std::size_t(page) : 0;
  for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(path);
    unsigned long long limit = 0;
    if (in >> limit && limit > 0) bytes = bytes == 0 ? std::size_t(limit) : std::min(bytes, std::size_t(limit));
  }
  return bytes;
}

}  // namespace

ReflectionOptions reflection_options(const ReflectionCliOptions& o) {
  ReflectionOptions r;
  // Three quarters of it for the rows of K: the rest for the visibility engines, the sensors'
  // cache and the other processes of the machine.
  r.memory_bytes = usable_memory_bytes() / 4 * 3;
  r.ground_reflectance = o.ground_reflectance;
  r.tolerance_percent = o.tolerance;
  r.element_size = o.element_size;
  r.max_refinements = o.max_refinements;
  r.grading = o.grading;
  r.reciprocal_transport = o.transport == "reciprocal";
  return r;
}

std::function<void(const std::string&, const std::string&, std::size_t, std::size_t)> reflection_progress_bars(
    bool shown) {
  if (!shown) return {};
  struct Bars {
    std::string stage;
    std::unique_ptr<ProgressBar> bar;
  };
  auto bars = std::make_shared<Bars>();
  return [bars](const std::string& stage, const std::string& unit, std::size_t done, std::size_t total) {
    if (!bars->bar || bars->stage != stage) {
      bars->bar.reset();  // the finished stage's bar closes its line first
      bars->stage = stage;
      bars->bar = std::make_unique<ProgressBar>(stage, total, true, unit);
    }
    bars->bar->update(done);
  };
}

void notice_unused_reflection_options(const ReflectionCliOptions& o, bool quiet, const Scene& scene) {
  if (quiet || o.all()) return;
  for (const CLI::Option* option : o.options)
    if (option->count() > 0)
      std::cerr << "notice: " << option->get_name()
                << " is not used: the reflected components are computed with --components all\n";
  // The materials that reflect, which this run leaves out (a mirror, which --components all
  // refuses, reflects too).
  std::set<std::string> used;  // by an occluder
  for (const Polygon& p : scene.occluders) used.insert(p.material);
  std::vector<std::string> reflecting;
  for (const auto& [name, m] : scene.materials) {
    if (!used.count(name)) continue;
    try {
      const double rho = surface_reflectance(&m).reflectance;
      if (rho > 0) reflecting.push_back(fmt::format("{} '{}' {:.3g}", m.type, name, rho));
    } catch (const Error&) {
      reflecting.push_back(m.type + " '" + name + "'");
    }
  }
  if (reflecting.empty()) return;
  std::string list;
  for (std::size_t i = 0; i < reflecting.size() && i < 4; ++i) list += (i ? ", " : "") + reflecting[i];
  if (reflecting.size() > 4) list += fmt::format(" and {} more", reflecting.size() - 4);
  std::cerr << "notice: the reflectances of " << reflecting.size() << " material" << (reflecting.size() > 1 ? "s" : "")
            << " (" << list << ") are not used: --components sc computes the sky seen directly (and the sun) only; "
               "--components all adds the externally and internally reflected components\n";
}

nlohmann::json reflection_summary(const ReflectionResult& r, const std::map<std::string, SurfaceReflectance>& materials,
                                  const ReflectionCliOptions& opt, double run_time_s,
                                  const std::string& unit) {
  nlohmann::json j;
  j["computed"] = {"sc", "erc", "irc"};
  j["ground_reflectance"] = opt.ground_reflectance;
  nlohmann::json mats;
  for (const auto& [name, m] : materials) mats[name] = {{"reflectance", m.reflectance}, {"description", m.description}};
  j["materials"] = mats;
  if (r.black) {
    j["radiosity"] = "none: every surface is black and the ground reflectance is 0, so ERC = IRC = 0 exactly";
    return j;
  }
  j["method"] =
      "radiosity over every reflecting polygon and every reflecting pane (glass, trans: see materials), both sides, "
      "triangles of linearly varying exitance (3 nodes inside "
      "each, the degree-2 rule's points); first bounce exact (sky and far ground through the apertures, and seen "
      "directly through a box around the model); transport exact per element (Chen-Arvo linear luminaire over the "
      "exactly visible part, occluders cut to the luminaire's side of its plane); ERC: far ground and surfaces seen "
      "through apertures (weighted by their transmittance; glass: T at the element's centre direction), IRC: "
      "surfaces seen inside; Gauss-Seidel sweeps to roundoff, over-relaxed where the transport is reciprocal (see "
      "solver), each refinement's starting from the solution of the mesh it refines";
  j["mesh"] = {{"elements", r.elements}, {"unknowns", r.unknowns}, {"max_level", r.max_level},
               {"refinement_rounds", r.refinements}, {"element_size", r.element_size},
               {"element_size_is", opt.element_size > 0 ? "as given (--element-size)"
                                                        : "automatic: a fifth of the longest side of the box around a grid's sensors, or of half the room's span around them where that is longer (the median over the grids)"},
               {"grading", opt.grading},
               {"max_error_percent_by_round", r.error_by_round}};
  j["solver"] = {{"sweeps", r.sweeps}, {"over_relaxation", r.over_relaxation},
                 {"last_relative_change", r.solver_change}, {"reflectance_max", r.reflectance_max}};
  j["error"] = {
      {"tolerance_percent", opt.tolerance},
      {"max_estimate_percent", r.max_error_percent},
      {"met", r.max_error_percent <= opt.tolerance},
      {"stopped", r.stopped.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.stopped)},
      {"how",
       "estimate, not a rigorous bound: each sensor's ERC and IRC from the reported mesh against those from the mesh "
       "it was split from (elements twice as large), element by element (|what an element gives - what its four "
       "children give|), summed, plus, through glass, the spread of T over each element's directions times what it "
       "gives; after local rounds, elements not split since keep the terms they had. It covers the error where "
       "halving the elements at least halves it; linear elements do better (second order where the exitance is "
       "smooth), so the actual error is usually a fraction of it"}};
  const bool reciprocal = opt.transport == "reciprocal";
  j["energy_balance"] = {
      {"first_bounce_flux", r.flux_first_bounce},
      {"absorbed_flux", r.flux_absorbed},
      {"escaping_flux", r.flux_escaping},
      {"relative_mismatch", r.balance_mismatch},
      {"how",
       unit + ": what the sky and far ground put on all surfaces (each element side's first bounce by the nodes' "
       "degree-2 rule) = what they absorb (a pane's share: what it does not reflect, transmitted or absorbed) + "
       "what leaves them unreceived (each node's exitance times the part of its view that meets no element). " +
       (reciprocal
            ? std::string("The transport is reciprocal and closed (see transport), so the discrete system conserves "
                          "energy and the mismatch is the solver's roundoff; the collocation's own reciprocity "
                          "defect, which the correction removed, is given beside it")
            : std::string("The transport is as collocated at the nodes: the mismatch is the mesh's reciprocity "
                          "defect and falls under refinement"))}};
  if (reciprocal)
    j["energy_balance"]["transport"] = {
        {"reciprocal", true},
        {"collocation_reciprocity_defect", r.reciprocity.reciprocity_defect},
        {"max_relative_exchange_change", r.reciprocity.max_entry_change},
        {"max_escaping_fraction_change", r.reciprocity.max_row_change},
        {"exchanges", r.reciprocity.entries},
        {"exchanges_added", r.reciprocity.entries_added},
        {"conjugate_gradient_iterations", r.reciprocity.iterations},
        {"conjugate_gradient_coarse_aggregates", r.reciprocity.coarse_aggregates},
        {"closure_residual", r.reciprocity.residual},
        {"how",
         "the exchanges w_u K_uj between nodes (w = element area / 3) replaced by the symmetric ones nearest to "
         "them, relative change (lambda_u + lambda_j) per exchange, each node's row plus what escapes it kept equal "
         "to its weight (a node that sees no opening keeps its row sum exactly), in the manner of the least-squares "
         "smoothing of exchange areas in zonal methods (Larsen and Howell 1986); defect: max over nodes of "
         "|sum_j (S_uj - G_uj)| / w_u"}};
  else
    j["energy_balance"]["transport"] = {{"reciprocal", false}};
  j["left_out"] = {
      {"direct_sky_at_sensors", "sensors see the sky through the apertures only (SC); a sensor outside the model "
                                "sees no sky directly"},
      {"receivers_seeing_no_sky_directly", r.receivers_direct_empty},
      {"receivers_enclosed", r.receivers_direct_enclosed},
      {"receivers_enclosed_why", "of those seeing no sky directly, the ones inside a closed surface of the model "
                                 "(polygons whose edges pair up, e.g. a room's walls, floor, ceiling and panes): known "
                                 "by the parity of an exact ray crossing count, so their six sky-box visibility queries "
                                 "were left out"},
      {"receivers", r.receivers_direct},
      {"surface_sides_solved", r.sides_solved},
      {"surface_sides_left_out", r.sides_left_out},
      {"surface_sides_left_out_why", "no light from them reaches a sensor, directly or by reflection (decided by "
                                     "which side of each plane the sensors and surfaces lie on; exact: the values "
                                     "solved are those of the whole system)"},
      {"specular", "specular parts of plastic and metal are reflected diffusely (see materials)"}};
  j["run_time_s"] = run_time_s;
  nlohmann::json stages = nlohmann::json::array();
  for (const auto& stage : r.stages) stages.push_back({{"stage", stage.stage}, {"wall_s", stage.wall_s}});
  j["stages"] = stages;
  return j;
}

}  // namespace daylit::cli
