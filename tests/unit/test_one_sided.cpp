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

}  // namespace
