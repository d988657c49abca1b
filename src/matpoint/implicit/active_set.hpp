// Active and inactive parts of a background mesh for one step (Aulisa & Capodaglio §2, eq. (4)):
// T_ab = elements hosting at least one particle, T_ib = the others, I_ab = nodes of active elements,
// I_ib = nodes that belong only to inactive elements. Generic: every particle formulation on a
// mesh needs it.
#pragma once

#include <span>
#include <vector>

#include "matpoint/core/types.hpp"

namespace matpoint::implicit {

struct ActiveSet {
  std::vector<Index> particles_in_element;  // per mesh element
  std::vector<char> active;                 // per mesh element: T_ab, or an element of an FE body
  std::vector<Index> active_elements;       // T_ab, ascending ids
  std::vector<Index> inactive_elements;     // T_ib, ascending ids
  std::vector<char> node_active;            // 1 for I_ab, 0 for I_ib
  std::vector<char> node_touches_inactive;  // 1 where the node belongs to at least one element of T_ib

  [[nodiscard]] bool element_active(Index e) const { return active[static_cast<std::size_t>(e)] != 0; }
};

/// From the host element of every particle (-1: none). connectivity: nodes_per_element ids per element.
/// always_active (per element, may be empty): elements active without particles, the elements of
/// FE bodies (Aulisa & Capodaglio §4: they belong to neither T_ab nor T_ib, and their nodes are
/// never in I_ib).
ActiveSet build_active_set(Index node_count, int nodes_per_element, std::span<const Index> connectivity,
                           std::span<const Index> particle_element, std::span<const char> always_active = {});

/// Particle indices grouped by host element (stable: ascending index within an element), and the
/// start of each active element's group: order[begin[k]..begin[k+1]) are the particles of
/// active_elements[k].
struct ParticlesByElement {
  std::vector<Index> order;
  std::vector<Index> begin;
};
ParticlesByElement sort_particles_by_element(const ActiveSet& set, std::span<const Index> particle_element);

}  // namespace matpoint::implicit
