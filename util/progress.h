// A one-line progress display for long work ("[matching] pair 12/39  1.4 s"), redrawn in place on
// stderr. It stays silent when stderr is not a terminal, so logs and CI output are not cluttered.
// Its calls may come from the threads of a parallel loop.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

namespace sfm {

class Progress {
 public:
  // `enabled` false silences it; true still requires stderr to be a terminal.
  explicit Progress(bool enabled);
  ~Progress();

  // Shows "[stage] <unit> i/n  elapsed" (i is 1-based for display).
  void Update(const std::string& stage, const std::string& unit, int i, int n);
  // One more of the n items of `stage` done (items of a parallel loop finish in any order): shows
  // the count done so far, as Update.
  void Tick(const std::string& stage, const std::string& unit, int n);
  // Shows "[stage] text  elapsed", for work whose length is not known ahead (solver iterations).
  void Show(const std::string& stage, const std::string& text);
  // Clears the line and the count of Tick.
  void Finish();

 private:
  void Draw(const std::string& stage, const std::string& text, bool last);

  bool active_;
  std::mutex mutex_;
  bool line_shown_ = false;
  std::string stage_;  // the stage drawn last
  int ticks_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace sfm
