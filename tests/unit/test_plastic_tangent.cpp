// d tau / d F of the Hencky plastic models (material/plastic_tangent.hpp), the tangent the implicit
// solvers differentiate through, against central differences of tau(F) (issue acceptance: tangents
// versus finite differences <= 1e-6 relative). Random deformation gradients from a random plastic
// history hit every return region (elastic, surface, edge, apex) of Mohr-Coulomb, Drucker-Prager and
// J2; a sample whose perturbed states fall in another region straddles a kink of the return map and
// is skipped (counted, and bounded so the test cannot pass by skipping everything).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "matpoint/material/drucker_prager.hpp"
#include "matpoint/material/mohr_coulomb.hpp"
#include "matpoint/material/plastic_tangent.hpp"
#include "matpoint/material/von_mises.hpp"

namespace {

using namespace matpoint;

constexpr double kDeg = 3.14159265358979323846 / 180.0;
const HenckyElasticity kSoil{1.8e6 * 0.3 / (1.3 * 0.4), 1.8e6 / 2.6};  // E = 1.8 MPa, nu = 0.3

Mat3 random_F(std::mt19937& rng, double size, bool plane) {
  std::uniform_real_distribution<double> u(-size, size);
  Mat3 F = Mat3::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F(i, j) += u(rng);
  if (plane) F.row(2) = Eigen::RowVector3d(0, 0, 1), F.col(2) = Vec3(0, 0, 1);
  return F;
}

struct Tally {
  std::array<int, 4> checked{};  // per YieldState
  int skipped = 0;
};

/// Checks d tau / d F against central differences at random F for one model; returns the tally.
template <class Yield>
Tally check_against_differences(const Yield& yield, double strain, bool plane, unsigned seed,
                                double dt = 0.0) {
  std::mt19937 rng(seed);
  Tally tally;
  for (int sample = 0; sample < 400; ++sample) {
    // A plastic history: one update from the virgin state at F0, then the response at F.
    std::vector<double> state(kPlasticStateSize, 0.0);
    (void)hencky_plastic_update(kSoil, yield, random_F(rng, strain, plane), state.data(), dt);
    const Mat3 F = random_F(rng, strain, plane);
    const PlasticResponse r = hencky_plastic_response(kSoil, yield, F, state.data(), true, dt);
    const double h = 1e-7;
    double worst = 0.0;
    bool kink = false;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        if (plane && (k == 2 || l == 2)) continue;
        Mat3 Fp = F, Fm = F;
        Fp(k, l) += h, Fm(k, l) -= h;
        const PlasticResponse p = hencky_plastic_response(kSoil, yield, Fp, state.data(), true, dt);
        const PlasticResponse m = hencky_plastic_response(kSoil, yield, Fm, state.data(), true, dt);
        kink = kink || p.state != r.state || m.state != r.state;
        const Mat3 difference = (p.tau - m.tau) / (2 * h);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            worst = std::max(worst, std::abs(difference(i, j) - r.dtau_dF(3 * i + j, 3 * k + l)));
      }
    if (kink) {
      ++tally.skipped;
      continue;
    }
    ++tally.checked[static_cast<std::size_t>(r.state)];
    // Relative to the elastic modulus scale lambda + 2 mu (the largest entry of the elastic tangent).
    EXPECT_LE(worst, 1e-6 * (kSoil.lambda + 2 * kSoil.mu))
        << "sample " << sample << " state " << static_cast<int>(r.state);
  }
  EXPECT_LT(tally.skipped, 40) << "too many samples straddle a kink: the test would prove little";
  return tally;
}

TEST(PlasticTangent, MohrCoulombEveryRegionMatchesDifferences) {
  for (const bool plane : {false, true}) {
    const Tally t = check_against_differences(MohrCoulombYield{5e3, 25 * kDeg, 5 * kDeg}, 0.02, plane, 7);
    for (int s = 0; s < 4; ++s) EXPECT_GT(t.checked[static_cast<std::size_t>(s)], 0) << "state " << s;
  }
}

// Tresca (phi = psi = 0: no apex): the plane and both edges (strains of 2 % are all beyond the
// yield strain 2 c / E = 0.6 %, so no sample stays elastic).
TEST(PlasticTangent, TrescaMatchesDifferences) {
  for (const bool plane : {false, true}) {
    const Tally t = check_against_differences(MohrCoulombYield{5e3, 0.0, 0.0}, 0.02, plane, 29);
    for (int s = 1; s < 3; ++s) EXPECT_GT(t.checked[static_cast<std::size_t>(s)], 0) << "state " << s;
    EXPECT_EQ(t.checked[static_cast<std::size_t>(YieldState::Apex)], 0);
  }
}

