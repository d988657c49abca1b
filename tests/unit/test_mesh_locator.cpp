// Point location (mesh/point_locator.hpp): points generated from a known (element, xi) through the
// element's isoparametric map must come back to that element and xi, on a curved Q9 mesh (moved
// interior mid-side nodes), T6 and Hex8 meshes; points on shared faces and corners go to the lowest
// element id among the elements holding the node (extraction A21), points on the domain boundary are
// found, points outside give nullopt; concurrent calls agree with serial ones. The speed on the
// Test A mesh at J = 2 (extraction §11.1) is printed.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <random>

#include "matpoint/mesh/point_locator.hpp"
#include "matpoint/mesh/refine.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::mesh;

/// Test A background mesh (extraction §11.1) refined j times.
Mesh<2> test_a_mesh(int j) {
  return refine(structured_rectangle(ElementShape::Q9, AxisSpacing::uniform(-2.0, 22.0, 20),
                                     AxisSpacing::geometric(-1.6, 3.4, 4, 1.25)),
                j);
}

/// Moves every interior mid-side node of a structured Q9 mesh by up to 0.15 of the smallest element
/// size (deterministic pseudo-random), which curves the interior edges.
Mesh<2> curved_q9() {
  Mesh<2> m = structured_rectangle(ElementShape::Q9, AxisSpacing::uniform(0.0, 3.0, 6),
                                   AxisSpacing::geometric(0.0, 2.0, 4, 1.3));
  std::vector<bool> boundary(m.node_count(), false);
  for (const auto& [name, set] : m.node_sets)
    for (Index n : set) boundary[n] = true;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<bool> moved(m.node_count(), false);
  for (Index e = 0; e < m.element_count(); ++e)
    for (int i = 4; i < 8; ++i) {
      const Index n = m.element_nodes(e)[i];
      if (boundary[n] || moved[n]) continue;
      moved[n] = true;
      m.nodes[n] += 0.15 * 0.37 * Vec<2>(u(rng), u(rng));  // smallest element: 0.5 x 0.37
    }
  return m;
}

/// Random points from random (element, xi strictly inside) pairs: locate must return them.
template <class E>
void expect_round_trip(const Mesh<E::kDim>& m, int count) {
  constexpr int D = E::kDim;
  const PointLocator<D> locator(m, m.nodes);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst_x = 0.0, worst_xi = 0.0;
  for (int k = 0; k < count; ++k) {
    const Index e = static_cast<Index>(u(rng) * m.element_count()) % m.element_count();
    Vec<D> xi;
    do {
      for (int a = 0; a < D; ++a) xi[a] = E::kSimplex ? u(rng) : 2.0 * u(rng) - 1.0;
    } while (!E::contains(xi, -1e-6));
    const auto nodes = element_coordinates<E>(m, m.nodes, e);
    const Vec<D> x = nodes.transpose() * E::values(xi);
    const auto loc = locator.locate(x, k % 2 == 0 ? -1 : (e + 1) % m.element_count());
    ASSERT_TRUE(loc.has_value());
    ASSERT_EQ(loc->element, e);
    worst_xi = std::max(worst_xi, (loc->xi - xi).template lpNorm<Eigen::Infinity>());
    worst_x =
        std::max(worst_x, (nodes.transpose() * E::values(loc->xi) - x).template lpNorm<Eigen::Infinity>());
  }
  EXPECT_LT(worst_x, 1e-12);
  EXPECT_LT(worst_xi, 1e-10);
}

TEST(PointLocator, RoundTripOnCurvedQ9) { expect_round_trip<Q9>(curved_q9(), 4000); }

TEST(PointLocator, RoundTripOnT6AndHex8) {
  Mesh<2> t;
  t.shape = ElementShape::T6;
  t.nodes_per_element = 6;
  t.nodes = {Vec<2>(0, 0),   Vec<2>(2, 0),     Vec<2>(2, 1), Vec<2>(0, 1),  Vec<2>(1, 0),
             Vec<2>(2, 0.5), Vec<2>(1.1, 0.6), Vec<2>(1, 1), Vec<2>(0, 0.5)};
  t.connectivity = {0, 1, 2, 4, 5, 6, 0, 2, 3, 6, 7, 8};  // the shared diagonal's mid-node moved
  expect_round_trip<T6>(refine(t, 2), 2000);
  const Mesh<3> box = structured_box(AxisSpacing::uniform(0, 2, 4), AxisSpacing::geometric(0, 1, 3, 1.5),
                                     AxisSpacing::uniform(-1, 0, 2));
  expect_round_trip<Hex8>(box, 2000);
}

