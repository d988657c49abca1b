// Element mesh .vtu output (mesh/mesh_vtu.hpp), read back by VTK's own XML reader (python3-vtk9)
// and by meshio: point, cell and type counts, the displacement array, and VTK's interpolation of
// each cell at parametric points against our isoparametric map at the same points (r = (xi + 1)/2
// for quads and hexes, r = xi for triangles), which checks that our local node order is VTK's.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "matpoint/core/subprocess.hpp"
#include "matpoint/mesh/mesh_vtu.hpp"
#include "matpoint/mesh/refine.hpp"
#include "matpoint/mesh/structured_mesh.hpp"

namespace {

using namespace matpoint;
using namespace matpoint::mesh;
namespace fs = std::filesystem;

const char* kReader = R"(import sys
import meshio
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

def check(path, points, cells, vtk_type, meshio_type, checks):
  reader = vtk.vtkXMLUnstructuredGridReader()
  reader.SetFileName(path)
  reader.Update()
  grid = reader.GetOutput()
  assert grid.GetNumberOfPoints() == int(points), grid.GetNumberOfPoints()
  assert grid.GetNumberOfCells() == int(cells), grid.GetNumberOfCells()
  assert all(grid.GetCellType(c) == int(vtk_type) for c in range(grid.GetNumberOfCells()))
  u = vtk_to_numpy(grid.GetPointData().GetArray("displacement"))
  assert u.shape == (int(points), 3), u.shape
  pts = vtk_to_numpy(grid.GetPoints().GetData())
  dim = 3 if int(vtk_type) == 12 else 2
  assert np.allclose(u[:, :dim], 0.1 * pts[:, :dim] + 0.01, rtol=0, atol=1e-15) and not u[:, dim:].any()
  m = meshio.read(path)
  assert len(m.points) == int(points) and m.cells[0].type == meshio_type and len(m.cells[0].data) == int(cells)
  assert np.array_equal(np.asarray(m.point_data["displacement"]), u)
  worst = 0.0
  for line in open(checks):
      e, r, s, t, x, y, z = map(float, line.split())
      cell = grid.GetCell(int(e))
      sub, found, weights = vtk.reference(0), [0.0, 0.0, 0.0], [0.0] * cell.GetNumberOfPoints()
      cell.EvaluateLocation(sub, [r, s, t], found, weights)
      worst = max(worst, float(np.max(np.abs(np.array(found) - [x, y, z]))))
  assert worst < 1e-12, (path, worst)

args = sys.argv[1:]
for k in range(0, len(args), 6):
  check(*args[k:k + 6])
)";

/// This test's scratch folder.
fs::path scratch() {
  const fs::path dir =
      fs::temp_directory_path() / ("matpoint_test_" + std::to_string(::getpid()) + "_mesh_vtu");
  fs::create_directories(dir);
  return dir;
}

/// Writes the mesh (as `name`.vtu) with a displacement field, and check points of our map; returns
/// the reader's arguments for it.
template <class E>
std::vector<std::string> prepare(const std::string& name, const Mesh<E::kDim>& m, const std::string& vtk_type,
                                 const std::string& meshio_type) {
  constexpr int D = E::kDim;
  const fs::path dir = scratch();
  std::vector<Vec<D>> u;
  for (const auto& x : m.nodes) u.push_back(0.1 * x + Vec<D>::Constant(0.01));
  write_mesh_vtu(dir / (name + ".vtu"), m, &u);
  std::ofstream checks(dir / (name + ".txt"));
  checks.precision(17);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (Index e = 0; e < m.element_count(); e += 3) {
    Vec<D> r;
    do {
      for (int a = 0; a < D; ++a) r[a] = unit(rng);
    } while (E::kSimplex && r.sum() > 1.0);
    const Vec<D> xi = E::kSimplex ? r : Vec<D>(2.0 * r.array() - 1.0);
    const Vec<D> x = element_coordinates<E>(m, m.nodes, e).transpose() * E::values(xi);
    checks << e;
    for (int a = 0; a < 3; ++a) checks << ' ' << (a < D ? r[a] : 0.0);
    for (int a = 0; a < 3; ++a) checks << ' ' << (a < D ? x[a] : 0.0);
    checks << '\n';
  }
  return {(dir / (name + ".vtu")).string(),
          std::to_string(m.node_count()),
          std::to_string(m.element_count()),
          vtk_type,
          meshio_type,
          (dir / (name + ".txt")).string()};
}

/// Runs the reader on all prepared meshes (one Python start-up).
void expect_readable(const std::vector<std::vector<std::string>>& meshes) {
  const fs::path dir = scratch();
  std::ofstream(dir / "read.py") << kReader;
  std::vector<std::string> args;
  for (const auto& m : meshes) args.insert(args.end(), m.begin(), m.end());
  EXPECT_EQ(run_python_script(dir / "read.py", args), "");
  fs::remove_all(dir);
}

/// 2 x 1 Q9 (or Q4) mesh with a curved shared edge, refined once.
Mesh<2> curved(ElementShape shape) {
  Mesh<2> m = structured_rectangle(shape, AxisSpacing::uniform(0, 2, 2), AxisSpacing::uniform(0, 1, 1));
  if (shape == ElementShape::Q9) m.nodes[m.element_nodes(0)[5]][0] += 0.2;
  return refine(m, 1);
}

/// Two triangles on the unit square (T6: the shared diagonal's mid-node moved), refined once.
Mesh<2> triangles(bool quadratic) {
  Mesh<2> t;
  t.shape = quadratic ? ElementShape::T6 : ElementShape::T3;
  t.nodes_per_element = quadratic ? 6 : 3;
  t.nodes = {Vec<2>(0, 0), Vec<2>(1, 0), Vec<2>(1, 1), Vec<2>(0, 1)};
  t.connectivity = {0, 1, 2, 0, 2, 3};
  if (quadratic) {
    t.nodes.insert(t.nodes.end(),
                   {Vec<2>(0.5, 0), Vec<2>(1, 0.5), Vec<2>(0.6, 0.45), Vec<2>(0.5, 1), Vec<2>(0, 0.5)});
    t.connectivity = {0, 1, 2, 4, 5, 6, 0, 2, 3, 6, 7, 8};
  }
  return refine(t, 1);
}

TEST(MeshVtu, QuadrilateralsReadBackByVtkAndMeshio) {
  expect_readable({prepare<Q9>("q9", curved(ElementShape::Q9), "28", "quad9"),
                   prepare<Q4>("q4", curved(ElementShape::Q4), "9", "quad")});
}

TEST(MeshVtu, TrianglesAndHexahedraReadBackByVtkAndMeshio) {
  const Mesh<3> box = structured_box(AxisSpacing::uniform(0, 2, 2), AxisSpacing::geometric(0, 1, 2, 2.0),
                                     AxisSpacing::uniform(0, 1, 1));
  expect_readable({prepare<T3>("t3", triangles(false), "5", "triangle"),
                   prepare<T6>("t6", triangles(true), "22", "triangle6"),
                   prepare<Hex8>("hex8", box, "12", "hexahedron")});
}

}  // namespace
