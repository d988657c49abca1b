// The brick order of the particle-to-grid sums (grid/brick_schedule.hpp): every particle once,
// storage order inside a brick, and no node reached from two bricks of one colour, which is what
// lets the threads scatter the bricks of a colour without synchronisation.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "matpoint/grid/brick_schedule.hpp"

namespace {

using namespace matpoint;

/// n particles in random cells of a grid of `cells` cells per axis; each particle's stencil is the
/// box of nodes from `below` nodes under its cell's lowest node to `above` nodes over it.
template <int D>
struct Layout {
  Grid<D> grid;
  std::vector<std::array<int, D>> cell;
  BrickSchedule<D> schedule;

  Layout(int cells, std::size_t n, int below, int above, unsigned seed) {
    std::array<int, D> c{};
    c.fill(cells);
    grid = Grid<D>(Vec<D>::Zero(), Vec<D>::Ones(), c, 0);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> any_cell(0, cells - 1);
    schedule.reset(grid, n);
    cell.resize(n);
    for (std::size_t p = 0; p < n; ++p) {
      for (int a = 0; a < D; ++a) cell[p][a] = any_cell(rng);
      schedule.assign(p, cell[p]);
    }
    schedule.finish(below, above);
  }
};

/// True when the stencil boxes [cell - below, cell + above] of two particles share a node.
template <int D>
bool boxes_overlap(const std::array<int, D>& p, const std::array<int, D>& q, int below, int above) {
  for (int a = 0; a < D; ++a)
    if (p[a] + above < q[a] - below || q[a] + above < p[a] - below) return false;
  return true;
}

template <int D>
void check_schedule(int cells, std::size_t n, int below, int above, int expected_colours_per_axis) {
  const Layout<D> layout(cells, n, below, above, 11);
  const auto& s = layout.schedule;
  EXPECT_EQ(s.colours_per_axis(), expected_colours_per_axis);

  // Every particle exactly once; within a brick in ascending storage order.
  std::vector<int> seen(n, 0);
  std::vector<std::size_t> order;
  s.for_each_particle([&](std::size_t p) { ++seen[p], order.push_back(p); });
  for (std::size_t p = 0; p < n; ++p) {
    EXPECT_EQ(seen[p], 1) << "particle " << p;
  }
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (s.brick_of(order[k]) == s.brick_of(order[k - 1])) {
      EXPECT_LT(order[k - 1], order[k]);
    }
  }

  // Two particles of different bricks with the same colour never reach a common node.
  std::size_t same_colour_pairs = 0;
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t q = p + 1; q < n; ++q) {
      const Index bp = s.brick_of(p), bq = s.brick_of(q);
      if (bp == bq || s.colour_of(bp) != s.colour_of(bq)) continue;
      ++same_colour_pairs;
      EXPECT_FALSE(boxes_overlap<D>(layout.cell[p], layout.cell[q], below, above))
          << "particles " << p << " and " << q << " in bricks " << bp << ", " << bq;
    }
  EXPECT_GT(same_colour_pairs, n) << "the layout must put many particles in bricks of one colour";
}

/// The quadratic B-spline reaches 1 node below a particle's cell and 2 above (3 nodes per axis).
TEST(BrickSchedule, TwoDimensionalQuadraticStencilsUseFourColours) { check_schedule<2>(80, 600, 1, 2, 2); }

TEST(BrickSchedule, StencilReachingABrickStillUsesTwoColoursPerAxis) {
  check_schedule<2>(80, 600, 7, BrickSchedule<2>::kNarrowestBrick - 7, 2);
}

TEST(BrickSchedule, StencilReachingBeyondABrickTakesAThirdColourPerAxis) {
  check_schedule<2>(120, 600, 7, BrickSchedule<2>::kNarrowestBrick - 6, 3);
}

TEST(BrickSchedule, ThreeDimensionalCubicStencils) { check_schedule<3>(40, 500, 1, 2, 2); }

TEST(BrickSchedule, ThreeDimensionalStencilReachingBeyondABrick) {
  check_schedule<3>(40, 500, 4, BrickSchedule<3>::kNarrowestBrick - 3, 3);
}

}  // namespace
