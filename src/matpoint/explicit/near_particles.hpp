// Ghost particles: the particles near a rank's grid window, its own and its neighbours', in the
// serial storage order (issue 23, docs/scale-out.md §16). Two computations of a decomposed run
// read particles of other ranks at the nodes they evaluate, and are not particle-to-grid sums in
// the brick order that the colour hand-off carries:
// - the MLS reconstructions (Gong 2015 §5.4 and §6.6, explicit/mls_mapping.hpp): a node or cell
//   point gathers the particles within two cells of it (mls_band: the window's cells and three
//   cells more below, two above, along every axis: the cubic weight's support at the nodes, the
//   quadratic weight's at the cell points);
// - the nodal volumes of the heat contact conductance (explicit/thermal_contact.hpp): sums over
//   the particles' GIMP domains in storage order (domain_band: the domain stencils' width).
// Every rank sends each neighbour the particles of its cells in the neighbour's band, with what
// those computations read of a particle (GhostParticle) and its place in the serial storage order
// (key, id), and merges what arrives with its own particles in (key, id) order: the serial run's
// storage order (the serial run stores its particles in (brick-major cell at the last sort, id)
// order, and a decomposed run carries each particle's key with it), so that every gather and every
// sum visits the particles in the serial order and gives the serial result to the bit.
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/grid/index_box.hpp"
#include "matpoint/parallel/bytes.hpp"
#include "matpoint/parallel/communicator.hpp"
#include "matpoint/particles/particle_set.hpp"
#include "matpoint/particles/serial_order.hpp"

namespace matpoint {

/// What the MLS reconstructions and the contact volumes read of a particle of another rank (the
/// body force: the MLS mappings' b_p, or zero), and its serial order.
template <int D>
struct GhostParticle {
  Vec<D> x, v, body_force, size0;
  Mat<D> F, stress;
  double mass = 0.0, volume0 = 0.0;
  Index key = 0;
  long id = 0;
  int material = 0, body = 0;
};

template <int D>
class NearParticles {
 public:
  /// The cells whose particles the MLS reconstructions of a rank storing the nodes `stored` read:
  /// a node sees the cells within two of it (cubic weight), a cell point in the cells next to a
  /// stored node the cells within 1.5 cells.
  static IndexBox<D> mls_band(const Grid<D>& grid, const IndexBox<D>& stored) {
    return grown(grid, stored, 3, 2);
  }
  /// The cells whose particles' stencils of `width` nodes per axis (the lowest at most width - 1
  /// nodes below the particle's cell, the highest at most width - 1 above its lowest node) reach
  /// the nodes `stored`.
  static IndexBox<D> domain_band(const Grid<D>& grid, const IndexBox<D>& stored, int width) {
    return grown(grid, stored, width - 1, width - 1);
  }

  /// Gathers this rank's particles (`own`, with their sort keys `keys` and body forces `body`, or
  /// none) and the other ranks' in this rank's band; `band_of(r)`: rank r's band (every rank
  /// computes the same bands). A collective. Then particles() and body() hold them in serial order.
  template <class BandOf>
  void gather(const Communicator& comm, const Grid<D>& grid, const ParticleSet<D>& own,
              const std::vector<Index>& keys, const std::vector<Vec<D>>* body, BandOf&& band_of) {
    const int me = comm.rank();
    const IndexBox<D> mine = band_of(me);
    // The cells this rank's particles lie in, and their bounding box: only the ranks whose band
    // meets it read any of them (a few neighbours, not every rank of a large run).
    std::vector<std::array<int, D>> cells(own.size());
    IndexBox<D> held;
    held.begin.fill(std::numeric_limits<int>::max());
    held.end.fill(std::numeric_limits<int>::min());
    for (std::size_t p = 0; p < own.size(); ++p) {
      cells[p] = grid.cell_coords(own.x[p]);
      for (int a = 0; a < D; ++a)
        held.begin[a] = std::min(held.begin[a], cells[p][a]),
        held.end[a] = std::max(held.end[a], cells[p][a] + 1);
    }
    std::vector<std::pair<int, IndexBox<D>>> neighbours;  // rank, band: those that read my particles
    for (int r = 0; r < comm.size(); ++r) {
      const IndexBox<D> theirs = band_of(r);
      if (r != me && !theirs.intersection(held).empty()) neighbours.push_back({r, theirs});
    }
    std::vector<std::vector<char>> out(static_cast<std::size_t>(comm.size()));
    for (std::size_t p = 0; p < own.size(); ++p) {
      const auto& cell = cells[p];
      for (const auto& [r, theirs] : neighbours)
        if (theirs.contains(cell))
          bytes::append(out[static_cast<std::size_t>(r)], ghost_of(own, keys, body, p));
    }
    std::vector<GhostParticle<D>> ghosts;
    for (const std::vector<char>& message : comm.exchange(out))
      for (std::size_t at = 0; at < message.size();)
        ghosts.push_back(bytes::take<GhostParticle<D>>(message, at, "near particles"));
    merge(own, keys, body, ghosts);
    band_ = mine;
  }

