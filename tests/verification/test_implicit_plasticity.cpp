// The plastic models through the implicit solver (Iaconeta et al. 2017 §7.2 materials in the
// updated-Lagrangian implicit MPM of §4.1, static analysis, Newton with the consistent tangent of
// material/plastic_tangent.hpp):
//   - unconfined plane-strain compression of a Mohr-Coulomb block between smooth platens (the
//     paper's soil: c = 5 kPa, phi = 25 deg, E = 1.8 MPa, nu = 0.3, extraction §7.2.5): once the
//     block yields, sigma_1 = sigma_xx = 0 (free side) and sigma_3 = sigma_yy, so the Kirchhoff
//     stress must sit at tau_yy = -sigma_c = -2 c cos(phi) / (1 - sin(phi)) = -15.6969 kPa (the
//     unconfined strength of §7.2.2); with psi = 0 the plastic flow keeps the volume (det C_p^-1 = 1),
//     with psi = phi the plastic strains follow the associated flow direction (m, 0, -1),
//     m = (1 + sin psi) / (1 - sin psi), so eps_p,xx / -eps_p,yy = m and eps_p,zz = 0;
//   - the same block in J2 (perfectly plastic): plane-strain flow at sigma_xx = 0 tends to
//     sigma_zz = sigma_yy / 2, so sqrt(3 J2) = sigma_y gives tau_yy -> -2 sigma_y / sqrt(3) (held to 1e-6 at
//     20 % strain: the transient dies out within a few yield strains);
//   - Drucker-Prager with the plane-strain match and associated flow collapses at Mohr-Coulomb's
//     plane-strain load (de Souza Neto et al. 2008 §6.4.1): tau_yy -> -sigma_c;
//   - Newton converges quadratically on a block between rough platens (non-uniform plastic zones).
// The deformation of the first three is uniform, which Q4 elements represent exactly: the stresses
// are the material point's, to the Newton tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "matpoint/implicit/implicit_mpm_solver.hpp"
#include "matpoint/io/input.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace matpoint {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCohesion = 5e3, kPhi = 25 * kPi / 180;
const double kSigmaC = 2 * kCohesion * std::cos(kPhi) / (1 - std::sin(kPhi));  // 15.6969 kPa

/// A 1 x 1 m block on a cells x cells Q4 mesh, 4 material points per cell at the Gauss points,
/// compressed from the top at 0.01 m/s for `end_time` s in static steps of 0.1 s; `rough`: the
/// platens hold x too (fixed bottom, top moving in y and held in x).
Spec block_spec(const std::string& material, int cells, double end_time, bool rough) {
  const std::string n = std::to_string(cells);
  const std::string bottom = rough ? R"({"type": "fixed", "boundary": "bottom"})"
                                   : R"({"type": "slip", "boundary": "bottom", "normal": "y"},
                                        {"type": "slip", "boundary": "left", "normal": "x"})";
  const std::string top_velocity = rough ? "[0, -0.01]" : "[null, -0.01]";
  return parse_spec(R"({
    "title": "implicit plastic block",
    "mesh": {"element": "q4", "min": [0, 0], "max": [1, 1], "cells": [)" +
                    n + ", " + n + R"(]},
    "materials": [)" +
                    material + R"(],
    "bodies": [{"material": "soil", "shape": {"type": "box", "min": [0, 0], "max": [1, 1]},
                "placement": "gauss", "particles_per_cell": 2}],
    "boundary_conditions": [)" +
                    bottom + R"(,
      {"type": "velocity", "boundary": "top", "velocity": )" +
                    top_velocity + R"(}],
    "solver": {"type": "implicit_ul", "dt": 0.1, "end_time": )" +
                    std::to_string(end_time) + R"(,
               "implicit": {"analysis": "static",
                            "newton": {"increment_tolerance": 1e-12, "residual_tolerance": 1e-12}}},
    "output": {"every_time": 100}
  })");
}

std::string mohr_coulomb(double psi_degrees) {
  return R"({"name": "soil", "model": "mohr_coulomb", "density": 1850, "E": 1.8e6, "nu": 0.3,
             "cohesion": 5000, "friction_angle": 25, "dilation_angle": )" +
         std::to_string(psi_degrees) + "}";
}

/// Runs the block; returns the solver for inspection.
template <class Check>
void run_block(const Spec& spec, int cells, Check&& check) {
  implicit::ImplicitMpmSolver<mesh::Q4> solver(
      spec, mesh::structured_rectangle(mesh::ElementShape::Q4, mesh::AxisSpacing::uniform(0, 1, cells),
                                       mesh::AxisSpacing::uniform(0, 1, cells)));
  while (solver.sim().time < spec.solver.end_time - 1e-9) solver.step(solver.time_step());
  check(solver);
}

/// Kirchhoff stress tau = J sigma of particle p (2 x 2) and its tau_zz.
Mat<2> kirchhoff(const ParticleSet<2>& particles, std::size_t p) {
  return particles.F[p].determinant() * particles.stress[p];
}

