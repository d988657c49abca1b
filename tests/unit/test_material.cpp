// Materials: the stress is the derivative of the stored energy (P = dW/dF, sigma = P F^T / J),
// checked by central differences; the small-strain limit equals Hooke's law; the exponential
// deformation update is exact for a constant velocity gradient.
#include "matpoint/core/matrix_exponential.hpp"
#include "matpoint/material/material.hpp"

#include <gtest/gtest.h>

namespace {

using namespace matpoint;

template <int D, class Model> void check_stress_is_energy_derivative(const Model& model) {
  Mat<D> F = Mat<D>::Identity();
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) F(i, j) += 0.05 * (i + 1) - 0.03 * j + (i == j ? 0.08 : 0.0);
  const double eps = 1e-6;
  Mat<D> P = Mat<D>::Zero();
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) {
      Mat<D> Fp = F, Fm = F;
      Fp(i, j) += eps;
      Fm(i, j) -= eps;
      P(i, j) = (model.template energy_density<D>(Fp) - model.template energy_density<D>(Fm)) / (2 * eps);
    }
  const Mat<D> sigma = P * F.transpose() / F.determinant();
  const Mat<D> s = model.template stress<D>(F);
  EXPECT_LT((sigma - s).norm(), 1e-6 * s.norm()) << "D = " << D << "\n" << sigma << "\n" << s;
}

TEST(Material, StressIsTheDerivativeOfTheStoredEnergy) {
  const LinearElastic elastic{1000.0, 2.6e6, 1.5e6, 1e6};
  const NeoHookean log_j{1000.0, 1.5e6, 1e6, NeoHookeanVolumetric::LogJ};
  const NeoHookean half_j2{1000.0, 1.5e6, 1e6, NeoHookeanVolumetric::HalfJSquared};
  check_stress_is_energy_derivative<2>(elastic);
  check_stress_is_energy_derivative<3>(elastic);
  check_stress_is_energy_derivative<1>(log_j);
  check_stress_is_energy_derivative<2>(log_j);
  check_stress_is_energy_derivative<3>(log_j);
  check_stress_is_energy_derivative<2>(half_j2);
  check_stress_is_energy_derivative<3>(half_j2);
}

TEST(Material, SmallStrainLimitIsHookesLaw) {
  const double E = 2e6, nu = 0.3, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  Mat<3> eps;
  eps << 1, 0.2, 0, 0.2, -0.5, 0.1, 0, 0.1, 0.3;
  eps *= 1e-7;
  const Mat<3> hooke = lambda * eps.trace() * Mat<3>::Identity() + 2 * mu * eps;
  const Mat<3> F = Mat<3>::Identity() + eps;
  const NeoHookean nh{1000, lambda, mu, NeoHookeanVolumetric::LogJ};
  const LinearElastic le{1000, E, lambda, mu};
  EXPECT_LT((nh.stress<3>(F) - hooke).norm(), 1e-6 * hooke.norm());
  EXPECT_LT((le.stress<3>(F) - hooke).norm(), 1e-6 * hooke.norm());
  // 1-D linear elasticity is a bar: sigma = E eps.
  EXPECT_NEAR(le.stress<1>(Mat<1>(1.0 + 1e-7))(0, 0), E * 1e-7, 1e-6 * E * 1e-7);
}

TEST(Material, WaveSpeeds) {
  const LinearElastic le{4.0, 100.0, 0.0, 50.0};
  EXPECT_DOUBLE_EQ(le.wave_speed<1>(), 5.0);                   // sqrt(E / rho)
  EXPECT_DOUBLE_EQ(le.wave_speed<2>(), std::sqrt(100.0 / 4));  // sqrt((lambda + 2 mu) / rho)
}

TEST(MatrixExponential, MatchesClosedForms) {
  Mat<2> A;  // rotation generator: exp = [[cos, -sin], [sin, cos]]
  A << 0, -0.7, 0.7, 0;
  Mat<2> R;
  R << std::cos(0.7), -std::sin(0.7), std::sin(0.7), std::cos(0.7);
  EXPECT_LT((matrix_exponential<2>(A) - R).norm(), 1e-14);
  Mat<3> B = Mat<3>::Zero();  // diagonal, large entries (exercises scaling and squaring)
  B.diagonal() << 3.0, -2.0, 0.5;
  const Mat<3> expB = matrix_exponential<3>(B);
  EXPECT_NEAR(expB(0, 0), std::exp(3.0), 1e-13 * std::exp(3.0));
  EXPECT_NEAR(expB(1, 1), std::exp(-2.0), 1e-14);
  Mat<2> N;  // nilpotent: exp = I + N
  N << 0, 2.5, 0, 0;
  EXPECT_LT((matrix_exponential<2>(N) - (Mat<2>::Identity() + N)).norm(), 1e-14);
  EXPECT_NEAR(matrix_exponential<2>(A).determinant(), 1.0, 1e-14);  // det exp(A) = exp(tr A)
}

}  // namespace
