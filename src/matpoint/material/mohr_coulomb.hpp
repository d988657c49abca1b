// Mohr-Coulomb plasticity at finite strain (Iaconeta et al. 2017 §7.2; extraction §7.2.2-7.2.4):
// the one-step closed-form return of Clausen, Damkilde & Andersen (2006, 2007) in principal
// Kirchhoff stress space, tension positive, tau_1 >= tau_2 >= tau_3:
//   f = k tau_1 - tau_3 - sigma_c,  k = (1 + sin phi)/(1 - sin phi),  sigma_c = 2 c cos phi/(1 - sin phi)
//   g = m tau_1 - tau_3,            m = (1 + sin psi)/(1 - sin psi)   (psi = phi: associated)
//   apex tau_apex = sigma_c/(k - 1) (1, 1, 1) = c cot phi (1, 1, 1)
// phi = 0 is Tresca (k = 1, sigma_c = 2 c: tau_1 - tau_3 <= 2 c, c the undrained shear strength):
// the two edge lines are then parallel to the hydrostatic axis and there is no apex.
// The return region (plane, edge tau_1 = tau_2, edge tau_2 = tau_3, apex) is chosen in closed form
// from the trial stress; each return is exact (no iteration), and its derivative is the consistent
// tangent in the principal frame (plane: D - D b a^T D / a^T D b; edge: r_l n^T D / n . r_l; apex: 0).
// Beyond the paper (perfectly plastic there): optional linear softening of c and phi with the
// equivalent plastic strain, from (c, phi) at 0 to (c_r, phi_r) at eps_s and constant after,
// evaluated at the start of the step (explicit in the hardening variable, so the return stays
// closed form). Equivalent plastic strain: the plastic multiplier |D eps_p| / |b| (extraction §7.2.3,
// ambiguity A12).
// Optional tension cut-off (beyond the paper; a Rankine limit tau_A <= sigma_t, 0 <= sigma_t < c cot phi,
// associated): when the pyramid's return (or an elastic trial) has tau_1 > sigma_t, the return is the
// multi-surface one over the three pyramid planes and the three cut-off planes
// (multisurface_return.hpp); the equivalent plastic strain grows by the same |D^-1 (tau^trial - tau)| /
// sqrt(1 + m^2) measure.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "matpoint/material/hencky_plasticity.hpp"
#include "matpoint/material/multisurface_return.hpp"

namespace matpoint {

struct MohrCoulombYield {
  double cohesion;        // c
  double friction_angle;  // phi (radians), 0 <= phi < pi/2 (0: Tresca)
  double dilation_angle;  // psi (radians), 0 <= psi <= phi
  double residual_cohesion = 0.0, residual_friction_angle = 0.0;
  double softening_strain = 0.0;                                    // eps_s; 0: no softening
  double tension_cutoff = std::numeric_limits<double>::infinity();  // sigma_t; infinite: none

  /// (c, phi) at equivalent plastic strain eps_p.
  [[nodiscard]] std::pair<double, double> strength(double eps_p) const {
    if (!(softening_strain > 0.0)) return {cohesion, friction_angle};
    const double s = std::min(eps_p / softening_strain, 1.0);
    return {cohesion + s * (residual_cohesion - cohesion),
            friction_angle + s * (residual_friction_angle - friction_angle)};
  }
  /// The apex c cot(phi) (mean stress of the returned apex state; infinite for Tresca, phi = 0).
  [[nodiscard]] double apex(double eps_p = 0.0) const {
    const auto [c, phi] = strength(eps_p);
    return c / std::tan(phi);
  }
  /// f(tau) for sorted principal stresses.
  [[nodiscard]] double yield_function(const Vec3& tau, double eps_p = 0.0) const {
    const auto [c, phi] = strength(eps_p);
    const double s = std::sin(phi);
    return (1.0 + s) / (1.0 - s) * tau[0] - tau[2] - 2.0 * c * std::cos(phi) / (1.0 - s);
  }

