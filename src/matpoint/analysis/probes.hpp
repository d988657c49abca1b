// Probes (output.probes): particles followed through the run, recorded at every output time in
// history.csv. A probe follows the particle whose reference (Lagrangian) position is nearest the
// probe's position, so a restart follows the same particle. Per probe and output, in this order:
//   position x (D), displacement u = x - X (D), velocity v (D), Cauchy stress components
//   (xx; xx yy xy; xx yy zz xy xz yz in 1-, 2-, 3-D) and det F.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "matpoint/io/spec.hpp"
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

/// For each probe, the id of the nearest of n points (position(k), id(k)), ties to the lowest id.
template <int D, class Position, class Id>
std::vector<long> nearest_ids(const std::vector<ProbeSpec>& probes, std::size_t n, const Position& position,
                              const Id& id) {
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
  }
  return ids;
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

/// Appends the probe values (column order of probe_column_names) of the particles `ids`
/// (0 <= id < particles.size(): ids are the generation order).
template <int D>
void append_probe_values(const ParticleSet<D>& particles, const std::vector<long>& ids,
                         std::vector<double>& out) {
  if (ids.empty()) return;
  std::vector<long> index_of(particles.size(), -1);
  for (std::size_t p = 0; p < particles.size(); ++p) index_of[particles.id[p]] = static_cast<long>(p);
  for (long id : ids) {
    const auto p = static_cast<std::size_t>(index_of[id]);
    const Vec<D>& x = particles.x[p];
    for (int a = 0; a < D; ++a) out.push_back(x[a]);
    for (int a = 0; a < D; ++a) out.push_back(x[a] - particles.x0[p][a]);
    for (int a = 0; a < D; ++a) out.push_back(particles.v[p][a]);
    for (const auto& [i, j] : probe_stress_components<D>()) out.push_back(particles.stress[p](i, j));
    out.push_back(particles.F[p].determinant());
  }
}

}  // namespace matpoint
