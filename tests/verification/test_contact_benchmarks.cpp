// Issue 5 verification items 2 and 3 (cheap versions; full resolution in the example READMEs).
// 2. examples/incline-friction: a block on a rigid incline (theta = 30 deg). Sliding: the centre
//    of mass follows 1/2 g (sin theta - mu cos theta) t^2 within 2 % in the second half of the run
//    (the bound); mu = 0 is the frictionless slide 1/2 g sin theta t^2; mu = 0.6 > tan 30
//    = 0.577 sticks: after settling it moves less than 1 % of the frictionless slide. Gravity is
//    switched on at t = 0 on an unstressed, undamped elastic block, so the normal force
//    oscillates between about 0 and twice its mean; a static-friction test needs that vibration
//    damped: the stick cases run PIC (lumped FMPM(1)), whose dissipation removes it (README.md
//    shows FLIP creeping at mu = 0.7). (The shipped mu = 0.3 input runs in test_examples.)
// 3. examples/two-disks-contact at the CI cell (1 mm, 20 cells per diameter, 3 x the paper's):
//    the energy (kinetic + strain + friction work) lost falls with k (FMPM(1) > FMPM(2) > FMPM(4),
//    Nairn 2026 Fig. 9B) and, for FLIP, with the cell size (1 mm > 0.5 mm, Fig. 11A: USL converges
//    toward zero loss); no run gains energy; and the FMPM(4) centre-of-mass trajectories stay
//    within 0.2 mm (1 % of a diameter, the paper's "essentially identical" at the scale of Fig. 8)
//    of FLIP's. The paper's absolute values (< 2 % for FLIP and FMPM(4), 18.7 % for FMPM(1)) are
//    1/3 mm results: sweep.py measures them (README.md), too slow for the default suite.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "matpoint/analysis/measures_eval.hpp"
#include "test_support.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::test;

double sliding_error(double mu, VelocityTransfer transfer, double end_time) {
  Spec spec = load_example("incline-friction");
  spec.contact.law =
      mu > 0 ? ContactLawSpec{ContactLaw::Coulomb, mu} : ContactLawSpec{ContactLaw::Frictionless, 0};
  spec.solver.transfer = transfer;
  spec.solver.end_time = end_time;
  const auto result = run_quietly(spec, "incline_" + std::to_string(mu));
  EXPECT_EQ(result.exit_code, 0) << result.message;
  return evaluate_measure("sliding_block_displacement_error", spec, result.history, 0.0);
}

TEST(InclineFriction, FrictionlessSlidesAtGSinTheta) {
  EXPECT_LT(sliding_error(0.0, VelocityTransfer::FLIP, 0.4), 0.02);  // 0.4 s: the block stays on the grid
}

TEST(InclineFriction, StaysPutWhenMuExceedsTanTheta) {
  EXPECT_LT(sliding_error(0.6, VelocityTransfer::PIC, 0.6), 0.01);
}

struct DiskRun {
  double loss;
  std::vector<std::array<double, 3>> left, right;  // centre-of-mass positions at the outputs
};

DiskRun run_disks(VelocityTransfer transfer, int order, const std::string& tag, double cell = 1e-3) {
  Spec spec = load_example("two-disks-contact");
  spec.grid.cell_size = {cell, cell, 0};
  for (int a = 0; a < 2; ++a)
    spec.grid.cells[a] = static_cast<int>(std::lround((spec.grid.max[a] - spec.grid.min[a]) / cell));
  spec.solver.transfer = transfer;
  spec.solver.fmpm.order = order;
  spec.solver.position_alpha = transfer == VelocityTransfer::FMPM ? 0.5 : 1.0;
  const auto result = run_quietly(spec, tag);
  EXPECT_EQ(result.exit_code, 0) << result.message;
  DiskRun run{-evaluate_measure("total_energy_change", spec, result.history, 0.0), {}, {}};
  for (const auto& s : result.history.samples) {
    run.left.push_back(s.body_com_position[0]);
    run.right.push_back(s.body_com_position[1]);
  }
  return run;
}

TEST(TwoDisksContact, EnergyLossAndTrajectoriesFollowNairnFigures8And9) {
  const DiskRun flip = run_disks(VelocityTransfer::FLIP, 1, "disks_contact_flip");
  const DiskRun k1 = run_disks(VelocityTransfer::FMPM, 1, "disks_contact_k1");
  const DiskRun k2 = run_disks(VelocityTransfer::FMPM, 2, "disks_contact_k2");
  const DiskRun k4 = run_disks(VelocityTransfer::FMPM, 4, "disks_contact_k4");
  const DiskRun fine = run_disks(VelocityTransfer::FLIP, 1, "disks_contact_flip_fine", 5e-4);
  for (const auto* run : {&flip, &k1, &k2, &k4, &fine}) EXPECT_GT(run->loss, 0.0);
  EXPECT_LT(fine.loss, flip.loss);
  EXPECT_GT(k1.loss, k2.loss);
  EXPECT_GT(k2.loss, k4.loss);
  double worst = 0.0;
  ASSERT_EQ(flip.left.size(), k4.left.size());
  for (std::size_t s = 0; s < flip.left.size(); ++s)
    for (int a = 0; a < 2; ++a) {
      worst = std::max(worst, std::abs(flip.left[s][a] - k4.left[s][a]));
      worst = std::max(worst, std::abs(flip.right[s][a] - k4.right[s][a]));
    }
  EXPECT_LT(worst, 2e-4);
  std::printf(
      "[ disks 1 mm, mu 0.3 ] loss FLIP %.4f (0.5 mm: %.4f), FMPM(1) %.4f, FMPM(2) %.4f, FMPM(4) %.4f; "
      "COM gap %.3g m\n",
      flip.loss, fine.loss, k1.loss, k2.loss, k4.loss, worst);
}

}  // namespace
