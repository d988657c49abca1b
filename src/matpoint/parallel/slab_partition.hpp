// Which rank owns which cells and nodes in a decomposed explicit run (issue 23; docs/scale-out.md §2).
//
// The grid's bricks (grid/brick_schedule.hpp) are cut into slabs of whole brick layers along the
// last axis (y in 2-D, z in 3-D): rank r owns the cells of brick layers [first_[r], first_[r + 1]),
// the particles in them and the lowest node of each of its cells (the last rank with cells also the
// top node layer), and stores every node its particles' stencils may reach. Along the last axis the
// bricks are 8 cells thick, so the cut can follow the particles finely, and the slowest node index
// makes a rank's owned nodes one contiguous range of flat indices. (The design's first sketch cut
// along x; the bricks are 64 (2-D) or 32 (3-D) cells long in x, too coarse for 4 ranks on a
// verification grid of 100 cells.)
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"

namespace matpoint {

template <int D>
class SlabPartition {
 public:
  static constexpr int kAxis = D - 1;

  /// One rank owning every cell.
  SlabPartition() = default;

  /// Cuts the brick layers among `ranks` so that each holds about the same number of the
  /// particles whose cells are `cells` (every rank computes the same cut from the same particles).
  static SlabPartition balanced(const Grid<D>& grid, const std::vector<std::array<int, D>>& cells,
                                int ranks) {
    std::vector<std::size_t> count(static_cast<std::size_t>(BrickSchedule<D>::bricks_along(grid, kAxis)), 0);
    for (const auto& c : cells) ++count[static_cast<std::size_t>(layer_of(c[kAxis]))];
    return balanced(grid, count, ranks);
  }

  /// The same cut from the particle count per brick layer (`count`, summed over the ranks: a
  /// re-partition computes it from one reduction, docs/scale-out.md §10).
  static SlabPartition balanced(const Grid<D>& grid, const std::vector<std::size_t>& count, int ranks) {
    const int layers = BrickSchedule<D>::bricks_along(grid, kAxis);
    std::size_t total = 0;
    for (const std::size_t n : count) total += n;
    // Rank r ends at the first layer boundary where the particles below reach (r + 1) n / P.
    std::vector<int> first(static_cast<std::size_t>(ranks) + 1, layers);
    first[0] = 0;
    std::size_t below = 0;
    int layer = 0;
    for (int r = 0; r + 1 < ranks; ++r) {
      const std::size_t target = (total * static_cast<std::size_t>(r + 1) + ranks - 1) / ranks;
      while (layer < layers && below + count[static_cast<std::size_t>(layer)] <= target) {
        below += count[static_cast<std::size_t>(layer)];
        ++layer;
      }
      // At least one layer per rank while layers remain, so that no rank is skipped needlessly.
      if (layer == first[r] && layer < layers) below += count[static_cast<std::size_t>(layer++)];
      first[static_cast<std::size_t>(r) + 1] = layer;
    }
    return from_first_layers(grid, std::move(first));
  }

  /// The partition whose rank r owns the brick layers [first[r], first[r + 1]) (a checkpoint
  /// stores `first_layers()`; first.front() == 0, first.back() == the layer count, non-decreasing).
  static SlabPartition from_first_layers(const Grid<D>& grid, std::vector<int> first) {
    SlabPartition out;
    out.cells_ = grid.cells[kAxis];
    out.first_ = std::move(first);
    const int layers = BrickSchedule<D>::bricks_along(grid, kAxis);
    out.owner_.assign(static_cast<std::size_t>(layers), 0);
    for (int r = 0; r < out.ranks(); ++r)
      for (int l = out.first_[r]; l < out.first_[r + 1]; ++l) out.owner_[static_cast<std::size_t>(l)] = r;
    return out;
  }

  /// Rank r's first brick layer, for r = 0..ranks() (the last entry: the layer count).
  [[nodiscard]] const std::vector<int>& first_layers() const { return first_; }

  [[nodiscard]] int ranks() const { return static_cast<int>(first_.size()) - 1; }
  /// The brick layer of a cell coordinate along the cut axis.
  [[nodiscard]] static int layer_of(int cell) { return cell >> BrickSchedule<D>::brick_shift(kAxis); }
  [[nodiscard]] int owner_of_layer(int layer) const {
    return owner_.empty() ? 0 : owner_[static_cast<std::size_t>(layer)];
  }
  [[nodiscard]] int owner_of_cell(const std::array<int, D>& cell) const {
    return owner_of_layer(layer_of(cell[kAxis]));
  }

  /// The cell layers [begin, end) along the cut axis that rank r owns (empty: begin == end).
  [[nodiscard]] std::pair<int, int> cells_of(int r) const {
    if (owner_.empty()) return {0, cells_};
    const int shift = BrickSchedule<D>::brick_shift(kAxis);
    return {std::min(first_[r] << shift, cells_), std::min(first_[r + 1] << shift, cells_)};
  }
  /// The node layers [begin, end) along the cut axis that rank r owns: the lowest node of each
  /// of its cells, and the top node layer when its cells reach the top.
  [[nodiscard]] std::pair<int, int> owned_nodes_of(int r) const {
    const auto [begin, end] = cells_of(r);
    return {begin, end == cells_ && begin < end ? end + 1 : end};
  }
  /// The node layers [begin, end) that rank r stores: those its particles' stencils reach, when a
  /// stencil reaches `below` node layers below a particle's cell and `above` above its lowest node.
  [[nodiscard]] std::pair<int, int> stored_nodes_of(int r, int below, int above) const {
    const auto [begin, end] = cells_of(r);
    if (begin == end) return {0, 0};
    return {std::max(0, begin - below), std::min(cells_ + 1, end + above)};
  }
  /// The node layers [begin, end) that ranks r and s both store under the same reach (empty:
  /// begin >= end): where the hand-off passes sums between them and where both fit contact normals.
  [[nodiscard]] std::pair<int, int> shared_nodes_of(int r, int s, int below, int above) const {
    const auto [r_begin, r_end] = stored_nodes_of(r, below, above);
    const auto [s_begin, s_end] = stored_nodes_of(s, below, above);
    return {std::max(r_begin, s_begin), std::min(r_end, s_end)};
  }

 private:
  std::vector<int> first_;  // rank r: brick layers [first_[r], first_[r + 1]) along kAxis
  std::vector<int> owner_;  // by brick layer
  int cells_ = 0;           // cells along kAxis (set by balanced)
};

}  // namespace matpoint
