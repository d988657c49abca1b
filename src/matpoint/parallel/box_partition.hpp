// Which rank owns which cells and nodes in a decomposed explicit run (issue 23; docs/scale-out.md
// §2, §10).
//
// Each rank owns an axis-aligned box of the grid's bricks (grid/brick_schedule.hpp): the cells in
// them, the particles in those cells and the lowest node of each of its cells (along an axis where
// its box reaches the grid's end, also the last node layer), and stores every node its particles'
// stencils may reach. The boxes come from a recursive coordinate bisection of the particle counts
// per brick (balanced()): the ranks are split in two, the box is cut along the axis with the most
// bricks at the brick boundary that leaves the two halves particles in proportion to their ranks,
// and each half is cut again. A rod or a thin layer is then cut into slabs; a cube into boxes, so
// that it can use more ranks than it has brick layers along one axis (bench/scaling.md).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/index_box.hpp"

namespace matpoint {

template <int D>
class BoxPartition {
 public:
  /// One rank owning every brick of the grid.
  static BoxPartition whole(const Grid<D>& grid) {
    BoxPartition out = of_grid(grid);
    IndexBox<D> all;
    all.end = out.bricks_;
    out.boxes_.assign(1, all);
    return out;
  }

  /// The boxes that give each of `ranks` about the same number of the particles whose cells are
  /// `cells` (every rank computes the same boxes from the same particles).
  static BoxPartition balanced(const Grid<D>& grid, const std::vector<std::array<int, D>>& cells, int ranks) {
    const BoxPartition layout = whole(grid);
    std::vector<std::size_t> count(layout.brick_count(), 0);
    for (const auto& c : cells) ++count[static_cast<std::size_t>(layout.brick_of_cell(c))];
    return balanced(grid, count, ranks);
  }

  /// The same boxes from the particle count per brick (`count`, by brick_of_cell, summed over the
  /// ranks: a re-partition computes it from one reduction, docs/scale-out.md §10).
  static BoxPartition balanced(const Grid<D>& grid, const std::vector<std::size_t>& count, int ranks) {
    BoxPartition out = of_grid(grid);
    if (count.size() != out.owner_.size())
      throw std::logic_error("box partition: " + std::to_string(count.size()) + " brick counts for " +
                             std::to_string(out.owner_.size()) + " bricks");
    out.boxes_.assign(static_cast<std::size_t>(ranks), IndexBox<D>{});
    IndexBox<D> all;
    all.end = out.bricks_;
    out.bisect(all, 0, ranks, count);
    out.assign_owners();
    return out;
  }

  /// The partition whose rank r owns the bricks of boxes[r] (a checkpoint stores them, as ints():
  /// begin and end per axis, rank after rank). Throws std::invalid_argument unless the boxes lie in
  /// the grid and hold every brick exactly once.
  static BoxPartition from_ints(const Grid<D>& grid, const std::vector<int>& ints) {
    BoxPartition out = of_grid(grid);
    if (ints.empty() || ints.size() % (2 * D) != 0)
      throw std::invalid_argument(std::to_string(ints.size()) + " values, not 2 x " + std::to_string(D) +
                                  " per rank");
    for (std::size_t k = 0; k < ints.size(); k += 2 * D) {
      IndexBox<D> box;
      for (int a = 0; a < D; ++a) box.begin[a] = ints[k + a], box.end[a] = ints[k + D + a];
      for (int a = 0; a < D; ++a)
        if (!box.empty() && (box.begin[a] < 0 || box.end[a] > out.bricks_[a]))
          throw std::invalid_argument("a box outside the grid's bricks");
      out.boxes_.push_back(box.empty() ? IndexBox<D>{} : box);
    }
    std::vector<int> holders(out.owner_.size(), 0);
    for (const auto& box : out.boxes_) box.for_each([&](const auto& b) { ++holders[out.brick_index(b)]; });
    if (std::any_of(holders.begin(), holders.end(), [](int n) { return n != 1; }))
      throw std::invalid_argument("boxes that do not hold every brick exactly once");
    out.assign_owners();
    return out;
  }
  /// The boxes as from_ints() reads them.
  [[nodiscard]] std::vector<int> ints() const {
    std::vector<int> out;
    for (const auto& box : boxes_) {
      out.insert(out.end(), box.begin.begin(), box.begin.end());
      out.insert(out.end(), box.end.begin(), box.end.end());
    }
    return out;
  }
  friend bool operator==(const BoxPartition& a, const BoxPartition& b) { return a.boxes_ == b.boxes_; }

  [[nodiscard]] int ranks() const { return static_cast<int>(boxes_.size()); }
  /// Rank r's box of bricks (empty for a rank without cells).
  [[nodiscard]] const IndexBox<D>& bricks_of(int r) const { return boxes_[static_cast<std::size_t>(r)]; }
  /// The bricks of the grid (the length of the count that balanced() takes).
  [[nodiscard]] std::size_t brick_count() const { return owner_.size(); }
  /// The flat index of the brick of a cell (x fastest), as balanced() counts it.
  [[nodiscard]] Index brick_of_cell(const std::array<int, D>& cell) const {
    std::array<int, D> b{};
    for (int a = 0; a < D; ++a) b[a] = cell[a] >> BrickSchedule<D>::brick_shift(a);
    return brick_index(b);
  }
  /// The flat index of the brick of coordinates b (x fastest).
  [[nodiscard]] Index brick_index(const std::array<int, D>& b) const {
    Index n = 0, stride = 1;
    for (int a = 0; a < D; ++a) {
      n += static_cast<Index>(b[a]) * stride;
      stride *= bricks_[a];
    }
    return n;
  }
  [[nodiscard]] int owner_of_brick(Index brick) const { return owner_[static_cast<std::size_t>(brick)]; }
  [[nodiscard]] int owner_of_cell(const std::array<int, D>& cell) const {
    return owner_of_brick(brick_of_cell(cell));
  }

