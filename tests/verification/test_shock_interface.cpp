// examples/shock-interface (Nairn 2026 §3.2.1, Fig. 4), single-material mode at the paper's
// resolution (0.25 mm cells, B2CPDI, USL, C = 0.2): a 1840 m/s wall drives a shock into
// Mie-Grueneisen nickel. Checked against Rankine-Hugoniot:
//  - the momentum jump rho0 U_s u_p from the run's own measured shock speed and particle speed,
//    within 1.5 % of the plateau (independent of the EOS constants);
//  - with the EOS constants: plateau stress 118.3 GPa +/- 2 % for FMPM(4), FMPM(8) and FLIP (the
//    constants are calibrated to the paper's 118.3 GPa, so this part is calibration, and 2 % is the
//    plateau's first-order dt error, README.md);
//  - FMPM(8) within 0.5 % of FMPM(4) (Nairn: "FMPM(k > 4) was within 0.5 % of FMPM(4)"): the
//    plateau values, and the mean difference of the column-averaged -sigma_xx profiles over the
//    plateau;
//  - the front (half plateau) at x = 50 mm - U_s t = 34.2 mm +/- 0.5 mm (extraction's test list);
//  - the wall's work is its velocity times the momentum it gave (FMPM increments included), and
//    kinetic + internal energy (AV heat included) stays within 2.5 % of it: measured -1.8 %, the
//    dissipation of the FMPM(4) transfer, which no model here turns into heat (FLIP -4.1 %,
//    FMPM(1) -16 %, FMPM(16) -1.0 %; README.md).
// The two-material bar (input-interface.json: split at x = 40 mm, Fig. 5):
//  - stick contact is the single-material run (Nairn §3.2: both increment methods revert exactly
//    to single-material mode): column profiles equal to round-off (1e-9 of the plateau);
//  - frictionless, Net, FMPM(4) and FMPM(8): plateau within 0.5 % of the single-material FMPM(4)
//    ("multimaterial equals single material", "FMPM(k > 4) within 0.5 %"), and no column within
//    1.5 mm of the interface off by more than 2 % (the column noise between orders is up to 1.6 %
//    in the single material, README.md);
//  - Evolving FMPM(8) shows the interface artefact Net does not: a column near the interface off
//    by more than twice that noise bound (measured 11.9 % against Net's 0.75 %).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "matpoint/analysis/diagnostics.hpp"
#include "matpoint/analysis/measures_eval.hpp"
#include "matpoint/explicit/explicit_step.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "test_support.hpp"

