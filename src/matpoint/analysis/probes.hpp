// Probes (output.probes): particles followed through the run, recorded at every output time in
// history.csv. A probe follows the particle whose reference (Lagrangian) position is nearest the
// probe's position, so a restart follows the same particle. Per probe and output, in this order:
//   position x (D), displacement u = x - X (D), velocity v (D), Cauchy stress components
//   (xx; xx yy xy; xx yy zz xy xz yz in 1-, 2-, 3-D) and det F.
// In a decomposed run (docs/scale-out.md §8) a probed particle lives on one rank: the functions
// taking a Communicator are collectives that give every rank the same ids and values.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "matpoint/io/spec.hpp"
#include "matpoint/parallel/communicator.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

/// The (row, column) of each stress component a probe records, by dimension.
template <int D>
constexpr auto probe_stress_components() {
  if constexpr (D == 1)
    return std::array<std::array<int, 2>, 1>{{{0, 0}}};
  else if constexpr (D == 2)
    return std::array<std::array<int, 2>, 3>{{{0, 0}, {1, 1}, {0, 1}}};
  else
    return std::array<std::array<int, 2>, 6>{{{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}}};
}

/// The history.csv column names of one probe: probe_NAME_x, ..._ux, ..._vx, ..._sxx, ..._J.
inline std::vector<std::string> probe_column_names(const std::string& name, int dim) {
  static constexpr const char* axis = "xyz";
  static const std::array<std::vector<std::string>, 3> stress{
      {{"sxx"}, {"sxx", "syy", "sxy"}, {"sxx", "syy", "szz", "sxy", "sxz", "syz"}}};
  const std::string prefix = "probe_" + name + "_";
  std::vector<std::string> out;
  for (const char* quantity : {"", "u", "v"})
    for (int a = 0; a < dim; ++a) out.push_back(prefix + quantity + axis[a]);
  for (const auto& component : stress[dim - 1]) out.push_back(prefix + component);
  out.push_back(prefix + "J");
  return out;
}

namespace probes_detail {

/// For each probe, the id of the nearest of n points (position(k), id(k)), ties to the lowest id
/// (-1 for none); `distances`, when given, receives the squared distances (+infinity for none).
template <int D, class Position, class Id>
std::vector<long> nearest_ids(const std::vector<ProbeSpec>& probes, std::size_t n, const Position& position,
                              const Id& id, std::vector<double>* distances = nullptr) {
  std::vector<long> ids;
  for (const auto& probe : probes) {
    Vec<D> target;
    for (int a = 0; a < D; ++a) target[a] = probe.position[a];
    long best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < n; ++k) {
      const double distance = (position(k) - target).squaredNorm();
      if (distance < best_distance || (distance == best_distance && id(k) < best)) {
        best_distance = distance;
        best = id(k);
      }
    }
    ids.push_back(best);
    if (distances) distances->push_back(best_distance);
  }
  return ids;
}

/// Appends particle p's probe values (column order of probe_column_names).
template <int D>
void append_probe_row(const ParticleSet<D>& particles, std::size_t p, std::vector<double>& out) {
  const Vec<D>& x = particles.x[p];
  for (int a = 0; a < D; ++a) out.push_back(x[a]);
  for (int a = 0; a < D; ++a) out.push_back(x[a] - particles.x0[p][a]);
  for (int a = 0; a < D; ++a) out.push_back(particles.v[p][a]);
  for (const auto& [i, j] : probe_stress_components<D>()) out.push_back(particles.stress[p](i, j));
  out.push_back(particles.F[p].determinant());
}

/// For each of `ids`, the `width` values that `row(p, out)` appends for the particle with that id,
/// wherever it lives: every rank gathers every rank's rows (rank order), so all get the same.
/// `found[k]` tells whether any rank holds ids[k] (its values are NaN otherwise).
template <int D, class Row>
std::vector<double> gather_rows(const ParticleSet<D>& particles, const std::vector<long>& ids,
                                std::size_t width, const Communicator& comm, const Row& row,
                                std::vector<char>& found) {
  std::vector<double> mine;  // per probe k whose particle is here: k, then its row
  for (std::size_t p = 0; p < particles.size(); ++p)
    for (std::size_t k = 0; k < ids.size(); ++k)
      if (particles.id[p] == ids[k]) {
        mine.push_back(static_cast<double>(k));
        row(p, mine);
      }
  const std::vector<double> all = comm.all_gather(mine);
  if (all.size() % (width + 1) != 0) throw std::logic_error("probes: a gathered row of the wrong width");
  std::vector<double> out(ids.size() * width, std::numeric_limits<double>::quiet_NaN());
  found.assign(ids.size(), 0);
  for (std::size_t at = 0; at < all.size(); at += width + 1) {
    const auto k = static_cast<std::size_t>(all[at]);
    if (found[k]) continue;  // an id held twice: the lowest rank's
    found[k] = 1;
    std::copy(all.begin() + static_cast<std::ptrdiff_t>(at + 1),
              all.begin() + static_cast<std::ptrdiff_t>(at + 1 + width),
              out.begin() + static_cast<std::ptrdiff_t>(k * width));
  }
  return out;
}

}  // namespace probes_detail

