#include <fmt/format.h>
#include <cstdio>

#include "cli/reports.hpp"
#include "geometry/error.hpp"

namespace daylit::cli {

void write_csv(std::FILE* out, const std::vector<GridReport>& reports) {
  fmt::print(out, "grid,index,x,y,z,dx,dy,dz,sc_percent,df_percent\n");
  for (const auto& r : reports) {
    const auto& sensors = r.grid->sensors;
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      const auto& s = sensors[i];
      // 17 significant digits: the values round-trip, so exactness is not lost in the file.
      fmt::print(out, "{},{},{},{},{},{},{},{},{:.17g},{:.17g}\n", r.grid->name, i, s.position.x, s.position.y,
                 s.position.z, s.normal.x, s.normal.y, s.normal.z, r.sc_percent[i], r.df_percent[i]);
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
