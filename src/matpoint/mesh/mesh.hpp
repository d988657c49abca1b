// An unstructured finite element mesh of one element type (Aulisa & Capodaglio §4: the background
// grid and the FEM body are QUAD9 meshes), with named node sets, element sets and boundary faces.
// Built by the structured generators (structured_mesh.hpp), refine() or the Gmsh import.
#pragma once

#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "matpoint/core/types.hpp"
#include "matpoint/mesh/element_types.hpp"

namespace matpoint::mesh {

template <int D>
struct Mesh {
  ElementShape shape = D == 3 ? ElementShape::Hex8 : ElementShape::Q9;  // one element type per mesh
  int nodes_per_element = 0;
  std::vector<Vec<D>> nodes;             // coordinates (undeformed)
  std::vector<Index> connectivity;       // element e: [e * nodes_per_element, (e + 1) * nodes_per_element)
  std::vector<ElementVariant> variants;  // per element (BSpline2: where it lies); empty: all 0
  std::map<std::string, std::vector<Index>> node_sets;     // named boundaries, ascending node ids
  std::map<std::string, std::vector<Index>> element_sets;  // Gmsh physical groups of dimension D
  std::map<std::string, std::vector<std::pair<Index, int>>> boundary_faces;  // (element, local face)

  Index element_count() const {
    return nodes_per_element == 0 ? 0 : static_cast<Index>(connectivity.size()) / nodes_per_element;
  }
  Index node_count() const { return static_cast<Index>(nodes.size()); }
  std::span<const Index> element_nodes(Index e) const {
    return {connectivity.data() + e * nodes_per_element, static_cast<std::size_t>(nodes_per_element)};
  }
  /// The variant of element e's shape functions (element_types.hpp); 0 for Lagrange elements.
  ElementVariant element_variant(Index e) const {
    return variants.empty() ? ElementVariant{0} : variants[static_cast<std::size_t>(e)];
  }
};

/// The coordinates of element e's nodes (one row per local node) taken from `coordinates` (the
/// mesh's own nodes, or a moved configuration of the same size).
template <class E>
Eigen::Matrix<double, E::kNodes, E::kDim> element_coordinates(const Mesh<E::kDim>& mesh,
                                                              std::span<const Vec<E::kDim>> coordinates,
                                                              Index e) {
  Eigen::Matrix<double, E::kNodes, E::kDim> x;
  const Index* ids = mesh.connectivity.data() + e * E::kNodes;
  for (int i = 0; i < E::kNodes; ++i) x.row(i) = coordinates[ids[i]].transpose();
  return x;
}

/// Measure (area, volume) of the mesh in the given coordinates: sum over elements and Gauss points
/// of w det J with J = dx/dxi (3 x 3 Gauss or the degree-4 triangle rule: exact for Q9/T6 with
/// straight sides, and for curved ones to the rule's order).
template <int D>
double mesh_measure(const Mesh<D>& mesh, std::span<const Vec<D>> coordinates) {
  return visit_element_type_of_dim<D>(mesh.shape, [&](auto element) {
    using E = decltype(element);
    const auto& rule = gauss_rule<E>(E::kSimplex ? 4 : 3);
    double sum = 0.0;
    for (Index e = 0; e < mesh.element_count(); ++e) {
      const auto x = element_coordinates<E>(mesh, coordinates, e);
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        const Mat<D> jac = x.transpose() * E::gradients(rule.points[q], mesh.element_variant(e));
        sum += rule.weights[q] * jac.determinant();
      }
    }
    return sum;
  });
}

}  // namespace matpoint::mesh
