// The slab partition of a decomposed explicit run (parallel/slab_partition.hpp, issue 23): every
// cell and every node has exactly one owner, the cut follows the particle count, and a rank's
// stored nodes cover every node its particles' stencils reach. Expected values from the
// definitions: bricks of 8 cells along y (2-D), a quadratic B-spline reaches 1 node below and 2
// above a particle's cell (docs/scale-out.md §3).
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "matpoint/parallel/slab_partition.hpp"

namespace {

using namespace matpoint;

Grid<2> grid_of(int nx, int ny) { return Grid<2>(Vec<2>::Zero(), Vec<2>::Ones(), {nx, ny}, 0); }

TEST(SlabPartition, EveryCellLayerAndNodeLayerHasOneOwner) {
  const Grid<2> grid = grid_of(10, 45);  // 6 brick layers, the last one 5 cells thick
  std::vector<std::array<int, 2>> cells;
  for (int j = 0; j < 45; ++j) cells.push_back({0, j});
  for (const int ranks : {1, 2, 3, 4, 6}) {
    const auto slabs = SlabPartition<2>::balanced(grid, cells, ranks);
    std::vector<int> cell_owners(45, 0), node_owners(46, 0);
    for (int r = 0; r < ranks; ++r) {
      const auto [c0, c1] = slabs.cells_of(r);
      for (int j = c0; j < c1; ++j) {
        ++cell_owners[static_cast<std::size_t>(j)];
        EXPECT_EQ(slabs.owner_of_cell({3, j}), r);
      }
      const auto [n0, n1] = slabs.owned_nodes_of(r);
      for (int j = n0; j < n1; ++j) ++node_owners[static_cast<std::size_t>(j)];
    }
    for (int j = 0; j < 45; ++j)
      EXPECT_EQ(cell_owners[static_cast<std::size_t>(j)], 1) << ranks << " ranks, cell " << j;
    for (int j = 0; j <= 45; ++j)
      EXPECT_EQ(node_owners[static_cast<std::size_t>(j)], 1) << ranks << " ranks, node " << j;
  }
}

TEST(SlabPartition, CutsWhereHalfTheParticlesLie) {
  // 100 particles in brick layer 0 (cells 0-7), 100 spread over layers 1-4: two ranks split
  // between layer 0 and the rest; the uniform layout splits in the middle layer boundary.
  const Grid<2> grid = grid_of(8, 40);
  std::vector<std::array<int, 2>> cells;
  for (int k = 0; k < 100; ++k) cells.push_back({0, k % 8});
  for (int k = 0; k < 100; ++k) cells.push_back({0, 8 + k % 32});
  const auto two = SlabPartition<2>::balanced(grid, cells, 2);
  EXPECT_EQ(two.cells_of(0), std::make_pair(0, 8));
  EXPECT_EQ(two.cells_of(1), std::make_pair(8, 40));
  std::vector<std::array<int, 2>> uniform;
  for (int j = 0; j < 32; ++j) uniform.push_back({0, j});
  const auto halves = SlabPartition<2>::balanced(grid_of(8, 32), uniform, 2);
  EXPECT_EQ(halves.cells_of(0), std::make_pair(0, 16));
}

TEST(SlabPartition, StoredNodesCoverTheStencilsOfTheOwnedCells) {
  const Grid<2> grid = grid_of(8, 40);
  std::vector<std::array<int, 2>> cells;
  for (int j = 0; j < 40; ++j) cells.push_back({0, j});
  const auto slabs = SlabPartition<2>::balanced(grid, cells, 3);
  for (int r = 0; r < 3; ++r) {
    const auto [c0, c1] = slabs.cells_of(r);
    const auto [s0, s1] = slabs.stored_nodes_of(r, /*below=*/1, /*above=*/2);
    EXPECT_EQ(s0, std::max(0, c0 - 1));
    EXPECT_EQ(s1, std::min(41, c1 + 2));  // the last cell c1 - 1 reaches node c1 + 1
  }
  EXPECT_EQ(SlabPartition<2>::balanced(grid, cells, 8).stored_nodes_of(7, 1, 2), std::make_pair(0, 0))
      << "a rank without cells (5 brick layers, 8 ranks) stores no node";
}

// The node layers two ranks both store: rank 0 (cells 0-7) stores nodes 0-9 with 2 layers above,
// rank 1 (cells 8-23) nodes 7-25 with 1 below: 7, 8, 9 are shared; ranks 0 and 2 share none.
TEST(SlabPartition, SharedNodesAreWhereTwoWindowsOverlap) {
  const Grid<2> grid = grid_of(8, 40);
  std::vector<std::array<int, 2>> cells;
  for (int j = 0; j < 40; ++j) cells.push_back({0, j});
  const auto slabs = SlabPartition<2>::balanced(grid, cells, 3);
  ASSERT_EQ(slabs.cells_of(0), std::make_pair(0, 8));
  ASSERT_EQ(slabs.cells_of(1), std::make_pair(8, 24));
  EXPECT_EQ(slabs.shared_nodes_of(0, 1, /*below=*/1, /*above=*/2), std::make_pair(7, 10));
  EXPECT_EQ(slabs.shared_nodes_of(1, 0, 1, 2), std::make_pair(7, 10));
  const auto [begin, end] = slabs.shared_nodes_of(0, 2, 1, 2);
  EXPECT_GE(begin, end) << "ranks 0 and 2 store no node together";
}

// The cut from per-layer counts (a re-partition's one reduction) is the cut from the particles'
// cells, and a stored cut (first_layers, as a checkpoint keeps it) gives the same owners back.
TEST(SlabPartition, CountsPerLayerAndStoredLayersGiveTheSameCut) {
  const Grid<2> grid = grid_of(8, 40);  // 5 brick layers
  std::vector<std::array<int, 2>> cells;
  const std::vector<std::size_t> count{7, 30, 2, 0, 11};
  for (int layer = 0; layer < 5; ++layer)
    for (std::size_t k = 0; k < count[static_cast<std::size_t>(layer)]; ++k) cells.push_back({0, 8 * layer});
  for (const int ranks : {1, 2, 3, 5}) {
    const auto from_cells = SlabPartition<2>::balanced(grid, cells, ranks);
    const auto from_counts = SlabPartition<2>::balanced(grid, count, ranks);
    EXPECT_EQ(from_counts.first_layers(), from_cells.first_layers()) << ranks << " ranks";
    const auto restored = SlabPartition<2>::from_first_layers(grid, from_cells.first_layers());
    for (int j = 0; j < 40; ++j) EXPECT_EQ(restored.owner_of_cell({0, j}), from_cells.owner_of_cell({0, j}));
  }
  // Two ranks: 7 + 30 = 37 of 50 lie in layers 0-1; the first layer boundary with at most
  // ceil(50 / 2) = 25 below is after layer 0 (7), so rank 0 owns layer 0 alone.
  EXPECT_EQ(SlabPartition<2>::balanced(grid, count, 2).first_layers(), (std::vector<int>{0, 1, 5}));
}

}  // namespace

