// Uniform Cartesian background grid: geometry and node numbering.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/index_box.hpp"

namespace matpoint {

/// Nodes sit at origin + i * h, i = -ghost .. cells + ghost per direction. Ghost layers lie
/// outside the user's domain and exist only so that wide bases (B-splines) have every node they
/// need next to the domain edge; boundary conditions on a face apply to its ghost nodes too.
///
/// The grid *stores* a window of those nodes: per axis the integer coordinates first[a] ..
/// first[a] + nodes[a] - 1, numbered x fastest from 0 (node_index, node_coords). A serial run stores
/// every node (first = -ghost); a rank of a decomposed run stores the nodes its particles reach
/// (window(), docs/scale-out.md §2), so that its node arrays and node loops shrink with the rank
/// count. The geometry (origin, h, cells, contains, cell_index) is the whole grid's either way.
template <int D>
struct Grid {
  Vec<D> origin = Vec<D>::Zero();
  Vec<D> h = Vec<D>::Ones();
  std::array<int, D> cells{};
  int ghost = 0;
  std::array<int, D> first{};     // per direction, the coordinate of the first stored node
  std::array<int, D> nodes{};     // per direction, the stored nodes (ghosts included)
  std::array<Index, D> stride{};  // flat node index = sum (i_a - first_a) * stride_a
  Index node_count = 0;           // stored nodes

  Grid() = default;
  Grid(const Vec<D>& origin_, const Vec<D>& h_, const std::array<int, D>& cells_, int ghost_)
      : origin(origin_), h(h_), cells(cells_), ghost(ghost_) {
    for (int a = 0; a < D; ++a) {
      first[a] = -ghost;
      nodes[a] = cells[a] + 1 + 2 * ghost;
    }
    number_nodes();
  }

  /// The same grid storing only the node coordinates in `box` (clamped to the grid's nodes, ghosts
  /// included): a rank's window.
  [[nodiscard]] Grid window(const IndexBox<D>& box) const {
    Grid out = *this;
    for (int a = 0; a < D; ++a) {
      const int begin = std::max(box.begin[a], -ghost), end = std::min(box.end[a], cells[a] + 1 + ghost);
      out.first[a] = begin;
      out.nodes[a] = std::max(0, end - begin);
    }
    out.number_nodes();
    return out;
  }
  /// The node coordinates this grid stores.
  [[nodiscard]] IndexBox<D> stored_nodes() const {
    IndexBox<D> box;
    for (int a = 0; a < D; ++a) box.begin[a] = first[a], box.end[a] = first[a] + nodes[a];
    return box;
  }
  /// True when the node of coordinates ijk is stored.
  [[nodiscard]] bool stores(const std::array<int, D>& ijk) const {
    for (int a = 0; a < D; ++a)
      if (ijk[a] < first[a] || ijk[a] >= first[a] + nodes[a]) return false;
    return true;
  }
  /// The stored node of coordinates ijk in grid `from`'s numbering (or -1 when `from` does not
  /// store it): for carrying a node array over to another window.
  [[nodiscard]] Index node_index_in(const Grid& from, Index n) const {
    const auto ijk = node_coords(n);
    return from.stores(ijk) ? from.node_index(ijk) : -1;
  }

  [[nodiscard]] Vec<D> domain_max() const {
    Vec<D> m;
    for (int a = 0; a < D; ++a) m[a] = origin[a] + cells[a] * h[a];
    return m;
  }
  /// Flat index of the stored node with (possibly negative) integer coordinates ijk.
  [[nodiscard]] Index node_index(const std::array<int, D>& ijk) const {
    Index n = 0;
    for (int a = 0; a < D; ++a) n += static_cast<Index>(ijk[a] - first[a]) * stride[a];
    return n;
  }
  /// Integer coordinates of a flat node index.
  [[nodiscard]] std::array<int, D> node_coords(Index n) const {
    std::array<int, D> ijk{};
    for (int a = D - 1; a >= 0; --a) {
      ijk[a] = static_cast<int>(n / stride[a]) + first[a];
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
  /// Nodes of the whole grid (ghosts included), whatever the window.
  [[nodiscard]] Index total_node_count() const {
    Index n = 1;
    for (int a = 0; a < D; ++a) n *= cells[a] + 1 + 2 * ghost;
    return n;
  }

 private:
  void number_nodes() {
    Index s = 1;
    for (int a = 0; a < D; ++a) {
      stride[a] = s;
      s *= nodes[a];
    }
    node_count = s;
  }
};

}  // namespace matpoint
