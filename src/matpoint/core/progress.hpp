// Run progress on stderr: a one-line bar with time, step and ETA on a terminal, plain log lines
// (every 10 % of the run) otherwise.
#pragma once

#include <chrono>

namespace matpoint {

class Progress {
 public:
  Progress(bool enabled, double end_time);
  void update(long step, double time);
  void finish(const char* status);

 private:
  bool enabled_, terminal_;
  double end_time_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace matpoint
