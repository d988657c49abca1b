// A known failure of the plastic frame (material/hencky_plasticity.hpp), kept DISABLED_ so that the
// suite stays green until it is fixed; run it with --gtest_also_run_disabled_tests.
//
// examples/soil-column-collapse/granular.json on h/4 = 0.0125 m stops at t = 0.91 s with a
// non-finite stress: a particle of the deposit's front tail (c = 0, at the apex for many steps) has
// F with entries ~4e5 and det F = 151 (stretches ~5e5 and ~3e-4), and C_p^-1 entries ~1e7. The
// trial b_e = F C_p^-1 F^T is then formed from products of order 1e18 that cancel to order 1: the
// round-off presumably makes b_e indefinite, and ln of a negative eigenvalue gives NaN. Storing C_p^-1 in the
// reference frame (so that the stress is a function of F and the state only) loses precision at
// extreme stretch; Iaconeta et al. 2017 §7.2 (and the Kratos code) update the spatial b_e with the
// step's relative f = F_n+1 F_n^-1 instead, which stays of order 1 here. F and the state below are
// the failing particle's, printed from that run (step 5276).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "matpoint/material/mohr_coulomb.hpp"

namespace {

using namespace matpoint;

TEST(PlasticExtremeStretch, DISABLED_MohrCoulombStressStaysFiniteAtTheGranularFrontsStretch) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  const double E = 1.8e6, nu = 0.3;
  const MohrCoulomb sand{
      1850, {E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))}, {0.0, 25 * kDeg, 0.0}};
  Mat<2> F;
  F << 436907.28890849405, -22168.979206924912, 173413.60767870804, -8799.1265176396319;
  ASSERT_NEAR(F.determinant(), 151.242, 0.01);
  std::vector<double> state{22620.431134371793,
                            8786324.1582957562,
                            -4.4408920985006262e-16,
                            445824.23609824735,
                            0,
                            0,
                            22.230051616627016,
                            1,
                            0};  // plastic work (not part of the captured state)
  double zz = 0;
  const Mat<2> sigma = sand.stress<2>(F, 0.0, state.data(), zz);
  EXPECT_TRUE(sigma.allFinite()) << sigma;
  EXPECT_TRUE(std::isfinite(zz));
}

}  // namespace
