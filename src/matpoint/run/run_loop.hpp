// The time loop every solver shares: output schedule, history and particle outputs, checkpoints
// and restart, guards, signals, summary and plots. The solver is the part that differs: it is a
// template argument with this small interface (the explicit one: explicit/explicit_solver.hpp):
//
//   Simulation<D>& sim();  const Simulation<D>& sim() const;
//                                  the state that outputs, checkpoints and guards read
//   double time_step();           the next full step (the loop shortens it to land on outputs)
//   void step(double h);          advances sim() by h; throws NumericalFailure (exit 3)
//   void after_step();            cheap per-step checks (may throw NumericalFailure)
//   void save(RunCounters&) const;        the solver's own counters into a checkpoint
//   void restore(const RunCounters&);     and back from one (restart)
//   void add_facts(RunFacts&) const;      its statistics and warnings for summary.json
//   std::vector<std::string> history_columns() const;   its own history.csv columns, and
//   std::vector<double> history_values() const;         their values after the last step
//   void write_static_outputs(const std::filesystem::path& dir, std::string& part);
//                                  files written once (an element mesh); `part`: the one shown
//                                  in results.pvd beside the particles ("" for none)
// and optionally
//   std::string frame_part_prefix() const;     a file written at every particle output ("" none)
//   void write_frame(const std::filesystem::path& file) const;   writes it (an FE body's mesh)
//   OtherBodiesEnergy other_bodies_energy() const;   energies of bodies that are not particles
//   static constexpr bool kEvenStepsToLand = true;
//                                  reach an output time without a tiny last step (steps_to_land)
//   static constexpr bool kCheckEnergyEveryStep = true;
//                                  the energy guard after every step, not every 10th (implicit)
#pragma once

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "matpoint/analysis/probes.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/core/interrupt.hpp"
#include "matpoint/core/progress.hpp"
#include "matpoint/io/atomic_file.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/io/output_folder.hpp"
#include "matpoint/run/energy_guard.hpp"
#include "matpoint/run/run_outputs.hpp"
#include "matpoint/run/run_summary.hpp"
#include "matpoint/run/runner.hpp"

namespace matpoint {

namespace run_loop_detail {

int current_threads();
const char* signal_name(int signal);
/// Every history.csv column of the input's probes (analysis/probes.hpp).
std::vector<std::string> probe_columns(const Spec& spec);

/// The step that advances `remaining` (> 0) toward the next output time or the end, when the
/// solver's full step is `dt`, and whether it lands there. A step within dt (1 + 1e-6) lands.
/// Otherwise the explicit solvers take dt, leaving whatever is left to the last step however
/// small. `even` splits a remainder between dt and 2 dt into two equal steps, so that no step is
/// shorter than dt / 2. The implicit particle-Newmark solvers need it: their acceleration
/// (u - u_pred) / (beta h^2) (Aulisa & Capodaglio eq. (19)) turns the Newton tolerance into an
/// error growing as 1 / h^2, and a landing step h << dt followed by a full one kicked the
/// particles (the bouncing disk with outputs at fixed times failed in flight).
struct LandingStep {
  double h;
  bool lands;
};
inline LandingStep steps_to_land(double remaining, double dt, bool even) {
  if (remaining <= dt * (1 + 1e-6)) return {remaining, true};
  if (even && remaining < 2 * dt) return {remaining / 2, false};
  return {dt, false};
}

/// Takes checkpoints when `output.checkpoint` asks for them (every N steps or T wall minutes)
/// and on demand; remembers the last one. due() reads this process' wall clock: a decomposed run
/// takes rank 0's decision (run_loop folds it into the step's one collective).
class CheckpointClock {
 public:
  CheckpointClock(const CheckpointSpec& every, std::filesystem::path out_dir, long restart_step)
      : every_(every), out_dir_(std::move(out_dir)), step_(restart_step) {}

  [[nodiscard]] bool due(long step) const {
    const auto minutes = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() / 60;
    return (every_.every_steps > 0 && step % every_.every_steps == 0) ||
           (every_.every_minutes > 0 && minutes >= every_.every_minutes);
  }

