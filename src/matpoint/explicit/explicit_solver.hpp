// The explicit solver as the shared run loop (run/run_loop.hpp) sees it: the Simulation, its
// stepper for one basis, the stable time step, and the solver's own counters and warnings.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/parallel/parallel_summary.hpp"
#include "matpoint/run/energy_guard.hpp"
#include "matpoint/run/run_summary.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace matpoint {

/// cpGIMP's half-width |F_aa| l0 is capped at h/2 (shape/tensor_stencils.hpp, as Gong's formula
/// assumes); past that the domain no longer has the volume V0 det F. Marks (by particle id) every
/// particle stretched past the cap, checked every few steps; the run warns once with the count.
/// Memory: the marked ids of this rank's particles only (a rank never holds one entry per
/// particle of the whole run).
class CappedDomains {
 public:
  /// `generated`: the particles of the whole run (every rank's).
  CappedDomains(const Spec& spec, long generated)
      : active_(spec.solver.shape == ShapeKind::CpGIMP), generated_(generated) {}

  template <int D>
  void check(const Simulation<D>& sim) {
    if (!active_ || sim.step % EnergyGuard::kInterval != 0) return;
    const auto& ps = sim.particles;
    for (std::size_t p = 0; p < ps.size(); ++p)
      for (int a = 0; a < D; ++a)
        if (stretched_half_width(sim.grid, ps, p, a) > 0.5) {
          if (first_time_ < 0) first_time_ = sim.time;
          capped_.insert(ps.id[p]);
        }
  }

  /// The warning, or an empty string when no particle reached the cap.
  /// In a decomposed run each rank marks its own particles (by id); the ranks' lists are gathered
  /// and a particle marked on two ranks (it migrated) counts once.
  [[nodiscard]] std::string warning(const Communicator& comm) const {
    std::vector<long> marked = comm.all_gather(std::vector<long>(capped_.begin(), capped_.end()));
    std::sort(marked.begin(), marked.end());
    const auto count = std::unique(marked.begin(), marked.end()) - marked.begin();
    // the earliest first time of any rank (-1: none on this rank)
    const double first_time =
        -comm.max(first_time_ < 0 ? -std::numeric_limits<double>::infinity() : -first_time_);
    if (count == 0) return {};
    std::ostringstream text;
    text << "cpGIMP: " << count << " of " << generated_
         << " particles were stretched past a domain half-width of h/2 (first at t = " << first_time
         << "); their domains were capped there and no longer have the volume V0 det F (Gong 2015 §6.3); "
            "uGIMP, CPDI or a finer grid avoid it";
    return text.str();
  }

 private:
  bool active_;
  long generated_;
  std::unordered_set<long> capped_;  // ids of this rank's particles marked so far
  double first_time_ = -1.0;
};

/// One explicit run of basis `Stencils` in D dimensions (run/run_loop.hpp lists the interface).
template <int D, class Stencils>
class ExplicitSolver {
 public:
  /// Builds the simulation; throws InputError (nothing written yet) for what only the set-up finds.
  /// `comm`: the ranks that share the run (a decomposed run when there are several).
  explicit ExplicitSolver(const Spec& spec, const Communicator& comm = Communicator::world())
      : spec_(spec),
        sim_(build_simulation<D>(spec, comm)),  // this rank's particles; ids in generation order
        capped_(spec, sim_.particles.next_id),  // the count of every rank's generated particles
        stepper_(sim_) {}
  ExplicitSolver(const ExplicitSolver&) = delete;
  ExplicitSolver& operator=(const ExplicitSolver&) = delete;

  Simulation<D>& sim() { return sim_; }
  [[nodiscard]] const Simulation<D>& sim() const { return sim_; }

