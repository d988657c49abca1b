// Element mesh .vtu output (mesh_vtu.hpp).
#include "matpoint/mesh/mesh_vtu.hpp"

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "matpoint/io/atomic_file.hpp"

namespace matpoint::mesh {

namespace {

/// Points padded to 3 components, one per line.
template <int D>
void write_vectors(std::ostringstream& out, const std::vector<Vec<D>>& v) {
  for (const auto& x : v) {
    for (int a = 0; a < 3; ++a) out << (a > 0 ? " " : "") << (a < D ? x[a] : 0.0);
    out << '\n';
  }
}

template <int D>
void write_cells(std::ostringstream& out, const Mesh<D>& mesh) {
  const Index n = mesh.element_count();
  out << "      <Cells>\n        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (Index e = 0; e < n; ++e) {
    for (Index node : mesh.element_nodes(e)) out << node << ' ';
    out << '\n';
  }
  out << "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (Index e = 1; e <= n; ++e) out << e * mesh.nodes_per_element << (e % 16 == 0 || e == n ? '\n' : ' ');
  out << "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  const int type = vtk_cell_type(mesh.shape);
  for (Index e = 1; e <= n; ++e) out << type << (e % 32 == 0 || e == n ? '\n' : ' ');
  out << "        </DataArray>\n      </Cells>\n";
}

/// The cells of a B-spline patch as a Q4 mesh through each cell's four mapped corners (not shared:
/// four points per element), and the displacement interpolated at them.
template <int D>
Mesh<D> bspline_cells(const Mesh<D>& mesh, const std::vector<Vec<D>>* displacement,
                      std::vector<Vec<D>>& corner_displacement) {
  Mesh<D> out;
  if constexpr (D == 2) {
    out.shape = ElementShape::Q4;
    out.nodes_per_element = Q4::kNodes;
    const auto corners = Q4::reference_nodes();
    for (Index e = 0; e < mesh.element_count(); ++e) {
      const auto ids = mesh.element_nodes(e);
      for (int c = 0; c < Q4::kNodes; ++c) {
        const auto N = BSpline2::values(corners.row(c).transpose(), mesh.element_variant(e));
        Vec<D> x = Vec<D>::Zero(), d = Vec<D>::Zero();
        for (int I = 0; I < BSpline2::kNodes; ++I) {
          const auto n = static_cast<std::size_t>(ids[static_cast<std::size_t>(I)]);
          x += N[I] * mesh.nodes[n];
          if (displacement != nullptr) d += N[I] * (*displacement)[n];
        }
        out.connectivity.push_back(out.node_count());
        out.nodes.push_back(x);
        corner_displacement.push_back(d);
      }
    }
  }
  return out;
}

}  // namespace

std::uint8_t vtk_cell_type(ElementShape shape) {
  switch (shape) {
    case ElementShape::T3:
      return 5;  // VTK_TRIANGLE
    case ElementShape::T6:
      return 22;  // VTK_QUADRATIC_TRIANGLE
    case ElementShape::Q4:
      return 9;  // VTK_QUAD
    case ElementShape::Q9:
      return 28;  // VTK_BIQUADRATIC_QUAD
    case ElementShape::Hex8:
      return 12;  // VTK_HEXAHEDRON
    case ElementShape::BSpline2:
      return 9;  // VTK_QUAD through the cell's corners (bspline_cells)
  }
  throw std::invalid_argument("vtk_cell_type: unknown element shape");
}

template <int D>
std::string mesh_vtu(const Mesh<D>& mesh, const std::vector<Vec<D>>* displacement) {
  if (displacement != nullptr && static_cast<Index>(displacement->size()) != mesh.node_count())
    throw std::invalid_argument("mesh_vtu: one displacement per node expected");
  if (mesh.shape == ElementShape::BSpline2) {
    std::vector<Vec<D>> corner_displacement;
    const Mesh<D> cells = bspline_cells(mesh, displacement, corner_displacement);
    return mesh_vtu(cells, displacement != nullptr ? &corner_displacement : nullptr);
  }
  std::ostringstream out;
  out << std::setprecision(17);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n"
      << "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" << mesh.node_count() << "\" NumberOfCells=\""
      << mesh.element_count() << "\">\n";
  if (displacement != nullptr) {
    out << "      <PointData Vectors=\"displacement\">\n"
        << "        <DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" "
           "format=\"ascii\">\n";
    write_vectors(out, *displacement);
    out << "        </DataArray>\n      </PointData>\n";
  }
  out << "      <CellData>\n        <DataArray type=\"Int64\" Name=\"element\" format=\"ascii\">\n";
  for (Index e = 0; e < mesh.element_count(); ++e) out << e << (e % 16 == 15 ? '\n' : ' ');
  out << "\n        </DataArray>\n      </CellData>\n";
  out << "      <Points>\n        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
  write_vectors(out, mesh.nodes);
  out << "        </DataArray>\n      </Points>\n";
  write_cells(out, mesh);
  out << "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out.str();
}

template <int D>
void write_mesh_vtu(const std::filesystem::path& file, const Mesh<D>& mesh,
                    const std::vector<Vec<D>>* displacement) {
  write_file_atomically(file, mesh_vtu(mesh, displacement));
}

template std::string mesh_vtu(const Mesh<2>&, const std::vector<Vec<2>>*);
template std::string mesh_vtu(const Mesh<3>&, const std::vector<Vec<3>>*);
template void write_mesh_vtu(const std::filesystem::path&, const Mesh<2>&, const std::vector<Vec<2>>*);
template void write_mesh_vtu(const std::filesystem::path&, const Mesh<3>&, const std::vector<Vec<3>>*);

}  // namespace matpoint::mesh
