// Particle-to-grid transfer of one scalar per node (the transport quantities of coupled heat
// conduction: nodal capacity, capacity-weighted temperature, heat flow; Nairn 2026 §3.5):
//   out_i = sum_p contribution(p, S_pi, grad S_pi)
// Race-free with threads in the same way as scatter_to_grid (particle_blocks.hpp).
#pragma once

#include <algorithm>
#include <vector>

#include "matpoint/explicit/particle_blocks.hpp"
#include "matpoint/grid/grid.hpp"

namespace matpoint {

/// Per-thread node bands reused from step to step.
struct ScalarScatterWorkspace {
  struct Band {
    Index lo = 0, hi = -1;
    std::vector<double> values;
  };
  std::vector<Band> bands;
};

/// Overwrites out (grid.node_count entries) with sum_p contribution(p, N, dN) over the particle-node
/// pairs of the step's stencils.
template <int D, class Stencils, class Contribution>
void scatter_scalar(const Grid<D>& grid, const Stencils& stencils, std::size_t particle_count,
                    std::vector<double>& out, ScalarScatterWorkspace& ws, const Contribution& contribution) {
  const auto n = static_cast<std::ptrdiff_t>(particle_count);
  out.assign(static_cast<std::size_t>(grid.node_count), 0.0);
  const int threads = scatter_threads(n);
  if (threads == 1) {
    for (std::ptrdiff_t p = 0; p < n; ++p)
      stencils.for_each_node(
          grid, p, [&](Index node, double N, const Vec<D>& dN) { out[node] += contribution(p, N, dN); });
    return;
  }
  ws.bands.resize(threads);
#pragma omp parallel num_threads(threads)
  {
    const int t = thread_number();
    const ParticleBlock block = particle_block(grid, stencils, n, t, threads);
    auto& band = ws.bands[t];
    band.lo = block.lo, band.hi = block.hi;
    band.values.assign(block.width(), 0.0);
    for (std::ptrdiff_t p = block.begin; p < block.end; ++p)
      stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>& dN) {
        band.values[node - band.lo] += contribution(p, N, dN);
      });
#pragma omp barrier
#pragma omp for schedule(static)
    for (Index i = 0; i < grid.node_count; ++i) {
      double sum = 0.0;
      for (const auto& b : ws.bands)
        if (i >= b.lo && i <= b.hi) sum += b.values[i - b.lo];
      out[i] = sum;
    }
  }
}

}  // namespace matpoint