  /// solver.dt, or the Courant step of the present state (Nairn 2026 §1.8), with the wave speeds
  /// the last stress update recorded (the set-up's, or the previous step's: nothing writes F or
  /// the material state between it and this call; restore() forgets them).
  [[nodiscard]] double time_step() const {
    const Traffic before = Communicator::collectives();
    const double dt = stable_time_step(sim_, /*use_recorded=*/true);
    count_collectives_since(before);
    return dt;
  }
  void step(double h) {
    const Traffic before = Communicator::collectives();
    // loads.gravity_scale at the step's start (the forward step's body force)
    const double scale = spec_.loads.gravity_scale(sim_.time);
    for (int a = 0; a < D; ++a) sim_.gravity[a] = scale * spec_.loads.gravity[a];
    stepper_.step(h);
    count_collectives_since(before);
  }
  void after_step() { capped_.check(sim_); }
  /// Re-partitions of a decomposed run so far (solver.rebalance).
  [[nodiscard]] long repartitions() const { return stepper_.repartitions(); }

  void save(RunCounters& counters) const {
    const auto state = stepper_.state();
    counters.next_fmpm_time = state.next_fmpm_time;
    counters.total_mass = state.total_mass;
    counters.fmpm_loops = state.fmpm.loops;
    counters.fmpm_passes = state.fmpm.passes;
    counters.fmpm_seconds = state.fmpm.seconds;
    counters.partition = state.partition;
    counters.sort_keys.assign(state.sort_keys.begin(), state.sort_keys.end());
    counters.sorted_prefix = state.sorted_prefix;
    counters.repartitions = state.repartitions;
    counters.partitioned_at = state.partitioned_at;
  }
  void restore(const RunCounters& c) {
    sim_.particles.recorded_wave_speed = -1.0;  // F and state were read from the checkpoint
    stepper_.restore({c.next_fmpm_time,
                      c.total_mass,
                      {c.fmpm_loops, c.fmpm_passes, c.fmpm_seconds},
                      c.partition,
                      std::vector<Index>(c.sort_keys.begin(), c.sort_keys.end()),
                      c.sorted_prefix,
                      c.repartitions,
                      c.partitioned_at});
  }

  /// Coupled heat (HeatSpec) adds its columns (docs/output.md): the largest and the mean particle
  /// temperature, the heat content Q_T = sum_p M_p C_V (T_p - T0), the heat in, Q = the heat
  /// through the thermal conditions plus the frictional work turned into heat, and the
  /// thermodynamic totals of docs/theory/heat.md: internal energy U, entropy S (relative to the
  /// initial state at T0) and Helmholtz free energy A = sum_p V0_p psi_p.
  [[nodiscard]] std::vector<std::string> history_columns() const {
    if (!sim_.heat.enabled) return {};
    return {"temperature_max", "temperature_mean", "heat_content", "heat_in",
            "internal_energy", "entropy",          "free_energy"};
  }
  std::vector<double> history_values() {
    if (!sim_.heat.enabled) return {};
    const auto& ps = sim_.particles;
    const double T0 = sim_.heat.initial_temperature;
    double largest = -std::numeric_limits<double>::infinity(), sum = 0.0, content = 0.0;
    double coupling = 0.0, entropy = 0.0, thermal_free = 0.0;  // sum_p V0_p (e - W), s, (psi - W)
    for (std::size_t p = 0; p < ps.size(); ++p) {
      const auto m = static_cast<std::size_t>(ps.material[p]);
      const double T = ps.temperature[p], heat = ps.mass[p] * sim_.heat_capacity[m] * (T - T0);
      const double lnJ = std::log(ps.F[p].determinant()), b = ps.volume0[p] * sim_.expansion_modulus[m] * lnJ;
      const double s = b + ps.mass[p] * sim_.heat_capacity[m] * std::log(T / T0);
      largest = std::max(largest, T);
      sum += T;
      content += heat;
      coupling += b * T0 + heat;
      entropy += s;
      thermal_free += heat - b * (T - T0) - T * (s - b);
    }
    // a decomposed run: each rank's particles and accumulated heats, added over the ranks
    std::vector<double> totals{sum,
                               static_cast<double>(ps.size()),
                               content,
                               sim_.boundary_heat + (sim_.heat.friction ? sim_.friction_work : 0.0),
                               strain_energy<D>(sim_.materials, ps),
                               coupling,
                               entropy,
                               thermal_free};
    sim_.comm.sum(totals);
    largest = sim_.comm.max(largest);
    const double mean = totals[1] > 0.0 ? totals[0] / totals[1] : 0.0;
    const double W = totals[4];
    return {largest, mean, totals[2], totals[3], W + totals[5], totals[6], W + totals[7]};
  }

