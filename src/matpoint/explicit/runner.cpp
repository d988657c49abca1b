#include "matpoint/explicit/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "matpoint/core/errors.hpp"
#include "matpoint/core/interrupt.hpp"
#include "matpoint/core/progress.hpp"
#include "matpoint/core/subprocess.hpp"
#include "matpoint/explicit/energy_guard.hpp"
#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/explicit/run_outputs.hpp"
#include "matpoint/explicit/run_summary.hpp"
#include "matpoint/io/atomic_file.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/io/output_folder.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace matpoint {

namespace {

int current_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

/// Every history.csv column of the input's probes (analysis/probes.hpp).
std::vector<std::string> probe_columns(const Spec& spec) {
  std::vector<std::string> out;
  for (const auto& probe : spec.output.probes) {
    const auto names = probe_column_names(probe.name, spec.grid.dim);
    out.insert(out.end(), names.begin(), names.end());
  }
  return out;
}

/// Starts a run: from the input (dt and the momentum scale from the initial state) or from a
/// checkpoint (everything as the interrupted run had it). Throws InputError before writing.
template <int D>
RunCounters start_state(const Spec& spec, const RunOptions& options, Simulation<D>& sim, History& history) {
  RunCounters run;
  if (!options.restart.empty()) {
    read_checkpoint<D>(options.restart, spec.echo, sim, run, history);
    refuse_stale_checkpoint(options.restart, sim.step);  // a finished run went further than it
    if (run.threads != current_threads())
      std::fprintf(
          stderr,
          "warning: the checkpoint was written by a run with %d thread(s), this one has %d: the results "
          "will differ from an uninterrupted run in round-off (same thread count: bit for bit)\n",
          run.threads, current_threads());
    return run;
  }
  run.dt = stable_time_step(sim);
  for (std::size_t p = 0; p < sim.particles.size(); ++p)
    run.momentum_scale += sim.particles.mass[p] * sim.particles.v[p].norm();
  run.next_output_time = spec.output.every_time;
  return run;
}

/// Takes checkpoints when `output.checkpoint` asks for them (every N steps or T wall minutes)
/// and on demand; remembers the last one.
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

/// cpGIMP's half-width |F_aa| l0 is capped at h/2 (shape/tensor_stencils.hpp, as Gong's formula
/// assumes); past that the domain no longer has the volume V0 det F. Marks (by particle id) every
/// particle stretched past the cap, checked every few steps; the run warns once with the count.
class CappedDomains {
 public:
  CappedDomains(const Spec& spec, std::size_t particles)
      : active_(spec.solver.shape == ShapeKind::CpGIMP), capped_(active_ ? particles : 0, 0) {}

  template <int D>
  void check(const Simulation<D>& sim) {
    if (!active_ || sim.step % EnergyGuard::kInterval != 0) return;
    const auto& ps = sim.particles;
    for (std::size_t p = 0; p < ps.size(); ++p)
      for (int a = 0; a < D; ++a)
        if (stretched_half_width(sim.grid, ps, p, a) > 0.5) {
          if (capped_[ps.id[p]] == 0 && first_time_ < 0) first_time_ = sim.time;
          capped_[ps.id[p]] = 1;
        }
  }

  /// The warning, or an empty string when no particle reached the cap.
  [[nodiscard]] std::string warning() const {
    const auto count = std::count(capped_.begin(), capped_.end(), 1);
    if (count == 0) return {};
    std::ostringstream text;
    text << "cpGIMP: " << count << " of " << capped_.size()
         << " particles were stretched past a domain half-width of h/2 (first at t = " << first_time_
         << "); their domains were capped there and no longer have the volume V0 det F (Gong 2015 §6.3); "
            "uGIMP, CPDI or a finer grid avoid it";
    return text.str();
  }

