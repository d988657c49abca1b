// examples/fmpm-vibrating-bar: Nairn 2026 §3.3 (1-D bar, L = 40, cell 1, 2 particles per cell,
// E = 2, rho = 0.5, v0 = 0.16, 5 periods), with the 1-D CPDI basis (the paper's 1-D basis is not
// stated; extraction ambiguity 1 recommends 1-D CPDI).
//  - kinetic energy after 5 periods, with the linear update of F (F <- (I + L dt) F): FLIP and
//    FMPM(k >= 2) within 0.05 % (paper: 0.03 % for FLIP and unblended FMPM(k >= 2)). The
//    exponential update (the default) adds 1/2 P : L^2 F dt^2 per step to the strain energy that
//    the grid work does not contain: the kinetic-energy peaks read high after a tension half
//    period and low after a compression one, by 0.07 % at C = 0.4 for every transfer (README.md);
//    a test below shows the alternation and that the linear update removes it;
//  - FMPM(1) at C = 0.84 loses 27.7 +/- 3 % (paper at C = 0.86, above our FMPM(1) limit 0.848);
//  - Courant limits by bisection to +/-0.005 within 0.03 of the paper's table, and the ordering
//    FMPM(80) < FMPM(40) < FMPM(4) < FLIP < FMPM(1); periodic FMPM raises the high-k limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "matpoint/analysis/stability_scan.hpp"
#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;

RunResult run_bar(VelocityTransfer transfer, int order, double courant, DeformationUpdate update) {
  Spec spec = load_example("fmpm-vibrating-bar");
  spec.solver.transfer = transfer;
  spec.solver.position_alpha = 0.5;
  spec.solver.fmpm.order = order;
  spec.solver.courant = courant;
  spec.solver.deformation_update = update;
  spec.solver.end_time = 420;
  spec.output.every_steps = 1;
  spec.output.every_time = 0;
  spec.checks = {{"peak", "late_kinetic_energy_peak_change", 0.0, 1.0, "test"}};
  auto result = run_quietly(spec, "nairn_bar");
  EXPECT_EQ(result.exit_code, 0) << result.message;
  return result;
}

/// Kinetic energy peak near the end of 5 periods relative to the start (run to 5.25 periods and
/// take the largest kinetic energy of the last tenth, so the period error does not count).
double energy_change(VelocityTransfer transfer, int order, double courant,
                     DeformationUpdate update = DeformationUpdate::Linear) {
  return measured(run_bar(transfer, order, courant, update), "late_kinetic_energy_peak_change");
}

/// The largest kinetic energy within `half_width` of time t, relative to the start, minus 1.
double peak_change_near(const History& history, double t, double half_width = 10) {
  double peak = 0;
  for (const auto& s : history.samples)
    if (std::abs(s.time - t) <= half_width) peak = std::max(peak, s.kinetic_energy);
  return peak / history.samples.front().kinetic_energy - 1;
}

TEST(FmpmVibratingBar, KineticEnergyReturnsAfterFivePeriods) {
  for (double courant : {0.2, 0.4})
    EXPECT_NEAR(energy_change(VelocityTransfer::FLIP, 1, courant), 0.0, 5e-4) << "FLIP, C = " << courant;
  for (int k : {2, 3, 4, 8})
    EXPECT_NEAR(energy_change(VelocityTransfer::FMPM, k, 0.4), 0.0, 5e-4) << "FMPM(" << k << ")";
}

// The kinetic energy peaks at t = 40, 80, ...: after a half period of tension (odd peaks, t = 360)
// and of compression (even peaks, t = 400). With the exponential update they differ by about
// dt E eps_m^3 omega 4 L / (9 pi) = 0.071 % of K(0) at C = 0.4 (eps_m the largest strain): the
// second-order term of exp(L dt) that the grid work lacks (measured 0.076 %); with the linear
// update the two peaks agree to a few thousandths of a per cent.
TEST(FmpmVibratingBar, ExponentialUpdateAlternatesBetweenTensionAndCompressionPeaks) {
  const auto exponential = run_bar(VelocityTransfer::FLIP, 1, 0.4, DeformationUpdate::Exponential).history;
  const auto linear = run_bar(VelocityTransfer::FLIP, 1, 0.4, DeformationUpdate::Linear).history;
  const double gap_exponential = peak_change_near(exponential, 360) - peak_change_near(exponential, 400);
  const double gap_linear = peak_change_near(linear, 360) - peak_change_near(linear, 400);
  EXPECT_GT(gap_exponential, 0.5e-3) << "predicted 0.71e-3";
  EXPECT_LT(gap_exponential, 1.0e-3) << "predicted 0.71e-3";
  EXPECT_LT(std::abs(gap_linear), 0.1e-3);
}

TEST(FmpmVibratingBar, LumpedPicDissipatesAsThePaperReports) {
  EXPECT_NEAR(energy_change(VelocityTransfer::FMPM, 1, 0.84, DeformationUpdate::Exponential), -0.277, 0.03);
}

nlohmann::json example_json() {
  std::ifstream file(std::string(MATPOINT_EXAMPLES_DIR) + "/fmpm-vibrating-bar/input.json");
  std::stringstream text;
  text << file.rdbuf();
  return nlohmann::json::parse(text.str(), nullptr, true, true);
}

double limit(const std::vector<std::pair<std::string, std::string>>& overrides) {
  ScanOptions options;
  options.lo = 0.05;
  options.hi = 1.0;
  options.growth = 10;
  options.overrides = overrides;
  const auto result = stability_scan(example_json(), options);
  EXPECT_TRUE(result.bracketed);
  return result.limit();
}

TEST(FmpmVibratingBar, CourantLimitsMatchThePaper) {
  const double flip = limit({{"solver.transfer", "\"flip\""}, {"solver.fmpm", "null"}});
  const double k1 = limit({{"solver.fmpm.order", "1"}});
  const double k4 = limit({{"solver.fmpm.order", "4"}});
  const double k40 = limit({{"solver.fmpm.order", "40"}});
  const double k80 = limit({{"solver.fmpm.order", "80"}});
  const double blend1 =
      limit({{"solver.fmpm.order", "40"}, {"solver.fmpm.blend", R"({"with": 1, "factor": 0.8})"}});
  const double blend2 =
      limit({{"solver.fmpm.order", "40"}, {"solver.fmpm.blend", R"({"with": 2, "factor": 0.8})"}});
  const double periodic = limit({{"solver.fmpm.order", "40"}, {"solver.fmpm.periodic", R"({"courant": 2})"}});
  // Nairn 2026 §3.3: 0.84, 0.86, 0.539, 0.25, 0.24, 0.51 (blend with FMPM(1), 0.8), 0.40 (FMPM(2), 0.8).
  EXPECT_NEAR(flip, 0.84, 0.03);
  EXPECT_NEAR(k1, 0.86, 0.03);
  EXPECT_NEAR(k4, 0.539, 0.03);
  EXPECT_NEAR(k40, 0.25, 0.03);
  EXPECT_NEAR(k80, 0.24, 0.03);
  EXPECT_NEAR(blend1, 0.51, 0.03);
  EXPECT_NEAR(blend2, 0.40, 0.03);
  EXPECT_LT(k80, k40 + 0.005);
  EXPECT_LT(k40, k4);
  EXPECT_LT(k4, flip);
  EXPECT_LT(flip, k1);
  // Periodic FMPM(40), C_X = 2: paper 0.40, ours 0.51 (README); the claim tested is that it
  // raises the high-k limit well above the plateau.
  EXPECT_GT(periodic, k40 + 0.1);
}

}  // namespace