  void write_static_outputs(const std::filesystem::path&, std::string&) const {}

  void add_facts(RunFacts& facts) const {
    const SolverSpec& s = spec_.solver;
    if (s.transfer == VelocityTransfer::FMPM || s.transfer == VelocityTransfer::XPIC)
      facts.fmpm = stepper_.fmpm_statistics();
    if (s.mapping != Mapping::MPM) {  // every rank counts its owned nodes and cells
      facts.mls = stepper_.mls_statistics();
      facts.mls->evaluations = sim_.comm.sum(facts.mls->evaluations);
      facts.mls->fallbacks = sim_.comm.sum(facts.mls->fallbacks);
    }
    if (sim_.has_contact && spec_.contact.normals == ContactNormals::Logistic)
      facts.logistic_fallbacks =  // every rank counts its owned nodes'
          static_cast<std::size_t>(sim_.comm.sum(static_cast<long>(sim_.contact.logistic_fallbacks())));
    if (auto warning = capped_.warning(sim_.comm); !warning.empty())
      facts.warnings.push_back(std::move(warning));
    if (sim_.comm.distributed()) add_parallel_facts(facts);
  }

 private:
  /// summary.json's `parallel` (a collective): what the ranks exchanged per step, and a warning
  /// when a rank runs more threads than the CPUs it may use (mpirun's binding).
  void add_parallel_facts(RunFacts& facts) const {
    RankTraffic mine;
    mine.particles = static_cast<long>(sim_.particles.size());
    mine.stored_nodes = static_cast<long>(sim_.grid.node_count);
    mine.threads = facts.threads;
    mine.step_wall = facts.step_wall;
    mine.step_cpu = facts.step_cpu;
    if (const Traffic* t = stepper_.halo_traffic()) mine.halo = *t;
    if (const Traffic* t = stepper_.migration_traffic()) mine.migration = *t;
    mine.collectives = step_collectives_;
    const long steps = facts.steps - std::max(0L, facts.restart_step);  // the steps of this process
    facts.parallel = parallel_summary(sim_.comm, mine, steps);
    (*facts.parallel)["repartitions"] = stepper_.repartitions();  // solver.rebalance (the same on every rank)
    const int threads = (*facts.parallel)["threads_per_rank"]["max"];
    const int cpus = (*facts.parallel)["cpus_per_rank"]["min"];
    if (threads > cpus)
      facts.warnings.push_back("a rank runs " + std::to_string(threads) + " threads but may use only " +
                               std::to_string(cpus) +
                               " CPU(s) (mpirun's binding): use `mpirun --bind-to none` or --map-by "
                               "slot:PE=<threads>, or fewer --threads");
  }

  /// Adds the collectives since `before` to the steps' count (serial runs: none).
  void count_collectives_since(const Traffic& before) const {
    const Traffic& now = Communicator::collectives();
    step_collectives_.calls += now.calls - before.calls;
    step_collectives_.seconds += now.seconds - before.seconds;
    step_collectives_.waiting_cpu += now.waiting_cpu - before.waiting_cpu;
  }

  const Spec& spec_;
  Simulation<D> sim_;
  CappedDomains capped_;
  ExplicitStepper<D, Stencils> stepper_;
  mutable Traffic step_collectives_;  // the collectives of time_step() and step()
};

}  // namespace matpoint
