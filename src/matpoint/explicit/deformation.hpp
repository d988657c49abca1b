// Deformation gradient update (Nairn 2026 §2.1 task 5): F <- dF F with dF = exp(L dt) or I + L dt.
#pragma once

#include "matpoint/core/matrix_exponential.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

template <int D> void update_deformation(ParticleSet<D>& particles, double dt, DeformationUpdate mode) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  particles.recorded_wave_speed = -1.0;  // F changes: the next update_stress records it again
  if (mode == DeformationUpdate::Exponential) {
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p) particles.F[p] = matrix_exponential<D>(particles.L[p] * dt) * particles.F[p];
  } else {
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
    for (std::ptrdiff_t p = 0; p < n; ++p)
      particles.F[p] = (Mat<D>::Identity() + particles.L[p] * dt) * particles.F[p];
  }
}

}  // namespace matpoint
