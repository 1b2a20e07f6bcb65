#include <fmt/format.h>
#include <cstdio>

#include "report/reports.hpp"
#include "geometry/error.hpp"

namespace daylit::cli {

void write_csv(std::FILE* out, const std::vector<GridReport>& reports) {
  const bool gradient = !reports.empty() && !reports.front().df_gradient.empty();
  const bool refined = !reports.empty() && reports.front().refinement.has_value();
  const bool reflected = !reports.empty() && !reports.front().erc_percent.empty();
  fmt::print(out, "grid,index,x,y,z,dx,dy,dz,sc_percent,{}{}{}\n",
             reflected ? "erc_percent,irc_percent,df_percent,reflection_error_estimate_percent" : "df_percent",
             gradient ? ",ddf_dx,ddf_dy,ddf_dz" : "", refined ? ",added,cell_area" : "");
  // 17 significant digits: the values round-trip, so exactness is not lost in the file.
  const auto row = [&](const GridReport& r, std::size_t index, const Sensor& s, double sc, double df, const Vec3* g,
                       int added, double area) {
    fmt::print(out, "{},{},{},{},{},{},{},{},{:.17g},{:.17g}", r.grid->name, index, s.position.x, s.position.y, s.position.z,
               s.normal.x, s.normal.y, s.normal.z, sc, df);
    if (gradient) fmt::print(out, ",{:.17g},{:.17g},{:.17g}", g->x, g->y, g->z);
    if (refined) fmt::print(out, ",{},{:.17g}", added, area);
    fmt::print(out, "\n");
  };
  for (const auto& r : reports) {
    const auto& sensors = r.grid->sensors;
    if (reflected) {
      // df computes reflections for every grid or none, and refuses them with gradients.
      for (std::size_t i = 0; i < sensors.size(); ++i) {
        const Sensor& s = sensors[i];
        fmt::print(out, "{},{},{},{},{},{},{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", r.grid->name, i, s.position.x,
                   s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z, r.sc_percent[i], r.erc_percent[i],
                   r.irc_percent[i], r.df_percent[i], r.reflection_error_percent[i]);
      }
      continue;
    }
    for (std::size_t i = 0; i < sensors.size(); ++i)
      row(r, i, sensors[i], r.sc_percent[i], r.df_percent[i], gradient ? &r.df_gradient[i] : nullptr, 0,
          refined ? r.refinement->cell_area[i] : 0);
    if (refined) {
      // The added sensors see only the sky component, as their parents: DF = SC.
      const GridRefinement& f = *r.refinement;
      for (std::size_t k = 0; k < f.added.size(); ++k)
        row(r, sensors.size() + k, f.added[k], f.added_df[k], f.added_df[k], &f.added_gradient[k], 1,
            f.cell_area[sensors.size() + k]);
    }
  }
}

void write_csv(const std::string& path, const std::vector<GridReport>& reports) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) throw Error(path + ": cannot open for writing");
  write_csv(out, reports);
  const bool failed = std::ferror(out) != 0;
  if (std::fclose(out) != 0 || failed) throw Error(path + ": cannot write CSV");
}

}  // namespace daylit::cli
