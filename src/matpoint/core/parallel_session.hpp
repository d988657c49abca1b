// MPI and PETSc for the life of a matpoint process (issue 23). In a build with -DMATPOINT_PETSC=ON the
// session initialises PETSc, which initialises MPI (a process started without mpirun is a singleton
// rank 0 of 1), and finalises both when it ends; in the serial default build it does nothing and the
// process is rank 0 of 1. Every rank runs the whole simulation; only the linear solves of an implicit
// run (solver.implicit.linear_solver "petsc", implicit/petsc_solver.hpp) are distributed, each rank
// assembling its own rows of the system. docs/user_guide.md "MPI and PETSc" says how to run.
#pragma once

#include <string>
#include <vector>

namespace matpoint {

class ParallelSession {
 public:
  /// petsc_options: PETSc's own options, the words after `--` on the command line (-ksp_type
  /// gmres -pc_type hypre ...); PETSC_OPTIONS in the environment works as well. Throws
  /// std::runtime_error when they are given to a build without PETSc, or PETSc fails to start.
  explicit ParallelSession(const std::vector<std::string>& petsc_options);
  ~ParallelSession();
  ParallelSession(const ParallelSession&) = delete;
  ParallelSession& operator=(const ParallelSession&) = delete;

  /// This process' rank and the number of ranks (0 and 1 without MPI).
  [[nodiscard]] static int rank();
  [[nodiscard]] static int size();
  /// Whether this build has PETSc (and MPI): solver.implicit.linear_solver "petsc" needs it.
  [[nodiscard]] static bool built_with_petsc();
  /// Whether PETSc is initialised in this process (a session exists, or a test started it).
  [[nodiscard]] static bool petsc_running();

 private:
  bool started_ = false;  // this session initialised PETSc (and finalises it)
};

}  // namespace matpoint
