// Linear elasticity at finite strain, written as Hencky's model (Hencky 1928; Bonet & Wood 2008
// §6.6; de Souza Neto, Peric & Owen 2008 §13.2.2): Hooke's law between the logarithmic strain
// and the Kirchhoff stress,
//   eps = 1/2 ln B (B = F F^T),  tau = lambda tr(eps) I + 2 mu eps,  sigma = tau / J,
//   W = lambda/2 (tr eps)^2 + mu eps : eps   (per unit initial volume)
// Why this definition (and not sigma = C : sym(F - I), nor St Venant-Kirchhoff):
// - sigma is symmetric and is the exact derivative of W (J sigma : L = dW/dt), so the discrete
//   energy balance closes as with the other hyperelastic models; Hooke on sym(F - I) has no stored
//   energy (the balance would not close) and is stressed by a rigid rotation;
// - St Venant-Kirchhoff (sigma = F S F^T / J, S = C : E) is also exact, but softens in compression
//   (its uniaxial stress peaks at a stretch of 1/sqrt(3)): in examples/two-disks the contact
//   particles then reached det F = 0.28 against 0.50 here and with the previous model;
// - it is the elastic part of the plastic models (hencky_plasticity.hpp): a Mohr-Coulomb or J2
//   material that never yields is this material;
// - at small strain it is Hooke's law on the symmetric gradient.
// 2-D is plane strain: B_zz = 1, eps_zz = 0, so sigma_zz = lambda tr(eps) / J = nu (sigma_xx +
// sigma_yy), Hooke's plane-strain relation, at any strain. 1-D is a bar in uniaxial stress, sigma = E (F - 1) (wave speed
// sqrt(E / rho)), a 1 x 1 stress with energy E (F - 1)^2 / 2.
#pragma once

#include <Eigen/Eigenvalues>
#include <cmath>

#include "matpoint/core/types.hpp"

namespace matpoint {

struct LinearElastic {
  double density, youngs_modulus, lambda, mu;

  /// Principal logarithmic strains 1/2 ln(eig B) and the axes of B (D >= 2).
  template <int D>
  struct Principal {
    Vec<D> eps;
    Mat<D> axes;
  };
  template <int D>
  [[nodiscard]] static Principal<D> principal_strain(const Mat<D>& F) {
    Eigen::SelfAdjointEigenSolver<Mat<D>> eigen;
    if constexpr (D == 2)
      eigen.computeDirect(F * F.transpose());  // closed form for 2 x 2
    else
      eigen.compute(F * F.transpose());
    return {0.5 * eigen.eigenvalues().array().log().matrix(), eigen.eigenvectors()};
  }
  /// Cauchy stress sigma = tau / J, and its out-of-plane component in plane strain.
  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& F, double& sigma_zz) const {
    if constexpr (D == 1) {
      sigma_zz = 0.0;
      return youngs_modulus * (F - Mat<D>::Identity());
    } else {
      const double J = F.determinant();
      const auto [eps, axes] = principal_strain<D>(F);
      const double volumetric = lambda * eps.sum();
      sigma_zz = D == 2 ? volumetric / J : 0.0;
      const Vec<D> tau = Vec<D>::Constant(volumetric) + 2.0 * mu * eps;
      return axes * (tau / J).asDiagonal() * axes.transpose();
    }
  }
  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& F) const {
    double zz;
    return stress<D>(F, zz);
  }
  /// Strain energy per unit initial volume.
  template <int D>
  [[nodiscard]] double energy_density(const Mat<D>& F) const {
    if constexpr (D == 1) {
      return 0.5 * youngs_modulus * (F(0, 0) - 1.0) * (F(0, 0) - 1.0);
    } else {
      const Vec<D> eps = principal_strain<D>(F).eps;
      return 0.5 * lambda * eps.sum() * eps.sum() + mu * eps.squaredNorm();
    }
  }
  template <int D>
  [[nodiscard]] double wave_speed() const {
    return D == 1 ? std::sqrt(youngs_modulus / density) : std::sqrt((lambda + 2.0 * mu) / density);
  }
};

}  // namespace matpoint
