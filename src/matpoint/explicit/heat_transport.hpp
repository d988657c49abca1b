// Coupled heat conduction in the explicit step (Nairn 2026 §3.2.2, §3.5; docs/theory/heat.md).
// Transport on the grid with the nodal capacity in place of the nodal mass:
//   c_i = sum_p w_p S_pi,  T_i = (sum_p w_p S_pi T_p) / c_i,        w_p = M_p C_V,p
//   grad T_p = sum_i T_i grad S_pi,  q_p = -kappa_p grad T_p
//   Qdot_i = sum_p V_p q_p . grad S_pi + (fixed fluxes) ,  T+_i = T_i + (Qdot_i dt + H_i) / c_i
// with H_i the frictional heat of the contact nodes, and fixed temperatures held on T_i and T+_i.
// Particle update: FLIP-like T_p += sum_i S_pi (T+_i - T_i) with T_i as extrapolated, before the
// fixed temperatures (as the velocity increment includes the conditions' reaction), or transport FMPM(k),
// T_p = sum_i S_pi T+(k)_i with T+(k) from the same FMPM loop as the velocities (fmpm.hpp).
// With contact, each field has its own nodal temperatures, coupled at the contact nodes by
// thermal_contact.hpp (perfect contact, an interface conductance, or insulated).
// Thermoelastic coupling (alpha > 0; linear_elastic, neo_hookean): the free energy per reference
// volume gains -3 K alpha (T - T0) ln J, so the Kirchhoff stress gains -3 K alpha (T - T0) I and the
// adiabatic heating is rho0 C_V dT/dt = -3 K alpha T d(ln J)/dt; with the step's d ln J = tr(L) dt
// it is integrated exactly, T <- T exp(-3 K alpha tr(L) dt / (rho0 C_V)), so that an adiabatic path
// gives T = T0 exp(-3 K alpha ln J / (rho0 C_V)), at small strain dT = -3 alpha K T0 tr(eps) / (rho0 C_V).
#pragma once

#include <cmath>
#include <vector>

#include "matpoint/explicit/fmpm.hpp"
#include "matpoint/explicit/scalar_scatter.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/explicit/thermal_contact.hpp"
#include "matpoint/grid/thermal_conditions.hpp"

namespace matpoint {

template <int D>
class HeatTransport {
 public:
  HeatTransport() = default;
  HeatTransport(const Simulation<D>& sim, int fields)
      : active_(sim.heat.enabled),
        conditions_(sim.heat.conditions, sim.grid, fields, sim.solver.shape),
        fmpm_(transport_fmpm(sim.heat)),
        fields_(fields) {
    if (!active_) return;
    if (fields > 1 && sim.heat.conduction)
      contact_ = ThermalContactCoupling<D>(sim.heat.contact, sim.heat.contact_conductance);
    transfer_flip_ = sim.heat.transfer == HeatTransfer::FLIP;
    node_heat_.assign(static_cast<std::size_t>(fields) * sim.grid.node_count, 0.0);
    double heaviest = 0.0;
    for (std::size_t p = 0; p < sim.particles.size(); ++p)
      heaviest = std::max(heaviest, sim.particles.mass[p] * sim.heat_capacity[sim.particles.material[p]]);
    floor_ = sim.solver.mass_tolerance * sim.comm.max(heaviest);  // a decomposed run: of every rank
    if (sim.comm.distributed())
      conditions_.count_only(sim.owned_nodes, sim.grid.node_count);
  }

  [[nodiscard]] bool active() const { return active_; }

  /// A decomposed run's owned nodes changed (a re-partition): the conditions' heat counts them.
  void count_only(const Simulation<D>& sim) {
    conditions_.count_only(sim.owned_nodes, sim.grid.node_count);
  }

