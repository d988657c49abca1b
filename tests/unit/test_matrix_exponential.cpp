// The matrix exponential of the F update (core/matrix_exponential.hpp) against closed forms, for
// norms on both sides of the scaling threshold 1/4 and of every Taylor degree's limit:
//   rotation generator [[0, -t], [t, 0]]:  [[cos t, -sin t], [sin t, cos t]]
//   diagonal diag(a_i):                    diag(e^(a_i))
//   nilpotent N (strictly upper, 3 x 3):   I + N + N^2 / 2, N^2 = a c e_1 e_3^T
// Rounding: the polynomial's terms are added to a sum of norm about 1, so below the threshold the
// error is a few units of 2^-53 (tolerance 4 eps); above it, each of the s squarings doubles the
// relative error, so the tolerance is 4 eps (1 + 2^s) relative to the result.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "matpoint/core/matrix_exponential.hpp"

namespace {

using namespace matpoint;

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// The number of squarings for an infinity norm x: the smallest s >= 0 with x / 2^s <= 1/4.
int squarings_for(double x) {
  int s = 0;
  while (x > 0.25) x *= 0.5, ++s;
  return s;
}

double tolerance(double norm) { return 4.0 * kEps * (1.0 + std::ldexp(1.0, squarings_for(norm))); }

/// Infinity norms on both sides of each degree's limit (x^(m+1)/(m+1)! = 1e-17) and of 1/4, and
/// large ones that need several squarings.
std::vector<double> norms() {
  std::vector<double> x{0.0, 1e-12, 1e-3, 0.1, 0.25, 0.2500001, 0.3, 0.5, 1.0, 2.0, 5.0, 10.0};
  double factorial = 1.0;
  for (int m = 1; m <= 12; ++m) {
    factorial *= m + 1;
    const double limit = std::pow(1e-17 * factorial, 1.0 / (m + 1));
    x.push_back(limit * 0.999);
    x.push_back(limit * 1.001);
  }
  return x;
}

TEST(MatrixExponential, RotationGeneratorGivesTheRotation) {
  for (double t : norms()) {
    for (double sign : {1.0, -1.0}) {
      Mat<2> A;
      A << 0.0, -sign * t, sign * t, 0.0;
      Mat<2> R;
      R << std::cos(t), -sign * std::sin(t), sign * std::sin(t), std::cos(t);
      const Mat<2> E = matrix_exponential<2>(A);
      EXPECT_LE((E - R).cwiseAbs().maxCoeff(), tolerance(t)) << "t = " << sign * t;
    }
  }
}

TEST(MatrixExponential, DiagonalGivesTheExponentials) {
  const Vec<3> direction(1.0, -0.5, 0.3);  // infinity norm of diag(x direction) = x
  for (double x : norms()) {
    const Vec<3> a = x * direction;
    const Mat<3> E = matrix_exponential<3>(Mat<3>(a.asDiagonal()));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (i == j)
          EXPECT_NEAR(E(i, i), std::exp(a[i]), tolerance(x) * std::exp(x)) << "x = " << x << ", i = " << i;
        else
          EXPECT_EQ(E(i, j), 0.0);
    const Mat<2> E2 = matrix_exponential<2>(Mat<2>(a.template head<2>().asDiagonal()));
    EXPECT_NEAR(E2(0, 0), std::exp(a[0]), tolerance(x) * std::exp(x)) << "x = " << x;
    EXPECT_NEAR(E2(1, 1), std::exp(a[1]), tolerance(x) * std::exp(x)) << "x = " << x;
  }
}

TEST(MatrixExponential, NilpotentGivesTheFinitePolynomial) {
  for (double x : norms()) {
    const double a = 0.6 * x, b = 0.4 * x, c = -x;  // infinity norm |a| + |b| = x
    Mat<3> N = Mat<3>::Zero();
    N(0, 1) = a, N(0, 2) = b, N(1, 2) = c;
    Mat<3> expected = Mat<3>::Identity();
    expected(0, 1) = a, expected(0, 2) = b + 0.5 * a * c, expected(1, 2) = c;
    const Mat<3> E = matrix_exponential<3>(N);
    const double size = expected.cwiseAbs().rowwise().sum().maxCoeff();
    EXPECT_LE((E - expected).cwiseAbs().maxCoeff(), tolerance(x) * size) << "x = " << x;
    EXPECT_EQ(E(1, 0), 0.0);
    EXPECT_EQ(E(2, 0), 0.0);
    EXPECT_EQ(E(2, 1), 0.0);
    Mat<2> N2 = Mat<2>::Zero();  // 2 x 2: exp = I + N exactly
    N2(0, 1) = x;
    const Mat<2> E2 = matrix_exponential<2>(N2);
    EXPECT_LE(std::abs(E2(0, 1) - x), tolerance(x) * (1.0 + x)) << "x = " << x;
    EXPECT_LE(std::abs(E2(0, 0) - 1.0) + std::abs(E2(1, 1) - 1.0) + std::abs(E2(1, 0)), tolerance(x))
        << "x = " << x;
  }
}

TEST(MatrixExponential, ZeroGivesTheIdentityExactly) {
  EXPECT_EQ(matrix_exponential<2>(Mat<2>::Zero()), Mat<2>::Identity());
  EXPECT_EQ(matrix_exponential<3>(Mat<3>::Zero()), Mat<3>::Identity());
}

}  // namespace
