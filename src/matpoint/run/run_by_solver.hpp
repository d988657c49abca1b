// The runs of each solver family, each compiled in its own translation unit (the explicit run of
// each dimension instantiates every basis; the implicit runs every element type): runner.cpp
// dispatches to them. Splitting them keeps each unit small, so they build in parallel and a change
// to one solver's headers rebuilds only its unit.
#pragma once

#include "matpoint/mesh/mesh.hpp"
#include "matpoint/run/runner.hpp"

namespace matpoint::run_by_solver {

/// The explicit run of dimension D (run_explicit_1d.cpp, _2d.cpp, _3d.cpp).
template <int D>
RunResult run_explicit_of_dim(const Spec& spec, const RunOptions& options);

/// The input's mesh: structured (graded per axis) or read from a Gmsh file, refined mesh.refine
/// times (run_implicit.cpp).
template <int D>
mesh::Mesh<D> build_mesh(const MeshSpec& m);

/// The implicit MPMs on the mesh's elements (run_implicit.cpp) and the Galerkin meshfree method
/// (run_meshfree.cpp).
template <int D>
RunResult run_implicit_mpm(const Spec& spec, const RunOptions& options, mesh::Mesh<D> background);
template <int D>
RunResult run_meshfree(const Spec& spec, const RunOptions& options, const mesh::Mesh<D>& background);

}  // namespace matpoint::run_by_solver
