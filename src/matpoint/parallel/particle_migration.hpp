// Particles between the ranks of a decomposed explicit run (issue 23; docs/scale-out.md §5, §6).
//
// A particle lives on the rank that owns its cell's brick (parallel/box_partition.hpp). At
// the end of every step the particles that moved into another rank's cells are packed (every array
// of for_each_array, so none is left behind), sent, and appended by the receivers; the departed are
// removed by a stable compaction. The scatter must visit a brick's particles in the order the
// serial run stores them: (brick-major cell at the last sort_by_cell, id). The particles sorted at
// the last sort keep that order through the compaction; the arrivals come after them, so each
// particle carries its sort key, and the brick order puts the arrivals in place
// (BrickSchedule::order_arrivals).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/grid/brick_schedule.hpp"
#include "matpoint/grid/grid.hpp"
#include "matpoint/parallel/bytes.hpp"
#include "matpoint/parallel/communicator.hpp"
#include "matpoint/parallel/box_partition.hpp"
#include "matpoint/parallel/traffic.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

template <int D>
class ParticleMigration {
 public:
  ParticleMigration(const Grid<D>& grid, const BoxPartition<D>& partition, const Communicator& comm)
      : grid_(grid), partition_(partition), comm_(comm) {}

  /// The set-up's particles of this rank (build_simulation generated only those, sorted by cell):
  /// their sort keys. A particle in another rank's cells would be a broken invariant.
  void start(const ParticleSet<D>& ps) {
    std::vector<Index> key(ps.size());
    for (std::size_t p = 0; p < ps.size(); ++p) {
      const auto cell = grid_.cell_coords(ps.x[p]);
      if (partition_.owner_of_cell(cell) != comm_.rank())
        throw std::logic_error("particle migration: the set-up left a particle of another rank here");
      key[p] = BrickSchedule<D>::brick_major_cell(grid_, cell);
    }
    key_ = std::move(key);
    sorted_prefix_ = ps.size();
  }

  /// After sort_by_cell: every particle is in (key, id) order, with key[p] its present
  /// brick-major cell (as sort_by_cell computed it).
  void sorted(std::vector<Index> key) {
    key_ = std::move(key);
    sorted_prefix_ = key_.size();
  }

  /// Sends the particles whose cells another rank owns, appends those that arrive. A collective.
  void migrate(ParticleSet<D>& ps) {
    const auto t0 = Traffic::start();
    const int P = comm_.size(), me = comm_.rank();
    std::vector<std::vector<std::size_t>> leaving(static_cast<std::size_t>(P));
    std::vector<char> keep(ps.size(), 1);
    std::size_t first_departure = ps.size();
    for (std::size_t p = 0; p < ps.size(); ++p) {
      const int owner = partition_.owner_of_cell(grid_.cell_coords(ps.x[p]));
      if (owner == me) continue;
      keep[p] = 0;
      first_departure = std::min(first_departure, p);
      leaving[static_cast<std::size_t>(owner)].push_back(p);
    }
    std::vector<std::vector<char>> out(static_cast<std::size_t>(P));
    for (int r = 0; r < P; ++r)
      if (r != me && !leaving[static_cast<std::size_t>(r)].empty())
        out[static_cast<std::size_t>(r)] = pack(ps, leaving[static_cast<std::size_t>(r)]);
    for (std::size_t r = 0; r < out.size(); ++r) traffic.sent(out[r].size(), leaving[r].size());
    const auto t1 = Traffic::start();
    const auto arrived = comm_.exchange(out);
    traffic.waited(t1);
    std::size_t survivors_in_prefix = 0;
    for (std::size_t p = 0; p < sorted_prefix_; ++p) survivors_in_prefix += keep[p] != 0 ? 1 : 0;
    if (first_departure < ps.size()) {  // nothing moves in front of the first departure
      compact(ps, keep, first_departure);
      compact_keys(keep, first_departure);
    }
    sorted_prefix_ = survivors_in_prefix;
    for (int r = 0; r < P; ++r)
      if (r != me && !arrived[static_cast<std::size_t>(r)].empty())
        unpack(ps, arrived[static_cast<std::size_t>(r)]);
    traffic.done(t0);
  }

  /// Particles, messages, bytes and seconds of every migration so far (summary.json's `parallel`).
  Traffic traffic;

  [[nodiscard]] const std::vector<Index>& keys() const { return key_; }
  [[nodiscard]] std::size_t sorted_prefix() const { return sorted_prefix_; }
  /// A restart: the keys and sorted prefix of the particles a checkpoint stored (in their order).
  void restore(std::vector<Index> keys, std::size_t sorted_prefix) {
    if (sorted_prefix > keys.size())
      throw std::logic_error("particle migration: a sorted prefix past the keys");
    key_ = std::move(keys);
    sorted_prefix_ = sorted_prefix;
  }

 private:
  /// Removes the particles with keep[p] == 0, keeping the order of the others (none before
  /// first_departure is removed, so those stay where they are).
  static void compact(ParticleSet<D>& ps, const std::vector<char>& keep, std::size_t first_departure = 0) {
    for_each_array(ps, [&keep, first_departure](const char*, auto& array, std::size_t count) {
      std::size_t to = first_departure;
      for (std::size_t p = first_departure; p < keep.size(); ++p) {
        if (keep[p] == 0) continue;
        if (to != p)
          for (std::size_t k = 0; k < count; ++k) array[to * count + k] = array[p * count + k];
        ++to;
      }
      array.resize(to * count);
    });
  }

  void compact_keys(const std::vector<char>& keep, std::size_t first_departure) {
    std::size_t to = first_departure;
    for (std::size_t p = first_departure; p < keep.size(); ++p)
      if (keep[p] != 0) key_[to++] = key_[p];
    key_.resize(to);
  }

  /// The particles `which`: their count, then each array of for_each_array in its order, then the keys.
  std::vector<char> pack(const ParticleSet<D>& ps, const std::vector<std::size_t>& which) const {
    std::vector<char> message;
    bytes::append(message, static_cast<std::size_t>(which.size()));
    for_each_array(ps, [&](const char*, const auto& array, std::size_t count) {
      for (const std::size_t p : which)
        for (std::size_t k = 0; k < count; ++k) bytes::append(message, array[p * count + k]);
    });
    for (const std::size_t p : which) bytes::append(message, key_[p]);
    return message;
  }

  static constexpr const char* kWhat = "particle migration";

  void unpack(ParticleSet<D>& ps, const std::vector<char>& message) {
    std::size_t at = 0;
    const auto n = bytes::take<std::size_t>(message, at, kWhat);
    for_each_array(ps, [&](const char*, auto& array, std::size_t count) {
      using T = typename std::remove_reference_t<decltype(array)>::value_type;
      for (std::size_t q = 0; q < n * count; ++q) array.push_back(bytes::take<T>(message, at, kWhat));
    });
    for (std::size_t q = 0; q < n; ++q) key_.push_back(bytes::take<Index>(message, at, kWhat));
    if (at != message.size()) throw std::logic_error("particle migration: a message of unexpected length");
  }

  const Grid<D>& grid_;
  const BoxPartition<D>& partition_;
  Communicator comm_;
  std::vector<Index> key_;         // brick-major cell at the last sort (or on the sender's side)
  std::size_t sorted_prefix_ = 0;  // particles [0, sorted_prefix_) are in (key, id) order
};

}  // namespace matpoint