  /// The particles near the window (x, v, mass, volume0, size0, F, stress, material, body, id), in
  /// serial order.
  [[nodiscard]] const ParticleSet<D>& particles() const { return near_; }
  /// Their body forces (null when gather had none).
  [[nodiscard]] const std::vector<Vec<D>>* body() const { return has_body_ ? &near_body_ : nullptr; }
  /// The cells where they lie.
  [[nodiscard]] const IndexBox<D>& band() const { return band_; }

 private:
  /// The cells within `below` cells below and `above` cells above the nodes `stored` (of the
  /// grid's cells; empty for no stored node).
  static IndexBox<D> grown(const Grid<D>& grid, const IndexBox<D>& stored, int below, int above) {
    if (stored.empty()) return {};
    IndexBox<D> out;
    for (int a = 0; a < D; ++a)
      out.begin[a] = std::max(0, stored.begin[a] - below),
      out.end[a] = std::min(grid.cells[a], stored.end[a] + above);
    return out;
  }

  static GhostParticle<D> ghost_of(const ParticleSet<D>& own, const std::vector<Index>& keys,
                                   const std::vector<Vec<D>>* body, std::size_t p) {
    GhostParticle<D> g;
    g.x = own.x[p], g.v = own.v[p], g.body_force = body != nullptr ? (*body)[p] : Vec<D>::Zero();
    g.size0 = own.size0[p], g.F = own.F[p], g.stress = own.stress[p];
    g.mass = own.mass[p], g.volume0 = own.volume0[p];
    g.key = keys[p], g.id = own.id[p];
    g.material = own.material[p], g.body = own.body[p];
    return g;
  }

  /// near_ = own particles and ghosts, sorted by (key, id).
  void merge(const ParticleSet<D>& own, const std::vector<Index>& keys, const std::vector<Vec<D>>* body,
             const std::vector<GhostParticle<D>>& ghosts) {
    const std::size_t n_own = own.size(), n = n_own + ghosts.size();
    const auto key_of = [&](std::size_t k) { return k < n_own ? keys[k] : ghosts[k - n_own].key; };
    const auto id_of = [&](std::size_t k) { return k < n_own ? own.id[k] : ghosts[k - n_own].id; };
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return serially_before(key_of(a), id_of(a), key_of(b), id_of(b));
    });
    has_body_ = body != nullptr;
    for (auto* array : {&near_.x, &near_.v, &near_.size0, &near_body_}) array->resize(n);
    for (auto* array : {&near_.F, &near_.stress}) array->resize(n);
    for (auto* array : {&near_.material, &near_.body}) array->resize(n);
    near_.mass.resize(n), near_.volume0.resize(n), near_.id.resize(n);
    for (std::size_t q = 0; q < n; ++q) {
      const std::size_t k = order[q];
      const GhostParticle<D> g = k < n_own ? ghost_of(own, keys, body, k) : ghosts[k - n_own];
      near_.x[q] = g.x, near_.v[q] = g.v, near_.size0[q] = g.size0, near_body_[q] = g.body_force;
      near_.F[q] = g.F, near_.stress[q] = g.stress;
      near_.mass[q] = g.mass, near_.volume0[q] = g.volume0, near_.id[q] = g.id;
      near_.material[q] = g.material, near_.body[q] = g.body;
    }
  }

  ParticleSet<D> near_;
  std::vector<Vec<D>> near_body_;
  bool has_body_ = false;
  IndexBox<D> band_;
};

}  // namespace matpoint