  /// The cells rank r owns.
  [[nodiscard]] IndexBox<D> cells_of(int r) const {
    const IndexBox<D>& bricks = bricks_of(r);
    if (bricks.empty()) return {};
    IndexBox<D> out;
    for (int a = 0; a < D; ++a) {
      const int shift = BrickSchedule<D>::brick_shift(a);
      out.begin[a] = std::min(bricks.begin[a] << shift, cells_[a]);
      out.end[a] = std::min(bricks.end[a] << shift, cells_[a]);
    }
    return out;
  }
  /// The nodes rank r owns: the lowest node of each of its cells, and along an axis where its
  /// cells reach the grid's end also the last node layer.
  [[nodiscard]] IndexBox<D> owned_nodes_of(int r) const {
    IndexBox<D> out = cells_of(r);
    if (out.empty()) return {};
    for (int a = 0; a < D; ++a)
      if (out.end[a] == cells_[a]) ++out.end[a];
    return out;
  }
  /// The nodes rank r stores: those its particles' stencils reach, when a stencil reaches `below`
  /// nodes below a particle's cell and `above` above its lowest node along every axis.
  [[nodiscard]] IndexBox<D> stored_nodes_of(int r, int below, int above) const {
    IndexBox<D> out = cells_of(r);
    if (out.empty()) return {};
    for (int a = 0; a < D; ++a) {
      out.begin[a] = std::max(-ghost_, out.begin[a] - below);
      out.end[a] = std::min(cells_[a] + 1 + ghost_, out.end[a] + above);
    }
    return out;
  }
  /// The nodes that ranks r and s both store under the same reach (possibly empty): where the
  /// hand-off passes sums between them and where both fit contact normals.
  [[nodiscard]] IndexBox<D> shared_nodes_of(int r, int s, int below, int above) const {
    return stored_nodes_of(r, below, above).intersection(stored_nodes_of(s, below, above));
  }

 private:
  BoxPartition() = default;  // see whole(), balanced() and from_ints()

  /// The grid's bricks, no ranks yet.
  static BoxPartition of_grid(const Grid<D>& grid) {
    BoxPartition out;
    Index count = 1;
    for (int a = 0; a < D; ++a) {
      out.cells_[a] = grid.cells[a];
      out.bricks_[a] = BrickSchedule<D>::bricks_along(grid, a);
      count *= out.bricks_[a];
    }
    out.ghost_ = grid.ghost;
    out.owner_.assign(static_cast<std::size_t>(count), 0);
    return out;
  }

  /// Gives the ranks [first, end) the bricks of `box`: split the ranks in two (the first half
  /// floor(P / 2)), cut the box along the axis with the most bricks (the last of equals) at the
  /// brick boundary where the particles before it come closest to their share, and recurse.
  void bisect(const IndexBox<D>& box, int first, int end, const std::vector<std::size_t>& count) {
    const int P = end - first;
    int axis = D - 1;
    for (int a = D - 2; a >= 0; --a)
      if (box.end[a] - box.begin[a] > box.end[axis] - box.begin[axis]) axis = a;
    if (P == 1 || box.end[axis] - box.begin[axis] < 2) {  // one rank, or a single brick: the first takes it
      boxes_[static_cast<std::size_t>(first)] = box;
      return;
    }
    const int P1 = P / 2;
    std::vector<std::size_t> slice(static_cast<std::size_t>(box.end[axis] - box.begin[axis]), 0);
    std::size_t total = 0;
    box.for_each([&](const std::array<int, D>& b) {
      const std::size_t n = count[static_cast<std::size_t>(brick_index(b))];
      slice[static_cast<std::size_t>(b[axis] - box.begin[axis])] += n;
      total += n;
    });
    // The cut k (bricks [begin, k) to the first half) with |P below - P1 total| least, first of equals.
    std::size_t below = 0;
    int cut = box.begin[axis] + 1;
    std::size_t best = 0;
    for (int k = box.begin[axis] + 1; k < box.end[axis]; ++k) {
      below += slice[static_cast<std::size_t>(k - 1 - box.begin[axis])];
      const std::size_t lhs = below * static_cast<std::size_t>(P), rhs = total * static_cast<std::size_t>(P1);
      const std::size_t miss = lhs > rhs ? lhs - rhs : rhs - lhs;
      if (k == box.begin[axis] + 1 || miss < best) best = miss, cut = k;
    }
    IndexBox<D> lower = box, upper = box;
    lower.end[axis] = cut;
    upper.begin[axis] = cut;
    bisect(lower, first, first + P1, count);
    bisect(upper, first + P1, end, count);
  }

  void assign_owners() {
    for (int r = 0; r < ranks(); ++r)
      boxes_[static_cast<std::size_t>(r)].for_each(
          [&](const auto& b) { owner_[static_cast<std::size_t>(brick_index(b))] = r; });
  }

  std::vector<IndexBox<D>> boxes_;  // by rank, in bricks
  std::vector<int> owner_;          // by flat brick index
  std::array<int, D> cells_{}, bricks_{};
  int ghost_ = 0;
};

}  // namespace matpoint