namespace shock_interface_tests {

using namespace matpoint;

const MieGruneisen kNickel{8870.0, 4600.0, 1.44, 1.93, 0.0};  // extraction A11
constexpr double kWallSpeed = 1840.0;
constexpr double kColumn = 0.25e-3;  // profile bins: one cell

struct ShockRun {
  std::vector<double> profile;  // column averages of -sigma_xx over x in [0, 50 mm)
  double plateau = 0, front = 0, energy_error = 0, time = 0, work = 0, momentum_x = 0;
  double half_time = 0, half_front = 0;  // the front at the middle of the run
  double particle_speed = 0;             // mean -v_x of the particles on the plateau at the end
  /// The shock speed measured between the middle and the end of the run (no start-up transient).
  [[nodiscard]] double shock_speed() const { return (half_front - front) / (time - half_time); }
};

/// Column averages of -sigma_xx over x in [0, 50 mm), and the plateau stress.
template <class Sim>
std::vector<double> stress_profile(const Sim& sim, double* plateau) {
  std::vector<double> sum(200, 0.0), count(200, 0.0), stress_xx, profile;
  for (std::size_t p = 0; p < sim.particles.size(); ++p) {
    stress_xx.push_back(sim.particles.stress[p](0, 0));
    const auto bin = static_cast<std::size_t>(std::floor(sim.particles.x[p][0] / kColumn));
    if (bin < sum.size()) sum[bin] -= sim.particles.stress[p](0, 0), count[bin] += 1;
  }
  for (std::size_t b = 0; b < sum.size(); ++b) profile.push_back(count[b] > 0 ? sum[b] / count[b] : 0.0);
  *plateau = shock_plateau_stress(stress_xx);
  return profile;
}

/// Where the column averages first reach half the plateau, from the left (linear between centres).
double front_position(const std::vector<double>& profile, double plateau) {
  for (std::size_t b = 0; b < profile.size(); ++b)
    if (profile[b] >= 0.5 * plateau) {
      const double below = b > 0 ? profile[b - 1] : 0.0;
      return kColumn * (static_cast<double>(b) - 0.5 + (0.5 * plateau - below) / (profile[b] - below));
    }
  return 0.0;
}

using B2Cpdi = CpdiStencils<2, QuadraticKernel, CpdiDomain::Parallelogram>;

/// `interface`: empty for the single material, else the split bar's contact law ("stick",
/// "frictionless") and `method` its FMPM increment method.
ShockRun run_shock(VelocityTransfer transfer, int order, const std::string& interface = "",
                   ContactFmpmMethod method = ContactFmpmMethod::Net) {
  Spec spec =
      test::load_example("shock-interface", interface.empty() ? "input.json" : "input-interface.json");
  spec.solver.transfer = transfer;
  spec.solver.fmpm.order = order;
  spec.solver.position_alpha = 0.5;  // Nairn 2026 eq. (7), alpha_t = 1/2 (NairnMPM) for FLIP and FMPM
  if (!interface.empty()) {
    spec.contact.law.law = interface == "stick" ? ContactLaw::Stick : ContactLaw::Frictionless;
    spec.contact.fmpm_method = method;
  }
  auto sim = build_simulation<2>(spec);
  const double dt = stable_time_step(sim);
  ShockRun out;
  const auto run_to_end = [&](auto&& stepper) {
    const double half = 0.5 * spec.solver.end_time;
    while (sim.time < half - 1e-9 * dt) stepper.step(std::min(dt, half - sim.time));
    double plateau = 0.0;
    const auto profile = stress_profile(sim, &plateau);
    out.half_time = sim.time;
    out.half_front = front_position(profile, plateau);
    while (sim.time < spec.solver.end_time - 1e-9 * dt)
      stepper.step(std::min(dt, spec.solver.end_time - sim.time));
  };
  if (interface.empty())
    run_to_end(ExplicitStepper<2, B2Cpdi>(sim));
  else
    run_to_end(ExplicitStepper<2, FieldStencils<2, B2Cpdi>>(sim));
  out.time = sim.time;
  out.profile = stress_profile(sim, &out.plateau);
  out.front = front_position(out.profile, out.plateau);
  double speed = 0.0;
  int behind = 0;
  const double wall = 0.05 - kWallSpeed * out.time;
  for (std::size_t p = 0; p < sim.particles.size(); ++p)
    if (sim.particles.x[p][0] > out.front + 1e-3 && sim.particles.x[p][0] < wall - 0.5e-3) {
      speed -= sim.particles.v[p][0];
      ++behind;
    }
  out.particle_speed = behind > 0 ? speed / behind : 0.0;
  const auto d = measure_diagnostics(sim, static_cast<int>(spec.bodies.size()));
  out.energy_error = (d.kinetic_energy + d.strain_energy - sim.external_work) / sim.external_work;
  out.work = sim.external_work;
  out.momentum_x = d.momentum[0];
  return out;
}

double hugoniot_front(double t) { return 0.05 - kNickel.shock_speed(kWallSpeed) * t; }

// One test for both claims: the FMPM(4) run is the costly part (8000 particles, 322 steps).
TEST(ShockInterface, Fmpm4MatchesRankineHugoniotAndHigherOrdersStayWithinHalfAPercent) {
  const auto four = run_shock(VelocityTransfer::FMPM, 4);
  const double p = kNickel.hugoniot_pressure(kWallSpeed);  // 118.33 GPa
  EXPECT_NEAR(four.plateau, p, 0.02 * p);
  EXPECT_NEAR(four.front, hugoniot_front(four.time), 0.5e-3);
  EXPECT_NEAR(four.work, -kWallSpeed * four.momentum_x, 1e-9 * four.work);
  EXPECT_LT(std::abs(four.energy_error), 0.025);
  // Independent of the EOS constants (which are calibrated to the paper's 118.3 GPa): the momentum
  // jump across the measured shock (Rankine-Hugoniot), p = rho0 U_s u_p, with U_s from the front's
  // travel between mid-run and the end (7.9 mm, the front read to about 0.03 mm at each time: 0.7 %)
  // and u_p the mean particle speed on the plateau, which must be the wall's (the material behind
  // the shock moves with it). Measured: U_s 7174 m/s, u_p 1837.4 m/s, 116.9 GPa against a plateau of
  // 116.2 GPa (0.6 %).
  const double jump = kNickel.density * four.shock_speed() * four.particle_speed;
  EXPECT_NEAR(four.particle_speed, kWallSpeed, 0.005 * kWallSpeed);
  EXPECT_NEAR(four.plateau, jump, 0.015 * jump)
      << "U_s " << four.shock_speed() << " m/s, u_p " << four.particle_speed << " m/s";
  const auto eight = run_shock(VelocityTransfer::FMPM, 8);
  EXPECT_NEAR(eight.plateau, p, 0.02 * p);
  EXPECT_LT(std::abs(eight.plateau - four.plateau), 0.005 * four.plateau);
  // Mean of the column differences over the plateau (1 mm behind the front to 0.5 mm before the
  // wall). Single columns differ by up to ~1 % (column noise; README.md), the level by far less.
  double sum = 0.0;
  int columns = 0;
  for (std::size_t b = 0; b < four.profile.size(); ++b) {
    const double x = kColumn * (static_cast<double>(b) + 0.5);
    if (x > four.front + 1e-3 && x < 0.05 - kWallSpeed * four.time - 0.5e-3) {
      sum += eight.profile[b] - four.profile[b];
      ++columns;
    }
  }
  ASSERT_GT(columns, 30);
  EXPECT_LT(std::abs(sum / columns), 0.005 * four.plateau);
}

TEST(ShockInterface, FlipPlateauAlsoMatchesRankineHugoniot) {
  const auto run = run_shock(VelocityTransfer::FLIP, 1);
  const double p = kNickel.hugoniot_pressure(kWallSpeed);
  EXPECT_NEAR(run.plateau, p, 0.02 * p);
  EXPECT_NEAR(run.front, hugoniot_front(run.time), 0.5e-3);
}

/// Largest |difference| of the column averages, in the single run's plateau, over the columns
/// behind both fronts and before the wall, optionally only within `radius` of x = 40 mm.
double largest_column_difference(const ShockRun& a, const ShockRun& b, double radius = 1.0) {
  double worst = 0.0;
  for (std::size_t c = 0; c < a.profile.size(); ++c) {
    const double x = kColumn * (static_cast<double>(c) + 0.5);
    const bool plateau = x > std::max(a.front, b.front) + 1e-3 && x < 0.05 - kWallSpeed * a.time - 0.5e-3;
    if (plateau && std::abs(x - 0.04) < radius)
      worst = std::max(worst, std::abs(a.profile[c] - b.profile[c]));
  }
  return worst / a.plateau;
}

TEST(ShockInterface, StickInterfaceIsTheSingleMaterialRun) {
  const auto single = run_shock(VelocityTransfer::FMPM, 4);
  const auto stick = run_shock(VelocityTransfer::FMPM, 4, "stick");
  EXPECT_LT(largest_column_difference(single, stick), 1e-9);
  EXPECT_NEAR(stick.plateau, single.plateau, 1e-9 * single.plateau);
}

TEST(ShockInterface, FrictionlessInterfaceNetMatchesTheSingleMaterialAndEvolvingDoesNot) {
  const auto single = run_shock(VelocityTransfer::FMPM, 4);
  const double near = 1.5e-3;  // columns within 1.5 mm of the interface
  for (int k : {4, 8}) {
    const auto net = run_shock(VelocityTransfer::FMPM, k, "frictionless");
    EXPECT_NEAR(net.plateau, single.plateau, 0.005 * single.plateau) << "Net FMPM(" << k << ")";
    EXPECT_LT(largest_column_difference(single, net, near), 0.02) << "Net FMPM(" << k << ")";
  }
  const auto evolving = run_shock(VelocityTransfer::FMPM, 8, "frictionless", ContactFmpmMethod::Evolving);
  EXPECT_GT(largest_column_difference(single, evolving, near), 0.04);
}

}  // namespace shock_interface_tests
