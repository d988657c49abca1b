// One-sided mesh boundaries of an implicit run (boundary_conditions[].one_sided,
// implicit/one_sided_boundary.hpp): a wall that pushes but never pulls.
//  - Lift-off: a block resting on a one-sided floor with the body force pointing away from it is
//    free: its centre of mass accelerates at g, so v_com(t) = g t exactly (Newmark's trapezoidal
//    rule integrates a constant force exactly when a^0 = b; a uniform translation has no strain).
//    On a plain "fixed" floor the same block is held by its bottom nodes and cannot (negative
//    control: the bottom half of its mass stays near the floor, v_com well below g t).
//  - Resting: with the body force towards the floor every node under the block is touched and
//    pushed, so the one-sided floor holds the same nodes as a "fixed" floor and the two runs agree
//    to round-off.
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
Spec block_on_floor(double gy, bool one_sided) {
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
        {"dt", 1e-3},
        {"end_time", kEnd},
        {"implicit", {{"initial_acceleration", "body_force"}}}}},
      {"output", {{"every_time", kEnd}, {"particles", false}}},
      {"checks",
       {{{"name", "v"},
         {"measure", "final_com_velocity_y"},
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
  const double one_sided = final_velocity(block_on_floor(-kG, true), "rest_one_sided");
  const double fixed = final_velocity(block_on_floor(-kG, false), "rest_fixed");
  EXPECT_NEAR(one_sided, fixed, 1e-12 + 1e-9 * std::abs(fixed));
  EXPECT_LT(std::abs(fixed), 1e-2 * kG * kEnd);  // at rest on the floor, up to its elastic settling
}

}  // namespace
