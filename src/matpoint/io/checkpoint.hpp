// Checkpoints: everything an explicit run needs to continue exactly where it stopped (docs/output.md
// "Checkpoints and restart"), in one HDF5 file written atomically. A restart rebuilds the
// Simulation from the input (grid, materials, conditions) and then replaces every evolving array
// by the checkpoint's, in the checkpoint's storage order, so the next re-sort and every later step
// repeat the uninterrupted run bit for bit (same thread count). A decomposed run (several MPI ranks)
// writes one piece per rank and a manifest that names them (docs/scale-out.md §9).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "matpoint/analysis/history.hpp"
#include "matpoint/explicit/simulation.hpp"

namespace matpoint {

inline constexpr const char* kCheckpointFile = "checkpoint.h5";
inline constexpr const char* kPreviousCheckpointFile = "checkpoint.previous.h5";
// 2: particles/stress_zz (plane strain); 3: history plastic_work; 4: particles/temperature and
// the heat through the thermal conditions (coupled heat conduction)
inline constexpr long kCheckpointFormatVersion = 4;

using PvdEntries = std::vector<std::pair<double, std::string>>;  // (time, file) of a .pvd collection

/// The state of a run outside the Simulation (run/runner.cpp) that a restart continues from.
struct RunCounters {
  double dt = 0.0;              // the run's time step (computed once at time 0)
  double momentum_scale = 0.0;  // sum m |v| at time 0 (the momentum checks' scale)
  double total_mass = 0.0;      // as the stepper summed it (the external impulse of gravity)
  long outputs = 0;             // output states written: the index of the next .vtu file
  double next_output_time = 0;  // output.every_time: the next output time
  long last_recorded_step = 0;  // the step of the last output state
  double next_fmpm_time = 0.0;  // periodic FMPM (Nairn 2026 §3.3): the next FMPM time
  long fmpm_loops = 0, fmpm_passes = 0;
  double fmpm_seconds = 0.0;
  double step_wall = 0.0, step_cpu = 0.0, wall = 0.0;  // timings summed over the run's sessions
  int threads = 1;                                     // OpenMP threads of the writing run
  PvdEntries results, domains;                         // results.pvd and domains.pvd so far
  // The solver's own state (the implicit solver's particle accelerations, host elements and
  // totals): named arrays, stored as datasets solver/NAME.
  std::map<std::string, std::vector<double>> solver_state;
  // A decomposed run (docs/scale-out.md §9): the ranks' boxes of bricks (BoxPartition::ints, the
  // same on every rank; empty on one rank) and this rank's migration state (ParticleMigration::keys
  // and sorted_prefix), with which the restarted run orders its particles as the uninterrupted one.
  std::vector<int> partition;
  std::vector<std::int64_t> sort_keys;
  std::size_t sorted_prefix = 0;
  // solver.rebalance (docs/scale-out.md §10): the re-partitions so far and the step of the last
  // one (0: the start), so that a restarted run re-partitions where the uninterrupted one does.
  long repartitions = 0, partitioned_at = 0;
};

/// The piece of a decomposed run's checkpoint that rank `rank` writes at step `step`, in the
/// manifest's folder: checkpoint.sSSSSSSSS.rRRRR.h5.
std::string checkpoint_piece_name(long step, int rank);

/// The part of an input that decides the physics: the input without `title`, `output`,
/// `checks`, `solver.end_time` and `solver.max_steps`, the keys a restart may change.
nlohmann::json physics_of(const nlohmann::json& input);

/// Hex FNV-1a hash of physics_of(input) in canonical form (sorted keys, no spaces).
std::string physics_hash(const nlohmann::json& input);

/// Writes the checkpoint to `file` atomically: to `file`.partial, fsync, then the current `file`
/// becomes `previous` and the new one takes its name. A run killed at any moment leaves `file`
/// complete (old or new). Throws std::runtime_error when the file cannot be written.
///
/// On several ranks (sim.comm.distributed(); a collective) each rank first writes its particles and
/// its own counters to its piece (checkpoint_piece_name, atomically as above), then rank 0 writes
/// `file` as the manifest: the global state, the history, the rank count, the partition and the
/// pieces' names. Then rank 0 deletes the pieces that neither `file` nor `previous` names. A failure
/// on any rank throws std::runtime_error on every rank (none waits for another).
template <int D>
void write_checkpoint(const std::filesystem::path& file, const std::filesystem::path& previous,
                      const Simulation<D>& sim, const RunCounters& run, const History& history,
                      const nlohmann::json& input);

/// Replaces the evolving state of `sim` (built by build_simulation from the same input), `run`
/// and `history` by the checkpoint's. Throws InputError (exit 2) naming the file when it is not a
/// complete matpoint checkpoint of a D-dimensional run, or was written for an input whose physics
/// differ from `input` (the message lists the changed keys). On several ranks (a collective) each
/// rank reads the manifest and its own piece, and `run` gets its piece's counters, migration state
/// and the stored partition; any rank's error is thrown on every rank. A checkpoint of another
/// rank count (a one-rank checkpoint counts as 1) is redistributed: every rank reads every piece
/// and keeps its cells' particles of a partition balanced anew, in (sort key, id) order, so the
/// particles continue bit for bit (docs/scale-out.md §9).
template <int D>
void read_checkpoint(const std::filesystem::path& file, const nlohmann::json& input, Simulation<D>& sim,
                     RunCounters& run, History& history);

}  // namespace matpoint
