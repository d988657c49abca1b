// Gong 2015's improved MPM (ch. 5) and improved CPDI (§6.6) on the manufactured solutions of
// §4.5-4.7 (extraction tests T7, T8, T11, T12 thresholds for improved CPDI) and the 2-D hourglass
// smoke test S4. Each check is the order the source claims with the margin kOrderMargin = 0.2
// ("expected 2, pass >= 1.8"); the orders are least-squares slopes over the listed meshes (2
// particles per cell per direction, T = 0.02). Velocity orders are reported, not checked (their
// 1.6 on 1/8 .. 1/64 is an open difference with Gong's "second order", docs/verification.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "matpoint/analysis/grid_modes.hpp"
#include "matpoint/analysis/verification.hpp"
#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace {

using namespace matpoint;

std::string report(const VerificationOutcome& o) {
  std::string s;
  for (const auto& r : o.runs)
    s += "h=1/" + std::to_string(r.cells) + " u " + std::to_string(r.displacement) + " s " +
         std::to_string(r.stress) + " rho " + std::to_string(r.density) + " v " + std::to_string(r.velocity) +
         " vg " + std::to_string(r.grid_velocity) + (r.finished ? "" : " " + r.message) + "\n";
  for (const auto& c : o.checks)
    s += (c.pass ? "PASS " : "FAIL ") + c.name + ": " + std::to_string(c.measured) + "\n";
  return s;
}

/// Runs a case of the built-in suite and expects every check to pass; returns the outcome.
VerificationOutcome expect_case_passes(VerificationCase c, std::size_t min_checks) {
  const auto o = run_case(c);
  EXPECT_GE(o.checks.size(), min_checks) << c.name;  // the thresholds did apply
  for (const auto& check : o.checks)
    EXPECT_TRUE(check.pass) << check.name << ": measured " << check.measured << " " << check.relation << " "
                            << check.expected << " (margin " << check.tolerance << ")"
                            << " [" << check.source << "]\n"
                            << report(o);
  return o;
}

// T7: 1-D IMPM, G = 0.1, h = 1/8 .. 1/64: stress, density, displacement expected 2 (Gong Fig. 5.6
// "second order"), pass >= 1.8, and E_stress(1/64) < 1e4 Pa (the extraction's independent
// reproduction: 7.48e3). MPM on the same problem does not converge (T6).
TEST(Impm, ManufacturedSolution1DLargeDeformationT7) {
  const auto o = expect_case_passes(make_case("mms-1d", ShapeKind::Linear, 0.1, false, Mapping::IMPM), 4);
  EXPECT_LT(o.runs.back().stress, 1e4);  // also a check of the case; kept here to name the claim
}

// T8: 1-D IMPM, G = 1e-4: as MPM's T5 (Gong Fig. 5.5): expected 2, >= 1.8 (stress, density,
// displacement).
TEST(Impm, ManufacturedSolution1DSmallDeformationT8) {
  expect_case_passes(make_case("mms-1d", ShapeKind::Linear, 1e-4, false, Mapping::IMPM), 3);
}

// T11 on coarse meshes (h = 1/8 .. 1/32 to keep the suite short; `matpoint verify --full` runs to
// 1/64): 2-D IMPM, G = 0.1: displacement, stress and density expected 2 (Gong Fig. 5.8 "close to
// second order"), pass >= 1.8.
TEST(Impm, ManufacturedSolution2DLargeDeformationT11) {
  expect_case_passes(make_case("mms-2d", ShapeKind::Linear, 0.1, false, Mapping::IMPM), 3);
}

// Improved CPDI (CPDI + the MLS velocity, Gong §6.6), 1-D, G = 0.1: expected 2 on h = 1/8 .. 1/64
// (Fig. 6.4, as CPDI in Fig. 6.1) and on 1/256 .. 1/512 (T14; `verify --full` runs to 1/2048).
TEST(ImprovedCpdi, ManufacturedSolution1DCoarse) {
  expect_case_passes(make_case("mms-1d", ShapeKind::CPDI1, 0.1, false, Mapping::MlsVelocity), 4);
}