namespace {

// Grid::window (docs/scale-out.md §2): a rank stores the node layers [begin, end) along the cut axis;
// each stored node keeps its coordinates and position, the numbering is x fastest from 0, and a
// value carried from one window to another by node lands on the same node. Expected values from
// the definition: a window of layers [3, 7) of a 10 x 20 grid stores 11 x 4 nodes.
TEST(GridWindow, StoresTheLayersAndKeepsEveryNodesCoordinatesAndPosition) {
  const Grid<2> whole(Vec<2>(-1.0, 2.0), Vec<2>(0.5, 0.25), {10, 20}, 0);
  const Grid<2> window = whole.window(1, 3, 7);
  EXPECT_EQ(window.node_count, 11 * 4);
  EXPECT_EQ(window.total_node_count(), whole.node_count);
  EXPECT_EQ(window.node_index({0, 3}), 0);
  EXPECT_EQ(window.node_index({10, 6}), 11 * 4 - 1);
  for (Index n = 0; n < window.node_count; ++n) {
    const auto ijk = window.node_coords(n);
    EXPECT_TRUE(window.stores(ijk));
    EXPECT_GE(ijk[1], 3);
    EXPECT_LT(ijk[1], 7);
    EXPECT_EQ(window.node_index(ijk), n);
    EXPECT_EQ(window.node_position(n), whole.node_position(whole.node_index(ijk)));
    EXPECT_EQ(window.node_index_in(whole, n), whole.node_index(ijk));
  }
  EXPECT_FALSE(window.stores({0, 2}));
  EXPECT_FALSE(window.stores({0, 7}));
  // Geometry is the whole grid's: cells, containment and cell indices do not change.
  EXPECT_EQ(window.cell_index(Vec<2>(3.0, 6.9)), whole.cell_index(Vec<2>(3.0, 6.9)));
  EXPECT_TRUE(window.contains(Vec<2>(3.9, 6.9)));
  // Another window: the shared layers map onto each other, the others onto none.
  const Grid<2> above = whole.window(1, 5, 21);
  EXPECT_EQ(above.nodes[1], 16);
  for (Index n = 0; n < window.node_count; ++n) {
    const Index k = window.node_index_in(above, n);
    if (window.node_coords(n)[1] < 5)
      EXPECT_EQ(k, -1);
    else
      EXPECT_EQ(above.node_coords(k), window.node_coords(n));
  }
  // Clamped to the grid's nodes (ghost layers included).
  const Grid<2> ghosted(Vec<2>::Zero(), Vec<2>::Ones(), {4, 4}, 1);
  const Grid<2> clamped = ghosted.window(1, -5, 50);
  EXPECT_EQ(clamped.node_count, ghosted.node_count);
  EXPECT_EQ(clamped.first[1], -1);
}

}  // namespace
