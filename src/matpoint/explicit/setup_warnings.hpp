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
  if (spec.heat.enabled && spec.heat.contact == ThermalContact::Conductance)
    out.push_back(
        "heat.contact \"conductance\": the nodal contact area is estimated from the bodies' volume "
        "gradients, exact where the interface lies on grid lines; with the interface inside a cell the "
        "shared free surfaces do not cancel and the area, hence the heat exchanged, comes out too large "
        "(1.8 times on a strip cut mid-cell; docs/theory/heat.md \"Contact\")");
  return out;
}

}  // namespace matpoint
