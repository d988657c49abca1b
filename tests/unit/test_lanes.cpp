// The per-particle passes that run kLanes particles at once (core/lanes.hpp) against their scalar
// code, compared with == (bitwise, signed zeros aside): the lanes must be an implementation detail
// that no result can see. The expected values are the scalar functions' own results, which the
// other tests check against closed forms (test_matrix_exponential.cpp, test_material.cpp).
//   - exp(L dt) F for D = 1, 2, 3 at every Taylor degree, with lanes of mixed degrees, and batches
//     that need scaling and squaring or hold a NaN (the scalar path then);
//   - the 2-D neo-Hookean stress, sigma_zz and wave speed, both volumetric forms;
//   - update_stress on a set with mixed materials, a det F <= 0 particle and a remainder, against
//     the stress computed particle by particle, on 1 and 2 threads;
//   - the stencils of the linear and quadratic B-spline bases (TensorStencils::evaluate) against
//     Basis::evaluate per particle, with particles in the edge cells (the fold: scalar path).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "matpoint/core/deformation_increment.hpp"
#include "matpoint/core/deformation_increment_lanes.hpp"
#include "matpoint/explicit/deformation.hpp"
#include "matpoint/material/material.hpp"
#include "matpoint/material/neo_hookean_lanes.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

namespace lanes_tests {

using namespace matpoint;

/// A random D x D matrix with entries in [-scale, scale].
template <int D>
Mat<D> random_matrix(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Mat<D> m;
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) m(i, j) = u(rng);
  return m;
}

/// A deformation gradient near the identity (det F > 0 for `spread` below 1 / D).
template <int D>
Mat<D> random_deformation(std::mt19937& rng, double spread) {
  return Mat<D>::Identity() + random_matrix<D>(rng, spread);
}

template <int D>
void expect_exponential_update_matches_scalar() {
  std::mt19937 rng(11 + D);
  const double dt = 1e-3;
  // |L dt| from 1e-10 (degree 1) to 0.4 (scaling and squaring), log-uniform, so that batches mix
  // degrees; the last matrices hold a NaN.
  std::uniform_real_distribution<double> exponent(-10.0, std::log10(0.4));
  const int count = 4003;
  std::vector<Mat<D>> F(count), L(count);
  for (int p = 0; p < count; ++p) {
    F[p] = random_deformation<D>(rng, 0.2);
    L[p] = random_matrix<D>(rng, std::pow(10.0, exponent(rng)) / dt / D);
  }
  L[count - 5](0, 0) = std::numeric_limits<double>::quiet_NaN();
  int batches_through_lanes = 0;
  for (int first = 0; first + kLanes <= count; first += kLanes) {
    std::vector<Mat<D>> lanes_F(F.begin() + first, F.begin() + first + kLanes);
    if (!advance_deformation_lanes<D>(lanes_F.data(), &L[first], dt)) continue;
    ++batches_through_lanes;
    for (int lane = 0; lane < kLanes; ++lane) {
      const Mat<D> scalar = advanced_deformation<D>(F[first + lane], L[first + lane], dt, true);
      for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j)
          ASSERT_EQ(lanes_F[lane](i, j), scalar(i, j)) << "particle " << first + lane << " entry " << i << j;
    }
  }
  // Most batches have all four norms below 1/4 (the scaled ones go the scalar way).
  EXPECT_GT(batches_through_lanes, count / kLanes / 2);
  EXPECT_LT(batches_through_lanes, count / kLanes);
}

TEST(Lanes, ExponentialUpdateIsTheScalarOneIn1D) { expect_exponential_update_matches_scalar<1>(); }
TEST(Lanes, ExponentialUpdateIsTheScalarOneIn2D) { expect_exponential_update_matches_scalar<2>(); }
TEST(Lanes, ExponentialUpdateIsTheScalarOneIn3D) { expect_exponential_update_matches_scalar<3>(); }

