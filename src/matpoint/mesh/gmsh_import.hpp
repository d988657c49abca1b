// Gmsh .msh import (formats 2 and 4) through the Gmsh SDK (Debian libgmsh-dev; gmsh_session.hpp), for the
// FEM bodies and background grids of the implicit family (Aulisa & Capodaglio §4: QUAD9 meshes;
// triangles and hexahedra for other geometries). One element type of dimension D per mesh:
//   Gmsh type 2 -> T3, 9 -> T6, 3 -> Q4, 10 -> Q9, 5 -> Hex8.
// Gmsh's local node order is ours (element_types.hpp); the importer checks it against
// getElementProperties' reference coordinates instead of assuming it, and turns clockwise
// elements (negative Jacobian at the centre) counter-clockwise. Physical groups of dimension D
// become element_sets, those of dimension D - 1 node_sets and boundary_faces (unnamed groups are
// named by their tag). Nodes are renumbered 0..n-1 in ascending Gmsh tag order (only the nodes of
// the D-dimensional elements are kept); elements keep Gmsh's order.
#pragma once

#include <string>

#include "matpoint/mesh/mesh.hpp"

namespace matpoint::mesh {

/// Reads `file`. Throws matpoint::InputError at `json_path` (naming the file and the problem) for a
/// missing, unreadable or corrupt file, no elements of dimension D, mixed or unsupported types.
template <int D>
Mesh<D> read_gmsh(const std::string& file, const std::string& json_path = "mesh.file");

extern template Mesh<2> read_gmsh(const std::string&, const std::string&);
extern template Mesh<3> read_gmsh(const std::string&, const std::string&);

}  // namespace matpoint::mesh
