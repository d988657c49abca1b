// Aulisa & Capodaglio's implicit MPM through the whole program (input -> run loop -> history): a
// body falling freely inside the mesh (no condition reached) follows the discrete Newmark solution
// exactly (extraction §12, AT-1): a rigid translation has grad u~ = 0, no stress, and the particle
// residual (20) gives a_p = g for n >= 1. With the paper's a^0 = 0 (eq. (21) initialisation):
//   v^n = (n - 1 + gamma) dt g,   u^n = beta dt^2 g + sum_{k=1}^{n-1} (dt v^k + dt^2 g / 2)
// (eqs. (17)-(19) with a^k = g for k >= 1); with a^0 = g (extraction A17) exactly v = g t, u = g t^2 / 2.
// The soft stiffness (eq. (26), C_E as the paper's eq. (50) pattern) is on: with one particle per
// Q9 element the consistent particle mass matrix is singular and only the soft stiffness makes the
// system regular (extraction §6); a rigid translation has no soft-stiffness energy, so it is exact.
#include <gtest/gtest.h>

#include <cmath>

#include "matpoint/io/input.hpp"
#include "test_support.hpp"

namespace matpoint {
namespace implicit_free_fall_tests {

constexpr double kG = 9.81, kDt = 0.01, kBeta = 0.3, kGamma = 0.5;

std::string fall_input(int dim, const std::string& initial_acceleration) {
  const bool three = dim == 3;
  return std::string(R"({"mesh": {"element": )") +
         (three ? R"("hex8", "min": [0, 0, 0], "max": [4, 4, 4], "cells": [4, 4, 4]},)"
                : R"("q9", "min": [0, 0], "max": [4, 4], "cells": [4, 4]},)") +
         R"("materials": [{"name": "rubber", "model": "neo_hookean", "density": 1000, "E": 4.2e6, "nu": 0.4}],)"
         R"("bodies": [{"name": "block", "material": "rubber", "particles_per_cell": 2, "shape": {"type": "box", )" +
         (three ? R"("min": [1.5, 2.5, 1.5], "max": [2.5, 3.5, 2.5]}}],)"
                : R"("min": [1.5, 2.5], "max": [2.5, 3.5]}}],)") +
         R"("loads": {"gravity": )" + (three ? "[0, 0, -9.81]}," : "[0, -9.81]},") +
         R"("solver": {"type": "implicit_mpm", "dt": 0.01, "end_time": 0.2, "implicit": {"beta": 0.3, "gamma": 0.5, )"
         R"("soft_stiffness": {"table": [[5, 1e-3], [9, 1e-7]]}, "initial_acceleration": ")" +
         initial_acceleration + R"("}}, "output": {"every_steps": 5, "plots": false}})";
}

/// The discrete Newmark fall with a^0 = 0 after n steps: (displacement, velocity) along g.
std::pair<double, double> discrete_fall(long n) {
  if (n == 0) return {0.0, 0.0};
  double u = kBeta * kDt * kDt * kG;  // step 1: a^1 = g (a^0 = 0), u^1 = beta dt^2 a^1
  double v = kGamma * kDt * kG;
  for (long k = 1; k < n; ++k) {  // a^k = a^{k+1} = g
    u += kDt * v + 0.5 * kDt * kDt * kG;
    v += kDt * kG;
  }
  return {u, v};
}

void expect_fall(int dim, const std::string& initial_acceleration) {
  const RunResult result =
      test::run_quietly(parse_spec(fall_input(dim, initial_acceleration)), "implicit_fall");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  const auto& samples = result.history.samples;
  ASSERT_GE(samples.size(), 5U);
  const int axis = dim - 1;  // gravity along -y (2-D) or -z (3-D)
  const double start = samples.front().body_com_position[0][axis];
  for (const auto& s : samples) {
    const auto [u, v] = initial_acceleration == "zero" ? discrete_fall(s.step)
                                                       : std::pair{0.5 * kG * s.time * s.time, kG * s.time};
    const double fallen = start - s.body_com_position[0][axis];
    const double speed = -s.body_com_velocity[0][axis];
    EXPECT_NEAR(fallen, u, 1e-10 * std::max(u, 1e-3)) << "step " << s.step;
    EXPECT_NEAR(speed, v, 1e-10 * std::max(v, 1e-2)) << "step " << s.step;
    for (int a = 0; a < dim; ++a)
      if (a != axis) {
        EXPECT_NEAR(s.body_com_velocity[0][a], 0.0, 1e-12);
      }
  }
}

