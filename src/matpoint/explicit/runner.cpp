#include "matpoint/explicit/runner.hpp"

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <iomanip>
#include <sstream>

#include "matpoint/analysis/diagnostics.hpp"
#include "matpoint/analysis/grid_modes.hpp"
#include "matpoint/analysis/history.hpp"
#include "matpoint/analysis/measures_eval.hpp"
#include "matpoint/core/errors.hpp"
#include "matpoint/core/interrupt.hpp"
#include "matpoint/core/progress.hpp"
#include "matpoint/core/version.hpp"
#include "matpoint/explicit/courant_limits.hpp"
#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/io/atomic_file.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/io/vtk_writer.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/domains.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace matpoint {

namespace {

template <int D> std::array<double, 3> pad(const Vec<D>& v) {
  std::array<double, 3> out{};
  for (int a = 0; a < D; ++a) out[a] = v[a];
  return out;
}

template <int D> HistorySample sample(const Simulation<D>& sim, int body_count) {
  const auto d = measure_diagnostics(sim, body_count);
  HistorySample s;
  s.time = sim.time;
  s.step = sim.step;
  s.kinetic_energy = d.kinetic_energy;
  s.strain_energy = d.strain_energy;
  s.external_work = sim.external_work;
  s.friction_work = sim.friction_work;
  s.momentum = pad<D>(d.momentum);
  s.external_impulse = pad<D>(sim.external_impulse);
  s.min_jacobian = d.min_jacobian;
  s.rms_velocity_change = d.rms_velocity_change;
  s.body_kinetic = d.body_kinetic;
  s.body_strain = d.body_strain;
  s.body_mass = d.body_mass;
  s.grid_momentum_difference = pad<D>(sim.grid_momentum_difference);
  const GridModes modes = measure_grid_modes(sim.grid, sim.fields.mass, sim.fields.velocity_new);
  s.checkerboard_velocity = modes.checkerboard_velocity;
  s.grid_rms_velocity = modes.rms_velocity;
  s.hourglass_energy = modes.hourglass_energy;
  for (int b = 0; b < body_count; ++b) {
    s.body_momentum.push_back(pad<D>(d.body_momentum[b]));
    s.body_com_velocity.push_back(pad<D>(Vec<D>(d.body_momentum[b] / std::max(d.body_mass[b], 1e-300))));
    s.body_com_position.push_back(pad<D>(d.body_com_position[b]));
  }
  return s;
}

nlohmann::json energies_json(const HistorySample& s, int dim) {
  return {{"time", s.time},
          {"kinetic_energy", s.kinetic_energy},
          {"strain_energy", s.strain_energy},
          {"total_energy", s.kinetic_energy + s.strain_energy},
          {"external_work", s.external_work},
          {"friction_work", s.friction_work},
          {"momentum", std::vector<double>(s.momentum.begin(), s.momentum.begin() + dim)}};
}

std::string output_name(long index, const char* prefix = "particles_") {
  std::ostringstream name;
  name << prefix << std::setw(6) << std::setfill('0') << index << ".vtu";
  return name.str();
}

/// Decides which steps write output.
class OutputSchedule {
 public:
  /// `next_time`: the next output time of an every_time schedule (a restart's, or every_time).
  OutputSchedule(const OutputSpec& o, double time, double next_time) : spec_(o), next_time_(next_time) {
    const double every = o.every_time;  // a restart may change every_time: start on its next multiple
    if (every > 0 && !(next_time_ > time && next_time_ <= time + every * (1 + 1e-9)))
      next_time_ = (std::floor(time / every) + 1) * every;
  }
  bool due(long step, double time, double dt) {
    if (spec_.every_steps > 0) return step % spec_.every_steps == 0;
    if (spec_.every_time > 0 && time >= next_time_ - 1e-6 * dt) {
      while (next_time_ <= time + 1e-6 * dt) next_time_ += spec_.every_time;
      return true;
    }
    return false;
  }
  [[nodiscard]] double next_time() const { return next_time_; }