TEST(Lanes, DeformationPassIsTheScalarUpdateOnAnyThreadCount) {
  std::mt19937 rng(5);
  ParticleSet<2> particles;
  for (int p = 0; p < 10001; ++p) {  // above kParallelMinimum, with a remainder
    particles.add(Vec<2>::Zero(), Vec<2>::Zero(), 1.0, 1.0, Vec<2>::Constant(0.1), 0, 0);
    particles.F.back() = random_deformation<2>(rng, 0.2);
    particles.L.back() = random_matrix<2>(rng, p % 97 == 0 ? 500.0 : 1.0);  // some |L dt| > 1/4
  }
  const double dt = 1e-3;
  const int threads_before = omp_get_max_threads();
  std::vector<Mat<2>> expected(particles.size());
  for (std::size_t p = 0; p < particles.size(); ++p)
    expected[p] = advanced_deformation<2>(particles.F[p], particles.L[p], dt, true);
  for (int threads : {1, 2}) {
    ParticleSet<2> updated = particles;
    omp_set_num_threads(threads);
    update_deformation(updated, dt, DeformationUpdate::Exponential);
    for (std::size_t p = 0; p < particles.size(); ++p)
      ASSERT_TRUE(updated.F[p] == expected[p]) << "particle " << p << " on " << threads << " threads";
  }
  omp_set_num_threads(threads_before);
}

void expect_neo_hookean_lanes_match_scalar(NeoHookeanVolumetric form) {
  const NeoHookean model{1000.0, 5.77e5, 3.85e5, form};
  std::mt19937 rng(7);
  for (int batch = 0; batch < 500; ++batch) {
    Mat<2> F[kLanes];
    for (auto& f : F) f = random_deformation<2>(rng, 0.3);
    Lanes sigma_zz, speed;
    const LaneMatrix<2> lanes_F = LaneMatrix<2>::load(F);
    const LaneMatrix<2> sigma =
        neo_hookean_stress_and_wave_speed_lanes(model, lanes_F, lanes_F.determinant(), sigma_zz, speed);
    for (int lane = 0; lane < kLanes; ++lane) {
      double zz = 0.0, c = 0.0;
      const Mat<2> expected = model.stress_and_wave_speed<2>(F[lane], zz, c);
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) ASSERT_EQ(sigma(i, j)[lane], expected(i, j)) << "batch " << batch;
      ASSERT_EQ(sigma_zz[lane], zz);
      ASSERT_EQ(speed[lane], c);
    }
  }
}

TEST(Lanes, NeoHookeanStressIsTheScalarOneWithLogJ) {
  expect_neo_hookean_lanes_match_scalar(NeoHookeanVolumetric::LogJ);
}
TEST(Lanes, NeoHookeanStressIsTheScalarOneWithHalfJSquared) {
  expect_neo_hookean_lanes_match_scalar(NeoHookeanVolumetric::HalfJSquared);
}

/// update_stress against the per-particle stress (and, in 2-D, sigma_zz) and the largest wave
/// speed at F, on 1 and 2 threads; then a det F < 0 and a NaN particle: the first is reported.
template <int D>
void expect_stress_pass_matches_scalar() {
  const NeoHookean rubber{1000.0, 5.77e5, 3.85e5}, soft{900.0, 1e4, 2e3, NeoHookeanVolumetric::HalfJSquared};
  const std::vector<Material> materials{rubber, soft};
  std::mt19937 rng(9 + D);
  ParticleSet<D> particles;
  const int count = 9003;
  for (int p = 0; p < count; ++p) {
    const int material = p % 13 == 0 ? 1 : 0;  // batches of one material and mixed ones
    particles.add(Vec<D>::Zero(), Vec<D>::Zero(), 1.0, 1.0, Vec<D>::Constant(0.1), material, 0);
    particles.F.back() = random_deformation<D>(rng, 0.2);
  }
  set_state_layout<D>(materials, particles);
  const int threads_before = omp_get_max_threads();
  std::vector<Mat<D>> expected(count);
  std::vector<double> expected_zz(count);
  double fastest = 0.0;
  for (int p = 0; p < count; ++p) {
    const NeoHookean& model = particles.material[p] == 0 ? rubber : soft;
    expected[p] = model.stress<D>(particles.F[p], expected_zz[p]);
    fastest = std::max(fastest, model.wave_speed_at<D>(particles.F[p]));
  }
  for (int threads : {1, 2}) {
    ParticleSet<D> updated = particles;
    omp_set_num_threads(threads);
    EXPECT_EQ(update_stress<D>(materials, updated, ArtificialViscosity{}, 1e-4), -1);
    EXPECT_EQ(updated.recorded_wave_speed, fastest);
    for (int p = 0; p < count; ++p) {
      ASSERT_TRUE(updated.stress[p] == expected[p]) << "particle " << p << " on " << threads << " threads";
      if constexpr (D == 2) {
        ASSERT_EQ(updated.stress_zz[p], expected_zz[p]);
      }
    }
  }
  particles.F[4101] = Mat<D>::Identity();
  particles.F[4101](0, 0) = -1.0;  // det F = -1
  particles.F[6002](0, 0) = std::numeric_limits<double>::quiet_NaN();
  for (int threads : {1, 2}) {
    ParticleSet<D> updated = particles;
    omp_set_num_threads(threads);
    EXPECT_EQ(update_stress<D>(materials, updated, ArtificialViscosity{}, 1e-4), 4101);
    EXPECT_LT(updated.recorded_wave_speed, 0.0);
    EXPECT_TRUE(updated.stress[4100] == expected[4100]);
  }
  omp_set_num_threads(threads_before);
}

