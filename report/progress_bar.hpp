#pragma once
// A progress bar on stderr for long runs: drawn only when stderr is a terminal and not --quiet.

#include <chrono>
#include <cstddef>
#include <string>

namespace daylit::cli {

class ProgressBar {
 public:
  // `unit`: what is counted ("sensors", "element sides").
  ProgressBar(std::string label, std::size_t total, bool enabled, std::string unit = "sensors");
  ~ProgressBar();
  void update(std::size_t done);

 private:
  std::string label_, unit_;
  std::size_t total_;
  bool enabled_;
  bool drawn_ = false;
  std::size_t last_done_ = 0;
  std::chrono::steady_clock::time_point start_, last_;
};

// True if stderr is a terminal.
bool stderr_is_terminal();

}  // namespace daylit::cli
