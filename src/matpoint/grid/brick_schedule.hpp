// The order in which particle-to-grid sums visit the particles: by bricks of B^D cells in a fixed
// colouring, so that a nodal sum is the same for any number of threads (docs/scale-out.md §6).
//
// Each particle belongs to the brick that holds its cell. Bricks are coloured by the parity of
// their coordinates (m colours per axis, m^D in all, m = 2 unless a stencil reaches farther than a
// brick); two bricks of one colour are at least (m - 1) B cells apart (B the shortest brick edge), so their
// particles' stencils never share a node and the bricks of one colour can be scattered by different threads
// straight into the grid, without atomics or private copies. The colours run one after the other. A node
// therefore receives its contributions in one fixed order — colour by colour; within a colour from its single
// brick, in the brick's particle order (storage order) — whatever the thread count, and the sums are bitwise
// equal on 1, 2 or 16 threads.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/particles/serial_order.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace matpoint {

/// A node array that a particle-to-grid sum writes: `width` doubles per node, node i's at
/// data[i * width ..], `nodes` nodes: the grid's N, or fields x N in a multi-field (contact) run,
/// field f at nodes f N .. f N + N - 1. The brick order hands these over between colours in a
/// decomposed run (every field's copy of a node).
struct NodeArray {
  double* data;
  int width;
  Index nodes;
};

/// What a decomposed run adds to the brick order (parallel/colour_hand_off.hpp): the ranks agree
/// on how far the stencils reach, and between two colours they pass on the running sums of the
/// nodes that another rank stores too. Called once per colour, not per particle.
class BrickBoundary {
 public:
  BrickBoundary() = default;
  BrickBoundary(const BrickBoundary&) = delete;
  BrickBoundary& operator=(const BrickBoundary&) = delete;
  virtual ~BrickBoundary() = default;
  /// Replaces this rank's reach by the one every rank uses (a collective, once per step).
  virtual void agree_reach(int& below, int& above) = 0;
  /// After colour `colour` of a sum over `arrays` (a collective, once per colour).
  virtual void after_colour(int colour, const NodeArray* arrays, int count) const = 0;
};

template <int D>
class BrickSchedule {
 public:
  /// Cells per brick edge along axis a, a power of two 2^brick_shift(a): bricks of 64 x 8 cells in
  /// 2-D and 32 x 8 x 8 in 3-D hold one to four thousand particles, enough work for a thread; long
  /// along x (the fastest node index), so that a brick reads and writes the grid in rows of 66 or
  /// 34 nodes, which the hardware prefetches (square 16 x 16 bricks cost 10 % of bench-2d).
  [[nodiscard]] static constexpr int brick_shift(int a) { return a == 0 ? (D == 3 ? 5 : 6) : 3; }
  [[nodiscard]] static constexpr int brick_cells(int a) { return 1 << brick_shift(a); }
  /// The shortest brick edge, in cells: what separates two bricks of one colour (finish()).
  static constexpr int kNarrowestBrick = D == 1 ? brick_cells(0) : brick_cells(1);

  /// Bricks along axis a of the grid (the last one may hold fewer cells).
  [[nodiscard]] static int bricks_along(const Grid<D>& grid, int a) {
    return (grid.cells[a] + brick_cells(a) - 1) >> brick_shift(a);
  }

  /// Sizes the schedule for n particles on the grid's cells (before assign()).
  void reset(const Grid<D>& grid, std::size_t n) {
    Index count = 1;
    for (int a = 0; a < D; ++a) {
      bricks_[a] = bricks_along(grid, a);
      brick_stride_[a] = count;
      count *= bricks_[a];
    }
    brick_count_ = count;
    brick_of_.resize(n);
  }

  /// Particle p lies in the cell of coordinates `cell` (0 .. cells - 1 per axis). Safe to call for
  /// different p from several threads.
  void assign(std::size_t p, const std::array<int, D>& cell) {
    Index b = 0;
    for (int a = 0; a < D; ++a) b += static_cast<Index>(cell[a] >> brick_shift(a)) * brick_stride_[a];
    brick_of_[p] = static_cast<std::int32_t>(b);
  }

