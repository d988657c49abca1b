// J2 (von Mises) plasticity with linear isotropic hardening at finite strain (Hencky frame,
// hencky_plasticity.hpp; Simo 1992, de Souza Neto, Peric & Owen 2008 Box 7.4 and §14.5):
//   f = q - (sigma_y + H eps_p),  q = sqrt(3 J2) = sqrt(3/2) |s|   (s = dev tau, Kirchhoff)
//   radial return: dgamma = f^trial / (3 G + H),  s = (1 - 3 G dgamma / q^trial) s^trial,  p = p^trial
//   eps_p <- eps_p + dgamma  (= sqrt(2/3) |Delta eps_p|)
// Consistent tangent in the principal frame (d tau / d eps^trial):
//   K 1 (x) 1 + 2 G (1 - 3 G dgamma / q) P_dev - s^trial (x) d(3 G dgamma / q)/d eps,
//   d q / d eps = 3 G s^trial / q,  d dgamma / d eps = (d q / d eps) / (3 G + H).
// In log strain and Kirchhoff stress, a monotone uniaxial test is exactly bilinear: tau = E eps up to
// sigma_y, then slope E H / (E + H).
#pragma once

#include <cmath>

#include "matpoint/material/hencky_plasticity.hpp"

namespace matpoint {

struct VonMisesYield {
  double yield_stress;       // sigma_y (initial)
  double hardening_modulus;  // H >= 0 (linear isotropic hardening)

  [[nodiscard]] double flow_stress(double eps_p) const { return yield_stress + hardening_modulus * eps_p; }
  [[nodiscard]] double yield_function(const Vec3& tau, double eps_p = 0.0) const {
    return std::sqrt(1.5) * (tau.array() - tau.mean()).matrix().norm() - flow_stress(eps_p);
  }

  [[nodiscard]] PrincipalReturn return_map(const HenckyElasticity& elastic, const Vec3& trial,
                                           double eps_p) const {
    const double G = elastic.mu, K = elastic.bulk_modulus(), H = hardening_modulus;
    PrincipalReturn r{trial, elastic.matrix(), 0.0, YieldState::Elastic};
    const double p = trial.mean();
    const Vec3 s = (trial.array() - p).matrix();
    const double q = std::sqrt(1.5) * s.norm();
    const double f = q - flow_stress(eps_p);
    if (!(f > 0.0)) return r;
    const double dgamma = f / (3.0 * G + H);
    const double scale = 1.0 - 3.0 * G * dgamma / q;
    r.state = YieldState::Surface;
    r.tau = Vec3::Constant(p) + scale * s;
    r.plastic_strain_increment = dgamma;
    const Vec3 one = Vec3::Ones();
    const Vec3 dq = 3.0 * G / q * s;
    const Vec3 dscale = -3.0 * G * (dq / ((3.0 * G + H) * q) - dgamma / (q * q) * dq);
    const Mat3 P = Mat3::Identity() - one * one.transpose() / 3.0;
    r.tangent = K * one * one.transpose() + 2.0 * G * scale * P + s * dscale.transpose();
    return r;
  }
};

using VonMises = HenckyPlastic<VonMisesYield>;

}  // namespace matpoint
