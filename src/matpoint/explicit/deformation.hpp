// Deformation gradient update (Nairn 2026 §2.1 task 5): F <- dF F with dF = exp(L dt) or I + L dt.
// Its own pass before update_stress (material.hpp): fused into the stress loop it was slower.
#pragma once

#include "matpoint/core/deformation_increment.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

template <int D>
void update_deformation(ParticleSet<D>& particles, double dt, DeformationUpdate mode) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  const bool exponential = mode == DeformationUpdate::Exponential;
  particles.recorded_wave_speed = -1.0;  // F changes: the next update_stress records it again
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
  for (std::ptrdiff_t p = 0; p < n; ++p)
    particles.F[p] = advanced_deformation<D>(particles.F[p], particles.L[p], dt, exponential);
}

}  // namespace matpoint