  /// Groups the particles by brick (stable: storage order within a brick) and the bricks by
  /// colour. A particle's stencil reaches at most `below` nodes below its cell's lowest node and
  /// `above` nodes above it, along any axis (1 and 2 for the quadratic B-spline).
  void finish(int below, int above) {
    if (boundary != nullptr) boundary->agree_reach(below, above);
    colours_per_axis_ = colours_per_axis_for(below, above);
    const auto n = static_cast<std::int32_t>(brick_of_.size());
    // A stable counting sort by brick. sort_by_cell keeps the storage brick-major, so the bricks
    // come in runs: each run is counted and placed at once (a counter per particle would be a
    // chain of dependent increments on one memory word).
    start_.assign(static_cast<std::size_t>(brick_count_) + 1, 0);
    for_each_run([&](std::int32_t b, std::int32_t begin, std::int32_t end) { start_[b + 1] += end - begin; });
    for (Index b = 0; b < brick_count_; ++b) start_[b + 1] += start_[b];
    order_.resize(static_cast<std::size_t>(n));
    fill_.assign(start_.begin(), start_.end() - 1);
    for_each_run([&](std::int32_t b, std::int32_t begin, std::int32_t end) {
      std::int32_t* out = order_.data() + fill_[b];
      for (std::int32_t p = begin; p < end; ++p) *out++ = p;
      fill_[b] += end - begin;
    });
    group_by_colour();
  }

  /// Colours per axis m when stencils reach `below` and `above` nodes past a particle's cell:
  /// bricks m apart along an axis are (m - 1) B cells apart, enough when (m - 1) B >= below + above.
  [[nodiscard]] static int colours_per_axis_for(int below, int above) {
    return 2 + std::max(0, (below + above - 1) / kNarrowestBrick);
  }

  /// Reorders the particles of the bricks that hold particles of storage index >= sorted_prefix
  /// by (key, id): a decomposed run appends the particles that arrive from other ranks after the
  /// ones sorted at the last sort_by_cell (which are in (key, id) order already, key = the
  /// brick-major cell at that sort), so that every brick visits its particles in the order the
  /// serial run stores them (docs/scale-out.md §6).
  void order_arrivals(const std::vector<Index>& key, const std::vector<long>& id, std::size_t sorted_prefix) {
    if (sorted_prefix >= brick_of_.size()) return;
    std::vector<std::int32_t> bricks;
    for (std::size_t p = sorted_prefix; p < brick_of_.size(); ++p) bricks.push_back(brick_of_[p]);
    std::sort(bricks.begin(), bricks.end());
    bricks.erase(std::unique(bricks.begin(), bricks.end()), bricks.end());
    const auto by_key = [&](std::int32_t a, std::int32_t b) {
      return serially_before(key[a], id[a], key[b], id[b]);
    };
    for (const std::int32_t b : bricks)
      std::sort(order_.begin() + start_[b], order_.begin() + start_[b + 1], by_key);
  }

  [[nodiscard]] Index brick_of(std::size_t p) const { return brick_of_[p]; }
  /// Colour of brick b: its coordinates modulo m per axis, read as a base-m number.
  [[nodiscard]] int colour_of(Index b) const {
    int colour = 0, weight = 1;
    for (int a = 0; a < D; ++a) {
      colour += static_cast<int>((b / brick_stride_[a]) % bricks_[a] % colours_per_axis_) * weight;
      weight *= colours_per_axis_;
    }
    return colour;
  }
  /// The cells in brick-major order (bricks in x-fastest order, cells x-fastest inside a brick):
  /// the key by which sort_by_cell stores the particles, so that a brick's particles lie together.
  [[nodiscard]] static Index brick_major_cell(const Grid<D>& grid, const std::array<int, D>& cell) {
    Index brick = 0, brick_stride = 1, local = 0, local_stride = 1;
    for (int a = 0; a < D; ++a) {
      brick += static_cast<Index>(cell[a] >> brick_shift(a)) * brick_stride;
      brick_stride *= bricks_along(grid, a);
      local += static_cast<Index>(cell[a] & (brick_cells(a) - 1)) * local_stride;
      local_stride *= brick_cells(a);
    }
    return brick * local_stride + local;
  }
  [[nodiscard]] int colours() const { return static_cast<int>(colour_start_.size()) - 1; }
  [[nodiscard]] int colours_per_axis() const { return colours_per_axis_; }