  /// A decomposed run's rank stores another window of the grid (sim.grid, `old` the last one):
  /// the thermal conditions' nodes are selected anew and the frictional heat waiting for the next
  /// step is carried over by node (a node the last window did not store has none on this rank).
  void use_window(const Simulation<D>& sim, const Grid<D>& old) {
    if (!active_) return;
    conditions_ = ThermalConditions<D>(sim.heat.conditions, sim.grid, fields_, sim.solver.shape);
    count_only(sim);
    const Index n = sim.grid.node_count, n_old = old.node_count;
    std::vector<double> heat(static_cast<std::size_t>(fields_) * n, 0.0);
    for (Index i = 0; i < n; ++i)
      if (const Index k = sim.grid.node_index_in(old, i); k >= 0)
        for (Index f = 0; f < fields_; ++f) heat[f * n + i] = node_heat_[f * n_old + k];
    node_heat_ = std::move(heat);
  }

  /// The frictional heat of this step by (multi-field) node, J; consumed by the next step().
  std::vector<double>& node_heat() { return node_heat_; }

  /// Adiabatic thermoelastic heating over the strain increment of L dt (after the stress update).
  void thermoelastic(const Simulation<D>& sim, ParticleSet<D>& ps, double dt) const {
    if (!sim.heat.thermoelastic) return;
    const auto n = static_cast<std::ptrdiff_t>(ps.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) {
      const auto m = static_cast<std::size_t>(ps.material[p]);
      const double b = sim.expansion_modulus[m];
      if (b == 0.0 || sim.heat_capacity[m] <= 0.0) continue;
      const double rho0 = ps.mass[p] / ps.volume0[p];
      ps.temperature[p] *= std::exp(-b * ps.L[p].trace() * dt / (rho0 * sim.heat_capacity[m]));
    }
  }

  /// Thermal expansion: Cauchy stress sigma -= 3 K alpha (T - T0) / J I (also sigma_zz in 2-D).
  void thermal_stress(const Simulation<D>& sim, ParticleSet<D>& ps) const {
    const auto n = static_cast<std::ptrdiff_t>(ps.size());
    const double T0 = sim.heat.initial_temperature;
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) {
      const double b = sim.expansion_modulus[ps.material[p]];
      if (b == 0.0) continue;
      const double pressure = b * (ps.temperature[p] - T0) / ps.F[p].determinant();
      ps.stress[p].diagonal().array() -= pressure;
      if constexpr (D == 2) ps.stress_zz[p] -= pressure;
    }
  }

  /// One conduction step of size dt on the step's stencils; adds the heat through the thermal
  /// conditions to `boundary_heat`.
  template <class Stencils>
  void step(const Simulation<D>& sim, const Grid<D>& grid, const Stencils& stencils, ParticleSet<D>& ps,
            double dt, double t_new, double& boundary_heat) {
    const std::size_t n = ps.size();
    weight_.resize(n);
    for (std::size_t p = 0; p < n; ++p) weight_[p] = ps.mass[p] * sim.heat_capacity[ps.material[p]];
    scatter_scalar(grid, stencils, capacity_,
                   [&](std::ptrdiff_t p, double N, const Vec<D>&) { return weight_[p] * N; });
    scatter_scalar(grid, stencils, temperature_, [&](std::ptrdiff_t p, double N, const Vec<D>&) {
      return weight_[p] * N * ps.temperature[p];
    });
    const auto nodes = static_cast<std::ptrdiff_t>(capacity_.size());
    for (std::ptrdiff_t i = 0; i < nodes; ++i)
      temperature_[i] = capacity_[i] > floor_ ? temperature_[i] / capacity_[i] : 0.0;
    if (fields_ > 1) contact_.prepare(sim.contact, capacity_, floor_);
    if (contact_.perfect()) contact_.mix(temperature_, capacity_);
    start_ = temperature_;  // the FLIP increment T+ - T includes the conditions' change of T_i
    conditions_.apply(temperature_, t_new, &capacity_, &boundary_heat);
    heat_flow(sim, grid, stencils, ps);
    boundary_heat += dt * conditions_.add_flux(flow_, capacity_, floor_);
    contact_.exchange(grid, stencils, ps, temperature_, capacity_, floor_, dt, flow_);
    updated_.resize(capacity_.size());
    for (std::ptrdiff_t i = 0; i < nodes; ++i) {
      updated_[i] =
          capacity_[i] > floor_ ? temperature_[i] + (flow_[i] * dt + node_heat_[i]) / capacity_[i] : 0.0;
      node_heat_[i] = 0.0;
    }
    if (contact_.perfect()) contact_.mix(updated_, capacity_);
    conditions_.apply(updated_, t_new, &capacity_, &boundary_heat);
    update_particles(grid, stencils, ps, t_new, boundary_heat);
  }

