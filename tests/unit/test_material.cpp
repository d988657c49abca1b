// Materials: the stress is the derivative of the stored energy (P = dW/dF, sigma = P F^T / J),
// checked by central differences; the small-strain limit equals Hooke's law; the exponential
// deformation update is exact for a constant velocity gradient.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "matpoint/core/matrix_exponential.hpp"
#include "matpoint/material/material.hpp"

namespace {

using namespace matpoint;

template <int D, class Model>
void check_stress_is_energy_derivative(const Model& model) {
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

/// The 2-D closed form of the largest eigenvalue against Eigen's iterative symmetric solver, on
/// left Cauchy-Green tensors B = F F^T of random deformations, and on matrices with equal or
/// nearly equal eigenvalues (where the square root is of a small number).
TEST(Material, LargestSymmetricEigenvalueMatchesEigensSolver) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (int k = 0; k < 2000; ++k) {
    Mat<2> F;
    F << 1 + u(rng), u(rng), u(rng), 1 + u(rng);
    const Mat<2> B = F * F.transpose();
    const double expected = Eigen::SelfAdjointEigenSolver<Mat<2>>(B).eigenvalues().maxCoeff();
    EXPECT_NEAR(largest_symmetric_eigenvalue<2>(B), expected, 1e-15 * expected) << B;  // ~5 ulp
  }
  EXPECT_DOUBLE_EQ(largest_symmetric_eigenvalue<2>(Mat<2>::Identity() * 3.0), 3.0);
  Mat<2> nearly;
  nearly << 2.0, 1e-9, 1e-9, 2.0;
  EXPECT_DOUBLE_EQ(largest_symmetric_eigenvalue<2>(nearly), 2.0 + 1e-9);
  Mat<3> C = Mat<3>::Zero();
  C.diagonal() << 1.0, 5.0, 2.0;
  EXPECT_NEAR(largest_symmetric_eigenvalue<3>(C), 5.0, 1e-14);
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

// --- Symmetric Cauchy stress for every model, and each model against a hand calculation ---

namespace {

const LinearElastic kSvk{1000.0, 2.6e6, 1.5e6, 1e6};
const NeoHookean kLogJ{1000.0, 1.5e6, 1e6, NeoHookeanVolumetric::LogJ};
const NeoHookean kHalfJ2{1000.0, 1.5e6, 1e6, NeoHookeanVolumetric::HalfJSquared};
const MieGruneisen kMieGruneisen{8870.0, 4600.0, 1.44, 1.93, 7.6e10};
const MohrCoulomb kMohrCoulomb{1850.0, {1.0385e6, 0.6923e6}, {5e3, 0.4363323129985824, 0.0}};
const DruckerPrager kDruckerPrager{1850.0, {1.0385e6, 0.6923e6}, {{5e3, 0.4363323129985824, 0.1}, {}}};
const VonMises kVonMises{8930.0, {9.68e10, 4.6e10}, {4e8, 1e8}};

/// The Cauchy stress of any model at F from a fresh (virgin) state, and its sigma_zz.
template <int D>
Mat<D> stress_of(const Material& material, const Mat<D>& F, double& zz) {
  std::vector<double> state(8, 0.0);
  return std::visit(
      [&](const auto& model) -> Mat<D> {
        using Model = std::decay_t<decltype(model)>;
        if constexpr (requires { Model::state_size; })
          return model.template stress<D>(F, 0.0, state.data(), zz);
        else
          return model.template stress<D>(F, zz);
      },
      material);
}

template <int D>
Mat<D> random_deformation(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (;;) {
    Mat<D> F = Mat<D>::Identity();
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) F(i, j) += u(rng);
    if (F.determinant() > 0.2) return F;
  }
}

}  // namespace

TEST(Material, CauchyStressIsSymmetricForEveryModel) {
  const std::vector<std::pair<const char*, Material>> models{{"linear_elastic", kSvk},
                                                             {"neo_hookean log_j", kLogJ},
                                                             {"neo_hookean half_j_squared", kHalfJ2},
                                                             {"mie_gruneisen", kMieGruneisen},
                                                             {"mohr_coulomb", kMohrCoulomb},
                                                             {"drucker_prager", kDruckerPrager},
                                                             {"von_mises", kVonMises}};
  std::mt19937 rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    const Mat<2> F2 = random_deformation<2>(rng, 0.4);
    const Mat<3> F3 = random_deformation<3>(rng, 0.4);
    for (const auto& [name, model] : models) {
      double zz;
      const Mat<2> s2 = stress_of<2>(model, F2, zz);
      const Mat<3> s3 = stress_of<3>(model, F3, zz);
      EXPECT_LE((s2 - s2.transpose()).norm(), 1e-13 * s2.norm()) << name << " 2-D\n" << s2;
      EXPECT_LE((s3 - s3.transpose()).norm(), 1e-13 * s3.norm()) << name << " 3-D\n" << s3;
      EXPECT_GT(s3.norm(), 0.0) << name;
    }
  }
}

