// Forward-mode AD (core/dual.hpp) and the scalar-templated Kirchhoff stress of the neo-Hookean law.
// Expected values: derivatives from calculus (d/dx of x^2 y, log, sqrt, 1/x, ...), the Kirchhoff
// stress tau = lambda ln J I + mu (B - I) of Aulisa & Capodaglio eq. (12) (times J) worked by hand
// for F = diag(2, 1), and tau = J sigma with sigma from the explicit solver's Cauchy stress().
#include <gtest/gtest.h>

#include <cmath>

#include "matpoint/core/dual.hpp"
#include "matpoint/material/neo_hookean.hpp"

namespace {

using namespace matpoint;
using D3 = Dual<3>;

TEST(ImplicitAD, DualArithmeticGivesTheCalculusDerivatives) {
  const D3 x = D3::variable(1.5, 0), y = D3::variable(-0.7, 1), z = D3::variable(2.0, 2);
  // f = x^2 y / z + log(z) - sqrt(x) + 3 / x - (2 - y)
  const D3 f = x * x * y / z + log(z) - sqrt(x) + 3.0 / x - (2.0 - y);
  const double xv = 1.5, yv = -0.7, zv = 2.0;
  EXPECT_NEAR(f.v, xv * xv * yv / zv + std::log(zv) - std::sqrt(xv) + 3.0 / xv - (2.0 - yv), 1e-15);
  EXPECT_NEAR(f.d[0], 2.0 * xv * yv / zv - 0.5 / std::sqrt(xv) - 3.0 / (xv * xv), 1e-14);
  EXPECT_NEAR(f.d[1], xv * xv / zv + 1.0, 1e-14);
  EXPECT_NEAR(f.d[2], -xv * xv * yv / (zv * zv) + 1.0 / zv, 1e-14);
  const D3 g = exp(x) * pow(z, 1.5) - abs(y);
  EXPECT_NEAR(g.d[0], std::exp(xv) * std::pow(zv, 1.5), 1e-13);
  EXPECT_NEAR(g.d[1], 1.0, 1e-15);  // d|y|/dy = -1 for y < 0, and g has -|y|
  EXPECT_NEAR(g.d[2], std::exp(xv) * 1.5 * std::sqrt(zv), 1e-13);
  EXPECT_TRUE(x < z && z > y && !(x == y));
}

TEST(ImplicitAD, EigenMatricesOfDualsGiveTheDeterminantAndInverseDerivatives) {
  // d det(A) / dA = det(A) A^-T (Jacobi's formula); d(A^-1) = -A^-1 dA A^-1.
  using D4 = Dual<4>;
  Eigen::Matrix<double, 2, 2> A;
  A << 1.2, 0.3, -0.4, 0.9;
  Eigen::Matrix<D4, 2, 2> Ad;
  for (int k = 0; k < 4; ++k) Ad(k / 2, k % 2) = D4::variable(A(k / 2, k % 2), k);
  const D4 det = Ad.determinant();
  const Eigen::Matrix<double, 2, 2> cof = A.determinant() * A.inverse().transpose();
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(det.d[k], cof(k / 2, k % 2), 1e-14);
  const Eigen::Matrix<D4, 2, 2> inv = Ad.inverse();
  const Eigen::Matrix<double, 2, 2> Ai = A.inverse();
  for (int k = 0; k < 4; ++k) {
    Eigen::Matrix<double, 2, 2> dA = Eigen::Matrix<double, 2, 2>::Zero();
    dA(k / 2, k % 2) = 1.0;
    const Eigen::Matrix<double, 2, 2> expected = -Ai * dA * Ai;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) EXPECT_NEAR(inv(i, j).d[k], expected(i, j), 1e-13);
  }
}

TEST(ImplicitAD, KirchhoffStressOfUniaxialPlaneStrainStretchByHand) {
  // F = diag(2, 1), plane strain: J = 2, B = diag(4, 1): tau = lambda ln 2 I + mu diag(3, 0).
  const NeoHookean m{1000.0, 3.0e6, 1.0e6};
  Mat<2> F = Mat<2>::Identity();
  F(0, 0) = 2.0;
  const Mat<2> tau = m.kirchhoff_stress<double, 2>(F);
  EXPECT_NEAR(tau(0, 0), 3.0e6 * std::log(2.0) + 3.0e6, 1e-6);
  EXPECT_NEAR(tau(1, 1), 3.0e6 * std::log(2.0), 1e-6);
  EXPECT_EQ(tau(0, 1), 0.0);
}

TEST(ImplicitAD, KirchhoffStressIsJTimesTheCauchyStressOfBothForms) {
  for (const auto form : {NeoHookeanVolumetric::LogJ, NeoHookeanVolumetric::HalfJSquared}) {
    const NeoHookean m{1000.0, 1.5e6, 1.0e6, form};
    Mat<2> F2;
    F2 << 1.1, 0.2, -0.05, 0.93;
    Mat<3> F3;
    F3 << 1.1, 0.2, 0.01, -0.05, 0.93, 0.1, 0.02, -0.03, 1.05;
    EXPECT_LT((m.kirchhoff_stress<double, 2>(F2) - F2.determinant() * m.stress<2>(F2)).norm(), 1e-9);
    EXPECT_LT((m.kirchhoff_stress<double, 3>(F3) - F3.determinant() * m.stress<3>(F3)).norm(), 1e-9);
  }
}

TEST(ImplicitAD, KirchhoffStressDerivativeMatchesCentralDifferences) {
  const NeoHookean m{1000.0, 1.5e6, 1.0e6};
  Mat<2> F;
  F << 1.1, 0.2, -0.05, 0.93;
  using D4 = Dual<4>;
  Eigen::Matrix<D4, 2, 2> Fd;
  for (int k = 0; k < 4; ++k) Fd(k / 2, k % 2) = D4::variable(F(k / 2, k % 2), k);
  const Eigen::Matrix<D4, 2, 2> tau = m.kirchhoff_stress<D4, 2>(Fd);
  const double h = 1e-6;
  for (int k = 0; k < 4; ++k) {
    Mat<2> Fp = F, Fm = F;
    Fp(k / 2, k % 2) += h;
    Fm(k / 2, k % 2) -= h;
    const Mat<2> fd = (m.kirchhoff_stress<double, 2>(Fp) - m.kirchhoff_stress<double, 2>(Fm)) / (2.0 * h);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) EXPECT_NEAR(tau(i, j).d[k], fd(i, j), 1e-6 * 1.5e6);
  }
}

}  // namespace
