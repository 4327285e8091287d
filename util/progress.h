// A one-line progress display for long work ("[matching] pair 12/39  1.4 s"), redrawn in place on
// stderr. It stays silent when stderr is not a terminal, so logs and CI output are not cluttered.
#pragma once

#include <chrono>
#include <string>

namespace sfm {

class Progress {
 public:
  // `enabled` false silences it; true still requires stderr to be a terminal.
  explicit Progress(bool enabled);
  ~Progress();

  // Shows "[stage] <unit> i/n  elapsed" (i is 1-based for display).
  void Update(const std::string& stage, const std::string& unit, int i, int n);
  // Clears the line.
  void Finish();

 private:
  bool active_;
  bool line_shown_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace sfm
