// Particles binned by grid cell (a counting sort into compressed rows), the neighbour search of the
// MLS reconstructions: the particles within a radius of a point lie in the cells that the box
// [x - r, x + r] overlaps. The bins cover the cell layers [begin, end) along the last axis: the
// whole grid, or a rank's window and the band of ghost particles around it (docs/scale-out.md).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"

namespace matpoint {

template <int D>
class ParticleBins {
 public:
  /// Bins the positions by the (clamped) user cell of the grid; O(particles + cells). `layers`:
  /// the cell layers [begin, end) along the last axis that the bins cover (end < 0: to the last),
  /// where every position must lie.
  void build(const Grid<D>& grid, const std::vector<Vec<D>>& x, std::pair<int, int> layers = {0, -1}) {
    grid_ = &grid;
    first_layer_ = layers.first;
    end_layer_ = layers.second < 0 ? grid.cells[D - 1] : layers.second;
    Index per_layer = 1;
    for (int a = 0; a + 1 < D; ++a) per_layer *= grid.cells[a];
    first_cell_ = first_layer_ * per_layer;
    const Index cells = (end_layer_ - first_layer_) * per_layer;
    start_.assign(cells + 1, 0);
    cell_.resize(x.size());
    for (std::size_t p = 0; p < x.size(); ++p) {
      cell_[p] = grid.cell_index(x[p]) - first_cell_;
      if (cell_[p] < 0 || cell_[p] >= cells)
        throw std::logic_error("particle bins: a position outside the layers");
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
      const bool last = a == D - 1;
      lo[a] = std::max(last ? first_layer_ : 0, floor_to_int(s - r));
      hi[a] = std::min((last ? end_layer_ : grid_->cells[a]) - 1,
                       -floor_to_int(-(s + r)) - 1);  // cell k starts at k
      if (lo[a] > hi[a]) return;
    }
    if constexpr (D == 1) {
      visit(lo[0] - first_cell_, hi[0] - first_cell_, fn);
    } else if constexpr (D == 2) {
      for (int j = lo[1]; j <= hi[1]; ++j) {
        const Index row = static_cast<Index>(j) * grid_->cells[0] - first_cell_;
        visit(row + lo[0], row + hi[0], fn);
      }
    } else {
      for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j) {
          const Index row = (static_cast<Index>(k) * grid_->cells[1] + j) * grid_->cells[0] - first_cell_;
          visit(row + lo[0], row + hi[0], fn);
        }
    }
  }

  /// The particles of one cell (flat user-cell index of the whole grid, in the layers).
  template <class Fn>
  void for_each_in_cell(Index c, Fn&& fn) const {
    visit(c - first_cell_, c - first_cell_, fn);
  }

 private:
  template <class Fn>
  void visit(Index first_cell, Index last_cell, Fn& fn) const {  // the cells of a row are contiguous
    for (Index k = start_[first_cell]; k < start_[last_cell + 1]; ++k) fn(order_[k]);
  }

  const Grid<D>* grid_ = nullptr;
  int first_layer_ = 0, end_layer_ = 0;  // the cell layers [first, end) along the last axis
  Index first_cell_ = 0;                 // the flat index of the first layer's first cell
  std::vector<Index> start_;             // start_[c] .. start_[c + 1]: the entries of cell c in order_
  std::vector<Index> order_;             // particle indices by cell
  std::vector<Index> cell_;              // scratch: each particle's cell
};

}  // namespace matpoint
