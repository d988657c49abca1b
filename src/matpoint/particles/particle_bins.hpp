// Particles binned by grid cell (a counting sort into compressed rows), the neighbour search of the
// MLS reconstructions: the particles within a radius of a point lie in the cells that the box
// [x - r, x + r] overlaps.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"

namespace matpoint {

template <int D>
class ParticleBins {
 public:
  /// Bins the positions by the (clamped) user cell of the grid; O(particles + cells).
  void build(const Grid<D>& grid, const std::vector<Vec<D>>& x) {
    grid_ = &grid;
    Index cells = 1;
    for (int a = 0; a < D; ++a) cells *= grid.cells[a];
    start_.assign(cells + 1, 0);
    cell_.resize(x.size());
    for (std::size_t p = 0; p < x.size(); ++p) {
      cell_[p] = grid.cell_index(x[p]);
      ++start_[cell_[p] + 1];
    }
    for (Index c = 0; c < cells; ++c) start_[c + 1] += start_[c];
    order_.resize(x.size());
    std::vector<Index> next(start_.begin(), start_.end() - 1);
    for (std::size_t p = 0; p < x.size(); ++p) order_[next[cell_[p]]++] = static_cast<Index>(p);
  }

  /// Calls fn(p) for every particle in the cells that the open box (x - r h, x + r h) overlaps (r
  /// in cells): every particle closer than r h along each axis, and no whole cell beyond.
  template <class Fn>
  void for_each_near(const Vec<D>& x, double r, Fn&& fn) const {
    std::array<int, D> lo{}, hi{};
    for (int a = 0; a < D; ++a) {
      const double s = (x[a] - grid_->origin[a]) / grid_->h[a];
      lo[a] = std::max(0, floor_to_int(s - r));
      hi[a] = std::min(grid_->cells[a] - 1, -floor_to_int(-(s + r)) - 1);  // cell k starts at k
      if (lo[a] > hi[a]) return;
    }
    if constexpr (D == 1) {
      visit(lo[0], hi[0], fn);
    } else if constexpr (D == 2) {
      for (int j = lo[1]; j <= hi[1]; ++j)
        visit(lo[0] + j * grid_->cells[0], hi[0] + j * grid_->cells[0], fn);
    } else {
      for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j) {
          const Index row = (static_cast<Index>(k) * grid_->cells[1] + j) * grid_->cells[0];
          visit(row + lo[0], row + hi[0], fn);
        }
    }
  }

  /// The particles of one cell (flat user-cell index).
  template <class Fn>
  void for_each_in_cell(Index c, Fn&& fn) const {
    visit(c, c, fn);
  }

 private:
  template <class Fn>
  void visit(Index first_cell, Index last_cell, Fn& fn) const {  // the cells of a row are contiguous
    for (Index k = start_[first_cell]; k < start_[last_cell + 1]; ++k) fn(order_[k]);
  }

  const Grid<D>* grid_ = nullptr;
  std::vector<Index> start_;  // start_[c] .. start_[c + 1]: the entries of cell c in order_
  std::vector<Index> order_;  // particle indices by cell
  std::vector<Index> cell_;   // scratch: each particle's cell
};

}  // namespace matpoint
