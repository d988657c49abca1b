// Numerical failures stop the run cleanly: exit code 3, a message naming step, time and particle,
// and the last good output left in place.
#include "test_support.hpp"

#include "matpoint/core/errors.hpp"

#include <gtest/gtest.h>

namespace {

using namespace matpoint;

TEST(Failures, ParticleLeavingTheGridStopsTheRunWithExitCode3) {
  Spec spec = test::load_example("two-disks");
  spec.bodies[0].velocity = {-50.0, 0, 0};  // flies out through the x- face, which has no condition
  spec.checks.clear();
  const auto result = test::run_quietly(spec, "leaves_grid");
  EXPECT_EQ(result.exit_code, 3);
  EXPECT_NE(result.message.find("step"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("time"), std::string::npos);
  EXPECT_NE(result.message.find("particle"), std::string::npos);
  EXPECT_EQ(result.summary["status"], "numerical_failure");
  EXPECT_LT(result.summary["time_reached"].get<double>(), spec.solver.end_time);
  ASSERT_FALSE(result.history.samples.empty());
}

TEST(Failures, ParticleOutrunningItsStencilStopsTheRun) {
  Spec spec = test::load_example("two-disks");  // cell 0.05, dt 1e-3: 60 per unit time crosses 1.2 cells a step
  spec.bodies[0].velocity = {60.0, 0, 0};
  spec.checks.clear();
  const auto result = test::run_quietly(spec, "too_fast");
  EXPECT_EQ(result.exit_code, 3);
  EXPECT_NE(result.message.find("more than one cell"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("step 1,"), std::string::npos) << "caught in the first step: " << result.message;
}

TEST(Failures, BodyWithoutParticlesIsAnInputError) {
  Spec spec = test::load_example("two-disks");
  spec.bodies[0].radius = 0.001;  // smaller than the sub-cell spacing: holds no particle centre
  spec.bodies[0].center = {0.2, 0.2, 0};  // a node, far from any sub-cell centre
  try {
    test::run_quietly(spec, "empty_body");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    ASSERT_EQ(e.issues().size(), 1u);
    EXPECT_EQ(e.issues()[0].path, "bodies[0].shape");
  }
}

}  // namespace
