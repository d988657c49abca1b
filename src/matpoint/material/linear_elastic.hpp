// Small-strain isotropic linear elasticity, written as the hyperelastic potential
//   W(F) = 1/2 eps : C : eps,  eps = sym(F) - I,  C : eps = lambda tr(eps) I + 2 mu eps,
// so that its first Piola-Kirchhoff stress is P = C : eps and the Cauchy stress is P F^T / J.
// Using P (not C : eps as a Cauchy stress) keeps the discrete energy balance exact in the limit of
// small time steps at the moderate strains of the two-disk test; for small strains the two agree.
// In 1-D the model is a bar in uniaxial stress, P = E eps (wave speed sqrt(E / rho)); 2-D is plane
// strain.
#pragma once

#include "matpoint/core/types.hpp"

#include <cmath>

namespace matpoint {

struct LinearElastic {
  double density, youngs_modulus, lambda, mu;

  template <int D> [[nodiscard]] Mat<D> strain(const Mat<D>& F) const {
    return 0.5 * (F + F.transpose()) - Mat<D>::Identity();
  }
  /// P = C : eps (symmetric).
  template <int D> [[nodiscard]] Mat<D> piola_stress(const Mat<D>& F) const {
    const Mat<D> eps = strain(F);
    if constexpr (D == 1) return youngs_modulus * eps;
    return lambda * eps.trace() * Mat<D>::Identity() + 2.0 * mu * eps;
  }
  /// Cauchy stress sigma = P F^T / J.
  template <int D> [[nodiscard]] Mat<D> stress(const Mat<D>& F) const {
    return piola_stress(F) * F.transpose() / F.determinant();
  }
  /// Strain energy per unit initial volume, 1/2 P : eps.
  template <int D> [[nodiscard]] double energy_density(const Mat<D>& F) const {
    return 0.5 * piola_stress(F).cwiseProduct(strain(F)).sum();
  }
  template <int D> [[nodiscard]] double wave_speed() const {
    return D == 1 ? std::sqrt(youngs_modulus / density) : std::sqrt((lambda + 2.0 * mu) / density);
  }
};

}  // namespace matpoint
