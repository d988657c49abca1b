// Uniform Cartesian background grid: geometry and node numbering.
#pragma once

#include <array>
#include <cmath>

#include "matpoint/core/types.hpp"

namespace matpoint {

/// Nodes sit at origin + i * h, i = -ghost .. cells + ghost per direction. Ghost layers lie
/// outside the user's domain and exist only so that wide bases (B-splines) have every node they
/// need next to the domain edge; boundary conditions on a face apply to its ghost nodes too.
template <int D>
struct Grid {
  Vec<D> origin = Vec<D>::Zero();
  Vec<D> h = Vec<D>::Ones();
  std::array<int, D> cells{};
  int ghost = 0;
  std::array<int, D> nodes{};     // per direction, ghosts included
  std::array<Index, D> stride{};  // flat node index = sum (i_a + ghost) * stride_a
  Index node_count = 0;

  Grid() = default;
  Grid(const Vec<D>& origin_, const Vec<D>& h_, const std::array<int, D>& cells_, int ghost_)
      : origin(origin_), h(h_), cells(cells_), ghost(ghost_) {
    Index s = 1;
    for (int a = 0; a < D; ++a) {
      nodes[a] = cells[a] + 1 + 2 * ghost;
      stride[a] = s;
      s *= nodes[a];
    }
    node_count = s;
  }

  [[nodiscard]] Vec<D> domain_max() const {
    Vec<D> m;
    for (int a = 0; a < D; ++a) m[a] = origin[a] + cells[a] * h[a];
    return m;
  }
  /// Flat index of the node with (possibly negative) integer coordinates ijk.
  [[nodiscard]] Index node_index(const std::array<int, D>& ijk) const {
    Index n = 0;
    for (int a = 0; a < D; ++a) n += static_cast<Index>(ijk[a] + ghost) * stride[a];
    return n;
  }
  /// Integer coordinates of a flat node index.
  [[nodiscard]] std::array<int, D> node_coords(Index n) const {
    std::array<int, D> ijk{};
    for (int a = D - 1; a >= 0; --a) {
      ijk[a] = static_cast<int>(n / stride[a]) - ghost;
      n %= stride[a];
    }
    return ijk;
  }
  [[nodiscard]] Vec<D> node_position(Index n) const {
    const auto ijk = node_coords(n);
    Vec<D> x;
    for (int a = 0; a < D; ++a) x[a] = origin[a] + ijk[a] * h[a];
    return x;
  }
  /// True when x lies inside the user's domain (ghost layers excluded).
  [[nodiscard]] bool contains(const Vec<D>& x) const {
    for (int a = 0; a < D; ++a) {
      const double xi = (x[a] - origin[a]) / h[a];
      if (!(xi >= 0.0 && xi <= cells[a])) return false;  // also false for NaN
    }
    return true;
  }
  /// Integer coordinates of the cell containing x (a point outside is put in the nearest cell).
  [[nodiscard]] std::array<int, D> cell_coords(const Vec<D>& x) const {
    std::array<int, D> c{};
    for (int a = 0; a < D; ++a) c[a] = cell_coordinate(x[a], a);
    return c;
  }
  /// Cell coordinate along axis a of the coordinate x_a (clamped to 0 .. cells - 1).
  [[nodiscard]] int cell_coordinate(double x_a, int a) const {
    const int i = floor_to_int((x_a - origin[a]) / h[a]);
    return i < 0 ? 0 : (i >= cells[a] ? cells[a] - 1 : i);
  }
  /// Flat index of the cell containing x (x inside the domain).
  [[nodiscard]] Index cell_index(const Vec<D>& x) const {
    Index c = 0, s = 1;
    for (int a = 0; a < D; ++a) {
      c += cell_coordinate(x[a], a) * s;
      s *= cells[a];
    }
    return c;
  }
  [[nodiscard]] double cell_volume() const { return h.prod(); }
  [[nodiscard]] double min_cell_size() const { return h.minCoeff(); }
};

}  // namespace matpoint
