// The projection of the particles' velocity and acceleration to the nodes of Iaconeta 2017's grid
// Newmark (implicit/particle_newmark/nodal_projection.hpp, eqs. (38)-(41)): the lumped projection
// reproduces a constant field exactly (partition of unity), and a linear one only on average: at a
// node whose particles lie symmetrically about it (an interior node of a uniform Gauss-point
// placement), sum_p N_I(x_p) m_p x_p / m_I = x_I, so a linear field is exact there too.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "matpoint/implicit/particle_newmark/nodal_projection.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::implicit;
using mesh::Mesh;

Vec<2> velocity_field(const Vec<2>& x) {
  return {1.0 + 0.3 * x[0] - 0.2 * x[1] + 0.15 * x[0] * x[1] - 0.05 * x[0] * x[0],
          -0.4 + 0.1 * x[1] * x[1] + 0.25 * x[0]};
}
Vec<2> acceleration_field(const Vec<2>& x) { return {2.0 - x[0] + 0.5 * x[1] * x[1], 0.7 * x[0] * x[1] - 3.0}; }

/// Particles at `rule`'s points of every element, with masses that differ (1 + 0.1 p).
template <class E>
struct Particles {
  std::vector<Index> element;
  std::vector<Vec<2>> xi, x, v, a;
  std::vector<double> mass;
  Particles(const Mesh<2>& m, const mesh::QuadratureRule<2>& rule) {
    for (Index e = 0; e < m.element_count(); ++e)
      for (const auto& point : rule.points) {
        const auto N = E::values(point);
        Vec<2> position = Vec<2>::Zero();
        const auto nodes = m.element_nodes(e);
        for (int I = 0; I < E::kNodes; ++I) position += N[I] * m.nodes[static_cast<std::size_t>(nodes[I])];
        element.push_back(e), xi.push_back(point), x.push_back(position);
        v.push_back(velocity_field(position)), a.push_back(acceleration_field(position));
        mass.push_back(1.0 + 0.1 * static_cast<double>(mass.size()));
      }
  }
  ProjectionInput<2> input() const { return {element, xi, mass, v, a}; }
};

TEST(NodalProjection, LumpedQ4ReproducesAConstantField) {
  const auto m = mesh::structured_rectangle(mesh::ElementShape::Q4, mesh::AxisSpacing::uniform(0, 2, 2),
                                            mesh::AxisSpacing::uniform(0, 1, 1));
  Particles<mesh::Q4> p(m, mesh::gauss_rule<mesh::Q4>(2));
  for (auto& v : p.v) v = Vec<2>(0.25, -1.5);
  for (auto& a : p.a) a = Vec<2>(-9.81, 3.0);
  std::vector<Vec<2>> nv, na;
  lumped_projection<mesh::Q4>(m, p.input(), nv, na);
  for (std::size_t n = 0; n < nv.size(); ++n) {
    EXPECT_NEAR((nv[n] - Vec<2>(0.25, -1.5)).norm(), 0.0, 1e-14);
    EXPECT_NEAR((na[n] - Vec<2>(-9.81, 3.0)).norm(), 0.0, 1e-14);
  }
}

TEST(NodalProjection, LumpedQ4IsExactForALinearFieldAtSymmetricInteriorNodes) {
  const auto m = mesh::structured_rectangle(mesh::ElementShape::Q4, mesh::AxisSpacing::uniform(0, 3, 3),
                                            mesh::AxisSpacing::uniform(0, 3, 3));
  Particles<mesh::Q4> p(m, mesh::gauss_rule<mesh::Q4>(2));
  for (auto& mass : p.mass) mass = 1.0;  // equal masses: the symmetry holds
  for (std::size_t q = 0; q < p.v.size(); ++q) p.v[q] = Vec<2>(0.5 + 2.0 * p.x[q][0] - p.x[q][1], 3.0 * p.x[q][1]);
  std::vector<Vec<2>> nv, na;
  lumped_projection<mesh::Q4>(m, p.input(), nv, na);
  int interior = 0;
  for (std::size_t n = 0; n < m.nodes.size(); ++n) {
    const Vec<2>& x = m.nodes[n];
    if (x[0] <= 0 || x[0] >= 3 || x[1] <= 0 || x[1] >= 3) continue;
    ++interior;
    EXPECT_NEAR((nv[n] - Vec<2>(0.5 + 2.0 * x[0] - x[1], 3.0 * x[1])).norm(), 0.0, 1e-13) << n;
  }
  EXPECT_EQ(interior, 4);
}

}  // namespace
