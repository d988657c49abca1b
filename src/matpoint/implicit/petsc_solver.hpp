// The PETSc back-end of LinearSolver: solver.implicit.linear_solver "petsc" (issue 23), in a build
// with -DMATPOINT_PETSC=ON (core/parallel_session.hpp starts PETSc and MPI).
//
// The matrix is a PETSc MPIAIJ matrix whose rows are split evenly over the ranks; each rank sets its
// own rows from the system it assembled (every rank assembles the whole system for now), with exact
// preallocation from the pattern, which is analysed again only when the pattern changes. The default
// Krylov method is GMRES(restart) with right preconditioning by additive Schwarz (overlap 1) with
// ILU(0) on each rank's block, to solver.implicit's tolerance (LinearSolverOptions); on 2 ranks block
// Jacobi/ILU(0) did not converge in 1000 iterations on the implicit MPM systems (issue 23 note).
// PETSc's own options override all of it (-ksp_type, -pc_type hypre, -pc_type lu
// -pc_factor_mat_solver_type mumps, ...). The solution is gathered to every rank.
#pragma once

#include <memory>

#include "matpoint/implicit/linear_solver.hpp"

namespace matpoint::implicit {

/// The PETSc solver, or nullptr in a build without PETSc. Throws std::runtime_error when PETSc is
/// not running (no ParallelSession).
std::unique_ptr<LinearSolver> make_petsc_solver(const LinearSolverOptions& options);

}  // namespace matpoint::implicit
