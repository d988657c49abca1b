// The implicit MPMs on the input's mesh (run_by_solver.hpp): the mesh, and the particle-Newmark
// or updated-Lagrangian solver of its element type through the shared loop.
#include "matpoint/implicit/implicit_mpm_solver.hpp"
#include "matpoint/mesh/gmsh_import.hpp"
#include "matpoint/mesh/refine.hpp"
#include "matpoint/mesh/structured_mesh.hpp"
#include "matpoint/run/run_by_solver.hpp"
#include "matpoint/run/run_loop.hpp"

namespace matpoint::run_by_solver {

/// build_mesh (run_by_solver.hpp):
/// A structured T3 mesh is refined on its axes before the cells are split (each cell into 2^refine
/// x 2^refine cells, then into triangles by mesh.diagonal), so that its triangles stay the halves
/// (quarters) of the run's grid cells, where bodies[].placement "gauss" puts the particles. A
/// B-spline patch likewise: refining it is splitting its equal cells (knot insertion).
template <int D>
mesh::Mesh<D> build_mesh(const MeshSpec& m) {
  mesh::Mesh<D> out;
  if (!m.file.empty()) {
    out = mesh::read_gmsh<D>(m.file, "mesh.file");
  } else {
    const bool triangles = m.element == MeshElement::T3;
    const bool splines = m.element == MeshElement::BSpline2;
    std::array<mesh::AxisSpacing, 3> axes;
    for (int a = 0; a < D; ++a) {
      auto& axis = axes[static_cast<std::size_t>(a)];
      const auto& lines = m.lines[static_cast<std::size_t>(a)];
      if (!lines.empty())
        axis.breaks = lines;  // mesh.lines
      else
        axis = mesh::AxisSpacing::geometric(m.min[a], m.max[a], m.cells[static_cast<std::size_t>(a)],
                                            m.ratio[a]);
      if (triangles || splines) axis = axis.refined(m.refine);
    }
    if constexpr (D == 2) {
      if (splines) return mesh::structured_bspline2(axes[0], axes[1]);
      const auto shape = triangles                      ? mesh::ElementShape::T3
                         : m.element == MeshElement::Q4 ? mesh::ElementShape::Q4
                                                        : mesh::ElementShape::Q9;
      out = mesh::structured_rectangle(shape, axes[0], axes[1], m.diagonal);
    } else {
      out = mesh::structured_box(axes[0], axes[1], axes[2]);
    }
    if (triangles) return out;
  }
  return m.refine > 0 ? mesh::refine(out, m.refine) : out;
}

template <int D>
RunResult run_implicit_mpm(const Spec& spec, const RunOptions& options, mesh::Mesh<D> background) {
  return mesh::visit_element_type_of_dim<D>(background.shape, [&](auto element) -> RunResult {
    using E = decltype(element);
    implicit::ImplicitMpmSolver<E> solver(spec, std::move(background));  // may throw InputError
    return run_loop<D>(spec, options, solver);
  });
}

template mesh::Mesh<2> build_mesh<2>(const MeshSpec&);
template mesh::Mesh<3> build_mesh<3>(const MeshSpec&);
template RunResult run_implicit_mpm<2>(const Spec&, const RunOptions&, mesh::Mesh<2>);
template RunResult run_implicit_mpm<3>(const Spec&, const RunOptions&, mesh::Mesh<3>);

}  // namespace matpoint::run_by_solver
