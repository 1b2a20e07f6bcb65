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
  namespace fs = std::filesystem;
  fs::path path(target);
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);  // of what a symbolic link names
  if (fs::is_directory(status)) throw Error(target + ": is a directory, not an output file");
  // A device, FIFO or socket (/dev/null, /dev/stdout, a pipe) is written in place: renaming a
  // file onto it would replace the device itself (as root, /dev/null became a plain file), and
  // what went into it cannot be taken back anyway.
  if (fs::exists(status) && !fs::is_regular_file(status)) return target;
  // A symbolic link keeps linking: the file it names is the one replaced.
  if (fs::is_symlink(fs::symlink_status(path, ec))) {
    const fs::path named = fs::read_symlink(path, ec);
    if (!ec) path = named.is_absolute() ? named : path.parent_path() / named;
  }
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