TEST(PointLocator, NodesAndSharedFacesGoToTheLowestElementId) {
  const Mesh<2> m = curved_q9();
  const PointLocator<2> locator(m, m.nodes);
  // The lowest id of the elements holding each node, from the connectivity.
  std::vector<Index> lowest(m.node_count(), -1);
  for (Index e = m.element_count() - 1; e >= 0; --e)
    for (Index n : m.element_nodes(e)) lowest[n] = e;
  for (Index n = 0; n < m.node_count(); ++n) {
    // Nodes: corners shared by up to 4 elements, mid-sides (on curved shared edges) by 2, on the
    // domain boundary by 1 or 2.
    const auto loc = locator.locate(m.nodes[n], m.element_count() - 1);
    ASSERT_TRUE(loc.has_value()) << n;
    EXPECT_EQ(loc->element, lowest[n]) << n;
  }
}

TEST(PointLocator, BoundaryToleranceAndOutsidePoints) {
  const Mesh<2> m = test_a_mesh(1);
  const PointLocator<2> locator(m, m.nodes);
  // On the boundary (x = -2 left side, y = -1.6 plane) and within rounding of it: found.
  EXPECT_TRUE(locator.locate(Vec<2>(-2.0, 0.3)).has_value());
  EXPECT_TRUE(locator.locate(Vec<2>(5.3, -1.6)).has_value());
  EXPECT_TRUE(locator.locate(Vec<2>(5.3, -1.6 - 1e-13)).has_value());
  EXPECT_TRUE(locator.locate(Vec<2>(22.0 + 1e-13, 3.4)).has_value());
  // Outside: nullopt, near and far.
  EXPECT_FALSE(locator.locate(Vec<2>(5.3, -1.6 - 1e-6)).has_value());
  EXPECT_FALSE(locator.locate(Vec<2>(-2.001, 0.0)).has_value());
  EXPECT_FALSE(locator.locate(Vec<2>(100.0, 100.0)).has_value());
  EXPECT_FALSE(locator.locate(Vec<2>(std::nan(""), 0.0)).has_value());
  // A point on the shared vertical face x = -0.8 between columns 0 and 1 of the bottom row: the
  // left element (lower id) wins, at xi = +1.
  const auto loc = locator.locate(Vec<2>(-0.8, -1.5));
  ASSERT_TRUE(loc.has_value());
  EXPECT_EQ(loc->element,
            1);  // row 0: parent 0's children 0 (left) and 1 (right); x = -0.8 is child 1's right face
  EXPECT_NEAR(loc->xi[0], 1.0, 1e-12);
}

TEST(PointLocator, UpdateFollowsAMovedConfiguration) {
  // The mesh moved by the shear x += 0.3 y: a point x0 of the reference configuration is found at
  // x0 + (0.3 y0, 0) in the same element with the same xi after update().
  const Mesh<2> m = test_a_mesh(1);
  PointLocator<2> locator(m, m.nodes);
  std::vector<Vec<2>> moved = m.nodes;
  for (auto& x : moved) x[0] += 0.3 * x[1];
  const Vec<2> x0(3.37, 0.41);
  const auto before = locator.locate(x0);
  locator.update(moved);
  const auto after = locator.locate(Vec<2>(x0[0] + 0.3 * x0[1], x0[1]));
  ASSERT_TRUE(before.has_value() && after.has_value());
  EXPECT_EQ(after->element, before->element);
  EXPECT_LT((after->xi - before->xi).norm(), 1e-12);
  EXPECT_FALSE(locator.locate(Vec<2>(x0[0], -1.7)).has_value());  // below the plane y = -1.6
}

TEST(PointLocator, EmptyMeshHoldsNoPoint) {
  Mesh<2> empty;
  empty.nodes_per_element = 9;
  const PointLocator<2> locator(empty, empty.nodes);
  EXPECT_FALSE(locator.locate(Vec<2>(0.0, 0.0)).has_value());
}

TEST(PointLocator, ConcurrentCallsAgreeWithSerialAndSpeedOnTestAJ2) {
  const Mesh<2> m = test_a_mesh(2);
  const PointLocator<2> locator(m, m.nodes);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> ux(-2.0, 22.0), uy(-1.6, 3.4);
  const int count = 50000;
  std::vector<Vec<2>> points(count);
  for (auto& p : points) p = Vec<2>(ux(rng), uy(rng));
  std::vector<Index> serial(count), parallel(count);
  const auto start = std::chrono::steady_clock::now();
  for (int p = 0; p < count; ++p) {
    const auto loc = locator.locate(points[p]);
    serial[p] = loc ? loc->element : -1;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "[ INFO     ] Test A J = 2 (%lld Q9, %d x %d bins): %d points in %.4f s, %.3g locations/s (1 thread)\n",
      static_cast<long long>(m.element_count()), locator.bins()[0], locator.bins()[1], count, seconds,
      count / seconds);
#pragma omp parallel for schedule(dynamic, 256)
  for (int p = 0; p < count; ++p) {
    const auto loc = locator.locate(points[p]);
    parallel[p] = loc ? loc->element : -1;
  }
  EXPECT_EQ(serial, parallel);
  EXPECT_EQ(std::count(serial.begin(), serial.end(), -1), 0);  // all points lie in the mesh
}

}  // namespace
