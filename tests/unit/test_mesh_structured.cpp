// Structured meshes and uniform refinement (mesh/structured_mesh.hpp, mesh/refine.hpp) against the
// background grid of Aulisa & Capodaglio's Test A (extraction §11.1: x in [-2, 22] with 20 columns,
// y layers bottom -> top 0.867209, 1.084011, 1.355013, 1.693767 (ratio 1.25); 20 2^J x 4 2^J
// elements, 82 689 nodes at J = 4, bottom element height 0.8672 / 2^J), refinement against direct
// generation of the finer mesh, and curved Q9 areas against Archimedes' parabolic segment
// (2/3 base x height).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "matpoint/mesh/refine.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::mesh;

Mesh<2> test_a_mesh() {
  return structured_rectangle(ElementShape::Q9, AxisSpacing::uniform(-2.0, 22.0, 20),
                              AxisSpacing::geometric(-1.6, 3.4, 4, 1.25));
}

TEST(StructuredMesh, GeometricGradingGivesTheTestALayers) {
  const AxisSpacing y = AxisSpacing::geometric(-1.6, 3.4, 4, 1.25);
  const double layers[] = {0.867209, 1.084011, 1.355013, 1.693767};  // extraction §11.1 ([CODE] mesh)
  ASSERT_EQ(y.cells(), 4);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(y.breaks[k + 1] - y.breaks[k], layers[k], 1e-6);
  const AxisSpacing z = AxisSpacing::layers(-1.6, layers);
  EXPECT_NEAR(z.breaks.back(), 3.4, 4e-6);
}

