// summary.json's `parallel` object for a decomposed run (docs/output.md; bench/scaling.md reads it):
// ranks and threads, particles per rank, and what the hand-off, the migration and the small
// collectives sent and cost per step, as the maximum and the sum over the ranks.
#pragma once

#include <nlohmann/json.hpp>

#include "matpoint/parallel/communicator.hpp"
#include "matpoint/parallel/traffic.hpp"

namespace matpoint {

/// One rank's counts at the end of a run.
struct RankTraffic {
  long particles = 0;
  long stored_nodes = 0;  // the grid nodes of its window (Grid::window), one field's
  int threads = 1;
  double step_wall = 0.0;  // wall seconds in the steps
  double step_cpu = 0.0;   // CPU seconds of the process in the steps (all its threads)
  Traffic halo;            // ColourHandOff::traffic
  Traffic migration;       // ParticleMigration::traffic
  Traffic collectives;     // the collectives of the steps and time steps
};

/// The `parallel` object from every rank's counts over `steps` steps. A collective: every rank
/// calls it and gets the same object.
[[nodiscard]] nlohmann::json parallel_summary(const Communicator& comm, const RankTraffic& mine, long steps);

/// The CPUs this process may run on (its affinity mask; the machine's count where unknown).
[[nodiscard]] int available_cpus();

}  // namespace matpoint
