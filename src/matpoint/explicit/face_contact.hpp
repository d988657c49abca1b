// One-sided faces as rigid-wall contacts (docs/input.md, boundary_conditions.one_sided): each step
// flags the nodes where a body's deformed particle domains reach a one-sided face. Without this test
// a one-sided face is a ratchet: a node that lifts off is free, and it is held as soon as it moves
// back although the body no longer touches the face, so every vibration pumps the body away from the
// face (examples/rolling-disk hopped 7 cm and gained 10 % energy in 1 s).
#pragma once

#include <cmath>
#include <span>
#include <vector>

#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/velocity_conditions.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

/// Sets conditions.touching(): 1 on a node when a particle whose support holds it reaches a one-sided
/// face with its deformed domain (half-extent particles.half_extent along the face normal) and covers
/// the node's position along the face (half-extents along the other axes), 0 elsewhere. The cover
/// test makes the contact point of a rolling body the node under it: a node ahead of the contact,
/// held as soon as the body's support touches the face, would be a pivot ahead of the contact point
/// about which the body climbs (examples/rolling-disk README). `field_grid` and `stencils` give the
/// multi-field node indices of a contact run; node positions come from `grid`.
/// The particles are visited in the scatter's brick order, the flags set as 1.0 in a node array:
/// a decomposed run hands them on between the colours as it does the sums (setting a flag is an
/// OR, which the hand-off carries as it carries a running sum), so a node that particles of two
/// ranks touch is flagged on both (docs/scale-out.md §17 stage 3).
template <int D, class Stencils>
void mark_nodes_touching_faces(const Grid<D>& grid, const Grid<D>& field_grid, const Stencils& stencils,
                               const ParticleSet<D>& particles, VelocityConditions<D>& conditions) {
  std::vector<double> flags(static_cast<std::size_t>(field_grid.node_count), 0.0);
  double* const flag = flags.data();
  const NodeArray written{flag, 1, field_grid.node_count};
  const auto mark = [&](std::size_t p) {
    Vec<D> extent;
    for (int a = 0; a < D; ++a) extent[a] = particles.half_extent(p, Vec<D>::Unit(a));
    const Vec<D>& x = particles.x[p];
    for (const auto& face : conditions.one_sided_faces()) {
      const int n = face.axis;
      const bool reaches =
          face.side == 0 ? x[n] - extent[n] <= face.position : x[n] + extent[n] >= face.position;
      if (!reaches) continue;
      stencils.for_each_node(field_grid, p, [&](Index node, double, const auto&) {
        const Vec<D> offset = grid.node_position(node % grid.node_count) - x;
        bool covers = true;
        for (int a = 0; a < D; ++a)
          covers = covers && (a == n || std::abs(offset[a]) <= extent[a] * (1.0 + 1e-9));
        if (covers) flag[node] = 1.0;
      });
    }
  };
  stencils.brick_order().for_each_particle(mark, std::span<const NodeArray>(&written, 1));
  auto& touching = conditions.touching();
  touching.resize(flags.size());
  for (std::size_t i = 0; i < flags.size(); ++i) touching[i] = flags[i] != 0.0 ? 1 : 0;
}

}  // namespace matpoint
