// Element flags M_E and soft-stiffness factors C_E (Aulisa & Capodaglio §3.3, eq. (26) and the
// piecewise C_E of eqs. (50), (51), (53)).
//   Paper rule: M_E = N_E minus the number of the element's nodes that also belong to an inactive
//   element (an interior element surrounded by active ones has M_E = N_E and C_E = 0).
//   Code rule (extraction A13, the authors' code, which made the published tables): nodes marked in
//   `not_fully_active` (FEM-interface nodes and the boundaries where the code's auxiliary field has a
//   Dirichlet tag, e.g. the contact plane) also decrease M_E, and elements with M_E < 2 get no soft
//   stiffness.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "matpoint/implicit/active_set.hpp"

namespace matpoint::implicit {

enum class FlagRule { Paper, Code };

/// C_E as a non-increasing piecewise-constant function of M_E: the value of the first entry with
/// M_E < below, and 0 past the last entry. The paper's form (50): {{5, C1}, {9, C2}} for Q9.
struct SoftStiffnessTable {
  struct Piece {
    int below;
    double value;
  };
  std::vector<Piece> pieces;
  [[nodiscard]] double operator()(int flag) const {
    for (const Piece& p : pieces)
      if (flag < p.below) return p.value;
    return 0.0;
  }
  /// Empty when the table is valid; otherwise what is wrong (bounds must increase, values must not
  /// increase and must be >= 0).
  [[nodiscard]] std::string validate() const;
};

/// M_E of every active element (in the order of set.active_elements).
std::vector<int> element_flags(const ActiveSet& set, int nodes_per_element,
                               std::span<const Index> connectivity, FlagRule rule,
                               std::span<const char> not_fully_active = {});

/// C_E of every active element from its flag; the code rule gives 0 below M_E = 2.
std::vector<double> soft_stiffness_factors(std::span<const int> flags, const SoftStiffnessTable& table,
                                           FlagRule rule);

}  // namespace matpoint::implicit
