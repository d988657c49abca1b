// examples/vibrating-bar-1d: a fixed-free elastic bar in its first mode. The exact centre-of-mass
// velocity is v_cm(t) = 2 v0 / pi cos(pi c t / (2 L)) (separation of variables for u_tt = c^2 u_xx,
// u(0) = 0, u_x(L) = 0). The lumped-mass MPM discretisation has an O(h^2) frequency (dispersion)
// error, so at a time step small enough to hide the O(dt) time error the velocity error must fall
// as h^2: we assert an observed order >= 1.8 over h = 1/8, 1/16, 1/32.
#include "test_support.hpp"

#include "matpoint/analysis/measures_eval.hpp"

#include <gtest/gtest.h>

namespace {

using namespace matpoint;
using namespace matpoint::test;

double bar_error(ShapeKind shape, double h, const char* tag) {
  Spec spec = load_example("vibrating-bar-1d");
  spec.grid.cell_size[0] = h;
  spec.grid.cells[0] = static_cast<int>(std::lround((spec.grid.max[0] - spec.grid.min[0]) / h));
  spec.solver.shape = shape;
  spec.solver.dt = 2e-5;  // c dt / h <= 0.0064: the time error is far below the space error
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

}  // namespace
