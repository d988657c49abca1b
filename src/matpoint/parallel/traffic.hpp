// What a decomposed run's exchanges cost, counted as they happen (issue 23; bench/scaling.md):
// messages and bytes sent, particles moved, and the wall and CPU time spent, accumulated over the
// run. Only the decomposed classes (ColourHandOff, ParticleMigration) and the communicator's
// collectives on more than one rank add to them, so a serial run never touches one.
#pragma once

#include <chrono>
#include <cstddef>
#include <ctime>

namespace matpoint {

struct Traffic {
  long calls = 0;          // hand-offs / migrations / collectives that did something
  long messages = 0;       // point-to-point messages this rank sent
  long bytes = 0;          // their payload
  long particles = 0;      // particles this rank sent away (migration)
  double seconds = 0;      // wall time inside the calls (packing, waiting and unpacking included)
  double cpu = 0;          // the process' CPU time inside them
  double waiting = 0;      // wall time inside the communicator's exchange (the wire, the wait for the peers)
  double waiting_cpu = 0;  // CPU time in there (MPI polls while it waits)

  /// A point in wall and process CPU time.
  struct Clock {
    std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
    std::clock_t cpu = std::clock();
    [[nodiscard]] double wall_since() const {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
    }
    [[nodiscard]] double cpu_since() const {
      return static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
    }
  };

  /// One message of `size` bytes carrying `moved` particles (none sent when `size` is 0).
  void sent(std::size_t size, std::size_t moved = 0) {
    if (size == 0) return;
    ++messages;
    bytes += static_cast<long>(size);
    particles += static_cast<long>(moved);
  }
  /// Starts a timed call (or exchange); `done` (`waited`) adds its times.
  [[nodiscard]] static Clock start() { return {}; }
  void waited(const Clock& t0) {
    waiting += t0.wall_since();
    waiting_cpu += t0.cpu_since();
  }
  void done(const Clock& t0) {
    ++calls;
    seconds += t0.wall_since();
    cpu += t0.cpu_since();
  }
};

}  // namespace matpoint
