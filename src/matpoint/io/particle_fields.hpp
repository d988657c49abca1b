// Names of the particle fields that output.fields may list (written to particles_NNNNNN.vtu).
// docs/input.md's table of them is generated from this one (scripts/check_input_reference.py).
#pragma once

#include <array>
#include <string_view>

namespace matpoint {

struct ParticleFieldInfo {
  std::string_view name;
  std::string_view content;
};

inline constexpr std::array<ParticleFieldInfo, 13> kParticleFields{{
    {"velocity", "particle velocity"},
    {"displacement", "displacement u = x - X from the initial position"},
    {"stress", "Cauchy stress"},
    {"pressure", "pressure p = -tr(sigma) / 3"},
    {"deformation_gradient", "deformation gradient F"},
    {"strain", "Green-Lagrange strain E = (F^T F - I) / 2"},
    {"jacobian", "det F"},
    {"mass", "particle mass"},
    {"volume", "current particle volume"},
    {"material", "material index (position in materials)"},
    {"body", "body index (position in bodies)"},
    {"id", "particle number"},
    {"state", "material history variables, where the model has any (components: docs/output.md)"},
}};

[[nodiscard]] constexpr bool is_particle_field(std::string_view name) {
  for (const auto& f : kParticleFields)
    if (f.name == name) return true;
  return false;
}

}  // namespace matpoint
