// The Galerkin meshfree method (solver.basis "mls" / "lme") through the shared loop (run_by_solver.hpp).
#include "matpoint/implicit/meshfree/meshfree_solver.hpp"
#include "matpoint/run/run_by_solver.hpp"
#include "matpoint/run/run_loop.hpp"

namespace matpoint::run_by_solver {

template <int D>
RunResult run_meshfree(const Spec& spec, const RunOptions& options, const mesh::Mesh<D>& background) {
  implicit::MeshfreeSolver<D> solver(spec, background);  // may throw InputError
  return run_loop<D>(spec, options, solver);
}

template RunResult run_meshfree<2>(const Spec&, const RunOptions&, const mesh::Mesh<2>&);
template RunResult run_meshfree<3>(const Spec&, const RunOptions&, const mesh::Mesh<3>&);

}  // namespace matpoint::run_by_solver
