// Sparse linear solvers behind one interface, generic over the formulation. The Jacobians of the
// implicit MPM are nonsymmetric (the receding-contact correction, Aulisa & Capodaglio §5), so all
// back-ends are general LU or Krylov methods:
//   umfpack          SuiteSparse UMFPACK through Eigen::UmfPackLU (default; direct, robust)
//   klu              SuiteSparse KLU through Eigen::KLU (direct, for circuit-like sparse matrices)
//   bicgstab_ilut    Eigen BiCGSTAB with an incomplete LU (IncompleteLUT) preconditioner
//   gmres_ilut       Eigen GMRES (unsupported/Eigen/IterativeSolvers) with IncompleteLUT; the
//                    authors' code used PETSc GMRES + ILU with rtol 1e-10 (extraction A16)
//   petsc            PETSc KSP on the MPI ranks (implicit/petsc_solver.hpp; a build with PETSc)
// The symbolic analysis (ordering, ILUT pattern) runs only when the pattern changes (a new
// SparseAssembly::pattern_version()); every Newton iteration refactorises numerically.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "matpoint/implicit/sparse_assembly.hpp"

namespace matpoint::implicit {

enum class LinearSolverKind { Umfpack, Klu, BicgstabIlut, GmresIlut, Petsc };

struct LinearSolverOptions {
  LinearSolverKind kind = LinearSolverKind::Umfpack;
  double relative_tolerance = 1e-10;  // Krylov: |b - K x| / |b|
  int max_iterations = 1000;          // Krylov
  int gmres_restart = 50;
  double ilut_drop_tolerance = 1e-8;
  int ilut_fill_factor = 20;
};

/// Time and counts, for the run summary (share of a step spent in the linear algebra).
struct LinearSolverStats {
  long analyses = 0, factorizations = 0, solves = 0, krylov_iterations = 0;
  double analyze_seconds = 0.0, factorize_seconds = 0.0, solve_seconds = 0.0;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// Prepares to solve with K: the symbolic analysis when pattern_version differs from the last
  /// call's, then the numerical factorisation. false (with message()) on a singular or failed
  /// factorisation; never throws on numerical trouble.
  bool factorize(const SparseMatrix& K, std::uint64_t pattern_version);
  /// x = K^-1 b with the K of the last factorize(). false (with message()) when it failed.
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  [[nodiscard]] const std::string& message() const { return message_; }
  [[nodiscard]] const LinearSolverStats& stats() const { return stats_; }

 protected:
  virtual bool analyze(const SparseMatrix& K) = 0;
  virtual bool factorize_numeric(const SparseMatrix& K) = 0;
  virtual bool solve_with(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  std::string message_;
  LinearSolverStats stats_;

 private:
  std::uint64_t analyzed_version_ = 0;
  bool analyzed_ = false;
};

/// Throws std::runtime_error for "petsc" in a build without PETSc, or without PETSc running.
std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverOptions& options = {});
/// "umfpack", "klu", "bicgstab_ilut", "gmres_ilut", "petsc".
std::string_view linear_solver_name(LinearSolverKind kind);

}  // namespace matpoint::implicit
