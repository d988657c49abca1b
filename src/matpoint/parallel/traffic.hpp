// What a decomposed run's exchanges cost, counted as they happen (issue 23; bench/scaling.md):
// messages and bytes sent, particles moved, and the wall time spent, accumulated over the run.
// Only the decomposed classes (ColourHandOff, ParticleMigration) and the communicator's collectives
// on more than one rank add to them, so a serial run never touches one.
#pragma once

#include <chrono>
#include <cstddef>

namespace matpoint {

struct Traffic {
  long calls = 0;      // hand-offs / migrations / collectives that did something
  long messages = 0;   // point-to-point messages this rank sent
  long bytes = 0;      // their payload
  long particles = 0;  // particles this rank sent away (migration)
  double seconds = 0;  // wall time inside the calls (packing, waiting and unpacking included)
  double waiting = 0;  // of which inside the communicator's exchange (the wire and the wait for the peers)

  /// One message of `size` bytes carrying `moved` particles (none sent when `size` is 0).
  void sent(std::size_t size, std::size_t moved = 0) {
    if (size == 0) return;
    ++messages;
    bytes += static_cast<long>(size);
    particles += static_cast<long>(moved);
  }
  /// Starts a timed call; `done` adds its wall time.
  [[nodiscard]] static std::chrono::steady_clock::time_point start() {
    return std::chrono::steady_clock::now();
  }
  /// Adds the wall time since t0 to `waiting` (around Communicator::exchange).
  void waited(std::chrono::steady_clock::time_point t0) {
    waiting += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  void done(std::chrono::steady_clock::time_point t0) {
    ++calls;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
};

}  // namespace matpoint
