// The material models a simulation can use, and the batched stress update over particles.
// Adding a model: a struct with stress<D>, energy_density<D>, wave_speed<D> in this folder, one
// alternative in Material, one case in make_material. stress<D>(F, sigma_zz) returns the Cauchy
// stress and sets its out-of-plane component (kept for plane strain). A model with history declares
// `state_size` and takes its state (stress<D>(F, q, state, sigma_zz), energy_density<D>(F, state)).
// The plastic models (hencky_plasticity.hpp) are HenckyPlastic<Yield>: a principal-space return
// map `Yield` in the shared finite-strain frame.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "matpoint/io/spec.hpp"
#include "matpoint/material/artificial_viscosity.hpp"
#include "matpoint/material/drucker_prager.hpp"
#include "matpoint/material/linear_elastic.hpp"
#include "matpoint/material/mie_gruneisen.hpp"
#include "matpoint/material/mohr_coulomb.hpp"
#include "matpoint/material/neo_hookean.hpp"
#include "matpoint/material/rigid.hpp"
#include "matpoint/material/von_mises.hpp"
#include "matpoint/particles/particle_set.hpp"

namespace matpoint {

using Material =
    std::variant<LinearElastic, NeoHookean, MieGruneisen, Rigid, MohrCoulomb, DruckerPrager, VonMises>;

Material make_material(const MaterialSpec& spec);

/// History values per particle a model needs (0 for the elastic models).
int state_size(const Material& m);

/// Sets the particles' state layout for these materials: state_stride (the largest state_size)
/// and which materials use the plastic layout (ParticleSet::plastic_material).
template <int D>
void set_state_layout(const std::vector<Material>& materials, ParticleSet<D>& particles);

/// The names of those values (the model's `state_names`, else state0, state1, ...): the
/// component names of the .vtu `state` array.
std::vector<std::string> state_names(const Material& m);

template <int D>
double wave_speed(const Material& m) {
  return std::visit([](const auto& model) { return model.template wave_speed<D>(); }, m);
}

/// Initial geostatic stress for the bodies that ask for it (BodySpec::geostatic): at height h
/// (the last coordinate), sigma_v = -rho g (surface - h) (0 above the surface), the horizontal
/// normal stresses k0 sigma_v, no shear. Held by the plastic state at F = I: C_p^-1 = b_e =
/// exp(2 D^-1 tau0) (hencky_plasticity.hpp). Call before the first stress update. Throws InputError
/// when gravity is not along -(last axis).
template <int D>
void set_geostatic_stress(const std::vector<Material>& materials, const std::vector<BodySpec>& bodies,
                          const Triple& gravity, ParticleSet<D>& particles);

/// sigma_p = sigma(F_p) - q_p I (and sigma_zz in 2-D) for every particle (q_p: artificial viscosity from L_p,
/// zero when `av` is inactive). The model is chosen once per material, not per particle. Returns the index of
/// the first particle with det F <= 0 or a non-finite stress, or -1. dt: the step, for rate-dependent
/// yield stresses (Johnson-Cook; 0: rate terms off). F is advanced before, by its own pass
/// (explicit/deformation.hpp): fused into this loop it measured 9-10 % slower on bench-2d (session 17).
template <int D>
long update_stress(const std::vector<Material>& materials, ParticleSet<D>& particles,
                   const ArtificialViscosity& av = {}, double dt = 0.0);

/// Sum over particles of V0_p W(F_p).
template <int D>
double strain_energy(const std::vector<Material>& materials, const ParticleSet<D>& particles, int body = -1);

/// Sum over the particles of plastic materials of V0_p times their plastic work per unit reference
/// volume (material/hencky_plasticity.hpp, state [kPlasticWork]): the energy the return maps removed.
template <int D>
double plastic_work(const ParticleSet<D>& particles);

}  // namespace matpoint
