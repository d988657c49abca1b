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

// The same test on the C1 quadratic B-spline background (mesh.element "bspline2", J = 3: 16 x 16
// cells) for the first 2.4 s (the release at 0.4 s and 2.5 cycles). On Q9 the reset C0 grid's
// equilibrium defect drains the free vibration (examples/implicit-cantilever/README.md: 7.6 % of K + U
// in these 2 s at J = 3 with these particles, 41 % at J = 4); a C1 background removes the defect
// (docs/theory/implicit.md). Expected, from the acceptance above: the amplitude within 5 % over the
// window, and K + U lost by 2.4 s below 2.6 % of K + U at the release, the share of the 5 % amplitude
// (10 % energy) budget of the 7.6 s free vibration that falls on its first 2 s at a constant rate.
TEST(ImplicitCantilever, TestBOnTheBSplineBackgroundKeepsItsEnergy) {
  Spec spec = test::load_example("implicit-cantilever");
  spec.mesh.element = MeshElement::BSpline2;
  spec.mesh.refine = 3;
  spec.grid.cells = {16, 16, 1};
  spec.grid.cell_size = {1.0 / 16, 1.0 / 16, 1.0};
  spec.solver.end_time = 2.4;
  const RunResult result = test::run_quietly(spec, "implicit_cantilever_bspline");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  const auto measure = [&](const char* name) {
    return evaluate_measure(name, spec, result.history, 0.0, nullptr);
  };
  const auto& samples = result.history.samples;
  std::size_t release = 0;
  while (samples[release].time < 0.4 - 1e-9) ++release;
  const auto energy = [&](const HistorySample& h) { return h.kinetic_energy + h.strain_energy; };
  const double lost = (energy(samples[release]) - energy(samples.back())) / energy(samples[release]);
  const double decay = measure("free_vibration_amplitude_decay"), period = measure("free_vibration_period");
  std::printf("Test B on B-splines, J = 3, to 2.4 s: K + U lost %.4f, amplitude decay %.4f, period %.4f s\n",
              lost, decay, period);
  EXPECT_EQ(measure("implicit_step_cuts"), 0.0);
  EXPECT_LT(lost, 0.026);
  EXPECT_LT(std::abs(decay), 0.05);
  EXPECT_GE(period, 0.7);
  EXPECT_LE(period, 0.85);
}

}  // namespace
}  // namespace matpoint
