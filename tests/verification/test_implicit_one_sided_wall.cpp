// One-sided mesh boundaries of an implicit run (boundary_conditions[].one_sided,
// implicit/one_sided_boundary.hpp): a wall that pushes but never pulls.
//  - Lift-off: a block resting on a one-sided floor with the body force pointing away from it is
//    free: its centre of mass accelerates at g, so v_com(t) = g t exactly (Newmark's trapezoidal
//    rule integrates a constant force exactly when a^0 = b; a uniform translation has no strain).
//    On a plain "fixed" floor the same block is held by its bottom nodes and cannot (negative
//    control: the bottom half of its mass stays near the floor, v_com well below g t).
//  - The same with the Galerkin meshfree method (solver.basis "mls", "lme"), whose wall acts on the
//    same feet through each point's cloud: the block lifts off at g t and rests (|v_com| below 1 %
//    of g t, its top within the static settlement of its start).
//  - Resting: with the body force towards the floor the block's bottom row of particles has its feet
//    on the floor (their surface vectors point down to the block's bottom face), the wall holds them
//    without slip, and the block stays where a "fixed" floor holds it: at rest (|v_com| below 1 % of
//    g t) and its top within the static settlement under its own weight of the fixed floor's, delta =
//    rho g H^2 / (2 E) = 2e-5 m (a block that sank into the wall or lifted would be off by more).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;
using nlohmann::json;

constexpr double kG = 9.81, kEnd = 0.05;

/// A 0.4 m x 0.2 m neo-Hookean block (2 x 2 particles per Q4 cell of 0.05 m) on the floor y = 0 of
/// a 1 m x 1 m mesh, body force (0, gy), 50 steps of 1 ms.
Spec block_on_floor(double gy, bool one_sided, const std::string& basis = "mesh") {
  json spec = {
      {"title", "block on a floor"},
      {"mesh", {{"element", "q4"}, {"min", {0, 0}}, {"max", {1, 1}}, {"cells", {20, 20}}}},
      {"materials", {{{"name", "m"}, {"model", "neo_hookean"}, {"density", 1000}, {"E", 1e7}, {"nu", 0.3}}}},
      {"bodies",
       {{{"name", "block"},
         {"material", "m"},
         {"placement", "gauss"},
         {"shape", {{"type", "box"}, {"min", {0.3, 0.0}}, {"max", {0.7, 0.2}}}}}}},
      {"boundary_conditions", {{{"type", "fixed"}, {"boundary", "bottom"}, {"one_sided", one_sided}}}},
      {"loads", {{"gravity", {0.0, gy}}}},
      {"solver",
       {{"type", "implicit_ul"},
        {"basis", basis},
        {"dt", 1e-3},
        {"end_time", kEnd},
        {"implicit", {{"initial_acceleration", "body_force"}}}}},
      {"output", {{"every_time", kEnd}, {"particles", false}}},
      {"checks",
       {{{"name", "v"},
         {"measure", "final_com_velocity_y"},
         {"expected", 0},
         {"tolerance", 0},
         {"source", "test"}},
        {{"name", "top"},
         {"measure", "final_max_y"},
         {"expected", 0},
         {"tolerance", 0},
         {"source", "test"}}}}};
  const auto path = scratch_folder("one_sided_input.json");
  std::ofstream(path) << spec.dump();
  Spec out = load_spec(path);
  std::filesystem::remove(path);
  return out;
}

double final_velocity(const Spec& spec, const std::string& tag) {
  const auto result = run_quietly(spec, tag);
  EXPECT_EQ(result.exit_code, 0) << result.message;
  return measured(result, "final_com_velocity_y");
}

TEST(ImplicitOneSidedWall, BlockLiftsOffFreely) {
  const double free = final_velocity(block_on_floor(kG, true), "lift_one_sided");
  EXPECT_NEAR(free, kG * kEnd, 1e-9 * kG * kEnd);
  const double glued = final_velocity(block_on_floor(kG, false), "lift_fixed");
  EXPECT_LT(glued, 0.75 * kG * kEnd);
  std::printf("v_com / (g t): one-sided %.12f, fixed %.4f\n", free / (kG * kEnd), glued / (kG * kEnd));
}

