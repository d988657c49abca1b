// Whole-body quantities recorded at output times: energies, linear momentum, extreme Jacobians.
// In a decomposed run (sim.comm.distributed()) each rank holds only its own particles: the raw
// sums are reduced over the ranks (docs/scale-out.md §7) and every rank gets the same values.
#pragma once

#include <limits>
#include <vector>

#include "matpoint/explicit/simulation.hpp"

namespace matpoint {

template <int D> struct Diagnostics {
  double kinetic_energy = 0.0;  // 1/2 sum M_p |V_p|^2
  double strain_energy = 0.0;   // sum V0_p W(F_p)
  Vec<D> momentum = Vec<D>::Zero();
  double min_jacobian = 1.0, max_jacobian = 1.0;
  double rms_velocity_change = 0.0;  // sqrt(mean_p |V_p - V_p(0)|^2)
  double plastic_work = 0.0;         // plastic_work() of every particle
  std::vector<double> body_kinetic, body_strain, body_mass;
  std::vector<Vec<D>> body_momentum;
  std::vector<Vec<D>> body_com_position;  // sum M_p X_p / sum M_p
};

/// Over every rank's particles: a collective in a decomposed run (every rank calls it).
template <int D> Diagnostics<D> measure_diagnostics(const Simulation<D>& sim, int body_count);

}  // namespace matpoint
