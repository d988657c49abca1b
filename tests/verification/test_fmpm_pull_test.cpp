// examples/fmpm-pull-test: Nairn 2026 §3.1 (Fig. 3). A 20 x 4 bar stretched by moving walls at both
// ends, whose exact particle velocities never change. Error = time average over all steps of the
// rms particle velocity change, in % of the end velocity (history: rms_velocity_change).
// Paper, CPDI with wall depth d = 1 cell: the new (incremental) and old (combined) boundary
// methods agree for k <= 2 and part for k > 2; the combined method grows with k and exceeds FLIP
// for k > 6; the new method stops improving near k = 8, where it is 400 times below FLIP (asserted:
// at least 100, since the paper's regime is unknown). B2CPDI (d = 1.5 cells): FMPM(8) 4400 times
// below FLIP (asserted: at least 1000). FLIP is run the same way in each test, so the ratios need
// no value from an earlier run.
// The paper does not state the strain rate or density; the FMPM error (not FLIP's) scales with the
// end velocity over the wave speed, V_end / c (README.md of the example). The shipped input has
// V_end / c = 0.1: CPDI 241 x, B2CPDI 957 x at k = 8. At V_end / c = 0.025 (density 0.0625 instead
// of 1) both of the paper's ratios come out together — CPDI 440 x (paper 400), B2CPDI 4491 x
// (paper 4400) — so the B2CPDI bound is asserted there, at k = 8. That regime was chosen to match
// the paper: a calibration (docs/verification.md, open differences).
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;

constexpr double kEndVelocity = 10 * 0.00866;

/// The end velocity over the wave speed sqrt(E / rho) is 0.1 sqrt(rho) (E = 0.75, V_end = 0.0866).
constexpr double kPaperRegimeDensity = 0.0625;  // V_end / c = 0.025

double error_percent(ShapeKind shape, double depth, VelocityTransfer transfer, int order,
                     FmpmBoundaryMethod method = FmpmBoundaryMethod::Incremental, double density = 1.0) {
  Spec spec = load_example("fmpm-pull-test");
  spec.materials[0].density = density;
  spec.solver.shape = shape;
  spec.solver.transfer = transfer;
  spec.solver.position_alpha = 0.5;
  spec.solver.fmpm = FmpmSpec{};
  spec.solver.fmpm.order = order;
  spec.solver.fmpm.boundary_method = method;
  for (auto& wall : spec.conditions) wall.depth = depth;
  spec.output.every_steps = 1;
  spec.checks = {{"error", "mean_rms_velocity_change", 0.0, 1.0, "test"}};
  const auto result = run_quietly(spec, "pull_test");
  EXPECT_EQ(result.exit_code, 0) << result.message;
  return 100.0 * measured(result, "mean_rms_velocity_change") / kEndVelocity;
}

TEST(FmpmPullTest, CpdiNewMethodBeatsFlipAndCombinedMethod) {
  const double h = 0.25;
  const double flip = error_percent(ShapeKind::CPDI1, h, VelocityTransfer::FLIP, 1);
  auto fmpm = [&](int k, FmpmBoundaryMethod m = FmpmBoundaryMethod::Incremental) {
    return error_percent(ShapeKind::CPDI1, h, VelocityTransfer::FMPM, k, m);
  };
  const auto combined = FmpmBoundaryMethod::Combined;
  EXPECT_EQ(fmpm(2), fmpm(2, combined)) << "identical for k <= 2";
  const double new3 = fmpm(3), old3 = fmpm(3, combined);
  EXPECT_GT(std::abs(new3 - old3), 0.1 * new3) << "they part at k = 3";
  const double old6 = fmpm(6, combined), old8 = fmpm(8, combined);
  EXPECT_LT(old6, flip);
  EXPECT_GT(old8, flip) << "the combined method exceeds FLIP for k > 6";
  EXPECT_GT(old8, old6) << "and grows with k";
  const double new8 = fmpm(8), new12 = fmpm(12);
  EXPECT_GE(flip / new8, 100.0) << "FLIP " << flip << " %, FMPM(8) " << new8 << " %";
  EXPECT_LT(new3, fmpm(2));
  EXPECT_GT(new12, 0.7 * new8) << "the new method stops improving near k = 8";
}

TEST(FmpmPullTest, B2CpdiIsThousandsOfTimesBelowFlip) {
  const double d = 0.375;  // 1.5 cells: the reach of the quadratic B-spline
  const double flip =
      error_percent(ShapeKind::B2CPDI, d, VelocityTransfer::FLIP, 1, {}, kPaperRegimeDensity);
  const double fmpm8 =
      error_percent(ShapeKind::B2CPDI, d, VelocityTransfer::FMPM, 8, {}, kPaperRegimeDensity);
  EXPECT_GE(flip / fmpm8, 1000.0) << "FLIP " << flip << " %, FMPM(8) " << fmpm8 << " %";
}

}  // namespace
