// What a run writes while it goes: the output schedule, history.csv and the particle (and domain)
// .vtu files with their .pvd collections (docs/output.md). Every file is written atomically.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "matpoint/analysis/diagnostics.hpp"
#include "matpoint/analysis/grid_modes.hpp"
#include "matpoint/analysis/history.hpp"
#include "matpoint/analysis/probes.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/atomic_file.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/io/vtk_writer.hpp"
#include "matpoint/run/other_bodies_energy.hpp"
#include "matpoint/shape/domains.hpp"

namespace matpoint {

/// Decides which steps write output. An every_time schedule has its output times at n every_time
/// (n = 1, 2, ...), computed from n rather than summed, and the time loop lands on them exactly.
class OutputSchedule {
 public:
  /// `next_time`: the next output time of an every_time schedule (a restart's, or every_time).
  OutputSchedule(const OutputSpec& o, double time, double next_time) : spec_(o) {
    const double every = o.every_time;
    if (every <= 0) return;
    next_index_ = std::llround(next_time / every);
    // a restart may change every_time: start on its next multiple
    if (!(next_index_ * every > time * (1 + 1e-12))) next_index_ = std::llround(std::floor(time / every)) + 1;
    while (next_index_ * every <= time * (1 + 1e-12)) ++next_index_;
  }
  /// The step ending at `time` writes output (every_steps, or `time` reached the next output time).
  bool due(long step, double time) {
    if (spec_.every_steps > 0) return step % spec_.every_steps == 0;
    if (spec_.every_time > 0 && time >= next_time() * (1 - 1e-12)) {
      while (next_time() <= time * (1 + 1e-12)) ++next_index_;
      return true;
    }
    return false;
  }
  /// The next output time (every_time), 0 without an every_time schedule.
  [[nodiscard]] double next_time() const {
    return spec_.every_time > 0 ? static_cast<double>(next_index_) * spec_.every_time : 0.0;
  }
  /// The time a step starting at `time` must not step over: the next output time, or +infinity.
  [[nodiscard]] double target_time(double time) const {
    const double next = next_time();
    return spec_.every_time > 0 && next > time ? next : std::numeric_limits<double>::infinity();
  }

