// The manufactured solutions of Gong 2015 §4.5-4.7 (extraction §7.3, §7.4). Each test names the
// order the source claims; the pass rule is that order with the one margin kOrderMargin = 0.2
// ("expected 2, pass >= 1.8"; "expected 1, pass 0.8 .. 1.2"). The orders are least-squares slopes
// of log(error) against log(h) over h = 1/8 .. 1/64 with 2 particles per cell per direction,
// errors at T = 0.02 (one period) by particle quadrature (extraction A8), Gong's walls (A24).
// Particle velocities are reported but not asserted for linear MPM and IMPM: their order on
// 1/8 .. 1/64 (1.64, the extraction's reproduction too) is below Gong's "second order", an open
// difference in docs/verification.md.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "matpoint/analysis/verification.hpp"

namespace {

using namespace matpoint;

std::vector<MmsResult> sweep(int dim, ShapeKind shape, double amplitude, const std::vector<int>& cells) {
  MmsOptions o;
  o.dim = dim;
  o.shape = shape;
  o.amplitude = amplitude;
  std::vector<MmsResult> runs;
  for (int n : cells) runs.push_back(run_mms(o, n));
  return runs;
}

double order(const std::vector<MmsResult>& runs, const std::string& quantity) {
  std::vector<double> h, e;
  for (const auto& r : runs) {
    EXPECT_TRUE(r.finished) << r.message;
    h.push_back(r.h);
    e.push_back(mms_quantity(r, quantity));
  }
  return least_squares_order(h, e);
}

std::string table(const std::vector<MmsResult>& runs) {
  std::string s;
  for (const auto& r : runs)
    s += "h=1/" + std::to_string(r.cells) + " u " + std::to_string(r.displacement) + " s " +
         std::to_string(r.stress) + " rho " + std::to_string(r.density) + " v " + std::to_string(r.velocity) +
         "\n";
  return s;
}

// Extraction U5: the body forces (4.39) and (4.46) balance rho0 A - dP/dX (central differences).
TEST(ManufacturedSolution, BodyForceBalancesMomentum) {
  const ManufacturedSolution m{0.1};
  const double lambda = m.lambda(), mu = m.mu();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (int k = 0; k < 20; ++k) {
    const Vec<2> X(u(rng), u(rng));
    const double t = 0.02 * u(rng);
    auto P11 = [&](double x) {
      const double f1 = m.F(x, t), f2 = m.F(X[1], t);
      return lambda / f1 * std::log(f1 * f2) + mu * (f1 - 1.0 / f1);
    };
    const double d = 1e-5;
    const double dP = (P11(X[0] + d) - P11(X[0] - d)) / (2 * d);
    const double c = m.c(), pi = std::numbers::pi;
    const double A = -m.G * c * c * pi * pi * std::sin(pi * X[0]) * std::sin(c * pi * t);
    const double expected = A - dP / m.rho0;
    EXPECT_NEAR(m.body_force<2>(X, t)[0], expected, 1e-6 * (std::abs(expected) + 1.0));
  }
  // Lame constants of the corrected relation (extraction A3): 5.769231e6 and 3.846154e6 Pa.
  EXPECT_NEAR(lambda, 5.769231e6, 1.0);
  EXPECT_NEAR(mu, 3.846154e6, 1.0);
}

// Extraction U9: T / dt = 5 N_e at dt = 0.4 h / c.
TEST(ManufacturedSolution, StepCountIsFiveTimesTheCells) {
  MmsOptions o;
  for (int n : {8, 16, 64}) EXPECT_EQ(run_mms(o, n).steps, 5L * n);
}

// T5 (Gong Fig. 4.7, "appears to be second order"): expected 2, slope >= 1.8 in displacement,
// stress and density.
TEST(MmsVerification, Linear1DSmallAmplitudeConvergesAtSecondOrder) {
  const auto runs = sweep(1, ShapeKind::Linear, 1e-4, {8, 16, 32, 64});
  EXPECT_GE(order(runs, "displacement"), 2.0 - kOrderMargin) << table(runs);
  EXPECT_GE(order(runs, "stress"), 2.0 - kOrderMargin) << table(runs);
  EXPECT_GE(order(runs, "density"), 2.0 - kOrderMargin) << table(runs);
}

// Gong ch. 8: IMPM raises MPM "from zeroth order"; Table 4.2: the mass-weighted (Shepard) mapping
// is first order once particles are unevenly spaced. At G = 1e-4 the errors of linear MPM stall
// below h = 1/128 at a level proportional to G^2 (a relative error O(G) that refinement does not
// remove): the stress order over 1/256 .. 1/1024 is below 0.5 with finite errors.
TEST(MmsVerification, Linear1DSmallAmplitudeStallsOnFineMeshes) {
  const auto runs = sweep(1, ShapeKind::Linear, 1e-4, {256, 512, 1024});
  EXPECT_LT(order(runs, "stress"), kNoConvergenceOrder) << table(runs);
  EXPECT_GT(runs.back().stress, 0.5 * runs.front().stress) << table(runs);
  const auto ten_times_smaller = sweep(1, ShapeKind::Linear, 1e-5, {1024});  // the floor scales as G^2
  EXPECT_NEAR(ten_times_smaller[0].stress / runs.back().stress, 0.01, 0.002) << table(runs);
}

// Extraction §8 ("two traps", 1) and A9: at T/4 the exact strain is not zero and the particle
// stress of linear elements is first order (cellwise-constant strain): expected 1, pass 0.8 .. 1.2,
// displacement and velocity still expected 2.
TEST(MmsVerification, Linear1DQuarterPeriodStressIsFirstOrder) {
  MmsOptions o;
  o.end_time = 0.005;
  std::vector<MmsResult> runs;
  for (int n : {8, 16, 32, 64}) runs.push_back(run_mms(o, n));
  EXPECT_NEAR(order(runs, "stress"), 1.0, kOrderMargin) << table(runs);
  EXPECT_GE(order(runs, "displacement"), 2.0 - kOrderMargin) << table(runs);
  EXPECT_GE(order(runs, "velocity"), 2.0 - kOrderMargin) << table(runs);
}

// The pass rules of order_check: "does not converge" passes on a det F <= 0 stop or on finite
// errors that do not fall, never on NaN errors or another guard's stop; a first-order claim
// fails on a second-order result.
TEST(MmsVerification, OrderChecksNeedTheSpecificFailure) {
  VerificationCase c = make_case("mms-1d", ShapeKind::Linear, 0.1, false);
  const OrderExpectation no_convergence{"stress", OrderClaim::NoConvergence, 0.0, "test"};
  auto run = [](int cells, double stress, bool finished = true, bool inverted = false) {
    MmsResult r;
    r.cells = cells;
    r.h = 1.0 / cells;
    r.stress = stress;
    r.finished = finished;
    r.inverted = inverted;
    return r;
  };
  const double nan = std::nan("");
  EXPECT_TRUE(order_check(c, no_convergence, {run(8, 1e6), run(16, 1e6), run(32, 1.2e6)})->pass);
  EXPECT_FALSE(order_check(c, no_convergence, {run(8, 1e6), run(16, 2.5e5), run(32, 6e4)})->pass);
  EXPECT_FALSE(order_check(c, no_convergence, {run(8, nan), run(16, nan), run(32, nan)})->pass);
  EXPECT_FALSE(order_check(c, no_convergence, {run(8, 1e6), run(16, 1e6), run(32, nan, false)})->pass);
  EXPECT_TRUE(order_check(c, no_convergence, {run(8, 1e6), run(16, 1e6), run(32, nan, false, true)})->pass);
  const OrderExpectation first{"stress", OrderClaim::Near, 1.0, "test"};
  EXPECT_TRUE(order_check(c, first, {run(8, 8.0), run(16, 4.0), run(32, 2.0)})->pass);
  EXPECT_FALSE(order_check(c, first, {run(8, 16.0), run(16, 4.0), run(32, 1.0)})->pass);
  const OrderExpectation second{"stress", OrderClaim::AtLeast, 2.0, "test"};
  EXPECT_FALSE(order_check(c, second, {run(8, 8.0), run(16, 4.0), run(32, 2.0)})->pass);
  EXPECT_FALSE(order_check(c, second, {run(8, 16.0), run(16, 4.0), run(32, nan, false)})->pass);
}

// T6 (Gong Fig. 4.8, "does not converge"): stress slope < 0.5 and E(1/64) > 0.5 E(1/8)
// (proto -0.15; 1.24e6 vs 9.73e5 Pa): particles crossing cells make the linear-basis force
// inconsistent, an O(1) error that refinement does not remove.
TEST(MmsVerification, Linear1DLargeAmplitudeDoesNotConverge) {
  const auto runs = sweep(1, ShapeKind::Linear, 0.1, {8, 16, 32, 64});
  EXPECT_LT(order(runs, "stress"), 0.5) << table(runs);
  EXPECT_GT(runs.back().stress, 0.5 * runs.front().stress) << table(runs);
}

// Extraction A29 / §8: linear MPM at G = 0.1 with 2 ppc reaches det F <= 0 from h = 1/128 on; the
// extraction's independent numpy reproduction stops at step 405 of 640 (its §8). The run must stop
// cleanly on the det F guard (the command line's exit 3), never crash or return NaN as if finished.
TEST(MmsVerification, Linear1DLargeAmplitudeReportsDivergenceCleanly) {
  MmsOptions o;
  o.amplitude = 0.1;
  const auto r = run_mms(o, 128);
  EXPECT_FALSE(r.finished);
  EXPECT_EQ(r.steps, 405);  // extraction §8's reproduction: det F <= 0 at step 405 of 640
  EXPECT_TRUE(r.inverted);
  EXPECT_NE(r.message.find("det F"), std::string::npos) << r.message;
}

// T12 (Gong Fig. 6.1, CPDI on coarse meshes "appears second order for all the field variables"):
// expected 2, slope >= 1.8 in stress, density and displacement over h = 1/8 .. 1/64. Integrating
// the basis over the particle domain removes the cell-crossing error of T6.
TEST(MmsVerification, Cpdi1LargeAmplitudeConvergesOnCoarseMeshes) {
  const auto runs = sweep(1, ShapeKind::CPDI1, 0.1, {8, 16, 32, 64});
  EXPECT_GE(order(runs, "displacement"), 2.0 - kOrderMargin) << table(runs);
  EXPECT_GE(order(runs, "stress"), 2.0 - kOrderMargin) << table(runs);
  EXPECT_GE(order(runs, "density"), 2.0 - kOrderMargin) << table(runs);
}

// T9 (Gong Fig. 4.9): displacement expected 2. Stress and density: Gong writes "between order 1
// and order 2"; at T = one period the exact strain vanishes and with it the O(h) strain error of
// linear elements (extraction §8), so expected 2 as in 1-D (the difference is in
// docs/verification.md). h = 1/8 .. 1/32 keeps the CI time short.
TEST(MmsVerification, Linear2DSmallAmplitudeConverges) {
  const auto runs = sweep(2, ShapeKind::Linear, 1e-4, {8, 16, 32});
  EXPECT_GE(order(runs, "displacement"), 2.0 - kOrderMargin) << table(runs);
  EXPECT_GE(order(runs, "stress"), 2.0 - kOrderMargin) << table(runs);
  EXPECT_GE(order(runs, "density"), 2.0 - kOrderMargin) << table(runs);
}

// T10 (Gong Fig. 4.10, G = 0.05: "MPM does not converge"): stress slope < 0.5 and the finest
// error above half the coarsest, all finite.
TEST(MmsVerification, Linear2DLargeAmplitudeDoesNotConverge) {
  const auto runs = sweep(2, ShapeKind::Linear, 0.05, {8, 16, 32});
  EXPECT_LT(order(runs, "stress"), kNoConvergenceOrder) << table(runs);
  EXPECT_GT(runs.back().stress, 0.5 * runs.front().stress) << table(runs);
}

// B-splines at G = 1e-4 (2 ppc): second order as Gong's Fig. 4.7 (small strain, no cell crossing,
// an O(h^2) interpolant): expected 2, slope >= 1.8 in stress, density and displacement on
// 1/8 .. 1/64, and in particle velocity past its pre-asymptotic meshes (1/64 .. 1/512).
TEST(MmsVerification, BSplinesSmallAmplitudeConvergeAtSecondOrder) {
  for (const auto shape : {ShapeKind::BSpline2, ShapeKind::BSpline3}) {
    const auto runs = sweep(1, shape, 1e-4, {8, 16, 32, 64});
    EXPECT_GE(order(runs, "displacement"), 2.0 - kOrderMargin) << shape_name(shape) << "\n" << table(runs);
    EXPECT_GE(order(runs, "stress"), 2.0 - kOrderMargin) << shape_name(shape) << "\n" << table(runs);
    EXPECT_GE(order(runs, "density"), 2.0 - kOrderMargin) << shape_name(shape) << "\n" << table(runs);
  }
  const auto fine = sweep(1, ShapeKind::BSpline2, 1e-4, {64, 128, 256, 512});
  EXPECT_GE(order(fine, "velocity"), 2.0 - kOrderMargin) << table(fine);
}

// B-splines at G = 0.1: point quadrature stalls (Steffen, Kirby & Berzins 2008),
// so no slope is asserted: finite results with F > 0 down to h = 1/1024, and the stress error
// falls at least 3x from h = 1/8 to 1/32 (measured 4.2x).
TEST(MmsVerification, BSplinesLargeAmplitudeStayFiniteAndFirstImprove) {
  for (const auto shape : {ShapeKind::BSpline2, ShapeKind::BSpline3}) {
    const auto runs = sweep(1, shape, 0.1, {8, 32, 1024});
    for (const auto& r : runs) {
      EXPECT_TRUE(r.finished) << shape_name(shape) << ": " << r.message;
      EXPECT_GT(r.min_jacobian, 0.0) << shape_name(shape);
      EXPECT_TRUE(std::isfinite(r.stress)) << shape_name(shape);
    }
    EXPECT_GE(runs[0].stress / runs[1].stress, 3.0) << shape_name(shape) << "\n" << table(runs);
  }
}

// Methods that integrate over the particle domain: second order at G = 0.1 as CPDI in Gong's
// Fig. 6.1 (expected 2, slope >= 1.8 on h = 1/8 .. 1/64).
TEST(MmsVerification, DomainIntegratedBasesLargeAmplitudeConverge) {
  for (ShapeKind shape : {ShapeKind::CPDI2, ShapeKind::B2CPDI}) {
    const auto runs = sweep(1, shape, 0.1, {8, 16, 32, 64});
    EXPECT_GE(order(runs, "displacement"), 2.0 - kOrderMargin) << shape_name(shape) << "\n" << table(runs);
    EXPECT_GE(order(runs, "stress"), 2.0 - kOrderMargin) << shape_name(shape) << "\n" << table(runs);
    EXPECT_GE(order(runs, "density"), 2.0 - kOrderMargin) << shape_name(shape) << "\n" << table(runs);
  }
}

// T13 (Gong Fig. 6.2: on finer meshes "the convergence rate of CPDI drops"; ch. 8: improved CPDI
// raises CPDI "from first order to second order for fine meshes"): expected 1, slope 0.8 .. 1.2
// over h = 1/256 .. 1/2048. The errors also match the extraction's independent reproduction (§8:
// 7.70e2, 3.66e2, 2.05e2, 1.29e2 Pa) to 1 %.
TEST(MmsVerification, Cpdi1LargeAmplitudeRateDropsOnFineMeshes) {
  const auto runs = sweep(1, ShapeKind::CPDI1, 0.1, {256, 512, 1024, 2048});
  EXPECT_NEAR(order(runs, "stress"), 1.0, kOrderMargin) << table(runs);
  const double reproduction[] = {7.70e2, 3.66e2, 2.05e2, 1.29e2};
  for (std::size_t k = 0; k < runs.size(); ++k)
    EXPECT_NEAR(runs[k].stress, reproduction[k], 0.01 * reproduction[k]) << table(runs);
}

}  // namespace
