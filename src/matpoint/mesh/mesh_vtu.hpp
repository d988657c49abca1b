// ParaView output of an element mesh: a VTK XML unstructured grid (.vtu, ASCII, 17 significant
// digits) with one cell per element, the element id as cell data and, if given, the node
// displacement as point data (ParaView's "Warp By Vector" then shows the deformed mesh). Our local
// node orders are VTK's: VTK_TRIANGLE (5), VTK_QUADRATIC_TRIANGLE (22: corners, then mid-edges
// 0-1, 1-2, 2-0), VTK_QUAD (9), VTK_BIQUADRATIC_QUAD (28: corners, mid-edges 0-1, 1-2, 2-3, 3-0,
// centre), VTK_HEXAHEDRON (12: bottom face, then top face, counter-clockwise). A B-spline patch
// (BSpline2), whose nodes are control points off the cells, is written as its cells: one VTK_QUAD
// per element through the four corners of the cell's map, the displacement interpolated there
// (the cells then show the deformed geometry, not the control net). ASCII because the
// compressed writer of io/vtk_writer.cpp keeps its appended-data helper private.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "matpoint/mesh/mesh.hpp"

namespace matpoint::mesh {

/// The VTK cell type of an element shape (numbers above).
std::uint8_t vtk_cell_type(ElementShape shape);

/// The .vtu text of the mesh (points: mesh.nodes); `displacement`, one per node, is written as the
/// point data "displacement" (3 components, zero-padded in 2-D).
template <int D>
std::string mesh_vtu(const Mesh<D>& mesh, const std::vector<Vec<D>>* displacement = nullptr);

/// Writes mesh_vtu atomically to `file` (io/atomic_file.hpp).
template <int D>
void write_mesh_vtu(const std::filesystem::path& file, const Mesh<D>& mesh,
                    const std::vector<Vec<D>>* displacement = nullptr);

extern template std::string mesh_vtu(const Mesh<2>&, const std::vector<Vec<2>>*);
extern template std::string mesh_vtu(const Mesh<3>&, const std::vector<Vec<3>>*);
extern template void write_mesh_vtu(const std::filesystem::path&, const Mesh<2>&, const std::vector<Vec<2>>*);
extern template void write_mesh_vtu(const std::filesystem::path&, const Mesh<3>&, const std::vector<Vec<3>>*);

}  // namespace matpoint::mesh
