// The particles' velocity and acceleration projected to the nodes for Iaconeta 2017's grid Newmark
// (§4.1, eqs. (38)-(41)): v~_I, a~_I, which the nodal predictor (43)-(44) turns into each particle's
// known acceleration.
//   - lumped (the paper, linear elements T3/Q4/Hex8): v~_I = sum_p N_I(x_p) m_p v_p / m_I with
//     m_I = sum_p N_I(x_p) m_p (eqs. (38)-(41));
//   - consistent (quadratic elements Q9/T6): solve M v~ = sum_p N_I(x_p) m_p v_p with the consistent
//     mass M_IJ = sum_p m_p N_I(x_p) N_J(x_p). Quadratic shape functions are negative in places, so
//     the lumped m_I can be near zero or negative (a division that explodes); M is the Gram matrix of
//     the mass-weighted least-squares fit of the particle values by the element functions, symmetric
//     positive semi-definite, and the projection reproduces every field of the element space exactly
//     (the L2 projection). Directions of M's null space (functions that vanish at every particle,
//     e.g. an element with fewer particles than nodes) do not change sum_I N_I(x_p) v~_I at any
//     particle, which is all the step uses; they are fixed by a small shift delta = 1e-8 max_I M_II,
//     whose effect on the rest is removed by two steps of iterative refinement (the error falls by
//     delta / (lambda + delta) per step for an eigenvalue lambda of M).
// Nodes no particle touches get v~ = a~ = 0.
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
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
                       std::vector<Vec<E::kDim>>& node_velocity, std::vector<Vec<E::kDim>>& node_acceleration) {
  constexpr int D = E::kDim;
  const auto nodes = static_cast<std::size_t>(mesh.node_count());
  std::vector<double> mass(nodes, 0.0);
  node_velocity.assign(nodes, Vec<D>::Zero());
  node_acceleration.assign(nodes, Vec<D>::Zero());
  for (std::size_t p = 0; p < in.mass.size(); ++p) {  // serial: a scatter, cheap beside the assembly
    const auto N = E::values(in.xi[p]);
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

/// The consistent (L2) projection: M [v~ a~] = sum_p N m_p [v_p a_p] (see the top of the file).
template <class E>
void consistent_projection(const mesh::Mesh<E::kDim>& mesh, const ProjectionInput<E::kDim>& in,
                           std::vector<Vec<E::kDim>>& node_velocity,
                           std::vector<Vec<E::kDim>>& node_acceleration) {
  constexpr int D = E::kDim, K = E::kNodes;
  using ElementMass = Eigen::Matrix<double, K, K>;
  const auto nodes = static_cast<Eigen::Index>(mesh.node_count());
  // Element by element first (K^2 triplets per host element, not per particle).
  std::vector<ElementMass> element_mass(static_cast<std::size_t>(mesh.element_count()));
  std::vector<char> hosts(element_mass.size(), 0);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nodes, 2 * D);  // [sum N m v | sum N m a]
  for (std::size_t p = 0; p < in.mass.size(); ++p) {
    const auto e = static_cast<std::size_t>(in.element[p]);
    const auto values = E::values(in.xi[p]);
    Eigen::Matrix<double, K, 1> N;
    for (int I = 0; I < K; ++I) N[I] = values[I];
    if (hosts[e] == 0) element_mass[e].setZero(), hosts[e] = 1;
    element_mass[e].noalias() += in.mass[p] * N * N.transpose();
    const auto element = mesh.element_nodes(in.element[p]);
    for (int I = 0; I < K; ++I) {
      const auto n = static_cast<Eigen::Index>(element[static_cast<std::size_t>(I)]);
      rhs.row(n).head<D>() += N[I] * in.mass[p] * in.velocity[p].transpose();
      rhs.row(n).tail<D>() += N[I] * in.mass[p] * in.acceleration[p].transpose();
    }
  }
  std::vector<Eigen::Triplet<double, int>> triplets;
  std::vector<char> touched(static_cast<std::size_t>(nodes), 0);
  for (std::size_t e = 0; e < hosts.size(); ++e) {
    if (hosts[e] == 0) continue;
    const auto element = mesh.element_nodes(static_cast<Index>(e));
    for (int I = 0; I < K; ++I) {
      touched[static_cast<std::size_t>(element[static_cast<std::size_t>(I)])] = 1;
      for (int J = 0; J < K; ++J)
        triplets.emplace_back(static_cast<int>(element[static_cast<std::size_t>(I)]),
                              static_cast<int>(element[static_cast<std::size_t>(J)]), element_mass[e](I, J));
    }
  }
  Eigen::SparseMatrix<double> M(nodes, nodes);
  M.setFromTriplets(triplets.begin(), triplets.end());
  const double delta = 1e-8 * M.diagonal().cwiseAbs().maxCoeff();
  Eigen::SparseMatrix<double> shifted = M;
  for (Eigen::Index n = 0; n < nodes; ++n)  // the shift; untouched nodes: the identity (v~ = 0)
    shifted.coeffRef(n, n) += touched[static_cast<std::size_t>(n)] != 0 ? delta : 1.0;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(shifted);
  Eigen::MatrixXd x = ldlt.solve(rhs);
  for (int refinement = 0; refinement < 2; ++refinement) x += ldlt.solve(rhs - M * x);
  node_velocity.resize(static_cast<std::size_t>(nodes));
  node_acceleration.resize(static_cast<std::size_t>(nodes));
  for (Eigen::Index n = 0; n < nodes; ++n) {
    node_velocity[static_cast<std::size_t>(n)] = x.row(n).head<D>().transpose();
    node_acceleration[static_cast<std::size_t>(n)] = x.row(n).tail<D>().transpose();
  }
}

/// Lumped for linear elements (the paper), consistent for quadratic ones.
template <class E>
void project_to_nodes(const mesh::Mesh<E::kDim>& mesh, const ProjectionInput<E::kDim>& in,
                      std::vector<Vec<E::kDim>>& node_velocity, std::vector<Vec<E::kDim>>& node_acceleration) {
  if constexpr (E::kDegree >= 2)
    consistent_projection<E>(mesh, in, node_velocity, node_acceleration);
  else
    lumped_projection<E>(mesh, in, node_velocity, node_acceleration);
}

}  // namespace matpoint::implicit
