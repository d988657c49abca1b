// Mie-Grueneisen solid for shock waves (Nairn 2026 §3.2.1; extraction §6.2 and A11): a Us-up
// Hugoniot as the reference curve, Grueneisen's rho Gamma = rho0 Gamma0, and an optional
// neo-Hookean deviatoric (shear) part:
//   eta = 1 - J,  p_H(eta) = rho0 C0^2 eta / (1 - S eta)^2   (eta >= 0; rho0 C0^2 eta in tension)
//   p(J, e) = p_H (1 - Gamma0 eta / 2) + Gamma0 rho0 e        (e: internal energy per unit mass)
//   sigma   = -p I + G / J dev(J^(-2/3) B)                    (B = F F^T, plane strain F_zz = 1)
// The Hugoniot follows from Rankine-Hugoniot with U_s = C0 + S u_p: p_H = rho0 U_s u_p at
// eta = u_p / U_s. e is history: each stress update integrates de = -(p + q) dv with the
// trapezoidal rule on p (solved exactly, p is linear in e) and the artificial viscosity q of the
// step (material/artificial_viscosity.hpp), dv = (J_new - J_old) / rho0. The trapezoidal rule is
// the Rankine-Hugoniot energy jump e = (p0 + p1)(v0 - v1) / 2 for a single jump.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "matpoint/core/types.hpp"

namespace matpoint {

struct MieGruneisen {
  double density;           // rho0
  double bulk_sound_speed;  // C0
  double hugoniot_slope;    // S in U_s = C0 + S u_p
  double gruneisen;         // Gamma0
  double shear_modulus;     // G (0: a fluid, no strength)

  /// History per particle: specific internal energy e and eta = 1 - J of the last update.
  static constexpr int state_size = 2;
  static constexpr std::array<const char*, 2> state_names{"e", "eta"};  // .vtu `state` components

  /// The reference part p_H (1 - Gamma0 eta / 2) of the pressure.
  [[nodiscard]] double reference_pressure(double eta) const {
    const double k = density * bulk_sound_speed * bulk_sound_speed;
    const double compression = eta > 0 ? 1.0 - hugoniot_slope * eta : 1.0;
    return k * eta * (1.0 - 0.5 * gruneisen * eta) / (compression * compression);
  }
  [[nodiscard]] double pressure(double eta, double e) const {
    return reference_pressure(eta) + gruneisen * density * e;
  }
  /// Rankine-Hugoniot state behind a steady shock driven at particle speed u_p into material at rest.
  [[nodiscard]] double shock_speed(double particle_speed) const {
    return bulk_sound_speed + hugoniot_slope * particle_speed;
  }
  [[nodiscard]] double hugoniot_pressure(double particle_speed) const {
    return density * shock_speed(particle_speed) * particle_speed;
  }

  /// Cauchy stress at F with the artificial viscosity q of this step; advances state = {e, eta}.
  /// sigma_zz: the out-of-plane component in plane strain, -p - q + G J^(-5/3) (1 - tr B / 3).
  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& F, double q, double* state, double& sigma_zz) const {
    const double J = F.determinant();
    const double eta = 1.0 - J, eta_old = state[1], e_old = state[0];
    const double dv = (eta_old - eta) / density;  // change of specific volume
    const double p_old = pressure(eta_old, e_old);
    const double reference = reference_pressure(eta);
    const double e =
        (e_old - 0.5 * (p_old + reference) * dv - q * dv) / (1.0 + 0.5 * gruneisen * density * dv);
    state[0] = e;
    state[1] = eta;
    const double pressure_q = reference + gruneisen * density * e + q;
    sigma_zz = -pressure_q + deviatoric_zz<D>(F, J);
    return -pressure_q * Mat<D>::Identity() + deviatoric<D>(F, J);
  }
  template <int D>
  [[nodiscard]] Mat<D> stress(const Mat<D>& F, double q, double* state) const {
    double zz;
    return stress<D>(F, q, state, zz);
  }
  /// Energy per unit initial volume: rho0 e (volumetric and heat) + G/2 (tr Bbar - 3).
  template <int D>
  [[nodiscard]] double energy_density(const Mat<D>& F, const double* state) const {
    const double J = F.determinant();
    const double trB3 =
        (F * F.transpose()).trace() + (3 - D);  // plane strain / uniaxial strain: F = 1 outside
    return density * state[0] + 0.5 * shear_modulus * (std::pow(J, -2.0 / 3.0) * trB3 - 3.0);
  }
  /// Small-strain dilatational speed sqrt(C0^2 + 4 G / (3 rho0)) (C0^2 = K / rho0).
  template <int D>
  [[nodiscard]] double wave_speed() const {
    return std::sqrt(bulk_sound_speed * bulk_sound_speed + 4.0 * shear_modulus / (3.0 * density));
  }
  /// The sound speed of the present state (the time step of a shocked body, Nairn 2026 §1.8):
  /// the isentropic bulk speed c_B^2 = dp/drho|_s = J^2 / rho0 (dp_ref/deta + Gamma0 p), from
  /// rho = rho0 / J, dp/dv|_s = dp/dv - p dp/de and dp/de = Gamma0 rho0, plus the shear part
  /// 4 G / (3 rho) with rho = rho0 / J. At rest both give wave_speed().
  template <int D>
  [[nodiscard]] double wave_speed_at(const Mat<D>& F, const double* state) const {
    const double J = F.determinant(), eta = 1.0 - J;
    const double k = density * bulk_sound_speed * bulk_sound_speed;
    double slope = k * (1.0 - gruneisen * eta);  // dp_ref/deta in tension (eta <= 0)
    if (eta > 0) {
      const double c = 1.0 - hugoniot_slope * eta;
      slope = k * ((1.0 - gruneisen * eta) * c + 2.0 * hugoniot_slope * eta * (1.0 - 0.5 * gruneisen * eta)) /
              (c * c * c);
    }
    const double bulk = J * J / density * (slope + gruneisen * pressure(eta, state[0]));
    return std::sqrt(std::max(0.0, bulk) + 4.0 * shear_modulus * J / (3.0 * density));
  }

 private:
  template <int D>
  [[nodiscard]] Mat<D> deviatoric(const Mat<D>& F, double J) const {
    if (shear_modulus == 0.0) return Mat<D>::Zero();
    const Mat<D> B = F * F.transpose();
    const double trB3 = B.trace() + (3 - D);
    return shear_modulus * std::pow(J, -5.0 / 3.0) * (B - trB3 / 3.0 * Mat<D>::Identity());
  }
  /// The zz component of the deviatoric part when F_zz = 1 (B_zz = 1).
  template <int D>
  [[nodiscard]] double deviatoric_zz(const Mat<D>& F, double J) const {
    if (shear_modulus == 0.0) return 0.0;
    const double trB3 = (F * F.transpose()).trace() + (3 - D);
    return shear_modulus * std::pow(J, -5.0 / 3.0) * (1.0 - trB3 / 3.0);
  }
};

}  // namespace matpoint