/// Ids followed by the probes: the nearest reference position (by id: an implicit run's nodes),
/// ties to the lowest id.
template <int D>
std::vector<long> probe_particle_ids(const std::vector<Vec<D>>& reference_position,
                                     const std::vector<ProbeSpec>& probes) {
  return probes_detail::nearest_ids<D>(
      probes, reference_position.size(),
      [&](std::size_t k) -> const Vec<D>& { return reference_position[k]; },
      [](std::size_t k) { return static_cast<long>(k); });
}

/// Particle ids followed by the probes: the particle whose reference position X_p (particles.x0)
/// is nearest, ties to the lowest id (the storage order does not matter).
template <int D>
std::vector<long> probe_particle_ids(const ParticleSet<D>& particles, const std::vector<ProbeSpec>& probes) {
  return probes_detail::nearest_ids<D>(
      probes, particles.size(), [&](std::size_t p) -> const Vec<D>& { return particles.x0[p]; },
      [&](std::size_t p) { return particles.id[p]; });
}

/// The same over every rank's particles (a collective in a decomposed run): each rank's nearest
/// particle, then the nearest of those, ties to the lowest id; every rank gets the same ids.
template <int D>
std::vector<long> probe_particle_ids(const ParticleSet<D>& particles, const std::vector<ProbeSpec>& probes,
                                     const Communicator& comm) {
  if (!comm.distributed()) return probe_particle_ids<D>(particles, probes);
  std::vector<double> distances;
  const std::vector<long> mine = probes_detail::nearest_ids<D>(
      probes, particles.size(), [&](std::size_t p) -> const Vec<D>& { return particles.x0[p]; },
      [&](std::size_t p) { return particles.id[p]; }, &distances);
  std::vector<double> pairs;  // per probe: squared distance, id (exact as a double below 2^53)
  for (std::size_t k = 0; k < mine.size(); ++k)
    pairs.insert(pairs.end(), {distances[k], static_cast<double>(mine[k])});
  const std::vector<double> all = comm.all_gather(pairs);  // every rank's, in rank order
  std::vector<long> ids(probes.size(), -1);
  std::vector<double> best(probes.size(), std::numeric_limits<double>::infinity());
  for (std::size_t at = 0; at + 1 < all.size(); at += 2) {
    const std::size_t k = (at / 2) % probes.size();
    const auto id = static_cast<long>(all[at + 1]);
    if (id < 0) continue;  // a rank without particles
    if (all[at] < best[k] || (all[at] == best[k] && (ids[k] < 0 || id < ids[k])))
      best[k] = all[at], ids[k] = id;
  }
  return ids;
}

/// Appends the probe values (column order of probe_column_names) of the particles `ids`
/// (0 <= id < particles.size(): ids are the generation order).
template <int D>
void append_probe_values(const ParticleSet<D>& particles, const std::vector<long>& ids,
                         std::vector<double>& out) {
  if (ids.empty()) return;
  std::vector<long> index_of(particles.size(), -1);
  for (std::size_t p = 0; p < particles.size(); ++p) index_of[particles.id[p]] = static_cast<long>(p);
  for (long id : ids) probes_detail::append_probe_row(particles, static_cast<std::size_t>(index_of[id]), out);
}

/// The same when the particles are spread over the ranks (a collective in a decomposed run; any
/// ids): the rank that holds a probed particle contributes its values, every rank gets all of
/// them (NaN for an id no rank holds).
template <int D>
void append_probe_values(const ParticleSet<D>& particles, const std::vector<long>& ids,
                         std::vector<double>& out, const Communicator& comm) {
  if (!comm.distributed()) return append_probe_values(particles, ids, out);
  if (ids.empty()) return;
  constexpr std::size_t width = 3 * D + probe_stress_components<D>().size() + 1;
  std::vector<char> found;
  const auto rows = probes_detail::gather_rows(
      particles, ids, width, comm,
      [&](std::size_t p, std::vector<double>& row) { probes_detail::append_probe_row(particles, p, row); },
      found);
  out.insert(out.end(), rows.begin(), rows.end());
}

/// The reference positions X (particles.x0) of the probed particles `ids` that some rank holds,
/// as (id, X) in the order of `ids`, on every rank (a collective in a decomposed run).
template <int D>
std::vector<std::pair<long, Vec<D>>> probe_reference_positions(const ParticleSet<D>& particles,
                                                               const std::vector<long>& ids,
                                                               const Communicator& comm) {
  std::vector<std::pair<long, Vec<D>>> out;
  if (!comm.distributed()) {
    for (long id : ids)
      for (std::size_t p = 0; p < particles.size(); ++p)
        if (particles.id[p] == id) out.emplace_back(id, particles.x0[p]);
    return out;
  }
  std::vector<char> found;
  const auto rows = probes_detail::gather_rows(
      particles, ids, D, comm,
      [&](std::size_t p, std::vector<double>& row) {
        for (int a = 0; a < D; ++a) row.push_back(particles.x0[p][a]);
      },
      found);
  for (std::size_t k = 0; k < ids.size(); ++k)
    if (found[k]) out.emplace_back(ids[k], Eigen::Map<const Vec<D>>(rows.data() + k * D));
  return out;
}

}  // namespace matpoint
