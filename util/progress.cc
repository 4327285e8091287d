#include "util/progress.h"

#include <unistd.h>

#include <cstdio>

namespace sfm {

Progress::Progress(bool enabled)
    : active_(enabled && ::isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { Finish(); }

void Progress::Update(const std::string& stage, const std::string& unit, int i, int n) {
  if (!active_) return;
  const auto now = std::chrono::steady_clock::now();
  // Redraw at most every 50 ms, and always for the last item, so progress costs nothing.
  if (line_shown_ && i < n && now - last_draw_ < std::chrono::milliseconds(50)) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r\033[K[%s] %s %d/%d  %.1f s", stage.c_str(), unit.c_str(), i, n, elapsed);
  std::fflush(stderr);
  line_shown_ = true;
}

void Progress::Finish() {
  if (active_ && line_shown_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  }
  line_shown_ = false;
}

}  // namespace sfm