 private:
  OutputSpec spec_;
  long long next_index_ = 0;
};

namespace run_outputs_detail {

template <int D>
std::array<double, 3> pad(const Vec<D>& v) {
  std::array<double, 3> out{};
  for (int a = 0; a < D; ++a) out[a] = v[a];
  return out;
}

inline std::string output_name(long index, const char* prefix, const char* extension = ".vtu") {
  std::ostringstream name;
  name << prefix << std::setw(6) << std::setfill('0') << index << extension;
  return name.str();
}

/// Rank `rank`'s piece of a decomposed run's output: PREFIXNNNNNN_rRRRR.vtu.
inline std::string piece_name(long index, const char* prefix, int rank) {
  std::ostringstream name;
  name << prefix << std::setw(6) << std::setfill('0') << index << "_r" << std::setw(4) << rank << ".vtu";
  return name.str();
}

}  // namespace run_outputs_detail

/// The names of the .vtu `state` components: the models' own where the materials with history
/// agree, "a|b" where two models use a component for different things.
template <int D>
std::vector<std::string> state_component_names(const Simulation<D>& sim) {
  std::vector<std::string> names(static_cast<std::size_t>(sim.particles.state_stride));
  for (const auto& material : sim.materials) {
    const auto own = state_names(material);
    for (std::size_t i = 0; i < own.size() && i < names.size(); ++i)
      if (names[i].empty())
        names[i] = own[i];
      else if (names[i] != own[i])
        names[i] += "|" + own[i];
  }
  return names;
}

/// One history.csv row of the simulation's present state; `probe_ids`: the particles of output.probes.
/// In a decomposed run (sim.comm.distributed()) a collective: the particle and owned-node sums and
/// the ranks' partial accumulated totals (external work and impulse, friction work, the grid
/// momentum difference) are added over the ranks, and every rank gets the same row.
template <int D>
HistorySample history_sample(const Simulation<D>& sim, int body_count, const std::vector<long>& probe_ids) {
  using run_outputs_detail::pad;
  const auto d = measure_diagnostics(sim, body_count);
  // the accumulated totals: each rank's part (one rank: the whole), added here, not where stored
  std::vector<double> totals{sim.external_work, sim.friction_work};
  for (int a = 0; a < D; ++a) totals.push_back(sim.external_impulse[a]);
  for (int a = 0; a < D; ++a) totals.push_back(sim.grid_momentum_difference[a]);
  sim.comm.sum(totals);
  Vec<D> external_impulse, grid_momentum_difference;
  for (int a = 0; a < D; ++a) {
    external_impulse[a] = totals[2 + a];
    grid_momentum_difference[a] = totals[2 + D + a];
  }
  HistorySample s;
  s.time = sim.time;
  s.step = sim.step;
  s.dt = sim.last_dt;
  s.kinetic_energy = d.kinetic_energy;
  s.strain_energy = d.strain_energy;
  s.external_work = totals[0];
  s.friction_work = totals[1];
  s.plastic_work = d.plastic_work;
  s.momentum = pad<D>(d.momentum);
  s.external_impulse = pad<D>(external_impulse);
  s.min_jacobian = d.min_jacobian;
  s.rms_velocity_change = d.rms_velocity_change;
  s.body_kinetic = d.body_kinetic;
  s.body_strain = d.body_strain;
  s.body_mass = d.body_mass;
  s.grid_momentum_difference = pad<D>(grid_momentum_difference);
  const GridModes modes =
      measure_grid_modes(sim.grid, sim.fields.mass, sim.fields.velocity_new,
                         NodeOwnership{sim.comm, sim.owned_nodes});
  s.checkerboard_velocity = modes.checkerboard_velocity;
  s.grid_rms_velocity = modes.rms_velocity;
  s.hourglass_energy = modes.hourglass_energy;
  for (int b = 0; b < body_count; ++b) {
    s.body_momentum.push_back(pad<D>(d.body_momentum[b]));
    s.body_com_velocity.push_back(pad<D>(Vec<D>(d.body_momentum[b] / std::max(d.body_mass[b], 1e-300))));
    s.body_com_position.push_back(pad<D>(d.body_com_position[b]));
  }
  append_probe_values(sim.particles, probe_ids, s.probes, sim.comm);
  return s;
}

/// The run's output folder: history (kept in memory whole, so the checks see every row) and the
/// particle states. history.csv is rewritten whole (atomically) at most once a second, with
/// every particle output, and at the end: rewriting it at each of many frequent outputs would
/// cost O(n^2).
/// On several MPI ranks (`comm` distributed; docs/output.md "Runs on several MPI ranks") every
/// rank keeps the same history and .pvd entries, but only rank 0 writes history.csv and the .pvd
/// files; each rank writes its own particles as a piece PREFIXNNNNNN_rRRRR.vtu, and rank 0 the
/// PREFIXNNNNNN.pvtu that names the pieces (after a barrier: every piece is on disk when the
/// .pvtu and the .pvd name it). record() is then a collective.
template <int D>
class RunOutputs {
 public:
  /// `run` carries the counters and the .pvd entries of a restart (zero at a fresh start);
  /// `probe_ids` the particles that output.probes follow.
  RunOutputs(const Spec& spec, std::filesystem::path out_dir, History history, const RunCounters& run,
             std::vector<long> probe_ids, const Communicator& comm = {})
      : spec_(spec),
        comm_(comm),
        out_dir_(std::move(out_dir)),
        history_(std::move(history)),
        body_count_(static_cast<int>(spec.bodies.size())),
        probe_ids_(std::move(probe_ids)),
        pvd_(out_dir_ / "results.pvd", comm.rank() == 0),
        domains_pvd_(out_dir_ / "domains.pvd", comm.rank() == 0),  // GIMP / CPDI particle domains
        write_domains_(spec.output.particles && has_particle_domains(spec.solver.shape)),
        outputs_(run.outputs) {
    pvd_.restore(run.results);  // a restart rewrites them as the checkpoint knew them
    domains_pvd_.restore(run.domains);
  }

