#include "matpoint/implicit/petsc_solver.hpp"

#ifdef MATPOINT_HAS_PETSC

#include <petscksp.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "matpoint/core/parallel_session.hpp"

namespace matpoint::implicit {

namespace {

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

class PetscSolver final : public LinearSolver {
 public:
  explicit PetscSolver(const LinearSolverOptions& options) : options_(options) {
    if (!ParallelSession::petsc_running())
      throw std::runtime_error("linear solver \"petsc\": PETSc is not initialised (no ParallelSession)");
  }
  ~PetscSolver() override { release(); }
  PetscSolver(const PetscSolver&) = delete;
  PetscSolver& operator=(const PetscSolver&) = delete;
  [[nodiscard]] std::string_view name() const override { return "petsc"; }

 protected:
  bool analyze(const SparseMatrix& K) override {
    release();
    const auto n = static_cast<PetscInt>(K.rows());
    if (!ok(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, n, &b_), "vector") ||
        !ok(VecDuplicate(b_, &x_), "vector") || !ok(VecGetOwnershipRange(b_, &first_row_, &end_row_), "rows") ||
        !ok(VecScatterCreateToAll(x_, &to_all_, &x_all_), "gather"))
      return false;
    rows_ = K;
    return create_matrix(n) && create_krylov();
  }

  bool factorize_numeric(const SparseMatrix& K) override {
    rows_ = K;  // the same pattern: only the values change
    for (PetscInt r = first_row_; r < end_row_; ++r) {
      const int begin = rows_.outerIndexPtr()[r], count = rows_.outerIndexPtr()[r + 1] - begin;
      if (!ok(MatSetValues(a_, 1, &r, count, rows_.innerIndexPtr() + begin, rows_.valuePtr() + begin,
                           INSERT_VALUES),
              "matrix values"))
        return false;
    }
    return ok(MatAssemblyBegin(a_, MAT_FINAL_ASSEMBLY), "matrix assembly") &&
           ok(MatAssemblyEnd(a_, MAT_FINAL_ASSEMBLY), "matrix assembly") &&
           ok(KSPSetOperators(ksp_, a_, a_), "operators");
  }

  bool solve_with(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    PetscScalar* local = nullptr;
    if (!ok(VecGetArray(b_, &local), "right-hand side")) return false;
    for (PetscInt r = first_row_; r < end_row_; ++r) local[r - first_row_] = b[r];
    if (!ok(VecRestoreArray(b_, &local), "right-hand side") || !ok(KSPSolve(ksp_, b_, x_), "KSPSolve"))
      return false;
    KSPConvergedReason reason{};
    PetscInt iterations = 0;
    KSPGetConvergedReason(ksp_, &reason);
    KSPGetIterationNumber(ksp_, &iterations);
    stats_.krylov_iterations += iterations;
    if (reason < 0) {
      message_ = std::string("petsc: KSP did not converge (") + KSPConvergedReasons[reason] + " after " +
                 std::to_string(iterations) + " iterations)";
      return false;
    }
    if (!ok(VecScatterBegin(to_all_, x_, x_all_, INSERT_VALUES, SCATTER_FORWARD), "gather") ||
        !ok(VecScatterEnd(to_all_, x_, x_all_, INSERT_VALUES, SCATTER_FORWARD), "gather"))
      return false;
    const PetscScalar* all = nullptr;
    if (!ok(VecGetArrayRead(x_all_, &all), "solution")) return false;
    x = Eigen::Map<const Eigen::VectorXd>(all, b.size());
    VecRestoreArrayRead(x_all_, &all);
    return x.allFinite();
  }

 private:
  /// MPIAIJ with this rank's rows, preallocated exactly: per row, the entries in the diagonal block
  /// (columns this rank owns) and the rest.
  bool create_matrix(PetscInt n) {
    const PetscInt local = end_row_ - first_row_;
    std::vector<PetscInt> diagonal(static_cast<std::size_t>(local), 0), off(static_cast<std::size_t>(local), 0);
    for (PetscInt r = first_row_; r < end_row_; ++r)
      for (int k = rows_.outerIndexPtr()[r]; k < rows_.outerIndexPtr()[r + 1]; ++k) {
        const int c = rows_.innerIndexPtr()[k];
        ++(c >= first_row_ && c < end_row_ ? diagonal : off)[static_cast<std::size_t>(r - first_row_)];
      }
    return ok(MatCreateAIJ(PETSC_COMM_WORLD, local, local, n, n, 0, diagonal.data(), 0, off.data(), &a_),
              "matrix") &&
           ok(MatSetOption(a_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "matrix");
  }

  /// GMRES(restart), right-preconditioned by ASM/ILU(0), then PETSc's options on top.
  bool create_krylov() {
    PC pc = nullptr;
    return ok(KSPCreate(PETSC_COMM_WORLD, &ksp_), "KSP") && ok(KSPSetType(ksp_, KSPGMRES), "KSP") &&
           ok(KSPGMRESSetRestart(ksp_, options_.gmres_restart), "KSP") &&
           ok(KSPSetPCSide(ksp_, PC_RIGHT), "KSP") &&
           ok(KSPSetTolerances(ksp_, options_.relative_tolerance, 1e-300, PETSC_DEFAULT, options_.max_iterations),
              "KSP") &&
           ok(KSPGetPC(ksp_, &pc), "PC") && ok(PCSetType(pc, PCASM), "PC") &&
           ok(KSPSetFromOptions(ksp_), "PETSc options");
  }

  bool ok(PetscErrorCode code, const char* what) {
    if (code == 0) return true;
    const char* text = nullptr;
    PetscErrorMessage(code, &text, nullptr);
    message_ = std::string("petsc: ") + what + " failed (" + (text != nullptr ? text : "error") + ")";
    return false;
  }

  void release() {
    if (ksp_ != nullptr) KSPDestroy(&ksp_);
    if (a_ != nullptr) MatDestroy(&a_);
    if (to_all_ != nullptr) VecScatterDestroy(&to_all_);
    for (::Vec* v : {&b_, &x_, &x_all_})
      if (*v != nullptr) VecDestroy(v);
  }

  LinearSolverOptions options_;
  RowMajorMatrix rows_;  // the system by rows: this rank sets rows [first_row_, end_row_)
  ::Mat a_ = nullptr;
  KSP ksp_ = nullptr;
  ::Vec b_ = nullptr, x_ = nullptr, x_all_ = nullptr;
  VecScatter to_all_ = nullptr;
  PetscInt first_row_ = 0, end_row_ = 0;
};

}  // namespace

std::unique_ptr<LinearSolver> make_petsc_solver(const LinearSolverOptions& options) {
  return std::make_unique<PetscSolver>(options);
}

}  // namespace matpoint::implicit

#else  // a build without PETSc

namespace matpoint::implicit {

std::unique_ptr<LinearSolver> make_petsc_solver(const LinearSolverOptions& /*options*/) { return nullptr; }

}  // namespace matpoint::implicit

#endif