TEST(PlasticTangent, MohrCoulombWithTensionCutoffMatchesDifferences) {
  MohrCoulombYield yield{5e3, 25 * kDeg, 5 * kDeg};
  yield.tension_cutoff = 3e3;
  for (const bool plane : {false, true}) {
    const Tally t = check_against_differences(yield, 0.02, plane, 23);
    // One and two active planes (pyramid, cut-off, and their edges); three (the cut-off's corner,
    // tau = sigma_t (1, 1, 1), tangent 0) is rare at these strains.
    for (int s = 0; s < 3; ++s) EXPECT_GT(t.checked[static_cast<std::size_t>(s)], 0) << "state " << s;
  }
}

TEST(PlasticTangent, DruckerPragerConeAndApexMatchDifferences) {
  for (const bool plane : {false, true}) {
    const Tally t = check_against_differences(
        DruckerPragerYield{MohrCoulombYield{5e3, 25 * kDeg, 25 * kDeg}, DruckerPragerMatch::Outer}, 0.02,
        plane, 11);
    EXPECT_GT(t.checked[0] + t.checked[1] + t.checked[3], 300);
    EXPECT_GT(t.checked[1], 0);
    EXPECT_GT(t.checked[3], 0);
  }
}

TEST(PlasticTangent, VonMisesMatchesDifferences) {
  for (const bool plane : {false, true}) {
    const Tally t = check_against_differences(VonMisesYield{2e4, 3e5}, 0.02, plane, 13);
    EXPECT_GT(t.checked[0], 0);
    EXPECT_GT(t.checked[1], 0);
  }
}

TEST(PlasticTangent, JohnsonCookMatchesDifferences) {
  // sigma_f = (2e4 + 1e5 eps_p^0.5)(1 + 0.05 ln(rate)), rate = dgamma / dt: the strain increments here
  // (up to 2 %) over dt = 1e-3 give rates of 1-20 /s, above the reference rate 1 /s.
  for (const bool plane : {false, true}) {
    const Tally t =
        check_against_differences(VonMisesYield{2e4, 0.0, 1e5, 0.5, 0.05, 1.0}, 0.02, plane, 29, 1e-3);
    EXPECT_GT(t.checked[1], 100);
  }
}

TEST(PlasticTangent, ElasticBranchAtIdentityIsIsotropicElasticity) {
  // At F = I, d tau / d F : dF = lambda tr(dF) I + 2 mu sym(dF) (the small-strain Hooke tangent).
  std::vector<double> state(kPlasticStateSize, 0.0);
  const PlasticResponse r =
      hencky_plastic_response(kSoil, VonMisesYield{1e9, 0.0}, Mat3::Identity(), state.data());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
          const double expected =
              kSoil.lambda * (i == j) * (k == l) + kSoil.mu * ((i == k) * (j == l) + (i == l) * (j == k));
          EXPECT_NEAR(r.dtau_dF(3 * i + j, 3 * k + l), expected, 1e-9 * kSoil.mu);
        }
}

TEST(PlasticTangent, DualNumbersCarryTheChainRule) {
  // kirchhoff_of on a dual F seeded with dF gives d tau = dtau/dF : dF.
  std::vector<double> state(kPlasticStateSize, 0.0);
  Mat<2> F2;
  F2 << 0.97, 0.01, -0.02, 1.01;
  const PlasticResponse r =
      hencky_plastic_response(kSoil, MohrCoulombYield{5e3, 25 * kDeg, 0.0}, embed3<2>(F2), state.data());
  ASSERT_NE(r.state, YieldState::Elastic);
  Eigen::Matrix<Dual<4>, 2, 2> F;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) F(a, b) = Dual<4>::variable(F2(a, b), 2 * a + b);
  const auto tau = kirchhoff_of<Dual<4>, 2>(r, F);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      EXPECT_EQ(tau(i, j).v, r.tau(i, j));
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          EXPECT_EQ(tau(i, j).d[static_cast<std::size_t>(2 * a + b)], r.dtau_dF(3 * i + j, 3 * a + b));
    }
}

}  // namespace
