// The explicit solver as the shared run loop (run/run_loop.hpp) sees it: the Simulation, its
// stepper for one basis, the stable time step, and the solver's own counters and warnings.
#pragma once

#include <algorithm>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/io/checkpoint.hpp"
#include "matpoint/run/energy_guard.hpp"
#include "matpoint/run/run_summary.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace matpoint {

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

/// One explicit run of basis `Stencils` in D dimensions (run/run_loop.hpp lists the interface).
template <int D, class Stencils>
class ExplicitSolver {
 public:
  /// Builds the simulation; throws InputError (nothing written yet) for what only the set-up finds.
  explicit ExplicitSolver(const Spec& spec)
      : spec_(spec), sim_(build_simulation<D>(spec)), stepper_(sim_), capped_(spec, sim_.particles.size()) {}
  ExplicitSolver(const ExplicitSolver&) = delete;
  ExplicitSolver& operator=(const ExplicitSolver&) = delete;

  Simulation<D>& sim() { return sim_; }
  [[nodiscard]] const Simulation<D>& sim() const { return sim_; }

  /// solver.dt, or the Courant step of the present state (Nairn 2026 §1.8).
  [[nodiscard]] double time_step() const { return stable_time_step(sim_); }
  void step(double h) {
    // loads.gravity_scale at the step's start (the forward step's body force)
    const double scale = spec_.loads.gravity_scale(sim_.time);
    for (int a = 0; a < D; ++a) sim_.gravity[a] = scale * spec_.loads.gravity[a];
    stepper_.step(h);
  }
  void after_step() { capped_.check(sim_); }

  void save(RunCounters& counters) const {
    const auto state = stepper_.state();
    counters.next_fmpm_time = state.next_fmpm_time;
    counters.total_mass = state.total_mass;
    counters.fmpm_loops = state.fmpm.loops;
    counters.fmpm_passes = state.fmpm.passes;
    counters.fmpm_seconds = state.fmpm.seconds;
  }
  void restore(const RunCounters& c) {
    stepper_.restore({c.next_fmpm_time, c.total_mass, {c.fmpm_loops, c.fmpm_passes, c.fmpm_seconds}});
  }

  /// Coupled heat (HeatSpec) adds its columns (docs/output.md): the largest and the mean particle
  /// temperature, the heat content Q_T = sum_p M_p C_V (T_p - T0), and the heat in, Q = the heat
  /// through the thermal conditions plus the frictional work turned into heat.
  [[nodiscard]] std::vector<std::string> history_columns() const {
    if (!sim_.heat.enabled) return {};
    return {"temperature_max", "temperature_mean", "heat_content", "heat_in"};
  }
  std::vector<double> history_values() {
    if (!sim_.heat.enabled) return {};
    const auto& ps = sim_.particles;
    double largest = -std::numeric_limits<double>::infinity(), sum = 0.0, content = 0.0;
    for (std::size_t p = 0; p < ps.size(); ++p) {
      largest = std::max(largest, ps.temperature[p]);
      sum += ps.temperature[p];
      content += ps.mass[p] * sim_.heat_capacity[ps.material[p]] * (ps.temperature[p] - sim_.heat.initial_temperature);
    }
    const double mean = ps.size() > 0 ? sum / static_cast<double>(ps.size()) : 0.0;
    const double in = sim_.boundary_heat + (sim_.heat.friction ? sim_.friction_work : 0.0);
    return {largest, mean, content, in};
  }
  void write_static_outputs(const std::filesystem::path&, std::string&) const {}

  void add_facts(RunFacts& facts) const {
    const SolverSpec& s = spec_.solver;
    if (s.transfer == VelocityTransfer::FMPM || s.transfer == VelocityTransfer::XPIC)
      facts.fmpm = stepper_.fmpm_statistics();
    if (s.mapping != Mapping::MPM) facts.mls = stepper_.mls_statistics();
    if (sim_.has_contact && spec_.contact.normals == ContactNormals::Logistic)
      facts.logistic_fallbacks = sim_.contact.logistic_fallbacks();
    if (auto warning = capped_.warning(); !warning.empty()) facts.warnings.push_back(std::move(warning));
  }

 private:
  const Spec& spec_;
  Simulation<D> sim_;
  ExplicitStepper<D, Stencils> stepper_;
  CappedDomains capped_;
};

}  // namespace matpoint
