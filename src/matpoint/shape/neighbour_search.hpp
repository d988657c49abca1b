// Neighbour search for meshfree clouds (Iaconeta et al. 2017 §4.2, Algorithm 2 step 1; extraction
// §6.1): every material point gathers the nodes within a radius R of itself. A uniform cell list
// (bins of width `cell`, counting sort, 3^D-block scan) answers a radius query in O(nodes found);
// the nearest-k query used by the repairs of §6.5 scans growing shells of cells. The cost is
// measured against the shape functions themselves in src/matpoint/shape/README.md.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"

namespace matpoint {

/// A node index with its distance to the query point.
struct NodeDistance {
  std::int32_t node;
  double distance;
  bool operator<(const NodeDistance& o) const {
    return distance < o.distance || (distance == o.distance && node < o.node);
  }
};

/// Uniform cell list over a fixed set of node positions. Rebuild it when the nodes move (once per
/// step in the Lagrangian GMM; a rebuild is one pass and one counting sort).
template <int D>
class NodeCellList {
 public:
  NodeCellList() = default;
  NodeCellList(std::span<const Vec<D>> nodes, double cell) { build(nodes, cell); }

  /// Bins the nodes into cells of width `cell` (use the search radius: a radius query then scans
  /// 3^D cells).
  void build(std::span<const Vec<D>> nodes, double cell) {
    nodes_ = nodes;
    cell_ = cell;
    lower_.setZero();
    dims_.fill(1);
    if (nodes.empty()) {
      start_.assign(2, 0);
      order_.clear();
      return;
    }
    Vec<D> upper = nodes[0];
    lower_ = nodes[0];
    for (const auto& x : nodes) {
      lower_ = lower_.cwiseMin(x);
      upper = upper.cwiseMax(x);
    }
    // Cells wider than asked when the nodes spread far (a node thrown off the body): at most about
    // 8 cells per node, so the list's memory stays bounded; the queries scan more cells then.
    const double most = std::max(64.0, 8.0 * static_cast<double>(nodes.size()));
    double wanted = 1.0;
    for (int a = 0; a < D; ++a) wanted *= (upper[a] - lower_[a]) / cell_ + 1.0;
    if (wanted > most) cell_ *= std::pow(wanted / most, 1.0 / D);
    for (int a = 0; a < D; ++a) dims_[a] = floor_to_int((upper[a] - lower_[a]) / cell_) + 1;
    std::size_t cells = 1;
    for (int a = 0; a < D; ++a) cells *= static_cast<std::size_t>(dims_[a]);
    start_.assign(cells + 1, 0);
    std::vector<std::int64_t> cell_of(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      cell_of[i] = flat(cell_coordinates(nodes[i]));
      ++start_[cell_of[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
    order_.resize(nodes.size());
    std::vector<std::int32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < nodes.size(); ++i) order_[fill[cell_of[i]]++] = static_cast<std::int32_t>(i);
  }

  /// Appends to `out` every node with |x - x_I| < radius, in no particular order. A node within a
  /// relative 1e-12 of the sphere counts as outside, so that a tie (a grid node at exactly R from a
  /// point at a node, as with R = sqrt(2) h) does not depend on the rounding of R.
  void within(const Vec<D>& x, double radius, std::vector<NodeDistance>& out) const {
    const int reach = static_cast<int>(std::ceil(radius / cell_));
    const double radius2 = radius * radius * (1.0 - 2e-12);
    scan_block(x, reach, [&](std::int32_t node, double r2) {
      if (r2 < radius2) out.push_back({node, std::sqrt(r2)});
    });
  }

  /// The k nearest nodes to x, sorted by distance (fewer when there are fewer nodes). Shells of
  /// cells are added until the k-th distance found is certainly below the unscanned region.
  void nearest(const Vec<D>& x, std::size_t k, std::vector<NodeDistance>& out) const {
    out.clear();
    k = std::min(k, nodes_.size());
    if (k == 0) return;
    // The reach at which the block around x's cell covers every cell.
    const auto centre = cell_coordinates(x);
    // The reach at which the block around x's cell first touches the grid, and covers all of it.
    int first_reach = 1, full_reach = 0;
    for (int a = 0; a < D; ++a) {
      first_reach = std::max({first_reach, -centre[a], centre[a] - (dims_[a] - 1)});
      full_reach = std::max({full_reach, std::abs(centre[a]), std::abs(dims_[a] - 1 - centre[a])});
    }
    for (int reach = first_reach;; ++reach) {
      out.clear();
      // distance holds the squared distance until the end.
      scan_block(x, reach, [&](std::int32_t node, double r2) { out.push_back({node, r2}); });
      if (reach >= full_reach) break;
      // x lies in its cell, so every node outside the scanned block is at least reach cells away.
      if (out.size() >= k) {
        std::nth_element(out.begin(), out.begin() + (k - 1), out.end());
        if (out[k - 1].distance <= reach * cell_ * reach * cell_) break;
      }
    }
    std::sort(out.begin(), out.end());
    out.resize(k);
    for (auto& n : out) n.distance = std::sqrt(n.distance);
  }

  double cell() const { return cell_; }

 private:
  std::array<int, D> cell_coordinates(const Vec<D>& x) const {
    std::array<int, D> c;
    for (int a = 0; a < D; ++a) c[a] = floor_to_int((x[a] - lower_[a]) / cell_);
    return c;
  }

  std::int64_t flat(const std::array<int, D>& c) const {
    std::int64_t f = 0;
    for (int a = D - 1; a >= 0; --a) f = f * dims_[a] + c[a];
    return f;
  }

  /// Calls f(node, squared distance) for every node in the cells within `reach` cells of x's cell.
  template <class F>
  void scan_block(const Vec<D>& x, int reach, F&& f) const {
    const auto centre = cell_coordinates(x);
    std::array<int, D> lo, hi;
    for (int a = 0; a < D; ++a) {
      lo[a] = std::max(centre[a] - reach, 0);
      hi[a] = std::min(centre[a] + reach, dims_[a] - 1);
      if (lo[a] > hi[a]) return;
    }
    std::array<int, D> c = lo;
    while (true) {
      const std::int64_t cell = flat(c);
      for (std::int32_t s = start_[cell]; s < start_[cell + 1]; ++s) {
        const std::int32_t node = order_[s];
        f(node, (nodes_[node] - x).squaredNorm());
      }
      int a = 0;
      while (a < D && ++c[a] > hi[a]) c[a] = lo[a], ++a;
      if (a == D) break;
    }
  }

  std::span<const Vec<D>> nodes_;
  double cell_ = 1.0;
  Vec<D> lower_ = Vec<D>::Zero();
  std::array<int, D> dims_{};
  std::vector<std::int32_t> start_;
  std::vector<std::int32_t> order_;
};

}  // namespace matpoint
