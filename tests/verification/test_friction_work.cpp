// Friction work against rigid-body Coulomb sliding: a block sliding down a rigid incline
// (examples/incline-friction, theta = 30 deg, mu = 0.3) dissipates D = mu M g cos(theta) d over a
// slip d, and its energy balance K + U + D - W_gravity stays at 0. Both follow from the rigid-body
// solution; d is the block's measured slip, so the check is on the friction accounting alone.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;

TEST(FrictionWork, FlipSlidingBlockDissipatesMuNTimesTheSlip) {
  Spec spec = load_example("incline-friction");
  const auto result = run_quietly(spec, "friction_work_flip");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  const auto& first = result.history.samples.front();
  const auto& last = result.history.samples.back();
  const double mass = first.body_mass[0], g = 9.81, theta = std::numbers::pi / 6, mu = 0.3;
  const double slip = last.body_com_position[0][0] - first.body_com_position[0][0];
  const double expected = mu * mass * g * std::cos(theta) * slip;
  EXPECT_NEAR(last.friction_work / expected, 1.0, 0.02);  // measured 0.989
  const double balance = last.kinetic_energy + last.strain_energy + last.friction_work - last.external_work;
  EXPECT_LT(std::abs(balance) / last.external_work, 0.005);  // measured -0.11 %
}

}  // namespace