/// Element-node coordinates of every element, sorted by the element's first node: a numbering-free
/// description of a mesh's geometry.
template <int D>
std::vector<std::vector<double>> element_geometry(const Mesh<D>& m) {
  std::vector<std::vector<double>> out;
  for (Index e = 0; e < m.element_count(); ++e) {
    std::vector<double> g;
    for (Index n : m.element_nodes(e))
      for (int a = 0; a < D; ++a) g.push_back(m.nodes[n][a]);
    out.push_back(g);
  }
  // Sort by the first node rounded to 1e-9 (y, then x), so rounding does not reorder elements.
  auto key = [](const std::vector<double>& g) {
    std::vector<long long> k;
    for (auto it = g.begin(); it != g.begin() + D; ++it) k.insert(k.begin(), std::llround(*it * 1e9));
    return k;
  };
  std::sort(out.begin(), out.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
  return out;
}

/// Two meshes with the same elements (local order included) up to renumbering, to tolerance.
template <int D>
void expect_same_geometry(const Mesh<D>& a, const Mesh<D>& b) {
  ASSERT_EQ(a.element_count(), b.element_count());
  ASSERT_EQ(a.node_count(), b.node_count());
  const auto ga = element_geometry(a), gb = element_geometry(b);
  double worst = 0.0;
  for (std::size_t e = 0; e < ga.size(); ++e)
    for (std::size_t k = 0; k < ga[e].size(); ++k) worst = std::max(worst, std::abs(ga[e][k] - gb[e][k]));
  EXPECT_LT(worst, 1e-12);
  for (const auto& [name, set] : b.node_sets) EXPECT_EQ(a.node_sets.at(name).size(), set.size()) << name;
  for (const auto& [name, faces] : b.boundary_faces)
    EXPECT_EQ(a.boundary_faces.at(name).size(), faces.size()) << name;
}

/// Every node set "side" holds exactly the nodes on that side, and every boundary face's nodes lie on it.
template <class E>
void expect_complete_sides(const Mesh<E::kDim>& m) {
  const char* names[3][2] = {{"left", "right"}, {"bottom", "top"}, {"back", "front"}};
  for (int a = 0; a < E::kDim; ++a) {
    double lo = 1e300, hi = -1e300;
    for (const auto& x : m.nodes) lo = std::min(lo, x[a]), hi = std::max(hi, x[a]);
    for (int side = 0; side < 2; ++side) {
      const double at = side == 0 ? lo : hi;
      std::vector<Index> expected;
      for (Index n = 0; n < m.node_count(); ++n)
        if (std::abs(m.nodes[n][a] - at) < 1e-12) expected.push_back(n);
      EXPECT_EQ(m.node_sets.at(names[a][side]), expected) << names[a][side];
      std::set<Index> on_faces;
      const auto faces = E::faces();
      for (const auto& [e, f] : m.boundary_faces.at(names[a][side]))
        for (int i : faces[f]) on_faces.insert(m.element_nodes(e)[i]);
      EXPECT_EQ(std::vector<Index>(on_faces.begin(), on_faces.end()), expected) << names[a][side];
    }
  }
}

TEST(StructuredMesh, TestAMeshCountsAndBottomHeightUnderRefinement) {
  Mesh<2> m = test_a_mesh();
  // Bottom layer height: h_0 = 5 (r - 1)/(r^4 - 1), r = 1.25 (geometric series), = 0.867209... .
  const double h0 = 5.0 * 0.25 / (std::pow(1.25, 4) - 1.0);
  for (int j = 0; j <= 4; ++j) {
    if (j > 0) m = refine(m, 1);
    const Index nx = 20 << j, ny = 4 << j;
    EXPECT_EQ(m.element_count(), nx * ny);
    EXPECT_EQ(m.node_count(), (2 * nx + 1) * (2 * ny + 1));
    for (const auto& [e, f] : m.boundary_faces.at("bottom")) {
      double top = -1e300;
      for (Index n : m.element_nodes(e)) top = std::max(top, m.nodes[n][1]);
      EXPECT_NEAR(top - (-1.6), h0 / (1 << j), 1e-12);
      EXPECT_NEAR(top - (-1.6), 0.8672 / (1 << j), 1e-4);  // the paper's rounding
    }
    EXPECT_EQ(static_cast<Index>(m.boundary_faces.at("bottom").size()), nx);
    EXPECT_EQ(static_cast<Index>(m.boundary_faces.at("left").size()), ny);
  }
  EXPECT_EQ(m.element_count(), 20480);  // extraction §11.1, J = 4
  EXPECT_EQ(m.node_count(), 82689);
  expect_complete_sides<Q9>(m);
  EXPECT_NEAR(mesh_measure<2>(m, m.nodes), 24.0 * 5.0, 1e-10);
}

TEST(StructuredMesh, RefiningEqualsGeneratingTheFinerMeshDirectly) {
  const AxisSpacing x = AxisSpacing::uniform(-2.0, 22.0, 5), y = AxisSpacing::geometric(-1.6, 3.4, 3, 1.25);
  for (ElementShape shape : {ElementShape::Q4, ElementShape::Q9}) {
    const Mesh<2> coarse = structured_rectangle(shape, x, y);
    for (int j = 1; j <= 2; ++j) {
      const Mesh<2> fine = structured_rectangle(shape, x.refined(j), y.refined(j));
      expect_same_geometry(refine(coarse, j), fine);
    }
  }
  const AxisSpacing z = AxisSpacing::geometric(0.0, 1.0, 2, 0.5);
  const Mesh<3> box = structured_box(x, y, z);
  const Mesh<3> fine = structured_box(x.refined(1), y.refined(1), z.refined(1));
  const Mesh<3> refined = refine(box, 1);
  expect_same_geometry(refined, fine);
  expect_complete_sides<Hex8>(refined);
  expect_complete_sides<Hex8>(box);
  EXPECT_NEAR(mesh_measure<3>(refined, refined.nodes), 24.0 * 5.0 * 1.0, 1e-10);
}

TEST(StructuredMesh, RefinementKeepsParentNodeIdsAndCarriesElementSets) {
  Mesh<2> m =
      structured_rectangle(ElementShape::Q9, AxisSpacing::uniform(0, 2, 2), AxisSpacing::uniform(0, 1, 1));
  m.element_sets["right_half"] = {1};
  m.node_sets["corner"] = {0};  // a set without boundary faces: only nodes whose corners are all in it
  const Mesh<2> r = refine(m, 1);
  for (Index n = 0; n < m.node_count(); ++n) EXPECT_EQ(r.nodes[n], m.nodes[n]);
  EXPECT_EQ(r.element_sets.at("right_half"), (std::vector<Index>{4, 5, 6, 7}));
  EXPECT_EQ(r.node_sets.at("corner"), std::vector<Index>{0});
  for (Index e : r.element_sets.at("right_half"))
    for (Index n : r.element_nodes(e)) EXPECT_GE(r.nodes[n][0], 1.0);
}

TEST(StructuredMesh, CurvedQ9ChildrenStayOnTheParentGeometry) {
  // 2 x 1 Q9 on [0, 2] x [0, 1]; the shared edge x = 1 has its mid-side node moved by delta in x:
  // element 0 gains a parabolic segment of area (2/3) * 1 * delta, element 1 loses it (Archimedes).
  Mesh<2> m =
      structured_rectangle(ElementShape::Q9, AxisSpacing::uniform(0, 2, 2), AxisSpacing::uniform(0, 1, 1));
  const double delta = 0.17;
  const Index mid = m.element_nodes(0)[5];  // right mid-side of element 0 = left of element 1
  ASSERT_EQ(m.element_nodes(1)[7], mid);
  m.nodes[mid][0] += delta;
  m.element_sets["left"] = {0};
  const Mesh<2> r = refine(m, 3);
  Mesh<2> part = r;
  part.connectivity.clear();
  for (Index e : r.element_sets.at("left"))
    for (Index n : r.element_nodes(e)) part.connectivity.push_back(n);
  const double left = mesh_measure<2>(part, part.nodes);
  EXPECT_NEAR(left, 1.0 + 2.0 / 3.0 * delta, 1e-13);
  EXPECT_NEAR(mesh_measure<2>(r, r.nodes), 2.0, 1e-13);
  // The 2 * 2^3 + 1 refined nodes of the curved edge lie on its parabola x = 1 + 4 delta y (1 - y).
  int on_curve = 0;
  for (const auto& x : r.nodes) on_curve += std::abs(x[0] - 1.0 - 4.0 * delta * x[1] * (1.0 - x[1])) < 1e-14;
  EXPECT_EQ(on_curve, 17);
}

TEST(StructuredMesh, TrianglesRefineIntoFourAndMergeSharedEdges) {
  for (ElementShape shape : {ElementShape::T3, ElementShape::T6}) {
    Mesh<2> m;
    m.shape = shape;
    const bool quadratic = shape == ElementShape::T6;
    m.nodes_per_element = quadratic ? 6 : 3;
    m.nodes = {Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(1, 1), Vec<2>(0, 1)};
    m.connectivity = {0, 1, 2, 0, 2, 3};
    if (quadratic) {
      m.nodes.insert(m.nodes.end(),
                     {Vec<2>(0.5, 0), Vec<2>(1, 0.5), Vec<2>(0.5, 0.5), Vec<2>(0.5, 1), Vec<2>(0, 0.5)});
      m.connectivity = {0, 1, 2, 4, 5, 6, 0, 2, 3, 6, 7, 8};
    }
    m.boundary_faces["bottom"] = {{0, 0}};
    m.node_sets["bottom"] = quadratic ? std::vector<Index>{0, 1, 4} : std::vector<Index>{0, 1};
    const Mesh<2> r = refine(m, 2);
    EXPECT_EQ(r.element_count(), 32);
    const int per_side = quadratic ? 9 : 5;  // lattice of the 4 x 4 refined square
    EXPECT_EQ(r.node_count(), per_side * per_side);
    EXPECT_NEAR(mesh_measure<2>(r, r.nodes), 1.0, 1e-14);
    EXPECT_EQ(r.boundary_faces.at("bottom").size(), 4u);
    EXPECT_EQ(static_cast<int>(r.node_sets.at("bottom").size()), per_side);
    for (Index n : r.node_sets.at("bottom")) EXPECT_EQ(r.nodes[n][1], 0.0);
  }
}

}  // namespace
