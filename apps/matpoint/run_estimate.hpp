// Before a run: how many steps and roughly how long, from the input alone (printed by `check` and
// before `run` starts), so that a unit mix-up or an oversized problem shows before the wait.
#pragma once

#include <string>

#include "matpoint/io/spec.hpp"

namespace matpoint {

struct RunEstimate {
  double dt = 0;          // solver.dt, or the Courant number with the fastest elastic wave
  double steps = 0;       // end_time / dt (at most solver.max_steps)
  double particles = 0;   // an upper estimate (bodies' bounding boxes, io/memory_estimate.hpp)
  double seconds = 0;     // on one thread at the measured rate of this basis and dimension
  bool implicit = false;  // solver.type "implicit_mpm": seconds counts the assembly only
};

/// The estimate; steps and seconds are 0 where no wave speed is known (rigid bodies only).
RunEstimate estimate_run(const Spec& spec);

/// "about 1.2e+04 steps of dt = 8e-06 x at most 1e+06 particles: roughly 25 min on one thread".
std::string describe(const RunEstimate& estimate);

}  // namespace matpoint
