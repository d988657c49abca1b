// examples/rolling-disk (Iaconeta et al. 2017 §5.2, extraction §8.2 / A8): a neo-Hookean disk on a
// 60 degree incline, the incline being the grid face y = 0 with gravity rotated (as Aulisa &
// Capodaglio do). The centre-of-mass acceleration along the incline, fitted over the run, against
// the analytic values (Iaconeta eqs. 64-66):
//  - no-slip face ("fixed", one-sided: every component zero on the nodes moving into the face):
//    rolling, a = 2/3 g sin(theta), within 5 % at R / h = 10 and closer than at R / h = 5, where
//    nodes ahead of the contact are held before the disk reaches them (issue 5; README.md table);
//  - frictionless face ("slip": the normal component zero): sliding, a = g sin(theta), within 2 %.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;

const double kTheta = std::numbers::pi / 3.0;
const double kGSin = 9.81 * std::sin(kTheta);

Spec disk(ConditionKind face, double cell_size) {
  Spec spec = load_example("rolling-disk");
  spec.conditions.at(0).kind = face;
  spec.conditions.at(0).normal_axis = 1;
  spec.grid.cell_size = {cell_size, cell_size, 0};
  for (int a = 0; a < 2; ++a)
    spec.grid.cells[a] = static_cast<int>(std::lround((spec.grid.max[a] - spec.grid.min[a]) / cell_size));
  return spec;
}

double acceleration(const Spec& spec, const std::string& tag) {
  Spec s = spec;
  s.checks.clear();
  s.checks.push_back({"a", "fitted_com_acceleration_x", 0, 0, ""});
  const auto result = run_quietly(s, tag);
  EXPECT_EQ(result.exit_code, 0) << result.message;
  return measured(result, "fitted_com_acceleration_x");
}

TEST(RollingDisk, NoSlipFaceRollsAtTwoThirdsGSinTheta) {
  const double exact = 2.0 / 3.0 * kGSin;  // Iaconeta eq. (64)
  const double coarse = acceleration(disk(ConditionKind::Fixed, 0.04), "rolling_coarse");  // R / h = 5
  const double fine = acceleration(disk(ConditionKind::Fixed, 0.02), "rolling_fine");      // R / h = 10
  EXPECT_NEAR(fine, exact, 0.05 * exact);
  EXPECT_LT(std::abs(fine - exact), std::abs(coarse - exact)) << "coarse " << coarse << ", fine " << fine;
}

TEST(RollingDisk, FrictionlessFaceSlidesAtGSinTheta) {
  const double a = acceleration(disk(ConditionKind::Slip, 0.04), "sliding");
  EXPECT_NEAR(a, kGSin, 0.02 * kGSin);
}

}  // namespace
