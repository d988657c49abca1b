#include "matpoint/core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace matpoint {

Progress::Progress(bool enabled, double end_time)
    : enabled_(enabled),
      terminal_(isatty(STDERR_FILENO) != 0),
      end_time_(end_time),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void Progress::update(long step, double time) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double fraction = std::clamp(time / end_time_, 0.0, 1.0);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  if (terminal_) {
    if (now - last_draw_ < std::chrono::milliseconds(200)) return;
    last_draw_ = now;
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width);
    std::fprintf(stderr, "\r[%-*.*s] %5.1f%%  t = %.4g  step %ld  ETA %.0f s   ", width, filled,
                 "##############################", 100.0 * fraction, time, step, eta);
  } else {
    const int decile = static_cast<int>(fraction * 10.0);
    if (decile == last_decile_) return;
    last_decile_ = decile;
    std::fprintf(stderr, "progress %3d%%  t = %.6g  step %ld  elapsed %.1f s  ETA %.0f s\n", decile * 10, time, step,
                 elapsed, eta);
  }
}

void Progress::finish(const char* status) {
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "%s%s after %.2f s\n", terminal_ ? "\n" : "", status, elapsed);
}

}  // namespace matpoint
