// Structured T3 meshes (mesh/structured_mesh.hpp, mesh/triangle_pattern.hpp) and the particles at
// their triangles' Gauss points (particles/generators.cpp, bodies[].placement "gauss" on a T3
// mesh: Iaconeta 2017 §5.2's three material points per cell). Expected values from geometry: the
// triangles tile the rectangle (areas sum to it, every interior edge shared by two triangles), the
// side faces cover each side once, and the 3-point rule (barycentric (2/3, 1/6, 1/6)) integrates
// quadratics exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

#include "matpoint/mesh/structured_mesh.hpp"
#include "matpoint/particles/generators.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::mesh;

constexpr std::array<TrianglePattern, 4> kPatterns{TrianglePattern::Rising, TrianglePattern::Falling,
                                                   TrianglePattern::Alternating, TrianglePattern::Crossed};

double signed_area(const Mesh<2>& m, Index e) {
  const auto n = m.element_nodes(e);
  const Vec<2> a = m.nodes[n[0]], b = m.nodes[n[1]], c = m.nodes[n[2]];
  return 0.5 * ((b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0]);
}

TEST(StructuredTriangles, TileTheRectangleConformingly) {
  const AxisSpacing x = AxisSpacing::uniform(-1.0, 2.0, 5), y = AxisSpacing::geometric(0.0, 1.0, 3, 1.5);
  for (const TrianglePattern pattern : kPatterns) {
    SCOPED_TRACE(static_cast<int>(pattern));
    const Mesh<2> m = structured_rectangle(ElementShape::T3, x, y, pattern);
    const bool crossed = pattern == TrianglePattern::Crossed;
    EXPECT_EQ(m.shape, ElementShape::T3);
    EXPECT_EQ(m.element_count(), 15 * (crossed ? 4 : 2));
    EXPECT_EQ(m.node_count(), 6 * 4 + (crossed ? 15 : 0));
    double area = 0.0;
    std::map<std::pair<Index, Index>, int> edges;  // undirected edge -> how many triangles hold it
    for (Index e = 0; e < m.element_count(); ++e) {
      EXPECT_GT(signed_area(m, e), 0.0) << "element " << e << " is not counter-clockwise";
      area += signed_area(m, e);
      const auto n = m.element_nodes(e);
      for (int k = 0; k < 3; ++k) ++edges[std::minmax(n[k], n[(k + 1) % 3])];
    }
    EXPECT_NEAR(area, 3.0 * 1.0, 1e-12);
    int boundary_edges = 0;
    for (const auto& [edge, count] : edges) {
      EXPECT_LE(count, 2);
      boundary_edges += count == 1;
    }
    EXPECT_EQ(boundary_edges, 2 * (5 + 3));  // the rectangle's perimeter in cell sides
    // Each side: one face per cell along it, both nodes on the side; the node sets as for Q4.
    const std::map<std::string, std::pair<int, double>> sides{
        {"left", {0, -1.0}}, {"right", {0, 2.0}}, {"bottom", {1, 0.0}}, {"top", {1, 1.0}}};
    for (const auto& [name, where] : sides) {
      const auto& faces = m.boundary_faces.at(name);
      EXPECT_EQ(static_cast<int>(faces.size()), where.first == 0 ? 3 : 5) << name;
      const auto local_faces = T3::faces();
      for (const auto& [e, f] : faces)
        for (int k : local_faces[static_cast<std::size_t>(f)])
          EXPECT_DOUBLE_EQ(m.nodes[m.element_nodes(e)[k]][where.first], where.second) << name;
      EXPECT_EQ(m.node_sets.at(name).size(), where.first == 0 ? 4u : 6u) << name;
    }
  }
}

TEST(StructuredTriangles, AlternatingDiagonalsFormACheckerboard) {
  const Mesh<2> m = structured_rectangle(ElementShape::T3, AxisSpacing::uniform(0.0, 2.0, 2),
                                         AxisSpacing::uniform(0.0, 2.0, 2), TrianglePattern::Alternating);
  ASSERT_EQ(m.element_count(), 8);
  // Cell (i, j) holds elements 2 (2 j + i) and the next; a rising diagonal joins its (x-, y-) and
  // (x+, y+) corners, so both triangles hold both.
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const Index low = j * 3 + i, high = (j + 1) * 3 + i + 1;  // lattice ids of the rising diagonal
      int holding = 0;
      for (Index e = 2 * (2 * j + i); e < 2 * (2 * j + i) + 2; ++e) {
        const auto n = m.element_nodes(e);
        holding += std::count(n.begin(), n.end(), low) + std::count(n.begin(), n.end(), high) == 2;
      }
      EXPECT_EQ(holding, (i + j) % 2 == 0 ? 2 : 0) << "cell " << i << ", " << j;
    }
}

/// A box body on a uniform grid of 4 x 3 cells of 0.5 x 0.25.
std::pair<Grid<2>, BodySpec> box_on_grid(TrianglePattern pattern) {
  Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.25), {4, 3}, 1);
  BodySpec body;
  body.shape = BodyShape::Box;
  body.min = {0.0, 0.0, 0.0};
  body.max = {2.0, 0.75, 0.0};
  body.triangle_points = pattern;
  return {grid, body};
}

TEST(StructuredTriangles, GaussPlacementPutsThreeParticlesInEachTriangle) {
  for (const TrianglePattern pattern : kPatterns) {
    SCOPED_TRACE(static_cast<int>(pattern));
    auto [grid, body] = box_on_grid(pattern);
    MaterialSpec material;
    material.density = 2.0;
    ParticleSet<2> particles;
    const std::size_t added = generate_body<2>(body, 0, material, grid, particles);
    const Mesh<2> m = structured_rectangle(ElementShape::T3, AxisSpacing::uniform(0.0, 2.0, 4),
                                           AxisSpacing::uniform(0.0, 0.75, 3), pattern);
    ASSERT_EQ(added, static_cast<std::size_t>(3 * m.element_count()));
    // The rule integrates 1, x, y, x^2, x y, y^2 exactly over the box [0, 2] x [0, 0.75].
    std::array<double, 6> sums{};
    double mass = 0.0;
    for (std::size_t p = 0; p < added; ++p) {
      const double v = particles.volume0[p], px = particles.x[p][0], py = particles.x[p][1];
      const std::array<double, 6> f{1.0, px, py, px * px, px * py, py * py};
      for (std::size_t k = 0; k < 6; ++k) sums[k] += v * f[k];
      mass += particles.mass[p];
    }
    const double a = 2.0, b = 0.75;
    const std::array<double, 6> exact{
        a * b, a * a * b / 2, a * b * b / 2, a * a * a * b / 3, a * a * b * b / 4, a * b * b * b / 3};
    for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(sums[k], exact[k], 1e-12) << "moment " << k;
    EXPECT_NEAR(mass, 2.0 * a * b, 1e-12);
  }
}

TEST(StructuredTriangles, GaussPlacementKeepsOnlyPointsInsideTheShape) {
  auto [grid, body] = box_on_grid(TrianglePattern::Rising);
  body.shape = BodyShape::Disk;
  body.center = {1.0, 0.375, 0.0};
  body.radius = 0.3;
  MaterialSpec material;
  ParticleSet<2> particles;
  const std::size_t added = generate_body<2>(body, 0, material, grid, particles);
  ASSERT_GT(added, 0u);
  ASSERT_LT(added, 72u);  // not the whole box
  for (std::size_t p = 0; p < added; ++p) EXPECT_LE((particles.x[p] - Vec<2>(1.0, 0.375)).norm(), 0.3);
}

}  // namespace
