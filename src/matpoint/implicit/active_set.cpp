#include "matpoint/implicit/active_set.hpp"

namespace matpoint::implicit {

ActiveSet build_active_set(Index node_count, int nodes_per_element, std::span<const Index> connectivity,
                           std::span<const Index> particle_element, std::span<const char> always_active) {
  const auto elements = static_cast<Index>(connectivity.size()) / nodes_per_element;
  ActiveSet s;
  s.particles_in_element.assign(static_cast<std::size_t>(elements), 0);
  for (const Index e : particle_element)
    if (e >= 0) ++s.particles_in_element[static_cast<std::size_t>(e)];
  s.active.assign(static_cast<std::size_t>(elements), 0);
  for (Index e = 0; e < elements; ++e) {
    const auto k = static_cast<std::size_t>(e);
    s.active[k] = s.particles_in_element[k] > 0 || (k < always_active.size() && always_active[k] != 0);
  }
  s.node_active.assign(static_cast<std::size_t>(node_count), 0);
  s.node_touches_inactive.assign(static_cast<std::size_t>(node_count), 0);
  for (Index e = 0; e < elements; ++e) {
    const bool active = s.element_active(e);
    (active ? s.active_elements : s.inactive_elements).push_back(e);
    auto& mark = active ? s.node_active : s.node_touches_inactive;
    for (int i = 0; i < nodes_per_element; ++i)
      mark[static_cast<std::size_t>(connectivity[static_cast<std::size_t>(e * nodes_per_element + i)])] = 1;
  }
  return s;
}

ParticlesByElement sort_particles_by_element(const ActiveSet& set, std::span<const Index> particle_element) {
  // Counting sort: the start of each element's group, then a stable fill.
  std::vector<Index> start(set.particles_in_element.size() + 1, 0);
  for (std::size_t e = 0; e < set.particles_in_element.size(); ++e)
    start[e + 1] = start[e] + set.particles_in_element[e];
  ParticlesByElement out;
  out.order.resize(static_cast<std::size_t>(start.back()));
  std::vector<Index> next(start.begin(), start.end() - 1);
  for (std::size_t p = 0; p < particle_element.size(); ++p)
    if (const Index e = particle_element[p]; e >= 0)
      out.order[static_cast<std::size_t>(next[static_cast<std::size_t>(e)]++)] = static_cast<Index>(p);
  out.begin.reserve(set.active_elements.size() + 1);
  for (const Index e : set.active_elements) out.begin.push_back(start[static_cast<std::size_t>(e)]);
  out.begin.push_back(start.back());
  return out;
}

}  // namespace matpoint::implicit
