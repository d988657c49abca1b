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

inline constexpr std::array<ParticleFieldInfo, 17> kParticleFields{{
    {"velocity", "particle velocity"},
    {"displacement", "displacement u = x - X from the initial position"},
    {"stress", "Cauchy stress (3 x 3; in 2-D with the plane-strain sigma_zz)"},
    {"deformation_gradient", "deformation gradient F"},
    {"strain", "Green-Lagrange strain E = (F^T F - I) / 2"},
    {"jacobian", "det F"},
    {"mass", "particle mass"},
    {"volume", "current particle volume"},
    {"material", "material index (position in materials)"},
    {"body", "body index (position in bodies)"},
    {"id", "particle number"},
    {"state", "material history variables, where the model has any (components: docs/output.md)"},
    {"pressure", "-tr(sigma) / 3 of the 3 x 3 Cauchy stress (compression positive)"},
    {"von_mises", "von Mises stress sqrt(3/2 s : s), s = dev(sigma) of the 3 x 3 Cauchy stress"},
    {"plastic_strain", "equivalent plastic strain (plastic materials; 0 elsewhere)"},
    {"yield_state", "return of the last stress update: 0 elastic, 1 surface, 2 edge, 3 apex"},
    {"temperature", "particle temperature (runs with a \"heat\" section only)"},
}};

[[nodiscard]] constexpr bool is_particle_field(std::string_view name) {
  for (const auto& f : kParticleFields)
    if (f.name == name) return true;
  return false;
}

}  // namespace matpoint
