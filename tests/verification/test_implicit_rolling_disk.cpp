// Aulisa & Capodaglio §6.2, Test A (examples/implicit-rolling-disk): the neo-Hookean disk rolling
// without slip down a 45 deg plane, implicit particle-Newmark MPM on the authors' graded Q9 mesh.
// Expected values: Table 1, E = 4.2e6 with C_E eq. (50): the averaged error (52) against the rigid
// rolling disk (49) is 5.545e-2 at J = 1 and 3.921e-2 at J = 2; +/- 30 % (the tolerance the
// acceptance of this method sets: the mesh is the code's (x-length 1.2 m, extraction A8), the gap
// d0 = R + 0.2 / 2^(J-1) as §11.1 gives it, C_c = 0 as in the code snapshot that made the table).
// The error must fall from J = 1 to J = 2, and x(2.5 s) = 14.4515 m (eq. (49)) within 5 % at J = 2.
// Measured when written (one thread, about 40 s per run): J = 1 5.73e-2, J = 2 4.21e-2, x(2.5) at
// J = 2 15.03 m (+4.0 %).
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "matpoint/analysis/measures_eval.hpp"
#include "test_support.hpp"

namespace matpoint {
namespace {

struct TestA {
  double error = 0.0, final_x = 0.0;
};

TestA run_test_a(int refine, const std::string& file = "input.json", double gap_j1 = 0.2,
                 std::optional<double> receding = std::nullopt) {
  Spec spec = test::load_example("implicit-rolling-disk", file);
  if (receding) spec.conditions[0].receding = *receding;
  const double gap = gap_j1 / std::ldexp(1.0, refine - 1);  // d0 - R = gap_J1 / 2^(J - 1) (extraction §11.1)
  spec.mesh.refine = refine;
  spec.bodies[0].center[1] = -1.6 + 1.6 + gap;
  spec.output.probes[0].position[1] = spec.bodies[0].center[1];
  for (std::size_t a = 0; a < 2; ++a) {  // the run's seeding grid follows the refined mesh
    spec.grid.cells[a] = spec.mesh.cells[a] << refine;
    spec.grid.cell_size[a] = (spec.grid.max[a] - spec.grid.min[a]) / spec.grid.cells[a];
  }
  const RunResult result = test::run_quietly(spec, "implicit_rolling_disk_" + std::to_string(refine));
  EXPECT_EQ(result.exit_code, 0) << result.message;
  TestA out;
  out.error = evaluate_measure("rolling_disk_mean_relative_error", spec, result.history, 0.0, nullptr);
  const auto& last = result.history.samples.back();
  out.final_x = last.probes.at(2) - result.history.samples.front().probes.at(2);  // probe ux
  std::printf("Test A, %s, C_c = %g, J = %d: error (52) %.4e, x(%.2f s) = %.4f m\n", file.c_str(),
              spec.conditions[0].receding, refine, out.error, last.time, out.final_x);
  return out;
}

TEST(ImplicitRollingDisk, TestATable1SoftDiskJ1AndJ2) {
  const TestA j1 = run_test_a(1), j2 = run_test_a(2);
  EXPECT_NEAR(j1.error, 5.545e-2, 0.3 * 5.545e-2);
  EXPECT_NEAR(j2.error, 3.921e-2, 0.3 * 3.921e-2);
  EXPECT_LT(j2.error, j1.error);
  EXPECT_NEAR(j2.final_x, 14.4515, 0.05 * 14.4515);
}

// Table 1, E = 4.2e8 with C_E eq. (51), C_c = 0.5 (the paper's value, §6.2), J = 1: 4.520e-2 +/- 30 %.
// Extraction AT-11 (the receding correction matters): with C_c = 0 the stiff disk sticks to the
// plane and lags the rigid disk rolling without slip, which an elastic disk rolling without slip
// does not do (eq. (49) is its rigid limit): x(2.5 s) below 95 % of 14.4515 m (5 %: the size of
// the paper's own averaged errors at this resolution). Measured when written: C_c = 0.5 error 4.52e-2, x
// = 15.52 m
// (+7.4 %: hence only the error is held to the table); C_c = 0: error 1.90e-1, x = 12.92 m (-10.6 %).
TEST(ImplicitRollingDisk, TestATable1StiffDiskAndRecedingCorrection) {
  const TestA corrected = run_test_a(1, "input-stiff.json", 0.3);
  const TestA sticky = run_test_a(1, "input-stiff.json", 0.3, 0.0);
  EXPECT_NEAR(corrected.error, 4.520e-2, 0.3 * 4.520e-2);
  EXPECT_LT(sticky.final_x, 0.95 * 14.4515);
}

}  // namespace
}  // namespace matpoint
