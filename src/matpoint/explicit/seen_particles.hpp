// The particles that see a grid node, for the logistic-regression contact normals (Nairn 2026
// extraction §2.5; explicit/contact.hpp) in a decomposed run (issue 23, docs/scale-out.md §17
// stage 5): a contact node near a rank boundary is seen by particles of two ranks, and its fit must
// read all of them in the serial run's order to give the serial normal to the bit.
//
// Each rank lists, per contact node, its own particles that see it (SeenParticle: what the fit and
// the gap read of a particle, and its serial storage order (key, id)); for the nodes that another
// rank stores too (SharedNodes, from the two ranks' grid windows) it sends that list to the
// other rank, and appends what it receives. Sorted by (key, id), the merged list is the serial
// run's: the serial run stores its particles in (brick-major cell at the last sort, id) order, and
// a decomposed run carries each particle's key with it (parallel/particle_migration.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/index_box.hpp"
#include "matpoint/parallel/bytes.hpp"
#include "matpoint/parallel/communicator.hpp"
#include "matpoint/particles/serial_order.hpp"

namespace matpoint {

/// A particle that sees a node: its field, position and domain (F, size0: the half-extent of the
/// gap, ParticleSet::half_extent), and its place in the serial storage order.
template <int D>
struct SeenParticle {
  Index key = 0;  // brick-major cell at the last sort
  long id = 0;
  int field = 0;
  Vec<D> x = Vec<D>::Zero();
  Mat<D> F = Mat<D>::Identity();
  Vec<D> size0 = Vec<D>::Zero();

  /// ParticleSet::half_extent's arithmetic: the deformed half-extent along n.
  [[nodiscard]] double half_extent(const Vec<D>& n) const {
    return 0.5 * (F.transpose() * n).cwiseAbs().dot(size0);
  }
  [[nodiscard]] bool before(const SeenParticle& other) const {
    return serially_before(key, id, other.key, other.id);
  }
};

/// The nodes that this rank and `rank` both store.
template <int D>
struct SharedNodes {
  int rank = 0;
  IndexBox<D> nodes;
};

/// Sends, for every listed node that another rank stores too, this rank's seen particles to it,
/// and appends the other ranks' to the node's list. A collective (every rank calls it).
/// `nodes[k]`: the grid node (of this rank's window) of list k; `slot_of_node`: its inverse (-1 for
/// a node without a list).
template <int D>
void exchange_seen_particles(const Communicator& comm, const Grid<D>& grid,
                             const std::vector<SharedNodes<D>>& shared, const std::vector<Index>& nodes,
                             const std::vector<int>& slot_of_node,
                             std::vector<std::vector<SeenParticle<D>>>& seen) {
  std::vector<std::vector<char>> out(static_cast<std::size_t>(comm.size()));
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (seen[k].empty()) continue;
    const std::array<int, D> ijk = grid.node_coords(nodes[k]);
    for (const SharedNodes<D>& s : shared) {
      if (!s.nodes.contains(ijk)) continue;
      auto& message = out[static_cast<std::size_t>(s.rank)];
      bytes::append(message, ijk);
      bytes::append(message, seen[k].size());
      for (const SeenParticle<D>& p : seen[k]) bytes::append(message, p);
    }
  }
  const auto arrived = comm.exchange(out);
  constexpr const char* kWhat = "seen particles";
  for (const std::vector<char>& message : arrived) {
    std::size_t at = 0;
    while (at < message.size()) {
      const auto ijk = bytes::take<std::array<int, D>>(message, at, kWhat);
      const auto count = bytes::take<std::size_t>(message, at, kWhat);
      // Both ranks find the same contact nodes on the nodes they both store (complete sums), so
      // the node has a list here; a node without one would be a broken invariant.
      const int k = grid.stores(ijk) ? slot_of_node[static_cast<std::size_t>(grid.node_index(ijk))] : -1;
      if (k < 0) throw std::logic_error("seen particles: a shared node that is no contact node here");
      for (std::size_t q = 0; q < count; ++q)
        seen[static_cast<std::size_t>(k)].push_back(bytes::take<SeenParticle<D>>(message, at, kWhat));
    }
  }
}

}  // namespace matpoint
