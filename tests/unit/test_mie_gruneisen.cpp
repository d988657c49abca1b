// Mie-Grueneisen nickel (material/mie_gruneisen.hpp) and the artificial viscosity: the
// Rankine-Hugoniot plateau of Nairn 2026 §3.2.1, the Hugoniot energy jump of a single update, the
// energy bookkeeping over a loading path, and the viscosity formula.
#include <gtest/gtest.h>

#include <cmath>

#include "matpoint/material/material.hpp"

namespace {

using namespace matpoint;

// Extraction nairn-2026-fmpm.md A11: rho0 = 8870 kg/m^3, C0 = 4600 m/s, S = 1.44, Gamma0 = 1.93.
const MieGruneisen kNickel{8870.0, 4600.0, 1.44, 1.93, 0.0};
constexpr double kWallSpeed = 1840.0;  // Nairn 2026 §3.2.1: the wall, 40 % of C0

TEST(MieGruneisen, RankineHugoniotPlateauIsThePapers118Point3GPa) {
  // The material behind the shock moves with the wall: u_p = 1840 m/s, U_s = C0 + S u_p.
  const double us = 4600.0 + 1.44 * kWallSpeed;
  EXPECT_DOUBLE_EQ(kNickel.shock_speed(kWallSpeed), us);
  EXPECT_NEAR(us, 7249.6, 1e-9);
  // p = rho0 U_s u_p (momentum jump): Nairn 2026 §3.2.1 "pressure 118.3 GPa" (to its 4 digits).
  EXPECT_NEAR(kNickel.hugoniot_pressure(kWallSpeed), 118.3e9, 0.05e9);
  // The EOS holds that state: at eta = u_p / U_s (mass jump) with the Hugoniot energy
  // e_H = p_H eta / (2 rho0) = u_p^2 / 2 (energy jump) it gives the same pressure.
  const double eta = kWallSpeed / us, e_h = 0.5 * kWallSpeed * kWallSpeed;
  EXPECT_NEAR(kNickel.pressure(eta, e_h), kNickel.hugoniot_pressure(kWallSpeed), 1e-9 * 118.3e9);
}

TEST(MieGruneisen, OneUpdateToTheShockedStateLandsOnTheHugoniot) {
  // A single jump from rest: the trapezoidal energy update is the Rankine-Hugoniot energy jump,
  // so the stress is -p_H exactly and e = u_p^2 / 2.
  const double eta = kWallSpeed / kNickel.shock_speed(kWallSpeed);
  double state[2] = {0.0, 0.0};
  Mat<2> F = Mat<2>::Identity();
  F(0, 0) = 1.0 - eta;  // uniaxial strain
  const Mat<2> sigma = kNickel.stress<2>(F, 0.0, state);
  EXPECT_NEAR(-sigma(0, 0), kNickel.hugoniot_pressure(kWallSpeed), 1e-9 * 118.3e9);
  EXPECT_NEAR(-sigma(1, 1), -sigma(0, 0), 1e-9 * 118.3e9);  // no strength: isotropic
  EXPECT_NEAR(state[0], 0.5 * kWallSpeed * kWallSpeed, 1e-9 * kWallSpeed * kWallSpeed);
  EXPECT_DOUBLE_EQ(state[1], eta);
}

TEST(MieGruneisen, EnergyIsTheWorkOfTheStressAlongAPath) {
  // With shear and artificial-viscosity heat: sum over small steps of -(p + q) dv + dev work equals
  // the change of energy_density / rho0 (second order in the step).
  const MieGruneisen nickel{8870.0, 4600.0, 1.44, 1.93, 76e9};
  double state[2] = {0.0, 0.0};
  const int steps = 2000;
  double work = 0.0;  // per unit initial volume
  Mat<2> F = Mat<2>::Identity(), sigma = Mat<2>::Zero();
  const double q = 1e9;  // a constant viscous pressure while compressing
  for (int k = 1; k <= steps; ++k) {
    const double s = static_cast<double>(k) / steps;
    Mat<2> next;
    next << 1.0 - 0.2 * s, 0.1 * s, 0.0, 1.0 - 0.05 * s;
    const Mat<2> sigma_next = nickel.stress<2>(next, q, state);
    // P : dF with P = J sigma F^-T, trapezoidal in time
    const Mat<2> dF = next - F;
    auto power = [&](const Mat<2>& G, const Mat<2>& sg) {
      return (G.determinant() * sg * G.inverse().transpose()).cwiseProduct(dF).sum();
    };
    work += 0.5 * (power(F, sigma) + power(next, sigma_next));
    F = next;
    sigma = sigma_next;
  }
  const double energy = nickel.energy_density<2>(F, state);
  EXPECT_NEAR(energy, work, 1e-5 * std::abs(work));
  EXPECT_GT(energy, 0.0);
}

TEST(MieGruneisen, StateSizeAndWaveSpeed) {
  EXPECT_EQ(state_size(Material{kNickel}), 2);
  EXPECT_EQ(state_size(Material{NeoHookean{1.0, 1.0, 1.0}}), 0);
  EXPECT_DOUBLE_EQ(kNickel.wave_speed<2>(), 4600.0);  // bulk speed without shear
  const MieGruneisen strong{8870.0, 4600.0, 1.44, 1.93, 76e9};
  EXPECT_NEAR(strong.wave_speed<2>(), std::sqrt(4600.0 * 4600.0 + 4.0 * 76e9 / (3.0 * 8870.0)), 1e-9);
}

TEST(ArtificialViscosity, LinearAndQuadraticOnlyInCompression) {
  const ArtificialViscosity av{0.2, 2.0, 0.25e-3};
  // q = rho h |D_kk| (A1 c + A2 h |D_kk|) (von Neumann-Richtmyer; NairnMPM's form)
  const double rho = 9000.0, rate = -1e6, c = 4600.0, h = 0.25e-3;
  EXPECT_NEAR(av.pressure(rho, rate, c), rho * h * 1e6 * (0.2 * c + 2.0 * h * 1e6), 1e-6);
  EXPECT_EQ(av.pressure(rho, 1e6, c), 0.0);
  EXPECT_EQ(av.pressure(rho, 0.0, c), 0.0);
  EXPECT_FALSE(ArtificialViscosity{}.active());
}

}  // namespace
