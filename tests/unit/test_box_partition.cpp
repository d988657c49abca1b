// The box partition of a decomposed explicit run (parallel/box_partition.hpp, issue 23): every
// cell and every node has exactly one owner, the cuts follow the particle count (recursive
// coordinate bisection of the brick counts), a cube is cut into boxes, and a rank's stored nodes
// cover every node its particles' stencils reach. Expected values from the definitions: bricks of
// 64 x 8 cells (2-D) and 32 x 8 x 8 (3-D); the ranks split floor(P / 2) : the rest, along the axis
// with the most bricks (the last of equals), where the particles before the cut come closest to
// their share; a quadratic B-spline reaches 1 node below and 2 above a particle's cell
// (docs/scale-out.md §3, §10).
#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <vector>

#include "matpoint/grid/owned_nodes.hpp"
#include "matpoint/parallel/box_partition.hpp"

namespace {

using namespace matpoint;

template <int D>
Grid<D> grid_of(const std::array<int, D>& cells) {
  return Grid<D>(Vec<D>::Zero(), Vec<D>::Ones(), cells, 0);
}

template <int D>
IndexBox<D> box(const std::array<int, D>& begin, const std::array<int, D>& end) {
  return IndexBox<D>{begin, end};
}

/// One particle in every cell.
template <int D>
std::vector<std::array<int, D>> every_cell(const Grid<D>& grid) {
  std::vector<std::array<int, D>> cells;
  box<D>({}, grid.cells).for_each([&](const std::array<int, D>& c) { cells.push_back(c); });
  return cells;
}

template <int D>
void expect_one_owner_per_cell_and_node(const Grid<D>& grid, int ranks) {
  const auto boxes = BoxPartition<D>::balanced(grid, every_cell(grid), ranks);
  IndexBox<D> nodes;
  for (int a = 0; a < D; ++a) nodes.end[a] = grid.cells[a] + 1;
  box<D>({}, grid.cells).for_each([&](const std::array<int, D>& c) {
    int holders = 0;
    for (int r = 0; r < ranks; ++r) holders += boxes.cells_of(r).contains(c) ? 1 : 0;
    EXPECT_EQ(holders, 1) << ranks << " ranks, a cell";
    EXPECT_TRUE(boxes.cells_of(boxes.owner_of_cell(c)).contains(c));
  });
  nodes.for_each([&](const std::array<int, D>& n) {
    int holders = 0;
    for (int r = 0; r < ranks; ++r) holders += boxes.owned_nodes_of(r).contains(n) ? 1 : 0;
    EXPECT_EQ(holders, 1) << ranks << " ranks, a node";
  });
}

TEST(BoxPartition, EveryCellAndNodeHasOneOwner) {
  for (const int ranks : {1, 2, 3, 4, 6, 7})
    expect_one_owner_per_cell_and_node<2>(grid_of<2>({150, 45}), ranks);
  for (const int ranks : {1, 2, 3, 5, 8})
    expect_one_owner_per_cell_and_node<3>(grid_of<3>({70, 20, 20}), ranks);
}

// A layer one brick wide along x is cut into slabs along y. 100 particles in brick layer 0
// (cells 0-7), 100 spread over layers 1-4: two ranks split between layer 0 and the rest; the
// uniform layout splits at its middle layer boundary.
TEST(BoxPartition, ALayerOneBrickWideIsCutIntoSlabsWhereHalfTheParticlesLie) {
  const Grid<2> grid = grid_of<2>({8, 40});
  std::vector<std::array<int, 2>> cells;
  for (int k = 0; k < 100; ++k) cells.push_back({0, k % 8});
  for (int k = 0; k < 100; ++k) cells.push_back({0, 8 + k % 32});
  const auto two = BoxPartition<2>::balanced(grid, cells, 2);
  EXPECT_EQ(two.cells_of(0), box<2>({0, 0}, {8, 8}));
  EXPECT_EQ(two.cells_of(1), box<2>({0, 8}, {8, 40}));
  const auto halves = BoxPartition<2>::balanced(grid_of<2>({8, 32}), every_cell(grid_of<2>({8, 32})), 2);
  EXPECT_EQ(halves.cells_of(0), box<2>({0, 0}, {8, 16}));
}

// A cube of 32^3 cells is 1 x 4 x 4 bricks: four ranks take 2 x 2 boxes (z cut first: y and z
// have 4 bricks each, the last of equals; then each half's y, now the longer); every rank stores
// the nodes its cells' stencils reach, and diagonal neighbours share the nodes along their edge.
TEST(BoxPartition, ACubeOnFourRanksIsCutIntoTwoByTwoBoxes) {
  const Grid<3> grid = grid_of<3>({32, 32, 32});
  const auto boxes = BoxPartition<3>::balanced(grid, every_cell(grid), 4);
  EXPECT_EQ(boxes.cells_of(0), box<3>({0, 0, 0}, {32, 16, 16}));
  EXPECT_EQ(boxes.cells_of(1), box<3>({0, 16, 0}, {32, 32, 16}));
  EXPECT_EQ(boxes.cells_of(2), box<3>({0, 0, 16}, {32, 16, 32}));
  EXPECT_EQ(boxes.cells_of(3), box<3>({0, 16, 16}, {32, 32, 32}));
  EXPECT_EQ(boxes.owned_nodes_of(0), box<3>({0, 0, 0}, {33, 16, 16}));
  EXPECT_EQ(boxes.owned_nodes_of(3), box<3>({0, 16, 16}, {33, 33, 33}));
  // Cells 0-15 reach nodes -1 .. 17 (clamped to 0); cells 16-31 nodes 15 .. 33 (clamped to 32).
  EXPECT_EQ(boxes.stored_nodes_of(0, 1, 2), box<3>({0, 0, 0}, {33, 18, 18}));
  EXPECT_EQ(boxes.stored_nodes_of(3, 1, 2), box<3>({0, 15, 15}, {33, 33, 33}));
  EXPECT_EQ(boxes.shared_nodes_of(0, 3, 1, 2), box<3>({0, 15, 15}, {33, 18, 18}));
  EXPECT_EQ(boxes.shared_nodes_of(0, 1, 1, 2), box<3>({0, 15, 0}, {33, 18, 18}));
}

TEST(BoxPartition, ARankWithoutCellsStoresNoNode) {
  const Grid<2> grid = grid_of<2>({8, 40});  // 5 bricks: 3 of 8 ranks get none
  const auto boxes = BoxPartition<2>::balanced(grid, every_cell(grid), 8);
  int empty = 0;
  for (int r = 0; r < 8; ++r) empty += boxes.stored_nodes_of(r, 1, 2).empty() ? 1 : 0;
  EXPECT_EQ(empty, 3);
}

// The boxes from per-brick counts (a re-partition's one reduction) are the boxes from the
// particles' cells, and stored boxes (ints(), as a checkpoint keeps them) give the same owners.
TEST(BoxPartition, CountsPerBrickAndStoredBoxesGiveTheSamePartition) {
  const Grid<2> grid = grid_of<2>({130, 40});  // 3 x 5 bricks
  std::vector<std::array<int, 2>> cells;
  std::vector<std::size_t> count(15, 0);
  for (int k = 0; k < 400; ++k) {
    const std::array<int, 2> c{(k * 37) % 130, (k * k) % 40};
    cells.push_back(c);
    ++count[static_cast<std::size_t>((c[0] / 64) + 3 * (c[1] / 8))];
  }
  for (const int ranks : {1, 2, 3, 5, 6}) {
    const auto from_cells = BoxPartition<2>::balanced(grid, cells, ranks);
    EXPECT_TRUE(BoxPartition<2>::balanced(grid, count, ranks) == from_cells) << ranks << " ranks";
    const auto restored = BoxPartition<2>::from_ints(grid, from_cells.ints());
    EXPECT_TRUE(restored == from_cells);
    for (const auto& c : cells) EXPECT_EQ(restored.owner_of_cell(c), from_cells.owner_of_cell(c));
  }
  // Layers of 7, 30, 2, 0, 11 particles (one brick wide): of 50, the cut after layer 1 leaves 37
  // below, 12 from half; after layer 0 it would leave 7 (18 from half).
  const Grid<2> layers = grid_of<2>({8, 40});
  EXPECT_EQ(BoxPartition<2>::balanced(layers, std::vector<std::size_t>{7, 30, 2, 0, 11}, 2).cells_of(0),
            box<2>({0, 0}, {8, 16}));
}

TEST(BoxPartition, StoredBoxesThatAreNoPartitionAreRefused) {
  const Grid<2> grid = grid_of<2>({130, 40});  // 3 x 5 bricks
  EXPECT_THROW(BoxPartition<2>::from_ints(grid, {0, 0, 3, 3, 0, 2, 3, 5}), std::invalid_argument)
      << "overlapping boxes";
  EXPECT_THROW(BoxPartition<2>::from_ints(grid, {0, 0, 3, 2, 0, 3, 3, 5}), std::invalid_argument)
      << "a brick layer in no box";
  EXPECT_THROW(BoxPartition<2>::from_ints(grid, {0, 0, 4, 5}), std::invalid_argument) << "outside the grid";
  EXPECT_THROW(BoxPartition<2>::from_ints(grid, {0, 0, 3}), std::invalid_argument) << "not 4 per rank";
  EXPECT_NO_THROW(BoxPartition<2>::from_ints(grid, {0, 0, 3, 2, 0, 2, 3, 5, 0, 0, 0, 0}));
}

// A rank's owned nodes in its window: one run of flat indices per row, rows that join merged.
TEST(OwnedNodes, ABoxOfAWindowIsItsRowsAndWholeRowsMerge) {
  const Grid<2> whole = grid_of<2>({10, 20});
  const Grid<2> window = whole.window(box<2>({2, 3}, {9, 8}));  // 7 x 5 nodes
  EXPECT_EQ(window.node_count, 35);
  const OwnedNodes owned = OwnedNodes::box(window, box<2>({4, 5}, {6, 30}));  // x 4-5, y 5-7
  std::vector<std::pair<Index, Index>> runs;
  owned.for_each_run(window.node_count, [&](Index b, Index e) { runs.push_back({b, e}); });
  EXPECT_EQ(runs, (std::vector<std::pair<Index, Index>>{{16, 18}, {23, 25}, {30, 32}}));
  for (Index n = 0; n < window.node_count; ++n) {
    const auto ijk = window.node_coords(n);
    EXPECT_EQ(owned.contains(n), ijk[0] >= 4 && ijk[0] < 6 && ijk[1] >= 5) << n;
  }
  const OwnedNodes rows = OwnedNodes::box(window, box<2>({0, 4}, {11, 6}));
  runs.clear();
  rows.for_each_run(window.node_count, [&](Index b, Index e) { runs.push_back({b, e}); });
  EXPECT_EQ(runs, (std::vector<std::pair<Index, Index>>{{7, 21}}));
  EXPECT_TRUE(OwnedNodes().all());
  EXPECT_TRUE(OwnedNodes().contains(123456789));
}

// Grid::window (docs/scale-out.md §2): a rank stores a box of nodes, here the node layers [3, 7) along y;
// each stored node keeps its coordinates and position, the numbering is x fastest from 0, and a
// value carried from one window to another by node lands on the same node. Expected values from
// the definition: a window of layers [3, 7) of a 10 x 20 grid stores 11 x 4 nodes.
TEST(GridWindow, StoresTheLayersAndKeepsEveryNodesCoordinatesAndPosition) {
  const Grid<2> whole(Vec<2>(-1.0, 2.0), Vec<2>(0.5, 0.25), {10, 20}, 0);
  const Grid<2> window = whole.window(box<2>({0, 3}, {11, 7}));
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
  const Grid<2> above = whole.window(box<2>({0, 5}, {11, 21}));
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
  const Grid<2> clamped = ghosted.window(box<2>({-9, -5}, {50, 50}));
  EXPECT_EQ(clamped.node_count, ghosted.node_count);
  EXPECT_EQ(clamped.first[1], -1);
}

}  // namespace
