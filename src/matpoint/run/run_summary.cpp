#include "matpoint/run/run_summary.hpp"

#include <sys/resource.h>

#include <cmath>

#include "matpoint/analysis/measures_eval.hpp"
#include "matpoint/core/version.hpp"
#include "matpoint/explicit/setup_warnings.hpp"

namespace matpoint {

namespace {

/// getrusage's maximum resident set size of this process (Linux reports KiB), in bytes.
double peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return 1024.0 * static_cast<double>(usage.ru_maxrss);
}

/// The input's name of a check kind (checks[].kind; docs/verification.md counts each kind apart).
const char* check_kind_name(CheckKind kind) {
  switch (kind) {
    case CheckKind::Regression:
      return "regression";
    case CheckKind::Guard:
      return "guard";
    case CheckKind::Verification:
      break;
  }
  return "verification";
}

}  // namespace

namespace {

nlohmann::json energies_json(const HistorySample& s, int dim) {
  return {{"time", s.time},
          {"kinetic_energy", s.kinetic_energy},
          {"strain_energy", s.strain_energy},
          {"total_energy", s.kinetic_energy + s.strain_energy},
          {"external_work", s.external_work},
          {"friction_work", s.friction_work},
          {"plastic_work", s.plastic_work},
          {"momentum", std::vector<double>(s.momentum.begin(), s.momentum.begin() + dim)}};
}

nlohmann::json or_null(bool present, const nlohmann::json& value) {
  return present ? value : nlohmann::json(nullptr);
}

/// The solver's own counters: FMPM loops and the cost fraction F, MLS fallbacks, contact fits.
void add_solver_statistics(const RunFacts& f, nlohmann::json& s) {
  if (f.fmpm) {
    s["fmpm_loops"] = f.fmpm->loops;
    s["fmpm_average_order"] = f.fmpm->average_order();
    s["fmpm_seconds"] = f.fmpm->seconds;
    // Nairn 2026 eq. (3): F = cost of one pass / cost of a step without the loop.
    const double other = f.step_wall - f.fmpm->seconds;
    if (f.fmpm->passes > 0 && f.steps > 0 && other > 0)
      s["fmpm_pass_cost_fraction"] =
          (f.fmpm->seconds / static_cast<double>(f.fmpm->passes)) / (other / static_cast<double>(f.steps));
  }
  if (f.mls) {  // Gong 2015 extraction A16: Shepard fallbacks, counted
    s["mls_reconstructions"] = f.mls->evaluations;
    s["mls_fallbacks"] = f.mls->fallbacks;
  }
  if (f.implicit) {
    s["implicit"] = *f.implicit;
    const double linear =
        f.implicit->value("factorization_seconds", 0.0) + f.implicit->value("solve_seconds", 0.0);
    if (f.step_wall > 0) s["implicit"]["linear_solve_share"] = linear / f.step_wall;
  }
  if (f.logistic_fallbacks)
    s["logistic_fallbacks"] = *f.logistic_fallbacks;  // fits that kept the average normal
}

/// The input's checks, each with its measured value; sets `checks_pass`.
void add_checks(const Spec& spec, const RunFacts& f, const History& history, nlohmann::json& s) {
  s["checks"] = nlohmann::json::array();
  bool all_pass = true;
  FinalState final_state{f.final_stress_xx, f.final_reach, f.final_radius_xy, f.final_runout_x};
  for (const auto& c : spec.checks) {
    const double measured = evaluate_measure(c.measure, spec, history, f.momentum_scale, &final_state);
    const bool pass = std::isfinite(measured) && std::abs(measured - c.expected) <= c.tolerance;
    all_pass = all_pass && pass;
    s["checks"].push_back({{"name", c.name},
                           {"measure", c.measure},
                           {"measured", or_null(std::isfinite(measured), measured)},
                           {"expected", c.expected},
                           {"tolerance", c.tolerance},
                           {"pass", pass},
                           {"kind", check_kind_name(c.kind)},
                           {"source", c.source}});
  }
  s["checks_pass"] = all_pass;
}

}  // namespace

nlohmann::json run_summary(const Spec& spec, const RunOptions& options, const RunFacts& f,
                           const History& history) {
  nlohmann::json s;
  s["matpoint_version"] = kVersion;
  s["title"] = spec.title;
  s["status"] = f.status;
  s["exit_code"] = f.exit_code;
  s["message"] = f.message;
  s["restarted_from"] = or_null(f.restart_step >= 0, options.restart.string());
  s["restarted_at_step"] = or_null(f.restart_step >= 0, f.restart_step);
  s["checkpoint"] = or_null(!f.checkpoint_file.empty(), f.checkpoint_file.string());
  s["checkpoint_step"] = or_null(f.checkpoint_step >= 0, f.checkpoint_step);
  if (!spec.output.probes.empty()) {
    s["probes"] = nlohmann::json::array();
    for (std::size_t k = 0; k < f.probes.size() && k < spec.output.probes.size(); ++k)
      s["probes"].push_back(nlohmann::json{{"name", spec.output.probes[k].name},
                                           {"particle", f.probes[k].particle},
                                           {"reference_position", f.probes[k].reference_position}});
  }
  s["warnings"] = nlohmann::json::array();  // e.g. a Courant number above the measured stability limit
  for (const auto& warning : setup_warnings(spec)) s["warnings"].push_back(warning);
  for (const auto& warning : f.warnings) s["warnings"].push_back(warning);
  s["dimension"] = f.dimension;
  s["particles"] = f.particles;
  s["nodes"] = f.nodes;
  s["bodies"] = spec.bodies.size();
  s["steps"] = f.steps;
  s["time_step"] = f.dt;
  s["time_reached"] = f.time;
  s["threads"] = f.threads;
  s["wall_time_seconds"] = f.wall;
  s["step_wall_seconds"] = f.step_wall;
  s["step_cpu_seconds"] = f.step_cpu;
  const double particle_steps = static_cast<double>(f.particles) * static_cast<double>(f.steps);
  s["particle_steps_per_second"] = f.step_wall > 0 ? particle_steps / f.step_wall : 0.0;
  s["particle_steps_per_cpu_second"] = f.step_cpu > 0 ? particle_steps / f.step_cpu : 0.0;
  // The process's peak resident memory so far (this rank's in a decomposed run), and per particle.
  const double peak = peak_resident_bytes();
  s["peak_memory_bytes"] = peak;
  if (!f.parallel)
    s["memory_bytes_per_particle"] = f.particles > 0 ? peak / static_cast<double>(f.particles) : 0.0;
  if (f.parallel) s["parallel"] = *f.parallel;  // a decomposed run (parallel/parallel_summary.hpp)
  add_solver_statistics(f, s);
  s["outputs"] = f.outputs;
  s["initial"] = energies_json(history.samples.front(), f.dimension);
  s["final"] = energies_json(history.samples.back(), f.dimension);
  add_checks(spec, f, history, s);
  s["input"] = spec.echo;
  return s;
}

}  // namespace matpoint
