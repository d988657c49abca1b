// One explicit MPM time step in the update schemes of Nairn 2026 §2.1 (Table: USL, USF, USL+ = MUSL,
// USAVG). The step reads as the list of stages in DESIGN.md; every stage is a free function over
// plain arrays, and the stencils are evaluated once per step and reused by every transfer.
#pragma once

#include "matpoint/core/errors.hpp"
#include "matpoint/explicit/deformation.hpp"
#include "matpoint/explicit/gather.hpp"
#include "matpoint/explicit/grid_update.hpp"
#include "matpoint/explicit/scatter.hpp"
#include "matpoint/explicit/simulation.hpp"
#include "matpoint/particles/generators.hpp"

#include <sstream>
#include <string>

namespace matpoint {

template <int D, class Stencils> class ExplicitStepper {
 public:
  /// Particles are re-sorted by cell every `sort_interval` steps (memory locality only).
  static constexpr long sort_interval = 10;

  explicit ExplicitStepper(Simulation<D>& sim) : s_(sim) {
    velocity_.resize(sim.grid.node_count);
    for (double m : sim.particles.mass) total_mass_ += m;
  }

  /// Advances the simulation by dt; throws NumericalFailure naming step, time and particle.
  void step(double dt) {
    if (s_.step % sort_interval == 0) sort_by_cell(s_.grid, s_.particles);
    stencils_.evaluate(s_.grid, s_.particles);
    step_dt_ = dt;
    const double t_new = s_.time + dt;
    switch (s_.solver.scheme) {
      case UpdateScheme::USL:
        scatter<kScatterMass | kScatterMomentum | kScatterForce>();
        grid_momentum_update(dt, t_new);
        move_particles(dt, /*with_gradient=*/true);
        update_strain(dt);
        break;
      case UpdateScheme::USF:
        scatter<kScatterMass | kScatterMomentum>();
        strain_from_momentum(dt, s_.time);
        scatter<kScatterForce>();
        grid_momentum_update(dt, t_new);
        move_particles(dt, /*with_gradient=*/false);
        break;
      case UpdateScheme::USAVG:  // USF and USL halves, each with dt / 2
        scatter<kScatterMass | kScatterMomentum>();
        strain_from_momentum(0.5 * dt, s_.time);
        scatter<kScatterForce>();
        grid_momentum_update(dt, t_new);
        move_particles(dt, /*with_gradient=*/true);
        update_strain(0.5 * dt);
        break;
      case UpdateScheme::MUSL:  // USL+: strain from the momenta re-extrapolated from the new velocities
        scatter<kScatterMass | kScatterMomentum | kScatterForce>();
        grid_momentum_update(dt, t_new);
        move_particles(dt, /*with_gradient=*/false);
        scatter<kScatterMomentum>();
        strain_from_momentum(dt, t_new);
        break;
    }
    s_.time = t_new;
    ++s_.step;
  }

  [[nodiscard]] const Stencils& stencils() const { return stencils_; }

 private:
  template <unsigned What> void scatter() {
    scatter_to_grid<What>(s_.grid, stencils_, s_.particles, s_.gravity, s_.fields, workspace_);
  }

  void grid_momentum_update(double dt, double t_new) {
    Vec<D> impulse = Vec<D>::Zero();
    double work = 0.0;
    update_grid_velocities(s_.fields, dt, s_.mass_floor, s_.conditions, t_new, impulse, work);
    s_.external_impulse += impulse + total_mass_ * s_.gravity * dt;
    s_.external_work += work;
  }

  void move_particles(double dt, bool with_gradient) {
    const TransferParameters transfer{s_.solver.transfer, s_.solver.position_alpha, s_.solver.flip_fraction};
    const auto result = gather_and_move(s_.grid, stencils_, s_.fields, s_.particles, transfer, dt, with_gradient, s_.gravity);
    if constexpr (requires { stencils_.move_domains(s_.grid, s_.fields, s_.particles, dt); })
      stencils_.move_domains(s_.grid, s_.fields, s_.particles, dt);  // CPDI2 corners (Gong 2015 eq. (6.28))
    s_.external_work += result.gravity_work;
    if (result.first_outside >= 0)
      fail(result.first_outside, "left the grid domain or has a non-finite velocity");
  }

  /// L from the lumped velocities p/m with the conditions at time t (USF task 1.b-1.d, MUSL 4.a-4.c).
  void strain_from_momentum(double dt, double t) {
    lumped_velocity(s_.fields, s_.mass_floor, velocity_);
    s_.conditions.apply(velocity_, t);
    gather_velocity_gradient(s_.grid, stencils_, velocity_, s_.particles);
    update_strain(dt);
  }

  void update_strain(double dt) {
    update_deformation(s_.particles, dt, s_.solver.deformation_update);
    const long bad = update_stress<D>(s_.materials, s_.particles);
    if (bad >= 0) {
      std::ostringstream what;
      what << "det F = " << s_.particles.F[bad].determinant() << " (needs > 0) or a non-finite stress";
      fail(bad, what.str());
    }
  }

  [[noreturn]] void fail(long p, const std::string& what) const {
    std::ostringstream entity;
    entity << "particle " << s_.particles.id[p] << " (body " << s_.particles.body[p] << ") at x = ("
           << s_.particles.x[p].transpose() << ")";
    throw NumericalFailure(s_.step + 1, s_.time + step_dt_, entity.str(), what);
  }

  Simulation<D>& s_;
  Stencils stencils_;
  ScatterWorkspace<D> workspace_;
  std::vector<Vec<D>> velocity_;  // scratch node velocities for USF / MUSL
  double total_mass_ = 0.0;
  double step_dt_ = 0.0;
};

}  // namespace matpoint
