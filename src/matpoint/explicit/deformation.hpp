// Deformation gradient update (Nairn 2026 §2.1 task 5): F <- dF F with dF = exp(L dt) or I + L dt.
// Its own pass before update_stress (material.hpp): fused into the stress loop it was slower.
// The exponential runs on kLanes particles at once (core/deformation_increment_lanes.hpp: bitwise
// the scalar result; bench/README.md "Session 30").
#pragma once

#include "matpoint/core/deformation_increment.hpp"
#include "matpoint/core/deformation_increment_lanes.hpp"
#include "matpoint/io/spec.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

template <int D>
void update_deformation(ParticleSet<D>& particles, double dt, DeformationUpdate mode) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  const bool exponential = mode == DeformationUpdate::Exponential;
  particles.recorded_wave_speed = -1.0;  // F changes: the next update_stress records it again
  auto advance = [&](std::ptrdiff_t p) {
    particles.F[p] = advanced_deformation<D>(particles.F[p], particles.L[p], dt, exponential);
  };
  const std::ptrdiff_t batches = exponential ? n / kLanes : 0;
#pragma omp parallel for schedule(static) if (n > kParallelMinimum)
  for (std::ptrdiff_t b = 0; b < batches; ++b) {
    const std::ptrdiff_t first = b * kLanes;
    if (!advance_deformation_lanes<D>(&particles.F[first], &particles.L[first], dt))
      for (std::ptrdiff_t p = first; p < first + kLanes; ++p) advance(p);
  }
  const std::ptrdiff_t rest = batches * kLanes;  // the remainder, or all of the first-order update
#pragma omp parallel for schedule(static) if (n - rest > kParallelMinimum)
  for (std::ptrdiff_t p = rest; p < n; ++p) advance(p);
}

}  // namespace matpoint
