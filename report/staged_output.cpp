#include "report/staged_output.hpp"

#include <unistd.h>

#include "geometry/error.hpp"

namespace daylit::cli {

StagedOutputs::~StagedOutputs() {
  if (committed_) return;
  std::error_code ignored;
  for (const auto& e : entries_) std::filesystem::remove(e.temporary, ignored);
}

std::string StagedOutputs::stage(const std::string& target) {
  const std::filesystem::path path(target);
  const auto parent = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  if (!std::filesystem::is_directory(parent)) throw Error(target + ": output directory does not exist");
  // Keep the extension last: image writers choose the format by it.
  std::string name = ".";  // appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "." + string
  name += path.stem().string();
  name += ".partial-";
  name += std::to_string(::getpid());
  name += path.extension().string();
  const std::filesystem::path temporary = parent / name;
  entries_.push_back({temporary, path});
  return temporary.string();
}

void StagedOutputs::commit() {
  for (const auto& e : entries_) {
    std::error_code ec;
    std::filesystem::rename(e.temporary, e.target, ec);
    if (ec) throw Error(e.target.string() + ": cannot write (" + ec.message() + ")");
  }
  committed_ = true;
}

}  // namespace daylit::cli