TEST(ImplicitPlasticity, MohrCoulombBlockYieldsAtTheUnconfinedStrength) {
  for (const double psi : {0.0, 25.0}) {
    const Spec spec = block_spec(mohr_coulomb(psi), 2, 3.0, false);  // 3 % strain: yield at about 0.8 %
    run_block(spec, 2, [&](auto& solver) {
      const ParticleSet<2>& particles = solver.sim().particles;
      const double m = (1 + std::sin(psi * kPi / 180)) / (1 - std::sin(psi * kPi / 180));
      for (std::size_t p = 0; p < particles.size(); ++p) {
        const Mat<2> tau = kirchhoff(particles, p);
        EXPECT_NEAR(tau(1, 1), -kSigmaC, 1e-8 * kSigmaC) << "psi " << psi << " particle " << p;
        EXPECT_NEAR(tau(0, 0), 0.0, 1e-8 * kSigmaC);
        const double* state = &particles.state[p * static_cast<std::size_t>(particles.state_stride)];
        EXPECT_EQ(state[kYieldState], static_cast<double>(YieldState::Surface));
        const Mat3 Cp_inv = plastic_metric(state);
        const double eps_xx = -0.5 * std::log(Cp_inv(0, 0)), eps_yy = -0.5 * std::log(Cp_inv(1, 1)),
                     eps_zz = -0.5 * std::log(Cp_inv(2, 2));
        EXPECT_GT(-eps_yy, 5e-3);  // it has flowed
        EXPECT_NEAR(eps_xx / -eps_yy, m, 1e-8) << "psi " << psi;
        EXPECT_NEAR(eps_zz, 0.0, 1e-12);
        if (psi == 0.0) {
          EXPECT_NEAR(Cp_inv.determinant(), 1.0, 1e-12);
        }
        if (p == 0)
          std::printf("MC psi = %g: tau_yy = %.6f kPa (-sigma_c = %.6f), eps_p xx/-yy = %.9f (m = %.9f)\n",
                      psi, tau(1, 1) / 1e3, -kSigmaC / 1e3, eps_xx / -eps_yy, m);
      }
    });
  }
}

TEST(ImplicitPlasticity, PlaneStrainFlowOfJ2AndMatchedDruckerPragerTendsToTheAnalyticLimit) {
  struct Case {
    std::string material;
    double limit;     // tau_yy at steady plane-strain flow
    double end_time;  // s: strain / 1 %; the dilating DP block must stay inside the 1 x 1 mesh
    const char* name;
  };
  const double sigma_y = 1e4;
  const Case cases[] = {
      {R"({"name": "soil", "model": "von_mises", "density": 1850, "E": 1.8e6, "nu": 0.3, "yield_stress": 1e4})",
       -2 * sigma_y / std::sqrt(3.0), 20.0, "J2"},
      {R"({"name": "soil", "model": "drucker_prager", "density": 1850, "E": 1.8e6, "nu": 0.3, "cohesion": 5000,
           "friction_angle": 25, "dilation_angle": 25, "match": "plane_strain"})",
       -kSigmaC, 10.0, "DP plane-strain match"}};
  for (const Case& c : cases) {
    const Spec spec = block_spec(c.material, 1, c.end_time, false);
    run_block(spec, 1, [&](auto& solver) {
      const Mat<2> tau = kirchhoff(solver.sim().particles, 0);
      std::printf("%s: tau_yy = %.6f kPa at %g %% strain, steady-flow limit %.6f kPa\n", c.name,
                  tau(1, 1) / 1e3, c.end_time, c.limit / 1e3);
      EXPECT_NEAR(tau(1, 1), c.limit, 1e-6 * std::abs(c.limit)) << c.name;
      EXPECT_NEAR(tau(0, 0), 0.0, 1e-8 * std::abs(c.limit)) << c.name;
    });
  }
}

// Newton with the consistent tangent converges quadratically in plastic steps: on a block between
// rough platens (plastic zones spreading from the corners) every step converges, and in the last
// iterations of each step |R_{k+1}| / |R_k|^2 does not grow by more than 10 from one iteration to the
// next (a linearly converging Newton, e.g. with the elastic tangent, has it grow by 1/q per
// iteration, here > 100); iterations near round-off (below 1e-10 of the first residual) are left out.
TEST(ImplicitPlasticity, NewtonConvergesQuadraticallyInPlasticSteps) {
  const Spec spec = block_spec(mohr_coulomb(0.0), 4, 2.0, true);
  implicit::ImplicitMpmSolver<mesh::Q4> solver(
      spec, mesh::structured_rectangle(mesh::ElementShape::Q4, mesh::AxisSpacing::uniform(0, 1, 4),
                                       mesh::AxisSpacing::uniform(0, 1, 4)));
  int plastic_steps = 0;
  while (solver.sim().time < spec.solver.end_time - 1e-9) {
    solver.step(solver.time_step());
    const auto& history = solver.last_newton().history;
    ASSERT_TRUE(solver.last_newton().converged());
    const ParticleSet<2>& particles = solver.sim().particles;
    bool plastic = false;
    for (std::size_t p = 0; p < particles.size(); ++p)
      plastic =
          plastic || particles.state[p * static_cast<std::size_t>(particles.state_stride) + kYieldState] > 0;
    if (!plastic) continue;
    ++plastic_steps;
    std::printf("step %ld residuals:", solver.sim().step);
    for (const auto& it : history) std::printf(" %.3e", it.residual_norm);
    std::printf("\n");
    const double floor = 1e-10 * history.front().residual_norm;
    double previous_c = 0.0;
    for (std::size_t k = 1; k + 1 < history.size(); ++k) {
      const double r0 = history[k].residual_norm, r1 = history[k + 1].residual_norm;
      if (r1 < floor) break;
      const double c = r1 / (r0 * r0);
      if (previous_c > 0.0) {
        EXPECT_LT(c, 10 * previous_c) << "step " << solver.sim().step << " iteration " << k;
      }
      previous_c = c;
    }
  }
  EXPECT_GT(plastic_steps, 5);
}

}  // namespace
}  // namespace matpoint