  /// Appends the present state to the history (with the solver's own columns, `solver_values`)
  /// and, with `output.particles`, writes its .vtu.
  void record(const Simulation<D>& sim, std::vector<double> solver_values,
              const OtherBodiesEnergy& other = {}) {
    history_.samples.push_back(history_sample(sim, body_count_, probe_ids_));
    auto& sample = history_.samples.back();
    sample.solver = std::move(solver_values);
    sample.kinetic_energy += other.kinetic;
    sample.strain_energy += other.strain;
    sample.external_work += other.external_work;
    if (spec_.output.particles ||
        std::chrono::steady_clock::now() - last_history_write_ > std::chrono::seconds(1))
      write_history();
    if (spec_.output.particles) {
      const std::string name = write_dataset(
          "particles_", particles_vtu(sim.particles, spec_.output.fields, true, state_component_names(sim)));
      pvd_.add(sim.time, name);
      if (frame_writer_)
        frame_writer_(out_dir_ / run_outputs_detail::output_name(outputs_, frame_prefix_.c_str()));
      if (write_domains_) {
        const auto corners = particle_domains<D>(spec_.solver.shape, sim.grid, sim.particles);
        domains_pvd_.add(sim.time, write_dataset("domains_", domains_vtu<D>(corners, sim.particles)));
      }
    }
    ++outputs_;
  }

  /// A dataset shown at every output time beside the particles (results.pvd part 1): an implicit
  /// run's element mesh, written once.
  void add_static_part(const std::string& file) { pvd_.set_static_part(file); }

  /// A dataset the solver writes at every particle output (an implicit run's FE bodies), as
  /// `prefix` + the output's number; results.pvd lists it beside the particles.
  void add_frame_part(std::string prefix, std::function<void(const std::filesystem::path&)> writer) {
    pvd_.set_companion_prefix(prefix);
    frame_prefix_ = std::move(prefix);
    frame_writer_ = std::move(writer);
  }

  void write_history() {
    if (comm_.rank() != 0) return;
    write_file_atomically(out_dir_ / "history.csv", history_.csv());
    last_history_write_ = std::chrono::steady_clock::now();
  }

  /// Output states written so far: the index of the next .vtu file.
  [[nodiscard]] long count() const { return outputs_; }
  [[nodiscard]] const History& history() const { return history_; }
  [[nodiscard]] History take_history() { return std::move(history_); }
  [[nodiscard]] PvdEntries results_entries() const { return pvd_.entries(); }
  [[nodiscard]] PvdEntries domains_entries() const { return domains_pvd_.entries(); }

 private:
  /// Writes this output's `vtu` (one rank: PREFIXNNNNNN.vtu; several: this rank's piece, and on
  /// rank 0 the .pvtu of all pieces) and returns the name the .pvd lists.
  std::string write_dataset(const char* prefix, const std::string& vtu) {
    using namespace run_outputs_detail;
    if (!comm_.distributed()) {
      const std::string name = output_name(outputs_, prefix);
      write_file_atomically(out_dir_ / name, vtu);
      return name;
    }
    write_file_atomically(out_dir_ / piece_name(outputs_, prefix, comm_.rank()), vtu);
    const std::string name = output_name(outputs_, prefix, ".pvtu");
    comm_.barrier();  // every piece is written before the .pvtu (and then the .pvd) names it
    if (comm_.rank() == 0) {
      std::vector<std::string> pieces;
      for (int r = 0; r < comm_.size(); ++r) pieces.push_back(piece_name(outputs_, prefix, r));
      write_file_atomically(out_dir_ / name, pvtu_file(vtu, pieces));
    }
    return name;
  }

  const Spec& spec_;
  Communicator comm_;
  std::filesystem::path out_dir_;
  History history_;
  int body_count_;
  std::vector<long> probe_ids_;
  PvdCollection pvd_, domains_pvd_;
  std::string frame_prefix_;
  std::function<void(const std::filesystem::path&)> frame_writer_;
  bool write_domains_;
  long outputs_;
  std::chrono::steady_clock::time_point last_history_write_ =
      std::chrono::steady_clock::now() - std::chrono::hours(1);
};

}  // namespace matpoint
