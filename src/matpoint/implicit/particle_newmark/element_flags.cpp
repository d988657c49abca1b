#include "matpoint/implicit/particle_newmark/element_flags.hpp"

namespace matpoint::implicit {

std::string SoftStiffnessTable::validate() const {
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    if (pieces[k].value < 0.0) return "C_E values must be >= 0";
    if (k > 0 && pieces[k].below <= pieces[k - 1].below) return "the M_E bounds must increase";
    if (k > 0 && pieces[k].value > pieces[k - 1].value) return "C_E must not increase with M_E";
  }
  return {};
}

std::vector<int> element_flags(const ActiveSet& set, int nodes_per_element,
                               std::span<const Index> connectivity, FlagRule rule,
                               std::span<const char> not_fully_active) {
  std::vector<int> flags;
  flags.reserve(set.active_elements.size());
  for (const Index e : set.active_elements) {
    int m = nodes_per_element;
    for (int i = 0; i < nodes_per_element; ++i) {
      const auto node =
          static_cast<std::size_t>(connectivity[static_cast<std::size_t>(e * nodes_per_element + i)]);
      const bool marked =
          rule == FlagRule::Code && node < not_fully_active.size() && not_fully_active[node] != 0;
      if (set.node_touches_inactive[node] != 0 || marked) --m;
    }
    flags.push_back(m);
  }
  return flags;
}

std::vector<double> soft_stiffness_factors(std::span<const int> flags, const SoftStiffnessTable& table,
                                           FlagRule rule) {
  std::vector<double> c;
  c.reserve(flags.size());
  for (const int m : flags) c.push_back(rule == FlagRule::Code && m < 2 ? 0.0 : table(m));
  return c;
}

}  // namespace matpoint::implicit