TEST(Material, LinearElasticIsStVenantKirchhoffByHand) {
  // lambda = 1.5e6, mu = 1e6. Uniaxial plane-strain stretch F = diag(1.2, 1): E11 = (1.2^2 - 1)/2
  // = 0.22, S11 = (lambda + 2 mu) 0.22 = 770000, S22 = S33 = lambda 0.22 = 330000, J = 1.2,
  // sigma11 = 1.2^2 S11 / J = 924000, sigma22 = S22 / J = 275000 = sigma_zz.
  double zz;
  Mat<2> F = Mat<2>::Identity();
  F(0, 0) = 1.2;
  Mat<2> s = kSvk.stress<2>(F, zz);
  EXPECT_NEAR(s(0, 0), 924000.0, 1e-9 * 924000.0);
  EXPECT_NEAR(s(1, 1), 275000.0, 1e-9 * 924000.0);
  EXPECT_NEAR(s(0, 1), 0.0, 1e-9 * 924000.0);
  EXPECT_NEAR(zz, 275000.0, 1e-9 * 924000.0);
  // Simple shear F = [[1, 0.2], [0, 1]]: E = [[0, 0.1], [0.1, 0.02]], tr E = 0.02,
  // S = [[30000, 200000], [200000, 70000]], sigma = F S F^T (J = 1) = [[112800, 214000], [214000, 70000]],
  // sigma_zz = lambda tr E = 30000.
  F << 1.0, 0.2, 0.0, 1.0;
  s = kSvk.stress<2>(F, zz);
  Mat<2> expected;
  expected << 112800.0, 214000.0, 214000.0, 70000.0;
  EXPECT_LT((s - expected).norm(), 1e-9 * expected.norm()) << s;
  EXPECT_NEAR(zz, 30000.0, 1e-9 * expected.norm());
  // 1-D: a bar, sigma = E (F - 1).
  EXPECT_NEAR(kSvk.stress<1>(Mat<1>(1.01))(0, 0), 2.6e6 * 0.01, 1e-9 * 2.6e6);
}

