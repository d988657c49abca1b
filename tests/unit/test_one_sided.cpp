// One-sided face conditions (docs/input.md, boundary_conditions.one_sided): a "fixed" or "slip"
// face holds only the nodes moving into it and leaves the nodes moving away free.
#include <gtest/gtest.h>

#include "matpoint/grid/velocity_conditions.hpp"

namespace {

using namespace matpoint;

TEST(OneSidedFace, HoldsApproachingNodesAndFreesSeparatingOnes) {
  const Grid<2> grid(Vec<2>(0, 0), Vec<2>(1, 1), {4, 4}, 0);
  VelocityConditionSpec fixed;
  fixed.face_axis = 1;  // y-
  fixed.face_side = 0;
  fixed.kind = ConditionKind::Fixed;
  fixed.one_sided = true;
  VelocityConditionSpec slip = fixed;
  slip.kind = ConditionKind::Slip;
  slip.normal_axis = 1;
  slip.face_side = 1;  // y+
  const VelocityConditions<2> conditions({fixed, slip}, grid);
  std::vector<Vec<2>> v(grid.node_count, Vec<2>(0.5, 0.0));
  const Index down = grid.node_index({1, 0}), up = grid.node_index({2, 0});
  const Index top_in = grid.node_index({1, 4}), top_out = grid.node_index({2, 4});
  v[down] = Vec<2>(0.5, -1.0);   // into the y- face: both components held at zero
  v[up] = Vec<2>(0.5, 1.0);      // leaving the y- face: free
  v[top_in] = Vec<2>(0.5, 1.0);  // into the y+ face: the normal component held (slip)
  v[top_out] = Vec<2>(0.5, -1.0);
  conditions.apply(v, 0.0);
  EXPECT_EQ(v[down], Vec<2>(0.0, 0.0));
  EXPECT_EQ(v[up], Vec<2>(0.5, 1.0));
  EXPECT_EQ(v[top_in], Vec<2>(0.5, 0.0));
  EXPECT_EQ(v[top_out], Vec<2>(0.5, -1.0));
  EXPECT_EQ(v[grid.node_index({2, 2})], Vec<2>(0.5, 0.0));  // interior untouched
}

// With touching flags (set each step by mark_nodes_touching_faces) a node moving into the face is
// held only where the body touches it, and the nodes chosen by the first apply of the step stay
// chosen for the later ones (the strain pass of MUSL / USF), whatever their velocity then.
TEST(OneSidedFace, HoldsOnlyTouchingNodesAndKeepsTheStepsChoice) {
  const Grid<2> grid(Vec<2>(0, 0), Vec<2>(1, 1), {4, 4}, 0);
  VelocityConditionSpec fixed;
  fixed.face_axis = 1;
  fixed.face_side = 0;
  fixed.kind = ConditionKind::Fixed;
  fixed.one_sided = true;
  VelocityConditions<2> conditions({fixed}, grid);
  ASSERT_EQ(conditions.one_sided_faces().size(), 1U);
  EXPECT_EQ(conditions.one_sided_faces()[0].position, 0.0);
  const Index touching = grid.node_index({1, 0}), apart = grid.node_index({2, 0});
  auto& flags = conditions.touching();
  flags.assign(static_cast<std::size_t>(grid.node_count), 0);
  flags[touching] = 1;
  std::vector<Vec<2>> v(grid.node_count, Vec<2>(0.5, -1.0));  // everything moves into the face
  conditions.apply(v, 0.0);
  EXPECT_EQ(v[touching], Vec<2>(0.0, 0.0));
  EXPECT_EQ(v[apart], Vec<2>(0.5, -1.0));  // not touching: free
  v[touching] = Vec<2>(0.5, 1.0);          // the second pass of the step: now moving away
  v[apart] = Vec<2>(0.5, -1.0);
  conditions.apply(v, 0.0);
  EXPECT_EQ(v[touching], Vec<2>(0.0, 0.0));  // still held: chosen by the step's first apply
  EXPECT_EQ(v[apart], Vec<2>(0.5, -1.0));
  conditions.touching()[touching] = 1;  // a new step: the choice is made again
  v[touching] = Vec<2>(0.5, 1.0);
  conditions.apply(v, 0.0);
  EXPECT_EQ(v[touching], Vec<2>(0.5, 1.0));
}

}  // namespace