 private:
  OutputSpec spec_;
  double next_time_;
};

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

/// Starts a run: from the input (dt and the momentum scale from the initial state) or from a
/// checkpoint (everything as the interrupted run had it). Throws InputError before writing.
template <int D>
RunCounters start_state(const Spec& spec, const RunOptions& options, Simulation<D>& sim, History& history) {
  RunCounters run;
  if (!options.restart.empty()) {
    read_checkpoint<D>(options.restart, spec.echo, sim, run, history);
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

template <int D, class Stencils> RunResult run_with(const Spec& spec, const RunOptions& options) {
  Simulation<D> sim = build_simulation<D>(spec);  // may throw InputError: nothing written yet
  const int body_count = static_cast<int>(spec.bodies.size());
  History history{D, body_count, {}};
  RunCounters run = start_state<D>(spec, options, sim, history);  // may throw InputError too
  const bool restarting = !options.restart.empty();
  const double dt = run.dt;
  const auto& out_dir = options.out_dir;
  std::filesystem::create_directories(out_dir);

  PvdCollection pvd(out_dir / "results.pvd");
  PvdCollection domains_pvd(out_dir / "domains.pvd");  // GIMP / CPDI particle domains (docs/output.md)
  pvd.restore(run.results);                            // a restart rewrites them as the checkpoint knew them
  domains_pvd.restore(run.domains);
  const bool write_domains = spec.output.particles && has_particle_domains(spec.solver.shape);
  long outputs = run.outputs;
  // history.csv is rewritten whole (atomically) at most once a second, with every particle
  // output, and at the end: rewriting it at every one of many frequent outputs would cost O(n^2).
  auto last_history_write = std::chrono::steady_clock::now() - std::chrono::hours(1);
  auto write_history = [&] {
    write_file_atomically(out_dir / "history.csv", history.csv());
    last_history_write = std::chrono::steady_clock::now();
  };
  auto record = [&] {
    history.samples.push_back(sample(sim, body_count));
    if (spec.output.particles || std::chrono::steady_clock::now() - last_history_write > std::chrono::seconds(1))
      write_history();
    if (spec.output.particles) {
      const std::string name = output_name(outputs);
      write_file_atomically(out_dir / name, particles_vtu(sim.particles, spec.output.fields));
      pvd.add(sim.time, name);
      if (write_domains) {
        const std::string domains = output_name(outputs, "domains_");
        const auto corners = particle_domains<D>(spec.solver.shape, sim.grid, sim.particles);
        write_file_atomically(out_dir / domains, domains_vtu<D>(corners, sim.particles));
        domains_pvd.add(sim.time, domains);
      }
    }
    ++outputs;
  };

  ExplicitStepper<D, Stencils> stepper(sim);
  if (restarting)
    stepper.restore(
        {run.next_fmpm_time, run.total_mass, {run.fmpm_loops, run.fmpm_passes, run.fmpm_seconds}});
  OutputSchedule schedule(spec.output, sim.time, run.next_output_time);
  Progress progress(options.progress, spec.solver.end_time);
  long last_recorded_step = run.last_recorded_step;
  const long restart_step = sim.step;
  if (restarting)
    write_history();  // drops any rows a killed run wrote after its checkpoint
  else
    record();

  RunResult result;
  const auto wall_start = std::chrono::steady_clock::now();
  double step_wall = run.step_wall, step_cpu = run.step_cpu;
  const auto wall_now = [&] {
    return run.wall + std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };

  // A checkpoint holds the state after a completed step with the scheduled outputs up to it; it is
  // taken before the extra output of a run's last step, so a restart repeats the outputs exactly.
  const CheckpointSpec& every = spec.output.checkpoint;
  auto last_checkpoint_wall = std::chrono::steady_clock::now();
  long checkpoint_step = restarting ? sim.step : -1;
  std::filesystem::path checkpoint_file;
  auto save_checkpoint = [&] {
    RunCounters now = run;
    const auto stepper_state = stepper.state();
    now.outputs = outputs;
    now.next_output_time = schedule.next_time();
    now.last_recorded_step = last_recorded_step;
    now.next_fmpm_time = stepper_state.next_fmpm_time;
    now.total_mass = stepper_state.total_mass;
    now.fmpm_loops = stepper_state.fmpm.loops;
    now.fmpm_passes = stepper_state.fmpm.passes;
    now.fmpm_seconds = stepper_state.fmpm.seconds;
    now.step_wall = step_wall, now.step_cpu = step_cpu, now.wall = wall_now();
    now.threads = current_threads();
    now.results = pvd.entries(), now.domains = domains_pvd.entries();
    checkpoint_file = out_dir / kCheckpointFile;
    write_checkpoint<D>(checkpoint_file, out_dir / kPreviousCheckpointFile, sim, now, history, spec.echo);
    last_checkpoint_wall = std::chrono::steady_clock::now();
    checkpoint_step = sim.step;
  };
  auto checkpoint_due = [&] {
    const auto minutes =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint_wall).count() / 60;
    return (every.every_steps > 0 && sim.step % every.every_steps == 0) ||
           (every.every_minutes > 0 && minutes >= every.every_minutes);
  };

  int interrupted = 0;
  const double end_time = spec.solver.end_time;
  while (sim.time < end_time - 1e-9 * dt && (spec.solver.max_steps == 0 || sim.step < spec.solver.max_steps)) {
    const double h = std::min(dt, end_time - sim.time);
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    try {
      stepper.step(h);
    } catch (const NumericalFailure& failure) {
      result.exit_code = kExitNumerical;
      result.message = failure.what();
      break;
    }
    step_cpu += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    step_wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (schedule.due(sim.step, sim.time, h)) {
      record();
      last_recorded_step = sim.step;
    }
    progress.update(sim.step, sim.time);
    if (checkpoint_due()) save_checkpoint();
    if ((interrupted = interrupt_signal()) != 0) break;
  }
  const bool finished = result.exit_code == kExitOk && interrupted == 0;
  if (checkpoint_step != sim.step && (interrupted != 0 || (finished && every.enabled()))) save_checkpoint();
  if (interrupted != 0) {
    result.exit_code = 128 + interrupted;
    std::ostringstream message;
    message << "interrupted by " << signal_name(interrupted) << " after step " << sim.step << ", time "
            << sim.time << "; continue with --restart " << checkpoint_file.string();
    result.message = message.str();
  }
  if (result.exit_code != kExitNumerical && last_recorded_step != sim.step) record();
  write_history();
  progress.finish(finished ? "done" : interrupted != 0 ? "interrupted" : "stopped: numerical failure");
  const double wall = wall_now();

  const double particle_steps = static_cast<double>(sim.particles.size()) * static_cast<double>(sim.step);
  auto& s = result.summary;
  s["matpoint_version"] = kVersion;
  s["title"] = spec.title;
  s["status"] = finished ? "ok" : interrupted != 0 ? "interrupted" : "numerical_failure";
  s["exit_code"] = result.exit_code;
  s["message"] = result.message;
  s["restarted_from"] = restarting ? nlohmann::json(options.restart.string()) : nlohmann::json(nullptr);
  s["restarted_at_step"] = restarting ? nlohmann::json(restart_step) : nlohmann::json(nullptr);
  s["checkpoint"] =
      checkpoint_file.empty() ? nlohmann::json(nullptr) : nlohmann::json(checkpoint_file.string());
  s["checkpoint_step"] = checkpoint_step >= 0 ? nlohmann::json(checkpoint_step) : nlohmann::json(nullptr);
  s["warnings"] = nlohmann::json::array();  // e.g. a Courant number above the measured stability limit
  if (const auto warning = courant_warning(spec.solver); !warning.empty()) s["warnings"].push_back(warning);
  s["dimension"] = D;
  s["particles"] = sim.particles.size();
  s["nodes"] = sim.grid.node_count;
  s["bodies"] = body_count;
  s["steps"] = sim.step;
  s["time_step"] = dt;
  s["time_reached"] = sim.time;
  s["threads"] = current_threads();
  s["wall_time_seconds"] = wall;
  s["step_wall_seconds"] = step_wall;
  s["step_cpu_seconds"] = step_cpu;
  s["particle_steps_per_second"] = step_wall > 0 ? particle_steps / step_wall : 0.0;
  s["particle_steps_per_cpu_second"] = step_cpu > 0 ? particle_steps / step_cpu : 0.0;
  if (spec.solver.transfer == VelocityTransfer::FMPM || spec.solver.transfer == VelocityTransfer::XPIC) {
    const auto& stats = stepper.fmpm_statistics();
    s["fmpm_loops"] = stats.loops;
    s["fmpm_average_order"] = stats.average_order();
    s["fmpm_seconds"] = stats.seconds;
    // Nairn 2026 eq. (3): F = cost of one pass / cost of a step without the loop.
    const double other = step_wall - stats.seconds;
    if (stats.passes > 0 && sim.step > 0 && other > 0)
      s["fmpm_pass_cost_fraction"] = (stats.seconds / static_cast<double>(stats.passes)) /
                                     (other / static_cast<double>(sim.step));
  }
  if (spec.solver.mapping != Mapping::MPM) {  // Gong 2015 extraction A16: Shepard fallbacks, counted
    s["mls_reconstructions"] = stepper.mls_statistics().evaluations;
    s["mls_fallbacks"] = stepper.mls_statistics().fallbacks;
  }
  s["outputs"] = outputs;
  s["initial"] = energies_json(history.samples.front(), D);
  s["final"] = energies_json(history.samples.back(), D);
  s["checks"] = nlohmann::json::array();
  bool all_pass = true;
  FinalState final_state;
  for (const auto& stress : sim.particles.stress) final_state.stress_xx.push_back(stress(0, 0));
  for (const auto& c : spec.checks) {
    const double measured = evaluate_measure(c.measure, spec, history, run.momentum_scale, &final_state);
    const bool pass = std::isfinite(measured) && std::abs(measured - c.expected) <= c.tolerance;
    all_pass = all_pass && pass;
    s["checks"].push_back({{"name", c.name},
                           {"measure", c.measure},
                           {"measured", std::isfinite(measured) ? nlohmann::json(measured) : nlohmann::json(nullptr)},
                           {"expected", c.expected},
                           {"tolerance", c.tolerance},
                           {"pass", pass},
                           {"source", c.source}});
  }
  s["checks_pass"] = all_pass;
  s["input"] = spec.echo;
  write_file_atomically(out_dir / "summary.json", s.dump(2) + "\n");
  if (spec.output.plots && !options.scripts_dir.empty() && !draw_plots(out_dir, options.scripts_dir))
    std::fprintf(stderr, "warning: could not draw plots (needs python3-matplotlib)\n");
  result.history = std::move(history);
  return result;
}

/// The basis's stencils, plain or (contact) shifted to each particle's velocity field.
template <int D, class Base>
RunResult run_with_fields(const Spec& spec, const RunOptions& options) {
  if constexpr (D > 1)
    if (spec.contact.enabled) return run_with<D, FieldStencils<D, Base>>(spec, options);
  return run_with<D, Base>(spec, options);
}

template <int D> RunResult run_dim(const Spec& spec, const RunOptions& options) {
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

bool draw_plots(const std::filesystem::path& out_dir, const std::filesystem::path& scripts_dir) {
  const auto script = scripts_dir / "plot_history.py";
  if (!std::filesystem::exists(script)) return false;
  // Debian's interpreter first: python3-matplotlib installs there, whatever else is on PATH.
  const char* python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string command = std::string(python) + " '" + script.string() + "' '" + out_dir.string() + "' > /dev/null";
  return std::system(command.c_str()) == 0;
}

}  // namespace matpoint
