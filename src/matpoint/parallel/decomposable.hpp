// What a decomposed explicit run supports so far (issue 23, docs/scale-out.md §17 stages 2 and 3),
// and the input error for the rest: it names the input's path and says what a run on one rank
// would do.
#pragma once

#include <string>
#include <vector>

#include "matpoint/core/errors.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

/// Throws InputError (exit 2, before anything runs) for every part of `spec` that a run on
/// `ranks` > 1 ranks cannot do yet: the contact conductance of coupled heat (it reads the particles
/// of other ranks). Since session 27 the logistic-regression contact normals run on ranks
/// (explicit/seen_particles.hpp), since session 28 the MLS mappings (explicit/mls_neighbourhood.hpp).
/// One rank: nothing is refused. (Checkpoints and restarts work on any rank count: one piece per rank
/// and a manifest, io/checkpoint.hpp.)
inline void check_decomposable(const Spec& spec, int ranks) {
  if (ranks <= 1) return;
  const std::string expected = "a run on 1 rank: the decomposed explicit solver (" + std::to_string(ranks) +
                               " MPI ranks) does not support this yet (docs/scale-out.md §17)";
  std::vector<InputIssue> issues;
  const auto refuse = [&](std::string path, std::string value) {
    issues.push_back({std::move(path), std::move(value), expected});
  };
  if (spec.heat.enabled && spec.contact.enabled && spec.heat.contact == ThermalContact::Conductance)
    refuse("heat.contact", "\"conductance\" (its contact areas sum the particles' domains in storage order)");
  if (!issues.empty()) throw InputError(std::move(issues));
}

}  // namespace matpoint