/// fall_input with `solver_extra` replacing solver.dt (a schedule or adaptive steps) and
/// `loads_extra` added to loads.
std::string fall_input_with(const std::string& solver_dt, const std::string& implicit_extra,
                            const std::string& loads_extra = "") {
  std::string text = fall_input(2, "body_force");
  auto replace = [&text](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace(R"("dt": 0.01, )", solver_dt);
  replace(R"("initial_acceleration": "body_force")",
          R"("initial_acceleration": "body_force")" + implicit_extra);
  replace(R"("gravity": [0, -9.81])", R"("gravity": [0, -9.81])" + loads_extra);
  replace(R"("every_steps": 5)", R"("every_steps": 1)");
  return text;
}

/// With a^0 = g the Newmark fall is exact for any sequence of steps (a^n = g throughout):
/// u = g t^2 / 2, v = g t at every row.
void expect_exact_fall(const RunResult& result) {
  ASSERT_EQ(result.exit_code, 0) << result.message;
  const auto& samples = result.history.samples;
  const double start = samples.front().body_com_position[0][1];
  for (const auto& s : samples) {
    EXPECT_NEAR(start - s.body_com_position[0][1], 0.5 * kG * s.time * s.time, 1e-10) << "step " << s.step;
    EXPECT_NEAR(-s.body_com_velocity[0][1], kG * s.time, 1e-10) << "step " << s.step;
  }
}

// solver.implicit.adaptive_dt (implicit/step_size_control.hpp): with easy_iterations above any
// count Newton needs here, every step is "easy" and the step grows by the factor each step up to
// max: the k-th step is min(max, dt0 factor^(k-1)) (the rule as docs/input.md states it), except
// the last two: what is left after 0.002 + 0.004 + 0.008 + 0.016 + 7 x 0.02 = 0.17 s is 0.03 s,
// less than two steps, and an implicit run splits it evenly (run/run_loop.hpp steps_to_land).
TEST(ImplicitTimeStep, AdaptiveStepsGrowByTheRuleAndTheFallStaysExact) {
  const RunResult result = test::run_quietly(
      parse_spec(fall_input_with(R"("dt": 0.002, )",
                                 R"(, "adaptive_dt": {"min": 0.001, "max": 0.02, )"
                                 R"("easy_iterations": 10, "hard_iterations": 15, "factor": 2})")),
      "implicit_adaptive_fall");
  expect_exact_fall(result);
  const auto& samples = result.history.samples;
  ASSERT_GE(samples.size(), 6U);
  for (std::size_t k = 1; k + 2 < samples.size(); ++k)
    EXPECT_DOUBLE_EQ(samples[k].dt, std::min(0.02, 0.002 * std::ldexp(1.0, static_cast<int>(k) - 1))) << k;
  EXPECT_NEAR(samples[samples.size() - 2].dt, 0.015, 1e-15);
  EXPECT_NEAR(samples.back().dt, 0.015, 1e-15);
  EXPECT_DOUBLE_EQ(samples.back().time, 0.2);
}

// solver.implicit.dt_schedule: the step taken from time t is the table's dt(t) (piecewise linear),
// but for the last two, which split what is left evenly (run/run_loop.hpp steps_to_land).
TEST(ImplicitTimeStep, ScheduledStepsFollowTheTable) {
  const RunResult result = test::run_quietly(
      parse_spec(fall_input_with("", R"(, "dt_schedule": {"table": [[0, 0.005], [0.1, 0.025]]})")),
      "implicit_scheduled_fall");
  expect_exact_fall(result);
  const auto& samples = result.history.samples;
  ASSERT_GE(samples.size(), 6U);
  for (std::size_t k = 1; k + 2 < samples.size(); ++k) {
    const double t = samples[k - 1].time;
    EXPECT_NEAR(samples[k].dt, t < 0.1 ? 0.005 + 0.2 * t : 0.025, 1e-15) << k;
  }
}

// loads.gravity_scale switched from 1 to 0 just after t1 = 0.1 s (a step boundary with dt = 0.01):
// the implicit step takes gravity at its end, so steps 1-10 fall with a = g and from step 11 on
// a = 0. Newmark's velocity update (eq. (19)) over step 11 adds dt (1 - gamma) g, then the body
// moves uniformly: v = g (t1 + (1 - gamma) dt) at every later row, u grows by v dt per step.
TEST(ImplicitTimeStep, GravitySwitchedOffFollowsDiscreteNewmark) {
  const RunResult result = test::run_quietly(
      parse_spec(
          fall_input_with(R"("dt": 0.01, )", "", R"(, "gravity_scale": {"table": [[0.1, 1], [0.1001, 0]]})")),
      "implicit_gravity_off");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  const double v_after = kG * (0.1 + (1 - kGamma) * kDt);
  for (const auto& s : result.history.samples) {
    const double v = -s.body_com_velocity[0][1];
    EXPECT_NEAR(v, s.time <= 0.1 + 1e-12 ? kG * s.time : v_after, 1e-10) << "t = " << s.time;
  }
}

// Iaconeta 2017's updated-Lagrangian MPM (solver.type "implicit_ul"): the particles' momentum and
// m a projected to the nodes (eqs. (38)-(41)) of a rigid translation are v and a themselves
// (partition of unity), so Newmark at the nodes (43)-(44) and back at the particles (47)-(48) is the
// particle Newmark of the fall: with a^0 = g exactly u = g t^2 / 2, v = g t. On Q4 cells, as the paper.
TEST(ImplicitFreeFall, UpdatedLagrangianGridNewmarkIsExact) {
  std::string text = fall_input(2, "body_force");
  text.replace(text.find("implicit_mpm"), 12, "implicit_ul");
  text.replace(text.find(R"("q9")"), 4, R"("q4")");  // the paper's linear cells (quadratic ones refused)
  expect_exact_fall(test::run_quietly(parse_spec(text), "implicit_ul_fall"));
}

TEST(ImplicitFreeFall, PaperInitialisationFollowsDiscreteNewmark2D) { expect_fall(2, "zero"); }
TEST(ImplicitFreeFall, BodyForceInitialisationIsExact2D) { expect_fall(2, "body_force"); }
TEST(ImplicitFreeFall, PaperInitialisationFollowsDiscreteNewmark3D) { expect_fall(3, "zero"); }
TEST(ImplicitFreeFall, BodyForceInitialisationIsExact3D) { expect_fall(3, "body_force"); }

}  // namespace implicit_free_fall_tests
}  // namespace matpoint
