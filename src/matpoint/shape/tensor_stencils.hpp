// Per-particle stencils of a tensor-product basis, evaluated once per step and reused by every
// particle-grid transfer of that step (Nairn 2026 §2.1: "shape data computed once, at step start").
// Only the 1-D factors are stored (2 D width numbers per particle); the D-dimensional weights and
// gradients are formed on the fly, which costs a few multiplications and saves memory traffic.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/particles/particle_set.hpp"
#include "matpoint/shape/tensor_bases.hpp"

namespace matpoint {

/// cpGIMP's half-width |F_aa| l0 in cells before the cap of gimp_half_width (above 1/2 it is capped).
template <int D>
double stretched_half_width(const Grid<D>& grid, const ParticleSet<D>& particles, std::size_t p, int a) {
  return 0.5 * particles.size0[p][a] / grid.h[a] * std::abs(particles.F[p](a, a));
}

/// Half-width, in cells of axis a, of particle p's GIMP domain: l0 = size0 / 2 (uGIMP, B2GIMP) or
/// |F_aa| l0 (cpGIMP), limited to [min_half_width, 1/2] (the stencil width assumes l <= h/2).
template <class Basis, int D>
double gimp_half_width(const Grid<D>& grid, const ParticleSet<D>& particles, std::size_t p, int a) {
  const double l = Basis::domain == DomainWidth::Stretched ? stretched_half_width(grid, particles, p, a)
                                                           : 0.5 * particles.size0[p][a] / grid.h[a];
  return std::clamp(l, Basis::min_half_width, 0.5);
}

template <int D, class Basis>
struct TensorStencils {
  static constexpr int W = Basis::width;
  static constexpr int nodes_per_particle = D == 1 ? W : (D == 2 ? W * W : W * W * W);

  std::vector<Index> base;                        // flat index of the lowest node
  std::vector<std::array<double, D * W>> weight;  // phi of each direction, [a * W + k]
  std::vector<std::array<double, D * W>> slope;   // d phi / dx of each direction
  BrickSchedule<D> bricks;                        // the particle order of the particle-to-grid sums

  void evaluate(const Grid<D>& grid, const ParticleSet<D>& particles);

  [[nodiscard]] const BrickSchedule<D>& brick_order() const { return bricks; }

  /// Largest flat-index distance from base[p] to any node of the stencil.
  [[nodiscard]] static Index max_node_offset(const Grid<D>& grid) {
    Index reach = 0;
    for (int a = 0; a < D; ++a) reach += (W - 1) * grid.stride[a];
    return reach;
  }

  /// First and last flat node index of particle p's stencil (for the threaded scatter's bands).
  [[nodiscard]] std::pair<Index, Index> node_span(const Grid<D>& grid, std::size_t p) const {
    return {base[p], base[p] + max_node_offset(grid)};
  }

  /// Calls fn(node, N, gradN) for every node in particle p's support.
  template <class Fn>
  void for_each_node(const Grid<D>& grid, std::size_t p, Fn&& fn) const {
    const auto& w = weight[p];
    const auto& s = slope[p];
    const Index b = base[p];
    if constexpr (D == 1) {
      for (int i = 0; i < W; ++i) fn(b + i, w[i], Vec<1>(s[i]));
    } else if constexpr (D == 2) {
      const Index sy = grid.stride[1];
      for (int j = 0; j < W; ++j)
        for (int i = 0; i < W; ++i)
          fn(b + i + j * sy, w[i] * w[W + j], Vec<2>(s[i] * w[W + j], w[i] * s[W + j]));
    } else {
      const Index sy = grid.stride[1], sz = grid.stride[2];
      for (int k = 0; k < W; ++k)
        for (int j = 0; j < W; ++j) {
          const double wjk = w[W + j] * w[2 * W + k];
          for (int i = 0; i < W; ++i)
            fn(b + i + j * sy + k * sz, w[i] * wjk,
               Vec<3>(s[i] * wjk, w[i] * s[W + j] * w[2 * W + k], w[i] * w[W + j] * s[2 * W + k]));
        }
    }
  }

