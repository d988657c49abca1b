// NeoHookean's stress (neo_hookean.hpp) for kLanes particles at once: the same operations per
// lane, so bitwise the scalar result (core/lanes.hpp). The stress pass of neo-Hookean runs uses it
// (material.cpp); its cost is arithmetic (the divisions, square roots and the log), which the
// lanes share (bench/README.md "Session 30").
#pragma once

#include <cmath>

#include "matpoint/core/lanes.hpp"
#include "matpoint/material/neo_hookean.hpp"

namespace matpoint {

/// ln J per lane with glibc's scalar log (a vector log would differ in the last bits).
[[nodiscard]] inline Lanes log_per_lane(const Lanes& J) {
  return Lanes([&](auto lane) { return std::log(static_cast<double>(J[lane])); });
}

/// NeoHookean::stress<D>(F, sigma_zz) of kLanes deformation gradients from their determinants J,
/// ln J (unused by half_j_squared) and B = F F^T: pressure_part I + mu / J (B - I).
template <int D>
[[nodiscard]] LaneMatrix<D> neo_hookean_stress_lanes(const NeoHookean& m, const Lanes& J, const Lanes& lnJ,
                                                     const LaneMatrix<D>& B, Lanes& sigma_zz) {
  const bool log_j = m.volumetric == NeoHookeanVolumetric::LogJ;
  const Lanes pressure_part = log_j ? m.lambda * lnJ / J : 0.5 * m.lambda * (J - 1.0 / J);
  sigma_zz = pressure_part;
  const Lanes shear = m.mu / J;
  LaneMatrix<D> sigma;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) {
      const double identity = i == j ? 1.0 : 0.0;
      sigma(i, j) = pressure_part * identity + shear * (B(i, j) - identity);
    }
  return sigma;
}

/// NeoHookean::stress_and_wave_speed<2>: the stress, sigma_zz and the wave speed c of kLanes 2-D
/// deformation gradients F with determinants J (the caller's, which tested J > 0).
[[nodiscard]] inline LaneMatrix<2> neo_hookean_stress_and_wave_speed_lanes(const NeoHookean& m,
                                                                           const LaneMatrix<2>& F,
                                                                           const Lanes& J, Lanes& sigma_zz,
                                                                           Lanes& c) {
  const bool log_j = m.volumetric == NeoHookeanVolumetric::LogJ;
  const Lanes lnJ = log_j ? log_per_lane(J) : Lanes(0.0);
  const LaneMatrix<2> B = F * F.transposed();
  const LaneMatrix<2> sigma = neo_hookean_stress_lanes<2>(m, J, lnJ, B, sigma_zz);
  // largest_symmetric_eigenvalue<2>: (a + c)/2 + sqrt(((a - c)/2)^2 + b^2)
  const Lanes mean = 0.5 * (B(0, 0) + B(1, 1)), half_difference = 0.5 * (B(0, 0) - B(1, 1));
  const Lanes b_max = mean + stdx::sqrt(half_difference * half_difference + B(1, 0) * B(1, 0));
  const Lanes volumetric_modulus = log_j ? m.lambda * (1.0 - lnJ) : 0.5 * m.lambda * (J * J + 1.0);
  const Lanes modulus = m.mu * (b_max + 1.0) + volumetric_modulus;
  Lanes clamped(0.0);
  stdx::where(Lanes(0.0) < modulus, clamped) = modulus;  // std::max(0.0, modulus)
  c = stdx::sqrt(clamped / m.density);
  return sigma;
}

}  // namespace matpoint
