#include "report/honeybee_results.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "geometry/error.hpp"

namespace daylit::cli {

void stage_honeybee_results(StagedOutputs& outputs, const std::string& folder, const std::vector<GridReport>& reports) {
  if (!std::filesystem::is_directory(folder)) throw Error(folder + ": results folder does not exist (create it first)");
  nlohmann::json info = nlohmann::json::array();
  for (const auto& r : reports) {
    const std::string path = (std::filesystem::path(folder) / (r.grid->name + ".res")).string();
    std::FILE* f = std::fopen(outputs.stage(path).c_str(), "w");
    if (!f) throw Error(path + ": cannot open for writing");
    // 17 significant digits, as the CSV: the values round-trip.
    for (const double df : r.df_percent) fmt::print(f, "{:.17g}\n", df);
    const bool failed = std::ferror(f) != 0;
    if (std::fclose(f) != 0 || failed) throw Error(path + ": cannot write");
    info.push_back({{"name", r.grid->name},
                    {"identifier", r.grid->name},
                    {"count", r.df_percent.size()},
                    {"group", ""},
                    {"full_id", r.grid->name},
                    {"start_ln", 0}});
  }
  const std::string info_path = (std::filesystem::path(folder) / "grids_info.json").string();
  std::ofstream out(outputs.stage(info_path));
  out << info.dump(2) << '\n';
  if (!out) throw Error(info_path + ": cannot write");
}

}  // namespace daylit::cli