 private:
  bool active_;
  std::vector<char> capped_;
  double first_time_ = -1.0;
};

/// The summary's facts about the final state and the solver's counters.
template <int D, class Stepper>
void add_state_facts(const Spec& spec, const Simulation<D>& sim, const Stepper& stepper, RunFacts& facts) {
  facts.dimension = D;
  facts.particles = sim.particles.size();
  facts.nodes = sim.grid.node_count;
  facts.steps = sim.step;
  facts.time = sim.time;
  facts.threads = current_threads();
  if (spec.solver.transfer == VelocityTransfer::FMPM || spec.solver.transfer == VelocityTransfer::XPIC)
    facts.fmpm = stepper.fmpm_statistics();
  if (spec.solver.mapping != Mapping::MPM) facts.mls = stepper.mls_statistics();
  if (sim.has_contact && spec.contact.normals == ContactNormals::Logistic)
    facts.logistic_fallbacks = sim.contact.logistic_fallbacks();
  for (const auto& stress : sim.particles.stress) facts.final_stress_xx.push_back(stress(0, 0));
}

/// The time loop of one basis and dimension: steps, outputs, checkpoints, guards and signals;
/// the summary is built from plain numbers afterwards (run_summary.cpp).
template <int D, class Stencils>
RunResult run_with(const Spec& spec, const RunOptions& options) {
  Simulation<D> sim = build_simulation<D>(spec);  // may throw InputError: nothing written yet
  History restored{D, static_cast<int>(spec.bodies.size()), probe_columns(spec), {}};
  RunCounters run = start_state<D>(spec, options, sim, restored);  // may throw InputError too
  const bool restarting = !options.restart.empty();
  std::filesystem::create_directories(options.out_dir);
  const auto probe_ids = probe_particle_ids<D>(sim.initial_position, spec.output.probes);
  RunOutputs<D> outputs(spec, options.out_dir, std::move(restored), run, probe_ids);

  ExplicitStepper<D, Stencils> stepper(sim);
  if (restarting)
    stepper.restore(
        {run.next_fmpm_time, run.total_mass, {run.fmpm_loops, run.fmpm_passes, run.fmpm_seconds}});
  OutputSchedule schedule(spec.output, sim.time, run.next_output_time);
  Progress progress(options.progress, spec.solver.end_time);
  long last_recorded_step = run.last_recorded_step;
  const long restart_step = sim.step;
  if (restarting)
    outputs.write_history();  // drops any rows a killed run wrote after its checkpoint
  else
    outputs.record(sim);

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
    const auto stepper_state = stepper.state();
    now.outputs = outputs.count();
    now.next_output_time = schedule.next_time();
    now.last_recorded_step = last_recorded_step;
    now.next_fmpm_time = stepper_state.next_fmpm_time;
    now.total_mass = stepper_state.total_mass;
    now.fmpm_loops = stepper_state.fmpm.loops;
    now.fmpm_passes = stepper_state.fmpm.passes;
    now.fmpm_seconds = stepper_state.fmpm.seconds;
    now.step_wall = step_wall, now.step_cpu = step_cpu, now.wall = wall_now();
    now.dt = dt;
    now.threads = current_threads();
    now.results = outputs.results_entries(), now.domains = outputs.domains_entries();
    checkpoints.save<D>(sim, now, outputs.history(), spec.echo);
  };

  int interrupted = 0;
  const double end_time = spec.solver.end_time;
  EnergyGuard energy_guard(spec.solver.max_energy_growth, outputs.history());
  CappedDomains capped_domains(spec, sim.particles.size());
  while (sim.time < end_time * (1 - 1e-12) && (spec.solver.max_steps == 0 || sim.step < spec.solver.max_steps)) {
    // Nairn 2026 §1.8: dt = C dx / max_p max(c_p, |V_p|) from the present state (or solver.dt),
    // shortened (or stretched by at most 1e-6) to land exactly on the next output time and the end.
    dt = stable_time_step(sim);
    const double target =
        spec.output.exact_times ? std::min(end_time, schedule.target_time(sim.time)) : end_time;
    const bool lands = target - sim.time <= dt * (1 + 1e-6);
    const double h = lands ? target - sim.time : dt;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    bool recorded = false;
    try {
      stepper.step(h);
      if (lands) sim.time = target;  // exactly, not t + (target - t) rounded
      step_cpu += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
      step_wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      recorded = schedule.due(sim.step, sim.time);
      energy_guard.after_step(sim, recorded);
      capped_domains.check(sim);
    } catch (const NumericalFailure& failure) {
      result.exit_code = kExitNumerical;
      result.message = failure.what();
      break;
    }
    if (recorded) {
      outputs.record(sim);
      last_recorded_step = sim.step;
    }
    progress.update(sim.step, sim.time);
    if (checkpoints.due(sim.step)) save_checkpoint();
    if ((interrupted = interrupt_signal()) != 0) break;
  }
  const bool finished = result.exit_code == kExitOk && interrupted == 0;
  if (checkpoints.step() != sim.step && (interrupted != 0 || (finished && spec.output.checkpoint.enabled())))
    save_checkpoint();
  if (interrupted != 0) {
    result.exit_code = 128 + interrupted;
    std::ostringstream message;
    message << "interrupted by " << signal_name(interrupted) << " after step " << sim.step << ", time "
            << sim.time << "; continue with --restart " << checkpoints.file().string();
    result.message = message.str();
  }
  if (result.exit_code != kExitNumerical && last_recorded_step != sim.step) outputs.record(sim);
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
  add_state_facts(spec, sim, stepper, facts);
  if (auto warning = capped_domains.warning(); !warning.empty()) facts.warnings.push_back(std::move(warning));
  for (long id : probe_ids) {
    const Vec<D>& X = sim.initial_position[id];
    facts.probes.push_back({id, std::vector<double>(X.data(), X.data() + D)});
  }

