// The time step of an implicit run (docs/input.md "Implicit runs"): solver.dt held fixed, a user
// schedule dt(t) read at each step's start (solver.implicit.dt_schedule), dt of the lowest particle's
// coordinate (solver.implicit.dt_by_position: Aulisa & Capodaglio's Test D), or adaptive on Newton's
// iteration count (solver.implicit.adaptive_dt). The adaptive rule, applied after each completed
// step:
//   - the step needed c > 0 cuts: the next step is the sub-step that converged, dt / 2^c;
//   - else Newton's largest iteration count in the step n <= easy_iterations: dt * factor;
//   - else n >= hard_iterations: dt / factor;
// always within [min, max]. The run loop may shorten a step to land on an output time; the
// controller keeps its own dt, so such a step does not shrink the next one.
#pragma once

#include <algorithm>
#include <cmath>

#include "matpoint/io/spec.hpp"

namespace matpoint::implicit {

class StepSizeControl {
 public:
  explicit StepSizeControl(const SolverSpec& solver)
      : schedule_(solver.implicit.dt_schedule),
        by_position_(solver.implicit.dt_by_position),
        adaptive_(solver.implicit.adaptive),
        dt_(solver.dt.value_or(schedule_ ? (*schedule_)(0.0) : 0.0)) {}

  /// Whether next() reads the lowest particle's coordinate.
  [[nodiscard]] bool by_position() const { return by_position_.has_value(); }

  /// The step to take from `time`; `lowest`: the lowest particle's coordinate along
  /// solver.implicit.dt_position_axis (read with dt_by_position only).
  [[nodiscard]] double next(double time, double lowest = 0.0) const {
    if (by_position_) return (*by_position_)(lowest);
    return schedule_ ? (*schedule_)(time) : dt_;
  }

  /// After a completed step that was tried at `dt_tried` (the run loop's, possibly shortened),
  /// needed `cuts` halvings, and whose Newton solves took at most `iterations`.
  void after_step(double dt_tried, int cuts, int iterations) {
    if (!adaptive_.enabled) return;
    if (cuts > 0)
      dt_ = std::min(dt_, dt_tried / std::ldexp(1.0, cuts));
    else if (iterations <= adaptive_.easy_iterations)
      dt_ *= adaptive_.factor;
    else if (iterations >= adaptive_.hard_iterations)
      dt_ /= adaptive_.factor;
    dt_ = std::clamp(dt_, adaptive_.min, adaptive_.max);
  }

  /// The adaptive step (a checkpoint keeps it).
  [[nodiscard]] double current() const { return dt_; }
  void restore(double dt) { dt_ = dt; }

 private:
  std::optional<TimeFunction> schedule_, by_position_;
  ImplicitSpec::Adaptive adaptive_;
  double dt_;
};

}  // namespace matpoint::implicit
