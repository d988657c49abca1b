// The manufactured solutions of Gong 2015 §4.5-4.7 (extraction §7.3, §7.4) and the acceptance
// thresholds of the extraction's §10: each test names its expected value and source. The orders
// are least-squares slopes of log(error) against log(h) over h = 1/8 .. 1/64 with 2 particles per
// cell per direction, errors at T = 0.02 (one period) by particle quadrature (extraction A8).
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

// T5 (Gong Fig. 4.7, "appears to be second order"): slope >= 1.8 in displacement, stress and
// density (proto 2.02 / 2.01 / 2.01), >= 1.4 in particle velocity (proto 1.64). The threshold 1.8
// leaves 0.2 for the pre-asymptotic first mesh of a second-order method.
TEST(MmsVerification, Linear1DSmallAmplitudeConvergesAtSecondOrder) {
  const auto runs = sweep(1, ShapeKind::Linear, 1e-4, {8, 16, 32, 64});
  EXPECT_GE(order(runs, "displacement"), 1.8) << table(runs);
  EXPECT_GE(order(runs, "stress"), 1.8) << table(runs);
  EXPECT_GE(order(runs, "density"), 1.8) << table(runs);
  EXPECT_GE(order(runs, "velocity"), 1.4) << table(runs);
}

// T6 (Gong Fig. 4.8, "does not converge"): stress slope < 0.5 and E(1/64) > 0.5 E(1/8)
// (proto -0.15; 1.24e6 vs 9.73e5 Pa): particles crossing cells make the linear-basis force
// inconsistent, an O(1) error that refinement does not remove.
TEST(MmsVerification, Linear1DLargeAmplitudeDoesNotConverge) {
  const auto runs = sweep(1, ShapeKind::Linear, 0.1, {8, 16, 32, 64});
  EXPECT_LT(order(runs, "stress"), 0.5) << table(runs);
  EXPECT_GT(runs.back().stress, 0.5 * runs.front().stress) << table(runs);
}

// Extraction A29 / §8: linear MPM at G = 0.1 with 2 ppc reaches det F <= 0 from h = 1/128 on
// (proto: step 405 of 640). The run must stop cleanly with the guard's message (the command
// line's exit 3), never crash or return NaN errors as if finished.
TEST(MmsVerification, Linear1DLargeAmplitudeReportsDivergenceCleanly) {
  MmsOptions o;
  o.amplitude = 0.1;
  const auto r = run_mms(o, 128);
  EXPECT_FALSE(r.finished);
  EXPECT_EQ(r.steps, 405);  // the extraction's proto: det F <= 0 at step 405 of 640
  EXPECT_NE(r.message.find("det F"), std::string::npos) << r.message;
}

// T12 (Gong Fig. 6.1, CPDI on coarse meshes "appears second order for all the field variables"):
// slope >= 1.7 in stress, density and displacement over h = 1/8 .. 1/64 (proto local 1.93-2.06).
// Integrating the basis over the particle domain removes the cell-crossing error of T6.
TEST(MmsVerification, Cpdi1LargeAmplitudeConvergesOnCoarseMeshes) {
  const auto runs = sweep(1, ShapeKind::CPDI1, 0.1, {8, 16, 32, 64});
  EXPECT_GE(order(runs, "displacement"), 1.7) << table(runs);
  EXPECT_GE(order(runs, "stress"), 1.7) << table(runs);
  EXPECT_GE(order(runs, "density"), 1.7) << table(runs);
}

// T9 (Gong Fig. 4.9): displacement slope >= 1.8; stress, density, velocity >= 1.0 ("between
// order 1 and order 2"; proto 2.0 / 2.0 / 1.64). h = 1/8 .. 1/32 keeps the CI time short.
TEST(MmsVerification, Linear2DSmallAmplitudeConverges) {
  const auto runs = sweep(2, ShapeKind::Linear, 1e-4, {8, 16, 32});
  EXPECT_GE(order(runs, "displacement"), 1.8) << table(runs);
  EXPECT_GE(order(runs, "stress"), 1.0) << table(runs);
  EXPECT_GE(order(runs, "density"), 1.0) << table(runs);
  EXPECT_GE(order(runs, "velocity"), 1.0) << table(runs);
}

// T10 (Gong Fig. 4.10, G = 0.05: "MPM does not converge"): stress slope < 0.5 (proto -0.14).
TEST(MmsVerification, Linear2DLargeAmplitudeDoesNotConverge) {
  const auto runs = sweep(2, ShapeKind::Linear, 0.05, {8, 16, 32});
  EXPECT_LT(order(runs, "stress"), 0.5) << table(runs);
}

// Issue 3 item 4, B-splines at G = 1e-4 (2 ppc): slope >= 1.8 in stress, density, displacement
// and >= 1.2 in particle velocity (measured 2.01 / 2.01 / 2.01 / 1.61).
TEST(MmsVerification, BSplinesSmallAmplitudeConvergeAtSecondOrder) {
  for (const auto shape : {ShapeKind::BSpline2, ShapeKind::BSpline3}) {  // measured 2.0 / 2.0 / 2.0 / 1.6, 1.5
    const auto runs = sweep(1, shape, 1e-4, {8, 16, 32, 64});
    EXPECT_GE(order(runs, "displacement"), 1.8) << shape_name(shape) << "\n" << table(runs);
    EXPECT_GE(order(runs, "stress"), 1.8) << shape_name(shape) << "\n" << table(runs);
    EXPECT_GE(order(runs, "density"), 1.8) << shape_name(shape) << "\n" << table(runs);
    EXPECT_GE(order(runs, "velocity"), 1.2) << shape_name(shape) << "\n" << table(runs);
  }
}

// Issue 3 item 4, B-splines at G = 0.1: point quadrature stalls (Steffen, Kirby & Berzins 2008),
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

// Issue 3 item 4: methods that integrate over the particle domain keep slope >= 1.7 at G = 0.1 on
// h = 1/8 .. 1/64 (measured CPDI2 1.97, B2CPDI 1.96 in stress).
TEST(MmsVerification, DomainIntegratedBasesLargeAmplitudeConverge) {
  for (ShapeKind shape : {ShapeKind::CPDI2, ShapeKind::B2CPDI}) {
    const auto runs = sweep(1, shape, 0.1, {8, 16, 32, 64});
    EXPECT_GE(order(runs, "displacement"), 1.7) << shape_name(shape) << "\n" << table(runs);
    EXPECT_GE(order(runs, "stress"), 1.7) << shape_name(shape) << "\n" << table(runs);
    EXPECT_GE(order(runs, "density"), 1.7) << shape_name(shape) << "\n" << table(runs);
  }
}

// T13 (Gong Fig. 6.2: on finer meshes "the convergence rate of CPDI drops"): stress slope <= 1.3
// over h = 1/256 .. 1/2048 (proto local 1.07, 0.84, 0.67; measured the same, errors 770, 366,
// 205, 129 Pa against the proto's 7.70e2, 3.66e2, 2.05e2, 1.29e2).
TEST(MmsVerification, Cpdi1LargeAmplitudeRateDropsOnFineMeshes) {
  const auto runs = sweep(1, ShapeKind::CPDI1, 0.1, {256, 512, 1024, 2048});
  EXPECT_LE(order(runs, "stress"), 1.3) << table(runs);
  EXPECT_GT(order(runs, "stress"), 0.3) << table(runs);  // still converging, not unstable yet
}

}  // namespace