  result.summary = run_summary(spec, options, facts, outputs.history());
  write_file_atomically(options.out_dir / "summary.json", result.summary.dump(2) + "\n");
  if (spec.output.plots && !options.scripts_dir.empty())
    if (const auto error = draw_plots(options.out_dir, options.scripts_dir); !error.empty())
      std::fprintf(stderr, "warning: could not draw plots: %s\n", error.c_str());
  result.history = outputs.take_history();
  return result;
}

/// The basis's stencils, plain or (contact) shifted to each particle's velocity field.
template <int D, class Base>
RunResult run_with_fields(const Spec& spec, const RunOptions& options) {
  if constexpr (D > 1)
    if (spec.contact.enabled) return run_with<D, FieldStencils<D, Base>>(spec, options);
  return run_with<D, Base>(spec, options);
}

template <int D>
RunResult run_dim(const Spec& spec, const RunOptions& options) {
  switch (spec.solver.shape) {
    case ShapeKind::BSpline2:
      return run_with_fields<D, TensorStencils<D, QuadraticBSplineBasis>>(spec, options);
    case ShapeKind::BSpline3:
      return run_with_fields<D, TensorStencils<D, CubicBSplineBasis>>(spec, options);
    case ShapeKind::UGIMP:
      return run_with_fields<D, TensorStencils<D, UGimpBasis>>(spec, options);
    case ShapeKind::CpGIMP:
      return run_with_fields<D, TensorStencils<D, CpGimpBasis>>(spec, options);
    case ShapeKind::B2GIMP:
      return run_with_fields<D, TensorStencils<D, B2GimpBasis>>(spec, options);
    case ShapeKind::CPDI1:
      return run_with_fields<D, CpdiStencils<D, HatKernel, CpdiDomain::Parallelogram>>(spec, options);
    case ShapeKind::CPDI2:  // contact with tracked corners is refused by the input reader
      return run_with<D, CpdiStencils<D, HatKernel, CpdiDomain::Tracked>>(spec, options);
    case ShapeKind::B2CPDI:
      return run_with_fields<D, CpdiStencils<D, QuadraticKernel, CpdiDomain::Parallelogram>>(spec, options);
    case ShapeKind::Linear:
      break;
  }
  return run_with_fields<D, TensorStencils<D, LinearBasis>>(spec, options);
}

}  // namespace

RunResult run_explicit(const Spec& spec, const RunOptions& options) {
#ifdef _OPENMP
  if (options.threads > 0) omp_set_num_threads(options.threads);
#endif
  switch (spec.grid.dim) {
    case 1:
      return run_dim<1>(spec, options);
    case 3:
      return run_dim<3>(spec, options);
    default:
      return run_dim<2>(spec, options);
  }
}

std::string draw_plots(const std::filesystem::path& out_dir, const std::filesystem::path& scripts_dir) {
  return run_python_script(scripts_dir / "plot_history.py", {out_dir.string()});
}

}  // namespace matpoint
