// Warnings a run gives before it starts (stderr) and keeps in summary.json "warnings": settings
// that are valid but known to give a poorer answer than the user probably expects.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "matpoint/explicit/courant_limits.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

[[nodiscard]] inline std::vector<std::string> setup_warnings(const Spec& spec) {
  std::vector<std::string> out;
  if (auto courant = courant_warning(spec.solver); !courant.empty()) out.push_back(std::move(courant));
  if (spec.solver.mass_tolerance > 0.0) {
    std::ostringstream text;
    text << "solver.mass_tolerance = " << spec.solver.mass_tolerance
         << " makes nodes lighter than that fraction of the heaviest particle inactive: the internal force on "
            "them is dropped, so linear momentum is no longer conserved exactly (the default 0 conserves it; "
            "docs/input.md)";
    out.push_back(text.str());
  }
  return out;
}

}  // namespace matpoint
