// examples/fmpm-two-blocks (Nairn 2026 §3.4), shortened to the impact (0.1 ms) for CI:
//  - dynamic FMPM(20) with a loose limit stops every loop at order 2, so it reproduces FMPM(2)
//    exactly (same arithmetic, bit for bit). Nairn: "limit >~ 0.1". Here "changes" at 0.1 does;
//    "means" at 0.1 runs a few loops to order 3 during the impact (average order 2.014 over this
//    test) and still one in 256 at 0.3 (2.0039 since every reached node is active and output
//    times are hit exactly): an open difference in docs/verification.md, not tested here with a
//    limit of our own choosing;
//  - the average order reached grows as the limit shrinks (Nairn Fig. 14);
//  - without boundary conditions FMPM conserves linear momentum to round-off.
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;

Spec blocks(FmpmMeasure measure, double limit, int order = 20) {
  Spec spec = load_example("fmpm-two-blocks");
  spec.solver.end_time = 1e-4;
  spec.solver.fmpm = FmpmSpec{};
  spec.solver.fmpm.order = order;
  spec.solver.fmpm.measure = measure;
  spec.solver.fmpm.limit = limit;
  return spec;
}

void expect_fmpm2(FmpmMeasure measure, double limit) {
  const auto dynamic = run_quietly(blocks(measure, limit), "blocks_dynamic");
  const auto fixed = run_quietly(blocks(FmpmMeasure::None, 0.0, 2), "blocks_fmpm2");
  ASSERT_EQ(dynamic.exit_code, 0) << dynamic.message;
  ASSERT_EQ(fixed.exit_code, 0) << fixed.message;
  EXPECT_EQ(dynamic.summary["fmpm_average_order"].get<double>(), 2.0);
  const auto& a = dynamic.history.samples;
  const auto& b = fixed.history.samples;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].kinetic_energy, b[k].kinetic_energy) << "output " << k;
    EXPECT_EQ(a[k].strain_energy, b[k].strain_energy) << "output " << k;
  }
}

TEST(FmpmTwoBlocks, LooseDynamicLimitReproducesFmpm2Exactly) {
  expect_fmpm2(FmpmMeasure::Changes, 0.1);  // the paper's value
}

TEST(FmpmTwoBlocks, AverageOrderGrowsAsTheLimitShrinks) {
  for (const auto measure : {FmpmMeasure::Means, FmpmMeasure::Changes}) {
    double previous = 0.0;
    for (double limit : {0.1, 0.01, 0.001, 1e-4}) {
      const auto result = run_quietly(blocks(measure, limit), "blocks_order");
      ASSERT_EQ(result.exit_code, 0) << result.message;
      const double order = result.summary["fmpm_average_order"].get<double>();
      EXPECT_GE(order, previous) << "limit " << limit;
      EXPECT_LE(order, 20.0);
      previous = order;
    }
    EXPECT_GT(previous, 2.0) << "a tight limit needs more than two terms after the impact";
  }
}

TEST(FmpmTwoBlocks, ConservesLinearMomentum) {
  const auto result = run_quietly(blocks(FmpmMeasure::None, 0.0, 8), "blocks_momentum");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  for (const auto& check : result.summary["checks"])
    if (check["measure"] == "max_relative_momentum_error") {
      EXPECT_TRUE(check["pass"].get<bool>()) << check.dump();
    }
}

}  // namespace