TEST(Material, NeoHookeanByHand) {
  // F = diag(1.2, 1) (plane strain): J = 1.2, B = diag(1.44, 1, 1).
  //   log_j:          sigma_ii = lambda ln(1.2) / 1.2 + mu (B_ii - 1) / 1.2
  //   half_j_squared: sigma_ii = lambda / 2 (1.2 - 1 / 1.2) + mu (B_ii - 1) / 1.2 = 275000 + ...
  const double lambda = 1.5e6, mu = 1e6, J = 1.2;
  Mat<2> F = Mat<2>::Identity();
  F(0, 0) = J;
  double zz;
  const double log_part = lambda * std::log(1.2) / 1.2;
  Mat<2> s = kLogJ.stress<2>(F, zz);
  EXPECT_NEAR(s(0, 0), log_part + mu * 0.44 / 1.2, 1e-9 * mu);
  EXPECT_NEAR(s(1, 1), log_part, 1e-9 * mu);
  EXPECT_NEAR(zz, log_part, 1e-9 * mu);
  s = kHalfJ2.stress<2>(F, zz);
  EXPECT_NEAR(s(0, 0), 275000.0 + mu * 0.44 / 1.2, 1e-9 * mu);
  EXPECT_NEAR(s(1, 1), 275000.0, 1e-9 * mu);
  EXPECT_NEAR(zz, 275000.0, 1e-9 * mu);
  // Simple shear F = [[1, 0.2], [0, 1]]: J = 1, B = [[1.04, 0.2], [0.2, 1]]: sigma = mu (B - I).
  F << 1.0, 0.2, 0.0, 1.0;
  s = kLogJ.stress<2>(F, zz);
  EXPECT_NEAR(s(0, 0), 40000.0, 1e-9 * mu);
  EXPECT_NEAR(s(0, 1), 200000.0, 1e-9 * mu);
  EXPECT_NEAR(s(1, 0), 200000.0, 1e-9 * mu);
  EXPECT_NEAR(s(1, 1), 0.0, 1e-9 * mu);
  EXPECT_NEAR(zz, 0.0, 1e-9 * mu);
}

TEST(Material, MieGruneisenByHand) {
  // Nickel (Nairn 2026 extraction A11) with G = 76 GPa, from rest (e = 0, eta = 0) to
  // F = diag(0.98, 1) (plane strain) in one update, q = 0: eta = 0.02, J = 0.98,
  //   p_H = rho0 C0^2 eta / (1 - S eta)^2,  reference p_r = p_H (1 - Gamma0 eta / 2),
  //   trapezoid: e = -(p_r / 2) dv / (1 + Gamma0 rho0 dv / 2), dv = -eta / rho0,
  //   p = p_r + Gamma0 rho0 e,  dev: G J^(-5/3) (B - tr(B3)/3 I), B3 = diag(0.9604, 1, 1).
  const double rho0 = 8870.0, c0 = 4600.0, S = 1.44, gamma0 = 1.93, G = 7.6e10, eta = 0.02, J = 0.98;
  const double p_h = rho0 * c0 * c0 * eta / ((1 - S * eta) * (1 - S * eta));
  const double p_r = p_h * (1 - gamma0 * eta / 2), dv = -eta / rho0;
  const double e = -(p_r / 2) * dv / (1 + gamma0 * rho0 * dv / 2);
  const double p = p_r + gamma0 * rho0 * e;
  const double tr_b = 0.9604 + 2.0, scale = G * std::pow(J, -5.0 / 3.0);
  double state[2] = {0.0, 0.0}, zz;
  Mat<2> F = Mat<2>::Identity();
  F(0, 0) = J;
  const Mat<2> s = kMieGruneisen.stress<2>(F, 0.0, state, zz);
  EXPECT_NEAR(s(0, 0), -p + scale * (0.9604 - tr_b / 3), 1e-9 * p);
  EXPECT_NEAR(s(1, 1), -p + scale * (1.0 - tr_b / 3), 1e-9 * p);
  EXPECT_NEAR(zz, -p + scale * (1.0 - tr_b / 3), 1e-9 * p);
  EXPECT_NEAR(state[0], e, 1e-12 * e);
}

TEST(Material, PlaneStrainLinearElasticityKeepsSigmaZz) {
  // Small plane-strain stretch: Hooke's law gives sigma_zz = lambda tr(eps) = nu (sigma_xx + sigma_yy).
  const double E = 2e6, nu = 0.3, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const LinearElastic le{1000, E, lambda, mu};
  Mat<2> F;
  F << 1.0 + 2e-7, 0.5e-7, 0.5e-7, 1.0 - 0.7e-7;
  double zz;
  const Mat<2> s = le.stress<2>(F, zz);
  EXPECT_NEAR(zz, nu * (s(0, 0) + s(1, 1)), 1e-6 * std::abs(zz));
}
