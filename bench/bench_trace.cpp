// `daylit bench trace`: the path tracer (path_tracer.hpp) on the user's own scene, the independent
// reference that `df --components all` is compared with on scenes outside the repository: the same
// model options as df, the CIE overcast sky (and a sun, where given), per sensor SC, ERC, IRC and DF
// with their standard errors, in df's columns, then the sun's direct part.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>

#include <unistd.h>

#include <fmt/format.h>

#include "bench/bench_suites.hpp"
#include "bench/path_tracer.hpp"
#include "geometry/error.hpp"
#include "report/staged_output.hpp"
#include "simulation/model_inputs.hpp"

namespace daylit::cli {

int run_bench_trace(const BenchOptions& opt) {
  ModelFiles files;
  files.scene_files = opt.trace.scene_files;
  files.aperture_files = opt.trace.aperture_files;
  files.grid_files = opt.trace.grid_files;
  const ModelInputs model = load_model(files, SkyModel::cie_overcast);
  if (!opt.quiet)
    for (const std::string& notice : model.scene.notices) std::cerr << "notice: " << notice << "\n";
  PathTracerOptions o;
  o.samples_per_sensor = opt.trace.paths;
  o.max_bounces = opt.trace.bounces;
  o.ground_reflectance = opt.trace.ground_reflectance;
  o.seed = opt.trace.seed;
  // The sun's direction from zenith and azimuth (clockwise from +y, north without a site).
  const double zenith = opt.trace.sun_zenith * std::numbers::pi / 180, azimuth = opt.trace.sun_azimuth * std::numbers::pi / 180;
  o.sun = {std::sin(zenith) * std::sin(azimuth), std::sin(zenith) * std::cos(azimuth), std::cos(zenith)};
  o.sun_normal = opt.trace.sun_normal;
  const std::filesystem::path dir(opt.out);
  std::filesystem::create_directories(dir);
  const std::string csv = (dir / "trace.csv").string();
  StagedOutputs outputs;
  std::ofstream f(outputs.stage(csv));
  f << "grid,index,x,y,z,dx,dy,dz,sc_percent,sc_se,erc_percent,erc_se,irc_percent,irc_se,df_percent,df_se,sun_percent,sun_se\n";
  const auto start = std::chrono::steady_clock::now();
  bench::StatusLine status(!opt.quiet && isatty(2));
  for (const SensorGrid& grid : model.grids) {
    status.show(fmt::format("bench trace: grid {}: {} sensors, {} paths, {} bounces", grid.name, grid.sensors.size(),
                            o.samples_per_sensor, o.max_bounces));
    const std::vector<PathTracedSensor> traced = path_trace(model.scene, grid.sensors, o);
    for (std::size_t i = 0; i < traced.size(); ++i) {
      const Sensor& s = grid.sensors[i];
      const PathTracedSensor& t = traced[i];
      f << fmt::format("{},{},{},{},{},{},{},{},{:.10g},{:.3g},{:.10g},{:.3g},{:.10g},{:.3g},{:.10g},{:.3g},{:.10g},{:.3g}\n",
                       grid.name, grid.first + i, s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y,
                       s.normal.z, t.sc.value, t.sc.standard_error, t.erc.value, t.erc.standard_error, t.irc.value,
                       t.irc.standard_error, t.df.value, t.df.standard_error, t.sun.value, t.sun.standard_error);
    }
  }
  status.clear();
  if (!f.flush()) throw Error(csv + ": cannot write");
  f.close();
  outputs.commit();
  if (!opt.quiet)
    std::cerr << fmt::format("bench trace: wrote {} ({} paths per sensor, {} bounces, {:.1f} s)\n", csv, o.samples_per_sensor,
                             o.max_bounces, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return 0;
}

}  // namespace daylit::cli
