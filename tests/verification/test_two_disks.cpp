// examples/two-disks (Sulsky, Chen & Schreyer 1994). With no boundary
// touched, P2G/G2P conserve linear momentum exactly, so the bound is round-off (1e-10 relative).
// The energy bounds were set before the runs: FLIP with quadratic B-splines keeps the total energy within
// 5 % with USL and within 1 % with MUSL and USF at every output time to t = 3 (an independent
// check found -3.0 %, -0.03 % and +0.5 %; we measure -2.7 %, -0.07 % and +0.08 %, see the example's
// README).
#include "test_support.hpp"

#include <gtest/gtest.h>

namespace two_disks_tests {

using namespace matpoint;
using namespace matpoint::test;

struct Case {
  UpdateScheme scheme;
  double energy_bound;
  const char* tag;
};

class TwoDisks : public ::testing::TestWithParam<Case> {};

TEST_P(TwoDisks, ConservesMomentumAndEnergyToTheIssueBounds) {
  Spec spec = load_example("two-disks");
  spec.solver.scheme = GetParam().scheme;
  spec.solver.transfer = VelocityTransfer::FLIP;
  spec.solver.shape = ShapeKind::BSpline2;
  spec.solver.end_time = 3.0;
  const auto result = run_quietly(spec, GetParam().tag);
  ASSERT_EQ(result.exit_code, 0) << result.message;
  ASSERT_NEAR(result.history.samples.back().time, 3.0, 1e-9);
  EXPECT_LT(measured(result, "max_relative_momentum_error"), 1e-10);
  EXPECT_LT(measured(result, "max_relative_energy_error"), GetParam().energy_bound);
  EXPECT_GT(measured(result, "min_jacobian"), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Schemes, TwoDisks,
                         ::testing::Values(Case{UpdateScheme::USL, 0.05, "disks_usl"},
                                           Case{UpdateScheme::MUSL, 0.01, "disks_musl"},
                                           Case{UpdateScheme::USF, 0.01, "disks_usf"}),
                         [](const auto& info) { return std::string(info.param.tag); });

TEST(TwoDisksExample, AsShippedPassesItsChecks) {
  const auto result = run_quietly(load_example("two-disks"), "disks_example");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  ASSERT_FALSE(result.summary["checks"].empty());
  for (const auto& check : result.summary["checks"]) EXPECT_TRUE(check["pass"].get<bool>()) << check.dump();
}

}  // namespace two_disks_tests
