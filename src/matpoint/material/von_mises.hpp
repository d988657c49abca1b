// J2 (von Mises) plasticity with isotropic hardening at finite strain (Hencky frame,
// hencky_plasticity.hpp; Simo 1992, de Souza Neto, Peric & Owen 2008 Box 7.4 and §14.5):
//   f = q - sigma_f(eps_p, eps_p rate),  q = sqrt(3 J2) = sqrt(3/2) |s|   (s = dev tau, Kirchhoff)
//   radial return: q^trial - 3 G dgamma = sigma_f(eps_p + dgamma, dgamma / dt),
//   s = (1 - 3 G dgamma / q^trial) s^trial,  p = p^trial,  eps_p <- eps_p + dgamma  (= sqrt(2/3) |Delta
//   eps_p|)
// Flow stress: linear hardening sigma_y + H eps_p (dgamma = f^trial / (3 G + H) in closed form) or,
// beyond the papers, Johnson & Cook (1983) without the thermal term,
//   sigma_f = (sigma_y + B eps_p^n) (1 + C ln(max(eps_p rate / eps_0 rate, 1))),
// with eps_p rate = dgamma / dt (the rate term is off when dt = 0); dgamma then by a safeguarded
// Newton iteration on the monotone scalar equation, bracketed by [0, q^trial / (3 G)].
// Consistent tangent in the principal frame (d tau / d eps^trial), with H' = d sigma_f / d dgamma:
//   K 1 (x) 1 + 2 G (1 - 3 G dgamma / q) P_dev - s^trial (x) d(3 G dgamma / q)/d eps,
//   d q / d eps = 3 G s^trial / q,  d dgamma / d eps = (d q / d eps) / (3 G + H').
// In log strain and Kirchhoff stress, a monotone uniaxial test with linear hardening is exactly
// bilinear: tau = E eps up to sigma_y, then slope E H / (E + H).
#pragma once

#include <cmath>

#include "matpoint/material/hencky_plasticity.hpp"

namespace matpoint {

struct VonMisesYield {
  double yield_stress;       // sigma_y (initial; Johnson-Cook's A)
  double hardening_modulus;  // H >= 0 (linear isotropic hardening)
  // Johnson-Cook (beyond the papers; all zero: linear hardening only)
  double jc_b = 0.0, jc_n = 1.0;               // B eps_p^n
  double jc_c = 0.0, jc_reference_rate = 1.0;  // C ln(rate / reference rate)

  [[nodiscard]] bool johnson_cook() const { return jc_b != 0.0 || jc_c != 0.0; }

  /// The rate-free flow stress sigma_y + H eps_p + B eps_p^n.
  [[nodiscard]] double hardening(double eps_p) const {
    return yield_stress + hardening_modulus * eps_p + (jc_b != 0.0 ? jc_b * std::pow(eps_p, jc_n) : 0.0);
  }
  /// Its slope H + n B eps_p^(n - 1).
  [[nodiscard]] double hardening_slope(double eps_p) const {
    return hardening_modulus + (jc_b != 0.0 ? jc_b * jc_n * std::pow(eps_p, jc_n - 1.0) : 0.0);
  }
  /// sigma_f at plastic strain eps_p and plastic strain rate `rate` (rate terms off when rate <= 0).
  [[nodiscard]] double flow_stress(double eps_p, double rate = 0.0) const {
    return hardening(eps_p) * rate_factor(rate);
  }
  [[nodiscard]] double yield_function(const Vec3& tau, double eps_p = 0.0) const {
    return std::sqrt(1.5) * (tau.array() - tau.mean()).matrix().norm() - flow_stress(eps_p);
  }

  [[nodiscard]] PrincipalReturn return_map(const HenckyElasticity& elastic, const Vec3& trial, double eps_p,
                                           double dt = 0.0) const {
    const double G = elastic.mu, K = elastic.bulk_modulus();
    PrincipalReturn r{trial, elastic.matrix(), 0.0, YieldState::Elastic};
    const double p = trial.mean();
    const Vec3 s = (trial.array() - p).matrix();
    const double q = std::sqrt(1.5) * s.norm();
    const double f = q - flow_stress(eps_p);
    if (!(f > 0.0)) return r;
    double dgamma = f / (3.0 * G + hardening_modulus), H = hardening_modulus;
    if (johnson_cook()) dgamma = johnson_cook_increment(q, G, eps_p, dt, H);
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

  /// 1 + C ln(max(rate / reference, 1)).
  [[nodiscard]] double rate_factor(double rate) const {
    return jc_c != 0.0 && rate > jc_reference_rate ? 1.0 + jc_c * std::log(rate / jc_reference_rate) : 1.0;
  }

  /// dgamma solving q^trial - 3 G dgamma - sigma_f(eps_p + dgamma, dgamma / dt) = 0 (monotone
  /// decreasing in dgamma, positive at 0, negative at q^trial / (3 G)), and H' = d sigma_f / d dgamma there.
  [[nodiscard]] double johnson_cook_increment(double q, double G, double eps_p, double dt, double& H) const {
    const auto residual = [&](double g) {
      return q - 3.0 * G * g - flow_stress(eps_p + g, dt > 0.0 ? g / dt : 0.0);
    };
    const auto slope = [&](double g) {  // d sigma_f / d dgamma at g > 0
      const double e = eps_p + g, rate = dt > 0.0 ? g / dt : 0.0;
      const double d_rate = jc_c != 0.0 && rate > jc_reference_rate ? jc_c / g : 0.0;
      return hardening_slope(e) * rate_factor(rate) + hardening(e) * d_rate;
    };
    double low = 0.0, high = q / (3.0 * G), g = 0.5 * high;
    for (int iteration = 0; iteration < 100; ++iteration) {
      const double r = residual(g);
      if (r > 0.0)
        low = g;
      else
        high = g;
      const double d = 3.0 * G + slope(g);
      double next = g + r / d;
      if (!(next > low && next < high) || !std::isfinite(next)) next = 0.5 * (low + high);
      const bool done = std::abs(next - g) <= 1e-14 * g || high - low <= 1e-14 * high;
      g = next;
      if (done) break;
    }
    H = slope(g);
    return g;
  }
};

using VonMises = HenckyPlastic<VonMisesYield>;

}  // namespace matpoint
