// Drucker-Prager plasticity at finite strain (Hencky frame, hencky_plasticity.hpp), tension positive,
// with p = tr(tau)/3 and s = dev(tau), J2 = s : s / 2 (de Souza Neto, Peric & Owen 2008 §8.3.3):
//   f = sqrt(J2) + eta p - xi c,   g = sqrt(J2) + eta_bar p
// matched to Mohr-Coulomb's (c, phi, psi) by one of (ibid. Table 6.1 / eq. 6.121-6.122):
//   outer (triaxial compression edges): eta = 6 sin phi / (sqrt3 (3 - sin phi)),  xi = 6 cos phi / (sqrt3 (3
//   - sin phi)) inner (triaxial extension edges):   eta = 6 sin phi / (sqrt3 (3 + sin phi)),  xi = 6 cos phi
//   / (sqrt3 (3 + sin phi)) plane strain (same collapse load):  eta = 3 tan phi / sqrt(9 + 12 tan^2 phi),  xi
//   = 3 / sqrt(9 + 12 tan^2 phi)
// eta_bar is eta's formula with psi. Return (perfect plasticity in the step; closed form):
//   cone: dgamma = f^trial / (G + K eta eta_bar),  s = (1 - G dgamma / sqrt(J2^trial)) s^trial,
//         p = p^trial - K eta_bar dgamma
//   apex, when sqrt(J2^trial) - G dgamma < 0: tau = xi c / eta (1, 1, 1), tangent 0.
// Beyond Iaconeta et al. 2017: optional linear softening of c, phi as in mohr_coulomb.hpp.
// Equivalent plastic strain: the multiplier |eps_p| / |dg/dtau| = |eps_p| / sqrt(1/2 + eta_bar^2 / 3).
#pragma once

#include <cmath>

#include "matpoint/io/spec.hpp"
#include "matpoint/material/hencky_plasticity.hpp"
#include "matpoint/material/mohr_coulomb.hpp"

namespace matpoint {

struct DruckerPragerYield {
  MohrCoulombYield strength_law;  // c, phi, psi and their softening
  DruckerPragerMatch match = DruckerPragerMatch::PlaneStrain;

  /// (eta, xi) for the friction angle `angle`.
  [[nodiscard]] std::pair<double, double> coefficients(double angle) const {
    const double s = std::sin(angle), root3 = std::sqrt(3.0);
    switch (match) {
      case DruckerPragerMatch::Outer:
        return {6.0 * s / (root3 * (3.0 - s)), 6.0 * std::cos(angle) / (root3 * (3.0 - s))};
      case DruckerPragerMatch::Inner:
        return {6.0 * s / (root3 * (3.0 + s)), 6.0 * std::cos(angle) / (root3 * (3.0 + s))};
      case DruckerPragerMatch::PlaneStrain:
        break;
    }
    const double t = std::tan(angle), root = std::sqrt(9.0 + 12.0 * t * t);
    return {3.0 * t / root, 3.0 / root};
  }
  [[nodiscard]] double yield_function(const Vec3& tau, double eps_p = 0.0) const {
    const auto [c, phi] = strength_law.strength(eps_p);
    const auto [eta, xi] = coefficients(phi);
    const double p = tau.mean();
    return std::sqrt(0.5 * (tau.array() - p).matrix().squaredNorm()) + eta * p - xi * c;
  }
  /// Mean stress of the apex, xi c / eta.
  [[nodiscard]] double apex(double eps_p = 0.0) const {
    const auto [c, phi] = strength_law.strength(eps_p);
    const auto [eta, xi] = coefficients(phi);
    return xi * c / eta;
  }

  [[nodiscard]] PrincipalReturn return_map(const HenckyElasticity& elastic, const Vec3& trial, double eps_p,
                                           double /*dt: rate-independent*/ = 0.0) const {
    const auto [c, phi] = strength_law.strength(eps_p);
    const auto [eta, xi] = coefficients(phi);
    const double eta_bar = coefficients(strength_law.dilation_angle).first;
    const double G = elastic.mu, K = elastic.bulk_modulus();
    PrincipalReturn r{trial, elastic.matrix(), 0.0, YieldState::Elastic};
    const double p = trial.mean();
    const Vec3 s = (trial.array() - p).matrix();
    const double rho = std::sqrt(0.5 * s.squaredNorm());  // sqrt(J2)
    const double f = rho + eta * p - xi * c;
    if (!(f > 0.0)) return r;
    const double dgamma = f / (G + K * eta * eta_bar);
    if (rho - G * dgamma >= 0.0) {
      r.state = YieldState::Surface;
      const double scale = 1.0 - G * dgamma / rho;
      r.tau = Vec3::Constant(p - K * eta_bar * dgamma) + scale * s;
      // d(dgamma)/d eps = (G s / rho + eta K 1) / (G + K eta eta_bar); d rho = G s / rho . d eps.
      const Vec3 one = Vec3::Ones();
      const Vec3 g = (G / rho * s + eta * K * one) / (G + K * eta * eta_bar);
      const Mat3 P = Mat3::Identity() - one * one.transpose() / 3.0;
      r.tangent = K * one * one.transpose() - K * eta_bar * one * g.transpose() + 2.0 * G * scale * P -
                  G / rho * s * g.transpose() + G * G * dgamma / (rho * rho * rho) * s * s.transpose();
    } else {
      r.state = YieldState::Apex;
      r.tau = Vec3::Constant(xi * c / eta);
      r.tangent.setZero();
    }
    r.plastic_strain_increment =
        elastic.strain(trial - r.tau).norm() / std::sqrt(0.5 + eta_bar * eta_bar / 3.0);
    return r;
  }
};

using DruckerPrager = HenckyPlastic<DruckerPragerYield>;

}  // namespace matpoint
