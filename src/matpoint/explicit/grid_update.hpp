// Grid tasks between the transfers (Nairn 2026 §2.1 tasks 2.a, 3): lumped velocities, the momentum
// update and the velocity conditions.
#pragma once

#include "matpoint/grid/grid_fields.hpp"
#include "matpoint/grid/velocity_conditions.hpp"

namespace matpoint {

struct BoundaryWork {
  double work = 0.0;  // work of moving walls on the grid
};

/// velocity = p / m on nodes heavier than mass_floor, zero elsewhere.
template <int D> void lumped_velocity(const GridFields<D>& fields, double mass_floor, std::vector<Vec<D>>& velocity) {
  const auto n = static_cast<std::ptrdiff_t>(fields.mass.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
  for (std::ptrdiff_t i = 0; i < n; ++i)
    velocity[i] = fields.mass[i] > mass_floor ? Vec<D>((fields.momentum[i] / fields.mass[i]).eval()) : Vec<D>::Zero();
}

/// v(1) = p/m, v+(1) = (p + f dt)/m with conditions at t_new, a = (v+ - v)/dt (the acceleration
/// includes the reaction of the conditions). Adds the conditions' impulse and work.
/// `constrain_old` also sets the conditions on v(1) before a is formed (Gong 2015 extraction A24:
/// the constrained components of v^{s-1/2}, a and v^{s+1/2} are all zero for a fixed node, so the
/// FLIP increment sees no boundary reaction).
template <int D>
void update_grid_velocities(GridFields<D>& fields, double dt, double mass_floor, const VelocityConditions<D>& conditions,
                            double t_new, Vec<D>& impulse, double& work, bool constrain_old = false) {
  const auto n = static_cast<std::ptrdiff_t>(fields.mass.size());
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const double m = fields.mass[i];
    if (m > mass_floor) {
      fields.velocity[i] = fields.momentum[i] / m;
      fields.velocity_new[i] = (fields.momentum[i] + fields.force[i] * dt) / m;
    } else {
      fields.velocity[i].setZero();
      fields.velocity_new[i].setZero();
    }
  }
  conditions.apply(fields.velocity_new, t_new, &fields.mass, &impulse, &work);
  if (constrain_old) conditions.apply(fields.velocity, t_new);
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
  for (std::ptrdiff_t i = 0; i < n; ++i) fields.acceleration[i] = (fields.velocity_new[i] - fields.velocity[i]) / dt;
}

}  // namespace matpoint
