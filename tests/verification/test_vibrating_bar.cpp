// examples/vibrating-bar-1d: a fixed-free elastic bar in its first mode. The exact centre-of-mass
// velocity is v_cm(t) = 2 v0 / pi cos(pi c t / (2 L)) (separation of variables for u_tt = c^2 u_xx,
// u(0) = 0, u_x(L) = 0). The lumped-mass MPM discretisation has an O(h^2) frequency (dispersion)
// error, so at a time step small enough to hide the O(dt) time error the velocity error must fall
// as h^2: we assert an observed order >= 1.8 over h = 1/8, 1/16, 1/32.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "matpoint/analysis/measures_eval.hpp"
#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;

double bar_error(ShapeKind shape, double h, const char* tag) {
  Spec spec = load_example("vibrating-bar-1d");
  spec.grid.cell_size[0] = h;
  spec.grid.cells[0] = static_cast<int>(std::lround((spec.grid.max[0] - spec.grid.min[0]) / h));
  spec.solver.shape = shape;
  spec.solver.dt = 2e-5;                    // c dt / h <= 0.0064: the time error is far below the space error
  spec.bodies[0].sine_amplitude[0] = 0.01;  // no particle crosses a cell: the smooth-solution regime
  const auto result = run_quietly(spec, tag);
  EXPECT_EQ(result.exit_code, 0) << result.message;
  return evaluate_measure("vibrating_bar_com_velocity_error", spec, result.history, 0.0);
}

void expect_second_order(ShapeKind shape, const char* tag) {
  const std::vector<double> h{1.0 / 8, 1.0 / 16, 1.0 / 32};
  std::vector<double> error;
  for (double hk : h) error.push_back(bar_error(shape, hk, tag));
  const double order = observed_order(h, error);
  EXPECT_GE(order, 1.8) << "errors " << error[0] << " " << error[1] << " " << error[2];
  EXPECT_LT(order, 2.5);
  EXPECT_LT(error.back(), 0.01);
}

TEST(VibratingBar, CentreOfMassVelocityConvergesAtSecondOrderWithLinearBasis) {
  expect_second_order(ShapeKind::Linear, "bar_linear");
}

TEST(VibratingBar, CentreOfMassVelocityConvergesAtSecondOrderWithQuadraticBSpline) {
  expect_second_order(ShapeKind::BSpline2, "bar_bspline2");
}

TEST(VibratingBar, ExampleAsShippedPassesItsChecks) {
  const auto result = run_quietly(load_example("vibrating-bar-1d"), "bar_example");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  for (const auto& check : result.summary["checks"]) EXPECT_TRUE(check["pass"].get<bool>()) << check.dump();
}

// A probe (output.probes) at the free end follows the particle nearest X = L, here X = L - h/4:
// u(X, t) = (v0 / omega) sin(pi X / 2L) sin(omega t), omega = pi c / 2L. At t = 0 its velocity is
// the initial condition v0 sin(pi X / 2L) exactly; the displacement amplitude over the first half
// period carries the O(h^2) error of the discrete mode, 0.1 % here, and the output sampling error
// 1 - cos(omega dt_out / 2) = 0.08 % (dt_out = 0.005); the bound 0.5 % is twice their sum, rounded.
TEST(VibratingBar, ProbeAtTheFreeEndFollowsTheFirstMode) {
  Spec spec = load_example("vibrating-bar-1d");
  spec.solver.dt = 2e-5;
  spec.solver.end_time = 0.2;  // half a period
  const double v0 = 0.01, L = 1.0, c = 10.0, h = 1.0 / 32;
  spec.bodies[0].sine_amplitude[0] = v0;  // no particle crosses a cell: the smooth-solution regime
  spec.output.probes = {{"free_end", {L, 0, 0}}};
  const auto result = run_quietly(spec, "bar_probe");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  ASSERT_EQ(result.history.probe_columns.size(), 5u);  // x, ux, vx, sxx, J
  EXPECT_EQ(result.history.probe_columns[1], "probe_free_end_ux");
  const double X = L - h / 4, omega = std::numbers::pi * c / (2 * L);
  const double shape = std::sin(std::numbers::pi * X / (2 * L));
  EXPECT_DOUBLE_EQ(result.summary["probes"][0]["reference_position"][0].get<double>(), X);
  const auto& first = result.history.samples.front().probes;
  EXPECT_NEAR(first[2], v0 * shape, 1e-15) << "initial velocity";
  double peak = 0;
  for (const auto& s : result.history.samples) peak = std::max(peak, s.probes[1]);
  EXPECT_NEAR(peak / (v0 / omega * shape), 1.0, 5e-3) << "displacement amplitude " << peak;
}

}  // namespace
