// Grid velocity conditions superposed on one node (Nairn 2026 §1.6, Table 2 top block): every
// condition first removes the velocity along its direction, then each adds its own prescribed
// velocity, so that v_i = v_i - sum_b (v_i . n_b) n_b + sum_b v^(b) n_b. Two conditions along
// the same direction therefore add their velocities; perpendicular ones each set their own
// component. The expected values follow from that formula by hand.
#include <gtest/gtest.h>

#include <random>

#include "matpoint/grid/velocity_conditions.hpp"

namespace {

using namespace matpoint;

VelocityConditionSpec face(int axis, ConditionKind kind) {
  VelocityConditionSpec c;
  c.on_face = true;
  c.face_axis = axis;
  c.kind = kind;
  c.normal_axis = axis;
  return c;
}

VelocityConditionSpec moving_box(Triple min, Triple max, int axis, double speed) {
  VelocityConditionSpec c;
  c.on_face = false;
  c.box_min = min;
  c.box_max = max;
  c.kind = ConditionKind::Velocity;
  c.velocity[axis] = TimeFunction{{}, {speed}};
  return c;
}

struct Fixture {
  Grid<2> grid{Vec<2>(0.0, 0.0), Vec<2>(0.1, 0.1), {10, 10}, 1};
  std::vector<Vec<2>> v;
  std::vector<double> mass;
  Fixture() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0), m(0.5, 2.0);
    for (Index i = 0; i < grid.node_count; ++i) {
      v.emplace_back(u(rng), u(rng));
      mass.push_back(m(rng));
    }
  }
};

// A fixed x- face, a slip y- face, and a box moving at v_x = 0.25 that really overlaps both
// faces (it starts left of the domain, so it covers the x- face and its ghost nodes, and reaches
// below y = 0.3, the y- face included). On the nodes of the x- face inside the box the fixed
// condition and the moving box superpose: v_x = 0 + 0.25, v_y = 0.
TEST(VelocityConditions, PerpendicularAndParallelConditionsSuperpose) {
  Fixture f;
  const std::vector<VelocityConditionSpec> specs{face(0, ConditionKind::Fixed), face(1, ConditionKind::Slip),
                                                 moving_box({-1.0, -1.0, 0.0}, {0.45, 0.3, 0.0}, 0, 0.25)};
  const VelocityConditions<2> conditions(specs, f.grid);
  auto v = f.v;
  Vec<2> impulse = Vec<2>::Zero();
  double work = 0.0;
  conditions.apply(v, 0.0, &f.mass, &impulse, &work);
  int overlap = 0;
  Vec<2> expected_impulse = Vec<2>::Zero();
  for (Index i = 0; i < f.grid.node_count; ++i) {
    const auto ijk = f.grid.node_coords(i);
    const Vec<2> x = f.grid.node_position(i);
    const bool fixed = ijk[0] <= 0, slip = ijk[1] <= 0;
    const bool box = x[0] <= 0.45 + 1e-9 && x[1] <= 0.3 + 1e-9;
    Vec<2> want = f.v[i];
    if (fixed) want.setZero();
    if (slip) want[1] = 0.0;
    if (box) want[0] = 0.25;  // on the fixed face: its 0 plus the box's 0.25
    EXPECT_EQ(v[i], want) << "node " << i;
    overlap += fixed && box ? 1 : 0;
    expected_impulse += f.mass[i] * (want - f.v[i]);
  }
  EXPECT_GT(overlap, 3) << "the box must overlap the fixed face";
  EXPECT_NEAR((impulse - expected_impulse).norm(), 0.0, 1e-12);
}

// Two boxes moving along x overlap: there the prescribed velocities add (0.25 + 0.1), and the
// impulse is the mass times the change to that sum.
TEST(VelocityConditions, ParallelConditionsAddTheirVelocities) {
  Fixture f;
  const std::vector<VelocityConditionSpec> specs{moving_box({0.2, 0.2, 0.0}, {0.6, 0.6, 0.0}, 0, 0.25),
                                                 moving_box({0.4, 0.4, 0.0}, {0.8, 0.8, 0.0}, 0, 0.1)};
  const VelocityConditions<2> conditions(specs, f.grid);
  auto v = f.v;
  Vec<2> impulse = Vec<2>::Zero();
  double work = 0.0;
  conditions.apply(v, 0.0, &f.mass, &impulse, &work);
  Vec<2> expected_impulse = Vec<2>::Zero();
  int both = 0;
  for (Index i = 0; i < f.grid.node_count; ++i) {
    const Vec<2> x = f.grid.node_position(i);
    const auto inside = [&](double lo, double hi) {
      return x[0] >= lo - 1e-9 && x[0] <= hi + 1e-9 && x[1] >= lo - 1e-9 && x[1] <= hi + 1e-9;
    };
    const bool a = inside(0.2, 0.6), b = inside(0.4, 0.8);
    Vec<2> want = f.v[i];
    if (a || b) want[0] = (a ? 0.25 : 0.0) + (b ? 0.1 : 0.0);
    both += a && b ? 1 : 0;
    EXPECT_NEAR((v[i] - want).norm(), 0.0, 1e-15) << "node " << i;
    expected_impulse += f.mass[i] * (want - f.v[i]);
  }
  EXPECT_EQ(both, 9);  // nodes 0.4, 0.5, 0.6 in x and y
  EXPECT_NEAR((impulse - expected_impulse).norm(), 0.0, 1e-12);
}

}  // namespace
