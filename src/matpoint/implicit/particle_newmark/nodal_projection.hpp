// The particles' velocity and acceleration projected to the nodes for Iaconeta 2017's grid Newmark
// (§4.1, eqs. (38)-(41)): v~_I = sum_p N_I(x_p) m_p v_p / m_I with the lumped mass
// m_I = sum_p N_I(x_p) m_p, and a~_I likewise; the nodal predictor (43)-(44) turns them into each
// particle's known acceleration. Only for shape functions >= 0 (T3, Q4, Hex8): a dynamic
// implicit_ul run on quadratic elements is refused (docs/theory/implicit.md: quadratic shape
// functions make m_I near zero or negative, and a consistent (L2) projection, tried in session 14,
// gained energy on the incline slide from 0.1 s on). Nodes no particle touches get v~ = a~ = 0.
#pragma once

#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/mesh/mesh.hpp"

namespace matpoint::implicit {

/// The particle data the projection reads (host element and local coordinates per particle).
template <int D>
struct ProjectionInput {
  const std::vector<Index>& element;
  const std::vector<Vec<D>>& xi;
  const std::vector<double>& mass;
  const std::vector<Vec<D>>& velocity;
  const std::vector<Vec<D>>& acceleration;
};

/// Eqs. (38)-(41) with the lumped mass (E's shape functions must be >= 0).
template <class E>
void lumped_projection(const mesh::Mesh<E::kDim>& mesh, const ProjectionInput<E::kDim>& in,
                       std::vector<Vec<E::kDim>>& node_velocity,
                       std::vector<Vec<E::kDim>>& node_acceleration) {
  constexpr int D = E::kDim;
  const auto nodes = static_cast<std::size_t>(mesh.node_count());
  std::vector<double> mass(nodes, 0.0);
  node_velocity.assign(nodes, Vec<D>::Zero());
  node_acceleration.assign(nodes, Vec<D>::Zero());
  for (std::size_t p = 0; p < in.mass.size(); ++p) {  // serial: a scatter, cheap beside the assembly
    const auto N = E::values(in.xi[p], mesh.element_variant(in.element[p]));
    const auto element = mesh.element_nodes(in.element[p]);
    for (int I = 0; I < E::kNodes; ++I) {
      const auto n = static_cast<std::size_t>(element[static_cast<std::size_t>(I)]);
      const double w = N[I] * in.mass[p];
      mass[n] += w;
      node_velocity[n] += w * in.velocity[p];
      node_acceleration[n] += w * in.acceleration[p];
    }
  }
  for (std::size_t n = 0; n < nodes; ++n)
    if (mass[n] > 0.0) node_velocity[n] /= mass[n], node_acceleration[n] /= mass[n];
}

}  // namespace matpoint::implicit
