// Names of the particle fields that output.fields may list (written to particles_NNNNNN.vtu).
#pragma once

#include <array>
#include <string_view>

namespace matpoint {

inline constexpr std::array<std::string_view, 11> kParticleFields{
    "velocity", "stress", "deformation_gradient", "strain", "jacobian", "mass",
    "volume",   "material", "body",               "id",     "state"};

[[nodiscard]] constexpr bool is_particle_field(std::string_view name) {
  for (auto f : kParticleFields)
    if (f == name) return true;
  return false;
}

}  // namespace matpoint
