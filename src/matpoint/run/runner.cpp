#include "matpoint/run/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "matpoint/core/subprocess.hpp"
#include "matpoint/explicit/explicit_solver.hpp"
#include "matpoint/implicit/implicit_mpm_solver.hpp"
#include "matpoint/implicit/meshfree/meshfree_solver.hpp"
#include "matpoint/mesh/gmsh_import.hpp"
#include "matpoint/mesh/refine.hpp"
#include "matpoint/mesh/structured_mesh.hpp"
#include "matpoint/run/run_loop.hpp"
#include "matpoint/shape/cpdi_stencils.hpp"
#include "matpoint/shape/tensor_bases.hpp"
#include "matpoint/shape/tensor_stencils.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace matpoint {

namespace run_loop_detail {

int current_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

std::vector<std::string> probe_columns(const Spec& spec) {
  std::vector<std::string> out;
  for (const auto& probe : spec.output.probes) {
    const auto names = probe_column_names(probe.name, spec.grid.dim);
    out.insert(out.end(), names.begin(), names.end());
  }
  return out;
}

}  // namespace run_loop_detail

namespace {

/// One explicit run of one basis through the shared loop.
template <int D, class Stencils>
RunResult run_with(const Spec& spec, const RunOptions& options) {
  ExplicitSolver<D, Stencils> solver(spec);  // may throw InputError: nothing written yet
  return run_loop<D>(spec, options, solver);
}

/// The basis's stencils, plain or (contact) shifted to each particle's velocity field.
template <int D, class Base>
RunResult run_with_fields(const Spec& spec, const RunOptions& options) {
  if constexpr (D > 1)
    if (spec.contact.enabled) return run_with<D, FieldStencils<D, Base>>(spec, options);
  return run_with<D, Base>(spec, options);
}

template <int D>
RunResult run_dim(const Spec& spec, const RunOptions& options) {
  switch (spec.solver.shape) {
    case ShapeKind::BSpline2:
      return run_with_fields<D, TensorStencils<D, QuadraticBSplineBasis>>(spec, options);
    case ShapeKind::BSpline3:
      return run_with_fields<D, TensorStencils<D, CubicBSplineBasis>>(spec, options);
    case ShapeKind::UGIMP:
      return run_with_fields<D, TensorStencils<D, UGimpBasis>>(spec, options);
    case ShapeKind::CpGIMP:
      return run_with_fields<D, TensorStencils<D, CpGimpBasis>>(spec, options);
    case ShapeKind::B2GIMP:
      return run_with_fields<D, TensorStencils<D, B2GimpBasis>>(spec, options);
    case ShapeKind::CPDI1:
      return run_with_fields<D, CpdiStencils<D, HatKernel, CpdiDomain::Parallelogram>>(spec, options);
    case ShapeKind::CPDI2:  // contact with tracked corners is refused by the input reader
      return run_with<D, CpdiStencils<D, HatKernel, CpdiDomain::Tracked>>(spec, options);
    case ShapeKind::B2CPDI:
      return run_with_fields<D, CpdiStencils<D, QuadraticKernel, CpdiDomain::Parallelogram>>(spec, options);
    case ShapeKind::Linear:
      break;
  }
  return run_with_fields<D, TensorStencils<D, LinearBasis>>(spec, options);
}

/// The input's mesh: structured (graded per axis) or read from a Gmsh file, refined mesh.refine times.
/// A structured T3 mesh is refined on its axes before the cells are split (each cell into 2^refine
/// x 2^refine cells, then into triangles by mesh.diagonal), so that its triangles stay the halves
/// (quarters) of the run's grid cells, where bodies[].placement "gauss" puts the particles.
template <int D>
mesh::Mesh<D> build_mesh(const MeshSpec& m) {
  mesh::Mesh<D> out;
  if (!m.file.empty()) {
    out = mesh::read_gmsh<D>(m.file, "mesh.file");
  } else {
    const bool triangles = m.element == MeshElement::T3;
    std::array<mesh::AxisSpacing, 3> axes;
    for (int a = 0; a < D; ++a) {
      auto& axis = axes[static_cast<std::size_t>(a)];
      const auto& lines = m.lines[static_cast<std::size_t>(a)];
      if (!lines.empty())
        axis.breaks = lines;  // mesh.lines
      else
        axis = mesh::AxisSpacing::geometric(m.min[a], m.max[a], m.cells[static_cast<std::size_t>(a)], m.ratio[a]);
      if (triangles) axis = axis.refined(m.refine);
    }
    if constexpr (D == 2) {
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
RunResult run_implicit_dim(const Spec& spec, const RunOptions& options) {
  mesh::Mesh<D> background = build_mesh<D>(spec.mesh);
  if (spec.solver.implicit.basis != ImplicitBasis::Mesh) {  // the Galerkin meshfree method
    implicit::MeshfreeSolver<D> solver(spec, background);   // may throw InputError
    return run_loop<D>(spec, options, solver);
  }
  return mesh::visit_element_type_of_dim<D>(background.shape, [&](auto element) -> RunResult {
    using E = decltype(element);
    implicit::ImplicitMpmSolver<E> solver(spec, std::move(background));  // may throw InputError
    return run_loop<D>(spec, options, solver);
  });
}

}  // namespace

RunResult run_explicit(const Spec& spec, const RunOptions& options) {
#ifdef _OPENMP
  if (options.threads > 0) omp_set_num_threads(options.threads);
#endif
  if (spec.solver.is_implicit())
    return spec.grid.dim == 3 ? run_implicit_dim<3>(spec, options) : run_implicit_dim<2>(spec, options);
  switch (spec.grid.dim) {
    case 1:
      return run_dim<1>(spec, options);
    case 3:
      return run_dim<3>(spec, options);
    default:
      return run_dim<2>(spec, options);
  }
}

std::string draw_plots(const std::filesystem::path& out_dir, const std::filesystem::path& scripts_dir) {
  return run_python_script(scripts_dir / "plot_history.py", {out_dir.string()});
}

}  // namespace matpoint
