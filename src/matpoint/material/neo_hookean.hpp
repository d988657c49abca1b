// Compressible neo-Hookean solid in the two forms the papers use:
//   log_j:          sigma = lambda ln J / J I + mu / J (B - I)       Gong 2015 eq. (4.5), Iaconeta 2017
//   half_j_squared: sigma = lambda / 2 (J - 1/J) I + mu / J (B - I)  Nairn 2026 eq. (14)
// B = F F^T. 2-D is plane strain (F_zz = 1), 1-D is uniaxial strain (F = diag(F11, 1, 1)), so the
// formulas hold with D x D matrices and J = det F; in plane strain sigma_zz = the volumetric part
// (lambda ln J / J, or lambda/2 (J - 1/J)), since B_zz = 1.
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "matpoint/core/types.hpp"
#include "matpoint/io/spec.hpp"

namespace matpoint {

/// The largest eigenvalue of a symmetric D x D matrix (its lower triangle is read). In 2-D the
/// closed form (a + c)/2 + sqrt(((a - c)/2)^2 + b^2), which costs about a tenth of Eigen's
/// computeDirect (measured 5-9 ns against 40-80 ns; the per-particle wave speed of every step's
/// time step is its hot use); in 3-D Eigen's direct (trigonometric) solver.
template <int D>
double largest_symmetric_eigenvalue(const Mat<D>& B) {
  if constexpr (D == 1) {
    return B(0, 0);
  } else if constexpr (D == 2) {
    const double mean = 0.5 * (B(0, 0) + B(1, 1)), half_difference = 0.5 * (B(0, 0) - B(1, 1));
    return mean + std::sqrt(half_difference * half_difference + B(1, 0) * B(1, 0));
  } else {
    return Eigen::SelfAdjointEigenSolver<Mat<D>>()
        .computeDirect(B, Eigen::EigenvaluesOnly)
        .eigenvalues()
        .maxCoeff();
  }
}

struct NeoHookean {
  double density, lambda, mu;
  NeoHookeanVolumetric volumetric = NeoHookeanVolumetric::LogJ;

  /// Cauchy stress at F, and sigma_zz = the volumetric part (B_zz = 1 in plane strain).
  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& F, double& sigma_zz) const {
    const double J = F.determinant();
    const double pressure_part =
        volumetric == NeoHookeanVolumetric::LogJ ? lambda * std::log(J) / J : 0.5 * lambda * (J - 1.0 / J);
    sigma_zz = pressure_part;
    return pressure_part * Mat<D>::Identity() + (mu / J) * (F * F.transpose() - Mat<D>::Identity());
  }
  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& F) const {
    double zz;
    return stress<D>(F, zz);
  }
  /// stress<D>(F, sigma_zz), and c = wave_speed_at<D>(F), with J, ln J and B computed once: the
  /// stress update's pass records the time step's wave speed (material.cpp). The same operations
  /// in the same order as the two functions (the build does not contract into FMAs), so both
  /// results are bitwise those of the separate calls.
  template <int D>
  [[nodiscard]] Mat<D> stress_and_wave_speed(const Mat<D>& F, double& sigma_zz, double& c) const {
    const double J = F.determinant();
    const bool log_j = volumetric == NeoHookeanVolumetric::LogJ;
    const double lnJ = log_j ? std::log(J) : 0.0;
    const double pressure_part = log_j ? lambda * lnJ / J : 0.5 * lambda * (J - 1.0 / J);
    sigma_zz = pressure_part;
    const Mat<D> B = F * F.transpose();
    const double b_max = largest_symmetric_eigenvalue<D>(B);
    const double volumetric_modulus = log_j ? lambda * (1.0 - lnJ) : 0.5 * lambda * (J * J + 1.0);
    c = std::sqrt(std::max(0.0, mu * (b_max + 1.0) + volumetric_modulus) / density);
    return pressure_part * Mat<D>::Identity() + (mu / J) * (B - Mat<D>::Identity());
  }
  /// Kirchhoff stress tau = J sigma at F for any scalar type S (double, or a dual number of the
  /// implicit solver's automatic differentiation):
  ///   log_j:          tau = lambda ln J I + mu (B - I)    (Aulisa & Capodaglio eq. (12) times J, the
  ///                                                       consistent form of their eq. (23))
  ///   half_j_squared: tau = lambda / 2 (J^2 - 1) I + mu (B - I)
  /// 2-D is plane strain (F_zz = 1, so J = det of the in-plane F). stress() above is unchanged.
  template <class S, int D>
  [[nodiscard]] Eigen::Matrix<S, D, D> kirchhoff_stress(const Eigen::Matrix<S, D, D>& F) const {
    using std::log;
    const S J = F.determinant();
    const S volumetric_part =
        volumetric == NeoHookeanVolumetric::LogJ ? S(lambda * log(J)) : S(0.5 * lambda * (J * J - 1.0));
    Eigen::Matrix<S, D, D> tau = mu * (F * F.transpose());
    for (int a = 0; a < D; ++a) tau(a, a) += volumetric_part - mu;
    return tau;
  }
  /// Stored energy per unit initial volume: mu/2 (tr C - D) - mu ln J + U(J), where
  /// U = lambda/2 (ln J)^2 (log_j) or lambda/2 ((J^2 - 1)/2 - ln J) (half_j_squared).
  template <int D>
  [[nodiscard]] double energy_density(const Mat<D>& F) const {
    const double J = F.determinant();
    const double lnJ = std::log(J);
    const double U = volumetric == NeoHookeanVolumetric::LogJ ? 0.5 * lambda * lnJ * lnJ
                                                              : 0.5 * lambda * (0.5 * (J * J - 1.0) - lnJ);
    return 0.5 * mu * ((F.transpose() * F).trace() - D) - mu * lnJ + U;
  }
  /// Small-strain dilatational wave speed sqrt((lambda + 2 mu) / rho).
  template <int D>
  [[nodiscard]] double wave_speed() const {
    return std::sqrt((lambda + 2.0 * mu) / density);
  }
  /// The fastest longitudinal wave at F (the time step of a deformed body, Nairn 2026 §1.8): the
  /// acoustic tensor of W = mu/2 (tr C - 3) - mu ln J + U(J) along a unit spatial direction n has
  /// the longitudinal value (mu (n.B n + 1) / J + J U''), so with rho = rho0 / J
  ///   c^2 = (mu (b_max + 1) + J^2 U''(J)) / rho0,  b_max the largest eigenvalue of B,
  /// J^2 U'' = lambda (1 - ln J) (log_j) or lambda (J^2 + 1) / 2 (half_j_squared); at F = I both
  /// give (lambda + 2 mu) / rho0.
  template <int D>
  [[nodiscard]] double wave_speed_at(const Mat<D>& F) const {
    const double J = F.determinant();
    const Mat<D> B = F * F.transpose();
    // Waves run only along the simulated directions: the in-plane (2-D) or axial (1-D) B.
    const double b_max = largest_symmetric_eigenvalue<D>(B);
    const double volumetric_modulus = volumetric == NeoHookeanVolumetric::LogJ ? lambda * (1.0 - std::log(J))
                                                                               : 0.5 * lambda * (J * J + 1.0);
    return std::sqrt(std::max(0.0, mu * (b_max + 1.0) + volumetric_modulus) / density);
  }
};

}  // namespace matpoint
