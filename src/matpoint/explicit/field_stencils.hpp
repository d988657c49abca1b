// Stencils of a multi-field (contact) run: each body (or material) has its own copy of the grid
// nodes, field f owning the flat indices [f N, (f + 1) N) of N grid nodes. The adapter shifts
// every node index of a particle's stencil by its field's offset, so that the scatter, the
// gather and the FMPM passes, unchanged, work on each field separately (Nairn 2026 §3.2: "each
// material velocity field runs its own loop"). Single-field runs use the plain stencils: the
// offset costs nothing where there is no contact.
#pragma once

#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

template <int D, class Base>
struct FieldStencils {
  static constexpr bool multi_field = true;

  Base base;
  std::vector<int> field_of;  // field of each body (or material), set once
  bool by_material = false;
  Index field_nodes = 0;      // N: nodes of one field
  std::vector<Index> offset;  // by particle storage index: field * N

  void evaluate(const Grid<D>& grid, const ParticleSet<D>& particles) {
    base.evaluate(grid, particles);
    offset.resize(particles.size());
    for (std::size_t p = 0; p < particles.size(); ++p)
      offset[p] = field_of[by_material ? particles.material[p] : particles.body[p]] * field_nodes;
  }

  /// The base stencils' particle order: the fields are separate node ranges, so two particles of
  /// different fields never share a node and the single-grid colouring serves every field.
  [[nodiscard]] const auto& brick_order() const { return base.bricks; }

  [[nodiscard]] int field(std::size_t p) const { return static_cast<int>(offset[p] / field_nodes); }

  [[nodiscard]] std::pair<Index, Index> node_span(const Grid<D>& grid, std::size_t p) const {
    const auto [lo, hi] = base.node_span(grid, p);
    return {lo + offset[p], hi + offset[p]};
  }

  template <class Fn>
  void for_each_node(const Grid<D>& grid, std::size_t p, Fn&& fn) const {
    const Index o = offset[p];
    base.for_each_node(grid, p, [&](Index node, double N, const auto& dN) { fn(node + o, N, dN); });
  }
};

}  // namespace matpoint