/// S4: a 32 x 32 grid on [0, 1]^2, 2 x 2 particles per cell, the MMS material, roller walls, no
/// body force; v = (5 sin(pi x) sin(2 pi y), -5 sin(2 pi x) sin(pi y)) m/s plus 1e-2 m/s Gaussian
/// noise per particle and component; T = 0.2 s in 1600 steps (dt = 0.4 h / c).
Spec swirl_spec(Mapping mapping) {
  MmsOptions o;
  o.dim = 2;
  Spec spec = mms_spec(o, 32);
  spec.solver.mapping = mapping;
  spec.solver.constrain_old_velocity = false;
  spec.solver.end_time = 0.2;
  spec.solver.dt = 0.2 / 1600;
  return spec;
}

struct SwirlResult {
  double worst_ratio = 0.0;  // max over steps of checkerboard / rms grid velocity
  double final_rms = 0.0, final_checkerboard = 0.0;
  double momentum_difference = 0.0;  // |sum_i p_i - sum_p M_p V_p| at the last transfer
  double momentum_scale = 0.0;       // sum_p M_p |V_p|
};

SwirlResult run_swirl(Mapping mapping) {
  Simulation<2> sim = build_simulation<2>(swirl_spec(mapping));
  std::mt19937 rng(2015);
  std::normal_distribution<double> noise(0.0, 1e-2);
  using std::numbers::pi;
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    const double x = sim.particles.x[p][0], y = sim.particles.x[p][1];
    sim.particles.v[p] = Vec<2>(5 * std::sin(pi * x) * std::sin(2 * pi * y) + noise(rng),
                                -5 * std::sin(2 * pi * x) * std::sin(pi * y) + noise(rng));
  }
  ExplicitStepper<2, TensorStencils<2, LinearBasis>> stepper(sim);
  SwirlResult r;
  for (int n = 0; n < 1600; ++n) {
    stepper.step(*sim.solver.dt);
    const auto g = measure_grid_modes(sim.grid, sim.fields.mass, sim.fields.velocity_new);
    r.worst_ratio = std::max(r.worst_ratio, g.checkerboard_velocity / g.rms_velocity);
    r.final_rms = g.rms_velocity;
    r.final_checkerboard = g.checkerboard_velocity;
  }
  r.momentum_difference = sim.grid_momentum_difference.norm();
  for (std::size_t p = 0; p < sim.particles.size(); ++p)
    r.momentum_scale += sim.particles.mass[p] * sim.particles.v[p].norm();
  return r;
}

// S4 (extraction §10.3, informs A18): the mass-weighted checkerboard component of the grid
// velocity stays <= 1e-2 of the rms grid velocity throughout, for MPM and for IMPM (proto: <= 4.7e-4
// m/s against an rms of 0.9-3.5 m/s). The grid-momentum diagnostic (A19): zero to round-off for
// MPM (the partition of unity), not for IMPM's MLS velocity.
TEST(Impm, HourglassSmokeTestS4) {
  for (const Mapping mapping : {Mapping::MPM, Mapping::IMPM}) {
    const auto r = run_swirl(mapping);
    const char* name = mapping == Mapping::MPM ? "MPM" : "IMPM";
    std::printf(
        "S4 %s: max checkerboard / rms %.3e, final checkerboard %.3e m/s, rms %.3f m/s, momentum "
        "difference / scale %.2e\n",
        name, r.worst_ratio, r.final_checkerboard, r.final_rms, r.momentum_difference / r.momentum_scale);
    EXPECT_LE(r.worst_ratio, 1e-2) << name << ": final checkerboard " << r.final_checkerboard << " m/s, rms "
                                   << r.final_rms << " m/s";
    EXPECT_GT(r.final_rms, 0.5) << name;  // the swirl is still there (not damped away)
    if (mapping == Mapping::MPM)
      EXPECT_LT(r.momentum_difference, 1e-12 * r.momentum_scale);
    else
      EXPECT_GT(r.momentum_difference, 1e-9 * r.momentum_scale);  // real, and what the column reports
  }
}

}  // namespace
