// Particles binned by grid cell (a counting sort into compressed rows), the neighbour search of the
// MLS reconstructions: the particles within a radius of a point lie in the cells that the box
// [x - r, x + r] overlaps. The bins cover a box of cells: the whole grid, or a rank's window and
// the band of ghost particles around it (docs/scale-out.md).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/index_box.hpp"

namespace matpoint {

template <int D>
class ParticleBins {
 public:
  /// Every cell of the grid.
  static IndexBox<D> all_cells(const Grid<D>& grid) {
    IndexBox<D> box;
    box.end = grid.cells;
    return box;
  }

  /// Bins the positions by the (clamped) user cell of the grid; O(particles + cells). `cells`: the
  /// cells the bins cover, where every position must lie.
  void build(const Grid<D>& grid, const std::vector<Vec<D>>& x) { build(grid, x, all_cells(grid)); }
  void build(const Grid<D>& grid, const std::vector<Vec<D>>& x, const IndexBox<D>& cells) {
    grid_ = &grid;
    box_ = cells;
    Index count = 1;
    for (int a = 0; a < D; ++a) {
      stride_[a] = count;
      count *= std::max(0, box_.end[a] - box_.begin[a]);
    }
    start_.assign(count + 1, 0);
    cell_.resize(x.size());
    for (std::size_t p = 0; p < x.size(); ++p) {
      const auto c = grid.cell_coords(x[p]);
      if (!box_.contains(c)) throw std::logic_error("particle bins: a position outside the binned cells");
      cell_[p] = local_index(c);
      ++start_[cell_[p] + 1];
    }
    for (Index c = 0; c < count; ++c) start_[c + 1] += start_[c];
    order_.resize(x.size());
    std::vector<Index> next(start_.begin(), start_.end() - 1);
    for (std::size_t p = 0; p < x.size(); ++p) order_[next[cell_[p]]++] = static_cast<Index>(p);
  }

  /// Calls fn(p) for every particle in the cells that the open box (x - r h, x + r h) overlaps (r
  /// in cells): every particle closer than r h along each axis, and no whole cell beyond.
  template <class Fn>
  void for_each_near(const Vec<D>& x, double r, Fn&& fn) const {
    IndexBox<D> near;
    for (int a = 0; a < D; ++a) {
      const double s = (x[a] - grid_->origin[a]) / grid_->h[a];
      near.begin[a] = std::max(box_.begin[a], floor_to_int(s - r));
      near.end[a] = std::min(box_.end[a], -floor_to_int(-(s + r)));  // cell k starts at k
      if (near.begin[a] >= near.end[a]) return;
    }
    IndexBox<D> rows = near;  // the cells of a row along x are contiguous
    rows.end[0] = rows.begin[0] + 1;
    const Index length = near.end[0] - near.begin[0];
    rows.for_each([&](const std::array<int, D>& c) {
      const Index first = local_index(c);
      visit(first, first + length - 1, fn);
    });
  }

  /// The particles of one cell (flat user-cell index of the whole grid, x fastest); none for a
  /// cell outside the binned box (a rank without cells bins none).
  template <class Fn>
  void for_each_in_cell(Index c, Fn&& fn) const {
    std::array<int, D> ijk{};
    for (int a = 0; a < D; ++a) {
      ijk[a] = static_cast<int>(c % grid_->cells[a]);
      c /= grid_->cells[a];
    }
    if (!box_.contains(ijk)) return;
    const Index local = local_index(ijk);
    visit(local, local, fn);
  }

 private:
  [[nodiscard]] Index local_index(const std::array<int, D>& c) const {
    Index n = 0;
    for (int a = 0; a < D; ++a) n += static_cast<Index>(c[a] - box_.begin[a]) * stride_[a];
    return n;
  }

  template <class Fn>
  void visit(Index first_cell, Index last_cell, Fn& fn) const {  // the cells of a row are contiguous
    for (Index k = start_[first_cell]; k < start_[last_cell + 1]; ++k) fn(order_[k]);
  }

  const Grid<D>* grid_ = nullptr;
  IndexBox<D> box_;                // the binned cells
  std::array<Index, D> stride_{};  // of the box's local cell index, x fastest
  std::vector<Index> start_;       // start_[c] .. start_[c + 1]: the entries of local cell c in order_
  std::vector<Index> order_;       // particle indices by cell
  std::vector<Index> cell_;        // scratch: each particle's local cell
};

}  // namespace matpoint