  /// Calls visit(p) for every particle, brick by brick, colour after colour; the bricks of one
  /// colour are shared among the threads (fewer than kParallelMinimum particles: one thread).
  /// visit may add into any node of p's stencil without synchronisation. `arrays`: the node
  /// arrays visit adds into, which a decomposed run (`boundary` set) hands on between colours.
  template <class Visit>
  void for_each_particle(Visit&& visit, std::span<const NodeArray> arrays = {}) const {
    const bool threaded = static_cast<std::ptrdiff_t>(order_.size()) > kParallelMinimum;
    const BrickBoundary* const shared = boundary;
#pragma omp parallel if (threaded)
    for (int c = 0; c < colours(); ++c) {
#pragma omp for schedule(dynamic, 1)
      for (std::ptrdiff_t k = colour_start_[c]; k < colour_start_[c + 1]; ++k) {
        const Index b = coloured_[k];
        for (Index q = start_[b]; q < start_[b + 1]; ++q) visit(static_cast<std::size_t>(order_[q]));
      }
      if (shared != nullptr) {  // the master thread talks to the other ranks (MPI_THREAD_FUNNELED)
#pragma omp master
        shared->after_colour(c, arrays.data(), static_cast<int>(arrays.size()));
#pragma omp barrier
      }
    }
  }

  /// Set by a decomposed run (parallel/colour_hand_off.hpp); null in a serial one.
  BrickBoundary* boundary = nullptr;

 private:
  /// Calls fn(brick, begin, end) for each maximal run of consecutive particles in one brick.
  template <class Fn>
  void for_each_run(Fn&& fn) const {
    const auto n = static_cast<std::int32_t>(brick_of_.size());
    for (std::int32_t begin = 0; begin < n;) {
      const std::int32_t b = brick_of_[begin];
      std::int32_t end = begin + 1;
      while (end < n && brick_of_[end] == b) ++end;
      fn(b, begin, end);
      begin = end;
    }
  }

  void group_by_colour() {
    const int m = colours_per_axis_;
    int colour_count = 1;
    for (int a = 0; a < D; ++a) colour_count *= m;
    // Counted, then placed: a counting sort of the non-empty bricks by colour (colour_of is cheap,
    // so it is computed twice rather than kept).
    colour_start_.assign(static_cast<std::size_t>(colour_count) + 1, 0);
    for (Index b = 0; b < brick_count_; ++b)
      if (start_[b] != start_[b + 1]) ++colour_start_[colour_of(b) + 1];
    for (int c = 0; c < colour_count; ++c) colour_start_[c + 1] += colour_start_[c];
    coloured_.resize(static_cast<std::size_t>(colour_start_[colour_count]));
    std::vector<std::ptrdiff_t> next(colour_start_.begin(), colour_start_.end() - 1);
    for (Index b = 0; b < brick_count_; ++b)
      if (start_[b] != start_[b + 1]) coloured_[next[colour_of(b)]++] = b;
  }

  std::array<Index, D> bricks_{}, brick_stride_{};
  Index brick_count_ = 0;
  int colours_per_axis_ = 2;
  std::vector<std::int32_t> brick_of_;        // by particle storage index
  std::vector<Index> start_, fill_;           // particles of brick b: order_[start_[b] .. start_[b + 1])
  std::vector<std::int32_t> order_;           // particle storage indices grouped by brick
  std::vector<std::ptrdiff_t> colour_start_;  // bricks of colour c: coloured_[colour_start_[c] ..]
  std::vector<Index> coloured_;               // non-empty bricks, by colour, ascending within one
};

}  // namespace matpoint
