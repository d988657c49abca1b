// The thread decomposition shared by the race-free particle-to-grid transfers (scatter.hpp,
// scalar_scatter.hpp): each thread takes a contiguous block of the cell-sorted particles and
// scatters it into a private band of nodes, the node range its particles' stencils touch; the
// bands are then summed node by node in thread order (a given thread count gives the same result).
#pragma once

#include <algorithm>
#include <cstddef>

#include "matpoint/grid/grid.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace matpoint {

/// The threads a transfer over n particles uses: 1 for small sets or without OpenMP.
inline int scatter_threads(std::ptrdiff_t n) {
#ifdef _OPENMP
  return n <= kParallelMinimum ? 1 : omp_get_max_threads();
#else
  (void)n;
  return 1;
#endif
}

/// The calling thread's number inside a parallel region (0 without OpenMP).
inline int thread_number() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/// Thread t's particles [begin, end) of n and the nodes [lo, hi] their stencils touch (hi < lo: none).
struct ParticleBlock {
  std::ptrdiff_t begin = 0, end = 0;
  Index lo = 0, hi = -1;
  [[nodiscard]] Index width() const { return std::max<Index>(hi - lo + 1, 0); }
};

template <int D, class Stencils>
ParticleBlock particle_block(const Grid<D>& grid, const Stencils& stencils, std::ptrdiff_t n, int t,
                             int threads) {
  ParticleBlock block{n * t / threads, n * (t + 1) / threads, grid.node_count, -1};
  for (std::ptrdiff_t p = block.begin; p < block.end; ++p) {
    const auto [lo, hi] = stencils.node_span(grid, p);  // the nodes particle p touches lie in [lo, hi]
    block.lo = std::min(block.lo, lo);
    block.hi = std::max(block.hi, hi);
  }
  return block;
}

}  // namespace matpoint
