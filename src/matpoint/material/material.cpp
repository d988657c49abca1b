#include "matpoint/material/material.hpp"

#include <cmath>
#include <type_traits>

namespace matpoint {

Material make_material(const MaterialSpec& spec) {
  switch (spec.model) {
    case MaterialModel::NeoHookean:
      return NeoHookean{spec.density, spec.lambda, spec.mu, spec.volumetric};
    case MaterialModel::MieGruneisen:
      return MieGruneisen{spec.density, spec.bulk_sound_speed, spec.hugoniot_slope, spec.gruneisen, spec.mu};
    case MaterialModel::Rigid:
      return Rigid{spec.density};
    case MaterialModel::LinearElastic:
      break;
  }
  return LinearElastic{spec.density, spec.youngs_modulus, spec.lambda, spec.mu};
}

int state_size(const Material& m) {
  return std::visit(
      [](const auto& model) {
        if constexpr (requires { std::decay_t<decltype(model)>::state_size; })
          return std::decay_t<decltype(model)>::state_size;
        return 0;
      },
      m);
}

std::vector<std::string> state_names(const Material& m) {
  return std::visit(
      [](const auto& model) {
        using Model = std::decay_t<decltype(model)>;
        std::vector<std::string> names;
        if constexpr (requires { Model::state_names; })
          for (const auto& name : Model::state_names) names.emplace_back(name);
        int size = 0;
        if constexpr (requires { Model::state_size; }) size = Model::state_size;
        for (int i = static_cast<int>(names.size()); i < size; ++i)
          names.push_back("state" + std::to_string(i));
        return names;
      },
      m);
}

template <int D>
long update_stress(const std::vector<Material>& materials, ParticleSet<D>& particles,
                   const ArtificialViscosity& av) {
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  const auto stride = static_cast<std::ptrdiff_t>(particles.state_stride);
  long first_bad = -1;
  for (std::size_t m = 0; m < materials.size(); ++m) {
    std::visit(
        [&](const auto& model) {
          using Model = std::decay_t<decltype(model)>;
          const double c = model.template wave_speed<D>();
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(max : first_bad)
          for (std::ptrdiff_t p = 0; p < n; ++p) {
            if (particles.material[p] != static_cast<int>(m)) continue;
            const Mat<D>& F = particles.F[p];
            const double J = F.determinant();
            if (!(J > 0.0)) {
              first_bad = std::max(first_bad, static_cast<long>(n - p));  // max of (n - p) = min p
              continue;
            }
            const double q = av.active() ? av.pressure(particles.mass[p] / (particles.volume0[p] * J),
                                                       particles.L[p].trace(), c)
                                         : 0.0;
            if constexpr (requires { Model::state_size; })
              particles.stress[p] = model.template stress<D>(F, q, &particles.state[p * stride]);
            else
              particles.stress[p] = model.template stress<D>(F) - q * Mat<D>::Identity();
            if (!particles.stress[p].allFinite()) first_bad = std::max(first_bad, static_cast<long>(n - p));
          }
        },
        materials[m]);
  }
  return first_bad < 0 ? -1 : n - first_bad;
}

template <int D>
double strain_energy(const std::vector<Material>& materials, const ParticleSet<D>& particles, int body) {
  const auto stride = static_cast<std::ptrdiff_t>(particles.state_stride);
  double energy = 0.0;
  const auto n = static_cast<std::ptrdiff_t>(particles.size());
  for (std::size_t m = 0; m < materials.size(); ++m) {
    std::visit(
        [&](const auto& model) {
#pragma omp parallel for schedule(static) if (n > kParallelMinimum) reduction(+ : energy)
          for (std::ptrdiff_t p = 0; p < n; ++p) {
            if (particles.material[p] != static_cast<int>(m) || (body >= 0 && particles.body[p] != body))
              continue;
            if constexpr (requires { std::decay_t<decltype(model)>::state_size; })
              energy += particles.volume0[p] *
                        model.template energy_density<D>(particles.F[p], &particles.state[p * stride]);
            else
              energy += particles.volume0[p] * model.template energy_density<D>(particles.F[p]);
          }
        },
        materials[m]);
  }
  return energy;
}

template long update_stress<1>(const std::vector<Material>&, ParticleSet<1>&, const ArtificialViscosity&);
template long update_stress<2>(const std::vector<Material>&, ParticleSet<2>&, const ArtificialViscosity&);
template long update_stress<3>(const std::vector<Material>&, ParticleSet<3>&, const ArtificialViscosity&);
template double strain_energy<1>(const std::vector<Material>&, const ParticleSet<1>&, int);
template double strain_energy<2>(const std::vector<Material>&, const ParticleSet<2>&, int);
template double strain_energy<3>(const std::vector<Material>&, const ParticleSet<3>&, int);

}  // namespace matpoint
