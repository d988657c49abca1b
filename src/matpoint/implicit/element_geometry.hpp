// Isoparametric geometry of one element, shared by every implicit formulation: the Jacobian of the
// map x(xi) = sum_I x_I N_I(xi) and the shape-function gradients with respect to x.
#pragma once

#include "matpoint/core/types.hpp"
#include "matpoint/mesh/element_types.hpp"

namespace matpoint::implicit {

/// Node coordinates of one element, one row per local node.
template <class E>
using NodeMatrix = Eigen::Matrix<double, E::kNodes, E::kDim>;
/// Shape-function gradients, one row per local node: G(I, j) = dN_I / dx_j.
template <class E>
using GradientMatrix = Eigen::Matrix<double, E::kNodes, E::kDim>;

/// dN/dx at the local point xi of the element with nodes x and variant `variant` (the mesh's
/// element_variant; 0 for Lagrange elements); det_jacobian gets det(dx/dxi).
template <class E>
GradientMatrix<E> physical_gradients(const NodeMatrix<E>& x, const Vec<E::kDim>& xi,
                                     mesh::ElementVariant variant, double* det_jacobian = nullptr) {
  const GradientMatrix<E> g = E::gradients(xi, variant);
  const Mat<E::kDim> jacobian = x.transpose() * g;  // J_ij = dx_i / dxi_j
  if (det_jacobian != nullptr) *det_jacobian = jacobian.determinant();
  return g * jacobian.inverse();  // dN/dx_k = sum_j dN/dxi_j (J^-1)_jk
}

/// The rows of the global node coordinates that belong to one element.
template <class E, class Coordinates, class NodeIds>
NodeMatrix<E> gather_nodes(const Coordinates& coordinates, const NodeIds& element_nodes) {
  NodeMatrix<E> x;
  for (int i = 0; i < E::kNodes; ++i)
    x.row(i) = coordinates[static_cast<std::size_t>(element_nodes[i])].transpose();
  return x;
}

}  // namespace matpoint::implicit
