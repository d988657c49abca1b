// ParaView output of FE bodies (Aulisa & Capodaglio §4): their elements as a .vtu of their own,
// written at every particle output beside the particles in results.pvd (`fe_bodies_NNNNNN.vtu`):
// the undeformed nodes with the nodal displacement as point data (ParaView's "Warp By Vector" shows
// the deformed bodies), as mesh/mesh_vtu.hpp writes an element mesh.
#pragma once

#include <filesystem>
#include <vector>

#include "matpoint/fem/fe_body.hpp"
#include "matpoint/mesh/mesh_vtu.hpp"

namespace matpoint::fem {

/// The FE bodies' elements as a mesh of their own (nodes renumbered) and their nodes' displacement.
template <class E>
void write_fe_bodies_vtu(const std::filesystem::path& file, const mesh::Mesh<E::kDim>& mesh,
                         const FeBodies<E>& fe) {
  constexpr int D = E::kDim;
  mesh::Mesh<D> part;
  part.shape = mesh.shape;
  part.nodes_per_element = mesh.nodes_per_element;
  std::vector<Index> renumbered(static_cast<std::size_t>(mesh.node_count()), -1);
  std::vector<Vec<D>> displacement;
  for (Index k = 0; k < fe.element_count(); ++k)
    for (const Index n : mesh.element_nodes(fe.mesh_element(k))) {
      Index& id = renumbered[static_cast<std::size_t>(n)];
      if (id < 0) {
        id = part.node_count();
        part.nodes.push_back(mesh.nodes[static_cast<std::size_t>(n)]);
        displacement.push_back(fe.displacement[static_cast<std::size_t>(n)]);
      }
      part.connectivity.push_back(id);
    }
  mesh::write_mesh_vtu<D>(file, part, &displacement);
}

}  // namespace matpoint::fem
