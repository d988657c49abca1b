// The projection of the particles' velocity and acceleration to the nodes of Iaconeta 2017's grid
// Newmark (implicit/particle_newmark/nodal_projection.hpp), against exact fields:
//   - consistent (Q9, T6): the L2 projection onto the element space reproduces every field of that
//     space, so particle values of a biquadratic (Q9) or quadratic (T6) field give its exact nodal
//     values when the particles determine the element functions (3 x 3 Gauss points per Q9, the
//     degree-4 rule's 6 points per T6), to round-off;
//   - with too few particles (2 x 2 per Q9: M is singular) the projected field still equals the
//     exact one at every particle, which is all the step uses, and stays finite;
//   - lumped (Q4, the paper's eqs. (38)-(41)): a constant field exactly (partition of unity).
#include <gtest/gtest.h>

#include <cmath>

#include "matpoint/implicit/particle_newmark/nodal_projection.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::implicit;
using mesh::Mesh;

Vec<2> velocity_field(const Vec<2>& x) {  // in Q9's and T6's space (degree <= 2 in each / in total)
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

/// The largest |projected - exact| over the nodes that carry a value.
double nodal_error(const Mesh<2>& m, const std::vector<Vec<2>>& nv, const std::vector<Vec<2>>& na) {
  double error = 0.0;
  for (std::size_t n = 0; n < m.nodes.size(); ++n) {
    error = std::max(error, (nv[n] - velocity_field(m.nodes[n])).norm());
    error = std::max(error, (na[n] - acceleration_field(m.nodes[n])).norm());
  }
  return error;
}

TEST(NodalProjection, ConsistentQ9ReproducesABiquadraticField) {
  const auto m = mesh::structured_rectangle(mesh::ElementShape::Q9, mesh::AxisSpacing::uniform(0, 3, 3),
                                            mesh::AxisSpacing::uniform(-1, 1, 2));
  const Particles<mesh::Q9> p(m, mesh::gauss_rule<mesh::Q9>(3));
  std::vector<Vec<2>> nv, na;
  project_to_nodes<mesh::Q9>(m, p.input(), nv, na);  // Q9: the consistent projection
  EXPECT_LT(nodal_error(m, nv, na), 1e-12);
}

TEST(NodalProjection, ConsistentT6ReproducesAQuadraticField) {
  Mesh<2> m;  // the unit square as two T6: (0,0) (1,0) (0,1) and (1,1) (0,1) (1,0), mid-side nodes
  m.shape = mesh::ElementShape::T6;
  m.nodes_per_element = 6;
  m.nodes = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}, {1, 1}, {0.5, 1}, {1, 0.5}};
  m.connectivity = {0, 1, 2, 3, 4, 5, 6, 2, 1, 7, 4, 8};
  const Particles<mesh::T6> p(m, mesh::gauss_rule<mesh::T6>(4));
  std::vector<Vec<2>> nv, na;
  project_to_nodes<mesh::T6>(m, p.input(), nv, na);
  EXPECT_LT(nodal_error(m, nv, na), 1e-12);
}

TEST(NodalProjection, TooFewParticlesStillExactAtEveryParticle) {
  const auto m = mesh::structured_rectangle(mesh::ElementShape::Q9, mesh::AxisSpacing::uniform(0, 3, 3),
                                            mesh::AxisSpacing::uniform(-1, 1, 2));
  const Particles<mesh::Q9> p(m, mesh::gauss_rule<mesh::Q9>(2));  // 4 points for 9 functions
  std::vector<Vec<2>> nv, na;
  consistent_projection<mesh::Q9>(m, p.input(), nv, na);
  double at_particles = 0.0;
  for (std::size_t q = 0; q < p.mass.size(); ++q) {
    const auto N = mesh::Q9::values(p.xi[q]);
    const auto nodes = m.element_nodes(p.element[q]);
    Vec<2> v = Vec<2>::Zero(), a = Vec<2>::Zero();
    for (int I = 0; I < 9; ++I) v += N[I] * nv[static_cast<std::size_t>(nodes[I])], a += N[I] * na[static_cast<std::size_t>(nodes[I])];
    at_particles = std::max({at_particles, (v - p.v[q]).norm(), (a - p.a[q]).norm()});
  }
  EXPECT_LT(at_particles, 1e-9);  // the shift's residue after refinement, relative to |v| ~ 1
  for (std::size_t n = 0; n < nv.size(); ++n) EXPECT_TRUE(nv[n].allFinite() && na[n].allFinite());
  std::printf("2 x 2 particles per Q9: |sum N v~ - v_p| <= %.1e at the particles\n", at_particles);
}

TEST(NodalProjection, LumpedQ4ReproducesAConstantField) {
  const auto m = mesh::structured_rectangle(mesh::ElementShape::Q4, mesh::AxisSpacing::uniform(0, 2, 2),
                                            mesh::AxisSpacing::uniform(0, 1, 1));
  Particles<mesh::Q4> p(m, mesh::gauss_rule<mesh::Q4>(2));
  for (auto& v : p.v) v = Vec<2>(0.25, -1.5);
  for (auto& a : p.a) a = Vec<2>(-9.81, 3.0);
  std::vector<Vec<2>> nv, na;
  project_to_nodes<mesh::Q4>(m, p.input(), nv, na);  // Q4: the lumped projection
  for (std::size_t n = 0; n < nv.size(); ++n) {
    EXPECT_NEAR((nv[n] - Vec<2>(0.25, -1.5)).norm(), 0.0, 1e-14);
    EXPECT_NEAR((na[n] - Vec<2>(-9.81, 3.0)).norm(), 0.0, 1e-14);
  }
}

}  // namespace
