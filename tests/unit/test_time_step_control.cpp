// The implicit time-step control (implicit/step_size_control.hpp) by its documented rule, and
// loads.gravity_scale in the explicit solver (taken at each step's start).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "matpoint/implicit/step_size_control.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/run/run_loop.hpp"
#include "test_support.hpp"

namespace matpoint {
namespace {

SolverSpec adaptive_solver() {
  SolverSpec s;
  s.kind = SolverKind::ImplicitMpm;
  s.dt = 0.01;
  s.implicit.adaptive = {true, 0.001, 0.04, 3, 8, 2.0};
  return s;
}

TEST(StepSizeControl, FixedStepStaysTheInputs) {
  SolverSpec s;
  s.dt = 0.01;
  implicit::StepSizeControl control(s);
  control.after_step(0.01, 2, 15);  // not adaptive: nothing changes
  EXPECT_EQ(control.next(3.0), 0.01);
}

TEST(StepSizeControl, AdaptiveGrowsShrinksAndFollowsCuts) {
  implicit::StepSizeControl control(adaptive_solver());
  EXPECT_EQ(control.next(0.0), 0.01);
  control.after_step(0.01, 0, 3);  // easy (<= 3 iterations): times the factor
  EXPECT_DOUBLE_EQ(control.next(0.0), 0.02);
  control.after_step(0.02, 0, 5);  // neither easy nor hard: unchanged
  EXPECT_DOUBLE_EQ(control.next(0.0), 0.02);
  control.after_step(0.02, 0, 8);  // hard (>= 8): divided by the factor
  EXPECT_DOUBLE_EQ(control.next(0.0), 0.01);
  control.after_step(0.01, 2, 4);  // two cuts: the sub-step that converged, 0.01 / 4
  EXPECT_DOUBLE_EQ(control.next(0.0), 0.0025);
  for (int k = 0; k < 10; ++k) control.after_step(control.next(0.0), 0, 1);
  EXPECT_DOUBLE_EQ(control.next(0.0), 0.04);  // held at max
  for (int k = 0; k < 10; ++k) control.after_step(control.next(0.0), 0, 12);
  EXPECT_DOUBLE_EQ(control.next(0.0), 0.001);  // held at min
}

TEST(StepSizeControl, AStepShortenedToLandOnAnOutputDoesNotShrinkTheNext) {
  implicit::StepSizeControl control(adaptive_solver());
  control.after_step(0.003, 0, 5);  // the run loop shortened the step; Newton was neither easy nor hard
  EXPECT_DOUBLE_EQ(control.next(0.0), 0.01);
}

TEST(StepsToLand, ExplicitTakesFullStepsThenWhateverIsLeft) {
  const auto far = run_loop_detail::steps_to_land(0.25, 0.1, false);
  EXPECT_EQ(far.h, 0.1);
  EXPECT_FALSE(far.lands);
  const auto near = run_loop_detail::steps_to_land(0.0500001, 0.1, false);
  EXPECT_EQ(near.h, 0.0500001);
  EXPECT_TRUE(near.lands);
}

TEST(StepsToLand, ImplicitSplitsAShortRemainderIntoTwoEqualSteps) {
  // 0.31 left with dt = 0.1: 0.1, 0.1, then 0.055 twice; never 0.1, 0.1, 0.1, 0.01.
  double remaining = 0.31;
  std::vector<double> steps;
  for (bool lands = false; !lands;) {
    const auto next = run_loop_detail::steps_to_land(remaining, 0.1, true);
    steps.push_back(next.h);
    lands = next.lands;
    remaining -= next.h;
  }
  ASSERT_EQ(steps.size(), 4U);
  EXPECT_EQ(steps[0], 0.1);
  EXPECT_EQ(steps[1], 0.1);
  EXPECT_NEAR(steps[2], 0.055, 1e-15);
  EXPECT_NEAR(steps[3], 0.055, 1e-15);
  // Within dt (1 + 1e-6) the step lands at once, stretched by at most 1e-6.
  EXPECT_TRUE(run_loop_detail::steps_to_land(0.1000000001, 0.1, true).lands);
}

TEST(StepSizeControl, ScheduleIsReadAtTheStepsStart) {
  SolverSpec s;
  s.implicit.dt_schedule = TimeFunction{{0.0, 1.0}, {0.01, 0.03}};
  implicit::StepSizeControl control(s);
  EXPECT_DOUBLE_EQ(control.next(0.0), 0.01);
  EXPECT_DOUBLE_EQ(control.next(0.5), 0.02);
  EXPECT_DOUBLE_EQ(control.next(7.0), 0.03);
}

// A block falling freely under the explicit solver with gravity switched off after t1 = 0.05 s:
// the explicit step takes gravity at its start, so the steps starting at t = 0, dt, ..., t1 (51
// steps of dt = 1e-3) accelerate it and the later ones do not: v = g (t1 + dt) from then on, the
// same for every particle (a rigid translation, no stress).
TEST(GravityScale, ExplicitGravitySwitchedOffAtAStepBoundary) {
  const Spec spec = parse_spec(R"({"grid": {"dim": 2, "min": [0, 0], "max": [1, 1], "cell_size": 0.1},
    "materials": [{"name": "m", "model": "linear_elastic", "density": 1000, "E": 1e6, "nu": 0.3}],
    "bodies": [{"material": "m", "shape": {"type": "box", "min": [0.4, 0.6], "max": [0.6, 0.8]}}],
    "loads": {"gravity": [0, -10], "gravity_scale": {"table": [[0.05, 1], [0.0505, 0]]}},
    "solver": {"dt": 0.001, "end_time": 0.1, "transfer": "flip", "basis": "linear"},
    "output": {"every_steps": 10, "plots": false, "particles": false}})");
  const RunResult result = test::run_quietly(spec, "explicit_gravity_off");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  for (const auto& s : result.history.samples) {
    const double v = -s.body_com_velocity[0][1];
    const double expected = s.time < 0.0505 ? 10 * s.time : 10 * 0.051;  // rows every 10 steps
    EXPECT_NEAR(v, expected, 1e-9) << "t = " << s.time;
  }
}

}  // namespace
}  // namespace matpoint