  template <int D>
  void save(const Simulation<D>& sim, const RunCounters& now, const History& history,
            const nlohmann::json& input) {
    file_ = out_dir_ / kCheckpointFile;
    write_checkpoint<D>(file_, out_dir_ / kPreviousCheckpointFile, sim, now, history, input);
    last_ = std::chrono::steady_clock::now();
    step_ = sim.step;
  }

  [[nodiscard]] long step() const { return step_; }  // of the last checkpoint; -1: none
  [[nodiscard]] const std::filesystem::path& file() const { return file_; }

 private:
  CheckpointSpec every_;
  std::filesystem::path out_dir_, file_;
  long step_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

/// Starts a run: from the input (dt and the momentum scale from the initial state) or from a
/// checkpoint (everything as the interrupted run had it). Throws InputError before writing.
template <int D, class Solver>
RunCounters start_state(const RunOptions& options, const Spec& spec, Solver& solver, History& history) {
  RunCounters run;
  Simulation<D>& sim = solver.sim();
  if (!options.restart.empty()) {
    read_checkpoint<D>(options.restart, spec.echo, sim, run, history);
    refuse_stale_checkpoint(options.restart, sim.step);  // a finished run went further than it
    if (run.threads != current_threads() && sim.comm.rank() == 0)
      std::fprintf(
          stderr,
          "warning: the checkpoint was written by a run with %d thread(s), this one has %d: the results "
          "will differ from an uninterrupted run in round-off (same thread count: bit for bit)\n",
          run.threads, current_threads());
    solver.restore(run);
    return run;
  }
  run.dt = solver.time_step();
  std::vector<double> momentum_scale{0.0};  // sum over every rank's particles (docs/scale-out.md §7)
  for (std::size_t p = 0; p < sim.particles.size(); ++p)
    momentum_scale[0] += sim.particles.mass[p] * sim.particles.v[p].norm();
  sim.comm.sum(momentum_scale);
  run.momentum_scale = momentum_scale[0];
  run.next_output_time = spec.output.every_time;
  return run;
}

/// The x behind which `fraction` of the mass of every rank's particles lies (final_runout_x of a
/// decomposed run; a collective): the smallest particle x with sum_{x_p <= x} m_p >= fraction *
/// sum_p m_p, found by bisection on the doubles between the smallest and the largest particle x
/// (at most 64 rounds, each one sum over the ranks, identical on every rank) instead of gathering
/// and sorting every particle (docs/scale-out.md §8). Equal to the sorted search of add_reach but
/// for the order of the mass sums (round-off at a front that splits at exactly 99 %).
template <int D>
double mass_front_x(const ParticleSet<D>& ps, double fraction, const Communicator& comm) {
  // finite doubles -> unsigned integers of the same order (-0 just below +0)
  const auto key = [](double x) {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    return (bits >> 63) != 0 ? ~bits : bits | (std::uint64_t{1} << 63);
  };
  const auto value = [](std::uint64_t k) {
    return std::bit_cast<double>((k >> 63) != 0 ? k & ~(std::uint64_t{1} << 63) : ~k);
  };
  std::vector<double> extremes{-std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity()};
  for (std::size_t p = 0; p < ps.size(); ++p)
    if (std::isfinite(ps.x[p][0])) {
      extremes[0] = std::max(extremes[0], -ps.x[p][0]);
      extremes[1] = std::max(extremes[1], ps.x[p][0]);
    }
  comm.max(extremes);
  const double smallest = -extremes[0], largest = extremes[1];
  if (!(smallest <= largest)) return kNoValue;  // no particle with a finite x
  const auto mass_behind = [&](double x) {
    std::vector<double> behind{0.0};
    for (std::size_t p = 0; p < ps.size(); ++p)
      if (ps.x[p][0] <= x) behind[0] += ps.mass[p];
    comm.sum(behind);
    return behind[0];
  };
  const double target = fraction * mass_behind(largest);
  if (!(target > 0.0)) return smallest + 0.0;
  std::uint64_t below = key(smallest) - 1, at = key(largest);  // mass_behind: < target, >= target
  while (at - below > 1) {
    const std::uint64_t middle = below + (at - below) / 2;
    (mass_behind(value(middle)) >= target ? at : below) = middle;
  }
  return value(at) + 0.0;  // + 0.0: -0 -> +0
}

/// The bodies' reach (final-state measures final_max_x/y/z and final_max_radius_xy): the largest
/// coordinate, and in 3-D the largest distance from the z axis, of any particle centre. (Not the
/// particle domains: in a granular flow F grows without bound and a domain's extent means nothing.)
/// And the x behind which 99 % of the mass lies (final_runout_x). Over every rank's particles: a
/// collective in a decomposed run.
template <int D>
void add_reach(const ParticleSet<D>& ps, RunFacts& facts, const Communicator& comm = {}) {
  if (comm.distributed()) {
    if (comm.sum(static_cast<long>(ps.size())) == 0) return;
    // per axis the largest coordinate, then the largest radius (3-D)
    std::vector<double> maxima(D + 1, -std::numeric_limits<double>::infinity());
    maxima[D] = 0.0;
    for (std::size_t p = 0; p < ps.size(); ++p) {
      for (int a = 0; a < D; ++a) maxima[a] = std::max(maxima[a], ps.x[p][a]);
      if constexpr (D == 3) maxima[D] = std::max(maxima[D], std::hypot(ps.x[p][0], ps.x[p][1]));
    }
    comm.max(maxima);
    for (int a = 0; a < D; ++a) facts.final_reach[static_cast<std::size_t>(a)] = maxima[a];
    if constexpr (D == 3) facts.final_radius_xy = maxima[D];
    facts.final_runout_x = mass_front_x(ps, 0.99, comm);
    return;
  }
  if (ps.size() == 0) return;
  for (int a = 0; a < D; ++a) {
    double reach = -std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < ps.size(); ++p) reach = std::max(reach, ps.x[p][a]);
    facts.final_reach[static_cast<std::size_t>(a)] = reach;
  }
  std::vector<std::pair<double, double>> x_mass(ps.size());  // (x, mass), for the 99 % mass front
  double total = 0.0;
  for (std::size_t p = 0; p < ps.size(); ++p) x_mass[p] = {ps.x[p][0], ps.mass[p]}, total += ps.mass[p];
  std::sort(x_mass.begin(), x_mass.end());
  double behind = 0.0;
  for (const auto& [x, m] : x_mass)
    if ((behind += m) >= 0.99 * total) {
      facts.final_runout_x = x;
      break;
    }
  if constexpr (D == 3) {
    double radius = 0.0;
    for (std::size_t p = 0; p < ps.size(); ++p) radius = std::max(radius, std::hypot(ps.x[p][0], ps.x[p][1]));
    facts.final_radius_xy = radius;
  }
}

/// The particles' sigma_xx that the final-state measures need, over every rank (a collective in a
/// decomposed run). One rank: every particle's, in storage order. Several: only the stresses
/// that shock_plateau_stress (analysis/measures_eval.cpp, the one measure that reads them) keeps,
/// those with -sigma_xx >= 0.5 max(0, max_p -sigma_xx), gathered in rank order; the plateau's
/// median is the same as from all of them, and a rank does not receive every particle's stress.
template <int D>
std::vector<double> final_stress_xx(const ParticleSet<D>& ps, const Communicator& comm) {
  std::vector<double> out;
  if (!comm.distributed()) {
    for (const auto& stress : ps.stress) out.push_back(stress(0, 0));
    return out;
  }
  double largest = 0.0;  // the largest compression
  for (const auto& stress : ps.stress) largest = std::max(largest, -stress(0, 0));
  largest = comm.max(largest);
  for (const auto& stress : ps.stress)
    if (-stress(0, 0) >= 0.5 * largest) out.push_back(stress(0, 0));
  return comm.all_gather(out);
}

/// The summary's facts that every solver shares: counts, time, threads, final stresses; over
/// every rank's particles (a collective in a decomposed run).
template <int D>
void add_state_facts(const Simulation<D>& sim, RunFacts& facts) {
  facts.dimension = D;
  facts.particles = static_cast<std::size_t>(sim.comm.sum(static_cast<long>(sim.particles.size())));
  facts.nodes = sim.grid.total_node_count();  // a decomposed run's rank stores a window of them
  facts.steps = sim.step;
  facts.time = sim.time;
  facts.threads = current_threads();
  facts.final_stress_xx = final_stress_xx(sim.particles, sim.comm);
  add_reach(sim.particles, facts, sim.comm);
}

}  // namespace run_loop_detail

/// The time loop of one solver: steps, outputs, checkpoints, guards and signals; the summary is
/// built from plain numbers afterwards (run_summary.cpp). Throws InputError before writing
/// anything when a restart's checkpoint does not fit.
template <int D, class Solver>
RunResult run_loop(const Spec& spec, const RunOptions& options, Solver& solver) {
  using namespace run_loop_detail;
  Simulation<D>& sim = solver.sim();
  History restored{
      D, static_cast<int>(spec.bodies.size()), solver.history_columns(), probe_columns(spec), {}};
  RunCounters run = start_state<D>(options, spec, solver, restored);  // may throw InputError
  const bool restarting = !options.restart.empty();
  std::filesystem::create_directories(options.out_dir);
  const auto probe_ids = probe_particle_ids<D>(sim.particles, spec.output.probes, sim.comm);
  RunOutputs<D> outputs(spec, options.out_dir, std::move(restored), run, probe_ids, sim.comm);
  if (spec.output.particles) {
    std::string part;
    solver.write_static_outputs(options.out_dir, part);
    if (!part.empty()) outputs.add_static_part(part);
    if constexpr (requires { solver.frame_part_prefix(); })
      if (const std::string prefix = solver.frame_part_prefix(); !prefix.empty())
        outputs.add_frame_part(prefix,
                               [&solver](const std::filesystem::path& file) { solver.write_frame(file); });
  }

  OutputSchedule schedule(spec.output, sim.time, run.next_output_time);
  Progress progress(options.progress, spec.solver.end_time);
  long last_recorded_step = run.last_recorded_step;
  const long restart_step = sim.step;
  const auto other_energy = [&solver] {
    if constexpr (requires { solver.other_bodies_energy(); })
      return solver.other_bodies_energy();
    else
      return OtherBodiesEnergy{};
  };
  if (restarting)
    outputs.write_history();  // drops any rows a killed run wrote after its checkpoint
  else
    outputs.record(sim, solver.history_values(), other_energy());

  RunResult result;
  const auto wall_start = std::chrono::steady_clock::now();
  double step_wall = run.step_wall, step_cpu = run.step_cpu;
  const auto wall_now = [&] {
    return run.wall + std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };

  // A checkpoint holds the state after a completed step with the scheduled outputs up to it; it is
  // taken before the extra output of a run's last step, so a restart repeats the outputs exactly.
  CheckpointClock checkpoints(spec.output.checkpoint, options.out_dir, restarting ? sim.step : -1);
  double dt = run.dt;  // the present full step (recomputed each step)
  auto save_checkpoint = [&] {
    RunCounters now = run;
    solver.save(now);
    now.outputs = outputs.count();
    now.next_output_time = schedule.next_time();
    now.last_recorded_step = last_recorded_step;
    now.step_wall = step_wall, now.step_cpu = step_cpu, now.wall = wall_now();
    now.dt = dt;
    now.threads = current_threads();
    now.results = outputs.results_entries(), now.domains = outputs.domains_entries();
    checkpoints.save<D>(sim, now, outputs.history(), spec.echo);
  };

  int interrupted = 0;
  const double end_time = spec.solver.end_time;
  constexpr bool kEvenSteps = requires { requires Solver::kEvenStepsToLand; };
  constexpr bool kEveryStep = requires { requires Solver::kCheckEnergyEveryStep; };
  EnergyGuard energy_guard(spec.solver.max_energy_growth, outputs.history(), kEveryStep);
  while (sim.time < end_time * (1 - 1e-12) &&
         (spec.solver.max_steps == 0 || sim.step < spec.solver.max_steps)) {
    // The solver's step (explicit: Nairn 2026 §1.8, dt = C dx / max_p max(c_p, |V_p|) from the
    // present state, or solver.dt), shortened (or stretched by at most 1e-6) to land exactly on
    // the next output time and the end. The step's timing (particle_steps_per_second) includes it.
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    dt = solver.time_step();
    const double target =
        spec.output.exact_times ? std::min(end_time, schedule.target_time(sim.time)) : end_time;
    const auto [h, lands] = steps_to_land(target - sim.time, dt, kEvenSteps);
    bool recorded = false;
    try {
      solver.step(h);
      if (lands) sim.time = target;  // exactly, not t + (target - t) rounded
      step_cpu += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
      step_wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      recorded = schedule.due(sim.step, sim.time);
      energy_guard.after_step(sim, recorded, other_energy);
      solver.after_step();
    } catch (const NumericalFailure& failure) {
      result.exit_code = kExitNumerical;
      result.message = failure.what();
      break;
    }
    if (recorded) {
      outputs.record(sim, solver.history_values(), other_energy());
      last_recorded_step = sim.step;
    }
    progress.update(sim.step, sim.time);
    // A decomposed run stops on every rank when one rank got the signal, and takes a checkpoint
    // when rank 0's clock says so (the ranks must agree): one small collective per step.
    bool checkpoint_due = checkpoints.due(sim.step);
    interrupted = interrupt_signal();
    if (sim.comm.distributed()) {
      std::vector<int> flags{interrupted, sim.comm.rank() == 0 && checkpoint_due ? 1 : 0};
      sim.comm.max(flags);
      interrupted = flags[0], checkpoint_due = flags[1] != 0;
    }
    if (checkpoint_due) save_checkpoint();
    if (interrupted != 0) break;
  }
  const bool finished = result.exit_code == kExitOk && interrupted == 0;
  if (checkpoints.step() != sim.step && (interrupted != 0 || (finished && spec.output.checkpoint.enabled())))
    save_checkpoint();
  if (interrupted != 0) {
    result.exit_code = 128 + interrupted;
    std::ostringstream message;
    const std::string mpirun =
        sim.comm.distributed() ? "mpirun -n " + std::to_string(sim.comm.size()) + " " : std::string();
    message << "interrupted by " << signal_name(interrupted) << " after step " << sim.step << ", time "
            << sim.time << "; continue with: " << mpirun << "matpoint run INPUT --out "
            << options.out_dir.string() << " --restart " << checkpoints.file().string();
    result.message = message.str();
  }
  if (result.exit_code != kExitNumerical && last_recorded_step != sim.step)
    outputs.record(sim, solver.history_values(), other_energy());
  outputs.write_history();
  progress.finish(finished ? "done" : interrupted != 0 ? "interrupted" : "stopped: numerical failure");

  RunFacts facts;
  facts.status = finished ? "ok" : interrupted != 0 ? "interrupted" : "numerical_failure";
  facts.exit_code = result.exit_code;
  facts.message = result.message;
  facts.restart_step = restarting ? restart_step : -1;
  facts.checkpoint_file = checkpoints.file();
  facts.checkpoint_step = checkpoints.step();
  facts.dt = dt;  // the last full step's (fixed: solver.dt)
  facts.wall = wall_now();
  facts.step_wall = step_wall;
  facts.step_cpu = step_cpu;
  facts.outputs = outputs.count();
  facts.momentum_scale = run.momentum_scale;
  add_state_facts(sim, facts);
  solver.add_facts(facts);
  for (const auto& [id, X] : probe_reference_positions<D>(sim.particles, probe_ids, sim.comm))
    facts.probes.push_back({id, std::vector<double>(X.data(), X.data() + D)});

  // Every rank builds the same summary (from reduced facts) and returns it; rank 0 writes it.
  result.summary = run_summary(spec, options, facts, outputs.history());
  if (sim.comm.rank() == 0)
    write_file_atomically(options.out_dir / "summary.json", result.summary.dump(2) + "\n");
  if (sim.comm.rank() == 0 && spec.output.plots && !options.scripts_dir.empty())
    if (const auto error = draw_plots(options.out_dir, options.scripts_dir); !error.empty())
      std::fprintf(stderr, "warning: could not draw plots: %s\n", error.c_str());
  result.history = outputs.take_history();
  return result;
}

}  // namespace matpoint