  [[nodiscard]] PrincipalReturn return_map(const HenckyElasticity& elastic, const Vec3& trial, double eps_p,
                                           double /*dt: rate-independent*/ = 0.0) const {
    const auto [c, phi] = strength(eps_p);
    const double sp = std::sin(phi), spsi = std::sin(dilation_angle);
    const double k = (1.0 + sp) / (1.0 - sp), m = (1.0 + spsi) / (1.0 - spsi);
    const double sigma_c = 2.0 * c * std::cos(phi) / (1.0 - sp);
    const Mat3 D = elastic.matrix();
    PrincipalReturn r{trial, D, 0.0, YieldState::Elastic};
    const double f = k * trial[0] - trial[2] - sigma_c;
    if (!(f > 0.0)) return with_tension_cutoff(r, elastic, trial, k, m, sigma_c);

    const Vec3 a(k, 0.0, -1.0), b(m, 0.0, -1.0);
    const Vec3 r_p = D * b / a.dot(D * b);  // plane corrector
    // Secondary planes f2 = k tau_2 - tau_3 - sigma_c, f3 = k tau_1 - tau_2 - sigma_c and their correctors.
    const Vec3 a2(0.0, k, -1.0), b2(0.0, m, -1.0), a3(k, -1.0, 0.0), b3(m, -1.0, 0.0);
    const Vec3 r_p2 = D * b2 / a2.dot(D * b2), r_p3 = D * b3 / a3.dot(D * b3);
    const Vec3 r_l1(1.0, 1.0, k), r_l2(1.0, k, k);  // edge directions tau_1 = tau_2, tau_2 = tau_3
    // A point of each edge line: the apex where both meet (phi > 0), or for Tresca (k = 1, no apex)
    // (0, 0, -sigma_c) on tau_1 = tau_2 and (sigma_c, 0, 0) on tau_2 = tau_3.
    const bool has_apex = k > 1.0;
    const Vec3 apex = Vec3::Constant(has_apex ? sigma_c / (k - 1.0) : 0.0);
    const Vec3 e1 = has_apex ? apex : Vec3(0.0, 0.0, -sigma_c);
    const Vec3 e2 = has_apex ? apex : Vec3(sigma_c, 0.0, 0.0);
    const Vec3 n_12 = r_p.cross(r_l1), n_13 = r_p.cross(r_l2);
    const Vec3 n2 = r_p.cross(r_p2), n3 = r_p.cross(r_p3);
    const Vec3 d1 = trial - e1, d2 = trial - e2;
    const double t1 = n2.dot(d1) / n2.dot(r_l1), t2 = n3.dot(d2) / n3.dot(r_l2);

    // The extraction's "apex if t1 > 0 or t2 > 0" sends some trial states of the edge-1 region to
    // the apex (t2 > 0 there means nothing); the brute-force closest-point test found it. An edge
    // return goes to the apex when its own parameter passes it (equivalently: t1 > 0 and t2 > 0).
    if (n_12.dot(d1) < 0.0) {
      r.state = has_apex && t1 > 0.0 ? YieldState::Apex : YieldState::Edge;
      r.tau = e1 + (has_apex ? std::min(t1, 0.0) : t1) * r_l1;
      r.tangent = r_l1 * (D * n2).transpose() / n2.dot(r_l1);
    } else if (n_13.dot(d2) <= 0.0) {
      r.state = YieldState::Surface;
      r.tau = trial - f * r_p;
      r.tangent = D - (D * b) * (D * a).transpose() / a.dot(D * b);
    } else {
      r.state = has_apex && t2 > 0.0 ? YieldState::Apex : YieldState::Edge;
      r.tau = e2 + (has_apex ? std::min(t2, 0.0) : t2) * r_l2;
      r.tangent = r_l2 * (D * n3).transpose() / n3.dot(r_l2);
    }
    if (r.state == YieldState::Apex) r.tangent.setZero();
    r.plastic_strain_increment = elastic.strain(trial - r.tau).norm() / std::sqrt(1.0 + m * m);
    return with_tension_cutoff(r, elastic, trial, k, m, sigma_c);
  }

  /// The pyramid's return r, or the multi-surface return with the cut-off planes when r (or the
  /// elastic trial) has tau_1 > sigma_t.
  [[nodiscard]] PrincipalReturn with_tension_cutoff(const PrincipalReturn& r, const HenckyElasticity& elastic,
                                                    const Vec3& trial, double k, double m,
                                                    double sigma_c) const {
    if (!(r.tau[0] > tension_cutoff * (1.0 + 1e-12))) return r;
    const YieldPlane planes[6] = {
        {Vec3(k, 0, -1), sigma_c, Vec3(m, 0, -1)},      {Vec3(0, k, -1), sigma_c, Vec3(0, m, -1)},
        {Vec3(k, -1, 0), sigma_c, Vec3(m, -1, 0)},      {Vec3(1, 0, 0), tension_cutoff, Vec3(1, 0, 0)},
        {Vec3(0, 1, 0), tension_cutoff, Vec3(0, 1, 0)}, {Vec3(0, 0, 1), tension_cutoff, Vec3(0, 0, 1)}};
    PrincipalReturn out = multisurface_return(elastic, planes, trial, sigma_c + tension_cutoff);
    out.plastic_strain_increment = elastic.strain(trial - out.tau).norm() / std::sqrt(1.0 + m * m);
    return out;
  }
};

using MohrCoulomb = HenckyPlastic<MohrCoulombYield>;

}  // namespace matpoint
