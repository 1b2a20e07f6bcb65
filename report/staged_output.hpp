#pragma once
// Output files that appear only when the whole run has succeeded: each is written under a
// temporary name beside its target and renamed at commit(); anything not committed is removed,
// so a failed run leaves no partial output behind. A target that is a device or a pipe
// (/dev/null, /dev/stdout) is written in place; one that is a symbolic link replaces the file the
// link names.

#include <filesystem>
#include <string>
#include <vector>

namespace daylit::cli {

class StagedOutputs {
 public:
  StagedOutputs() = default;
  StagedOutputs(const StagedOutputs&) = delete;
  StagedOutputs& operator=(const StagedOutputs&) = delete;
  ~StagedOutputs();

  // Path to write instead of `target` (`target` itself where it is a device or a pipe).
  std::string stage(const std::string& target);
  // Renames every staged file onto its target.
  void commit();

 private:
  struct Entry {
    std::filesystem::path temporary, target;
  };
  std::vector<Entry> entries_;
  bool committed_ = false;
};

}  // namespace daylit::cli
