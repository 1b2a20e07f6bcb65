#include "cli/grid_command.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cli/number_checks.hpp"
#include "geometry/error.hpp"
#include "geometry/obj_model.hpp"
#include "report/staged_output.hpp"
#include "simulation/floor_grid.hpp"

namespace daylit::cli {

namespace {

struct GridOptions {
  FloorSources sources;
  FloorGridOptions grid;
  std::string out;
  bool quiet = false;
  bool obj_options_given = false;
};

// One sensor per line, x y z dx dy dz, 17 significant digits (the positions round-trip).
void write_pts(const std::string& path, const SensorGrid& grid) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw Error(path + ": cannot open for writing");
  for (const Sensor& s : grid.sensors)
    fmt::print(f, "{:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", s.position.x, s.position.y, s.position.z,
               s.normal.x, s.normal.y, s.normal.z);
  const bool failed = std::ferror(f) != 0;
  if (std::fclose(f) != 0 || failed) throw Error(path + ": cannot write");
}

int run_grid(const GridOptions& opt) {
  if (opt.sources.model.empty() == opt.sources.rad_files.empty())
    throw Error("give the floors with --model (an HBJSON or OBJ model) or with --scene (.rad files), one of them");
  if ((!opt.sources.obj_materials.empty() || opt.obj_options_given) && !is_obj_path(opt.sources.model))
    throw Error("--obj-materials, --obj-scale and --obj-up apply to an OBJ model (a --model ending in .obj)");
  if (!std::filesystem::is_directory(opt.out)) throw Error(opt.out + ": output directory does not exist");
  std::vector<std::string> notices;
  const std::vector<SensorGrid> grids = floor_grids(opt.sources, opt.grid, notices);
  StagedOutputs outputs;
  for (const auto& g : grids) write_pts(outputs.stage((std::filesystem::path(opt.out) / (g.name + ".pts")).string()), g);
  outputs.commit();
  if (!opt.quiet) {
    for (const auto& n : notices) std::cerr << "notice: " << n << '\n';
    for (const auto& g : grids) std::cerr << fmt::format("{}: {} sensors\n", g.name, g.sensors.size());
  }
  return 0;
}

}  // namespace

std::function<int()> add_grid_command(CLI::App& app) {
  auto opt = std::make_shared<GridOptions>();
  CLI::App* cmd = app.add_subcommand("grid", "Sensor grids on the floors of rooms (.pts)");
  cmd->description(
      "Lays cell-centred sensors, facing up, on a square lattice over the floors of rooms: at --height above\n"
      "the floor (0.85 m: EN 17037's reference plane) and at least --offset from the floor's edges (0.5 m:\n"
      "BREEAM Hea 01's perimeter band), every --spacing (0.5 m). Floors come from an HBJSON model (one grid\n"
      "per room, named by the room, from its faces of type Floor), from an OBJ model (the faces a rule of\n"
      "--obj-materials marks \"floor\": true, else every horizontal face facing up; one grid per group), or\n"
      "from .rad files (one grid per floor polygon: those with a --floor-modifier, else every horizontal\n"
      "polygon facing up). Writes DIR/<grid>.pts.");
  cmd->add_option("--model", opt->sources.model, "HBJSON or OBJ (.obj) model whose floors get grids")->check(CLI::ExistingFile);
  cmd->add_option("--obj-materials", opt->sources.obj_materials,
                  "With an OBJ --model: the map of df's --obj-materials; its rules with \"floor\": true mark the floors")
      ->check(CLI::ExistingFile);
  cmd->add_option_function<double>(
         "--obj-scale", [o = opt.get()](double s) { o->sources.obj.metres_per_unit = s; o->obj_options_given = true; },
         "With an OBJ --model: metres per unit (default 1)")
      ->check(positive_number());
  cmd->add_option_function<std::string>(
         "--obj-up",
         [o = opt.get()](const std::string& up) {
           o->sources.obj.up = up == "y" ? ObjUpAxis::y : ObjUpAxis::z;
           o->obj_options_given = true;
         },
         "With an OBJ --model: its up axis, z (default) or y")
      ->check(CLI::IsMember({"z", "y"}));
  cmd->add_option("--scene", opt->sources.rad_files, "Radiance files (.rad) holding the floor polygons")->check(CLI::ExistingFile);
  cmd->add_option("--floor-modifier", opt->sources.floor_modifiers,
                  "With --scene: the modifiers of the floor polygons (default: every horizontal polygon facing up)");
  cmd->add_option("--spacing", opt->grid.spacing, "Distance between sensors (model units; default 0.5)")->check(positive_number());
  cmd->add_option("--height", opt->grid.height, "Height of the sensors above the floor (default 0.85)");
  cmd->add_option("--offset", opt->grid.wall_offset, "Least distance of a sensor from the floor's edges (default 0.5)")
      ->check(non_negative_number());
  cmd->add_option("--out", opt->out, "Folder for the .pts files (one per grid)")->required();
  cmd->add_flag("--quiet", opt->quiet, "No notices on stderr");
  return [opt] { return run_grid(*opt); };
}

}  // namespace daylit::cli
