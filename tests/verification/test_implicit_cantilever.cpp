// Aulisa & Capodaglio §6.2, Test B (examples/implicit-cantilever): the graded neo-Hookean
// cantilever deflects under its own weight, gravity is removed after 49 steps, and the beam
// vibrates freely for the remaining 7.6 s (1000 steps of 0.008 s, J = 2: 8 x 8 Q9 elements).
// The paper gives no numbers ("the damping of the oscillations is very small, for all mesh sizes"),
// so the expected values are the extraction's acceptance AT-9 and its estimates:
//   - Newton converges at every step (no step cut);
//   - the tip's amplitude decays by less than 5 % between the first and the last whole cycle;
//   - the period lies in 0.7-0.85 s (plane-strain Euler-Bernoulli first mode 0.67 s, lengthened by
//     shear, H / L = 0.4, and by the large deflection; README.md has a Timoshenko estimate);
//   - the oscillation's centre is the undeformed position (within 5 % of the peak-to-peak): an
//     elastic beam up-down symmetric about its axis, free of load, has no other equilibrium.
#include <gtest/gtest.h>

#include <cstdio>

#include "matpoint/analysis/measures_eval.hpp"
#include "test_support.hpp"

namespace matpoint {
namespace {

TEST(ImplicitCantilever, TestBFreeVibrationAtJ2) {
  const Spec spec = test::load_example("implicit-cantilever");
  const RunResult result = test::run_quietly(spec, "implicit_cantilever");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  const auto measure = [&](const char* name) {
    return evaluate_measure(name, spec, result.history, 0.0, nullptr);
  };
  const double cuts = measure("implicit_step_cuts"), period = measure("free_vibration_period");
  const double decay = measure("free_vibration_amplitude_decay"),
               offset = measure("free_vibration_mean_offset");
  std::printf(
      "Test B, J = 2: %ld steps, step cuts %g, period %.4f s, amplitude decay %.4f, centre offset %.4f\n",
      result.summary["steps"].get<long>(), cuts, period, decay, offset);
  EXPECT_EQ(result.summary["steps"].get<long>(), 1000);
  EXPECT_EQ(cuts, 0.0);
  EXPECT_GE(period, 0.7);
  EXPECT_LE(period, 0.85);
  EXPECT_LT(std::abs(decay), 0.05);
  EXPECT_LT(std::abs(offset), 0.05);
}

}  // namespace
}  // namespace matpoint
