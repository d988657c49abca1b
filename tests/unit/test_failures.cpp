// Numerical failures stop the run cleanly: exit code 3, a message naming step, time and particle,
// and the last good output left in place.
#include <gtest/gtest.h>

#include <limits>

#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/courant_limits.hpp"
#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"
#include "test_support.hpp"

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
  Spec spec =
      test::load_example("two-disks");  // cell 0.05, dt 1e-3: 60 per unit time crosses 1.2 cells a step
  spec.bodies[0].velocity = {60.0, 0, 0};
  spec.checks.clear();
  const auto result = test::run_quietly(spec, "too_fast");
  EXPECT_EQ(result.exit_code, 3);
  EXPECT_NE(result.message.find("more than one cell"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("step 1,"), std::string::npos)
      << "caught in the first step: " << result.message;
}

// A 1-D bar compressed at a rate of 1500 /s (V = 750 - 1500 x, at rest at its centre x = 0.5):
// with F <- (I + L dt) F and dt = 1e-3, det F = 1 - 1.5 = -0.5 after the first strain update.
constexpr const char* kCrushedBar = R"({
  "grid": {"dim": 1, "min": [0], "max": [1], "cell_size": 0.1},
  "materials": [{"name": "m", "model": "neo_hookean", "density": 1000, "E": 1e6, "nu": 0.3}],
  "bodies": [{"material": "m", "shape": {"type": "box", "min": [0.3], "max": [0.7]},
              "velocity": [750], "velocity_gradient": [[-1500]]}],
  "solver": {"scheme": "usf", "basis": "linear", "deformation_update": "linear", "dt": 1e-3, "end_time": 0.01},
  "output": {"plots": false}})";

// The linear basis maps the bar's linear velocity field exactly: det F = 1 - 1500 dt = -0.5.
TEST(Failures, InvertedParticleStopsTheRunNamingDetF) {
  const auto result = test::run_quietly(parse_spec(kCrushedBar), "inverted");
  EXPECT_EQ(result.exit_code, 3);
  EXPECT_NE(result.message.find("det F = -0.5"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("step 1, time 0.001"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("particle"), std::string::npos) << result.message;
  EXPECT_EQ(result.summary["status"], "numerical_failure");
  EXPECT_EQ(result.summary["steps"], 0) << "the failed step is not counted";
  ASSERT_EQ(result.history.samples.size(), 1u) << "the last good state (time 0) is kept";
}

/// The message of the second step of two-disks when `damage` hit the particles after the first.
/// MUSL (the example's) moves the particles first, USF updates the strains first.
template <class Damage>
std::string failure_after(UpdateScheme scheme, Damage damage) {
  Spec spec = test::load_example("two-disks");
  spec.solver.scheme = scheme;
  auto sim = build_simulation<2>(spec);
  ExplicitStepper<2, TensorStencils<2, QuadraticBSplineBasis>> stepper(sim);
  stepper.step(1e-3);
  damage(sim.particles);
  try {
    stepper.step(1e-3);
  } catch (const NumericalFailure& failure) {
    EXPECT_EQ(failure.step(), 2);
    EXPECT_DOUBLE_EQ(failure.time(), 2e-3);
    return failure.what();
  }
  return "no failure";
}

TEST(Failures, NonFiniteVelocityIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::string message =
      failure_after(UpdateScheme::MUSL, [&](ParticleSet<2>& ps) { ps.v[7][1] = nan; });
  EXPECT_NE(message.find("non-finite velocity"), std::string::npos) << message;
}

TEST(Failures, NonFiniteStressIsNamed) {
  // F_xx = 1e306: det F is finite and positive, but lambda tr(eps) overflows.
  const std::string message =
      failure_after(UpdateScheme::USF, [&](ParticleSet<2>& ps) { ps.F[3](0, 0) = 1e306; });
  EXPECT_NE(message.find("non-finite stress"), std::string::npos) << message;
}

TEST(Failures, NonFiniteDeformationGradientIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::string message =
      failure_after(UpdateScheme::USF, [&](ParticleSet<2>& ps) { ps.F[3](1, 0) = nan; });
  EXPECT_NE(message.find("nan (needs > 0)"), std::string::npos) << message;  // glibc may print -nan
}

// A CPDI1 particle whose domain has grown past the grid (a stretch of 200 along x puts the corners of
// its 0.025-wide domain 2.5 away, 30 cells beyond the unit grid of two-disks) stops the step that
// would evaluate it,
// naming the particle, its F and the grid; the folded basis alone would have gone on with
// extrapolated weights (adcd7b7 found one at 1e10 cells in a diverging stability scan).
TEST(Failures, DomainCornerFarOutsideTheGridIsNamed) {
  Spec spec = test::load_example("two-disks");
  spec.solver.shape = ShapeKind::CPDI1;
  auto sim = build_simulation<2>(spec);
  ExplicitStepper<2, CpdiStencils<2, HatKernel, CpdiDomain::Parallelogram>> stepper(sim);
  stepper.step(1e-3);
  sim.particles.F[5](0, 0) = 200.0;
  std::string message = "no failure";
  try {
    stepper.step(1e-3);
  } catch (const NumericalFailure& failure) {
    EXPECT_EQ(failure.step(), 2);
    message = failure.what();
  }
  EXPECT_NE(message.find("domain corner more than one cell outside the grid"), std::string::npos) << message;
  EXPECT_NE(message.find("particle " + std::to_string(sim.particles.id[5])), std::string::npos) << message;
  EXPECT_NE(message.find("det F = 200"), std::string::npos) << message;
}

TEST(Failures, CourantAboveTheMeasuredLimitWarnsInTheSummary) {
  // The measured limits (courant_limits.hpp) come from 1-D benchmarks; above them a run may still
  // be stable, so the run goes on with a warning, and the guards above stop it if it blows up.
  Spec spec = test::load_example("vibrating-bar-1d");
  spec.solver.dt.reset();
  spec.solver.courant = 0.8;  // FLIP's measured limit is 0.709
  spec.solver.end_time = 0.01 * spec.solver.end_time;
  spec.checks.clear();
  const auto result = test::run_quietly(spec, "courant_warning");
  ASSERT_EQ(result.summary["warnings"].size(), 1u);
  EXPECT_NE(result.summary["warnings"][0].get<std::string>().find("0.709"), std::string::npos);
  EXPECT_EQ(courant_warning(spec.solver), result.summary["warnings"][0].get<std::string>());
}

TEST(Failures, BodyWithoutParticlesIsAnInputError) {
  Spec spec = test::load_example("two-disks");
  spec.bodies[0].radius = 0.001;          // smaller than the sub-cell spacing: holds no particle centre
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
