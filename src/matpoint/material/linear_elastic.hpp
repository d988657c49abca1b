// Linear elasticity at finite strain: the St Venant-Kirchhoff solid (Holzapfel 2000 §6.5; Bonet &
// Wood 2008 §6.4), whose stress is linear in the Green-Lagrange strain:
//   E = (F^T F - I) / 2,  S = lambda tr(E) I + 2 mu E,  sigma = F S F^T / J,  W = S : E / 2
// Why this definition: sigma is symmetric, frame invariant and the exact derivative of W
// (J sigma : L = dW/dt), so the discrete energy balance closes, and it is Hooke's law at small
// strain. Measured in examples/two-disks (energy error with MUSL / XPIC(4) USL, smallest det F):
//   previous model sigma = C : sym(F - I) F^T / J (asymmetric)   0.19 % /  7.7 % / 0.50
//   St Venant-Kirchhoff (this)                                   0.18 % /  9.2 % / 0.28
//   Hooke as Cauchy stress, sigma = C : sym(F - I)                2.2 %  /  9.2 % / 0.49
//   Hencky, tau = C : ln(B)/2 (the plastic models' elasticity)    0.20 % / 14.7 % / 0.59
// Hooke as Cauchy stress has no stored energy (2.2 % > the 1 % bound), Hencky dissipated twice as
// much with XPIC (above Hammerquist & Nairn's tenfold-below-PIC bound). Caveat: St Venant-Kirchhoff
// softens in strong compression (its uniaxial stress peaks at a stretch of 1/sqrt(3); the contact
// particles of the two disks reach det F = 0.28): use neo_hookean for large compression.
// 2-D is plane strain: E_zz = 0, so sigma_zz = lambda tr(E) / J (nu (sigma_xx + sigma_yy) at small
// strain). 1-D is a bar in uniaxial stress, sigma = E_Young (F - 1) (wave speed sqrt(E / rho)), a
// 1 x 1 stress with energy E (F - 1)^2 / 2.
#pragma once

#include <cmath>

#include "matpoint/core/types.hpp"

namespace matpoint {

struct LinearElastic {
  double density, youngs_modulus, lambda, mu;

  /// Green-Lagrange strain (D >= 2); the engineering strain F - 1 of the bar (D = 1).
  template <int D>
  [[nodiscard]] Mat<D> strain(const Mat<D>& F) const {
    if constexpr (D == 1) return F - Mat<D>::Identity();
    return 0.5 * (F.transpose() * F - Mat<D>::Identity());
  }
  /// Second Piola-Kirchhoff stress S = C : E (D >= 2); the bar's stress E eps (D = 1).
  template <int D>
  [[nodiscard]] Mat<D> second_piola_stress(const Mat<D>& F) const {
    const Mat<D> E = strain(F);
    if constexpr (D == 1) return youngs_modulus * E;
    return lambda * E.trace() * Mat<D>::Identity() + 2.0 * mu * E;
  }
  /// Cauchy stress sigma = F S F^T / J, and its out-of-plane component in plane strain.
  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& F, double& sigma_zz) const {
    if constexpr (D == 1) {
      sigma_zz = 0.0;
      return second_piola_stress(F);
    } else {
      const double J = F.determinant();
      const Mat<D> E = strain(F);
      sigma_zz = D == 2 ? lambda * E.trace() / J : 0.0;
      return F * (lambda * E.trace() * Mat<D>::Identity() + 2.0 * mu * E) * F.transpose() / J;
    }
  }
  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& F) const {
    double zz;
    return stress<D>(F, zz);
  }
  /// Strain energy per unit initial volume, S : E / 2.
  template <int D>
  [[nodiscard]] double energy_density(const Mat<D>& F) const {
    return 0.5 * second_piola_stress(F).cwiseProduct(strain(F)).sum();
  }
  template <int D>
  [[nodiscard]] double wave_speed() const {
    return D == 1 ? std::sqrt(youngs_modulus / density) : std::sqrt((lambda + 2.0 * mu) / density);
  }
};

}  // namespace matpoint