TEST(ImplicitOneSidedWall, PressedBlockIsHeldAsOnAFixedFloor) {
  const auto one_sided = run_quietly(block_on_floor(-kG, true), "rest_one_sided");
  const auto fixed = run_quietly(block_on_floor(-kG, false), "rest_fixed");
  ASSERT_EQ(one_sided.exit_code, 0) << one_sided.message;
  ASSERT_EQ(fixed.exit_code, 0) << fixed.message;
  const double settlement = 1000.0 * kG * 0.2 * 0.2 / (2.0 * 1e7);  // rho g H^2 / (2 E)
  const double top_difference = measured(one_sided, "final_max_y") - measured(fixed, "final_max_y");
  EXPECT_LT(std::abs(measured(one_sided, "final_com_velocity_y")), 1e-2 * kG * kEnd);
  EXPECT_LT(std::abs(measured(fixed, "final_com_velocity_y")), 1e-2 * kG * kEnd);
  EXPECT_LT(std::abs(top_difference), settlement);
  std::printf("top of the block, one-sided minus fixed floor: %.3g m (static settlement %.3g m)\n",
              top_difference, settlement);
}

TEST(ImplicitOneSidedWall, MeshfreeBlockLiftsOffAndRests) {
  for (const char* basis : {"mls", "lme"}) {
    const double lift = final_velocity(block_on_floor(kG, true, basis), std::string("lift_") + basis);
    EXPECT_NEAR(lift, kG * kEnd, 1e-6 * kG * kEnd) << basis;
    const auto rest = run_quietly(block_on_floor(-kG, true, basis), std::string("rest_") + basis);
    ASSERT_EQ(rest.exit_code, 0) << rest.message;
    EXPECT_LT(std::abs(measured(rest, "final_com_velocity_y")), 1e-2 * kG * kEnd) << basis;
    const double settlement = 1000.0 * kG * 0.2 * 0.2 / (2.0 * 1e7);  // rho g H^2 / (2 E)
    const double top = measured(rest, "final_max_y");
    const double top0 = 0.175 + 0.05 / (2.0 * std::sqrt(3.0));  // the top row: 2 x 2 Gauss points per cell
    EXPECT_LT(std::abs(top - top0), settlement) << basis;
    std::printf(
        "%s: v_com / (g t) lifting %.9f; resting: v_com / (g t) %.2g, top moved %.3g m (settlement %.3g m)\n",
        basis, lift / (kG * kEnd), measured(rest, "final_com_velocity_y") / (kG * kEnd), top - top0,
        settlement);
  }
}

// A change of the contact set keeps the sparse pattern (the feet's penalties are assembled in their
// particles' element blocks, particle_newmark_system.hpp), so the linear solver's symbolic analysis
// is done once while the active elements stay. The block is pressed onto the floor for 5 ms (its
// feet held: it moves down slower than free fall, v > -g t) and then pulled away by
// the reversed body force (loads.gravity_scale -1): the feet are released over a few steps of
// re-solve rounds and the block flies, its velocity growing by exactly g dt per step. Its particles
// move by less than 0.3 mm, far from their cells' edges (10 mm), so the active set never changes.
TEST(ImplicitOneSidedWall, ContactChangesKeepTheSparsePatternAndItsAnalysis) {
  Spec spec = block_on_floor(-kG, true);
  spec.loads.gravity_scale = {{0.005, 0.0051}, {1.0, -1.0}};
  spec.solver.end_time = 0.01;
  spec.output.every_time = 0.0;
  spec.output.every_steps = 1;
  const auto result = run_quietly(spec, "press_then_lift");
  ASSERT_EQ(result.exit_code, 0) << result.message;
  const auto& rows = result.history.samples;
  ASSERT_EQ(rows.size(), 11U);
  const auto vy = [&](std::size_t k) { return rows[k].body_com_velocity[0][1]; };
  EXPECT_GT(vy(2), -kG * 0.002);  // held while pressed: slower than free fall, -g t
  for (std::size_t k = 9; k <= 10; ++k) EXPECT_NEAR(vy(k) - vy(k - 1), kG * 1e-3, 1e-9) << "step " << k;
  const long newton = result.summary["implicit"]["newton_iterations"].get<long>();
  std::printf(
      "press, then lift: v_y(2 ms) %.4f m/s, %ld Newton iterations in 10 steps, %ld symbolic analyses\n",
      vy(2), newton, result.summary["implicit"]["symbolic_analyses"].get<long>());
  EXPECT_EQ(result.summary["implicit"]["symbolic_analyses"].get<long>(), 1);
}

}  // namespace
