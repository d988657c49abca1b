// What a decomposed explicit run supports so far (issue 23, docs/scale-out.md §17 stage 2), and the
// input error for the rest: it names the input's path and says what a run on one rank would do.
#pragma once

#include <string>
#include <vector>

#include "matpoint/core/errors.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

/// Throws InputError (exit 2, before anything runs) for every part of `spec` that a run on
/// `ranks` > 1 ranks cannot do yet: contact, heat, the CPDI domains, the MLS mappings, one-sided
/// faces, the dynamic FMPM measure. One rank: nothing is refused. (Checkpoints and restarts work
/// on any rank count: one piece per rank and a manifest, io/checkpoint.hpp.)
inline void check_decomposable(const Spec& spec, int ranks) {
  if (ranks <= 1) return;
  const std::string expected = "a run on 1 rank: the decomposed explicit solver (" + std::to_string(ranks) +
                               " MPI ranks) does not support this yet (docs/scale-out.md §17)";
  std::vector<InputIssue> issues;
  const auto refuse = [&](std::string path, std::string value) {
    issues.push_back({std::move(path), std::move(value), expected});
  };
  if (spec.contact.enabled) refuse("contact", "multi-field contact");
  if (spec.heat.enabled) refuse("heat", "coupled heat conduction");
  switch (spec.solver.shape) {
    case ShapeKind::CPDI1:
    case ShapeKind::CPDI2:
    case ShapeKind::B2CPDI:
      refuse("solver.basis", "a CPDI basis (its ghost width grows with the domains)");
      break;
    default:
      break;
  }
  if (spec.solver.mapping != Mapping::MPM)
    refuse("solver.mapping", "an MLS mapping (it gathers neighbour particles)");
  if (spec.solver.fmpm.measure != FmpmMeasure::None)
    refuse("solver.fmpm.measure", "dynamic FMPM (its measure needs an exact global sum)");
  for (std::size_t k = 0; k < spec.conditions.size(); ++k)
    if (spec.conditions[k].one_sided) refuse("conditions[" + std::to_string(k) + "].one_sided", "true");
  if (!issues.empty()) throw InputError(std::move(issues));
}

}  // namespace matpoint
