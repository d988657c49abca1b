// The largest wave speed of the particles' present states, for the explicit time step of Nairn
// 2026 §1.8, dt = C dx / max_p max(c_p, |V_p|). A model with a state-dependent speed provides
// wave_speed_at<D>(F[, state]); the others have one speed, wave_speed<D>().
#pragma once

#include <algorithm>
#include <vector>

#include "matpoint/material/material.hpp"

namespace matpoint {

template <int D>
double max_current_wave_speed(const std::vector<Material>& materials, const ParticleSet<D>& particles) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  const auto stride = static_cast<std::ptrdiff_t>(particles.state_stride);
  double fastest = 0.0;
  for (std::size_t m = 0; m < materials.size(); ++m)
    std::visit(
        [&](const auto& model) {
          using Model = std::decay_t<decltype(model)>;
          if constexpr (requires { model.template wave_speed_at<D>(Mat<D>{}, nullptr); }) {
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(max : fastest)
            for (std::ptrdiff_t p = 0; p < n; ++p)
              if (particles.material[p] == static_cast<int>(m))
                fastest = std::max(fastest, model.template wave_speed_at<D>(particles.F[p], &particles.state[p * stride]));
          } else if constexpr (requires { model.template wave_speed_at<D>(Mat<D>{}); }) {
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(max : fastest)
            for (std::ptrdiff_t p = 0; p < n; ++p)
              if (particles.material[p] == static_cast<int>(m))
                fastest = std::max(fastest, model.template wave_speed_at<D>(particles.F[p]));
          } else {
            (void)sizeof(Model);
            fastest = std::max(fastest, model.template wave_speed<D>());
          }
        },
        materials[m]);
  return fastest;
}

}  // namespace matpoint