TEST(Lanes, StressPassIsTheScalarUpdateIn2D) { expect_stress_pass_matches_scalar<2>(); }
TEST(Lanes, StressPassIsTheScalarUpdateIn3D) { expect_stress_pass_matches_scalar<3>(); }

/// TensorStencils<D, Basis>::evaluate against Basis::evaluate, particle by particle: weights,
/// slopes (per unit length) and the lowest node, bitwise. Particles anywhere in a grid of 20 cells
/// per axis, origin and spacing not round, some in the edge cells (folded stencils, scalar path).
template <int D, class Basis>
void expect_stencils_match_scalar() {
  constexpr int W = Basis::width;
  Vec<D> origin, h;
  std::array<int, D> cells{};
  for (int a = 0; a < D; ++a) origin[a] = -0.37 + 0.1 * a, h[a] = 0.0113 * (1 + a), cells[a] = 20;
  const Grid<D> grid(origin, h, cells, 0);
  std::mt19937 rng(17 + D);
  ParticleSet<D> particles;
  const int count = 5003;  // above kParallelMinimum, with a remainder
  for (int p = 0; p < count; ++p) {
    Vec<D> x;
    for (int a = 0; a < D; ++a)
      x[a] = origin[a] + h[a] * std::uniform_real_distribution<double>(0.0, cells[a])(rng);
    particles.add(x, Vec<D>::Zero(), 1.0, 1.0, Vec<D>::Constant(0.01), 0, 0);
  }
  TensorStencils<D, Basis> stencils;
  stencils.evaluate(grid, particles);
  for (int p = 0; p < count; ++p) {
    std::array<int, D> lowest{};
    for (int a = 0; a < D; ++a) {
      double w[W], dw[W];
      lowest[a] = Basis::evaluate((particles.x[p][a] - origin[a]) / h[a], cells[a], w, dw);
      for (int k = 0; k < W; ++k) {
        ASSERT_EQ(stencils.weight[p][a * W + k], w[k]) << "particle " << p;
        ASSERT_EQ(stencils.slope[p][a * W + k], dw[k] * (1.0 / h[a])) << "particle " << p;
      }
    }
    ASSERT_EQ(stencils.base[p], grid.node_index(lowest)) << "particle " << p;
  }
}

TEST(Lanes, LinearStencilsAreTheScalarOnes) {
  expect_stencils_match_scalar<2, LinearBasis>();
  expect_stencils_match_scalar<3, LinearBasis>();
}
TEST(Lanes, QuadraticBSplineStencilsAreTheScalarOnes) {
  expect_stencils_match_scalar<2, QuadraticBSplineBasis>();
  expect_stencils_match_scalar<3, QuadraticBSplineBasis>();
}

}  // namespace lanes_tests