 private:
  /// Particle p's stencil and brick; below / above: the thread's running reach.
  void evaluate_one(const Grid<D>& grid, const ParticleSet<D>& particles, std::ptrdiff_t p, int& below,
                    int& above);
  /// The kLanes particles from `first` at once (Basis::evaluate_lanes); false, with none of them
  /// finished, when a stencil needs the edge fold or a coordinate is not finite.
  bool evaluate_lanes(const Grid<D>& grid, const ParticleSet<D>& particles, std::ptrdiff_t first, int& below,
                      int& above);
};

template <int D, class Basis>
void TensorStencils<D, Basis>::evaluate(const Grid<D>& grid, const ParticleSet<D>& particles) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  base.resize(n);
  weight.resize(n);
  slope.resize(n);
  bricks.reset(grid, particles.size());
  int below = 0, above = 0;  // farthest stencil node below / above a particle's cell, in nodes
  // A point basis with evaluate_lanes takes kLanes particles at once where their stencils need no
  // edge fold (bitwise the scalar result, core/lanes.hpp); the rest go one by one.
  constexpr bool kLanesPath = requires(const Lanes& xi, Lanes* w, Lanes& lowest) {
    Basis::evaluate_lanes(xi, 0, w, w, lowest);
  };
  const std::ptrdiff_t batches = kLanesPath ? n / kLanes : 0;
#pragma omp parallel for schedule(static) reduction(max : below, above) if (n > kParallelMinimum)
  for (std::ptrdiff_t b = 0; b < batches; ++b) {
    if constexpr (kLanesPath)
      if (evaluate_lanes(grid, particles, b * kLanes, below, above)) continue;
    for (std::ptrdiff_t p = b * kLanes; p < (b + 1) * kLanes; ++p)
      evaluate_one(grid, particles, p, below, above);
  }
  const std::ptrdiff_t rest = batches * kLanes;
#pragma omp parallel for schedule(static) reduction(max : below, above) if (n - rest > kParallelMinimum)
  for (std::ptrdiff_t p = rest; p < n; ++p) evaluate_one(grid, particles, p, below, above);
  bricks.finish(below, above);
}

template <int D, class Basis>
void TensorStencils<D, Basis>::evaluate_one(const Grid<D>& grid, const ParticleSet<D>& particles,
                                            std::ptrdiff_t p, int& below, int& above) {
  std::array<int, D> lowest{}, cell{};
  for (int a = 0; a < D; ++a) {
    const double xi = (particles.x[p][a] - grid.origin[a]) / grid.h[a];
    if constexpr (Basis::domain == DomainWidth::None)
      lowest[a] = Basis::evaluate(xi, grid.cells[a], &weight[p][a * W], &slope[p][a * W]);
    else
      lowest[a] = Basis::evaluate(xi, gimp_half_width<Basis, D>(grid, particles, p, a), grid.cells[a],
                                  &weight[p][a * W], &slope[p][a * W]);
    const double inv_h = 1.0 / grid.h[a];
    for (int k = 0; k < W; ++k) slope[p][a * W + k] *= inv_h;
    cell[a] = std::clamp(floor_to_int(xi), 0, grid.cells[a] - 1);  // as Grid::cell_coordinate
    below = std::max(below, cell[a] - lowest[a]);
    above = std::max(above, lowest[a] + W - 1 - cell[a]);
  }
  base[p] = grid.node_index(lowest);
  bricks.assign(p, cell);
}

template <int D, class Basis>
bool TensorStencils<D, Basis>::evaluate_lanes(const Grid<D>& grid, const ParticleSet<D>& particles,
                                              std::ptrdiff_t first, int& below, int& above) {
  Lanes w[D][W], dw[D][W], lowest[D], cell[D];
  for (int a = 0; a < D; ++a) {
    const Lanes x([&](auto lane) { return particles.x[first + lane][a]; });
    const Lanes xi = (x - grid.origin[a]) / grid.h[a];
    if (!Basis::evaluate_lanes(xi, grid.cells[a], w[a], dw[a], lowest[a])) return false;
    const double inv_h = 1.0 / grid.h[a];
    for (int k = 0; k < W; ++k) dw[a][k] *= inv_h;
    cell[a] = stdx::floor(xi);  // inside the grid: no clamp acts (evaluate_lanes checked)
  }
  for (int lane = 0; lane < kLanes; ++lane) {
    const std::ptrdiff_t p = first + lane;
    std::array<int, D> low{}, at{};
    for (int a = 0; a < D; ++a) {
      for (int k = 0; k < W; ++k) {
        weight[p][a * W + k] = w[a][k][lane];
        slope[p][a * W + k] = dw[a][k][lane];
      }
      low[a] = static_cast<int>(lowest[a][lane]);
      at[a] = std::clamp(static_cast<int>(cell[a][lane]), 0, grid.cells[a] - 1);
      below = std::max(below, at[a] - low[a]);
      above = std::max(above, low[a] + W - 1 - at[a]);
    }
    base[p] = grid.node_index(low);
    bricks.assign(p, at);
  }
  return true;
}

}  // namespace matpoint
