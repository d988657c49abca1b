// Logistic-regression contact normal (logistic_normal.hpp; Nairn 2026 §3.2, extraction §2.5).
// The fit depends on positions only through beta . x and |beta|^2, so it is equivariant under
// rotations: for a point set mirror-symmetric about the plane x . e = 0 (labels by the sign of
// x . e) the normal is e exactly, and rotating the whole set rotates the normal with it. Gauss-
// Newton keeps the symmetry at every iterate, so these hold to round-off (1e-10).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "matpoint/explicit/logistic_normal.hpp"

namespace {

using namespace matpoint;

/// 2 x 2 particles per cell in the 3 x 3 cells around a node, labelled -1 left of x = gap / 2.
std::vector<LabelledPoint<2>> split_lattice(double gap) {
  std::vector<LabelledPoint<2>> points;
  for (int i = -6; i < 6; ++i)
    for (int j = -6; j < 6; ++j) {
      const double x = 0.25 + 0.5 * i, y = 0.25 + 0.5 * j;
      if (std::abs(x) < gap) continue;
      points.push_back({Vec<2>(x, y), x < 0 ? -1.0 : 1.0});
    }
  return points;
}

TEST(LogisticNormal, SymmetricSplitGivesTheSplittingNormal) {
  const auto points = split_lattice(0.0);
  const auto fit = logistic_normal<2>(std::span<const LabelledPoint<2>>(points));
  ASSERT_TRUE(fit.found);
  EXPECT_NEAR(fit.normal[0], 1.0, 1e-12);
  EXPECT_NEAR(fit.normal[1], 0.0, 1e-12);
  EXPECT_GE(fit.iterations, 1);
  EXPECT_LE(fit.iterations, 15);
}

TEST(LogisticNormal, RotatingThePointsRotatesTheNormal) {
  for (double degrees : {10.0, 30.0, 45.0, 71.0, 160.0}) {
    const double a = degrees * std::numbers::pi / 180.0;
    Mat<2> rotation;
    rotation << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    auto points = split_lattice(0.6);  // separated sets with a gap, as for bodies not yet touching
    for (auto& p : points) p.x = rotation * p.x;
    const auto fit = logistic_normal<2>(std::span<const LabelledPoint<2>>(points));
    ASSERT_TRUE(fit.found) << degrees;
    EXPECT_NEAR(fit.normal[0], std::cos(a), 1e-10) << degrees;
    EXPECT_NEAR(fit.normal[1], std::sin(a), 1e-10) << degrees;
  }
}

TEST(LogisticNormal, ThreeDimensionalSplitAlongATiltedAxis) {
  const Vec<3> axis = Vec<3>(1.0, 2.0, -2.0) / 3.0;
  const Mat<3> rotation = Eigen::Quaterniond::FromTwoVectors(Vec<3>::UnitX(), axis).toRotationMatrix();
  std::vector<LabelledPoint<3>> points;
  for (int i = -4; i < 4; ++i)
    for (int j = -4; j < 4; ++j)
      for (int k = -4; k < 4; ++k) {
        const Vec<3> x(0.25 + 0.5 * i, 0.25 + 0.5 * j, 0.25 + 0.5 * k);
        points.push_back({rotation * x, x[0] < 0 ? -1.0 : 1.0});
      }
  const auto fit = logistic_normal<3>(std::span<const LabelledPoint<3>>(points));
  ASSERT_TRUE(fit.found);
  EXPECT_NEAR((fit.normal - axis).norm(), 0.0, 1e-10);
}

TEST(LogisticNormal, CurvedInterfaceNormalPointsAcrossTheContact) {
  // Two disks of radius 3 cells touching at the origin; the node sits 0.3 cells above the contact
  // point. By the mirror symmetry about x = 0 the normal is e_x although the node is off-axis,
  // where the volume gradients of each disk tilt by the curvature.
  std::vector<LabelledPoint<2>> points;
  for (int i = -12; i < 12; ++i)
    for (int j = -12; j < 12; ++j) {
      const Vec<2> x(0.25 + 0.5 * i, 0.25 + 0.5 * j);
      const Vec<2> left(-3.0, 0.0), right(3.0, 0.0);
      const Vec<2> relative = x - Vec<2>(0.0, 0.3);
      if ((x - left).norm() < 3.0 && std::abs(relative[0]) < 2.0 && std::abs(relative[1]) < 2.0)
        points.push_back({relative, -1.0});
      if ((x - right).norm() < 3.0 && std::abs(relative[0]) < 2.0 && std::abs(relative[1]) < 2.0)
        points.push_back({relative, 1.0});
    }
  const auto fit = logistic_normal<2>(std::span<const LabelledPoint<2>>(points));
  ASSERT_TRUE(fit.found);
  EXPECT_NEAR(fit.normal[0], 1.0, 1e-10);
  EXPECT_NEAR(fit.normal[1], 0.0, 1e-10);
}

TEST(LogisticNormal, OneLabelOnlyHasNoNormal) {
  std::vector<LabelledPoint<2>> points{{Vec<2>(0.25, 0.25), 1.0}, {Vec<2>(-0.25, 0.5), 1.0}};
  EXPECT_FALSE(logistic_normal<2>(std::span<const LabelledPoint<2>>(points)).found);
  EXPECT_FALSE(logistic_normal<2>(std::span<const LabelledPoint<2>>()).found);
}

}  // namespace
