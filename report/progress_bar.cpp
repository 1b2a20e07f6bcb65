#include "report/progress_bar.hpp"

#include <unistd.h>

#include <cstdio>

namespace daylit::cli {

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(std::string label, std::size_t total, bool enabled, std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      total_(total),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fputc('\n', stderr);
}

void ProgressBar::update(std::size_t done) {
  if (!enabled_ || total_ == 0 || (drawn_ && done == last_done_)) return;
  const auto now = std::chrono::steady_clock::now();
  // Draw after half a second (short runs stay silent), then at most ten times a second.
  if (now - start_ < std::chrono::milliseconds(500) && done < total_) return;
  if (drawn_ && now - last_ < std::chrono::milliseconds(100) && done < total_) return;
  last_ = now;
  last_done_ = done;
  constexpr int width = 40;
  const double fraction = double(done) / double(total_);
  const int filled = int(fraction * width);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r%s [%-*s] %3d%% %zu/%zu %s, %.1f s", label_.c_str(), width,
               std::string(std::size_t(filled), '=').c_str(), int(100 * fraction), done, total_, unit_.c_str(), elapsed);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace daylit::cli
