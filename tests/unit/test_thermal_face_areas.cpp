// The fixed-flux condition's nodal face areas (grid/thermal_conditions.hpp): the integral over the
// face of each node's grid function, per axis int_0^cells N_j(xi) dxi. Worked out by hand from the
// kernels and the edge fold of shape/kernels.hpp (u_-1 = 2 u_0 - u_1, so N_0 + 2 N_-1 and
// N_1 - N_-1 near xi = 0):
//  - hat: 1/2 at the edge nodes, 1 inside;
//  - quadratic B-spline (support 3 cells): int_0^0.5 N_-1 = int_1^1.5 (1.5 - r)^2 / 2 dr = 1/48, and
//    N_1 loses the same 1/48 below xi = 0: node 0 gets 1/2 + 2/48 = 13/24, node 1 1 - 2/48 = 23/24;
//  - cubic B-spline (support 4 cells): int_0^1 N_-1 = int_1^2 (2 - r)^3 / 6 dr = 1/24: node 0 gets
//    1/2 + 2/24 = 7/12, node 1 1 - 2/24 = 11/12;
// every other node 1, mirrored at the far edge, and the sum is the face's width in cells.
#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "matpoint/grid/thermal_conditions.hpp"

namespace matpoint {
namespace {

std::vector<double> expected_integrals(int cells, double edge, double next) {
  std::vector<double> out(static_cast<std::size_t>(cells) + 1, 1.0);
  out.front() = out.back() = edge;
  out[1] = out[out.size() - 2] = next;
  return out;
}

void expect_integrals(ShapeKind shape, double edge, double next) {
  constexpr int kCells = 8;
  const auto integrals = ThermalConditions<2>::grid_function_integrals(shape, kCells);
  const auto expected = expected_integrals(kCells, edge, next);
  ASSERT_EQ(integrals.size(), expected.size());
  for (std::size_t j = 0; j < expected.size(); ++j)
    EXPECT_NEAR(integrals[j], expected[j], 1e-14) << "node " << j;
  EXPECT_NEAR(std::accumulate(integrals.begin(), integrals.end(), 0.0), kCells, 1e-13);
}

TEST(ThermalFaceAreas, HatQuadraticAndCubicGridFunctionsIntegrateToTheirExactShares) {
  expect_integrals(ShapeKind::Linear, 0.5, 1.0);
  expect_integrals(ShapeKind::UGIMP, 0.5, 1.0);
  expect_integrals(ShapeKind::BSpline2, 13.0 / 24.0, 23.0 / 24.0);
  expect_integrals(ShapeKind::B2GIMP, 13.0 / 24.0, 23.0 / 24.0);
  expect_integrals(ShapeKind::BSpline3, 7.0 / 12.0, 11.0 / 12.0);
}

}  // namespace
}  // namespace matpoint
