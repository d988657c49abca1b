// Particle-to-grid transfer of one scalar per node (the transport quantities of coupled heat
// conduction: nodal capacity, capacity-weighted temperature, heat flow; Nairn 2026 §3.5):
//   out_i = sum_p contribution(p, S_pi, grad S_pi)
// Race-free and independent of the thread count in the same way as scatter_to_grid (the
// stencils' brick order, grid/brick_schedule.hpp).
#pragma once

#include <span>
#include <vector>

#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"

namespace matpoint {

/// Overwrites out (grid.node_count entries; a multi-field run passes its field grid) with
/// sum_p contribution(p, N, dN) over the particle-node pairs of the step's stencils.
template <int D, class Stencils, class Contribution>
void scatter_scalar(const Grid<D>& grid, const Stencils& stencils, std::vector<double>& out,
                    const Contribution& contribution) {
  out.assign(static_cast<std::size_t>(grid.node_count), 0.0);
  const NodeArray written{out.data(), 1, grid.node_count};  // for a decomposed run's hand-off between colours
  const auto add_particle = [&](std::size_t p) {
    stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
      out[node] += contribution(static_cast<std::ptrdiff_t>(p), N, dN);
    });
  };
  stencils.brick_order().for_each_particle(add_particle, std::span<const NodeArray>(&written, 1));
}

}  // namespace matpoint
