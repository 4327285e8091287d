#include "util/progress.h"

#include <unistd.h>

#include <cstdio>

namespace sfm {

Progress::Progress(bool enabled)
    : active_(enabled && ::isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { Finish(); }

void Progress::Update(const std::string& stage, const std::string& unit, int i, int n) {
  if (!active_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  Draw(stage, unit + " " + std::to_string(i) + "/" + std::to_string(n), i >= n);
}

void Progress::Tick(const std::string& stage, const std::string& unit, int n) {
  if (!active_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  ++ticks_;
  Draw(stage, unit + " " + std::to_string(ticks_) + "/" + std::to_string(n), ticks_ >= n);
}

void Progress::Show(const std::string& stage, const std::string& text) {
  if (!active_) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  // A new stage is drawn at once.
  Draw(stage, text, /*last=*/stage != stage_);
}

// Redraws at most every 50 ms, and always for the last item, so progress costs nothing.
void Progress::Draw(const std::string& stage, const std::string& text, bool last) {
  const auto now = std::chrono::steady_clock::now();
  if (line_shown_ && !last && now - last_draw_ < std::chrono::milliseconds(50)) return;
  last_draw_ = now;
  stage_ = stage;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r\033[K[%s] %s%s%.1f s", stage.c_str(), text.c_str(), text.empty() ? "" : "  ",
               elapsed);
  std::fflush(stderr);
  line_shown_ = true;
}

void Progress::Finish() {
  const std::lock_guard<std::mutex> lock(mutex_);
  ticks_ = 0;
  if (active_ && line_shown_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  }
  line_shown_ = false;
}

}  // namespace sfm
