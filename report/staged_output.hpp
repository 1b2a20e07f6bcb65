#pragma once
// Output files that appear only when the whole run has succeeded: each is written under a
// temporary name beside its target and renamed at commit(); anything not committed is removed,
// so a failed run leaves no partial output behind.

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

  // Temporary path to write instead of `target`.
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
