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

struct Dissipation {
  double ratio;    // friction work / (mu M g cos(theta) slip)
  double balance;  // (K + U + D - W_gravity) / W_gravity at the end
};

Dissipation slide(Spec spec, const char* name) {
  const auto result = run_quietly(spec, name);
  EXPECT_EQ(result.exit_code, 0) << result.message;
  if (result.history.samples.empty()) return {0.0, 1.0};
  const auto& first = result.history.samples.front();
  const auto& last = result.history.samples.back();
  const double mass = first.body_mass[0], g = 9.81, theta = std::numbers::pi / 6, mu = 0.3;
  const double slip = last.body_com_position[0][0] - first.body_com_position[0][0];
  const double expected = mu * mass * g * std::cos(theta) * slip;
  const double balance = last.kinetic_energy + last.strain_energy + last.friction_work - last.external_work;
  return {last.friction_work / expected, balance / last.external_work};
}

TEST(FrictionWork, FlipSlidingBlockDissipatesMuNTimesTheSlip) {
  const auto d = slide(load_example("incline-friction"), "friction_work_flip");
  EXPECT_NEAR(d.ratio, 1.0, 0.02);        // measured 0.989
  EXPECT_LT(std::abs(d.balance), 0.005);  // measured -0.11 %
}

// Under FMPM the particles take V = S v+(k), which keeps task 1.a's contact correction of the
// momenta: its impulse is friction too (contact.hpp apply_lumped). Without it FMPM(4) counted
// 0.83 / 0.90 / 0.92 of the exact work at C = 0.1 / 0.2 / 0.3, a fixed loss per step.
TEST(FrictionWork, FmpmSlidingBlockDissipatesMuNTimesTheSlip) {
  for (const double courant : {0.1, 0.3}) {
    Spec spec = load_example("incline-friction");
    spec.solver.transfer = VelocityTransfer::FMPM;
    spec.solver.fmpm.order = 4;
    spec.solver.courant = courant;
    const auto d = slide(spec, "friction_work_fmpm");
    EXPECT_NEAR(d.ratio, 1.0, 0.02) << "C = " << courant;
    EXPECT_LT(std::abs(d.balance), 0.005) << "C = " << courant;
  }
}

}  // namespace