  [[nodiscard]] const FmpmStatistics& fmpm_statistics() const { return fmpm_.statistics(); }
  [[nodiscard]] const ThermalContactCoupling<D>& contact() const { return contact_; }
  /// A decomposed run's particles near the window, for the contact conductance's volumes.
  void use_near_domains(const typename ThermalContactCoupling<D>::NearDomains* near) {
    contact_.use_near(near);
  }

 private:
  static FmpmSpec transport_fmpm(const HeatSpec& h) {
    FmpmSpec f;
    f.order = h.transfer == HeatTransfer::FMPM ? h.fmpm_order : 1;
    return f;
  }

  /// flow_i = sum_p V_p q_p . grad S_pi with q_p = -kappa_p grad T_p (zero without conduction).
  template <class Stencils>
  void heat_flow(const Simulation<D>& sim, const Grid<D>& grid, const Stencils& stencils,
                 const ParticleSet<D>& ps) {
    if (!sim.heat.conduction) {
      flow_.assign(capacity_.size(), 0.0);
      return;
    }
    const auto n = static_cast<std::ptrdiff_t>(ps.size());
    flux_.resize(ps.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) {
      Vec<D> gradient = Vec<D>::Zero();
      stencils.for_each_node(
          grid, p, [&](Index node, double, const Vec<D>& dN) { gradient += temperature_[node] * dN; });
      flux_[p] = -sim.conductivity[ps.material[p]] * ps.volume(p) * gradient;  // V_p q_p
    }
    scatter_scalar(grid, stencils, flow_,
                   [&](std::ptrdiff_t p, double, const Vec<D>& dN) { return flux_[p].dot(dN); });
  }

  /// FLIP-like T_p += S (T+ - T), or transport FMPM(k) T_p = S T+(k); particles without
  /// capacity (a rigid material without C_V) keep their temperature.
  template <class Stencils>
  void update_particles(const Grid<D>& grid, const Stencils& stencils, ParticleSet<D>& ps, double t_new,
                        double& boundary_heat) {
    const bool flip = transfer_flip_;
    if (!flip) {
      fmpm_.set_particle_weights(&weight_);
      if (contact_.perfect())  // perfect contact: one increment per contact node, as one temperature
        fmpm_.set_increment_correction([this](std::vector<double>& dT) { contact_.mix(dT, capacity_); });
      else
        fmpm_.set_increment_correction(nullptr);
      fmpm_.run(grid, stencils, ps, capacity_, floor_, conditions_, t_new, updated_, &boundary_heat);
    } else {
      for (std::size_t i = 0; i < updated_.size(); ++i) updated_[i] -= start_[i];
    }
    const auto n = static_cast<std::ptrdiff_t>(ps.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) {
      if (!(weight_[p] > 0.0)) continue;
      double T = 0.0;
      stencils.for_each_node(grid, p, [&](Index node, double N, const Vec<D>&) { T += N * updated_[node]; });
      ps.temperature[p] = flip ? ps.temperature[p] + T : T;
    }
  }

  bool active_ = false;
  bool transfer_flip_ = true;
  ThermalConditions<D> conditions_;
  FmpmLoop<D, double> fmpm_;
  ThermalContactCoupling<D> contact_;  // insulated unless contact fields conduct
  int fields_ = 1;
  double floor_ = 0.0;               // nodes at or below this capacity are inactive
  std::vector<double> weight_;       // w_p = M_p C_V,p
  std::vector<double> capacity_;     // c_i
  std::vector<double> temperature_;  // T_i, fixed temperatures applied
  std::vector<double> start_;        // T_i as extrapolated from the particles
  std::vector<double> flow_;         // Qdot_i
  std::vector<double> updated_;      // T+_i (FLIP: T+_i - T_i)
  std::vector<double> node_heat_;    // H_i
  std::vector<Vec<D>> flux_;         // V_p q_p
};

}  // namespace matpoint
